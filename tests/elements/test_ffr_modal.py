"""The modally reduced FFR beam (FfrBeam(..., modes=N), scenario key beam.modes).

Oracles: with every mode kept the reduced beam is the nodal one in other coordinates, so
every term must be the nodal term mapped by the basis and a dynamic run must repeat the
nodal run; the basis must solve the nodal eigenproblem (checked with a different solver);
the system's own modal analysis of the reduced beam must give the kept frequencies; with
fewer modes, strain histories, a spin-up tip lag and a rotating stiffened frequency must
converge to the nodal FFR's; static deflections missed by the kept modes must match what the
static solver of the reduced system misses.
"""

import itertools
import tomllib

import numpy as np
import pytest
from scipy.linalg import expm

from hubbeam.elements.ffr import modal
from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.io.scenario import (
    ScenarioError,
    Sensor,
    apply_overrides,
    example_text,
    validate,
)
from hubbeam.simulation import simulate
from hubbeam.solvers.newton_control import NewtonOptions
from hubbeam.solvers.modal import modal_analysis, rotating_modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system.multibody import single_beam_system
from hubbeam.system.laws import DriveProfile
from hubbeam.system.mount import Mount
from hubbeam.system.tip_body import TipBody
from tests.conftest import L, plate, tapered_sections
from tests.system.test_tip_body import (
    FREQUENCY_BODY,
    TIP_J_M,
    TIP_MASS,
    tip_body_frequencies_hz,
)

GRAVITY = np.array([0.0, -9.81, 0.0])
OFFSET_BODY = TipBody(0.2, (1e-4, 2e-4, 3e-4), (0.01, 0.005, -0.003))
#: a fresh Newton matrix every step: as exact as full Newton here, at half its cost; the default
#: adaptive (modified Newton) iteration leaves ~6e-4 of the spin-up tip lag, which would hide
#: the comparison
FRESH_NEWTON = NewtonOptions(update="step")


def skew(a):
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def lift(B):
    """v = [r_C', omega, p'] = T [r_C', omega, eta']."""
    T = np.zeros((6 + B.shape[0], 6 + B.shape[1]))
    T[:6, :6] = np.eye(6)
    T[6:, 6:] = B
    return T


