"""The ANCF beam's inertia: the translational mass of its centre line (paper Eq. 35, first
term) and the rotary inertia of its sections (Eq. 35's rotary terms and the quadratic-velocity
force Q_ve of Eq. 36), with the sections' own angular momentum. Coordinates and Gauss-point
variables: :mod:`hubbeam.elements.ancf.coordinates`.

Matrix kernels *add* ``scale`` times their element blocks (n_el, 16, 16) to ``blocks``.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.elements.ancf.coordinates import (
    ANG_OFFSETS, ELEMENT_DOFS, NODE_DOFS, ROTARY_COLUMN, VEC_OFFSETS, add_symmetric, dof_weights,
    gather_slopes, mass_to_global, to_global,
)
from hubbeam.elements.ancf.frame import section_frame
from hubbeam.elements.ancf.strain import PHI, PSI, strain_jet


def translational_mass_blocks(length, S, w, rho_a) -> np.ndarray:
    """Every element's translational mass int rho A S^T S dx (Eq. 35, first term): (n_el, 16,
    16), independent of q; ``rho_a`` (n_el, ng): rho A (kg/m) at the Gauss points (weights
    ``w``, shape functions ``S`` (ng, 4)). Set-up work in numpy: a compiled function called
    from Python costs a load from numba's cache at every start."""
    S, w, rho_a = (np.asarray(a, dtype=float) for a in (S, w, rho_a))
    blocks = np.zeros((rho_a.shape[0], 4, 4))
    for g in range(w.shape[0]):
        jw = w[g] * length * rho_a[:, g]
        blocks += (jw[:, None] * S[g][None, :])[:, :, None] * S[g][None, None, :]
    out = np.zeros((rho_a.shape[0], ELEMENT_DOFS, ELEMENT_DOFS))
    for a, oa in enumerate(VEC_OFFSETS):
        for b, ob in enumerate(VEC_OFFSETS):
            for k in range(3):
                out[:, oa + k, ob + k] = blocks[:, a, b]
    return out


@njit(cache=True, error_model="numpy")


def add_translational_mass(mass, n_el, scale, blocks):
    """blocks[e] += scale * mass[e] for every element (``mass``: (>= n_el, 16, 16), the blocks of
    :func:`translational_mass_blocks`: only the same components of the vector coefficients
    couple, so only those 48 entries are added)."""
    for el in range(n_el):
        for oa in VEC_OFFSETS:
            for ob in VEC_OFFSETS:
                for k in range(3):
                    blocks[el, oa + k, ob + k] += scale * mass[el, oa + k, ob + k]


@njit(cache=True, error_model="numpy")


def translational_mass_product(mass, u, out):
    """out += M_trans u (element blocks ``mass`` (>= n_el, 16, 16); only the 48 entries that
    :func:`add_translational_mass` adds are nonzero, and only they are read: the same sums, in
    the same order, without the zeros)."""
    n_el = (u.shape[0] - NODE_DOFS) // NODE_DOFS
    for el in range(n_el):
        o = NODE_DOFS * el
        for oa in VEC_OFFSETS:
            for k in range(3):
                i = oa + k
                acc = 0.0
                for ob in VEC_OFFSETS:
                    acc += mass[el, i, ob + k] * u[o + ob + k]
                out[o + i] += acc


@njit(cache=True, error_model="numpy")


