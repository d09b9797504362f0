"""The hub with an FFR beam: clamp, statics and modes against ANCF, rotating softening and
stiffening, dynamics (energy, momentum, strain histories against ANCF)."""

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.io.scenario import Sensor
from hubbeam.simulation import simulate
from hubbeam.solvers.modal import modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.laws import DriveProfile
from hubbeam.system.mount import Mount
from hubbeam.system.multibody import single_beam_system
from tests.conftest import L, central_difference, newton_matrix_and_differences, plate, rotation

THICK = plate(thickness=0.01)


def pair(section=THICK, elements=8, stiffening=False, **kw):
    """The same model with both formulations."""
    return (single_beam_system(AncfBeam(L, elements, section), **kw),
            single_beam_system(FfrBeam(L, elements, section, geometric_stiffening=stiffening), **kw))


@pytest.mark.parametrize("theta, beta, azimuth, precone",
                         [(0.0, 0.0, 0.0, 0.0), (0.7, np.pi / 4, 0.0, 0.0), (-2.5, np.pi / 2, 2.0, 0.2),
                          (3.0, -0.3, -1.0, -0.4)])
def test_body_frame_is_the_mount_frame(theta, beta, azimuth, precone):
    """The FFR beam floats on its root section frame: at hub angle theta its body frame is
    A_h(theta + psi) R_k(p) R_x(-beta) and its origin R i_k (the mount's convention, written
    out here with plain rotation matrices), its tip at (L, 0, 0) of that frame when undeformed,
    and it has no coordinates but its elastic ones (no clamp)."""
    system = single_beam_system(FfrBeam(L, 2, THICK), radius=0.35, twist=beta, azimuth=azimuth, precone=precone)
    x, F = system.initial_state(theta)
    a = theta + azimuth
    A_h = np.array([[np.cos(a), 0.0, -np.sin(a)], [0.0, 1.0, 0.0], [np.sin(a), 0.0, np.cos(a)]])
    R_k = rotation([0, 0, 1], precone)
    R_x = rotation([1, 0, 0], -beta)
    r, R = system.root_pose(0, x, F)
    assert np.allclose(R, A_h @ R_k @ R_x, atol=1e-14)
    assert np.allclose(r, 0.35 * A_h[:, 0], atol=1e-14)
    assert np.allclose(system.tip_position(x, 0, F), r + L * R[:, 0], atol=1e-14)
    assert system.layout.n_lambda == 1 and system.beams[0].ndof == x.size - 1  # the drive; theta and p


def test_static_sag_and_frequencies_agree_with_ancf_at_small_deformation():
    """A 10 mm plate under gravity (sag 1.4 % of L), weak axis vertical, fixed hub."""
    ancf, ffr = pair(radius=0.35, twist=np.pi / 2, gravity=np.array([0, -9.81, 0]))
    sa, sf = solve_static(ancf, load_steps=2), solve_static(ffr, load_steps=2)
    assert ffr.tip_displacement(sf.x)["vertical"] == pytest.approx(ancf.tip_displacement(sa.x)["vertical"], rel=2e-3)
    fa = modal_analysis(ancf, sa, count=6).frequencies_hz
    ff = modal_analysis(ffr, sf, count=6).frequencies_hz
    assert np.max(np.abs(ff / fa - 1)) < 5e-3, (fa, ff)


def test_rotating_lateral_stiffness_plain_ffr_softens_stiffened_ffr_follows_ancf():
    """Steady rotation at Omega with a tangential tip force, weak axis tangential: plain FFR's
    in-plane stiffness falls like omega_0^2 - Omega^2 (omega_0 its clamped first frequency);
    with geometric stiffening FFR follows ANCF, which stiffens."""
    force = np.array([0.0, 0.0, 1.0])
    deflection = {}
    for omega in (0.0, 20.0):
        for name, system in zip(("ancf", "ffr"), pair(radius=0.35, motion="prescribed", tip_force=force,
                                                      drive=DriveProfile("constant", omega or 1e-12))):
            deflection[name, omega] = system.tip_displacement(solve_static(system, spin=omega).x)["tangential"]
        stiff = pair(stiffening=True, radius=0.35, motion="prescribed", tip_force=force,
                     drive=DriveProfile("constant", omega or 1e-12))[1]
        deflection["ffr+", omega] = stiff.tip_displacement(solve_static(stiff, spin=omega).x)["tangential"]
    ffr0 = FfrBeam(L, 8, THICK)
    omega0 = np.sqrt(np.min(np.abs(np.linalg.eigvals(
        np.linalg.solve(ffr0.mass_matrix(np.zeros(ffr0.ndof), np.eye(3))[6:, 6:], ffr0.stiffness_matrix)))))
    # plain FFR: the lateral flexibility grows like 1 / (1 - Omega^2 / omega_0^2) (one-mode estimate)
    assert deflection["ffr", 20.0] / deflection["ffr", 0.0] == pytest.approx(1 / (1 - (20 / omega0) ** 2), rel=0.03)
    assert deflection["ancf", 20.0] < 0.8 * deflection["ancf", 0.0]
    assert deflection["ffr+", 20.0] == pytest.approx(deflection["ancf", 20.0], rel=1e-2)


