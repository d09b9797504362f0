"""Compiled element loops of the ANCF beam's elasticity: strain energy (paper Eq. 19), the
internal force with Kelvin-Voigt structural damping, and its Newton matrix; the strains at
the Gauss points. Coordinates and Gauss-point variables: :mod:`hubbeam.elements.ancf.coordinates`.

Matrix kernels *add* ``scale`` times their element blocks (n_el, 16, 16) to ``blocks``,
so that an iteration matrix coef_m M + coef_c C + coef_k K is built in one array.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.elements.ancf.coordinates import (
    DOF_FIRST, DOF_SECOND, ELEMENT_DOFS, GAUSS_SLOTS, NODE_DOFS, ROTARY_SLOTS,
    add_element_to_global, add_sandwich, dof_weights, gather, gauss_variables, scatter, to_chart,
    to_global,
)
from hubbeam.elements.ancf.strain import strain_jet


@njit(cache=True, error_model="numpy")


def elastic_kernel(q, qdot, F, length, S, dS, d2S, w, stiffness, reference, damping, coef_c, scale, force, blocks):
    """Strain energy (Eq. 19), internal force and (when ``blocks`` has n_el rows) its Newton
    matrix, with Kelvin-Voigt structural damping.

    Per element and Gauss point: ``stiffness[el, g]`` = D = (EA, GJ_t, EI_y, EI_z) (N, N m^2) and
    ``reference[el, g]`` = e_ref, the strains (eps0, kappa1, kappa2, kappa3) of the stress-free
    state (a pretwisted beam's kappa1 = its twist rate). The energy is
    U = 1/2 int (e - e_ref)^T D (e - e_ref) dx, so the stress-free state carries none. ``damping``
    c (s) adds the resultants c D e_dot, e_dot = G X_dot (G = de/dX at the Gauss point, X_dot from
    ``qdot``): the force int G^T D (e - e_ref + c e_dot) dx overwrites ``force`` (n_dof, the
    internal force, opposite to Q_f of Eq. 36). Unless ``blocks`` is empty, it gains ``scale``
    times d(force)/dq (the elastic tangent and the damping force's dependence on q through G
    and H) plus ``coef_c`` times the damping matrix c int G^T D G dx.
    Returns (U, min(1 + d.tau), dissipated power c int e_dot^T D e_dot dx (W)).
    """
    return elastic_rotary_kernel(q, qdot, F, length, S, dS, d2S, w, stiffness, reference, damping,
                                 np.empty((0, 0, 3)), 0.0, coef_c, scale, force, blocks)


@njit(cache=True, error_model="numpy")


def elastic_rotary_kernel(q, qdot, F, length, S, dS, d2S, w, stiffness, reference, damping, inertia, coef_m, coef_c,
                          scale, force, blocks):
    """:func:`elastic_kernel`, and, when it builds the matrix (``blocks`` (n_el, 16, 16)) and ``inertia``
    (kg m, as in :func:`rotary_inertia_kernel`) has n_el rows, ``coef_m`` times the rotary mass
    M_rot of :func:`rotary_inertia_kernel` added to the same blocks (its force is left to that
    kernel). M_rot's B = d omega / d Xdot is the gradient of the curvature with respect to
    (r0'', theta_1') (omega is the curvature function of (U, Udot, theta_1, theta_1dot), and
    the curvature is linear in (V, theta_1')), which depends on (U, theta_1) only: it is read
    from the strains' G at the Gauss point, and J-weighted it joins the point's 8 x 8 matrix on
    the (U, theta_1) slots, whose weights in the coordinates are M_rot's (dS, S).

    Every Gauss point's 8 x 8 matrix is in chart components; B^T (.) B is summed over the
    element's points in chart components of the coordinates and rotated once per element
    (:func:`add_element_to_global`). Returns what :func:`elastic_kernel` returns."""
    n_el = (q.shape[0] - NODE_DOFS) // NODE_DOFS
    if blocks.shape[0] != n_el:
        return _elastic_forces(q, qdot, F, length, S, dS, d2S, w, stiffness, reference, damping, force)
    rotary = inertia.shape[0] == n_el
    damped = damping != 0.0
    force[:] = 0.0
    X = np.empty(8)
    Xd = np.zeros(8)
    e = np.empty(4)
    ed = np.zeros(4)
    r = np.empty(4)
    G = np.empty((4, 8))
    H = np.empty((4, 8, 8))
    gW = np.empty(8)
    gY = np.empty(8)
    mats = np.empty((4, 8, 8))
    HW, AW, HXd = mats[0], mats[1], mats[2, 0:4]
    R = np.empty((8, ELEMENT_DOFS))
    elmats = np.empty((3, ELEMENT_DOFS, ELEMENT_DOFS))
    Ke, Kn, Kt = elmats[0], elmats[1], elmats[2]
    w1 = np.empty(ELEMENT_DOFS)
    w2 = np.empty(ELEMENT_DOFS)
    energy = 0.0
    power = 0.0
    chart_margin = 2.0
    cg = scale + coef_c * damping
    for el in range(n_el):
        o = NODE_DOFS * el
        Ke[:, :] = 0.0
        if damped:
            Kn[:, :] = 0.0
        for g in range(w.shape[0]):
            D = stiffness[el, g]
            dof_weights(S, dS, d2S, g, w1, w2)
            gauss_variables(q, o, F, w1, w2, gY, X)
            s0 = strain_jet(X, e, G, H, True)
            L = e[0] + 1.0  # |U| (eps0 = L - 1: exact for 0.5 <= L <= 2, and so is L)
            chart_margin = min(chart_margin, s0 / L)
            jw = w[g] * length
            if damped:
                gauss_variables(qdot, o, F, w1, w2, gY, Xd)
            du, dp = _section_resultant(G, Xd, e, reference[el, g], D, damping, damped, jw, ed, r, gW)
            energy += du
            power += dp
            to_global(F, gW, gY)
            for j in range(ELEMENT_DOFS):
                force[o + j] += jw * (w1[j] * gY[DOF_FIRST[j]] + w2[j] * gY[DOF_SECOND[j]])
            # HW (chart components): the same products as sum_k (scale + coef_c c) D_k G_ki G_kj +
            # scale r_k H_kij, in the same order, with the factors of each k hoisted out of the
            # loops; B^T HW B (B: the weights w1, w2, the same in either components) is summed in
            # chart components and rotated once per element below
            d0, d1, d2, d3 = cg * D[0], cg * D[1], cg * D[2], cg * D[3]
            s0_, s1_, s2_, s3_ = scale * r[0], scale * r[1], scale * r[2], scale * r[3]
            for i in range(8):
                a0, a1, a2, a3 = d0 * G[0, i], d1 * G[1, i], d2 * G[2, i], d3 * G[3, i]
                for j in range(i, 8):
                    acc = 0.0
                    acc += a0 * G[0, j] + s0_ * H[0, i, j]
                    acc += a1 * G[1, j] + s1_ * H[1, i, j]
                    acc += a2 * G[2, j] + s2_ * H[2, i, j]
                    acc += a3 * G[3, j] + s3_ * H[3, i, j]
                    HW[i, j] = acc
                    HW[j, i] = acc
            if rotary:  # coef_m B^T J B on (U, theta_1), B[i, k] = G[1 + i, ROTARY_SLOTS[k]]
                J = inertia[el, g]
                j0, j1, j2 = coef_m * J[0], coef_m * J[1], coef_m * J[2]
                for a in range(4):
                    sa, ta = ROTARY_SLOTS[a], GAUSS_SLOTS[a]
                    b0, b1, b2 = j0 * G[1, sa], j1 * G[2, sa], j2 * G[3, sa]
                    for b in range(a + 1):
                        sb, tb = ROTARY_SLOTS[b], GAUSS_SLOTS[b]
                        m = b0 * G[1, sb] + b1 * G[2, sb] + b2 * G[3, sb]
                        HW[ta, tb] += m
                        if a != b:
                            HW[tb, ta] += m
            add_sandwich(Ke, HW, w1, w2, jw, R, True)
            if damped:  # c D e_dot through G: G^T c D (H X_dot), not symmetric
                for k in range(4):
                    for j in range(8):
                        acc = 0.0
                        for i in range(8):
                            acc += H[k, j, i] * Xd[i]
                        HXd[k, j] = acc
                for i in range(8):
                    for j in range(8):
                        acc = 0.0
                        for k in range(4):
                            acc += D[k] * G[k, i] * HXd[k, j]
                        AW[i, j] = scale * damping * acc
                add_sandwich(Kn, AW.T, w1, w2, jw, R, False)  # Kn[j, i] += (B^T AW^T B)[j, i] = (B^T AW B)[i, j]
        # Kt = the chart block (Ke's lower triangle mirrored, plus Kn when damped), then T_e Kt T_e^T
        # into blocks[el] (only its lower triangle computed when Kt is symmetric)
        for j in range(ELEMENT_DOFS):
            Kt[j, j] = Ke[j, j]
            for i in range(j):
                Kt[i, j] = Ke[j, i]
                Kt[j, i] = Ke[j, i]
        if damped:
            for i in range(ELEMENT_DOFS):
                for j in range(ELEMENT_DOFS):
                    Kt[i, j] += Kn[i, j]
        add_element_to_global(F, Kt, Ke, blocks, el, not damped)
    return energy, chart_margin, power


@njit(cache=True, error_model="numpy")


def _section_resultant(G, Xd, e, reference, D, damping, damped, jw, ed, r, gW):
    """At one Gauss point of weight jw (m): the strain rates ed = G X_dot (when ``damped``), the
    section resultants r = D (e - e_ref + c ed) (N, N m) and gW = G^T r (chart components);
    returns this point's strain energy 1/2 jw (e - e_ref)^T D (e - e_ref) (J) and dissipated
    power jw c ed^T D ed (W)."""
    energy = 0.0
    power = 0.0
    if damped:
        for k in range(4):
            acc = 0.0
            for i in range(8):
                acc += G[k, i] * Xd[i]
            ed[k] = acc
    for k in range(4):
        strain = e[k] - reference[k]
        energy += 0.5 * jw * D[k] * strain * strain
        power += jw * damping * D[k] * ed[k] * ed[k]
        r[k] = D[k] * (strain + damping * ed[k])
    for i in range(8):
        acc = 0.0
        for k in range(4):
            acc += r[k] * G[k, i]
        gW[i] = acc
    return energy, power


@njit(cache=True, error_model="numpy")


def _elastic_forces(q, qdot, F, length, S, dS, d2S, w, stiffness, reference, damping, force):
    """:func:`elastic_kernel` without the matrix: the same arithmetic in the same order, with
    the Gauss-point variables gathered straight from the Hermite tables (:func:`gather`) and
    only the scratch the force needs."""
    n_el = (q.shape[0] - NODE_DOFS) // NODE_DOFS
    damped = damping != 0.0
    force[:] = 0.0
    buf = np.empty(44)
    X, Xd, gW, gY, e, ed, r = buf[0:8], buf[8:16], buf[16:24], buf[24:32], buf[32:36], buf[36:40], buf[40:44]
    Xd[:] = 0.0
    ed[:] = 0.0
    G = np.empty((4, 8))
    H = np.empty((0, 0, 0))
    energy = 0.0
    power = 0.0
    chart_margin = 2.0
    for el in range(n_el):
        o = NODE_DOFS * el
        for g in range(w.shape[0]):
            D = stiffness[el, g]
            gather(q, o, dS, d2S, S, dS, g, gY)
            to_chart(F, gY, X)
            s0 = strain_jet(X, e, G, H, False)
            L = e[0] + 1.0  # |U| (eps0 = L - 1: exact for 0.5 <= L <= 2, and so is L)
            chart_margin = min(chart_margin, s0 / L)
            jw = w[g] * length
            if damped:
                gather(qdot, o, dS, d2S, S, dS, g, gY)
                to_chart(F, gY, Xd)
            du, dp = _section_resultant(G, Xd, e, reference[el, g], D, damping, damped, jw, ed, r, gW)
            energy += du
            power += dp
            to_global(F, gW, gY)
            scatter(force, o, dS, d2S, S, dS, g, jw, gY)
    return energy, chart_margin, power


@njit(cache=True, error_model="numpy")


def gauss_strains(q, F, length, S, dS, d2S, w, out):
    """The strains (eps0, kappa1, kappa2, kappa3) of the state q at every Gauss point: ``out``
    (n_el, ng, 4), computed exactly as :func:`elastic_kernel` computes them (the stress-free
    state's reference strains)."""
    n_el = (q.shape[0] - NODE_DOFS) // NODE_DOFS
    X = np.empty(8)
    Y = np.empty(8)
    e = np.empty(4)
    G = np.empty((4, 8))
    H = np.empty((4, 8, 8))
    w1 = np.empty(ELEMENT_DOFS)
    w2 = np.empty(ELEMENT_DOFS)
    for el in range(n_el):
        for g in range(w.shape[0]):
            dof_weights(S, dS, d2S, g, w1, w2)
            gauss_variables(q, NODE_DOFS * el, F, w1, w2, Y, X)
            strain_jet(X, e, G, H, False)
            for k in range(4):
                out[el, g, k] = e[k]
