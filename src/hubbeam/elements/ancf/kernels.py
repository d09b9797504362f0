"""Compiled element loops of the ANCF beam: elastic force and tangent, mass matrix.

Node coordinates (paper Eq. 14): [r0 (3), r0' (3), theta_1, theta_1'], 8 per node;
element e joins nodes e and e+1, so its 16 coordinates are q[8e : 8e + 16].
Integrals use Gauss-Legendre points on each element; ``S, dS, d2S`` are the Hermite
functions tabulated at those points (:func:`hubbeam.elements.hermite.hermite`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.elements.ancf.frame import section_frame_jacobian
from hubbeam.elements.ancf.strain import strain_jet

NODE_DOFS = 8
ELEMENT_DOFS = 16
#: offsets of the four Hermite coefficient groups inside an element's 16 coordinates
_VEC_OFFSETS = (0, 3, 8, 11)
_ANG_OFFSETS = (6, 7, 14, 15)


@njit(cache=True)
def gauss_variables(qe, F, S, dS, d2S, X):
    """Fill X = (F^T r0', F^T r0'', theta, theta') at one Gauss point from qe (16)."""
    X[:] = 0.0
    for a in range(4):
        o = _VEC_OFFSETS[a]
        for i in range(3):
            for k in range(3):
                X[i] += F[k, i] * dS[a] * qe[o + k]
                X[3 + i] += F[k, i] * d2S[a] * qe[o + k]
        X[6] += S[a] * qe[_ANG_OFFSETS[a]]
        X[7] += dS[a] * qe[_ANG_OFFSETS[a]]


@njit(cache=True)
def gauss_operator(F, S, dS, d2S, B):
    """B (8 x 16) with X = B qe at one Gauss point."""
    B[:, :] = 0.0
    for a in range(4):
        o = _VEC_OFFSETS[a]
        for i in range(3):
            for k in range(3):
                B[i, o + k] = F[k, i] * dS[a]
                B[3 + i, o + k] = F[k, i] * d2S[a]
        B[6, _ANG_OFFSETS[a]] = S[a]
        B[7, _ANG_OFFSETS[a]] = dS[a]


@njit(cache=True)
def elastic_kernel(q, F, length, S, dS, d2S, w, stiffness, want_tangent, force, tangent):
    """Strain energy (Eq. 19), internal force dU/dq and element tangents.

    stiffness = (EA, GJ_t, EI_y, EI_z) in N, N m^2. ``force`` (n_dof) is overwritten with
    dU/dq (the internal force, opposite to Q_f of Eq. 36); ``tangent`` (n_el, 16, 16)
    receives the element Hessians when ``want_tangent``. Returns (U, min(1 + d.tau)).
    """
    n_el = (q.shape[0] - NODE_DOFS) // NODE_DOFS
    ng = w.shape[0]
    force[:] = 0.0
    X = np.empty(8)
    e = np.empty(4)
    G = np.empty((4, 8))
    H = np.empty((4, 8, 8))
    B = np.empty((8, 16))
    gW = np.empty(8)
    HW = np.empty((8, 8))
    energy = 0.0
    chart_margin = 2.0
    for el in range(n_el):
        qe = q[NODE_DOFS * el : NODE_DOFS * el + ELEMENT_DOFS]
        if want_tangent:
            tangent[el, :, :] = 0.0
        for g in range(ng):
            gauss_variables(qe, F, S[g], dS[g], d2S[g], X)
            s0 = strain_jet(X, e, G, H)
            L = np.sqrt(X[0] ** 2 + X[1] ** 2 + X[2] ** 2)
            chart_margin = min(chart_margin, s0 / L)
            jw = w[g] * length
            gW[:] = 0.0
            for k in range(4):
                energy += 0.5 * jw * stiffness[k] * e[k] * e[k]
                gW += stiffness[k] * e[k] * G[k]
            gauss_operator(F, S[g], dS[g], d2S[g], B)
            fe = jw * (B.T @ gW)
            for i in range(ELEMENT_DOFS):
                force[NODE_DOFS * el + i] += fe[i]
            if want_tangent:
                HW[:, :] = 0.0
                for k in range(4):
                    for i in range(8):
                        for j in range(8):
                            HW[i, j] += stiffness[k] * (G[k, i] * G[k, j] + e[k] * H[k, i, j])
                tangent[el] += jw * (B.T @ (HW @ B))
    return energy, chart_margin


@njit(cache=True)
def mass_kernel(q, F, length, S, dS, w, rho_a, rho_iy, rho_iz, mass):
    """Element mass matrices (Eq. 35): translational rho A plus rotary rho I_z |m_s|^2, rho I_y |n_s|^2.

    mass (n_el, 16, 16) is overwritten. rho_iy = rho int z^2 dA multiplies the motion of n,
    rho_iz = rho int y^2 dA that of m (kg m).
    """
    n_el = (q.shape[0] - NODE_DOFS) // NODE_DOFS
    ng = w.shape[0]
    Nr = np.empty((3, 16))
    Bm = np.empty((3, 16))
    Bn = np.empty((3, 16))
    U = np.empty(3)
    for el in range(n_el):
        qe = q[NODE_DOFS * el : NODE_DOFS * el + ELEMENT_DOFS]
        mass[el, :, :] = 0.0
        for g in range(ng):
            U[:] = 0.0
            phi = 0.0
            for a in range(4):
                o = _VEC_OFFSETS[a]
                for i in range(3):
                    for k in range(3):
                        U[i] += F[k, i] * dS[g, a] * qe[o + k]
                phi += S[g, a] * qe[_ANG_OFFSETS[a]]
            m, n, dm, dn = section_frame_jacobian(U, phi)
            # global derivatives: dm_glob/dr0' = F dm F^T, dm_glob/dtheta = F n
            dmg = F @ dm @ F.T
            dng = F @ dn @ F.T
            mg = F @ m
            ng_ = F @ n
            Nr[:, :] = 0.0
            Bm[:, :] = 0.0
            Bn[:, :] = 0.0
            for a in range(4):
                o = _VEC_OFFSETS[a]
                for i in range(3):
                    Nr[i, o + i] = S[g, a]
                    for k in range(3):
                        Bm[i, o + k] = dmg[i, k] * dS[g, a]
                        Bn[i, o + k] = dng[i, k] * dS[g, a]
                    Bm[i, _ANG_OFFSETS[a]] = ng_[i] * S[g, a]
                    Bn[i, _ANG_OFFSETS[a]] = -mg[i] * S[g, a]
            jw = w[g] * length
            mass[el] += jw * (rho_a * (Nr.T @ Nr) + rho_iz * (Bm.T @ Bm) + rho_iy * (Bn.T @ Bn))


@njit(cache=True)
def distributed_load(n_el, length, S, w, load, out):
    """Generalized force of a constant load per unit length ``load`` (N/m, global): int S1^T p dx (Eq. 32)."""
    out[:] = 0.0
    for el in range(n_el):
        for g in range(w.shape[0]):
            jw = w[g] * length
            for a in range(4):
                o = _VEC_OFFSETS[a]
                for i in range(3):
                    out[NODE_DOFS * el + o + i] += jw * S[g, a] * load[i]
