"""A hub carrying several beams: symmetries, conservation laws, the Newton matrix, mixed
formulations and tip-body statics.

The oracles do not share the code's derivation: mirror and rotation symmetries of the
physics (a mirror-symmetric system cannot turn its hub; two rotationally symmetric twins
are one beam on half the hub), the balance laws of a free hub (dH/dt = T about the axis,
the energy balance), central differences of the residual, the other formulation (FFR
against ANCF) and the linear cantilever's closed form.
"""

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.io.scenario import Sensor
from hubbeam.simulation import simulate
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers.modal import modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.beam import AncfBeam
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.multibody import Hub, MultibodySystem, single_beam_system
from hubbeam.system.laws import DriveProfile, TorqueLaw
from hubbeam.system.mount import Mount
from hubbeam.system.tip_body import TipBody
from tests.conftest import (ALPHA_COEFS, L, assert_compiled_steps_are_python_steps, newton_matrix_and_differences, plate)
from tests.system.conftest import parts_of, rigid_axis_inertia, tips

GRAVITY = (0.0, -9.81, 0.0)
BETA = np.pi / 4
#: a tip body with rotary inertia and an offset in every section direction
BODY = TipBody(0.2, (1e-4, 2e-4, 1.5e-4), (0.02, 0.01, 0.005))


def sensors(*beams):
    out = [Sensor(name="theta", kind="hub_angle"), Sensor(name="omega", kind="hub_angular_velocity"),
           Sensor(name="H", kind="angular_momentum"), Sensor(name="energy", kind="energy")]
    return out + [Sensor(name=f"tip_{b}", kind="tip_deflection", beam=b) for b in beams]


# --------------------------------------------------------------------------- 1. mirror
def mirror_pair(body=None, precone=0.0, mirrored_body=True):
    """Beam b1 at azimuth 0 with twist +beta, b2 at 180 deg with -beta: mirror images in the
    plane through j0 and k_h. The reflection takes b1's section frame (tau, m, n) to b2's
    (tau, m, -n), so the mirror image of a tip body offset (c_tau, c_m, c_n) is
    (c_tau, c_m, -c_n) (principal inertias unchanged)."""
    other = body
    if body is not None and mirrored_body:
        c = body.offset
        other = TipBody(body.mass, body.inertia, (c[0], c[1], -c[2]))
    return MultibodySystem([AncfPart(AncfBeam(L, 3, plate()), Mount(0.35, BETA, 0.0, precone), tip_body=body, name="b1"),
                      AncfPart(AncfBeam(L, 3, plate()), Mount(0.35, -BETA, np.pi, precone), tip_body=other,
                               name="b2")],
                     Hub(motion="free", inertia=9.5), gravity=GRAVITY)


@pytest.mark.parametrize("body, precone", [(None, 0.0), (BODY, 0.0), (BODY, 0.1)],
                         ids=["bare", "tip_bodies", "tip_bodies_precone"])
def test_mirror_symmetric_beams_do_not_turn_a_free_hub(body, precone):
    """Released straight at rest under gravity, the twisted beams sag a lot (vertical and,
    being twisted, tangential) but the free hub stays at rest to round-off; each tip's
    deflection in its own hub frame is the mirror image of the other's: radial and vertical
    equal, tangential opposite."""
    traj = simulate(mirror_pair(body, precone), sensors("b1", "b2"), t_end=0.5, dt=2e-3, output_dt=0.05)
    a, b = tips(traj.records["tip_b1"]), tips(traj.records["tip_b2"])
    assert np.max(np.abs(a[:, 1])) > 0.3 and np.max(np.abs(a[:, 2])) > 0.3  # a big, bent and twisted sag
    assert np.max(np.abs(a - b * [1, 1, -1])) < 1e-12  # measured: 1.4e-14
    assert np.max(np.abs(traj.records["omega"])) < 1e-10  # measured: 2e-14 rad/s
    assert np.max(np.abs(traj.records["theta"])) < 1e-12
    assert np.max(np.abs(traj.records["H"])) < 1e-10


