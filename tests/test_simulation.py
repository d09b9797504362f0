"""Runs of the hub-beam system: steady rotation, Kane's spin-up, chart replacement mid-run."""

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from hubbeam.api import tip_displacement
from hubbeam.elements.section import Section
from hubbeam.io.scenario import Sensor
from hubbeam.simulation import change_chart, initial_state, simulate
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers import newton_control as nc
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.laws import DriveProfile
from hubbeam.system.multibody import single_beam_system
from tests.conftest import L, plate

TIP = Sensor(name="tip", kind="tip_deflection")


@pytest.mark.slow
def test_ten_revolutions_at_constant_speed_stay_on_the_static_centrifugal_state():
    """exp1's beam (twist 45 deg, gravity) driven at 3 rad/s for ten revolutions from the
    steady state: in the hub frame the tip must stay where the static analysis with the
    centrifugal load puts it, with no chart change and the constraints at round-off."""
    omega = 3.0
    system = single_beam_system(AncfBeam(L, 4, plate()), radius=0.35, twist=np.pi / 4, motion="prescribed",
                           drive=DriveProfile("constant", omega), gravity=np.array([0, -9.81, 0]))
    steady = tip_displacement(system, solve_static(system, spin=omega).x)
    sensors = [TIP, Sensor(name="angle", kind="hub_angle"), Sensor(name="torque", kind="hub_torque"),
               Sensor(name="violation", kind="constraint_violation")]
    traj = simulate(system, sensors, t_end=10 * 2 * np.pi / omega, dt=4e-3, output_dt=0.2)
    assert traj.records["angle"][-1] == pytest.approx(20 * np.pi, rel=1e-3)
    assert traj.chart_switches == 0
    assert abs(steady["vertical"]) > 0.1 and abs(steady["tangential"]) > 0.1  # a bent, twisted state
    for part in ("radial", "vertical", "tangential"):
        assert max(abs(r[part] - steady[part]) for r in traj.records["tip"]) < 5e-5
    assert max(traj.records["violation"]) < 1e-12
    # steady and undamped: the drive does no work (torque at the level of the discretisation)
    assert max(abs(t) for t in traj.records["torque"]) < 1e-2


def kane_beam() -> Section:
    """Kane, Ryan and Banerjee (1987): E = 7e10 Pa, rho = 3000 kg/m^3, A = 4e-4 m^2, I = 2e-7 m^4
    (EI = 14 000 N m^2, rho A = 1.2 kg/m), here as a rectangle whose thickness is tangential."""
    h = np.sqrt(12 * 2e-7 / 4e-4)
    return Section(4e-4 / h, h, 3000.0, 7e10, 7e10 / 2.6, 1e-6)


def quasi_static_tip(drive, t, L=10.0, EI=14000.0, rhoA=1.2):
    """In-plane tip deflection of the linear rotating beam under the Euler load -rho A alpha x,
    with centrifugal stiffening -(N w')' and softening -rho A w^2 w (scipy BVP), R = 0."""
    _, w, a = drive(t)

    def rhs(x, y):
        N = rhoA * w * w * (L * L - x * x) / 2
        return np.vstack([y[1], y[2] / EI, y[3] + N * y[1], -rhoA * a * x + rhoA * w * w * y[0]])

    xs = np.linspace(0, L, 50)
    sol = solve_bvp(rhs, lambda ya, yb: np.array([ya[0], ya[1], yb[2], yb[3]]), xs, np.zeros((4, 50)), tol=1e-8)
    return sol.sol(L)[0]


