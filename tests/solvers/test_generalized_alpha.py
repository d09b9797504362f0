"""Generalized-alpha on the hub-beam DAE: energy balance, constraint satisfaction, parameters."""

import numpy as np
import pytest

from hubbeam.io.scenario import Sensor
from hubbeam.simulation import simulate
from hubbeam.solvers.generalized_alpha import AlphaParameters
from hubbeam.system.beam import AncfBeam
from hubbeam.system.multibody import single_beam_system
from tests.conftest import L, plate

SENSORS = [Sensor(name="energy", kind="energy"), Sensor(name="violation", kind="constraint_violation"),
           Sensor(name="omega", kind="hub_angular_velocity")]


def free_hub(damping=(0.0, 0.0), elements=4):
    return single_beam_system(AncfBeam(L, elements, plate()), radius=0.35, twist=np.pi / 4, motion="free",
                         hub_inertia=9.557, gravity=np.array([0, -9.81, 0]), damping=damping)


def test_chung_hulbert_parameters():
    p = AlphaParameters.from_spectral_radius(1.0)
    assert (p.alpha_m, p.alpha_f, p.gamma, p.beta) == pytest.approx((0.5, 0.5, 0.5, 0.25))
    p = AlphaParameters.from_spectral_radius(0.8)
    assert p.gamma == pytest.approx(0.5 + p.alpha_f - p.alpha_m)


def test_free_hub_without_damping_conserves_energy():
    traj = simulate(free_hub(), SENSORS, t_end=0.6, dt=2e-3, spectral_radius=1.0, output_dt=0.02)
    e = traj.records["energy"]
    total = np.array([r["total"] for r in e])
    scale = max(r["kinetic"] for r in e)
    assert scale > 0.05  # the beam falls and the hub turns: energy is exchanged
    assert np.max(np.abs(total - total[0])) < 1e-4 * scale
    assert np.max(traj.records["violation"]) < 1e-10
    assert max(abs(w) for w in traj.records["omega"]) > 1e-3


def test_with_damping_total_plus_dissipated_is_constant():
    traj = simulate(free_hub(damping=(1.73, 1.4)), SENSORS, t_end=0.6, dt=2e-3, spectral_radius=1.0, output_dt=0.02)
    e = traj.records["energy"]
    balance = np.array([r["total"] + r["dissipated"] for r in e])
    assert e[-1]["dissipated"] > 1e-3
    assert np.max(np.abs(balance - balance[0])) < 1e-3 * e[-1]["dissipated"] + 1e-6


def test_free_hub_keeps_angular_momentum_about_the_axis():
    """Gravity is parallel to j0: no torque about the axis, so H (zero at rest) stays zero
    while hub and beam exchange momentum."""
    sensors = SENSORS + [Sensor(name="H", kind="angular_momentum")]
    traj = simulate(free_hub(), sensors, t_end=1.0, dt=2e-3, spectral_radius=1.0, output_dt=0.02)
    hub_momentum = 9.557 * max(abs(w) for w in traj.records["omega"])
    assert hub_momentum > 1e-2
    assert max(abs(h) for h in traj.records["H"]) < 1e-4 * hub_momentum


def test_angular_momentum_sensor_matches_a_direct_quadrature():
    """H from M(q) v (the sensor) against sum rho A (r x r_dot) . (-j0) dx + J theta_dot by
    Gauss quadrature of the interpolated centre line, plus the sections' spin
    rho (I_y + I_z) omega_axis, for a beam in rigid rotation (a known velocity field)."""
    from hubbeam.elements.hermite import gauss_legendre

    system = free_hub()
    x, F = system.axis_chart(*system.initial_state(0.3))
    v, _ = system.steady_rotation_rates(x, F, 1.7)
    beam = system.beam
    sec = beam.section
    xi, w = gauss_legendre(6)
    h_direct = system.hub.inertia * 1.7
    l = beam.element_length
    for e in range(beam.elements):
        for s, ws in zip(xi, w):
            r = beam.interpolate(x[1:], (e + s) * l)[0]
            rdot = beam.interpolate(v[1:], (e + s) * l)[0]
            h_direct += sec.mass_per_length * np.cross(r, rdot) @ np.array([0, -1.0, 0]) * ws * l
    # the sections spin about j0 too: rho I_axis omega per length, with the area moment of
    # the section about the in-plane direction j0 = a_m m + a_n n: i_y a_m^2 + i_z a_n^2
    # (i_y = b h^3 / 12 is the moment about m, the width axis)
    frame = beam.frame_at(x[1:], F[0], 0.0)
    a_m, a_n = frame[:, 1] @ [0, 1, 0], frame[:, 2] @ [0, 1, 0]
    h_direct += sec.density * (sec.i_y * a_m**2 + sec.i_z * a_n**2) * 1.7 * beam.length
    h_sensor = system.angular_momentum(x, v, F)
    assert h_sensor == pytest.approx(h_direct, rel=1e-6)