# ----------------------------------------------------------------------------- exact mapping
@pytest.mark.parametrize("stiffening, real_blade", [(False, False), (True, False), (False, True), (True, True)])
def test_all_modes_map_every_term_of_the_nodal_beam(stiffening, real_blade):
    """3 elements, an offset tip body, every mode kept: invariants, M_v, Q_v, Q_g, the elastic
    energy, force and tangent, the structural damping and every row are the nodal ones mapped by
    the basis; also for a tapered, pretwisted beam."""
    extra = {"sections": tapered_sections(), "structural_damping": 1e-3} if real_blade else {}
    nodal = FfrBeam(L, 3, plate(), geometric_stiffening=stiffening, tip_body=OFFSET_BODY, **extra)
    red = FfrBeam(L, 3, plate(), geometric_stiffening=stiffening, tip_body=OFFSET_BODY, modes=18, **extra)
    B = red.basis
    assert red.ndof == 18 and nodal.ndof == red.nodal_ndof == 18 and B.shape == (18, 18)
    assert np.linalg.matrix_rank(B) == 18
    assert red.elements == 3 and red.element_length == nodal.element_length and red.modes == 18
    inv, rinv = nodal.invariants, red.invariants
    for key in ("m", "c0", "I0"):
        assert np.array_equal(rinv[key], inv[key])
    scale = {k: np.max(np.abs(v)) for k, v in inv.items()}
    assert np.allclose(rinv["Sbar"], inv["Sbar"] @ B, rtol=0, atol=1e-13 * scale["Sbar"])
    assert np.allclose(rinv["J"], inv["J"] @ B, rtol=0, atol=1e-13 * scale["J"])
    II = np.array([[B.T @ inv["II"][k, l] @ B for l in range(3)] for k in range(3)])
    assert np.allclose(rinv["II"], II, rtol=0, atol=1e-13 * np.max(np.abs(II)))
    assert np.allclose(rinv["Mff"], B.T @ inv["Mff"] @ B, rtol=0, atol=1e-14)
    if not stiffening:  # B is the Mff-normalised eigenbasis
        assert np.allclose(rinv["Mff"], np.eye(18), atol=1e-12)
        w2 = (2 * np.pi * red.frequencies_hz) ** 2
        assert np.allclose(red.stiffness_matrix, np.diag(w2), rtol=0, atol=1e-12 * w2.max())

    rng = np.random.default_rng(7)
    T = lift(B)
    for _ in range(3):
        eta, etad = 0.02 * rng.standard_normal(18), rng.standard_normal(18)
        p, pd = B @ eta, B @ etad
        A0 = expm(skew(rng.standard_normal(3)))
        omega, g = rng.standard_normal(3), 9.81 * rng.standard_normal(3)
        M = T.T @ nodal.mass_matrix(p, A0) @ T
        assert np.allclose(red.mass_matrix(eta, A0), M, rtol=0, atol=1e-13 * np.max(np.abs(M)))
        Q = T.T @ nodal.quadratic_velocity(p, pd, omega, A0)
        assert np.allclose(red.quadratic_velocity(eta, etad, omega, A0), Q, rtol=0, atol=1e-12 * np.max(np.abs(Q)))
        Q = T.T @ nodal.gravity(p, A0, g)
        assert np.allclose(red.gravity(eta, A0, g), Q, rtol=0, atol=1e-13 * np.max(np.abs(Q)))
        U, f, K = nodal.elastic(p)
        Ur, fr, Kr = red.elastic(eta)
        assert Ur == pytest.approx(U, rel=1e-11)
        assert np.allclose(fr, B.T @ f, rtol=0, atol=1e-11 * np.max(np.abs(f)))
        assert np.allclose(Kr, B.T @ K @ B, rtol=0, atol=1e-11 * np.max(np.abs(K)))
        for x in (0.0, 0.3, 1.0, L):
            assert np.allclose(red.displacement_row(x, 0.01, -0.001), nodal.displacement_row(x, 0.01, -0.001) @ B)
            assert np.allclose(red.rotation_row(x), nodal.rotation_row(x) @ B)
            assert np.allclose(red.strain_row(x, 0.0, 0.00125), nodal.strain_row(x, 0.0, 0.00125) @ B)
            assert red.surface_strain(eta, x, 0.0, 0.00125) == pytest.approx(nodal.surface_strain(p, x, 0.0, 0.00125),
                                                                              rel=1e-10, abs=1e-15)
        assert np.allclose(red.centre_line_table["N"], nodal.centre_line_table["N"] @ B)
        assert np.array_equal(red.centre_line_table["b"], nodal.centre_line_table["b"])
        Cn = B.T @ nodal.damping_matrix @ B
        assert np.allclose(red.damping_matrix, Cn, rtol=0, atol=1e-11 * max(np.max(np.abs(Cn)), 1e-300))
        assert np.allclose(red.first_moment(eta), nodal.first_moment(p))


def test_all_modes_repeat_the_nodal_run():
    """exp1's hub (free, beta = 45 deg, gravity), 4 elements, 0.5 s: the P1 strain of the
    reduced beam with every mode kept is the nodal one to 1e-8 of its range."""
    sensors = [Sensor(name="P1", kind="surface_strain", x=0.3, surface="upper"),
               Sensor(name="tip", kind="tip_deflection")]
    runs = []
    for modes in (None, 24):
        system = single_beam_system(FfrBeam(L, 4, plate(), modes=modes), radius=0.35, twist=np.pi / 4, motion="free",
                                    hub_inertia=9.557, gravity=GRAVITY)
        runs.append(simulate(system, sensors, 0.5, 1e-3, output_dt=0.01, newton=FRESH_NEWTON))
    a, b = (np.array(r.records["P1"]) for r in runs)
    assert np.ptp(a) > 1e-4
    assert np.max(np.abs(a - b)) < 1e-8 * np.ptp(a)
    ta, tb = ([r["vertical"] for r in run.records["tip"]] for run in runs)
    assert np.max(np.abs(np.subtract(ta, tb))) < 1e-8 * np.ptp(ta)


