"""Large deflection: the elastica, an end moment rolling the beam into circles, Newton's matrix."""

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from hubbeam.errors import ConvergenceError
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.multibody import single_beam_system
from tests.conftest import L, central_difference, plate


def elastica_tip(k):
    """Inextensible cantilever, dead tip load P perpendicular to the undeformed axis, k = P L^2 / EI.

    theta'' = k cos(theta) on [0, 1], theta(0) = 0, theta'(1) = 0 (scipy's BVP solver):
    returns the tip (x, y) / L, y along the load."""
    s = np.linspace(0, 1, 201)
    sol = solve_bvp(lambda s, y: np.vstack([y[1], k * np.cos(y[0])]), lambda a, b: np.array([a[0], b[1]]),
                    s, np.zeros((2, s.size)), tol=1e-10, max_nodes=100000)
    assert sol.success
    ss = np.linspace(0, 1, 20001)
    th = sol.sol(ss)[0]
    return np.trapezoid(np.cos(th), ss), np.trapezoid(np.sin(th), ss)


def test_elastica_oracle_matches_published_values():
    # Bisshopp & Drucker (1945): vertical tip deflection / L = 0.3017 at k = 1, 0.8106 at k = 10
    assert np.isclose(-elastica_tip(1.0)[1], 0.3017, atol=2e-4)
    assert np.isclose(-elastica_tip(10.0)[1], 0.8106, atol=2e-4)


@pytest.mark.parametrize("k", [1.0, 2.0, 5.0, 10.0])
def test_tip_force_follows_the_elastica(k):
    sec = plate()
    EIy = sec.stiffness[2]
    # twist 90 deg: the weak axis bends in the vertical plane; the load points down (-j0)
    x_ref, y_ref = elastica_tip(k)
    errors = []
    for n in (12, 24):
        system = single_beam_system(AncfBeam(L, n, sec), radius=0.0, twist=np.pi / 2, motion="fixed",
                               tip_force=np.array([0.0, -k * EIy / L**2, 0.0]))
        tip = solve_static(system, load_steps=10).x[1:][system.beam.node_slice(-1)][0:3] / L
        errors.append(np.hypot(tip[0] - x_ref, tip[1] - y_ref))
        assert abs(tip[2]) < 1e-9
    # 24 elements: within 2e-4 L of the elastica (measured 1.3e-4 L at k = 10), and converging
    assert errors[1] < 2e-4
    assert errors[1] < errors[0] / 4 or errors[1] < 1e-6


def circle_case(fraction, case, elements=16):
    """End moment rolling the beam into ``fraction`` of a circle.

    plate-j: plate, weak axis, bending about j0 (circle in the horizontal x-z plane)
    plate-k: plate twisted 90 deg, weak axis, bending about k0 (circle in the vertical x-y plane)
    square-k: square section, bending about n = k0 (the kappa3 path) in the x-y plane"""
    if case == "square-k":
        sec, twist, axis = plate(0.01, 0.01), 0.0, np.array([0, 0, 1.0])
        EI = sec.stiffness[3]
    else:
        sec = plate()
        EI = sec.stiffness[2]
        twist, axis = (0.0, np.array([0, 1.0, 0])) if case == "plate-j" else (np.pi / 2, np.array([0, 0, 1.0]))
    M = 2 * np.pi * fraction * EI / L
    system = single_beam_system(AncfBeam(L, elements, sec), radius=0.0, twist=twist, motion="fixed", tip_moment=M * axis)
    return system, axis, solve_static(system, load_steps=int(40 * fraction))


@pytest.mark.parametrize("case", ["plate-j", "plate-k", "square-k"])
def test_end_moment_rolls_the_beam_into_half_and_full_circle(case):
    system, axis, half = circle_case(0.5, case)
    tip = half.x[1:][system.beam.node_slice(-1)]
    # half circle: tip at 2 L / pi across the axis, tangent reversed
    side = np.cross(axis, [1.0, 0, 0])  # direction the beam curls towards
    assert np.allclose(tip[0:3], 2 * L / np.pi * side, atol=2e-4)
    assert np.allclose(tip[3:6] / np.linalg.norm(tip[3:6]), [-1, 0, 0], atol=2e-3)
    system, axis, full = circle_case(1.0, case)
    tip = full.x[1:][system.beam.node_slice(-1)]
    assert np.linalg.norm(tip[0:3]) < 5e-4
    assert np.allclose(tip[3:6] / np.linalg.norm(tip[3:6]), [1, 0, 0], atol=2e-3)
    assert full.chart_switches >= 1  # the tangent swept through the first chart's singular direction
    # every point lies on the circle of radius L / (2 pi)
    centre = L / (2 * np.pi) * side
    pts = np.array([system.beam.interpolate(full.x[1:], s)[0] for s in np.linspace(0, L, 50)])
    assert np.allclose(np.linalg.norm(pts - centre, axis=1), L / (2 * np.pi), atol=5e-4)


def test_full_circle_tip_error_converges():
    errors = []
    for n in (8, 16, 32):  # measured: 2.7e-2, 2.6e-4, 9.4e-6 m
        system, _, full = circle_case(1.0, "plate-k", elements=n)
        errors.append(np.linalg.norm(full.x[1:][system.beam.node_slice(-1)][0:3]))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(rates > 3.0), (errors, rates)


def test_newton_matrix_is_the_derivative_of_the_residual_and_symmetric_at_equilibrium():
    sec = plate()
    system = single_beam_system(AncfBeam(L, 3, sec), radius=0.35, twist=0.7, motion="fixed",
                           gravity=np.array([0, -9.81, 0]), tip_force=np.array([0.3, -1.0, 0.5]))
    sol = solve_static(system, load_steps=4)
    mu = sol.multipliers / system.constraint_scale
    res, matrix = system.static_equations(sol.x, mu, sol.chart, 1.0)
    A = matrix.to_dense()
    layout = system.layout_for(True)

    def residual(z):
        x, mu = layout.split_z(z)
        return system.static_equations(x, mu, sol.chart, 1.0)[0]

    z = layout.to_z(sol.x, mu)
    A_fd = central_difference(residual, z, 1e-7)
    assert np.max(np.abs(A - A_fd)) < 1e-5 * np.max(np.abs(A))
    assert np.max(np.abs(A - A.T)) < 1e-8 * np.max(np.abs(A))
    assert np.max(np.abs(res)) < 1e-6


def test_failure_names_the_load_step_and_keeps_the_last_equilibrium():
    sec = plate()
    EIy = sec.stiffness[2]
    system = single_beam_system(AncfBeam(L, 4, sec), twist=np.pi / 2, motion="fixed",
                           tip_moment=np.array([0, 0, 6 * np.pi * EIy / L]))
    with pytest.raises(ConvergenceError) as info:
        solve_static(system, load_steps=1, max_cuts=0, max_iterations=5)
    assert "load step 1" in str(info.value) and "load_steps" in str(info.value)
    assert info.value.partial is not None and info.value.partial.load_factor == 0.0