def test_second_order_convergence_in_dt_on_a_smooth_spin_up():
    """Prescribed smooth spin-up (no jump in acceleration), tip deflection and drive torque at
    t = 0.4 s: the differences between successive halvings of dt fall by about 4."""
    from hubbeam.system.laws import DriveProfile

    sensors = [Sensor(name="tip", kind="tip_deflection"), Sensor(name="torque", kind="hub_torque"),
               Sensor(name="violation", kind="constraint_violation")]
    values = []
    for dt in (4e-3, 2e-3, 1e-3, 5e-4):
        system = single_beam_system(AncfBeam(L, 4, plate()), radius=0.35, twist=np.pi / 4, motion="prescribed",
                               drive=DriveProfile("spin_up", 1.0, 1.0))
        traj = simulate(system, sensors, t_end=0.4, dt=dt, spectral_radius=0.8, output_dt=0.4)
        assert max(traj.records["violation"]) < 1e-14
        tip = traj.records["tip"][-1]
        values.append([tip["tangential"], tip["vertical"], traj.records["torque"][-1]])
    diffs = np.abs(np.diff(np.array(values), axis=0))
    ratios = diffs[:-1] / diffs[1:]
    assert np.all(ratios > 3.2), ratios
    assert abs(values[-1][0]) > 0.01  # the beam does lag


def test_modified_newton_gives_the_full_newton_answer():
    from hubbeam.solvers.newton_control import NewtonOptions

    sensors = [Sensor(name="tip", kind="tip_deflection")]
    tips = []
    for update in ("iteration", "step", "adaptive"):
        traj = simulate(free_hub(damping=(1.73, 1.4)), sensors, t_end=0.3, dt=2e-3, output_dt=0.3,
                        newton=NewtonOptions(update=update))
        tips.append(list(traj.records["tip"][-1].values()))
    tips = np.array(tips)
    assert np.max(np.abs(tips - tips[0])) < 1e-7


def _modified_and_full(example, overrides):
    """The example's results with newton = "modified" (the default) and "full"."""
    from hubbeam import api
    from hubbeam.io.results import to_dataset
    from hubbeam.io.scenario import load_example

    out = {}
    for newton in ("modified", "full"):
        sc = load_example(example, overrides + [f'analysis.newton="{newton}"'])
        traj, failure = api.run(sc)
        assert failure is None
        out[newton] = to_dataset(traj, sc)
    return out["modified"], out["full"]


@pytest.mark.slow
@pytest.mark.parametrize("dt", ["0.001", "0.0005"])
def test_the_newton_test_does_not_loosen_with_dt_rotor3(dt):
    """rotor3 (8 elements per blade, 3 s of the spin-up) at dt = 1 ms and 0.5 ms: modified and
    full Newton give one hub torque (1e-5 of its peak) and the three identical blades stay
    identical (1e-13 m); measured 2.3e-6 and 8.7e-7 N m, 1e-15 m. With the drive's torque tested
    as a length (beta h^2 lambda / mass scale) its tolerance grew as 1/h^2: a 211 Hz blade
    oscillation of 0.019 N m (1 ms) and 0.0075 N m (0.5 ms) in hub_torque, 760 times the run's
    time-discretisation error, blades apart by 9e-10 m."""
    modified, full = _modified_and_full("rotor3", ["beams[*].elements=8", f"analysis.dt={dt}", "analysis.t_end=3.0"])
    peak = float(np.abs(full["drive_torque"]).max())
    assert float(np.abs(modified["drive_torque"] - full["drive_torque"]).max()) < 1e-5 * peak
    for ds in (modified, full):
        assert float(np.abs(ds["tip1_vertical"] - ds["tip2_vertical"]).max()) < 1e-13