# ----------------------------------------------------------------------------- frequencies
def test_kept_frequencies_are_the_nodal_ones_and_the_systems():
    """The kept modes solve K phi = w^2 Mff phi of the nodal beam (checked against numpy's
    non-symmetric solver); the system's modal analysis of the reduced beam on a fixed hub finds
    exactly them; the first is the plate's 0.978 Hz."""
    nodal = FfrBeam(L, 6, plate())
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(nodal.invariants["Mff"], nodal.stiffness_matrix)).real)
    exact_hz = np.sqrt(w2) / (2 * np.pi)
    for n in (1, 4, 10):
        red = FfrBeam(L, 6, plate(), modes=n)
        assert red.ndof == n and red.frequencies_hz.shape == (n,)
        # (the non-symmetric solver resolves w^2 to ~1e-16 of the largest, 1e8 times the smallest)
        assert np.allclose(red.frequencies_hz, exact_hz[:n], rtol=1e-7, atol=0)
        assert red.max_frequency_hz == pytest.approx(exact_hz[n - 1], rel=1e-7)
        phi = red.mode_shapes
        assert np.allclose(nodal.stiffness_matrix @ phi, nodal.invariants["Mff"] @ phi * w2[:n], atol=1e-8 * w2[n - 1])
        system = single_beam_system(red, radius=0.35, twist=np.pi / 4, motion="fixed")
        f = modal_analysis(system, solve_static(system, load_steps=1), count=n).frequencies_hz
        assert np.allclose(f, exact_hz[:n], rtol=1e-6)
    assert FfrBeam(L, 6, plate(), modes=1).frequencies_hz[0] == pytest.approx(0.978, abs=5e-4)
    assert nodal.max_frequency_hz is None and nodal.frequencies_hz is None


def test_a_mode_of_uncoupled_sections_is_exactly_zero_outside_its_direction():
    """A straight, untwisted plate's axial, y-bending, z-bending and twist coordinates are not
    coupled by K or Mff, so each kept mode moves one of them and is exactly zero on the others
    (the drag's rows and II then hold no round-off entries); the modes still solve the nodal
    eigenproblem as a whole (numpy's non-symmetric solver), and a square section's equal bending
    frequencies come as one pure y and one pure z mode, in that order (the groups' order, not
    the order of the frequencies' round-off)."""
    groups = {"axial": [0], "y": [1, 2], "z": [3, 4], "twist": [5]}  # a node's six coordinates (DOF_NAMES)
    for section, n in ((plate(), 12), (plate(0.01, 0.01), 8)):
        nodal = FfrBeam(L, 6, section)
        K, M = nodal.stiffness_matrix, nodal.invariants["Mff"]
        w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
        red = FfrBeam(L, 6, section, modes=n)
        assert np.allclose(red.frequencies_hz, np.sqrt(w2[:n]) / (2 * np.pi), rtol=1e-7, atol=0)
        phi = red.mode_shapes
        assert np.allclose(K @ phi, M @ phi * (2 * np.pi * red.frequencies_hz) ** 2, atol=1e-8 * w2[n - 1])
        assert np.allclose(phi.T @ M @ phi, np.eye(n), atol=1e-12)
        moved = []
        for k in range(n):
            touched = [name for name, own in groups.items()
                       if np.any(phi[[6 * j + c for j in range(6) for c in own], k] != 0.0)]
            assert len(touched) == 1, (k, touched)
            moved.append(touched[0])
        N = red.centre_line_table["N"]
        for k, name in enumerate(moved):  # the centre line moves along the mode's direction only
            others = [i for i, own in enumerate(("axial", "y", "z")) if own != name]
            assert np.all(N[:, others, k] == 0.0)
    # the square section (the last one): pairs of equal frequency
    f = red.frequencies_hz
    assert moved[:4] == ["y", "z", "y", "z"]
    assert f[1] == pytest.approx(f[0], rel=1e-9) and f[3] == pytest.approx(f[2], rel=1e-9)


