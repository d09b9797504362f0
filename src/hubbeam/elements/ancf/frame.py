"""Cross-section frame R = [tau m n] of the ANCF beam from r0' and theta_1.

The paper builds R from Cardan angles (Eqs. 3, 12), whose 3-2-1 sequence is singular
when r0' is parallel to k0 and whose 2-3-1 sequence is singular along j0. hubbeam
uses instead a *reference-director chart* (the idea of the paper's ref. [15]): a
right-handed orthonormal frame F = [d f2 f3] held constant over the beam, and

    R0(tau) = Rot(d -> tau) F          (the smallest rotation taking d onto tau),
    R       = R0(tau) Rx(theta_1)      (twist theta_1 about tau),

so m = cos(theta_1) m0 + sin(theta_1) n0 and n = -sin(theta_1) m0 + cos(theta_1) n0 with

    m0 = f2 - (tau.f2) / (1 + d.tau) (d + tau),   n0 = f3 - (tau.f3) / (1 + d.tau) (d + tau).

The chart has a single singular direction, tau = -d (a Cardan chart has two), and
the system replaces the chart (with an exact remapping of the nodal angles) before a
tangent gets near it; see :mod:`hubbeam.elements.ancf.chart`.

All functions here take vectors in *chart components*: U = F^T r0', so d = e0,
f2 = e1, f3 = e2.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def untwisted_frame(T):
    """Chart frame vectors (m0, n0) at unit tangent T (chart components)."""
    den = 1.0 + T[0]
    h1 = T[1] / den
    h2 = T[2] / den
    m0 = np.empty(3)
    n0 = np.empty(3)
    for i in range(3):
        w = T[i]
        if i == 0:
            w += 1.0
        m0[i] = (1.0 if i == 1 else 0.0) - h1 * w
        n0[i] = (1.0 if i == 2 else 0.0) - h2 * w
    return m0, n0


@njit(cache=True)
def section_frame(U, phi):
    """(tau, m, n) in chart components from U = F^T r0' (any length) and theta_1."""
    L = np.sqrt(U[0] * U[0] + U[1] * U[1] + U[2] * U[2])
    T = U / L
    m0, n0 = untwisted_frame(T)
    c = np.cos(phi)
    s = np.sin(phi)
    return T, c * m0 + s * n0, -s * m0 + c * n0


@njit(cache=True)
def section_frames(U, phi):
    """[tau m n] (n x 3 x 3, columns, chart components) of :func:`section_frame` for every row of U and phi."""
    out = np.empty((U.shape[0], 3, 3))
    for i in range(U.shape[0]):
        T, m, n = section_frame(U[i], phi[i])
        out[i, :, 0] = T
        out[i, :, 1] = m
        out[i, :, 2] = n
    return out


@njit(cache=True)
def block_to_global(F, A, out):
    """out[0:3, 0:3] = F A[0:3, 0:3] F^T: a 3 x 3 block of chart components (a Jacobian or
    a mass block on r0') in global components."""
    for i in range(3):
        for j in range(3):
            acc = 0.0
            for a in range(3):
                for b in range(3):
                    acc += F[i, a] * A[a, b] * F[j, b]
            out[i, j] = acc


def frame_global(F: np.ndarray, r_prime: np.ndarray, theta: float) -> np.ndarray:
    """R = [tau m n] (3x3, global components) for one r0' (global) and theta_1."""
    T, m, n = section_frame(F.T @ np.asarray(r_prime, dtype=float), float(theta))
    return F @ np.column_stack([T, m, n])