SENSORS = [Sensor(name="energy", kind="energy"), Sensor(name="H", kind="angular_momentum"),
           Sensor(name="omega", kind="hub_angular_velocity"), Sensor(name="P1", kind="surface_strain", x=0.3,
                                                                     surface="upper"),
           Sensor(name="violation", kind="constraint_violation")]


def test_ffr_free_hub_keeps_energy_and_angular_momentum():
    system = single_beam_system(FfrBeam(L, 4, plate()), radius=0.35, twist=np.pi / 4, motion="free", hub_inertia=9.557,
                          gravity=np.array([0, -9.81, 0]))
    traj = simulate(system, SENSORS, t_end=0.6, dt=2e-3, spectral_radius=1.0, output_dt=0.02)
    e = traj.records["energy"]
    total = np.array([r["total"] for r in e])
    scale = max(r["kinetic"] for r in e)
    assert scale > 0.05
    assert np.max(np.abs(total - total[0])) < 1e-4 * scale
    hub_momentum = 9.557 * max(abs(w) for w in traj.records["omega"])
    assert max(abs(h) for h in traj.records["H"]) < 1e-4 * hub_momentum
    assert max(traj.records["violation"]) < 1e-12


def test_strain_histories_agree_with_ancf_at_small_deformation():
    """exp1's hub (free, beta = 45 deg, drag) with a 10 mm plate: the P1 strain over several
    periods of the first mode (3.9 Hz) agrees with ANCF to 1 % of its range."""
    strains = []
    for system in pair(radius=0.35, twist=np.pi / 4, motion="free", hub_inertia=9.557,
                       gravity=np.array([0, -9.81, 0]), damping=(1.73, 1.4)):
        traj = simulate(system, SENSORS, t_end=1.0, dt=1e-3, output_dt=0.005)
        strains.append(np.array(traj.records["P1"]))
    span = np.ptp(strains[0])
    assert span > 1e-4
    assert np.max(np.abs(strains[0] - strains[1])) < 0.01 * span  # measured: 0.22 %


@pytest.mark.slow
def test_kane_spin_up_at_10_rad_s_plain_ffr_diverges_stiffened_ffr_follows_ancf():
    """Kane et al. (1987): at omega_s = 10 rad/s (above the first clamped frequency, 3.8
    rad/s) the linear FFR loses its lateral stiffness and the tip runs away; with geometric
    stiffening FFR stays bounded and follows ANCF (8 elements each)."""
    from hubbeam.errors import ComputationError
    from tests.test_simulation import kane_beam

    drive = DriveProfile("spin_up", 10.0, 15.0)
    tip = [Sensor(name="tip", kind="tip_deflection")]
    runs = {}
    for name, system in (("ancf", single_beam_system(AncfBeam(10.0, 8, kane_beam()), motion="prescribed", drive=drive)),
                         ("ffr+", single_beam_system(FfrBeam(10.0, 8, kane_beam(), geometric_stiffening=True),
                                               motion="prescribed", drive=drive)),
                         ("ffr", single_beam_system(FfrBeam(10.0, 8, kane_beam()), motion="prescribed", drive=drive))):
        try:
            traj = simulate(system, tip, t_end=20.0, dt=0.01, output_dt=0.5)
        except ComputationError as exc:
            traj = exc.partial
        runs[name] = np.array([r["tangential"] for r in traj.records["tip"]])
    assert np.max(np.abs(runs["ffr"])) > 10.0  # diverged (or failed after running away)
    assert -0.9 < runs["ancf"].min() < -0.8
    assert np.max(np.abs(runs["ffr+"] - runs["ancf"])) < 0.02


