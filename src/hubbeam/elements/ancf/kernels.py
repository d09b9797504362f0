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
    T = np.empty((8, 16))
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
            for k in range(4):
                energy += 0.5 * jw * stiffness[k] * e[k] * e[k]
            for i in range(8):
                acc = 0.0
                for k in range(4):
                    acc += stiffness[k] * e[k] * G[k, i]
                gW[i] = acc
            gauss_operator(F, S[g], dS[g], d2S[g], B)
            # force += jw B^T gW and tangent += jw B^T HW B, without temporaries
            for j in range(ELEMENT_DOFS):
                acc = 0.0
                for i in range(8):
                    acc += B[i, j] * gW[i]
                force[NODE_DOFS * el + j] += jw * acc
            if want_tangent:
                for i in range(8):
                    for j in range(8):
                        acc = 0.0
                        for k in range(4):
                            acc += stiffness[k] * (G[k, i] * G[k, j] + e[k] * H[k, i, j])
                        HW[i, j] = acc
                for i in range(8):
                    for j in range(ELEMENT_DOFS):
                        acc = 0.0
                        for k in range(8):
                            acc += HW[i, k] * B[k, j]
                        T[i, j] = acc
                for i in range(ELEMENT_DOFS):
                    for j in range(ELEMENT_DOFS):
                        acc = 0.0
                        for k in range(8):
                            acc += B[k, i] * T[k, j]
                        tangent[el, i, j] += jw * acc
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
            for i in range(ELEMENT_DOFS):
                for j in range(ELEMENT_DOFS):
                    acc = 0.0
                    for k in range(3):
                        acc += rho_a * Nr[k, i] * Nr[k, j] + rho_iz * Bm[k, i] * Bm[k, j] + rho_iy * Bn[k, i] * Bn[k, j]
                    mass[el, i, j] += jw * acc


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


@njit(cache=True)
def rotary_inertia_kernel(q, qdot, F, length, S, dS, w, inertia, force):
    """Quadratic-velocity force Q_v of the section's rotary inertia and its kinetic energy.

    The angular velocity of the section in its own frame, omega = (omega.tau, omega.m,
    omega.n), is the same function of (r0', d r0'/dt, theta_1, d theta_1/dt) as the
    curvature (kappa1, kappa2, kappa3) is of (r0', r0'', theta_1, theta_1') (compare
    Eqs. 8 and 25), so :func:`strain_jet` gives omega with its exact derivatives, and
    T_rot = 1/2 int (rho (I_y + I_z) omega1^2 + rho I_y omega2^2 + rho I_z omega3^2) dx.
    Lagrange's equations then give M_rot (as :func:`mass_kernel`) and

        Q_v = -sum_i c_i [ (d omega_i / d Xdot)(d omega_i / dX . Xdot)
                           + omega_i (d2 omega_i / dXdot dX) Xdot - omega_i d omega_i / dX ],

    X = (r0', theta_1) (the paper's Q_ve, Eq. 36). inertia = (rho (I_y + I_z), rho I_y,
    rho I_z) in kg m. ``force`` (n_dof) is overwritten with Q_v. Returns T_rot (J).
    """
    n_el = (q.shape[0] - NODE_DOFS) // NODE_DOFS
    force[:] = 0.0
    Z = np.empty(8)
    Xq = np.empty(8)
    Xv = np.empty(8)
    e = np.empty(4)
    G = np.empty((4, 8))
    H = np.empty((4, 8, 8))
    xi = (0, 1, 2, 6)  # X = (U, phi) inside Z = (U, Udot, phi, phidot)
    vi = (3, 4, 5, 7)  # Xdot
    energy = 0.0
    for el in range(n_el):
        qe = q[NODE_DOFS * el : NODE_DOFS * el + ELEMENT_DOFS]
        ve = qdot[NODE_DOFS * el : NODE_DOFS * el + ELEMENT_DOFS]
        for g in range(w.shape[0]):
            # Z = (F^T r0', F^T d r0'/dt, theta_1, d theta_1/dt); the r0'' slots of X are unused
            gauss_variables(qe, F, S[g], dS[g], dS[g], Xq)
            gauss_variables(ve, F, S[g], dS[g], dS[g], Xv)
            Z[0:3] = Xq[0:3]
            Z[3:6] = Xv[0:3]
            Z[6] = Xq[6]
            Z[7] = Xv[6]
            strain_jet(Z, e, G, H)
            QX = np.zeros(4)
            for i in range(3):
                c = inertia[i]
                om = e[i + 1]
                energy += 0.5 * w[g] * length * c * om * om
                rate = 0.0  # d omega / dX . Xdot
                for k in range(4):
                    rate += G[i + 1, xi[k]] * Z[vi[k]]
                for r in range(4):
                    mixed = 0.0
                    for k in range(4):
                        mixed += H[i + 1, vi[r], xi[k]] * Z[vi[k]]
                    QX[r] -= c * (G[i + 1, vi[r]] * rate + om * mixed - om * G[i + 1, xi[r]])
            jw = w[g] * length
            for a in range(4):
                o = _VEC_OFFSETS[a]
                for k in range(3):
                    acc = 0.0
                    for i in range(3):
                        acc += F[k, i] * QX[i]
                    force[NODE_DOFS * el + o + k] += jw * dS[g, a] * acc
                force[NODE_DOFS * el + _ANG_OFFSETS[a]] += jw * S[g, a] * QX[3]
    return energy


@njit(cache=True)
def drag_kernel(qdot, length, S, w, frontal_width, c1, c2, force, blocks):
    """Damping of Eq. 37-39: f_d = -(c1 + c2 |v|) v per unit frontal area on the centre-line
    velocity v, times the frontal width b per unit length.

    ``force`` (n_dof) is overwritten with Q_d, ``blocks`` (n_el, 16, 16) with -dQ_d/dqdot
    (the damping matrix). Returns the dissipated power -Q_d . qdot (W).
    """
    n_el = (qdot.shape[0] - NODE_DOFS) // NODE_DOFS
    force[:] = 0.0
    blocks[:, :, :] = 0.0
    power = 0.0
    v = np.empty(3)
    for el in range(n_el):
        ve = qdot[NODE_DOFS * el : NODE_DOFS * el + ELEMENT_DOFS]
        for g in range(w.shape[0]):
            v[:] = 0.0
            for a in range(4):
                o = _VEC_OFFSETS[a]
                for k in range(3):
                    v[k] += S[g, a] * ve[o + k]
            speed = np.sqrt(v[0] ** 2 + v[1] ** 2 + v[2] ** 2)
            jw = w[g] * length * frontal_width
            coef = c1 + c2 * speed
            power += jw * coef * speed * speed
            for a in range(4):
                oa = _VEC_OFFSETS[a]
                for k in range(3):
                    force[NODE_DOFS * el + oa + k] -= jw * S[g, a] * coef * v[k]
                for b in range(4):
                    ob = _VEC_OFFSETS[b]
                    for k in range(3):
                        for m in range(3):
                            Ckm = coef if k == m else 0.0
                            if speed > 0.0:
                                Ckm += c2 * v[k] * v[m] / speed
                            blocks[el, oa + k, ob + m] += jw * S[g, a] * S[g, b] * Ckm
    return power