def test_kane_spin_up_follows_the_quasi_static_lag_and_stays_bounded():
    """Kane's spin-up, omega_s = 4 rad/s, T = 15 s, 10 m beam (8 elements): the tangential tip
    deflection lags (negative) by about 0.40 m at mid spin-up, follows the quasi-static linear
    rotating-beam solution to within a small dynamic ripple, and stays bounded after T; the
    radial stretch at 4 rad/s is rho w^2 L^3 / (3 E). A formulation without geometric stiffening
    diverges here (Kane et al. 1987)."""
    drive = DriveProfile("spin_up", 4.0, 15.0)
    system = single_beam_system(AncfBeam(10.0, 8, kane_beam()), radius=0.0, twist=0.0, motion="prescribed", drive=drive)
    traj = simulate(system, [TIP], t_end=20.0, dt=0.01, output_dt=0.5)
    t = np.array(traj.times)
    tang = np.array([r["tangential"] for r in traj.records["tip"]])
    during = t <= 15.0
    expected = np.array([quasi_static_tip(drive, ti) for ti in t[during]])
    assert np.max(np.abs(tang[during] - expected)) < 0.01
    assert -0.45 < tang.min() < -0.35
    assert np.max(np.abs(tang[t > 15.0])) < 0.01
    radial = np.array([r["radial"] for r in traj.records["tip"]])[t > 15.0]
    assert np.mean(radial) == pytest.approx(3000.0 * 16.0 * 1000.0 / (3 * 7e10), rel=0.05)


def _switch_difference(elements: int, tilted: bool) -> float:
    """Largest position / frame difference after 100 steps of a falling, turning beam between
    a run that changes its chart at step 50 and one that does not."""
    system = single_beam_system(AncfBeam(L, elements, plate()), radius=0.35, twist=np.pi / 4, motion="free",
                           hub_inertia=9.557, gravity=np.array([0, -9.81, 0]))
    p = ga.AlphaParameters.from_spectral_radius(0.8)
    reference = switched = initial_state(system)
    tilt = np.linalg.qr(np.array([[0.3, 0.9, 0.2], [-0.8, 0.3, 0.1], [0.1, -0.2, 1.0]]))[0]
    tilt *= np.sign(np.linalg.det(tilt))
    for k in range(100):
        reference, _, _ = ga.step(system, reference, 2e-3, p)
        if k == 50:
            switched = change_chart(system, switched, tilt[None] if tilted else switched.chart.copy())
        switched, _, _ = ga.step(system, switched, 2e-3, p)
    beam = system.beam
    diff = abs(reference.v[0] - switched.v[0])
    for station in (0.0, 0.7, L):
        diff = max(diff, np.max(np.abs(beam.interpolate(reference.x[1:], station)[0]
                                       - beam.interpolate(switched.x[1:], station)[0])))
        diff = max(diff, np.max(np.abs(beam.frame_at(reference.x[1:], reference.chart[0], station)
                                       - beam.frame_at(switched.x[1:], switched.chart[0], station))))
    return diff


def test_a_chart_change_mid_run_does_not_change_the_motion():
    """Moving the state to another chart changes nothing when the chart is the same, and
    otherwise only by the cubic interpolation of the re-expressed twist inside curved elements
    (docs/ancf.md): a discretisation effect that vanishes fast under mesh refinement."""
    assert _switch_difference(4, tilted=False) < 1e-12  # round-off, through Newton's stop (1.6e-14 at KAPPA 0.1, 1.1e-13 at 0.01)
    coarse, fine = _switch_difference(8, tilted=True), _switch_difference(16, tilted=True)
    assert coarse < 1e-4
    assert fine < coarse / 16


def test_a_constant_drive_starts_in_steady_rotation():
    system = single_beam_system(AncfBeam(L, 4, plate()), radius=0.35, twist=np.pi / 4, motion="prescribed",
                           drive=DriveProfile("constant", 2.0), gravity=np.array([0, -9.81, 0]))
    state = initial_state(system)
    assert state.v[0] == 2.0
    assert np.allclose(state.chart[0][:, 0], [0, -1, 0])


