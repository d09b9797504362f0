"""The air drag on an FFR beam's centre line (paper Eqs. 37-39) in v-space: its generalized
force, dissipated power and damping matrix, summed over the centre-line points of the drag
tuple (:mod:`hubbeam.elements.ffr.kernels`: ``drag = (N, span, x, w, width, c1, c2)``).
A point's shape rows N[k] (3, nf) vanish outside its element, so each point reads only its
span of coordinates (:func:`point_spans`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


def point_spans(N: np.ndarray) -> np.ndarray:
    """(first, last + 1) of the coordinates f where N[k, :, f] is not zero, for each point k of
    N (npts, 3, nf) (int64 (npts, 2); (0, 0) for a point without any)."""
    spans = np.zeros((N.shape[0], 2), dtype=np.int64)
    for k in range(N.shape[0]):
        touched = np.flatnonzero(np.any(N[k] != 0.0, axis=0))
        if touched.size:
            spans[k] = touched[0], touched[-1] + 1
    return spans


@njit(cache=True, error_model="numpy", _nrt=False)
def drag_point(Npts, xpts, k, p, pd, A, vb, rb, ub, rd):
    """Drag point k of the centre line: its body-frame position r_b = [x_k, 0, 0] + N_k p (m, into
    ``rb``), u_b = omega x r_b + N_k p' (``ub``) and its absolute velocity rdot = r_C' + A0 u_b
    (m/s, ``rd``); vb = [r_C', omega^b, ...] (v-space rates)."""
    nf = p.shape[0]
    for i in range(3):
        s = xpts[k] if i == 0 else 0.0
        s2 = 0.0
        for f in range(nf):
            s += Npts[k, i, f] * p[f]
            s2 += Npts[k, i, f] * pd[f]
        rb[i] = s
        ub[i] = s2
    w0, w1, w2 = vb[3], vb[4], vb[5]
    ub[0] += w1 * rb[2] - w2 * rb[1]
    ub[1] += w2 * rb[0] - w0 * rb[2]
    ub[2] += w0 * rb[1] - w1 * rb[0]
    for i in range(3):
        rd[i] = vb[i] + A[i, 0] * ub[0] + A[i, 1] * ub[1] + A[i, 2] * ub[2]


@njit(cache=True, error_model="numpy", _nrt=False)
def drag_loop(Npts, span, xpts, wpts, width, dc1, dc2, p, pd, A, vb, Qd, want_force):
    """The drag of Eq. 64 summed over the centre-line points: returns its dissipated power
    sum_k b_k w_k (c1 + c2 |rdot_k|) |rdot_k|^2 (W) and, when ``want_force``, writes Q_d (on v,
    6 + nf) into the leading entries of ``Qd`` (6 + 3 npts + nf: the rest is scratch). Works in
    the body frame: A0^T rdot_k = A0^T r_C' + omega^b x r_b,k + N_k p' (|rdot| = |A0^T rdot|),
    so that Q_d[0:3] = -A0 sum_k f_k A0^T rdot_k is turned to the global frame once; Q_d on
    omega^b = -sum_k r_b,k x (f_k A0^T rdot_k) and on p = -sum_k N_k^T (f_k A0^T rdot_k),
    f_k = b_k w_k (c1 + c2 |rdot_k|). No arrays per point (the residual's drag took about 2 us of
    its 4 us on exp1 with 4 modes and 24 points when each point filled small arrays). Point k
    reads only the coordinates of its span (module docstring: N_k is zero outside it, so the
    sums are those over every coordinate, term for term)."""
    nf = p.shape[0]
    w0, w1, w2 = vb[3], vb[4], vb[5]
    # body-frame velocity of the frame origin, A0^T r_C'
    c0 = A[0, 0] * vb[0] + A[1, 0] * vb[1] + A[2, 0] * vb[2]
    c1 = A[0, 1] * vb[0] + A[1, 1] * vb[1] + A[2, 1] * vb[2]
    c2 = A[0, 2] * vb[0] + A[1, 2] * vb[1] + A[2, 2] * vb[2]
    power = 0.0
    s0 = 0.0
    s1 = 0.0
    s2 = 0.0
    m0 = 0.0
    m1 = 0.0
    m2 = 0.0
    npts = Npts.shape[0]
    for k in range(npts):
        r0 = xpts[k]
        r1 = 0.0
        r2 = 0.0
        u0 = 0.0
        u1 = 0.0
        u2 = 0.0
        for f in range(span[k, 0], span[k, 1]):
            pf = p[f]
            pdf = pd[f]
            n0 = Npts[k, 0, f]
            n1 = Npts[k, 1, f]
            n2 = Npts[k, 2, f]
            r0 += n0 * pf
            r1 += n1 * pf
            r2 += n2 * pf
            u0 += n0 * pdf
            u1 += n1 * pdf
            u2 += n2 * pdf
        # A0^T rdot = A0^T r_C' + omega x r_b + N p'
        y0 = c0 + u0 + (w1 * r2 - w2 * r1)
        y1 = c1 + u1 + (w2 * r0 - w0 * r2)
        y2 = c2 + u2 + (w0 * r1 - w1 * r0)
        sq = y0 * y0 + y1 * y1 + y2 * y2
        fac = width[k] * wpts[k] * (dc1 + dc2 * math.sqrt(sq))
        power += fac * sq
        if want_force:
            f0 = fac * y0
            f1 = fac * y1
            f2 = fac * y2
            s0 += f0
            s1 += f1
            s2 += f2
            m0 += r1 * f2 - r2 * f1
            m1 += r2 * f0 - r0 * f2
            m2 += r0 * f1 - r1 * f0
            Qd[6 + 3 * k] = f0  # scratch: the point's force, body frame
            Qd[7 + 3 * k] = f1
            Qd[8 + 3 * k] = f2
    if not want_force:
        return power
    # Q_d on p: -sum_k N_k^T f_k (Qd[6:] holds the f_k until then), summed into Qd[3 npts + 6:]
    # point by point over its span (for each f, the points in the same order as a sum over all)
    acc = Qd[3 * npts + 6:3 * npts + 6 + nf]
    for f in range(nf):
        acc[f] = 0.0
    for k in range(npts):
        fk0 = Qd[6 + 3 * k]
        fk1 = Qd[7 + 3 * k]
        fk2 = Qd[8 + 3 * k]
        for f in range(span[k, 0], span[k, 1]):
            acc[f] += Npts[k, 0, f] * fk0 + Npts[k, 1, f] * fk1 + Npts[k, 2, f] * fk2
    for f in range(nf):
        Qd[6 + f] = -acc[f]
    for i in range(3):
        Qd[i] = -(A[i, 0] * s0 + A[i, 1] * s1 + A[i, 2] * s2)
    Qd[3] = -m0
    Qd[4] = -m1
    Qd[5] = -m2
    return power


@njit(cache=True, error_model="numpy", _nrt=False)
def drag_matrix(Npts, xpts, wpts, width, dc1, dc2, p, pd, A, vb, coef_c, block, points, Sb, Sr, Cv, cols):
    """block += coef_c C_v, C_v = -dQ_d/dv of the drag (Eq. 64) on the centre line (v-space, on the
    leading 6 + nf square): body-frame S_b = A0^T S = [A0^T, -skew(r), N], C_v = sum_k b_k w_k
    S_b^T G_b S_b with G_b = alpha I + beta r_b' r_b'^T, r_b' = A0^T rdot (alpha = c1 + c2 |rdot|,
    beta = c2 / |rdot|). Scratch: ``points`` (4, 3), Sb (3, n), Sr (n), Cv (n, n), ``cols`` (int, n),
    n = 6 + nf (or larger)."""
    nf = p.shape[0]
    n = 6 + nf
    rb, ub, rd, yb = points[0], points[1], points[2], points[3]
    for i in range(n):
        for j in range(n):
            Cv[i, j] = 0.0  # upper triangle of coef_c C_v
    for i in range(6):
        cols[i] = i
    for k in range(Npts.shape[0]):
        drag_point(Npts, xpts, k, p, pd, A, vb, rb, ub, rd)
        speed = math.sqrt(rd[0] * rd[0] + rd[1] * rd[1] + rd[2] * rd[2])
        weight = width[k] * wpts[k]
        alpha = dc1 + dc2 * speed
        beta = dc2 / speed if speed > 0.0 else 0.0
        for i in range(3):
            for j in range(3):
                Sb[i, j] = A[j, i]
        Sb[0, 3], Sb[0, 4], Sb[0, 5] = 0.0, rb[2], -rb[1]
        Sb[1, 3], Sb[1, 4], Sb[1, 5] = -rb[2], 0.0, rb[0]
        Sb[2, 3], Sb[2, 4], Sb[2, 5] = rb[1], -rb[0], 0.0
        # the columns of S_b that are not zero: r_C', omega and the point's element
        nc = 6
        for f in range(nf):
            Sb[0, 6 + f] = Npts[k, 0, f]
            Sb[1, 6 + f] = Npts[k, 1, f]
            Sb[2, 6 + f] = Npts[k, 2, f]
            if Sb[0, 6 + f] != 0.0 or Sb[1, 6 + f] != 0.0 or Sb[2, 6 + f] != 0.0:
                cols[nc] = 6 + f
                nc += 1
        for i in range(3):
            yb[i] = A[0, i] * rd[0] + A[1, i] * rd[1] + A[2, i] * rd[2]
        for j in range(n):
            Sr[j] = Sb[0, j] * yb[0] + Sb[1, j] * yb[1] + Sb[2, j] * yb[2]
        ca = coef_c * weight * alpha
        cb = coef_c * weight * beta
        for ii in range(nc):
            i = cols[ii]
            for jj in range(ii, nc):
                j = cols[jj]
                Cv[i, j] += ca * (Sb[0, i] * Sb[0, j] + Sb[1, i] * Sb[1, j] + Sb[2, i] * Sb[2, j]) \
                    + cb * Sr[i] * Sr[j]
    for i in range(n):
        block[i, i] += Cv[i, i]
        for j in range(i + 1, n):
            block[i, j] += Cv[i, j]
            block[j, i] += Cv[i, j]