def test_coupled_sections_keep_every_coordinate_in_one_eigenproblem():
    """Pretwist couples the bending along y and z: the modes of the tapered, pretwisted blade are
    those of the whole pencil (numpy's non-symmetric solver) and move both directions."""
    nodal = FfrBeam(L, 6, plate(), sections=tapered_sections())
    K, M = nodal.stiffness_matrix, nodal.invariants["Mff"]
    assert len(modal.uncoupled_groups(K, M)) == 1
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    red = FfrBeam(L, 6, plate(), sections=tapered_sections(), modes=4)
    assert np.allclose(red.frequencies_hz, np.sqrt(w2[:4]) / (2 * np.pi), rtol=1e-7, atol=0)
    phi = red.mode_shapes
    along_y, along_z = [6 * j + c for j in range(6) for c in (1, 2)], [6 * j + c for j in range(6) for c in (3, 4)]
    assert np.all(np.abs(phi[along_y]).max(axis=0) > 1e-3 * np.abs(phi).max(axis=0))
    assert np.all(np.abs(phi[along_z]).max(axis=0) > 1e-3 * np.abs(phi).max(axis=0))


def test_modes_must_fit_the_nodal_model():
    for bad in (0, 19, 2.0, True):
        with pytest.raises(ValueError, match="modes"):
            FfrBeam(L, 3, plate(), modes=bad)


def test_the_modes_are_those_of_the_beam_with_its_tip_body():
    """A tip body added by single_beam_system (dataclasses.replace) rebuilds the modes with it:
    the weak-axis ones match the closed-form frequency equation of a cantilever with a tip
    mass and rotary inertia, and the system's modal analysis finds the kept frequencies."""
    bare = FfrBeam(L, 8, plate(), modes=6)
    system = single_beam_system(bare, radius=0.0, twist=0.0, motion="fixed", tip_body=FREQUENCY_BODY)
    beam = system.beams[0].beam
    assert beam.tip_body is FREQUENCY_BODY and beam.modes == 6 and beam.ndof == 6
    exact = tip_body_frequencies_hz(plate(), L, TIP_MASS, TIP_J_M)
    weak = [k for k in range(6) if np.sum(beam.mode_shapes[3::6, k] ** 2 + beam.mode_shapes[4::6, k] ** 2)
            > 0.5 * np.sum(beam.mode_shapes[:, k] ** 2)][:2]
    assert np.allclose(beam.frequencies_hz[weak], exact, rtol=2e-4)
    assert beam.frequencies_hz[0] < 0.6 * bare.frequencies_hz[0]  # the body matters
    f = modal_analysis(system, solve_static(system, load_steps=1), count=6).frequencies_hz
    assert np.allclose(f, beam.frequencies_hz, rtol=1e-6)
    # and its inertia is in the invariants: the nodal beam with the body, mapped
    nodal = FfrBeam(L, 8, plate(), tip_body=FREQUENCY_BODY)
    assert np.allclose(beam.invariants["J"], nodal.invariants["J"] @ beam.basis, atol=1e-14)
    assert np.allclose(beam.invariants["Mff"], np.eye(6), atol=1e-12)


