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


@njit(cache=True)
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


@njit(cache=True)
def _sym_outer_add(H, coef, a, b):
    """H += coef (a b^T + b a^T)."""
    n = a.shape[0]
    for i in range(n):
        for j in range(n):
            H[i, j] += coef * (a[i] * b[j] + b[i] * a[j])


@njit(cache=True)
def strain_jet(X, e, G, H):
    """Strain measures e[4], gradients G[4, 8] and Hessians H[4, 8, 8] at X.

    Order of e: eps0, kappa1 (torsion), kappa2 (about m, weak axis for b > h),
    kappa3 (about n). Returns L + U0, the distance to the chart singularity
    (divided by L it is 1 + d.tau).
    """
    U = X[0:3]
    V = X[3:6]
    phi = X[PHI]
    psi = X[PSI]
    L2 = U[0] * U[0] + U[1] * U[1] + U[2] * U[2]
    L = np.sqrt(L2)
    G[:, :] = 0.0
    H[:, :, :] = 0.0

    # L = |U|
    gL = np.zeros(8)
    HL = np.zeros((8, 8))
    for i in range(3):
        gL[i] = U[i] / L
    for i in range(3):
        for j in range(3):
            HL[i, j] = ((1.0 if i == j else 0.0) - gL[i] * gL[j]) / L

    # lam = 1 / L^2
    lam = 1.0 / L2
    glam = np.zeros(8)
    Hlam = np.zeros((8, 8))
    for i in range(3):
        glam[i] = -2.0 * lam * lam * U[i]
    for i in range(3):
        for j in range(3):
            Hlam[i, j] = 8.0 * lam * lam * lam * U[i] * U[j] - (2.0 * lam * lam if i == j else 0.0)

    # K = lam (U x V): C_i = eps_ijk U_j V_k
    K = np.empty(3)
    gK = np.zeros((3, 8))
    HK = np.zeros((3, 8, 8))
    for i in range(3):
        j = (i + 1) % 3
        k = (i + 2) % 3
        Ci = U[j] * V[k] - U[k] * V[j]
        gC = np.zeros(8)
        gC[j] = V[k]
        gC[k] = -V[j]
        gC[3 + k] = U[j]
        gC[3 + j] = -U[k]
        K[i] = lam * Ci
        for p in range(8):
            gK[i, p] = lam * gC[p] + Ci * glam[p]
        # lam * Hess(C_i): d2 C_i / dU_j dV_k = +1, d2 C_i / dU_k dV_j = -1
        HK[i, j, 3 + k] += lam
        HK[i, 3 + k, j] += lam
        HK[i, k, 3 + j] -= lam
        HK[i, 3 + j, k] -= lam
        for p in range(8):
            for q in range(8):
                HK[i, p, q] += glam[p] * gC[q] + gC[p] * glam[q] + Ci * Hlam[p, q]

    # qi = 1 / (L + U0)
    s0 = L + U[0]
    qi = 1.0 / s0
    gs0 = gL.copy()
    gs0[0] += 1.0
    gq = -qi * qi * gs0
    Hq = np.empty((8, 8))
    for p in range(8):
        for q in range(8):
            Hq[p, q] = 2.0 * qi * qi * qi * gs0[p] * gs0[q] - qi * qi * HL[p, q]

    # g = K0 qi
    g = K[0] * qi
    gg = qi * gK[0] + K[0] * gq
    Hg = qi * HK[0] + K[0] * Hq
    _sym_outer_add(Hg, 1.0, gq, gK[0])

    # a = K1 - U1 g,  b = K2 - U2 g
    a = K[1] - U[1] * g
    b = K[2] - U[2] * g
    ga = gK[1] - U[1] * gg
    ga[1] -= g
    gb = gK[2] - U[2] * gg
    gb[2] -= g
    Ha = HK[1] - U[1] * Hg
    Hb = HK[2] - U[2] * Hg
    e1v = np.zeros(8)
    e1v[1] = 1.0
    e2v = np.zeros(8)
    e2v[2] = 1.0
    _sym_outer_add(Ha, -1.0, e1v, gg)
    _sym_outer_add(Hb, -1.0, e2v, gg)

    # eps0
    e[0] = L - 1.0
    G[0] = gL
    H[0] = HL

    # kappa1 = psi - L g
    e[1] = psi - L * g
    G[1] = -L * gg - g * gL
    G[1, PSI] += 1.0
    H[1] = -L * Hg - g * HL
    _sym_outer_add(H[1], -1.0, gL, gg)

    # kappa2, kappa3: rotation of (a, b) by theta
    c = np.cos(phi)
    s = np.sin(phi)
    k2 = c * a + s * b
    k3 = -s * a + c * b
    g2 = c * ga + s * gb
    g3 = -s * ga + c * gb
    e[2] = k2
    e[3] = k3
    G[2] = g2
    G[2, PHI] += k3
    G[3] = g3
    G[3, PHI] -= k2
    H[2] = c * Ha + s * Hb
    H[3] = -s * Ha + c * Hb
    ephi = np.zeros(8)
    ephi[PHI] = 1.0
    _sym_outer_add(H[2], 1.0, ephi, g3)
    _sym_outer_add(H[3], -1.0, ephi, g2)
    H[2, PHI, PHI] -= k2
    H[3, PHI, PHI] -= k3
    return s0
