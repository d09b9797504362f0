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


@njit(cache=True, error_model="numpy")
def strain_measures_at(U, V, phi, psi):
    """:func:`strain_measures` for every row of U, V, phi, psi: an (n, 4) array."""
    out = np.empty((U.shape[0], 4))
    for i in range(U.shape[0]):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = strain_measures(U[i], V[i], phi[i], psi[i])
    return out


@njit(cache=True, error_model="numpy")
def _levi_civita(i, j, k):
    return float((i - j) * (j - k) * (k - i)) / 2.0


@njit(cache=True, error_model="numpy")
def _partials(p, X, L, lam, qi, C0, C1, C2, K0):
    """Derivatives with respect to y_p, y = (U, V), of the intermediates L, lam = 1/L^2,
    C = U x V, K = lam C, qi = 1/(L + U0) and g = K0 qi (all as scalars, no arrays)."""
    if p < 3:
        Up = X[p]
        gL = Up / L
        glam = -2.0 * lam * lam * Up
        # d(U x V)/dU_p = e_p x V
        V0, V1, V2 = X[3], X[4], X[5]
        if p == 0:
            gC0, gC1, gC2 = 0.0, -V2, V1
        elif p == 1:
            gC0, gC1, gC2 = V2, 0.0, -V0
        else:
            gC0, gC1, gC2 = -V1, V0, 0.0
        gq = -qi * qi * (gL + (1.0 if p == 0 else 0.0))
    else:
        gL = glam = gq = 0.0
        # d(U x V)/dV_k = U x e_k
        U0, U1, U2 = X[0], X[1], X[2]
        k = p - 3
        if k == 0:
            gC0, gC1, gC2 = 0.0, U2, -U1
        elif k == 1:
            gC0, gC1, gC2 = -U2, 0.0, U0
        else:
            gC0, gC1, gC2 = U1, -U0, 0.0
    gK0 = lam * gC0 + C0 * glam
    gK1 = lam * gC1 + C1 * glam
    gK2 = lam * gC2 + C2 * glam
    gg = qi * gK0 + K0 * gq
    return gL, glam, gC0, gC1, gC2, gK0, gK1, gK2, gq, gg


@njit(cache=True, error_model="numpy")
def strain_jet(X, e, G, H, hessian):
    """Strain measures e[4], gradients G[4, 8] and (when ``hessian``) Hessians H[4, 8, 8] at X.

    Order of e: eps0, kappa1 (torsion), kappa2 (about m, weak axis for b > h),
    kappa3 (about n). Returns L + U0, the distance to the chart singularity (divided by L
    it is 1 + d.tau).

    Every intermediate depends on y = (U, V) only, and none is more than linear in V, so
    their Hessians live on the upper U-U and the U-V pairs of the 6 x 6 (U, V) block;
    theta enters by the final rotation and theta' linearly. Everything is scalar
    arithmetic (:func:`_partials` gives the intermediates' gradients one variable at a
    time): arrays of intermediates cost more in reference counting and memory traffic
    than the arithmetic itself.
    """
    U0, U1, U2 = X[0], X[1], X[2]
    V0, V1, V2 = X[3], X[4], X[5]
    phi = X[PHI]
    psi = X[PSI]
    L2 = U0 * U0 + U1 * U1 + U2 * U2
    L = np.sqrt(L2)
    lam = 1.0 / L2
    C0 = U1 * V2 - U2 * V1
    C1 = U2 * V0 - U0 * V2
    C2 = U0 * V1 - U1 * V0
    K0, K1, K2 = lam * C0, lam * C1, lam * C2
    s0 = L + U0
    qi = 1.0 / s0
    g = K0 * qi
    a = K1 - U1 * g
    b = K2 - U2 * g
    c = np.cos(phi)
    s = np.sin(phi)
    k2 = c * a + s * b
    k3 = -s * a + c * b
    e[0] = L - 1.0
    e[1] = psi - L * g
    e[2] = k2
    e[3] = k3
    for p in range(6):
        gL, _, _, _, _, gK0, gK1, gK2, _, gg = _partials(p, X, L, lam, qi, C0, C1, C2, K0)
        ga = gK1 - U1 * gg - (g if p == 1 else 0.0)
        gb = gK2 - U2 * gg - (g if p == 2 else 0.0)
        G[0, p] = gL
        G[1, p] = -L * gg - g * gL
        G[2, p] = c * ga + s * gb
        G[3, p] = -s * ga + c * gb
    G[0, PHI] = G[0, PSI] = 0.0
    G[1, PHI] = 0.0
    G[1, PSI] = 1.0
    G[2, PHI] = k3
    G[3, PHI] = -k2
    G[2, PSI] = G[3, PSI] = 0.0
    if not hessian:
        return s0

    for k in range(4):
        for p in range(8):
            for q in range(8):
                H[k, p, q] = 0.0
    for p in range(3):
        gLp, glamp, gC0p, gC1p, gC2p, gK0p, _, _, gqp, ggp = _partials(p, X, L, lam, qi, C0, C1, C2, K0)
        for q in range(p, 6):
            gLq, glamq, gC0q, gC1q, gC2q, gK0q, _, _, gqq, ggq = _partials(q, X, L, lam, qi, C0, C1, C2, K0)
            if q < 3:
                dpq = 1.0 if p == q else 0.0
                HL = (dpq - gLp * gLq) / L
                Hlam = 8.0 * lam * lam * lam * X[p] * X[q] - 2.0 * lam * lam * dpq
                Hq = 2.0 * qi * qi * qi * (gLp + (1.0 if p == 0 else 0.0)) * (gLq + (1.0 if q == 0 else 0.0)) \
                    - qi * qi * HL
            else:
                HL = Hlam = Hq = 0.0
            # K_i = lam C_i; d2 C_i / dU_p dV_l = eps_{i p l}
            HK0 = glamp * gC0q + gC0p * glamq + C0 * Hlam
            HK1 = glamp * gC1q + gC1p * glamq + C1 * Hlam
            HK2 = glamp * gC2q + gC2p * glamq + C2 * Hlam
            if q >= 3:
                HK0 += lam * _levi_civita(0, p, q - 3)
                HK1 += lam * _levi_civita(1, p, q - 3)
                HK2 += lam * _levi_civita(2, p, q - 3)
            Hg = qi * HK0 + K0 * Hq + gqp * gK0q + gK0p * gqq
            Ha = HK1 - U1 * Hg - ((ggq if p == 1 else 0.0) + (ggp if q == 1 else 0.0))
            Hb = HK2 - U2 * Hg - ((ggq if p == 2 else 0.0) + (ggp if q == 2 else 0.0))
            H[0, p, q] = H[0, q, p] = HL
            H[1, p, q] = H[1, q, p] = -L * Hg - g * HL - gLp * ggq - ggp * gLq
            H[2, p, q] = H[2, q, p] = c * Ha + s * Hb
            H[3, p, q] = H[3, q, p] = -s * Ha + c * Hb
    # the rotation by theta: d/dtheta of (k2, k3) is (k3, -k2)
    for p in range(6):
        H[2, PHI, p] = H[2, p, PHI] = G[3, p]
        H[3, PHI, p] = H[3, p, PHI] = -G[2, p]
    H[2, PHI, PHI] = -k2
    H[3, PHI, PHI] = -k3
    return s0