@pytest.mark.slow
@pytest.mark.parametrize("dt,t_end,torque,pair", [("0.001", "20.0", 5e-5, 1e-8), ("0.0005", "10.0", 1e-6, 1e-10)])
def test_the_newton_test_does_not_loosen_with_dt_spacecraft(dt, t_end, torque, pair):
    """spacecraft (8 elements per panel) at dt = 1 ms (20 s) and 0.5 ms (10 s): modified and
    full Newton give one control torque (5e-5 and 1e-6 of its peak) and keep the two identical
    panels together (1e-8 and 1e-10 m; full Newton: 1e-14 m); measured 2.3e-5 N m and 3.2e-9 m
    at 1 ms, 2.3e-8 N m and 6e-12 m at 0.5 ms. Before (KAPPA = 0.1): 3.3e-5 N m and 4.0e-8 m
    at 1 ms, 1.4e-5 N m and 1.2e-8 m at 0.5 ms: modified Newton's stop at 0.1 of the
    tolerance, its errors adding up in the undamped panel modes, more of them as dt shrinks."""
    modified, full = _modified_and_full("spacecraft", ["beams[*].elements=8", f"analysis.dt={dt}",
                                                       f"analysis.t_end={t_end}"])
    peak = float(np.abs(full["torque"]).max())
    assert float(np.abs(modified["torque"] - full["torque"]).max()) < torque * peak
    assert float(np.abs(modified["tip_a_tangential"] - modified["tip_b_tangential"]).max()) < pair
    assert float(np.abs(full["tip_a_tangential"] - full["tip_b_tangential"]).max()) < 1e-12


# --- the first-iteration test with a borrowed contraction rate (NewtonOptions.borrowed_rate_steps) ---

def _exp1(extra):
    from hubbeam import api
    from hubbeam.io.scenario import load_example

    return api.build_system(load_example("exp1", ['beam.formulation="ffr"'] + extra))


def _compiled_run(system, options, steps, every=10, dt=1e-3):
    """(recorded coordinates, Newton iterations per step) of ``steps`` compiled steps from the start."""
    from hubbeam.simulation import CompiledSteps, initial_state
    from hubbeam.solvers import generalized_alpha as ga

    state = initial_state(system)
    loop = CompiledSteps(system, ga.AlphaParameters.from_spectral_radius(0.8), options, dt, state)
    _, n, its, _, error, chunk = loop.advance(state, steps, 0, every, steps)
    assert error is None and n == steps
    return chunk.states.x, its / steps


def test_the_borrowed_rate_keeps_the_results_within_the_tolerance_of_a_run_converged_further():
    """exp1 on 4 modes (5 s at 1 ms, released under gravity: the matrix is kept for the whole
    run) stops most steps after one increment, and its coordinates stay within N tol L of the
    run converged to 1e-12 (N steps, each leaving at most the tolerance: the test bounds the
    estimate by kappa tol, which leaves a factor 1/kappa for a borrowed rate that is too
    small). Measured 6.4e-7 (the first mode's amplitude; the step size's error, dt against
    dt/2, is 4.9e-6 there), against 7.3e-6."""
    from hubbeam.solvers import newton_control as nc

    system = _exp1(["beam.modes=4"])
    steps = 5000
    reference, _ = _compiled_run(system, nc.NewtonOptions(tolerance=1e-12, borrowed_rate_steps=0), steps)
    x, newton = _compiled_run(system, nc.NewtonOptions(borrowed_rate_steps=8), steps)
    assert newton < 1.2  # measured 1.12: most steps stopped after one increment
    bound = steps * nc.NewtonOptions().tolerance * max(system.length_scale, 1.0)
    assert np.max(np.abs(x - reference)) < bound


def test_a_kept_matrix_that_goes_stale_within_steps_is_not_trusted_with_its_first_rates():
    """The nodal FFR beam on a stiff flap hinge, its matrix refactorised every ~6 steps (no
    column update): a rate borrowed as measured (no age factor, not the larger of two) let
    steps stop with 1e-8 m left (one pair of increments measured 2e-6 where the matrix
    contracted at 5e-3) and took the run 3.0e-7 from the run converged to 1e-12 in 2 s,
    against 2.9e-8 without borrowing. It must stay where borrowing leaves it (measured: equal)."""
    from hubbeam.solvers import newton_control as nc

    system = _exp1(['beam.joint={kind="revolute", axis="flap", stiffness=1.0e4}'])
    reference, _ = _compiled_run(system, nc.NewtonOptions(tolerance=1e-12, borrowed_rate_steps=0), 2000, every=20)
    never, _ = _compiled_run(system, nc.NewtonOptions(update_columns=False, borrowed_rate_steps=0), 2000, every=20)
    borrowed, _ = _compiled_run(system, nc.NewtonOptions(update_columns=False, borrowed_rate_steps=8), 2000, every=20)
    assert np.max(np.abs(borrowed - reference)) < 2.0 * np.max(np.abs(never - reference))


