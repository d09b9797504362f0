"""The clamp of an ANCF root to a frame (system/clamp.py): its Jacobian and multiplier-weighted
Hessian against central differences of the six equations, evaluated from the frame's pose alone."""

from __future__ import annotations

import numpy as np
import pytest

from hubbeam.elements.ancf.chart import frame_from_director
from hubbeam.system import frames as fr
from hubbeam.system import rotations as rot
from hubbeam.system import chains as ch
from hubbeam.system.clamp import frame_clamp_equations


def _setup(seed):
    rng = np.random.default_rng(seed)
    x = rng.normal(size=30)
    const = lambda: ch.constant(rng.normal(size=3), rot.rotation_vector_matrix(rng.normal(size=3)))  # noqa: E731
    chain = ch.Chain((ch.free(0), const(), ch.revolute(10, (0.0, 1.0, 0.0), -1.0), const(),
                      ch.revolute(11, rng.normal(size=3)), const()))
    table = ch.ChainTable.of([chain])
    F = frame_from_director(rng.normal(size=3))
    r, R, *_ = fr.chain_pose(table, 0, x)
    # a root near its clamped state (the tangent along R's axis, the twist near the chart angle)
    root = np.concatenate([r + 0.01 * rng.normal(size=3), 1.05 * R[:, 0] + 0.02 * rng.normal(size=3), [0.3]])
    return rng, x, chain, table, F, root


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_clamp_jacobian_and_hessian_against_differences(seed):
    rng, x, chain, table, F, root = _setup(seed)
    twist = 0.4
    lam = rng.normal(size=6)
    cols = chain.coordinates
    nc = len(cols)

    def equations(xx, rr, order=2):
        r, R, Jr, Jw, Hr, Hw = fr.chain_pose(table, 0, xx, order=order)
        return frame_clamp_equations(r, R, Jr, Jw, Hr, Hw, rr, F, twist, lam, order)

    phi, jac, hess = equations(x, root)
    # the twist equation picks the branch nearest theta_1: a whole turn of theta_1 keeps it
    root2 = root.copy()
    root2[6] += 2 * np.pi
    assert np.isclose(equations(x, root2)[0][5], phi[5])

    def perturbed(j, h):
        xx, rr = x.copy(), root.copy()
        if j < nc:
            xx[cols[j]] += h
        else:
            rr[j - nc] += h
        return xx, rr

    h = 1e-6
    for j in range(nc + 7):
        p_plus, p_minus = (equations(*perturbed(j, s), order=1) for s in (h, -h))
        assert np.allclose((p_plus[0] - p_minus[0]) / (2 * h), jac[:, j], atol=1e-7), j
        dlam = lam @ (p_plus[1] - p_minus[1]) / (2 * h)  # d(lambda . dPhi/dc)/dc_j
        assert np.allclose(dlam, hess[:, j], atol=1e-6), j
    assert np.allclose(hess, hess.T, atol=1e-10)