def test_steady_rotation_with_drag_the_drive_pays_for_the_dissipation():
    """With drag the steady state lags; it stays put in the hub frame, and the drive's work
    equals the work dissipated by drag (energy balance, an independent check of the
    steady-rotation load's drag part and of the drive torque multiplier)."""
    system = single_beam_system(AncfBeam(L, 4, plate()), radius=0.35, twist=np.pi / 4, motion="prescribed",
                           drive=DriveProfile("constant", 3.05), gravity=np.array([0, -9.81, 0]),
                           damping=(1.73, 1.4))
    sensors = [TIP, Sensor(name="energy", kind="energy")]
    traj = simulate(system, sensors, t_end=0.5, dt=2e-3, output_dt=0.05)
    tips = np.array([[r["radial"], r["vertical"], r["tangential"]] for r in traj.records["tip"]])
    assert tips[0, 2] < -0.1  # the drag makes it lag
    assert np.max(np.abs(tips - tips[0])) < 1e-5
    e = traj.records["energy"][-1]
    assert e["dissipated"] > 1.0
    assert e["drive"] == pytest.approx(e["dissipated"], rel=1e-4)


def test_an_equilibrium_start_on_a_turning_hub_is_at_rest_in_the_runs_chart():
    """start = 'equilibrium' on a driven hub: the sag under gravity (bent out of one plane, twist
    80 deg) is solved in the axis chart the run uses, so the consistent accelerations vanish (a
    remap of the bent beam after the solve left an imbalance: accelerations up to 9e4 here)."""
    system = single_beam_system(AncfBeam(L, 4, plate()), radius=0.35, twist=np.radians(80.0), motion="prescribed",
                                drive=DriveProfile("spin_up", 3.0, 5.0), gravity=np.array([0, -9.81, 0]))
    state = initial_state(system, start="equilibrium")
    assert np.allclose(state.chart[0][:, 0], [0.0, -1.0, 0.0])  # the axis chart
    assert np.max(np.abs(state.xdd)) < 1e-3


def test_strain_gauges_read_over_a_chunk_are_the_gauges_read_state_by_state():
    """Compiled steps read every gauge of a chunk's records at once: ANCF gauges in the compiled
    measures, FFR gauges (nodal with geometric stiffening, and modal) in one product over the
    records. Each record's strains equal the parts' own surface_strain at that record's state,
    gauge by gauge (the wiring: keys, beams, charts, record order); surface_strain itself is
    held to closed forms in tests/elements and tests/system."""
    from hubbeam.elements.ffr.body import FfrBeam
    from hubbeam.simulation import CompiledSteps
    from hubbeam.system.ancf_part import AncfPart
    from hubbeam.system.ffr_part import FfrPart
    from hubbeam.system.multibody import Hub, MultibodySystem
    from hubbeam.system.mount import Mount

    parts = [AncfPart(AncfBeam(L, 3, plate()), Mount(0.3, 0.2, 0.0, 0.0), name="a"),
             FfrPart(FfrBeam(L, 3, plate(), geometric_stiffening=True), Mount(0.3, 0.4, 2.0, 0.0), name="b"),
             FfrPart(FfrBeam(L, 4, plate(), modes=3), Mount(0.3, -0.3, 4.0, 0.1), name="c")]
    system = MultibodySystem(parts, Hub("prescribed", 1.0, drive=DriveProfile("spin_up", 3.0, 0.2)),
                       gravity=(0.0, -9.81, 0.0))
    gauges = [(0, 0.2, 0.01, 0.00125), (1, 0.3, -0.02, 0.00125), (1, 1.0, 0.0, -0.00125), (2, 0.5, 0.01, 0.00125)]
    state = initial_state(system)
    params = ga.AlphaParameters.from_spectral_radius(0.8)
    steps = CompiledSteps(system, params, nc.NewtonOptions(), 2e-3, state, (False, False, gauges))
    *_, error, chunk = steps.advance(state, 60, 0, 20, 60)
    assert error is None and len(chunk) == 3
    for i in range(len(chunk)):
        st = chunk.state(i)
        for beam, x, y, z in gauges:
            expected = system.surface_strain(st.x, st.chart, x, y, z, beam)
            assert abs(expected) > 1e-7
            assert chunk.strains[(beam, x, y, z)][i] == pytest.approx(expected, rel=1e-9)  # ANCF: compiled and Python strain measures