@pytest.mark.parametrize("motion", ["free", "prescribed"])
def test_exact_newton_matrix_with_ffr_beams_is_the_derivative_of_the_residual(motion):
    """A hub with an FFR beam (tip body with an offset, tip force and moment, drag, gravity)
    beside an ANCF beam: with the exact stiffness (statics, modes) the compiled Newton matrix
    equals central differences of the compiled residual along the generalized-alpha correction
    at rest, where the inertia terms it leaves out vanish."""
    from hubbeam.system.ancf_part import AncfPart
    from hubbeam.system.ffr_part import FfrPart
    from hubbeam.system.multibody import Hub, MultibodySystem
    from hubbeam.system.tip_body import TipBody

    body = TipBody(0.2, (2e-4, 3e-4, 4e-4), (0.03, 0.01, -0.02))
    system = MultibodySystem([FfrPart(FfrBeam(L, 3, THICK, tip_body=body), Mount(0.35, 0.4, 0.3, 0.1),
                                tip_force=np.array([0.3, -1.0, 0.5]), tip_moment=np.array([0.1, 0.05, -0.2]),
                                name="ffr"),
                        AncfPart(AncfBeam(L, 3, THICK), Mount(0.35, -0.4, np.pi, 0.0), tip_body=body, name="ancf")],
                       Hub(motion, 9.5, drive=DriveProfile("spin_up", 2.0, 1.0)), gravity=(0.0, -9.81, 0.0),
                       damping=(1.73, 1.4))
    A, A_fd, res, res_fd = newton_matrix_and_differences(system, seed=5, perturbation=0.01, stiffness="exact")
    assert np.allclose(res, res_fd, rtol=0, atol=1e-14 * np.max(np.abs(res)))
    assert np.max(np.abs(A - A_fd)) < 1e-6 * np.max(np.abs(A))
    layout = system.layout
    ffr = layout.z_of_x[layout.beam_x(0)]
    # the FFR block on its own scale (its load stiffness is small against its elastic stiffness)
    block, block_fd = A[np.ix_(ffr, ffr)], A_fd[np.ix_(ffr, ffr)]
    assert np.max(np.abs(block - block_fd)) < 1e-6 * np.max(np.abs(block))


@pytest.mark.parametrize("motion", ["free", "prescribed"])
def test_drag_damping_matrix_is_the_velocity_derivative_of_the_drag_in_motion(motion):
    """The Newton matrix's damping part (coef_c C) against central differences in the rates of
    the drag's share of the residual (the residual with drag minus the residual without it: the
    inertia, elastic, gravity and constraint rows cancel) at a moving, deformed state: an FFR
    beam with an offset tip body beside an ANCF beam. At rest (the test above) only the linear
    drag c1 has a slope; here the speeds are a few m/s, so the quadratic drag c2 |rdot| rdot
    and its rank-one part (c2 / |rdot|) rdot rdot^T dominate C."""
    from hubbeam.system.ancf_part import AncfPart
    from hubbeam.system.ffr_part import FfrPart
    from hubbeam.system.multibody import Hub, MultibodySystem
    from hubbeam.system.tip_body import TipBody

    body = TipBody(0.2, (2e-4, 3e-4, 4e-4), (0.03, 0.01, -0.02))
    system = MultibodySystem([FfrPart(FfrBeam(L, 3, THICK, tip_body=body), Mount(0.35, 0.4, 0.3, 0.1), name="ffr"),
                        AncfPart(AncfBeam(L, 3, THICK), Mount(0.35, -0.4, np.pi, 0.0), tip_body=body, name="ancf")],
                       Hub(motion, 9.5, drive=DriveProfile("spin_up", 2.0, 1.0)), gravity=(0.0, -9.81, 0.0),
                       damping=(1.73, 1.4))
    still = system.without_damping()
    layout, s, t = system.layout, system.mass_scale, 0.3
    x, F = system.initial_state(t)
    rng = np.random.default_rng(11)
    x[1:] += 0.01 * rng.normal(size=x.size - 1)
    v = rng.normal(size=x.size)  # hub, frame and node rates of order 1
    ffr = layout.beam_x(0)
    v[ffr] *= 0.3  # elastic rates
    acc = rng.normal(size=x.size)
    lam = rng.normal(size=layout.n_lambda)

    def drag_rows(rates):
        return (system.equations(x, rates, acc, lam, F, t, 0.0, 0.0, 1.0, s, want_matrix=False)[0]
                - still.equations(x, rates, acc, lam, F, t, 0.0, 0.0, 1.0, s, want_matrix=False)[0])

    C = (system.equations(x, v, acc, lam, F, t, 0.0, 1.0, 0.0, s)[1].to_dense()
         - still.equations(x, v, acc, lam, F, t, 0.0, 1.0, 0.0, s)[1].to_dense())
    assert np.max(np.abs(drag_rows(v))) > 0.1  # the drag does act here (measured: 0.30)
    C_x = C[:, layout.z_of_x]  # on the rates of x; the multipliers' columns carry no drag
    assert np.all(np.delete(C, layout.z_of_x, axis=1) == 0.0)
    C_fd = central_difference(drag_rows, v, 1e-3)  # the drag is smooth in the rates away from rdot = 0
    assert np.max(np.abs(C_x - C_fd)) < 1e-5 * np.max(np.abs(C_x))  # measured: 2.3e-7
    z = layout.z_of_x[ffr]
    block, block_fd = C_x[np.ix_(z, range(ffr.start, ffr.stop))], C_fd[np.ix_(z, range(ffr.start, ffr.stop))]
    assert np.max(np.abs(block - block_fd)) < 1e-5 * np.max(np.abs(block))  # measured: 1.3e-7


