"""Statics with free joints (solvers/static.py): a beam on a free hinge lying level under gravity
finds its hanging equilibrium and its pendulum frequency; a joint no load can hold fails with a
message that names it."""

from __future__ import annotations

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.errors import ConvergenceError
from hubbeam.solvers.modal import modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.beam import AncfBeam
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.joints import Joint
from hubbeam.system.laws import TorqueLaw
from hubbeam.system.mount import Mount
from hubbeam.system.multibody import Hub, MultibodySystem
from tests.conftest import plate

L = 0.8


@pytest.mark.parametrize("part, beam", [(AncfPart, AncfBeam), (FfrPart, FfrBeam)])
def test_a_level_beam_on_a_free_hinge_hangs_and_swings_as_a_compound_pendulum(part, beam):
    """Released level on a flap hinge (no spring): the static solver turns it to hang straight
    down (psi = -90 deg, where Newton's matrix starts singular along the hinge), and its lowest
    mode is the compound pendulum's, omega^2 = m g (L / 2) / I with I = m L^2 / 3 + rho I_sec L
    (the sections turning about c), to 1e-3 (the plate's own flexibility)."""
    section = plate(0.05, 0.01)
    system = MultibodySystem([part(beam(L, 3, section), Mount(0.2, joint=Joint.named("flap")))], Hub("fixed"),
                             gravity=(0.0, -9.81, 0.0))
    solution = solve_static(system)
    assert solution.x[system.layout.joint_x(0).start] == pytest.approx(-np.pi / 2, abs=1e-9)
    m = section.mass_per_length * L
    inertia = m * L**2 / 3 + section.density * section.i_z * L
    f = modal_analysis(system, solution, count=1).frequencies_hz[0]
    assert f == pytest.approx(np.sqrt(m * 9.81 * L / 2 / inertia) / (2 * np.pi), rel=1e-3)


def test_a_joint_no_load_holds_fails_naming_it():
    """A constant motor torque on a free hinge, nothing to resist it: no equilibrium, and the
    error names the free joint."""
    joint = Joint.named("lag", torque=TorqueLaw.constant(0.5))
    system = MultibodySystem([AncfPart(AncfBeam(L, 2, plate()), Mount(0.2, joint=joint), name="panel")],
                             Hub("fixed"), gravity=(0.0, 0.0, 0.0))
    with pytest.raises(ConvergenceError, match=r"no equilibrium holds the free joint panel \(lag\)"):
        solve_static(system, load_steps=2, max_cuts=1)