def rotary_inertia_kernel(q, qdot, acc, F, length, S, dS, w, inertia, scale, force, blocks):
    """Rotary inertia of the sections: kinetic energy, generalized force and mass matrix.

    The angular velocity of the section in its own frame, omega = (omega.tau, omega.m,
    omega.n), is the same function of (r0', d r0'/dt, theta_1, d theta_1/dt) as the
    curvature (kappa1, kappa2, kappa3) is of (r0', r0'', theta_1, theta_1') (compare
    Eqs. 8 and 25), so :func:`strain_jet` gives omega = B(X) Xdot with B = d omega / d Xdot
    and d omega / dX, X = (r0', theta_1). With J = diag(rho (I_y + I_z), rho I_y, rho I_z)
    (``inertia[el, g]``, kg m, at each Gauss point) the kinetic energy is
    T_rot = 1/2 int omega^T J omega dx, and
    Lagrange's equations for a body-frame angular velocity are Euler's equations projected
    by B: B^T (J omega_dot + omega x J omega) with omega_dot = B Xddot + (d omega / dX) Xdot.
    Hence the mass M_rot = int B^T J B dx (Eq. 35's rotary terms, rho I_z |m_s|^2 +
    rho I_y |n_s|^2) and the quadratic-velocity force (the paper's Q_ve, Eq. 36)

        Q_v = -int B^T (J (d omega / dX) Xdot + omega x J omega) dx.

    ``force`` (n_dof) is overwritten with Q_v - M_rot ``acc``; ``scale`` M_rot is added to
    ``blocks`` (n_el, 16, 16) unless it is empty. Returns T_rot (J).
    """
    n_el = (q.shape[0] - NODE_DOFS) // NODE_DOFS
    want_matrix = blocks.shape[0] == n_el
    force[:] = 0.0
    buf = np.empty(32)
    Z, Y, QX, QY = buf[0:8], buf[8:16], buf[16:24], buf[24:32]
    vec = np.empty(16)
    Xq, Xv, Xa, e, h = vec[0:3], vec[3:6], vec[6:9], vec[9:13], vec[13:16]
    G = np.empty((4, 8))
    H = np.empty((0, 0, 0))
    B = np.empty((3, 4))
    xi = (0, 1, 2, PHI)  # X = (U, phi) inside Z = (U, Udot, phi, phidot)
    vi = (3, 4, 5, PSI)  # Xdot
    energy = 0.0
    if want_matrix:
        mats = np.empty((2 + ELEMENT_DOFS, 4, 4))
        Mx, Mg = mats[0], mats[1]
        Ke = mats[2:].reshape((ELEMENT_DOFS, ELEMENT_DOFS))
        w1 = np.empty(2 * ELEMENT_DOFS)
    else:
        Mx = Mg = Ke = np.empty((0, 0))
        w1 = np.empty(0)
    for i in range(8):
        QX[i] = 0.0
    for el in range(n_el):
        o = NODE_DOFS * el
        if want_matrix:
            Ke[:, :] = 0.0
        for g in range(w.shape[0]):
            # Z = (F^T r0', F^T d r0'/dt, theta_1, d theta_1/dt); the r0'' slots of X are unused
            gather_slopes(q, o, dS, S, g, F, Y, Xq)
            Z[6] = Y[6]
            gather_slopes(qdot, o, dS, S, g, F, Y, Xv)
            Z[7] = Y[6]
            gather_slopes(acc, o, dS, S, g, F, Y, Xa)
            phi_a = Y[6]
            for i in range(3):
                Z[i] = Xq[i]
                Z[3 + i] = Xv[i]
            strain_jet(Z, e, G, H, False)  # gradients only
            J = inertia[el, g]
            J0, J1, J2 = J[0], J[1], J[2]
            om0, om1, om2 = e[1], e[2], e[3]
            # omega x J omega
            gy0 = (J2 - J1) * om1 * om2
            gy1 = (J0 - J2) * om2 * om0
            gy2 = (J1 - J0) * om0 * om1
            for i in range(3):
                rate = 0.0  # (d omega_i / dX) Xdot + B_i Xddot
                for k in range(4):
                    B[i, k] = G[i + 1, vi[k]]
                    rate += G[i + 1, xi[k]] * Z[vi[k]] + B[i, k] * (Xa[k] if k < 3 else phi_a)
                h[i] = J[i] * rate
            h[0] += gy0
            h[1] += gy1
            h[2] += gy2
            jw = w[g] * length
            energy += 0.5 * jw * (J0 * om0 * om0 + J1 * om1 * om1 + J2 * om2 * om2)
            for k in range(4):
                QX[xi[k]] = -(B[0, k] * h[0] + B[1, k] * h[1] + B[2, k] * h[2])
            to_global(F, QX, QY)
            for a in range(4):
                oa = o + VEC_OFFSETS[a]
                u = jw * dS[g, a]
                for k in range(3):
                    force[oa + k] += u * QY[k]
                force[o + ANG_OFFSETS[a]] += jw * S[g, a] * QY[6]
            if want_matrix:
                dof_weights(S, dS, dS, g, w1, w1[ELEMENT_DOFS:])
                for r in range(4):
                    for c in range(4):
                        Mx[r, c] = J0 * B[0, r] * B[0, c] + J1 * B[1, r] * B[1, c] + J2 * B[2, r] * B[2, c]
                mass_to_global(F, Mx, Mg)
                for j in range(ELEMENT_DOFS):
                    cj = ROTARY_COLUMN[j]
                    wj = scale * jw * w1[j]
                    for i in range(j + 1):
                        Ke[j, i] += wj * w1[i] * Mg[ROTARY_COLUMN[i], cj]
        if want_matrix:
            add_symmetric(blocks, el, Ke)
    return energy


@njit(cache=True, error_model="numpy")


def rotary_momentum(q, qdot, F, length, S, dS, w, inertia, out):
    """out += int R J omega dx (N m s, global): the sections' own angular momentum (their
    rotary inertia J at the Gauss points; omega as in :func:`rotary_inertia_kernel`)."""
    n_el = (q.shape[0] - NODE_DOFS) // NODE_DOFS
    Y = np.empty(8)
    Z = np.empty(8)
    Xq, Xv = np.empty(3), np.empty(3)
    e = np.empty(4)
    G = np.empty((4, 8))
    H = np.empty((0, 0, 0))
    for el in range(n_el):
        o = NODE_DOFS * el
        for g in range(w.shape[0]):
            gather_slopes(q, o, dS, S, g, F, Y, Xq)
            Z[6] = Y[6]
            gather_slopes(qdot, o, dS, S, g, F, Y, Xv)
            Z[7] = Y[6]
            for i in range(3):
                Z[i] = Xq[i]
                Z[3 + i] = Xv[i]
            strain_jet(Z, e, G, H, False)
            J = inertia[el, g]
            T, m, n = section_frame(Xq, Z[6])
            jw = w[g] * length
            for a in range(3):  # R (J omega), R = F [T m n]
                loc = (T[0] * J[0] * e[1] + m[0] * J[1] * e[2] + n[0] * J[2] * e[3],
                       T[1] * J[0] * e[1] + m[1] * J[1] * e[2] + n[1] * J[2] * e[3],
                       T[2] * J[0] * e[1] + m[2] * J[1] * e[2] + n[2] * J[2] * e[3])
                out[a] += jw * (F[a, 0] * loc[0] + F[a, 1] * loc[1] + F[a, 2] * loc[2])
