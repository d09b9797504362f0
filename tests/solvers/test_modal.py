"""Natural frequencies against Euler-Bernoulli and St-Venant closed forms, and their convergence."""

import numpy as np
import pytest

from hubbeam.solvers.modal import modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.multibody import single_beam_system
from tests.conftest import L, RHO, plate

BETA_L = np.array([1.8751040687, 4.6940911330, 7.8547574382])  # clamped-free roots of cos cosh = -1


def clamped(elements, count=40, **kw):
    sec = plate()
    system = single_beam_system(AncfBeam(L, elements, sec), radius=0.35, motion="fixed", **kw)
    return sec, system, modal_analysis(system, solve_static(system, load_steps=1), count=count)


def dominant_component(system, shape):
    """Which motion dominates a mode shape at the tip: 'x', 'y', 'z' translation or 'twist'."""
    tip = shape[1:][system.beam.node_slice(-1)]
    amps = {"x": abs(tip[0]), "y": abs(tip[1]), "z": abs(tip[2]), "twist": abs(tip[6]) * system.beam.section.width}
    return max(amps, key=amps.get)


def test_clamped_frequencies_match_closed_forms():
    sec, system, modes = clamped(8)
    EA, GJ, EIy, EIz = sec.stiffness
    rhoA = sec.mass_per_length
    f = modes.frequencies_hz
    kinds = [dominant_component(system, modes.shapes[:, i]) for i in range(f.size)]
    # beta = 0: the width is vertical, so weak-axis bending (EI_y) moves along z, strong along y
    weak = f[[k == "z" for k in kinds]][:3]
    strong = f[[k == "y" for k in kinds]][:2]
    twist = f[[k == "twist" for k in kinds]][:1]
    axial = f[[k == "x" for k in kinds]][:1]
    weak_ref = BETA_L**2 / (2 * np.pi) * np.sqrt(EIy / (rhoA * L**4))
    strong_ref = BETA_L[:2] ** 2 / (2 * np.pi) * np.sqrt(EIz / (rhoA * L**4))
    torsion_ref = 1 / (4 * L) * np.sqrt(GJ / (RHO * (sec.i_y + sec.i_z)))
    axial_ref = 1 / (4 * L) * np.sqrt(sec.youngs_modulus / RHO)
    assert np.allclose(weak, weak_ref, rtol=2e-3)
    assert np.allclose(strong, strong_ref, rtol=2e-3)  # rotary inertia lowers mode 2 by 0.15 %
    assert np.isclose(twist[0], torsion_ref, rtol=2e-3)
    assert np.isclose(axial[0], axial_ref, rtol=2e-3)
    assert abs(weak[0] / weak_ref[0] - 1) < 1e-4
    # the reference plate's first frequency (conventions.md: 0.978 Hz)
    assert abs(weak[0] - 0.978) < 5e-4


def test_frequency_error_converges_at_high_order():
    sec = plate()
    EIy = sec.stiffness[2]
    ref = BETA_L[1] ** 2 / (2 * np.pi) * np.sqrt(EIy / (sec.mass_per_length * L**4))
    errors = []
    for n in (4, 8, 16):
        _, system, modes = clamped(n, count=3)
        errors.append(abs(modes.frequencies_hz[1] - ref) / ref)
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(rates > 3.5), (errors, rates)  # cubic Hermite: O(h^4) for bending frequencies


def test_free_hub_leaves_out_one_rigid_mode():
    sec = plate()
    system = single_beam_system(AncfBeam(L, 6, sec), radius=0.35, motion="free", hub_inertia=9.557)
    modes = modal_analysis(system, solve_static(system, load_steps=1), count=4)
    assert modes.rigid_modes == 1
    assert abs(modes.rigid_frequencies_hz[0]) < 1e-3
    # a hub of finite inertia raises the in-plane (strong-axis, y... here z-tangential) frequencies above clamped
    _, _, fixed = clamped(6, count=4)
    assert modes.frequencies_hz[0] >= fixed.frequencies_hz[0] * (1 - 1e-9)