# ----------------------------------------------------------------------------- convergence
def _exp1_strain(modes):
    system = single_beam_system(FfrBeam(L, 6, plate(), modes=modes), radius=0.35, twist=np.pi / 4, motion="free",
                                hub_inertia=9.557, gravity=GRAVITY)
    traj = simulate(system, [Sensor(name="P1", kind="surface_strain", x=0.3, surface="upper")], 1.0, 1e-3,
                    output_dt=0.01)
    return np.array(traj.records["P1"])


def test_exp1_strain_history_converges_to_the_nodal_ffr():
    """exp1-like release under gravity (free hub, beta = 45 deg), 6 elements, 1 s: max error of
    the P1 strain / its range, measured 1.8e-2 (N = 2), 7.6e-3 (4), 9.3e-4 (8)."""
    ref = _exp1_strain(None)
    errors = [np.max(np.abs(_exp1_strain(n) - ref)) / np.ptp(ref) for n in (2, 4, 8)]
    assert np.ptp(ref) > 5e-4
    assert errors[0] > errors[1] > errors[2], errors
    assert errors[0] < 3e-2 and errors[2] < 2e-3, errors


def _spin_up_lag(modes, stiffening=False):
    system = single_beam_system(FfrBeam(L, 6, plate(), modes=modes, geometric_stiffening=stiffening), radius=0.55,
                                twist=0.0, motion="prescribed", drive=DriveProfile("spin_up", 3.0, 2.0),
                                gravity=GRAVITY)
    traj = simulate(system, [Sensor(name="tip", kind="tip_deflection")], 2.5, 2e-3, output_dt=0.01,
                    newton=FRESH_NEWTON)
    return np.array([r["tangential"] for r in traj.records["tip"]])


def test_spin_up_tip_lag_converges_to_the_nodal_ffr():
    """exp2-like prescribed spin-up to 3 rad/s in 2 s (beta = 0: the lag is along the weak
    axis), 6 elements: max error of the tangential tip deflection / its largest value (0.278 m),
    measured 3.0e-4 (N = 2), 4.8e-5 (4), 1.8e-6 (8)."""
    ref = _spin_up_lag(None)
    errors = [np.max(np.abs(_spin_up_lag(n) - ref)) / np.max(np.abs(ref)) for n in (2, 4, 8)]
    assert -0.3 < ref.min() < -0.25
    assert errors[0] > errors[1] > errors[2], errors
    assert errors[0] < 1e-3 and errors[2] < 1e-5, errors


def _rotating_flap_hz(beam, speed):
    system = single_beam_system(beam, radius=0.0, twist=np.pi / 2, motion="prescribed",
                                drive=DriveProfile("constant", max(speed, 1e-12)))
    steady = solve_static(system, spin=speed, load_steps=2)
    return rotating_modal_analysis(system, steady, speed, count=1).frequencies_hz[0]


def test_projected_geometric_stiffening_converges_to_the_nodal_stiffened_frequency():
    """Rotating plate (R = 0, lambda = 3, as tests/solvers/test_modal.py), 8 elements: the
    stiffened first flap frequency of the reduced beam (kept modes plus the nodal axial
    coordinates) converges to the nodal stiffened one (1.3353 Hz; measured +2.0e-3, +3.1e-4,
    +6.3e-5, +2.5e-6 for N = 1, 2, 4, 8). Projecting on the lowest modes alone keeps no axial
    freedom and loses the stiffening (0.978 Hz, the frequency at rest)."""
    sec = plate()
    speed = 3.0 * np.sqrt(sec.stiffness[2] / (sec.mass_per_length * L**4))
    ref = _rotating_flap_hz(FfrBeam(L, 8, sec, geometric_stiffening=True), speed)
    assert ref > 1.3
    errors = []
    for n in (1, 2, 4, 8):
        beam = FfrBeam(L, 8, sec, geometric_stiffening=True, modes=n)
        assert beam.ndof == n + 8
        errors.append(abs(_rotating_flap_hz(beam, speed) / ref - 1))
    assert all(a > b for a, b in itertools.pairwise(errors)), errors
    assert errors[0] < 5e-3 and errors[-1] < 1e-5, errors
    modal_only = FfrBeam(L, 8, sec, geometric_stiffening=True)
    modal.reduce(modal_only, 8, axial="modal")
    assert _rotating_flap_hz(modal_only, speed) == pytest.approx(modal_only.frequencies_hz[0], rel=1e-4)