def test_an_unmirrored_tip_body_does_turn_the_hub():
    """The same pair with the tip body offset NOT mirrored (c_n the same on both) is no longer
    symmetric: the hub turns (the mirror test above can fail), while H stays zero."""
    traj = simulate(mirror_pair(BODY, mirrored_body=False), sensors(), t_end=0.5, dt=2e-3, output_dt=0.05)
    assert np.max(np.abs(traj.records["omega"])) > 1e-4  # measured: 1e-3 rad/s
    assert np.max(np.abs(traj.records["H"])) < 5e-4 * 9.5 * np.max(np.abs(traj.records["omega"]))  # measured: 6e-5


# --------------------------------------------------------------------------- 2. twins
J_HUB, TORQUE = 9.5, 3.0


def twin_part(azimuth, name):
    return AncfPart(AncfBeam(L, 3, plate()), Mount(0.35, BETA, azimuth, 0.05), tip_body=BODY, name=name)


def twins():
    """Two identical beams (same twist, precone, tip body) at 0 and 180 deg: a half-turn about
    j0 maps the system onto itself."""
    return MultibodySystem([twin_part(0.0, "b1"), twin_part(np.pi, "b2")], Hub("free", J_HUB, TorqueLaw.constant(TORQUE)),
                     gravity=GRAVITY)


def half():
    """One of the twins on half the hub inertia with half the torque."""
    return MultibodySystem([twin_part(0.0, "b1")], Hub("free", J_HUB / 2, TorqueLaw.constant(TORQUE / 2)), gravity=GRAVITY)


def test_two_rotationally_symmetric_beams_move_like_one_on_half_the_hub():
    """J theta'' = T - (reaction of b1) - (reaction of b2) and the two reactions are equal by
    symmetry: the pair moves exactly as one beam on J/2 with T/2 (theta and each tip)."""
    two = simulate(twins(), sensors("b1", "b2"), t_end=0.6, dt=2e-3, output_dt=0.05)
    one = simulate(half(), sensors("b1"), t_end=0.6, dt=2e-3, output_dt=0.05)
    theta2, theta1 = np.array(two.records["theta"]), np.array(one.records["theta"])
    assert theta1[-1] > 0.1  # the torque turns the hub
    assert np.max(np.abs(theta2 - theta1)) < 1e-12  # measured: 5e-16
    reference = tips(one.records["tip_b1"])
    assert np.max(np.abs(reference[:, 1])) > 0.3
    for name in ("tip_b1", "tip_b2"):
        assert np.max(np.abs(tips(two.records[name]) - reference)) < 1e-11  # measured: 1.4e-14
    # and the angular momentum of the pair is twice the half system's
    assert np.max(np.abs(np.array(two.records["H"]) - 2 * np.array(one.records["H"]))) < 1e-10


def test_twin_modes_are_the_collective_and_the_antisymmetric_ones():
    """About the sagged equilibrium, the pair's free-hub modes split into collective ones (both
    beams alike: one beam on J/2, hub free) and anti-symmetric ones (opposite: the hub
    reactions cancel, theta = 0, each beam a cantilever on a held hub). The union of the two
    single-beam spectra is the pair's spectrum."""
    two, one = twins(), half()
    pair = modal_analysis(two, solve_static(two), count=10, free_hub=True).frequencies_hz
    sol = solve_static(one)
    collective = modal_analysis(one, sol, count=5, free_hub=True).frequencies_hz
    antisymmetric = modal_analysis(one, sol, count=5, free_hub=False).frequencies_hz
    expected = np.sort(np.concatenate([collective, antisymmetric]))
    assert np.min(np.abs(np.diff(expected))) > 1e-3  # the two families do not coincide
    assert np.max(np.abs(pair / expected - 1)) < 1e-7  # measured: 2e-9


