"""Tip moment: virtual work M . delta omega, with delta omega from the frame itself."""

import numpy as np

from hubbeam.elements.ancf.chart import frame_from_director
from hubbeam.elements.ancf.frame import frame_global
from hubbeam.system.loads import tip_moment_load
from tests.conftest import central_difference


def test_generalized_moment_does_the_work_of_the_section_rotation():
    F = frame_from_director(np.array([0.2, 0.3, 0.9]))
    rng = np.random.default_rng(1)
    u, phi, M = rng.normal(size=3) + np.array([0, 0, 1.5]), 0.7, rng.normal(size=3)
    Q, J = tip_moment_load(u, M, F)
    for _ in range(4):
        du, dphi = rng.normal(size=3), rng.normal()
        h = 1e-6
        dR = (frame_global(F, u + h * du, phi + h * dphi) - frame_global(F, u - h * du, phi - h * dphi)) / (2 * h)
        W = dR @ frame_global(F, u, phi).T  # [delta omega]x
        domega = np.array([W[2, 1], W[0, 2], W[1, 0]])
        assert np.isclose(Q[0:3] @ du + Q[3] * dphi, M @ domega, atol=1e-8)
    J_fd = central_difference(lambda uu: tip_moment_load(uu, M, F)[0], u, 1e-6)
    assert np.allclose(J, J_fd, atol=1e-7)
