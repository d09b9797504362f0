"""Strain measures of the ANCF beam and their exact first and second derivatives.

Per unit *reference* length x (paper Eqs. 8-10):

    eps0 = |r0'| - 1                        (Eq. 10)
    [kappa1 kappa2 kappa3] = axial(R^T R')  (Eq. 8): torsion, bending about m, about n.

With the reference-director chart of :mod:`.frame` and U = F^T r0', V = F^T r0''
(chart components), L = |U|, K = U x V / L^2 (the curvature vector tau x tau'):

    kappa1 = theta' - K0 L / (L + U0)
    a = K1 - U1 K0 / (L + U0),   b = K2 - U2 K0 / (L + U0)     (a = m0.K, b = n0.K)
    kappa2 = cos(theta) a + sin(theta) b                        (= m.K = -n.tau')
    kappa3 = -sin(theta) a + cos(theta) b                       (= n.K =  m.tau')

The kernel :func:`strain_jet` returns the four measures, their gradients and Hessians
with respect to X = (U0, U1, U2, V0, V1, V2, theta, theta'), built by the chain rule
on the closed forms above. Tests check them against finite differences.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: Index of theta_1 and theta_1' in the Gauss-point variable vector X.
PHI = 6
PSI = 7


@njit(cache=True, error_model="numpy")
def strain_measures(U, V, phi, psi):
    """(eps0, kappa1, kappa2, kappa3) at one point; U, V in chart components."""
    L = np.sqrt(U[0] * U[0] + U[1] * U[1] + U[2] * U[2])
    lam = 1.0 / (L * L)
    K0 = lam * (U[1] * V[2] - U[2] * V[1])
    K1 = lam * (U[2] * V[0] - U[0] * V[2])
    K2 = lam * (U[0] * V[1] - U[1] * V[0])
    g = K0 / (L + U[0])
    a = K1 - U[1] * g
    b = K2 - U[2] * g
    c = np.cos(phi)
    s = np.sin(phi)
    return L - 1.0, psi - L * g, c * a + s * b, -s * a + c * b


#: rows of the scratch arrays of :func:`strain_jet`: gradients (6-vectors on y = (U, V)) of
#: L, lam = 1/L^2, qi = 1/(L + U0), g, a, b, L + U0, and Hessians (6 x 6) of L, lam, qi, g, a, b
_GL, _GLAM, _GQ, _GG, _GA, _GB, _GS0 = 0, 1, 2, 3, 4, 5, 6
_HL, _HLAM, _HQ, _HG, _HA, _HB = 0, 1, 2, 3, 4, 5
_WS_VEC = 7
_WS_MAT = 6


@njit(cache=True, error_model="numpy")
def jet_workspace():
    """Scratch arrays for :func:`strain_jet`, allocated once by the caller and reused."""
    return np.empty((_WS_VEC, 6)), np.empty((_WS_MAT, 6, 6)), np.empty((3, 6)), np.empty((3, 6)), np.empty((3, 6, 6))


@njit(cache=True, error_model="numpy")
def strain_jet(X, e, G, H, ws, hessian):
    """Strain measures e[4], gradients G[4, 8] and (when ``hessian``) Hessians H[4, 8, 8] at X.

    Order of e: eps0, kappa1 (torsion), kappa2 (about m, weak axis for b > h),
    kappa3 (about n). ``ws`` is a :func:`jet_workspace`; nothing is allocated.
    Returns L + U0, the distance to the chart singularity (divided by L it is 1 + d.tau).

    Every intermediate depends on y = (U, V) only, and none is more than linear in V, so
    their Hessians live on the 6 x 6 (U, V) block with a zero V-V part; theta enters by
    the final rotation and theta' linearly.
    """
    # scratch rows (indexing the 2-D arrays directly: a view would cost a reference count)
    vec, mat, gC, gK, HK = ws
    U0, U1, U2 = X[0], X[1], X[2]
    V0, V1, V2 = X[3], X[4], X[5]
    phi = X[PHI]
    psi = X[PSI]
    L2 = U0 * U0 + U1 * U1 + U2 * U2
    L = np.sqrt(L2)
    lam = 1.0 / L2

    # L = |U|, lam = 1/L^2 (functions of U only)
    for p in range(6):
        vec[_GL, p] = 0.0
        vec[_GLAM, p] = 0.0
    for i in range(3):
        vec[_GL, i] = X[i] / L
        vec[_GLAM, i] = -2.0 * lam * lam * X[i]
    # K = lam (U x V): C_i = eps_ijk U_j V_k
    K0 = K1 = K2 = 0.0
    for i in range(3):
        j = (i + 1) % 3
        k = (i + 2) % 3
        Ci = X[j] * X[3 + k] - X[k] * X[3 + j]
        for p in range(6):
            gC[i, p] = 0.0
        gC[i, j] = X[3 + k]
        gC[i, k] = -X[3 + j]
        gC[i, 3 + k] = X[j]
        gC[i, 3 + j] = -X[k]
        Ki = lam * Ci
        for p in range(6):
            gK[i, p] = lam * gC[i, p] + Ci * vec[_GLAM, p]
        if i == 0:
            K0 = Ki
        elif i == 1:
            K1 = Ki
        else:
            K2 = Ki
        if hessian:
            for p in range(6):
                for q in range(6):
                    HK[i, p, q] = vec[_GLAM, p] * gC[i, q] + gC[i, p] * vec[_GLAM, q]
            for p in range(3):
                for q in range(3):
                    HK[i, p, q] += Ci * (8.0 * lam * lam * lam * X[p] * X[q] - (2.0 * lam * lam if p == q else 0.0))
            # lam * Hess(C_i): d2 C_i / dU_j dV_k = +1, d2 C_i / dU_k dV_j = -1
            HK[i, j, 3 + k] += lam
            HK[i, 3 + k, j] += lam
            HK[i, k, 3 + j] -= lam
            HK[i, 3 + j, k] -= lam

    # qi = 1 / (L + U0); g = K0 qi
    s0 = L + U0
    qi = 1.0 / s0
    for p in range(6):
        vec[_GS0, p] = vec[_GL, p]
    vec[_GS0, 0] += 1.0
    for p in range(6):
        vec[_GQ, p] = -qi * qi * vec[_GS0, p]
    g = K0 * qi
    for p in range(6):
        vec[_GG, p] = qi * gK[0, p] + K0 * vec[_GQ, p]
    # a = K1 - U1 g,  b = K2 - U2 g
    a = K1 - U1 * g
    b = K2 - U2 * g
    for p in range(6):
        vec[_GA, p] = gK[1, p] - U1 * vec[_GG, p]
        vec[_GB, p] = gK[2, p] - U2 * vec[_GG, p]
    vec[_GA, 1] -= g
    vec[_GB, 2] -= g

    c = np.cos(phi)
    s = np.sin(phi)
    k2 = c * a + s * b
    k3 = -s * a + c * b
    e[0] = L - 1.0
    e[1] = psi - L * g
    e[2] = k2
    e[3] = k3
    for k in range(4):
        G[k, 6] = 0.0
        G[k, 7] = 0.0
    for p in range(6):
        G[0, p] = vec[_GL, p]
        G[1, p] = -L * vec[_GG, p] - g * vec[_GL, p]
        G[2, p] = c * vec[_GA, p] + s * vec[_GB, p]
        G[3, p] = -s * vec[_GA, p] + c * vec[_GB, p]
    G[1, PSI] = 1.0
    G[2, PHI] = k3
    G[3, PHI] = -k2
    if not hessian:
        return s0

    for p in range(6):
        for q in range(6):
            mat[_HL, p, q] = 0.0
            mat[_HQ, p, q] = 2.0 * qi * qi * qi * vec[_GS0, p] * vec[_GS0, q]
    for p in range(3):
        for q in range(3):
            mat[_HL, p, q] = ((1.0 if p == q else 0.0) - vec[_GL, p] * vec[_GL, q]) / L
            mat[_HQ, p, q] -= qi * qi * mat[_HL, p, q]
    for p in range(6):
        for q in range(6):
            mat[_HG, p, q] = qi * HK[0, p, q] + K0 * mat[_HQ, p, q] + vec[_GQ, p] * gK[0, q] + gK[0, p] * vec[_GQ, q]
    for p in range(6):
        for q in range(6):
            mat[_HA, p, q] = HK[1, p, q] - U1 * mat[_HG, p, q]
            mat[_HB, p, q] = HK[2, p, q] - U2 * mat[_HG, p, q]
    for p in range(6):
        mat[_HA, 1, p] -= vec[_GG, p]
        mat[_HA, p, 1] -= vec[_GG, p]
        mat[_HB, 2, p] -= vec[_GG, p]
        mat[_HB, p, 2] -= vec[_GG, p]
    for k in range(4):
        for p in range(8):
            for q in range(6, 8):
                H[k, p, q] = 0.0
                H[k, q, p] = 0.0
    for p in range(6):
        for q in range(6):
            H[0, p, q] = mat[_HL, p, q]
            H[1, p, q] = -L * mat[_HG, p, q] - g * mat[_HL, p, q] - vec[_GL, p] * vec[_GG, q] - vec[_GG, p] * vec[_GL, q]
            H[2, p, q] = c * mat[_HA, p, q] + s * mat[_HB, p, q]
            H[3, p, q] = -s * mat[_HA, p, q] + c * mat[_HB, p, q]
    # the rotation by theta: d/dtheta of (k2, k3) is (k3, -k2)
    for p in range(6):
        H[2, PHI, p] = H[2, p, PHI] = G[3, p]
        H[3, PHI, p] = H[3, p, PHI] = -G[2, p]
    H[2, PHI, PHI] = -k2
    H[3, PHI, PHI] = -k3
    return s0