def test_sensors_read_over_a_chunk_are_the_sensors_read_state_by_state():
    """Sensors read a chunk of compiled records at once (the compiled steps' energies, tips and
    gauges as arrays, :func:`hubbeam.sensors.prepare_chunk`). Every sensor of the spacecraft
    example -- one panel ANCF, the other shorter, lighter and FFR on 3 modes, both with tip
    bodies, under a PD controller and gravity -- plus the energy of one beam and a gauge on the FFR panel gives, at every
    record, what it gives read state by state (:func:`hubbeam.sensors.prepare`: the Python
    tip positions and strains, the system's energies)."""
    from hubbeam import api
    from hubbeam.io.scenario import load_example, validate
    from hubbeam.sensors import prepare, prepare_chunk, record_needs
    from hubbeam.simulation import CompiledSteps

    scenario = load_example("spacecraft", ['beams[1].formulation="ffr"', "beams[1].modes=3", "beams[1].length=1.5",
                                           "beams[1].tip_body.mass=0.4", "environment.gravity=[0.0, -9.81, 0.0]"])
    extra = [{"name": "energy_b", "kind": "energy", "beam": "panel_b"},
             {"name": "strain_b", "kind": "surface_strain", "beam": "panel_b", "x": 0.4, "surface": "lower"}]
    scenario = validate({**scenario.model_dump(exclude_none=True),
                         "sensors": [s.model_dump(exclude_none=True) for s in scenario.sensors] + extra})
    system = api.build_system(scenario)
    assert system.compiled
    state = initial_state(system)
    params = ga.AlphaParameters.from_spectral_radius(0.8)
    steps = CompiledSteps(system, params, nc.NewtonOptions(), 2e-3, state, record_needs(scenario.sensors, system))
    *_, error, chunk = steps.advance(state, 90, 0, 30, 90)
    assert error is None and len(chunk) == 3
    assert {s.kind for s in scenario.sensors} >= {"hub_angle", "hub_angular_velocity", "applied_torque",
                                                  "tip_deflection", "surface_strain", "angular_momentum", "energy"}
    for sensor in scenario.sensors:
        together = prepare_chunk(sensor, system)(chunk)
        one_by_one = [prepare(sensor, system)(chunk.state(i), chunk.work(i)) for i in range(len(chunk))]
        assert len(together) == len(one_by_one) == 3
        for a, b in zip(together, one_by_one):
            if isinstance(b, dict):
                assert a.keys() == b.keys(), sensor.name
                assert [a[k] for k in b] == pytest.approx([b[k] for k in b], rel=1e-9, abs=1e-12), sensor.name
            else:
                assert a == pytest.approx(b, rel=1e-9, abs=1e-15), sensor.name


