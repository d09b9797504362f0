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


@njit(cache=True)
def _cross(a, b):
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


@njit(cache=True)
def tip_moment_terms(u, moment, F, Q, J):
    """Generalized force Q (4: r0'(3), theta_1) of a fixed-direction tip moment and its
    Jacobian J (4 x 3) with respect to r0' (global components), written into Q and J.
    It does not depend on theta_1."""
    U = F.T @ u
    Mc = F.T @ moment
    L2 = U[0] * U[0] + U[1] * U[1] + U[2] * U[2]
    L = np.sqrt(L2)
    s = Mc[0] * U[0] + Mc[1] * U[1] + Mc[2] * U[2]
    w = np.array([0.0, -U[2], U[1]])  # e0 x U
    g = 1.0 / (L2 * (L + U[0]))
    MxU = _cross(Mc, U)
    QU = MxU / L2 - s * g * w
    grad_g = np.empty(3)
    for k in range(3):
        grad_g[k] = -g * (2.0 * U[k] / L2 + (U[k] / L + (1.0 if k == 0 else 0.0)) / (L + U[0]))
    dQU = np.empty((3, 3))
    # d(M x U)/dU = [M]x ;  d(e0 x U)/dU = [e0]x
    skM = np.array([[0.0, -Mc[2], Mc[1]], [Mc[2], 0.0, -Mc[0]], [-Mc[1], Mc[0], 0.0]])
    ske = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
    for i in range(3):
        for j in range(3):
            dQU[i, j] = (skM[i, j] / L2 - 2.0 * MxU[i] * U[j] / L2**2
                         - g * w[i] * Mc[j] - s * g * ske[i, j] - s * w[i] * grad_g[j])
    dQphi = (Mc - s * U / L2) / L
    Qg = F @ QU
    Jg = F @ dQU @ F.T
    dg = F @ dQphi
    for i in range(3):
        Q[i] = Qg[i]
        for j in range(3):
            J[i, j] = Jg[i, j]
        J[3, i] = dg[i]
    Q[3] = s / L


def tip_moment_load(u: np.ndarray, moment: np.ndarray, F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Generalized force (4: r0'(3), theta_1) of a fixed-direction tip moment and its
    Jacobian (4 x 3) with respect to r0' (global components). It does not depend on theta_1."""
    Q, J = np.empty(4), np.empty((4, 3))
    tip_moment_terms(np.asarray(u, dtype=float), np.asarray(moment, dtype=float), np.ascontiguousarray(F, dtype=float), Q, J)
    return Q, J