def test_a_rigid_frequency_is_never_negative():
    """exp1 without gravity: the straight beam's rigid rotation has omega^2 = -3.4e-8 (1/s^2)
    by round-off; it was reported as -2.95e-5 Hz. It is sqrt(|omega^2|) / 2 pi."""
    from hubbeam import api
    from hubbeam.io.scenario import load_example

    result = api.modes(load_example("exp1", ["environment.gravity=[0.0, 0.0, 0.0]"]))
    rigid = result.to_dict()["rigid_frequencies_hz"]
    assert result.modes.rigid_modes == 1 and 0.0 <= rigid[0] < 1e-3


def test_rigid_mode_frequency_about_a_bent_state_vanishes_with_refinement():
    sec = plate()
    out = []
    for n in (4, 8):
        system = single_beam_system(AncfBeam(L, n, sec), radius=0.35, twist=np.pi / 2, motion="free", hub_inertia=9.557,
                               gravity=np.array([0, -9.81, 0]))
        out.append(abs(modal_analysis(system, solve_static(system, load_steps=5), count=1).rigid_frequencies_hz[0]))
    assert out[1] < out[0] / 2 and out[0] < 5e-3


def _rotating_frequencies(system_class, beam, speed):
    from hubbeam.solvers.modal import rotating_modal_analysis
    from hubbeam.system.laws import DriveProfile

    system = system_class(beam, radius=0.0, twist=np.pi / 2, motion="prescribed",
                          drive=DriveProfile("constant", max(speed, 1e-12)))
    steady = solve_static(system, spin=speed, load_steps=2)
    return rotating_modal_analysis(system, steady, speed, count=4).frequencies_hz


@pytest.mark.parametrize("lam, first, second", [(1.0, 3.6816, 22.1810), (3.0, 4.7973, 23.3203)])
def test_rotating_cantilever_flapwise_frequencies_match_the_classic_values(lam, first, second):
    """Rotating cantilever, R = 0, flapwise (out of the plane of rotation): frequency parameter
    w sqrt(rho A L^4 / EI) at lam = Omega sqrt(rho A L^4 / EI) (Wright et al. 1982; Hodges and
    Rutkowski 1981): 3.6816 / 22.1810 at lam = 1, 4.7973 / 23.3203 at lam = 3; 3.5160 at rest."""
    sec = plate()
    unit = np.sqrt(sec.stiffness[2] / (sec.mass_per_length * L**4))
    f = _rotating_frequencies(single_beam_system, AncfBeam(L, 8, sec), lam * unit) * 2 * np.pi / unit
    assert f[0] == pytest.approx(first, rel=2e-4)
    assert f[1] == pytest.approx(second, rel=1e-3)


def test_rotating_ffr_plain_does_not_stiffen_stiffened_follows_ancf():
    """Plain FFR: the flapwise frequency stays at its value at rest and the chordwise one
    softens exactly as w^2 = w0^2 - Omega^2 (linear rotating-frame model); with geometric
    stiffening FFR follows ANCF."""
    from hubbeam.elements.ffr.body import FfrBeam
    
    sec = plate()
    unit = np.sqrt(sec.stiffness[2] / (sec.mass_per_length * L**4))
    speed = 3.0 * unit
    rest = _rotating_frequencies(single_beam_system, FfrBeam(L, 8, sec), 0.0)
    plain = _rotating_frequencies(single_beam_system, FfrBeam(L, 8, sec), speed)
    stiff = _rotating_frequencies(single_beam_system, FfrBeam(L, 8, sec, geometric_stiffening=True), speed)
    ancf = _rotating_frequencies(single_beam_system, AncfBeam(L, 8, sec), speed)
    assert plain[0] == pytest.approx(rest[0], rel=1e-6)  # flapwise: no centrifugal term in linear FFR
    chord = np.argmin(np.abs(rest - 70.3 * unit / (2 * np.pi)))  # the first chordwise (strong-axis) mode
    w0, w = 2 * np.pi * rest[chord], 2 * np.pi * plain[chord]
    assert w**2 == pytest.approx(w0**2 - speed**2, rel=1e-5)
    assert np.max(np.abs(stiff / ancf - 1)) < 2e-3
    assert ancf[0] > 1.3 * rest[0]