def test_the_compiled_loop_borrows_as_the_python_step_does_across_chunks():
    """exp1 on 4 modes, 300 steps in chunks of 7 (the rates are carried between the compiled
    loop's calls): the same Newton iterations in every chunk and the same states."""
    from hubbeam.simulation import CompiledSteps, PythonSteps, initial_state
    from hubbeam.solvers import generalized_alpha as ga
    from hubbeam.solvers import newton_control as nc

    system = _exp1(["beam.modes=4"])
    state = initial_state(system)
    p, options = ga.AlphaParameters.from_spectral_radius(0.8), nc.NewtonOptions(borrowed_rate_steps=8)
    fast, slow = CompiledSteps(system, p, options, 1e-3, state), PythonSteps(system, p, options, 1e-3, state)
    a = b = state
    total = 0
    for k in range(0, 301, 7):
        a, _, its_a, _, err_a, _ = fast.advance(a, 7, k, 7, 301)
        b, _, its_b, _, err_b, _ = slow.advance(b, 7, k, 7, 301)
        assert err_a is None and err_b is None and its_a == its_b
        total += its_a
    assert total < 1.3 * 301  # most steps stopped after one increment
    for u, w in ((a.x, b.x), (a.v, b.v), (a.lam, b.lam)):
        assert w.size == 0 or np.max(np.abs(u - w)) <= 1e-9 * max(1.0, np.max(np.abs(w)))


def test_without_borrowing_the_solver_gives_the_numbers_it_gave_before():
    """borrowed_rate_steps = 0 (the default): exp1 on 4 modes (20 s at 1 ms) gives the P1 strains and Newton
    iterations printed by the solver before the test existed (`python benchmarks/loop_cost.py
    first-iteration exp1_modal 1 0` on commit 3378476): 1.98675 iterations per step, P1 at 5 s
    2.732459343782e-4, peak 8.132899212080e-4, end 4.176980610330e-4 (with borrowing: 1.113 and
    2.7324627e-4, 8.1328826e-4, 4.1769884e-4)."""
    from hubbeam import api
    from hubbeam.io.scenario import load_example

    traj, failure = api.run(load_example("exp1", ['beam.formulation="ffr"', "beam.modes=4", "analysis.t_end=20.0"]))
    assert failure is None
    assert traj.newton_iterations == 39735 and traj.steps == 20000
    p1 = np.array(traj.records["strain_P1"])
    at5 = p1[int(np.argmin(np.abs(np.array(traj.times) - 5.0)))]
    assert [at5, p1.max(), p1[-1]] == pytest.approx([2.732459343782e-4, 8.132899212080e-4, 4.176980610330e-4],
                                                   rel=1e-10)


def test_a_modal_beam_on_a_free_hub_keeps_energy_and_angular_momentum_while_borrowing():
    """An undamped FFR beam on 4 modes on a free hub (rho_inf = 1, 5 s at 1 ms, the same model
    and bounds as tests/system/test_ffr_system.py's 0.6 s) with most steps stopping after one
    increment: the total energy within 1e-4 of the largest kinetic energy, the angular momentum
    about the axis (gravity along it) within 1e-4 of the hub's. Measured 6.8e-6 and 1.6e-5 (the
    energy's drift grows about linearly: 1.4e-5 at 10 s, 2.8e-5 at 20 s); without borrowing
    4e-8 and 5e-8 over 20 s: each borrowed step leaves theta |dx1|, with the same sign step
    after step, where a second iteration left theta^2 |dx1|."""
    from hubbeam.elements.ffr.body import FfrBeam
    from hubbeam.solvers import newton_control as nc

    system = single_beam_system(FfrBeam(L, 4, plate(), modes=4), radius=0.35, twist=np.pi / 4, motion="free",
                                hub_inertia=9.557, gravity=np.array([0, -9.81, 0]))
    sensors = SENSORS + [Sensor(name="H", kind="angular_momentum")]
    traj = simulate(system, sensors, t_end=5.0, dt=1e-3, spectral_radius=1.0, output_dt=0.05,
                    newton=nc.NewtonOptions(borrowed_rate_steps=8))
    assert traj.newton_iterations < 1.2 * traj.steps  # measured 1.11
    e = traj.records["energy"]
    total = np.array([r["total"] for r in e])
    assert np.max(np.abs(total - total[0])) < 1e-4 * max(r["kinetic"] for r in e)
    hub_momentum = 9.557 * max(abs(w) for w in traj.records["omega"])
    assert max(abs(h) for h in traj.records["H"]) < 1e-4 * hub_momentum
