"""The second-order kinematics of a chain of frames (:mod:`hubbeam.system.frames`, whose
docstring states the serial-chain rule they follow): the velocity products h_r = sum_il
Hr[:, i, l] c'_i c'_l and h_w from a chain's derivatives (:func:`contracted_products`) or in one
pass over its columns without them (:func:`direct_products`), and the derivatives among an FFR
tip's own columns (:func:`tip_blocks`). Inlined into
:func:`~hubbeam.system.frames.chain_kinematics_into`.
"""

from __future__ import annotations

from numba import njit

from hubbeam.system.chains import COORD, TIP_COMBINATION, W_AXES, W_DIRECTION, W_INDEX, W_ORIGIN, W_TYPE
from hubbeam.system.rotations import cross3


@njit(cache=True, inline="always")
def contracted_products(Hr, Hw, cols, v, out):
    """out[0] = h_r = sum_il Hr[:, i, l] c'_i c'_l and out[1] = h_w likewise, c' = v[cols] (the
    velocity products of a chain from its derivatives)."""
    nc = cols.shape[0]
    for a in range(3):
        hr = hw = 0.0
        for i in range(nc):
            cd = v[cols[i]]
            if cd != 0.0:
                sr = sw = 0.0
                for l in range(nc):
                    cl = v[cols[l]]
                    sr += Hr[a, i, l] * cl
                    sw += Hw[a, i, l] * cl
                hr += sr * cd
                hw += sw * cd
        out[0, a] = hr
        out[1, a] = hw


@njit(cache=True, inline="always")
def direct_products(table, k, x, v, P, J, nc, root_columns, out):
    """The velocity products of chain k (a free body's link, if any, then screws: no ANCF or FFR
    tip) in one pass over its columns, without H (out[0] = h_r, out[1] = h_w; module docstring's
    rule summed over c'_i c'_l). With W_i = sum_{l<i} Jw_l c'_l (every column before i, the first
    link's included) and a_i = Jw_i c'_i, b_i = Jr_i c'_i for the columns i after the first
    link: h_w = sum_i W_i x a_i and h_r = sum_i (2 W_i + a_i) x b_i (the pairs l <= i give
    W_i x b_i + a_i x b_i, the pairs l > i, turned round, W_i x b_i again). A free body's own
    columns add theirs: with w_e = sum Jw_j e'_j over its Euler parameters (Jw_j = 2 E_j / |e|^2,
    E linear in e and E(e') e' = 0), h_w = -2 (e . e') / |e|^2 w_e and h_r = h_w x d + w_e x (w_e x
    d), d = r - r_b."""
    cs = table.column_start[k]
    cols = table.columns
    w0 = w1 = w2 = 0.0
    hw0 = hw1 = hw2 = 0.0
    hr0 = hr1 = hr2 = 0.0
    if root_columns > 0:  # a free body (an ANCF tip never comes here)
        c0 = table.links[table.start[k], COORD]
        s = ed = 0.0
        for j in range(3, 7):
            cd = v[cols[cs + j]]
            e = x[c0 + j]
            s += e * e
            ed += e * cd
            w0 += J[1, 0, j] * cd
            w1 += J[1, 1, j] * cd
            w2 += J[1, 2, j] * cd
        f = -2.0 * ed / s
        hw0, hw1, hw2 = f * w0, f * w1, f * w2
        d0, d1, d2 = P[0, 0] - x[c0], P[1, 0] - x[c0 + 1], P[2, 0] - x[c0 + 2]
        u0, u1, u2 = cross3(w0, w1, w2, d0, d1, d2)
        p0, p1, p2 = cross3(hw0, hw1, hw2, d0, d1, d2)
        q0, q1, q2 = cross3(w0, w1, w2, u0, u1, u2)
        hr0, hr1, hr2 = p0 + q0, p1 + q1, p2 + q2
    for i in range(root_columns, nc):
        cd = v[cols[cs + i]]
        a0, a1, a2 = J[1, 0, i] * cd, J[1, 1, i] * cd, J[1, 2, i] * cd
        b0, b1, b2 = J[0, 0, i] * cd, J[0, 1, i] * cd, J[0, 2, i] * cd
        c0, c1, c2 = cross3(w0, w1, w2, a0, a1, a2)
        hw0 += c0
        hw1 += c1
        hw2 += c2
        c0, c1, c2 = cross3(2.0 * w0 + a0, 2.0 * w1 + a1, 2.0 * w2 + a2, b0, b1, b2)
        hr0 += c0
        hr1 += c1
        hr2 += c2
        w0 += a0
        w1 += a1
        w2 += a2
    out[0, 0], out[0, 1], out[0, 2] = hr0, hr1, hr2
    out[1, 0], out[1, 1], out[1, 2] = hw0, hw1, hw2