# --------------------------------------------------------------------------- 3. three beams
J_HUB_THREE = 2.0


def three_beams(torque=None, hub_inertia=J_HUB_THREE):
    """Three beams at 0, 120, 240 deg with different twists and precones and offset tip bodies
    (no drag): nothing is symmetric."""
    layout = [(BETA, 0.0, 0.0), (np.pi / 6, 2 * np.pi / 3, 0.1), (0.0, 4 * np.pi / 3, -0.05)]
    parts = [AncfPart(AncfBeam(L, 3, plate()), Mount(0.35, beta, azimuth, precone), tip_body=BODY, name=f"b{i}")
             for i, (beta, azimuth, precone) in enumerate(layout)]
    return MultibodySystem(parts, Hub("free", hub_inertia, torque or TorqueLaw()), gravity=GRAVITY)


def test_constant_torque_on_three_beams_angular_momentum_is_torque_times_time():
    """Gravity is along the axis and there is no drag: dH/dt = T exactly, so H = T t; the
    integrator's error shrinks like dt^2. The energy balance total - (work of T) holds too."""
    T = 2.0
    errors, balances = [], []
    for dt in (2e-3, 1e-3):
        traj = simulate(three_beams(TorqueLaw.constant(T)), sensors("b0"), t_end=1.0, dt=dt, output_dt=0.05)
        t = np.array(traj.times)
        errors.append(np.max(np.abs(np.array(traj.records["H"]) - T * t)))
        e = traj.records["energy"]
        balance = parts_of(e, "total") - parts_of(e, "drive")
        kinetic = np.max(parts_of(e, "kinetic"))
        assert kinetic > 1.0  # the beams fall and the hub spins up
        # the drive's work is the torque's: T times the hub angle
        assert e[-1]["drive"] == pytest.approx(T * traj.records["theta"][-1], rel=1e-4)
        balances.append(np.max(np.abs(balance - balance[0])) / kinetic)
        assert np.max(np.abs(tips(traj.records["tip_b0"])[:, 1])) > 0.3
    assert errors[0] < 1e-5 * T  # measured: 4.9e-6 N m s of H = 2 N m s
    assert errors[0] / errors[1] > 3.0  # measured: 4.8 (second order)
    assert max(balances) < 5e-5  # measured: 2.5e-5, 1.3e-5 of the kinetic energy
    assert balances[1] < balances[0]


def test_three_beams_spinning_freely_keep_energy_and_angular_momentum():
    """Started in rigid rotation at 3 rad/s (ga.init with the steady-rotation velocities), no
    torque: the beams sag and vibrate, H and the total energy stay put. At t = 0, H must be
    omega times the rigid inertia of hub, beams and tip bodies about the axis."""
    omega = 3.0
    system = three_beams()
    x, F = system.axis_chart(*system.initial_state(0.0))
    v0, _ = system.steady_rotation_rates(x, F, omega)
    state = ga.init(system, x, F, v0=v0)
    traj = simulate(system, sensors("b0"), t_end=1.0, dt=2e-3, output_dt=0.05, spectral_radius=1.0, state=state)
    H = np.array(traj.records["H"])
    assert H[0] == pytest.approx(omega * rigid_axis_inertia(system), rel=1e-9)
    total = parts_of(traj.records["energy"], "total")
    assert np.max(np.abs(H - H[0])) < 3e-5 * H[0]  # measured: 1.0e-5 (second order in dt)
    assert np.max(np.abs(total - total[0])) < 5e-5 * total[0]  # measured: 2.1e-5
    assert np.max(np.abs(tips(traj.records["tip_b0"])[:, 1])) > 0.1  # it does sag while spinning


