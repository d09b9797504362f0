"""Concentrated tip loads of constant global direction.

A tip force P (N) at the tip centroid does the work P . delta r0(L): generalized force
P on the tip position coordinates, no stiffness.

A tip moment M (N m) of fixed global direction does the work M . delta omega, with
delta omega the virtual rotation of the tip section, [delta omega]x = delta R R^T. For
the chart frame of :mod:`hubbeam.elements.ancf.frame` this is

    delta omega = tau x delta tau + tau (delta theta_1 - d . (tau x delta tau) / (1 + d . tau)),

so, with u = r0'(L), L = |u|, in chart components:

    Q_u     = (M x u) / L^2 - (M . u) (d x u) / (L^2 (L + d . u)),     Q_theta = M . u / L.

It is not conservative for general 3D rotations (its load stiffness is not symmetric);
for rotation in one plane about M it is, which is the case of the end-moment tests.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.elements.ancf.frame import block_to_global


@njit(cache=True)
def tip_moment_terms(u, moment, F, Q, J):
    """Generalized force Q (4: r0'(3), theta_1) of a fixed-direction tip moment and its
    Jacobian J (4 x 3) with respect to r0' (global components), written into Q and J.
    It does not depend on theta_1. Plain scalar loops (small matrix products and array
    literals cost seconds of compilation)."""
    U = np.zeros(3)
    Mc = np.zeros(3)
    for i in range(3):
        for k in range(3):
            U[i] += F[k, i] * u[k]
            Mc[i] += F[k, i] * moment[k]
    L2 = U[0] * U[0] + U[1] * U[1] + U[2] * U[2]
    L = np.sqrt(L2)
    s = Mc[0] * U[0] + Mc[1] * U[1] + Mc[2] * U[2]
    w = np.empty(3)  # e0 x U
    w[0], w[1], w[2] = 0.0, -U[2], U[1]
    MxU = np.empty(3)
    MxU[0] = Mc[1] * U[2] - Mc[2] * U[1]
    MxU[1] = Mc[2] * U[0] - Mc[0] * U[2]
    MxU[2] = Mc[0] * U[1] - Mc[1] * U[0]
    g = 1.0 / (L2 * (L + U[0]))
    QU = np.empty(3)
    grad_g = np.empty(3)
    dQphi = np.empty(3)
    for k in range(3):
        QU[k] = MxU[k] / L2 - s * g * w[k]
        grad_g[k] = -g * (2.0 * U[k] / L2 + (U[k] / L + (1.0 if k == 0 else 0.0)) / (L + U[0]))
        dQphi[k] = (Mc[k] - s * U[k] / L2) / L
    dQU = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            skM = _skew(Mc, i, j)  # d(M x U)/dU = [M]x
            ske = _skew_e0(i, j)  # d(e0 x U)/dU = [e0]x
            dQU[i, j] = (skM / L2 - 2.0 * MxU[i] * U[j] / (L2 * L2)
                         - g * w[i] * Mc[j] - s * g * ske - s * w[i] * grad_g[j])
    # back to global components: Q = F QU, J = F dQU F^T, d Q_theta / d r0' = F dQphi
    for i in range(3):
        Q[i] = F[i, 0] * QU[0] + F[i, 1] * QU[1] + F[i, 2] * QU[2]
        J[3, i] = F[i, 0] * dQphi[0] + F[i, 1] * dQphi[1] + F[i, 2] * dQphi[2]
    block_to_global(F, dQU, J)
    Q[3] = s / L


@njit(cache=True)
def _skew(a, i, j):
    """Entry (i, j) of the cross-product matrix [a]x."""
    if i == j:
        return 0.0
    k = 3 - i - j
    sign = 1.0 if (j - i) % 3 == 1 else -1.0
    return -sign * a[k]


@njit(cache=True)
def _skew_e0(i, j):
    """Entry (i, j) of [e0]x = [[0, 0, 0], [0, 0, -1], [0, 1, 0]]."""
    if i == 1 and j == 2:
        return -1.0
    if i == 2 and j == 1:
        return 1.0
    return 0.0


def tip_moment_load(u: np.ndarray, moment: np.ndarray, F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Generalized force (4: r0'(3), theta_1) of a fixed-direction tip moment and its
    Jacobian (4 x 3) with respect to r0' (global components). It does not depend on theta_1."""
    Q, J = np.empty(4), np.empty((4, 3))
    tip_moment_terms(np.asarray(u, dtype=float), np.asarray(moment, dtype=float), np.ascontiguousarray(F, dtype=float), Q, J)
    return Q, J
