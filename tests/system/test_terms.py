"""The registry of part kinds (hubbeam.system.terms): a new kind of part is its own module plus
its registration.

This module *is* such a module: it defines a kind the library does not have -- point masses
on ANCF nodes -- with its pack, packer and compiled terms, registers it, and puts it on a
system as an attachment, without a change anywhere in the system layer. The oracle is a
different derivation of the same physics: a tip body with no rotary inertia and no offset
is a point mass on the tip node (:mod:`hubbeam.system.tip_body`, Newton-Euler through the
section frame), so the two systems must move, vibrate and store energy alike; and energy is
conserved with the new kind's own energies.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import pytest

from hubbeam.io.scenario import Sensor
from hubbeam.simulation import simulate
from hubbeam.solvers.modal import modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system import terms
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.assembly import add_entry
from hubbeam.system.beam import AncfBeam
from hubbeam.system.multibody import Hub, MultibodySystem
from hubbeam.system.mount import Mount
from hubbeam.system.tip_body import TipBody
from tests.conftest import L, plate

GRAVITY = (0.0, -9.81, 0.0)
MASS = 0.15  # kg


# --------------------------------------------------------------------------- the new kind
@dataclass(frozen=True)
class PointMass:
    """A point mass (kg) on node ``node`` of the ANCF beam ``beam`` (its index)."""

    beam: int
    node: int
    mass: float


class PointMasses(NamedTuple):
    index: np.ndarray  # int64 (n,): the beam's place among all beams
    x0: np.ndarray  # int64 (n,): where the node's position r starts in x
    mass: np.ndarray  # (n,) kg


def pack_point_masses(system, layout):
    found = [a for a in system.attachments if isinstance(a, PointMass)]
    if not found:
        return None
    x0 = [layout.beam_x(a.beam).start + system.beams[a.beam].beam.node_slice(a.node).start for a in found]
    return PointMasses(np.array([a.beam for a in found], dtype=np.int64), np.array(x0, dtype=np.int64),
                       np.array([a.mass for a in found], dtype=float))


def point_mass_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                         want_matrix, res, ab, brow, bcol, bb):
    """m (r'' - g) on the node's position rows; coef_m m I in the matrix."""
    zx = ctx.z_of_x
    for k in range(pack.x0.shape[0]):
        m = pack.mass[k]
        for i in range(3):
            z = zx[pack.x0[k] + i]
            res[z] += coef_k * m * (acc[pack.x0[k] + i] - load_factor * ctx.gravity[i])
            if want_matrix:
                add_entry(ab, brow, bcol, bb, ctx.ku, z, z, coef_m * m)
    return 2.0, 0.0


def point_mass_energies(pack, ctx, F, x, v, beams):
    for k in range(pack.x0.shape[0]):
        m = pack.mass[k]
        for i in range(3):
            r = pack.x0[k] + i
            terms.add_beam_energy(beams, pack.index[k], 0.5 * m * v[r] * v[r], 0.0, -m * ctx.gravity[i] * x[r])
    return 0.0, 0.0, 0.0


def point_mass_momenta(pack, ctx, F, x, v, out):
    """m, m r, m v and r x m v about the origin (what a kind with mass adds to the momenta)."""
    for k in range(pack.x0.shape[0]):
        m = pack.mass[k]
        r = x[pack.x0[k]:pack.x0[k] + 3]
        u = v[pack.x0[k]:pack.x0[k] + 3]
        out[0] += m
        for i in range(3):
            out[1 + i] += m * r[i]
            out[4 + i] += m * u[i]
        out[7] += m * (r[1] * u[2] - r[2] * u[1])
        out[8] += m * (r[2] * u[0] - r[0] * u[2])
        out[9] += m * (r[0] * u[1] - r[1] * u[0])


terms.register(PointMasses, pack_point_masses, point_mass_equations, point_mass_energies,
               bandwidth=lambda system, layout: 1, momenta=point_mass_momenta)


# --------------------------------------------------------------------------- the checks
def systems(elements=4, motion="free"):
    """The same beam with a point mass on its tip node, and with a tip body of that mass."""
    beam = AncfBeam(L, elements, plate())
    mount = Mount(0.2, np.pi / 4, 0.0, 0.0)
    hub = Hub(motion, 0.5)
    with_point = MultibodySystem([AncfPart(beam, mount)], hub, GRAVITY, attachments=[PointMass(0, elements, MASS)])
    with_body = MultibodySystem([AncfPart(beam, mount, tip_body=TipBody(MASS))], hub, GRAVITY)
    return with_point, with_body