def test_each_beams_energy_sensor_measures_that_beam():
    """In rigid rotation at omega each beam's kinetic energy is omega^2 J_k / 2 with J_k its own
    rigid inertia about the axis (the mount-data oracle applied to that beam alone; the three
    differ by twist, precone and azimuth-independent terms); afterwards the beams' energies
    and the hub's add up to the system's at every output."""
    omega = 3.0
    system = three_beams()
    x, F = system.axis_chart(*system.initial_state(0.0))
    v0, _ = system.steady_rotation_rates(x, F, omega)
    names = [b.name for b in system.beams]
    watch = [Sensor(name="omega", kind="hub_angular_velocity"), Sensor(name="energy", kind="energy")]
    watch += [Sensor(name=f"e_{n}", kind="energy", beam=n) for n in names]
    traj = simulate(system, watch, t_end=0.3, dt=2e-3, output_dt=0.05, spectral_radius=1.0,
                    state=ga.init(system, x, F, v0=v0))
    expected = []
    for part in system.beams:
        alone = MultibodySystem([part], Hub("free", 1.0))
        expected.append(0.5 * omega**2 * (rigid_axis_inertia(alone) - 1.0))
    measured = [traj.records[f"e_{n}"][0]["kinetic"] for n in names]
    assert measured == pytest.approx(expected, rel=1e-9)
    assert max(expected) - min(expected) > 1e-3 * max(expected)  # the beams do differ
    hub = 0.5 * J_HUB_THREE * np.array(traj.records["omega"]) ** 2
    beams = sum(parts_of(traj.records[f"e_{n}"], "total") for n in names)
    total = parts_of(traj.records["energy"], "total")
    assert np.max(np.abs(beams + hub - total)) < 1e-12 * np.max(np.abs(total))
    assert set(traj.records[f"e_{names[0]}"][0]) == {"kinetic", "strain", "gravity", "total"}


def test_a_torque_pulse_leaves_its_impulse_as_angular_momentum():
    """A triangular torque pulse (TorqueLaw.table: 0 -> 4 N m -> 0 over 0.1 s, impulse 0.2 N m s)
    from rest: afterwards H = 0.2 N m s and the total energy stay constant."""
    system = three_beams(TorqueLaw.table([0.0, 0.05, 0.1], [0.0, 4.0, 0.0]))
    traj = simulate(system, sensors(), t_end=0.8, dt=2e-3, output_dt=0.02, spectral_radius=1.0)
    t = np.array(traj.times)
    after = t > 0.1 - 1e-9
    H = np.array(traj.records["H"])
    assert np.max(np.abs(H[after] - 0.2)) < 1e-5  # measured: 2.6e-6
    total = parts_of(traj.records["energy"], "total")[after]
    kinetic = np.max(parts_of(traj.records["energy"], "kinetic"))
    assert np.max(np.abs(total - total[0])) < 5e-5 * kinetic  # measured: 1.5e-5
    assert traj.records["theta"][-1] > 0.01


# --------------------------------------------------------------------------- 7. Newton matrix
REFERENCE = DriveProfile("spin_up", 2.0, 1.0)
KP, KD = 40.0, 7.0


def pd_reference(t, theta, omega):
    ref = REFERENCE(t)
    return KP * (ref[0] - theta) + KD * (ref[1] - omega)


def loaded_pair(motion, torque):
    """Two beams, one with precone and azimuth, offset tip bodies, tip forces and moments, drag."""
    parts = [AncfPart(AncfBeam(L, 3, plate()), Mount(0.35, BETA, 0.0, 0.0),
                      tip_body=TipBody(0.3, (2e-4, 3e-4, 4e-4), (0.03, -0.02, 0.01)),
                      tip_force=(0.1, 0.2, -0.3), tip_moment=(0.03, -0.02, 0.05), name="b1"),
             AncfPart(AncfBeam(L, 2, plate()), Mount(0.3, -np.pi / 6, 2.2, 0.15),
                      tip_body=TipBody(0.2, (1e-4, 1e-4, 1.5e-4), (-0.02, 0.01, 0.03)),
                      tip_force=(-0.2, 0.1, 0.1), tip_moment=(-0.01, 0.04, 0.02), name="b2")]
    return MultibodySystem(parts, Hub(motion, 9.5, torque, REFERENCE), gravity=GRAVITY, damping=(1.73, 1.4))


