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
    from hubbeam.solvers.generalized_alpha import NewtonOptions

    sensors = [Sensor(name="tip", kind="tip_deflection")]
    tips = []
    for update in ("iteration", "step", "adaptive"):
        traj = simulate(free_hub(damping=(1.73, 1.4)), sensors, t_end=0.3, dt=2e-3, output_dt=0.3,
                        newton=NewtonOptions(update=update))
        tips.append(list(traj.records["tip"][-1].values()))
    tips = np.array(tips)
    assert np.max(np.abs(tips - tips[0])) < 1e-7
