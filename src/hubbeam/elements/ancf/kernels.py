"""Compiled element loops of the ANCF beam, one per physical term.

Node coordinates (paper Eq. 14): [r0 (3), r0' (3), theta_1, theta_1'], 8 per node;
element e joins nodes e and e+1, so its 16 coordinates are q[8e : 8e + 16].
Integrals use Gauss-Legendre points on each element; ``S, dS, d2S`` are the Hermite
functions tabulated at those points (:func:`hubbeam.elements.hermite.hermite`).

The Gauss-point variables X = (r0', r0'', theta_1, theta_1') (global components) are
linear in the element coordinates, and each coordinate enters exactly two of them: the
component k of the vector coefficient of Hermite function a enters r0'_k with weight
S_a' and r0''_k with S_a''; the twist coefficient of function a enters theta_1 with S_a
and theta_1' with S_a' (:data:`DOF_FIRST`, :data:`DOF_SECOND`, :func:`dof_weights`). The
kernels use this sparsity instead of a dense 8 x 16 operator. Strain and frame
quantities are computed in chart components (U = F^T r0') and rotated back: forces per
Gauss point, the elastic matrix once per element (:func:`_add_element_to_global`).

Matrix kernels *add* ``scale`` times their element blocks (n_el, 16, 16) to ``blocks``,
so that an iteration matrix coef_m M + coef_c C + coef_k K is built in one array.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.elements.ancf.frame import block_to_global, section_frame
from hubbeam.elements.ancf.strain import PHI, PSI, strain_jet

NODE_DOFS = 8
ELEMENT_DOFS = 16
#: offsets of the four Hermite coefficient groups inside an element's 16 coordinates
_VEC_OFFSETS = (0, 3, 8, 11)
_ANG_OFFSETS = (6, 7, 14, 15)
#: for each element coordinate: the Hermite function it multiplies ...
DOF_SHAPE = np.array([0, 0, 0, 1, 1, 1, 0, 1, 2, 2, 2, 3, 3, 3, 2, 3])
#: ... its vector component (-1 for the twist coordinates) ...
DOF_COMPONENT = np.array([0, 1, 2, 0, 1, 2, -1, -1, 0, 1, 2, 0, 1, 2, -1, -1])
#: ... and the two Gauss-point variables it enters (index into X)
DOF_FIRST = np.array([0, 1, 2, 0, 1, 2, PHI, PHI, 0, 1, 2, 0, 1, 2, PHI, PHI])
DOF_SECOND = np.array([3, 4, 5, 3, 4, 5, PSI, PSI, 3, 4, 5, 3, 4, 5, PSI, PSI])
#: ... and, for the rotary inertia on (r0' (3), theta_1), the variable it moves with weight w1
ROTARY_COLUMN = np.array([0, 1, 2, 0, 1, 2, 3, 3, 0, 1, 2, 0, 1, 2, 3, 3])
#: the slots of (U, theta_1) in X, and of (V, theta_1') (the curvature's gradient there is the
#: rotary inertia's d omega / d Xdot)
GAUSS_SLOTS = (0, 1, 2, PHI)
ROTARY_SLOTS = (3, 4, 5, PSI)


@njit(cache=True, error_model="numpy")
def dof_weights(S, dS, d2S, g, w1, w2):
    """Weights of the element coordinates in X at Gauss point g: X[DOF_FIRST[j]] gets
    w1[j] qe[j], X[DOF_SECOND[j]] gets w2[j] qe[j] (r0' and theta_1 rows use S', S)."""
    for j in range(ELEMENT_DOFS):
        a = DOF_SHAPE[j]
        if DOF_COMPONENT[j] >= 0:
            w1[j] = dS[g, a]
            w2[j] = d2S[g, a]
        else:
            w1[j] = S[g, a]
            w2[j] = dS[g, a]


@njit(cache=True, error_model="numpy")
def gauss_variables(q, o, F, w1, w2, Y, X):
    """X = (F^T r0', F^T r0'', theta_1, theta_1') (chart components) from the element
    coordinates q[o : o + 16]; Y: scratch (8)."""
    for i in range(8):
        Y[i] = 0.0
    for j in range(ELEMENT_DOFS):
        Y[DOF_FIRST[j]] += w1[j] * q[o + j]
        Y[DOF_SECOND[j]] += w2[j] * q[o + j]
    _to_chart(F, Y, X)


@njit(cache=True, error_model="numpy")
def _to_chart(F, Y, X):
    """X = T^T Y, T = blockdiag(F, F, 1, 1): global to chart components of an 8-vector."""
    for b in range(2):
        for i in range(3):
            X[3 * b + i] = F[0, i] * Y[3 * b] + F[1, i] * Y[3 * b + 1] + F[2, i] * Y[3 * b + 2]
    X[6] = Y[6]
    X[7] = Y[7]


@njit(cache=True, error_model="numpy")
def _gather(q, o, A, B, C, D, g, Y):
    """Y = (sum_a A[g, a] r_a, sum_a B[g, a] r_a, sum_a C[g, a] theta_a, sum_a D[g, a] theta_a)
    (global components; r_a, theta_a: the vector and twist coefficients of Hermite function a
    in q[o : o + 16]): :func:`gauss_variables` before the rotation to the chart, with the
    weights read from the tables (A, B, C, D = dS, d2S, S, dS there) and the same sums in the
    same order, without the index tables."""
    a0, a1, a2, a3 = A[g, 0], A[g, 1], A[g, 2], A[g, 3]
    b0, b1, b2, b3 = B[g, 0], B[g, 1], B[g, 2], B[g, 3]
    for k in range(3):
        r0, r1, r2, r3 = q[o + k], q[o + 3 + k], q[o + 8 + k], q[o + 11 + k]
        Y[k] = a0 * r0 + a1 * r1 + a2 * r2 + a3 * r3
        Y[3 + k] = b0 * r0 + b1 * r1 + b2 * r2 + b3 * r3
    t0, t1, t2, t3 = q[o + 6], q[o + 7], q[o + 14], q[o + 15]
    Y[6] = C[g, 0] * t0 + C[g, 1] * t1 + C[g, 2] * t2 + C[g, 3] * t3
    Y[7] = D[g, 0] * t0 + D[g, 1] * t1 + D[g, 2] * t2 + D[g, 3] * t3


@njit(cache=True, error_model="numpy")
def _scatter(force, o, A, B, C, D, g, jw, Y):
    """force[o : o + 16] += jw B^T Y, the transpose of :func:`_gather` (Y global)."""
    for a in range(4):
        oa = o + _VEC_OFFSETS[a]
        u1, u2 = A[g, a], B[g, a]
        for k in range(3):
            force[oa + k] += jw * (u1 * Y[k] + u2 * Y[3 + k])
        force[o + _ANG_OFFSETS[a]] += jw * (C[g, a] * Y[6] + D[g, a] * Y[7])


@njit(cache=True, error_model="numpy")
def _to_global(F, X, Y):
    """Y = T X, T = blockdiag(F, F, 1, 1): chart to global components of an 8-vector."""
    for b in range(2):
        for i in range(3):
            Y[3 * b + i] = F[i, 0] * X[3 * b] + F[i, 1] * X[3 * b + 1] + F[i, 2] * X[3 * b + 2]
    Y[6] = X[6]
    Y[7] = X[7]


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
    (:func:`_add_element_to_global`). Returns what :func:`elastic_kernel` returns."""
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
            _to_global(F, gW, gY)
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
            _add_sandwich(Ke, HW, w1, w2, jw, R, True)
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
                _add_sandwich(Kn, AW.T, w1, w2, jw, R, False)  # Kn[j, i] += (B^T AW^T B)[j, i] = (B^T AW B)[i, j]
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
        _add_element_to_global(F, Kt, Ke, blocks, el, not damped)
    return energy, chart_margin, power