@pytest.mark.parametrize("motion, torque", [("free", TorqueLaw.pd(KP, KD, REFERENCE)),
                                            ("free", TorqueLaw.callable(pd_reference)),
                                            ("prescribed", TorqueLaw.pd(KP, KD, REFERENCE))],
                         ids=["free_pd", "free_callable", "prescribed"])
def test_newton_matrix_of_two_beams_is_the_derivative_of_the_residual(motion, torque):
    """z = [theta, mu, q] moves x by dz, v by gamma' dz, xdd by beta' dz and lambda by s/ck dmu.
    At rest every term the matrix leaves out vanishes, so it must equal the central
    differences of the residual; for the free hub the PD law enters the hub row as
    -ck (dT/dtheta + gamma' dT/domega) = ck (kp + gamma' kd)."""
    A, A_fd, res, res_fd = newton_matrix_and_differences(loaded_pair(motion, torque))
    assert np.allclose(res, res_fd, rtol=0, atol=1e-14 * np.max(np.abs(res)))
    assert np.max(np.abs(A - A_fd)) < 1e-6 * np.max(np.abs(A))  # measured: 1e-9
    # the hub's own entry, to a small fraction of the torque law's share of it (which is only
    # 2.5e-4 of the entry, below the whole-matrix tolerance above)
    ck, gp, _ = ALPHA_COEFS
    law_share = ck * (KP + gp * KD)
    assert abs(A[0, 0] - A_fd[0, 0]) < 1e-3 * law_share  # measured: 3e-13 of 2.3e-3
    if motion == "free":  # the law does enter: the differences see it too
        A0 = newton_matrix_and_differences(loaded_pair(motion, TorqueLaw()))[0]  # the same state
        assert A_fd[0, 0] - A0[0, 0] == pytest.approx(law_share, rel=1e-6)


# --------------------------------------------------------------------------- 8. mixed formulations
THICK = plate(thickness=0.01)
MIXED_BODY = TipBody(0.1, (2e-4, 3e-4, 4e-4), (0.02, 0.0, 0.0))


def mixed_pair(elements=4):
    """An ANCF beam at 0 deg and an FFR beam at 180 deg (mirror twists), tip bodies on both,
    a 10 mm plate (small deformation, where the two formulations agree)."""
    return MultibodySystem([AncfPart(AncfBeam(L, elements, THICK), Mount(0.35, BETA, 0.0, 0.0), tip_body=MIXED_BODY,
                               name="ancf"),
                      FfrPart(FfrBeam(L, elements, THICK, tip_body=MIXED_BODY), Mount(0.35, -BETA, np.pi, 0.0),
                              name="ffr")],
                     Hub("free", 9.557), gravity=GRAVITY)


def test_ancf_and_ffr_beams_on_one_hub_agree_statically():
    system = mixed_pair()
    sol = solve_static(system, load_steps=2)
    ancf, ffr = system.tip_displacement(sol.x, 0), system.tip_displacement(sol.x, 1)
    assert ancf["vertical"] < -0.01
    assert ffr["vertical"] == pytest.approx(ancf["vertical"], rel=5e-3)  # measured: 1.8e-4
    # mirror twists: tangential deflections opposite
    assert ffr["tangential"] == pytest.approx(-ancf["tangential"], rel=5e-3)  # measured: 2.8e-4


@pytest.mark.parametrize("update", ["iteration", "adaptive"])
def test_compiled_steps_of_ancf_and_ffr_beams_are_the_python_steps(update):
    """The compiled loop and the Python step on a mixed hub (ANCF and FFR beams, tip bodies):
    the same Newton iterations and states."""
    assert_compiled_steps_are_python_steps(mixed_pair(), update)