def test_ffr_energy_balance_on_a_driven_hub():
    """exp1's FFR beam spun up by the drive (Kane's profile to 2 rad/s in 1 s) under gravity and
    drag: kinetic + strain + gravity + dissipated work - drive work stays at its initial value.
    The drive work integrates the drive's reaction, a constraint multiplier: with the iteration
    matrix kept for the whole run it is only as accurate as the Newton test makes it (testing
    the coordinates' increments alone left 1.1e-4 of the drive work; the ANCF beam 1e-6)."""
    from hubbeam import api
    from hubbeam.io.scenario import load_example

    sc = load_example("exp1", ['beam.formulation="ffr"', "beam.elements=4", "analysis.t_end=1.0",
                               "analysis.spectral_radius=1.0", 'hub.motion="prescribed"', 'hub.drive.profile="spin_up"',
                               "hub.drive.omega_s=2.0", "hub.drive.T=1.0"])
    traj, failure = api.run(sc)
    assert failure is None
    e = traj.records["energy"]
    balance = np.array([r["total"] + r["dissipated"] - r["drive"] for r in e])
    assert e[-1]["drive"] > 20.0 and e[-1]["dissipated"] > 1.0  # the drive does the work, the drag takes some
    assert np.max(np.abs(balance - balance[0])) < 1e-5 * e[-1]["drive"]  # measured: 1.0e-6


def test_ffr_energy_balance_with_drag():
    """exp1's free hub and drag with the nodal FFR beam: kinetic + strain + gravity + dissipated
    work stays at its initial value while the drag dissipates a good part of it."""
    from hubbeam import api
    from hubbeam.io.scenario import load_example

    sc = load_example("exp1", ['beam.formulation="ffr"', "beam.elements=4", "analysis.t_end=1.0",
                               "analysis.spectral_radius=1.0"])
    traj, failure = api.run(sc)
    assert failure is None
    e = traj.records["energy"]
    balance = np.array([r["total"] + r["dissipated"] - r["drive"] for r in e])
    dissipated = e[-1]["dissipated"]
    assert dissipated > 1e-3
    assert np.max(np.abs(balance - balance[0])) < 2e-4 * dissipated  # measured: 2.6e-5 (1.8e-6 J of 0.070 J)


#: case R's plate (benchmarks/case_a.toml: a fixed hub, gravity, no drag, no damping) on 4 modes,
#: and each source of a step power added to it in turn
CASE_A = __import__("pathlib").Path(__file__).parents[2] / "benchmarks" / "case_a.toml"
PLATE_ON_MODES = ['beam.formulation="ffr"', "beam.modes=4", "beam.elements=4", "analysis.t_end=0.3",
                  "analysis.spectral_radius=1.0"]