def test_a_kind_registers_once():
    with pytest.raises(ValueError, match="registered already"):
        terms.register(PointMasses, pack_point_masses, point_mass_equations)


def test_a_kind_absent_from_a_system_is_not_in_its_model():
    with_point, with_body = systems()
    assert any(isinstance(p, PointMasses) for p in with_point.model().parts)
    assert not any(isinstance(p, PointMasses) for p in with_body.model().parts)


def test_a_point_mass_moves_the_system_as_a_tip_body_of_that_mass():
    """Released from straight on a free hub under gravity: hub angle, tip, energies and angular
    momentum of the two systems agree to round-off over 0.5 s (the tip falls 0.6 m and the hub
    turns 0.2 rad; measured differences: tip 6.9e-15 m, theta 1.6e-15 rad, energies 3e-14 J,
    H 8e-15 N m s); the total energy, with the new kind's own energies, drifts 1.4e-5 of the
    kinetic energy (no drag, no torque)."""
    watch = [Sensor(name="theta", kind="hub_angle"), Sensor(name="tip", kind="tip_deflection"),
             Sensor(name="energy", kind="energy"), Sensor(name="H", kind="angular_momentum")]
    runs = [simulate(s, watch, t_end=0.5, dt=2e-3, output_dt=0.05) for s in systems()]
    point, body = (r.records for r in runs)
    tips = [np.array([[d["radial"], d["vertical"], d["tangential"]] for d in r["tip"]]) for r in (point, body)]
    assert np.max(np.abs(tips[0][:, 1])) > 0.5
    assert np.max(np.abs(tips[0] - tips[1])) < 1e-12
    assert np.max(np.abs(np.array(point["theta"]) - np.array(body["theta"]))) < 1e-12
    for key in ("kinetic", "strain", "gravity"):
        got = np.array([e[key] for e in point["energy"]])
        want = np.array([e[key] for e in body["energy"]])
        assert np.max(np.abs(got - want)) < 1e-12 * np.max(np.abs(want)) + 1e-13, key
    assert np.max(np.abs(np.array(point["H"]) - np.array(body["H"]))) < 1e-12
    # no drag, no torque: the new kind's energies close the balance
    total = np.array([e["total"] for e in point["energy"]])
    assert np.max(np.abs(total - total[0])) < 5e-5 * np.max([e["kinetic"] for e in point["energy"]])


def test_a_point_mass_gives_the_modes_of_a_tip_body_of_that_mass():
    """Clamped (fixed hub) about the static sag: the lowest six frequencies (0.70 ... 48.9 Hz) agree."""
    point, body = (modal_analysis(s, solve_static(s, load_steps=2), count=6) for s in systems(motion="fixed"))
    assert np.allclose(point.frequencies_hz, body.frequencies_hz, rtol=1e-12, atol=0)


def test_the_time_step_terms_of_a_counting_kind_are_called_as_its_own_functions():
    """The equations, power and drive power of a kind that counts references (ANCF beams, as in
    exp1) resolve to the kind's own functions, called by the system's functions and not inlined
    into them. It fails if an inlined wrapper that only calls them comes back: numba compiled
    such a wrapper once more on its own just to type it, with the callee's code linked in (on
    exp1's first run about 3 s of CPU, ``python benchmarks/compile_time.py exp1``)."""
    from numba import typeof
    from numba.core.registry import cpu_target

    from hubbeam import api
    from hubbeam.io.scenario import load_example
    from hubbeam.system import ancf_part

    model = api.build_system(load_example("exp1")).model()
    pack_type = typeof(next(p for p in model.parts if isinstance(p, ancf_part.AncfBeams)))
    cpu_target.typing_context.refresh()  # the registered overloads
    for stub, own in ((terms.part_equations, ancf_part.ancf_equations), (terms.part_power, ancf_part.ancf_power),
                      (terms.part_drive_power, ancf_part.ancf_drive_power)):
        templates = cpu_target.typing_context.resolve_value_type(stub).templates
        found = [t for t in templates if t._overload_func(pack_type) is not None]
        assert len(found) == 1
        assert found[0]._overload_func(pack_type) is own
        assert found[0]._inline.is_never_inline