def test_ancf_and_ffr_beams_on_a_free_hub_conserve_energy_and_momentum():
    system = mixed_pair()
    assert system.compiled  # FFR beams integrate in compiled code too
    traj = simulate(system, sensors("ancf", "ffr") + [Sensor(name="violation", kind="constraint_violation")],
                    t_end=0.5, dt=2e-3, spectral_radius=1.0, output_dt=0.02)
    e = traj.records["energy"]
    total = parts_of(e, "total")
    kinetic = np.max(parts_of(e, "kinetic"))
    assert kinetic > 0.05
    assert np.max(np.abs(total - total[0])) < 3e-5 * kinetic  # measured: 1.1e-6
    hub_momentum = 9.557 * np.max(np.abs(traj.records["omega"]))
    assert hub_momentum > 1e-4  # the two formulations differ slightly: the hub does turn a little
    assert np.max(np.abs(traj.records["H"])) < 1e-3 * hub_momentum  # measured: 3e-5
    assert max(traj.records["violation"]) < 1e-12
    a, f = tips(traj.records["tip_ancf"]), tips(traj.records["tip_ffr"])
    assert np.max(np.abs(a[:, 1] - f[:, 1])) < 0.01 * np.max(np.abs(a[:, 1]))


def test_mixed_beams_under_a_callable_torque_law_keep_the_energy_balance():
    """The Python path with both Python pieces at once (an FFR beam and a callable PD law
    tracking a slew): total energy minus the law's work stays constant without drag."""
    slew = DriveProfile.slew(0.4, 0.5)

    def law(t, theta, omega):
        ref = slew(t)
        return 30.0 * (ref[0] - theta) + 10.0 * (ref[1] - omega)

    system = mixed_pair().with_hub(torque=TorqueLaw.callable(law))
    traj = simulate(system, sensors(), t_end=0.6, dt=2e-3, spectral_radius=1.0, output_dt=0.02)
    e = traj.records["energy"]
    balance = parts_of(e, "total") - parts_of(e, "drive")
    assert e[-1]["drive"] > 1.0 and traj.records["theta"][-1] > 0.1
    assert np.max(np.abs(balance - balance[0])) < 5e-5 * np.max(parts_of(e, "kinetic"))  # measured: 1e-5


# --------------------------------------------------------------------------- charts
def test_a_chart_change_of_one_beam_among_two_matches_the_python_run():
    """Beam a starts in a chart whose singular direction its falling tangents approach; beam b
    keeps its own. The compiled and the Python run change a's chart at the same step and end
    in the same state, and the motion is the one of the run without the bad chart up to the
    re-interpolation of the twist (a discretisation effect, tests/test_simulation.py)."""
    from hubbeam.elements.ancf.chart import frame_from_director
    from hubbeam.simulation import initial_state

    class PythonOnly(MultibodySystem):
        compiled = False

    parts = [AncfPart(AncfBeam(L, 4, plate()), Mount(0.35, np.pi / 2, 0.0, 0.0), tip_body=MIXED_BODY, name="a"),
             AncfPart(AncfBeam(L, 3, plate()), Mount(0.3, 0.3, 2.0, 0.1), name="b")]
    system = MultibodySystem(parts, Hub("free", 3.0, TorqueLaw.constant(1.0)), gravity=GRAVITY)
    python = PythonOnly(system.beams, system.hub, system.gravity, system.damping)
    start = initial_state(system)
    charts = start.chart.copy()
    charts[0] = frame_from_director(np.array([-0.3, 0.954, 0.0]))  # 1 + d.tau = 0.7 when straight
    state = ga.init(system, system.remap(start.x, start.chart, charts), charts)
    watch = [Sensor(name=f"tip_{b}", kind="tip_deflection", beam=b) for b in ("a", "b")] + [sensors()[0]]
    runs = [simulate(s, watch, t_end=0.4, dt=1e-3, output_dt=0.1, state=state) for s in (system, python)]
    plain = simulate(system, watch, t_end=0.4, dt=1e-3, output_dt=0.1)
    assert runs[0].chart_switches == runs[1].chart_switches == 1 and plain.chart_switches == 0
    for name in ("tip_a", "tip_b"):
        assert np.max(np.abs(tips(runs[0].records[name]) - tips(runs[1].records[name]))) < 1e-9
        assert np.max(np.abs(tips(runs[0].records[name]) - tips(plain.records[name]))) < 1e-4  # measured: 1.3e-5
    assert np.max(np.abs(tips(plain.records["tip_a"])[:, 1])) > 0.1