@njit(cache=True, error_model="numpy")
def _add_element_to_global(F, Kc, tmp, blocks, el, symmetric):
    """blocks[el] += T_e Kc T_e^T: a 16 x 16 element block in chart components (Kc) in global
    components; T_e = blockdiag(F, F, 1, 1, F, F, 1, 1) maps the chart components of the
    element coordinates (F^T r, F^T r', theta_1, theta_1' at both nodes) to the global ones.
    As X = T^T Y (:func:`_to_chart`) and each 3-vector of Y is a Hermite sum of the element's
    3-vectors, T^T B = B T_e^T: sum_g B^T T HW_g T^T B = T_e (sum_g B^T HW_g B) T_e^T.
    For a ``symmetric`` Kc only the lower triangle of T_e Kc T_e^T is computed (and mirrored).
    ``tmp`` (16 x 16): scratch."""
    for r in range(ELEMENT_DOFS):  # tmp = Kc T_e^T
        for o in _VEC_OFFSETS:
            k0, k1, k2 = Kc[r, o], Kc[r, o + 1], Kc[r, o + 2]
            for i in range(3):
                tmp[r, o + i] = k0 * F[i, 0] + k1 * F[i, 1] + k2 * F[i, 2]
        for o in _ANG_OFFSETS:
            tmp[r, o] = Kc[r, o]
    for o in _VEC_OFFSETS:  # blocks[el] += T_e tmp
        for i in range(3):
            f0, f1, f2 = F[i, 0], F[i, 1], F[i, 2]
            row = o + i
            if symmetric:
                for c in range(row):
                    value = f0 * tmp[o, c] + f1 * tmp[o + 1, c] + f2 * tmp[o + 2, c]
                    blocks[el, row, c] += value
                    blocks[el, c, row] += value
                blocks[el, row, row] += f0 * tmp[o, row] + f1 * tmp[o + 1, row] + f2 * tmp[o + 2, row]
            else:
                for c in range(ELEMENT_DOFS):
                    blocks[el, row, c] += f0 * tmp[o, c] + f1 * tmp[o + 1, c] + f2 * tmp[o + 2, c]
    for o in _ANG_OFFSETS:
        if symmetric:
            for c in range(o):
                blocks[el, o, c] += tmp[o, c]
                blocks[el, c, o] += tmp[o, c]
            blocks[el, o, o] += tmp[o, o]
        else:
            for c in range(ELEMENT_DOFS):
                blocks[el, o, c] += tmp[o, c]


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
    the Gauss-point variables gathered straight from the Hermite tables (:func:`_gather`) and
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
            _gather(q, o, dS, d2S, S, dS, g, gY)
            _to_chart(F, gY, X)
            s0 = strain_jet(X, e, G, H, False)
            L = e[0] + 1.0  # |U| (eps0 = L - 1: exact for 0.5 <= L <= 2, and so is L)
            chart_margin = min(chart_margin, s0 / L)
            jw = w[g] * length
            if damped:
                _gather(qdot, o, dS, d2S, S, dS, g, gY)
                _to_chart(F, gY, Xd)
            du, dp = _section_resultant(G, Xd, e, reference[el, g], D, damping, damped, jw, ed, r, gW)
            energy += du
            power += dp
            _to_global(F, gW, gY)
            _scatter(force, o, dS, d2S, S, dS, g, jw, gY)
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