@njit(cache=True, inline="always")
def tip_blocks(table, P, work, nc, H):
    """H among each FFR tip's own columns (j, m): with A_j = M[3:6, j] the weights of its rotations
    w_0, w_1, w_2 (x, y', z'') about its place o and u_a = w_a x (r - o),
    Hw_jm = sum_{b<a} A_j[a] A_m[b] w_b x w_a and Hr_jm = sum_ab A_j[a] A_m[b] w_min(a,b) x u_max(a,b)
    (the serial rule over the screws; the translations give no terms among them)."""
    maps = table.maps
    for i in range(nc):
        if work[i, W_TYPE] != TIP_COMBINATION or work[i, W_INDEX] != 0.0:
            continue
        pr = int(work[i, W_DIRECTION])
        off, nf = int(table.params[pr, 1]), int(table.params[pr, 2])
        d0 = P[0, 0] - work[i, W_ORIGIN]
        d1 = P[1, 0] - work[i, W_ORIGIN + 1]
        d2 = P[2, 0] - work[i, W_ORIGIN + 2]
        a0, a1, a2 = work[i, W_AXES], work[i, W_AXES + 1], work[i, W_AXES + 2]
        b0, b1, b2 = work[i, W_AXES + 3], work[i, W_AXES + 4], work[i, W_AXES + 5]
        c0, c1, c2 = work[i, W_AXES + 6], work[i, W_AXES + 7], work[i, W_AXES + 8]
        ua0, ua1, ua2 = cross3(a0, a1, a2, d0, d1, d2)  # u = w x d
        ub0, ub1, ub2 = cross3(b0, b1, b2, d0, d1, d2)
        uc0, uc1, uc2 = cross3(c0, c1, c2, d0, d1, d2)
        ab0, ab1, ab2 = cross3(a0, a1, a2, b0, b1, b2)  # Hw's pairs w_a x w_b
        ac0, ac1, ac2 = cross3(a0, a1, a2, c0, c1, c2)
        bc0, bc1, bc2 = cross3(b0, b1, b2, c0, c1, c2)
        qaa0, qaa1, qaa2 = cross3(a0, a1, a2, ua0, ua1, ua2)  # Hr's pairs w_min x u_max
        qbb0, qbb1, qbb2 = cross3(b0, b1, b2, ub0, ub1, ub2)
        qcc0, qcc1, qcc2 = cross3(c0, c1, c2, uc0, uc1, uc2)
        qab0, qab1, qab2 = cross3(a0, a1, a2, ub0, ub1, ub2)
        qac0, qac1, qac2 = cross3(a0, a1, a2, uc0, uc1, uc2)
        qbc0, qbc1, qbc2 = cross3(b0, b1, b2, uc0, uc1, uc2)
        for j in range(nf):
            ja, jb, jc = maps[off + 3 * nf + j], maps[off + 4 * nf + j], maps[off + 5 * nf + j]
            for m in range(nf):
                ma, mb, mc = maps[off + 3 * nf + m], maps[off + 4 * nf + m], maps[off + 5 * nf + m]
                fab, fac, fbc = jb * ma, jc * ma, jc * mb
                H[1, 0, i + j, i + m] = fab * ab0 + fac * ac0 + fbc * bc0
                H[1, 1, i + j, i + m] = fab * ab1 + fac * ac1 + fbc * bc1
                H[1, 2, i + j, i + m] = fab * ab2 + fac * ac2 + fbc * bc2
                gaa, gbb, gcc = ja * ma, jb * mb, jc * mc
                gab, gac, gbc = ja * mb + jb * ma, ja * mc + jc * ma, jb * mc + jc * mb
                H[0, 0, i + j, i + m] = gaa * qaa0 + gbb * qbb0 + gcc * qcc0 + gab * qab0 + gac * qac0 + gbc * qbc0
                H[0, 1, i + j, i + m] = gaa * qaa1 + gbb * qbb1 + gcc * qcc1 + gab * qab1 + gac * qac1 + gbc * qbc1
                H[0, 2, i + j, i + m] = gaa * qaa2 + gbb * qbb2 + gcc * qcc2 + gab * qab2 + gac * qac2 + gbc * qbc2