# --------------------------------------------------------------------------- 9. tip body statics
TIP_MASS, TIP_OFFSET = 0.3, 0.25


def tip_slope(position, length, h=1e-3):
    """d(vertical)/d(axial) at the tip from three centre-line points (second-order one-sided)."""
    d = (3 * position(length) - 4 * position(length - h) + position(length - 2 * h)) / (2 * h)
    return d[1] / d[0]


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_tip_body_on_a_cantilever_is_a_tip_force_and_moment(formulation):
    """A fixed hub, twist 90 deg (the weak axis, E b h^3 / 12, bends vertically), a tip body of
    mass M with its centre c along the axis beyond the tip, small gravity g: the linear
    cantilever under its weight q = rho A g, a tip force P = M g and a tip moment M g c:
    w = P L^3/(3EI) + M g c L^2/(2EI) + q L^4/(8EI), w' = P L^2/(2EI) + M g c L/EI + q L^3/(6EI)."""
    g = 0.981  # small load: w/L = 0.3 %, geometric nonlinearity below 1e-5
    body = TipBody(TIP_MASS, (1e-4, 2e-4, 2e-4), (TIP_OFFSET, 0.0, 0.0))
    EI, q = THICK.stiffness[2], THICK.mass_per_length * g
    P, moment = TIP_MASS * g, TIP_MASS * g * TIP_OFFSET
    w = P * L**3 / (3 * EI) + moment * L**2 / (2 * EI) + q * L**4 / (8 * EI)
    slope = P * L**2 / (2 * EI) + moment * L / EI + q * L**3 / (6 * EI)
    assert moment * L**2 / (2 * EI) > 0.05 * w  # the offset's moment is a visible share (7 %)
    if formulation == "ancf":
        beam = AncfBeam(L, 4, THICK)
        system = single_beam_system(beam, radius=0.35, twist=np.pi / 2, gravity=(0, -g, 0), tip_body=body)
    else:
        beam = FfrBeam(L, 4, THICK)
        system = single_beam_system(beam, radius=0.35, twist=np.pi / 2, gravity=(0, -g, 0), tip_body=body)
    sol = solve_static(system, load_steps=2)
    part, qk = system.beams[0], sol.x[system.layout.beam_x(0)]
    position = (lambda s: beam.interpolate(qk, s)[0]) if formulation == "ancf" else \
        (lambda s: part.point_position(qk, system.root_pose(0, sol.x, sol.chart), s))
    tip = system.tip_displacement(sol.x)
    # ANCF (nonlinear, cubic centre line): measured 9e-6 and 1.7e-6, a discretisation effect
    # that falls ~16x per mesh halving and grows with the load squared (about 1 % with 2
    # elements at g = 9.81: the cubic centre line cannot bend without stretching);
    # FFR (linear, Hermite cubics are nodally exact): round-off, the slope by the difference 2e-7
    tol = 5e-5 if formulation == "ancf" else 1e-10
    assert -tip["vertical"] == pytest.approx(w, rel=tol)
    assert -tip_slope(position, L) == pytest.approx(slope, rel=max(tol, 1e-6))
    assert abs(tip["tangential"]) < 1e-12
