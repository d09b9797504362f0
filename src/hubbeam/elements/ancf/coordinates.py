"""The ANCF beam's coordinates and their Gauss-point variables, shared by its element loops
(:mod:`~hubbeam.elements.ancf.elastic`, :mod:`~hubbeam.elements.ancf.inertia`,
:mod:`~hubbeam.elements.ancf.loads`).

Node coordinates (paper Eq. 14): [r0 (3), r0' (3), theta_1, theta_1'], 8 per node;
element e joins nodes e and e+1, so its 16 coordinates are q[8e : 8e + 16].
Integrals use Gauss-Legendre points on each element; ``S, dS, d2S`` are the Hermite
functions tabulated at those points (:func:`hubbeam.elements.hermite.hermite`).

The Gauss-point variables X = (r0', r0'', theta_1, theta_1') (global components) are
linear in the element coordinates, and each coordinate enters exactly two of them: the
component k of the vector coefficient of Hermite function a enters r0'_k with weight
S_a' and r0''_k with S_a''; the twist coefficient of function a enters theta_1 with S_a
and theta_1' with S_a' (:data:`DOF_FIRST`, :data:`DOF_SECOND`, :func:`dof_weights`). The
element loops use this sparsity instead of a dense 8 x 16 operator. Strain and frame
quantities are computed in chart components (U = F^T r0') and rotated back
(:func:`to_chart`, :func:`to_global`; a 16 x 16 element block once per element,
:func:`add_element_to_global`).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.elements.ancf.frame import block_to_global
from hubbeam.elements.ancf.strain import PHI, PSI

NODE_DOFS = 8
ELEMENT_DOFS = 16
#: offsets of the four Hermite coefficient groups inside an element's 16 coordinates
VEC_OFFSETS = (0, 3, 8, 11)
ANG_OFFSETS = (6, 7, 14, 15)
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
    to_chart(F, Y, X)


@njit(cache=True, error_model="numpy")


def to_chart(F, Y, X):
    """X = T^T Y, T = blockdiag(F, F, 1, 1): global to chart components of an 8-vector."""
    for b in range(2):
        for i in range(3):
            X[3 * b + i] = F[0, i] * Y[3 * b] + F[1, i] * Y[3 * b + 1] + F[2, i] * Y[3 * b + 2]
    X[6] = Y[6]
    X[7] = Y[7]


@njit(cache=True, error_model="numpy")


def gather(q, o, A, B, C, D, g, Y):
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


def scatter(force, o, A, B, C, D, g, jw, Y):
    """force[o : o + 16] += jw B^T Y, the transpose of :func:`gather` (Y global)."""
    for a in range(4):
        oa = o + VEC_OFFSETS[a]
        u1, u2 = A[g, a], B[g, a]
        for k in range(3):
            force[oa + k] += jw * (u1 * Y[k] + u2 * Y[3 + k])
        force[o + ANG_OFFSETS[a]] += jw * (C[g, a] * Y[6] + D[g, a] * Y[7])


@njit(cache=True, error_model="numpy")


def to_global(F, X, Y):
    """Y = T X, T = blockdiag(F, F, 1, 1): chart to global components of an 8-vector."""
    for b in range(2):
        for i in range(3):
            Y[3 * b + i] = F[i, 0] * X[3 * b] + F[i, 1] * X[3 * b + 1] + F[i, 2] * X[3 * b + 2]
    Y[6] = X[6]
    Y[7] = X[7]


@njit(cache=True, error_model="numpy")


def add_element_to_global(F, Kc, tmp, blocks, el, symmetric):
    """blocks[el] += T_e Kc T_e^T: a 16 x 16 element block in chart components (Kc) in global
    components; T_e = blockdiag(F, F, 1, 1, F, F, 1, 1) maps the chart components of the
    element coordinates (F^T r, F^T r', theta_1, theta_1' at both nodes) to the global ones.
    As X = T^T Y (:func:`to_chart`) and each 3-vector of Y is a Hermite sum of the element's
    3-vectors, T^T B = B T_e^T: sum_g B^T T HW_g T^T B = T_e (sum_g B^T HW_g B) T_e^T.
    For a ``symmetric`` Kc only the lower triangle of T_e Kc T_e^T is computed (and mirrored).
    ``tmp`` (16 x 16): scratch."""
    for r in range(ELEMENT_DOFS):  # tmp = Kc T_e^T
        for o in VEC_OFFSETS:
            k0, k1, k2 = Kc[r, o], Kc[r, o + 1], Kc[r, o + 2]
            for i in range(3):
                tmp[r, o + i] = k0 * F[i, 0] + k1 * F[i, 1] + k2 * F[i, 2]
        for o in ANG_OFFSETS:
            tmp[r, o] = Kc[r, o]
    for o in VEC_OFFSETS:  # blocks[el] += T_e tmp
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
    for o in ANG_OFFSETS:
        if symmetric:
            for c in range(o):
                blocks[el, o, c] += tmp[o, c]
                blocks[el, c, o] += tmp[o, c]
            blocks[el, o, o] += tmp[o, o]
        else:
            for c in range(ELEMENT_DOFS):
                blocks[el, o, c] += tmp[o, c]


@njit(cache=True, error_model="numpy")


def add_sandwich(Ke, HY, w1, w2, factor, R, lower):
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


def add_symmetric(blocks, el, Ke):
    """blocks[el] += the symmetric matrix whose lower triangle is stored in Ke."""
    for j in range(ELEMENT_DOFS):
        blocks[el, j, j] += Ke[j, j]
        for i in range(j):
            blocks[el, i, j] += Ke[j, i]
            blocks[el, j, i] += Ke[j, i]


@njit(cache=True, error_model="numpy")


def gather_slopes(q, o, dS, S, g, F, Y, X):
    """X = F^T r0' (3) from the element coordinates q[o : o + 16] at Gauss point g, and
    Y[6] = theta_1 there (:func:`gauss_variables` with the weights dS, S, only those slots)."""
    a0, a1, a2, a3 = dS[g, 0], dS[g, 1], dS[g, 2], dS[g, 3]
    for k in range(3):
        Y[k] = a0 * q[o + k] + a1 * q[o + 3 + k] + a2 * q[o + 8 + k] + a3 * q[o + 11 + k]
    Y[6] = S[g, 0] * q[o + 6] + S[g, 1] * q[o + 7] + S[g, 2] * q[o + 14] + S[g, 3] * q[o + 15]
    for i in range(3):
        X[i] = F[0, i] * Y[0] + F[1, i] * Y[1] + F[2, i] * Y[2]


@njit(cache=True, error_model="numpy")


def mass_to_global(F, Mx, Mg):
    """Mg = T Mx T^T on (r0', theta_1), T = blockdiag(F, 1): chart to global components."""
    block_to_global(F, Mx, Mg)
    for r in range(3):
        side = F[r, 0] * Mx[0, 3] + F[r, 1] * Mx[1, 3] + F[r, 2] * Mx[2, 3]
        Mg[r, 3] = side
        Mg[3, r] = side  # Mx is symmetric
    Mg[3, 3] = Mx[3, 3]
