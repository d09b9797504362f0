"""Clamp constraints: Jacobian and multiplier Hessian against finite differences, and meaning."""

import numpy as np
import pytest

from hubbeam.elements.ancf.chart import frame_from_director
from hubbeam.system.beam import AncfBeam
from hubbeam.system.clamp import clamp_constraints, clamp_twist_angle
from hubbeam.system.hub import clamp_frame, hub_frame
from hubbeam.system.ancf_system import AncfHubSystem
from tests.conftest import central_difference, plate

R, BETA = 0.35, np.radians(45)


@pytest.mark.parametrize("director", [[1, 0, 0], [0.2, 0.9, -0.3], [0, -1, 0]])
def test_twist_angle_rate_matches_finite_difference(director):
    F = frame_from_director(np.array(director, float))
    for theta in (0.1, 1.3, 2.9):
        fd = (clamp_twist_angle(theta + 1e-6, BETA, F, 0) - clamp_twist_angle(theta - 1e-6, BETA, F, 0)) / 2e-6
        c = np.zeros(8)
        c[0] = theta
        c[7] = clamp_twist_angle(theta, BETA, F)
        _, jac, _ = clamp_constraints(c, R, BETA, F, None)
        assert np.isclose(-jac[5, 0], fd, atol=1e-7)


@pytest.mark.parametrize("drive", [None, 0.4])
def test_constraint_jacobian_and_hessian_match_finite_differences(drive):
    F = frame_from_director(np.array([0.3, 0.5, 0.8]))
    rng = np.random.default_rng(0)
    c = rng.normal(size=8)
    c[7] = clamp_twist_angle(c[0], BETA, F) + 0.1
    phi, jac, hess = clamp_constraints(c, R, BETA, F, drive)
    fun = lambda c: clamp_constraints(c, R, BETA, F, drive)[0]
    assert np.allclose(central_difference(fun, c, 1e-6), jac, atol=1e-8)
    lam = rng.normal(size=phi.size)
    H_fd = central_difference(lambda c: clamp_constraints(c, R, BETA, F, drive)[1].T @ lam, c, 1e-6)
    assert np.allclose(H_fd, hess(lam), atol=1e-7)


@pytest.mark.parametrize("theta", [0.0, 1.0, np.pi, 4.5])
def test_straight_clamped_state_satisfies_the_clamp(theta):
    system = AncfHubSystem(AncfBeam(1.45, 3, plate()), radius=R, twist=BETA, motion="free")
    x, F = system.initial_state(theta)
    phi, _, _ = system.constraints(x, F, None)
    assert np.allclose(phi, 0, atol=1e-12)
    # the root section: tangent i_h, and n = sin(beta) j_h + cos(beta) k_h (conventions.md)
    A = hub_frame(theta)
    frame = system.beam.frame_at(x[1:], F, 0.0)
    assert np.allclose(frame[:, 0], A[:, 0])
    assert np.allclose(frame[:, 2], np.sin(BETA) * A[:, 1] + np.cos(BETA) * A[:, 2])
    assert np.allclose(frame, clamp_frame(theta, BETA))


def test_upper_surface_faces_up_for_beta_45():
    n = clamp_frame(0.0, np.radians(45))[:, 2]
    assert n[1] > 0.7
