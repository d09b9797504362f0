"""A tip body through the whole system: the modes of a cantilever carrying it, both formulations.

tests/system/test_tip_body.py and tests/elements/test_ffr_tip_body.py check the body's own
terms (the ANCF kernel, the FFR invariants) and, with those terms added by hand to a bare
beam's matrices, the frequencies. Here the body goes in as a user puts it in
(``single_beam_system(..., tip_body=...)``: the compiled system equations for ANCF, the FFR
beam's invariants for FFR) and :func:`hubbeam.solvers.modal.modal_analysis` gives the modes,
picked by their kinetic energy (:meth:`MultibodySystem.kinetic_energy_split`). Every principal
inertia of the body is checked against a closed form that knows nothing of the code:

- bending about m (deflection along n, the weak axis; ``lag`` at twist 0): tip mass and J_m,
  the frequency equation of Laura, Pombo & Susemihl (tests/system/test_tip_body.py);
- bending about n (deflection along m, the strong axis; ``flap``): the same equation with
  EI_z and J_n;
- torsion: a uniform shaft (GJ_t, polar rotary inertia rho (I_y + I_z) per length) carrying
  a disc J_tau, lambda tan(lambda) = rho (I_y + I_z) L / J_tau, omega = lambda / L sqrt(GJ_t /
  (rho (I_y + I_z))).
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.solvers.modal import modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.multibody import single_beam_system
from tests.conftest import L, plate
from tests.system.test_tip_body import FREQUENCY_BODY, MESHES, TIP_MASS, check_convergence, tip_body_roots

SECTION = plate()


def bending_hz(stiffness, inertia, count=2):
    """Cantilever of bending stiffness EI (N m^2) with the tip mass and a rotary inertia (kg m^2)."""
    rho_a = SECTION.mass_per_length
    lam = tip_body_roots(TIP_MASS / (rho_a * L), inertia / (rho_a * L**3), count)
    return lam**2 / L**2 * np.sqrt(stiffness / rho_a) / (2 * np.pi)


def torsion_hz(inertia):
    """First torsion frequency of the clamped shaft carrying a disc of rotary inertia J_tau (kg m^2)."""
    polar = SECTION.density * (SECTION.i_y + SECTION.i_z)  # kg m
    mu = polar * L / inertia
    lam = brentq(lambda x: x * np.tan(x) - mu, 1e-9, np.pi / 2 - 1e-12)
    return lam / L * np.sqrt(SECTION.stiffness[1] / polar) / (2 * np.pi)


J_TAU, J_M, J_N = FREQUENCY_BODY.inertia
#: (label of the motion, frequencies of the closed form) for each principal inertia
EXACT = {"lag": bending_hz(SECTION.stiffness[2], J_M), "flap": bending_hz(SECTION.stiffness[3], J_N, 1),
         "torsion": np.array([torsion_hz(J_TAU)])}


def labelled_modes(formulation, elements, body=FREQUENCY_BODY):
    """{motion: frequencies (Hz)} of a fixed-hub cantilever at twist 0 carrying ``body``, each mode
    filed under the motion holding most of its kinetic energy."""
    beam = AncfBeam(L, elements, SECTION) if formulation == "ancf" else FfrBeam(L, elements, SECTION)
    system = single_beam_system(beam, radius=0.2, twist=0.0, motion="fixed", tip_body=body)
    sol = solve_static(system, load_steps=1)
    modes = modal_analysis(system, sol, count=8)
    out = {}
    for i, f in enumerate(modes.frequencies_hz):
        split = system.kinetic_energy_split(sol.x, sol.chart, modes.shapes[:, i])
        out.setdefault(max(split, key=split.get), []).append(f)
    return {k: np.array(v) for k, v in out.items()}


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_cantilever_with_a_tip_body_has_the_closed_form_modes(formulation):
    """Weak-axis bending (two modes: the second is lowered from 4.52 to 3.14 Hz by J_m) converges
    to the closed form under mesh refinement (measured, both formulations: 1.6e-5 and 2.1e-3 with
    2 elements, 1.1e-7 and 1.5e-7 with 16, the floor of the sections' own rotary inertia);
    strong-axis bending (J_n) and torsion (J_tau: 3.10 Hz, the bare shaft's is far higher) match
    their closed forms too."""
    errors = {motion: [] for motion in EXACT}
    for n in MESHES:
        found = labelled_modes(formulation, n)
        for motion, exact in EXACT.items():
            errors[motion].append(found[motion][: exact.size] / exact - 1)
    check_convergence(errors["lag"])
    # measured on 16 elements, both formulations: flap -4.6e-5 (the closed form leaves out the
    # section's own rotary inertia rho I_z; without J_n the error would be +1.4e-2), torsion
    # 4e-12 (ANCF) and 4e-9 (FFR)
    assert np.all(np.abs(errors["flap"][-1]) < 1e-4)
    assert np.all(np.abs(errors["torsion"][-1]) < 1e-6)


def test_each_principal_inertia_moves_its_own_mode():
    """The checks above would pass with a body's inertias misplaced only if its modes did not
    depend on them: scaling J_tau, J_m or J_n by 1.3 moves its own mode (measured: torsion
    -12 %, the second weak-axis mode -7.8 %, strong-axis -0.40 %) and leaves the others alone
    (below 1e-7: no offset, the motions are uncoupled)."""
    from hubbeam.system.tip_body import TipBody

    base = labelled_modes("ancf", 4)
    for i, (motion, shift) in enumerate((("torsion", 0.1), ("lag", 0.05), ("flap", 3e-3))):
        inertia = list(FREQUENCY_BODY.inertia)
        inertia[i] *= 1.3  # 1.3 keeps the triangle inequalities of a rigid body
        changed = labelled_modes("ancf", 4, TipBody(TIP_MASS, tuple(inertia)))
        index = 1 if motion == "lag" else 0  # the first weak-axis mode is the mass's, not J_m's
        assert changed[motion][index] < (1 - shift) * base[motion][index]
        for other in {"torsion", "lag", "flap"} - {motion}:
            assert changed[other][0] == pytest.approx(base[other][0], rel=1e-6)
