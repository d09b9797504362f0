"""The compiled equations of motion: the Newton matrix against finite differences of the residual."""

import numpy as np
import pytest

from hubbeam.system.beam import AncfBeam
from hubbeam.system.laws import DriveProfile
from hubbeam.system.hub_system import single_beam_system
from tests.conftest import L, central_difference, plate


def system_of(motion):
    return single_beam_system(AncfBeam(L, 3, plate()), radius=0.35, twist=np.pi / 4, motion=motion, hub_inertia=9.5,
                         drive=DriveProfile("spin_up", 2.0, 1.0), gravity=np.array([0, -9.81, 0]),
                         tip_moment=np.array([0.03, -0.02, 0.05]), tip_force=np.array([0.1, 0.2, -0.3]),
                         damping=(1.73, 1.4))


@pytest.mark.parametrize("motion", ["free", "prescribed"])
def test_newton_matrix_is_the_derivative_of_the_residual(motion):
    """z = [theta, mu, q] moves x by dz, v by gamma' dz, xdd by beta' dz and lambda by s/ck dmu
    (the generalized-alpha correction). At rest (v = 0, xdd = 0) the terms the matrix leaves out
    (velocity derivatives of Q_v, the q-derivative of M(q) xdd) vanish, so it must be exact."""
    system = system_of(motion)
    x0, F = system.initial_state(0.3)
    rng = np.random.default_rng(3)
    x0[1:] += 0.02 * rng.normal(size=x0.size - 1)
    layout = system.layout
    lam0 = rng.normal(size=layout.n_lambda)
    ck, gp, bp, s = 0.3e-6, 1.1e3, 3.3e6, system.mass_scale  # beta h^2, gamma', beta' at h = 1 ms
    coefs = (ck * bp, ck * gp, ck, s)
    zero = np.zeros_like(x0)

    def residual(z):
        dx, dmu = layout.split_z(z)
        return system.dynamic_residual(x0 + dx, gp * dx, bp * dx, lam0 + s / ck * dmu, F, 0.3, ck, s)

    res, matrix = system.dynamic_equations(x0, zero, zero, lam0, F, 0.3, *coefs)
    A = matrix.to_dense()
    A_fd = central_difference(residual, np.zeros(A.shape[0]), 1e-7)
    assert np.allclose(res, residual(np.zeros(A.shape[0])), rtol=0, atol=1e-14 * np.max(np.abs(res)))
    assert np.max(np.abs(A - A_fd)) < 1e-6 * np.max(np.abs(A))