# ----------------------------------------------------------------------------- coverage checks
def test_static_residual_is_what_the_reduced_static_solution_misses():
    """Fixed hub, beta = 45 deg, gravity: the reduced system's static tip deflection (static
    solver) misses exactly the share static_residual predicts; it shrinks as modes are added
    and vanishes with all of them; coverage_warnings flags a one-mode beam."""
    nodal_system = single_beam_system(FfrBeam(L, 6, plate()), radius=0.35, twist=np.pi / 4, gravity=GRAVITY)
    ref = np.array(list(nodal_system.tip_displacement(solve_static(nodal_system, load_steps=1).x).values()))
    g_body = Mount(0.35, np.pi / 4).frame(0.0).T @ GRAVITY
    previous = np.inf
    for n in (1, 2, 4, 8, 36):
        beam = FfrBeam(L, 6, plate(), modes=n)
        system = single_beam_system(beam, radius=0.35, twist=np.pi / 4, gravity=GRAVITY)
        tip = np.array(list(system.tip_displacement(solve_static(system, load_steps=1).x).values()))
        residual = modal.static_residual(beam, g_body)
        missed = np.linalg.norm(tip - ref) / np.linalg.norm(ref)
        assert missed == pytest.approx(residual.tip, rel=1e-3, abs=1e-9), (n, missed, residual)
        assert residual.tip <= previous and residual.energy >= residual.tip * 0.5
        previous = residual.tip
    assert residual.tip < 1e-9 and residual.energy < 1e-9
    assert modal.static_residual(FfrBeam(L, 6, plate()), g_body) == modal.StaticResidual(0.0, 0.0)
    warn = modal.coverage_warnings(FfrBeam(L, 6, plate(), modes=1), g_body, excitation_hz=2.0, name="blade")
    assert len(warn) == 2 and all(w.startswith("blade: ") for w in warn)
    assert modal.coverage_warnings(FfrBeam(L, 6, plate(), modes=8), g_body, excitation_hz=2.0) == []
    assert modal.coverage_warnings(FfrBeam(L, 6, plate()), g_body, excitation_hz=1e6) == []


# ----------------------------------------------------------------------------- scenario
def test_scenario_key_modes():
    base = tomllib.loads(example_text("exp1"))
    sc = validate(apply_overrides(base, ["beam.formulation=ffr", "beam.modes=5"]))
    assert sc.resolved_beams()[0].modes == 5 and validate(sc.to_dict()) == sc
    assert validate(base).resolved_beams()[0].modes is None
    from hubbeam.api import build_system

    beam = build_system(sc).beams[0].beam
    assert beam.modes == 5 and beam.ndof == 5 and beam.max_frequency_hz > 17.0
    for overrides, start in ((["beam.modes=4"], "beam.modes: only applies to formulation = 'ffr'"),
                             (["beam.formulation=ffr", "beam.modes=37"], "beam.modes: at most"),
                             (["beam.formulation=ffr", "beam.modes=0"], "beam.modes: must be >= 1")):
        with pytest.raises(ScenarioError) as info:
            validate(apply_overrides(base, overrides))
        assert str(info.value).startswith(start), str(info.value)
    rotor = tomllib.loads(example_text("rotor3"))
    with pytest.raises(ScenarioError) as info:
        validate(apply_overrides(rotor, ["beams[1].modes=3"]))
    assert str(info.value).startswith("beams[1].modes:")
    # switching to ANCF drops the key
    base["beam"].update(formulation="ffr", modes=4)
    assert validate(apply_overrides(base, ["beam.formulation=ancf"])).beam.modes is None