POWER_SOURCES = {"nothing": [], "drag": ["damping.linear=0.5"],
                 "structural damping": ["beam.damping.stiffness_proportional=1e-3"],
                 "tip force": ["loads.tip_force=[0.0, 1.0, 0.0]"], "tip moment": ["loads.tip_moment=[0.0, 0.0, 0.1]"],
                 "driven hub": ['hub.motion="prescribed"', 'hub.drive.profile="spin_up"', "hub.drive.omega_s=2.0",
                                "hub.drive.T=1.0"]}


@pytest.mark.parametrize("source", POWER_SOURCES)
def test_step_powers_skipped_only_where_every_power_is_zero(source):
    """The time loop skips the step's powers where no part can have one (``model.powers`` False:
    a fixed hub, FFR beams without drag, structural damping or tip loads;
    :func:`hubbeam.system.terms.with_powers`). The flag against the powers themselves, computed
    in full (the model with the flag forced on) at a state with random elastic coordinates,
    rates and multipliers (theta' = 0 on the fixed hub, its constraint's rate): both zero where
    the flag is off, not both zero for each source of power, so that a dissipating or driving
    part declared powerless fails here."""
    from hubbeam import api
    from hubbeam.io.scenario import load_scenario
    from hubbeam.simulation import initial_state

    system = api.build_system(load_scenario(CASE_A, PLATE_ON_MODES + POWER_SOURCES[source]))
    model = system.model()
    st = initial_state(system)
    rng = np.random.default_rng(26)
    theta = system.layout.theta
    x, v, lam = st.x.copy(), rng.normal(size=st.v.shape), rng.normal(size=st.lam.shape)
    elastic = np.arange(x.size) != theta
    x[elastic] += 1e-3 * rng.normal(size=int(elastic.sum()))
    if source != "driven hub":
        v[theta] = 0.0
    dissipated, drive = system.functions.step_powers(model._replace(powers=True), np.ascontiguousarray(st.chart),
                                                     0.5, x, v, lam)
    assert model.powers == (source != "nothing")
    if source == "nothing":
        assert dissipated == 0.0 and drive == 0.0
    else:
        assert abs(dissipated) + abs(drive) > 1e-6, (dissipated, drive)


def test_energy_balance_with_powers_skipped_is_the_balance_with_them_computed(monkeypatch):
    """Case R's plate on 4 modes (a fixed hub, no drag, no damping), 0.3 s at rho_inf = 1: the run
    that skips the step's powers (``model.powers`` False) and the run that computes them (the flag
    forced on) give the same states and energies to the last bit; the powers computed are zero to
    roundoff (the fixed hub's reaction does no work, theta' = 0), and kinetic + strain +
    gravity energy stays at its initial value (the balance with no work; an independent check). The
    drive work computed is the drive's multiplier times theta', roundoff of a rate held at zero."""
    from hubbeam import api
    from hubbeam.io.scenario import load_scenario
    from hubbeam.system import terms

    sc = load_scenario(CASE_A, PLATE_ON_MODES)
    skipped, failure = api.run(sc, sensors=[Sensor(name="energy", kind="energy")])
    assert failure is None
    monkeypatch.setattr(terms, "with_powers", lambda packs, ctx: True)
    computed, failure = api.run(sc, sensors=[Sensor(name="energy", kind="energy")])
    assert failure is None
    e_skipped, e_computed = ({key: np.array([r[key] for r in run.records["energy"]]) for key in
                              ("kinetic", "strain", "gravity", "total", "dissipated", "drive")}
                             for run in (skipped, computed))
    for key in ("kinetic", "strain", "gravity", "total"):
        assert np.array_equal(e_skipped[key], e_computed[key]), key
    assert np.all(e_skipped["dissipated"] == 0.0) and np.all(e_skipped["drive"] == 0.0)
    scale = np.max(e_skipped["kinetic"])  # measured: 0.38 J
    assert np.all(e_computed["dissipated"] == 0.0)
    assert np.max(np.abs(e_computed["drive"])) < 1e-12 * scale  # measured: 8.9e-58 J (the multiplier times theta')
    total = e_skipped["total"]
    assert np.max(np.abs(total - total[0])) < 1e-9 * scale  # measured: 1.3e-15 J