@njit(cache=True, error_model="numpy")
def _add_sandwich(Ke, HY, w1, w2, factor, R, lower):
    """Ke[j, i] += factor (B^T HY B)[i, j] for the two-entry columns of B (:func:`dof_weights`):
    for a symmetric HY only the lower triangle (i <= j) when ``lower``; else every entry, which
    adds factor (B^T HY^T B);
    R (8 x 16): scratch for (B^T HY)^T, so that the inner loops run along contiguous memory."""
    for i in range(ELEMENT_DOFS):
        a1, a2 = DOF_FIRST[i], DOF_SECOND[i]
        u1, u2 = factor * w1[i], factor * w2[i]
        for c in range(8):
            R[c, i] = u1 * HY[a1, c] + u2 * HY[a2, c]
    for j in range(ELEMENT_DOFS):
        b1, b2 = DOF_FIRST[j], DOF_SECOND[j]
        v1, v2 = w1[j], w2[j]
        for i in range(j + 1 if lower else ELEMENT_DOFS):
            Ke[j, i] += v1 * R[b1, i] + v2 * R[b2, i]


@njit(cache=True, error_model="numpy")
def _add_symmetric(blocks, el, Ke):
    """blocks[el] += the symmetric matrix whose lower triangle is stored in Ke."""
    for j in range(ELEMENT_DOFS):
        blocks[el, j, j] += Ke[j, j]
        for i in range(j):
            blocks[el, i, j] += Ke[j, i]
            blocks[el, j, i] += Ke[j, i]


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
    for a, oa in enumerate(_VEC_OFFSETS):
        for b, ob in enumerate(_VEC_OFFSETS):
            for k in range(3):
                out[:, oa + k, ob + k] = blocks[:, a, b]
    return out


@njit(cache=True, error_model="numpy")
def add_translational_mass(mass, n_el, scale, blocks):
    """blocks[e] += scale * mass[e] for every element (``mass``: (>= n_el, 16, 16), the blocks of
    :func:`translational_mass_blocks`: only the same components of the vector coefficients
    couple, so only those 48 entries are added)."""
    for el in range(n_el):
        for oa in _VEC_OFFSETS:
            for ob in _VEC_OFFSETS:
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
        for oa in _VEC_OFFSETS:
            for k in range(3):
                i = oa + k
                acc = 0.0
                for ob in _VEC_OFFSETS:
                    acc += mass[el, i, ob + k] * u[o + ob + k]
                out[o + i] += acc


