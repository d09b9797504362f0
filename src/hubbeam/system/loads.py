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


def tip_moment_load(u: np.ndarray, moment: np.ndarray, F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Generalized force (4: r0'(3), theta_1) of a fixed-direction tip moment and its
    Jacobian (4 x 3) with respect to r0' (global components). It does not depend on theta_1."""
    U = F.T @ np.asarray(u, dtype=float)
    Mc = F.T @ np.asarray(moment, dtype=float)
    L2 = U @ U
    L = np.sqrt(L2)
    e0 = np.array([1.0, 0.0, 0.0])
    s = Mc @ U
    w = np.cross(e0, U)
    g = 1.0 / (L2 * (L + U[0]))
    QU = np.cross(Mc, U) / L2 - s * g * w
    Qphi = s / L

    def skew(a):
        return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])

    grad_g = -g * (2.0 * U / L2 + (U / L + e0) / (L + U[0]))
    dQU = skew(Mc) / L2 - 2.0 * np.outer(np.cross(Mc, U), U) / L2**2
    dQU -= g * np.outer(w, Mc) + s * g * skew(e0) + s * np.outer(w, grad_g)
    dQphi = (Mc - (Mc @ U) * U / L2) / L
    Q = np.concatenate([F @ QU, [Qphi]])
    J = np.vstack([F @ dQU @ F.T, (F @ dQphi)[None, :]])
    return Q, J
