"""The compiled equations of motion: the Newton matrix against finite differences of the residual."""

import numpy as np
import pytest

from hubbeam.system.beam import AncfBeam
from hubbeam.system.laws import DriveProfile
from hubbeam.system.multibody import single_beam_system
from tests.conftest import L, newton_matrix_and_differences, plate


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
    A, A_fd, res, res_fd = newton_matrix_and_differences(system_of(motion))
    assert np.allclose(res, res_fd, rtol=0, atol=1e-14 * np.max(np.abs(res)))
    assert np.max(np.abs(A - A_fd)) < 1e-6 * np.max(np.abs(A))