def distributed_load(n_el, length, S, w, density, load) -> np.ndarray:
    """Generalized force (n_el + 1 nodes) of the load per unit length density[el, g] * ``load``
    (``load`` global, e.g. rho A (kg/m) times g (m/s^2): N/m): int S1^T p dx (Eq. 32). Set-up
    work in numpy, as :func:`translational_mass_blocks`."""
    out = np.zeros(NODE_DOFS * (n_el + 1))
    rows = np.add.outer(np.asarray(_VEC_OFFSETS), np.arange(3))  # (4, 3): r and r' of both nodes
    for el in range(n_el):
        rows_el = NODE_DOFS * el + rows
        for g in range(w.shape[0]):
            out[rows_el] += (w[g] * length * S[g])[:, None] * (density[el, g] * load)[None, :]
    return out


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
            _gather_slopes(q, o, dS, S, g, F, Y, Xq)
            Z[6] = Y[6]
            _gather_slopes(qdot, o, dS, S, g, F, Y, Xv)
            Z[7] = Y[6]
            _gather_slopes(acc, o, dS, S, g, F, Y, Xa)
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
            _to_global(F, QX, QY)
            for a in range(4):
                oa = o + _VEC_OFFSETS[a]
                u = jw * dS[g, a]
                for k in range(3):
                    force[oa + k] += u * QY[k]
                force[o + _ANG_OFFSETS[a]] += jw * S[g, a] * QY[6]
            if want_matrix:
                dof_weights(S, dS, dS, g, w1, w1[ELEMENT_DOFS:])
                for r in range(4):
                    for c in range(4):
                        Mx[r, c] = J0 * B[0, r] * B[0, c] + J1 * B[1, r] * B[1, c] + J2 * B[2, r] * B[2, c]
                _mass_to_global(F, Mx, Mg)
                for j in range(ELEMENT_DOFS):
                    cj = ROTARY_COLUMN[j]
                    wj = scale * jw * w1[j]
                    for i in range(j + 1):
                        Ke[j, i] += wj * w1[i] * Mg[ROTARY_COLUMN[i], cj]
        if want_matrix:
            _add_symmetric(blocks, el, Ke)
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
            _gather_slopes(q, o, dS, S, g, F, Y, Xq)
            Z[6] = Y[6]
            _gather_slopes(qdot, o, dS, S, g, F, Y, Xv)
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


@njit(cache=True, error_model="numpy")
def _gather_slopes(q, o, dS, S, g, F, Y, X):
    """X = F^T r0' (3) from the element coordinates q[o : o + 16] at Gauss point g, and
    Y[6] = theta_1 there (:func:`gauss_variables` with the weights dS, S, only those slots)."""
    a0, a1, a2, a3 = dS[g, 0], dS[g, 1], dS[g, 2], dS[g, 3]
    for k in range(3):
        Y[k] = a0 * q[o + k] + a1 * q[o + 3 + k] + a2 * q[o + 8 + k] + a3 * q[o + 11 + k]
    Y[6] = S[g, 0] * q[o + 6] + S[g, 1] * q[o + 7] + S[g, 2] * q[o + 14] + S[g, 3] * q[o + 15]
    for i in range(3):
        X[i] = F[0, i] * Y[0] + F[1, i] * Y[1] + F[2, i] * Y[2]


@njit(cache=True, error_model="numpy")
def _mass_to_global(F, Mx, Mg):
    """Mg = T Mx T^T on (r0', theta_1), T = blockdiag(F, 1): chart to global components."""
    block_to_global(F, Mx, Mg)
    for r in range(3):
        side = F[r, 0] * Mx[0, 3] + F[r, 1] * Mx[1, 3] + F[r, 2] * Mx[2, 3]
        Mg[r, 3] = side
        Mg[3, r] = side  # Mx is symmetric
    Mg[3, 3] = Mx[3, 3]


@njit(cache=True, error_model="numpy")
def drag_kernel(qdot, length, S, w, frontal_width, c1, c2, scale, force, blocks):
    """Damping of Eq. 37-39: f_d = -(c1 + c2 |v|) v per unit frontal area on the centre-line
    velocity v, times the frontal width b per unit length (``frontal_width[el, g]``, m).

    ``force`` (n_dof) is overwritten with Q_d; ``scale`` times -dQ_d/dqdot (the damping
    matrix) is added to ``blocks`` (n_el, 16, 16) unless ``blocks`` is empty.
    Returns the dissipated power -Q_d . qdot (W).
    """
    n_el = (qdot.shape[0] - NODE_DOFS) // NODE_DOFS
    force[:] = 0.0
    if c1 == 0.0 and c2 == 0.0:
        return 0.0
    want_matrix = blocks.shape[0] == n_el
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
            jw = w[g] * length * frontal_width[el, g]
            coef = c1 + c2 * speed
            power += jw * coef * speed * speed
            for a in range(4):
                oa = _VEC_OFFSETS[a]
                for k in range(3):
                    force[NODE_DOFS * el + oa + k] -= jw * S[g, a] * coef * v[k]
                if not want_matrix:
                    continue
                for b in range(4):
                    ob = _VEC_OFFSETS[b]
                    for k in range(3):
                        for m in range(3):
                            Ckm = coef if k == m else 0.0
                            if speed > 0.0:
                                Ckm += c2 * v[k] * v[m] / speed
                            blocks[el, oa + k, ob + m] += scale * jw * S[g, a] * S[g, b] * Ckm
    return power