def test_base_sensors_read_over_a_chunk_are_the_base_sensors_read_state_by_state():
    """The free base's sensors read over a chunk of records in one compiled call
    (:meth:`MultibodySystem.base_motions`) give, at every record of a tumbling spacecraft with
    FFR panels, what the Python frame gives state by state (:func:`hubbeam.sensors.prepare`);
    a wrong chain, a velocity without the Euler-parameter rates or the angular velocity in
    global instead of base axes would differ."""
    from hubbeam import api
    from hubbeam.io.scenario import load_example, validate
    from hubbeam.sensors import prepare, prepare_chunk, record_needs
    from hubbeam.simulation import CompiledSteps

    scenario = load_example("spacecraft3d", ['beams[*].formulation="ffr"', "beams[*].modes=2",
                                             "base.initial.angular_velocity=[0.1, 0.3, 0.2]",
                                             "base.initial.velocity=[0.5, -0.2, 0.1]"])
    extra = [{"name": "where", "kind": "base_position"}, {"name": "speed", "kind": "base_velocity"},
             {"name": "turn", "kind": "base_angular_velocity"}]
    scenario = validate({**scenario.model_dump(exclude_none=True), "sensors": extra})
    system = api.build_system(scenario)
    state = initial_state(system)
    steps = CompiledSteps(system, ga.AlphaParameters.from_spectral_radius(0.8), nc.NewtonOptions(), 2e-3, state,
                          record_needs(scenario.sensors, system))
    *_, error, chunk = steps.advance(state, 60, 0, 20, 60)
    assert error is None and len(chunk) == 3
    for sensor in scenario.sensors:
        together = prepare_chunk(sensor, system)(chunk)
        one_by_one = [prepare(sensor, system)(chunk.state(i), chunk.work(i)) for i in range(len(chunk))]
        assert len(together) == 3
        for a, b in zip(together, one_by_one):
            assert a.keys() == b.keys()
            assert max(abs(b[k]) for k in b) > 1e-3, sensor.name  # moving: the test can tell
            assert [a[k] for k in b] == pytest.approx([b[k] for k in b], rel=1e-12, abs=1e-15), sensor.name


@pytest.mark.parametrize("t0, dt", [(0.0, 1e-3), (0.3, 5e-3), (12.345, 0.0025), (0.1 + 0.2, 1e-5), (3.0, 0.3)])
def test_output_times_are_the_doubles_nearest_the_decimal_times(t0, dt):
    """The output time after k steps is the double nearest the decimal t0 + k dt (not the sum
    of steps); integer arithmetic over a common power of ten gives what Python's decimal
    arithmetic gives, for steps up to 10^6."""
    from decimal import Decimal

    from hubbeam.simulation import decimal_units

    t0_units, dt_units, scale = decimal_units(t0, dt)
    for k in (0, 1, 7, 999, 20_000, 123_457, 1_000_000):
        assert (t0_units + dt_units * k) / scale == float(Decimal(repr(t0)) + Decimal(repr(dt)) * k)
    assert (0 + decimal_units(0.0, 1e-3)[1] * 20_000) / decimal_units(0.0, 1e-3)[2] == 20.0


def test_a_fixed_hubs_holding_torque_is_tested_as_a_torque_only_where_a_sensor_reads_it():
    """The bundled spacecraft3d (a fixed hub on a free bus): without a ``hub_torque`` sensor the
    Newton test leaves the holding torque to the length test (NewtonOptions.hold_torque), so
    fewer iterations, and the motion it records is the same to well within the tolerance's
    effect; with the sensor the torque is converged as a torque again: the same iterations as
    a run that tests it always."""
    from dataclasses import replace

    from hubbeam import api
    from hubbeam.io.scenario import load_example

    base = load_example("spacecraft3d", ["analysis.t_end=3", "analysis.output_dt=0.5"])
    plain, failure = api.run(base)
    assert failure is None
    held = api.with_sensors(base, [*base.sensors, {"name": "hold", "kind": "hub_torque"}])
    read, failure = api.run(held)
    assert failure is None
    assert plain.newton_iterations < 0.95 * read.newton_iterations
    for name in ("rate", "tip_a", "tip_b"):
        a, b = (np.array([[r[k] for k in sorted(r)] for r in t.records[name]]) for t in (plain, read))
        assert np.max(np.abs(a - b)) <= 1e-6 * np.max(np.abs(b)), name
    hold = np.asarray(read.records["hold"], dtype=float)
    assert np.ptp(hold) > 0.1  # the slew loads the hub: the torque converged is not trivially zero
    strict = simulate(api.build_system(held), [s for s in held.sensors if s.kind != "hub_torque"], 3.0,
                      held.analysis.dt, output_dt=0.5, newton=replace(nc.NewtonOptions(), hold_torque=True))
    assert strict.newton_iterations > plain.newton_iterations
