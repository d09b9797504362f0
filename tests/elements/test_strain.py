"""Strain measures: exact derivatives, agreement with the definition of Eq. 8, objectivity."""

import numpy as np
import pytest

from hubbeam.elements.ancf.chart import frame_from_director
from hubbeam.elements.ancf.frame import frame_global, section_frame
from hubbeam.elements.ancf.strain import strain_jet, strain_measures
from tests.conftest import central_difference, rotation


def jet(X):
    e, G, H = np.zeros(4), np.zeros((4, 8)), np.zeros((4, 8, 8))
    strain_jet(np.asarray(X, float), e, G, H, True)
    return e, G, H


@pytest.mark.parametrize("seed", range(6))
def test_strain_jet_matches_finite_differences(seed):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=8)
    X[0] += 1.5  # keep away from the chart singularity U = -|U| e0
    e, G, H = jet(X)
    values = lambda X: np.array(strain_measures(X[0:3], X[3:6], X[6], X[7]))
    assert np.allclose(e, values(X), rtol=0, atol=1e-14)
    G_fd = central_difference(values, X, 1e-6)
    assert np.max(np.abs(G_fd - G)) < 1e-7 * max(1.0, np.max(np.abs(G)))
    H_fd = central_difference(lambda X: jet(X)[1].ravel(), X, 1e-6).reshape(4, 8, 8)
    assert np.max(np.abs(H_fd - H)) < 1e-6 * max(1.0, np.max(np.abs(H)))
    assert np.allclose(H, H.transpose(0, 2, 1), atol=1e-12)


def _curve(x):
    return np.array([np.cos(x) + 0.3 * x, 0.5 * np.sin(2 * x), 0.2 * x**2 + x])


def _twist(x):
    return 0.7 * x + 0.3 * np.sin(x)


@pytest.mark.parametrize("director", [[1, 0, 0], [0, 1, 0], [0.3, -0.2, 0.9]])
def test_curvature_is_axial_of_RtR_prime(director):
    """kappa from the closed form equals axial(R^T dR/dx) by differentiating the frame itself (Eq. 8)."""
    F = frame_from_director(np.array(director, float))
    h = 1e-5
    for x in (0.1, 0.4, 0.9):
        rp = lambda s: (_curve(s + 1e-6) - _curve(s - 1e-6)) / 2e-6
        rpp = (_curve(x + 1e-4) - 2 * _curve(x) + _curve(x - 1e-4)) / 1e-8
        R = lambda s: frame_global(F, rp(s), _twist(s))
        A = R(x).T @ (R(x + h) - R(x - h)) / (2 * h)
        assert np.allclose(A + A.T, 0, atol=1e-6)
        k_def = np.array([A[2, 1], A[0, 2], A[1, 0]])
        dtwist = (_twist(x + h) - _twist(x - h)) / (2 * h)
        _, k1, k2, k3 = strain_measures(F.T @ rp(x), F.T @ rpp, _twist(x), dtwist)
        assert np.allclose([k1, k2, k3], k_def, atol=2e-5)
        # and the stretch of Eq. 10
        assert np.isclose(strain_measures(F.T @ rp(x), F.T @ rpp, 0.0, 0.0)[0], np.linalg.norm(rp(x)) - 1)


def test_frame_is_orthonormal_right_handed_with_tau_along_r_prime():
    rng = np.random.default_rng(3)
    for _ in range(50):
        U = rng.normal(size=3)
        if U[0] < -0.8 * np.linalg.norm(U):
            continue
        T, m, n = section_frame(U, rng.normal())
        R = np.column_stack([T, m, n])
        assert np.allclose(R.T @ R, np.eye(3), atol=1e-13)
        assert np.isclose(np.linalg.det(R), 1.0)
        assert np.allclose(T, U / np.linalg.norm(U))


@pytest.mark.parametrize("axis", [[0, 1, 0], [0, 0, 1], [1, 1, 1]])
@pytest.mark.parametrize("angle_deg", [90, 180, 270, 33])
def test_rigid_rotation_of_a_curved_state_keeps_strains(axis, angle_deg):
    """Rotating a bent and twisted state (centre line and section frame) leaves every strain unchanged."""
    Q = rotation(axis, np.radians(angle_deg))
    F = frame_from_director(np.array([1.0, 0.2, -0.1]))
    U = np.array([1.02, 0.3, -0.2])
    V = np.array([0.1, -0.5, 0.8])
    phi, psi = 0.4, -0.3
    e0 = strain_measures(F.T @ U, F.T @ V, phi, psi)
    # rotated state expressed in a chart chosen for it (the old chart may be singular there)
    F2 = frame_from_director(Q @ U / np.linalg.norm(U))
    R1 = frame_global(F, U, phi)
    T2, m2, n2 = section_frame(F2.T @ (Q @ U), 0.0)
    target_m = F2.T @ (Q @ R1[:, 1])
    phi2 = np.arctan2(target_m @ n2, target_m @ m2)
    # the twist rate changes by the difference of the charts' own twist rates (invariant torsion)
    t = U / np.linalg.norm(U)
    dt = (V - t * (t @ V)) / np.linalg.norm(U)
    tau0 = lambda d, t, dt: -d @ np.cross(t, dt) / (1 + d @ t)
    psi2 = psi + tau0(F[:, 0], t, dt) - tau0(F2[:, 0], Q @ t, Q @ dt)
    e1 = strain_measures(F2.T @ (Q @ U), F2.T @ (Q @ V), phi2, psi2)
    assert np.allclose(frame_global(F2, Q @ U, phi2), Q @ R1, atol=1e-12)
    assert np.allclose(e0, e1, atol=1e-12)


def test_strain_jet_without_hessian_gives_the_same_measures_and_gradients():
    rng = np.random.default_rng(7)
    X = rng.normal(size=8)
    X[0] += 1.5
    e, G, _ = jet(X)
    e2, G2, H2 = np.zeros(4), np.zeros((4, 8)), np.full((4, 8, 8), 7.0)
    strain_jet(X, e2, G2, H2, False)
    assert np.array_equal(e, e2) and np.array_equal(G, G2)
    assert np.all(H2 == 7.0)  # untouched
