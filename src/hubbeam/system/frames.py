"""Frames: where bodies and beam roots hang, as chains of elementary transforms.

A frame of a system (the base, the hub, a beam's root section, a rigid body's principal
axes at its centre of mass, ...) is a *chain*: the product of elementary transforms, each
either constant or moved by coordinates of the system:

    T = T_1 T_2 ... T_n,   T_i = (t_i, R_i): a point p of the next frame is at t_i + R_i p

- ``CONSTANT``: a fixed offset t and rotation R (a mount, the hub's place on the base, a
  twist);
- ``REVOLUTE``: a rotation by ``sign * c`` about a fixed unit axis of the current frame, c one
  coordinate (the hub angle theta turns about -j, ``sign = -1``; a joint angle psi);
- ``FREE`` (first link only): a rigid body's six degrees of freedom in seven coordinates,
  the position r_b (3) and the Euler parameters e = (e0, e1, e2, e3) (4) of its rotation
  R(e / |e|) (the rotation of the normalised parameters: it is exact for any e != 0, and the
  norm is fixed by a constraint elsewhere);
- ``ANCF_TIP`` (first link only): the section frame of an ANCF node, from its position r0
  (3), slope r0' (3) and twist theta_1 (1) in a rotation chart F (:mod:`hubbeam.elements.ancf.frame`);
- ``FFR_TIP`` (never first): the tip section of an FFR beam floating on the current frame,
  moved by its nf elastic coordinates p: a translation by (L, 0, 0) + N_L p and a small
  rotation by phi = Phi_L p (N_L, Phi_L: the tip's displacement and rotation rows of
  :class:`~hubbeam.elements.ffr.body.FfrBeam`), turned as successive rotations by phi_1,
  phi_2, phi_3 about the current x, y', z'' axes (equal to the rotation vector phi to first
  order, FFR's own kinematics).

For every coordinate c_i of a chain :func:`chain_kinematics` gives the frame's pose (r, R)
and the velocity Jacobians: Jw[:, i], the frame's angular velocity per unit c_i' (global
axes), and Jr[:, i], its origin's velocity; and, on request, their derivatives
Hw[:, i, l] = dJw[:, i] / dc_l and Hr[:, i, l] = dJr[:, i] / dc_l. For coordinates whose
motion is a fixed screw of the frame before them (revolute: axis u_i through o_i, so
Jw_i = u_i, Jr_i = u_i x (r - o_i); a translation: Jw_i = 0, Jr_i = a fixed direction) the
serial-chain rule gives them all by cross products:

    l before or equal i:  Hw_il = Jw_l x Jw_i,   Hr_il = Jw_l x Jr_i
    l after i:            Hw_il = 0,             Hr_il = Jw_i x Jr_l

(a translation along an axis of the current frame, Jw_i = 0 and Jr_i that axis, follows the
same rule). The first link's own coordinates (``FREE``, ``ANCF_TIP``) are not such screws among
each other: their mutual derivatives are written out below; with every later coordinate the
rule holds (the first link carries the rest of the chain). An ``FFR_TIP`` link is six such
screws in a row (three translations t_a along the current axes, then three rotations w_a
about the current x, y', z'', all through the tip's place o) whose *virtual* coordinates
v = M p, M = [N_L; Phi_L] (6 x nf), are linear in its nf coordinates: its column j is the
combination sum_a M[a, j] of the six screws (Jr_j = sum_{a<3} M[a, j] t_a + Jw_j x (r - o),
Jw_j = sum_{a>=3} M[a, j] w_a), so with any other column the rule holds as it is; among its
own columns, H_jm = sum_ab M[a, j] M[b, m] H_ab of the rule over the screws (only the
rotations give terms) is written out below. Tests check every Jacobian and derivative
against finite differences of the pose.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from hubbeam.system.chains import (COORD, HESSIANS, KIND, PARAM, POSE, PRODUCTS, ROOT_ROTATION, SCREW, TIP_COMBINATION,
                                   TRANSLATION, W_AXES, W_DIRECTION, W_INDEX, W_ORIGIN, W_TYPE, W_WIDTH, ChainTable,
                                   LinkKind)
from hubbeam.system.frame_products import contracted_products, direct_products, tip_blocks
from hubbeam.system.rotations import euler_rotation_into


# ---------------------------------------------------------------------------- small pieces
@njit(cache=True)
def _rotate_about(P, a0, a1, a2, angle):
    """P[:, 1:4] = R Rot(a, angle) in place (R = P[:, 1:4]; a a unit vector of the frame R)."""
    c, s = math.cos(angle), math.sin(angle)
    C = 1.0 - c
    q00, q01, q02 = c + a0 * a0 * C, a0 * a1 * C - a2 * s, a0 * a2 * C + a1 * s
    q10, q11, q12 = a1 * a0 * C + a2 * s, c + a1 * a1 * C, a1 * a2 * C - a0 * s
    q20, q21, q22 = a2 * a0 * C - a1 * s, a2 * a1 * C + a0 * s, c + a2 * a2 * C
    for i in range(3):
        r0, r1, r2 = P[i, 1], P[i, 2], P[i, 3]
        P[i, 1] = r0 * q00 + r1 * q10 + r2 * q20
        P[i, 2] = r0 * q01 + r1 * q11 + r2 * q21
        P[i, 3] = r0 * q02 + r1 * q12 + r2 * q22


@njit(cache=True, inline="always")
def _ancf_section(F, x, c, P):
    """The section frame R = F [tau m n](F^T u, phi) (global columns) of slope u = x[c:c+3] and
    twist phi = x[c+3] into P[:, 1:4]; returns |u|."""
    U0 = F[0, 0] * x[c] + F[1, 0] * x[c + 1] + F[2, 0] * x[c + 2]
    U1 = F[0, 1] * x[c] + F[1, 1] * x[c + 1] + F[2, 1] * x[c + 2]
    U2 = F[0, 2] * x[c] + F[1, 2] * x[c + 1] + F[2, 2] * x[c + 2]
    L = math.sqrt(U0 * U0 + U1 * U1 + U2 * U2)
    T0, T1, T2 = U0 / L, U1 / L, U2 / L
    den = 1.0 + T0
    h1, h2 = T1 / den, T2 / den
    # m0, n0 (chart components) of the untwisted chart frame
    m00, m01, m02 = -h1 * (T0 + 1.0), 1.0 - h1 * T1, -h1 * T2
    n00, n01, n02 = -h2 * (T0 + 1.0), -h2 * T1, 1.0 - h2 * T2
    co, si = math.cos(x[c + 3]), math.sin(x[c + 3])
    m0, m1, m2 = co * m00 + si * n00, co * m01 + si * n01, co * m02 + si * n02
    n0, n1, n2 = -si * m00 + co * n00, -si * m01 + co * n01, -si * m02 + co * n02
    for i in range(3):
        P[i, 1] = F[i, 0] * T0 + F[i, 1] * T1 + F[i, 2] * T2
        P[i, 2] = F[i, 0] * m0 + F[i, 1] * m1 + F[i, 2] * m2
        P[i, 3] = F[i, 0] * n0 + F[i, 1] * n1 + F[i, 2] * n2
    return L


@njit(cache=True, inline="always")
def _cross_unit(a0, a1, a2, i):
    """a x e_i (e_i the i-th unit vector), a 3-tuple."""
    if i == 0:
        return 0.0, a2, -a1
    if i == 1:
        return -a2, 0.0, a0
    return a1, -a0, 0.0


@njit(cache=True, inline="always")
def _ancf_rate_column(d0, d1, d2, t0, t1, t2, L, b):
    """A e_b, the angular velocity of the chart's untwisted frame for a unit rate of the slope's
    component b (a 3-tuple): (tau x e_b - tau d.(tau x e_b) / (1 + d.tau)) / L."""
    c0, c1, c2 = _cross_unit(t0, t1, t2, b)
    k = (d0 * c0 + d1 * c1 + d2 * c2) / (1.0 + d0 * t0 + d1 * t1 + d2 * t2)
    return (c0 - t0 * k) / L, (c1 - t1 * k) / L, (c2 - t2 * k) / L


@njit(cache=True, inline="always")
def _ancf_rate_derivative(d0, d1, d2, t0, t1, t2, L, i, b):
    """d(A e_i)/d u_b (u = r0'): the derivative of :func:`_ancf_rate_column` along the slope's
    component b (a 3-tuple)."""
    dL = (t0, t1, t2)[b]
    # d tau / d u_b
    s0 = ((1.0 if b == 0 else 0.0) - t0 * dL) / L
    s1 = ((1.0 if b == 1 else 0.0) - t1 * dL) / L
    s2 = ((1.0 if b == 2 else 0.0) - t2 * dL) / L
    den = 1.0 + d0 * t0 + d1 * t1 + d2 * t2
    y0, y1, y2 = _cross_unit(t0, t1, t2, i)
    z0, z1, z2 = _cross_unit(s0, s1, s2, i)
    k = (d0 * y0 + d1 * y1 + d2 * y2) / den
    dk = (d0 * z0 + d1 * z1 + d2 * z2) / den - k * (d0 * s0 + d1 * s1 + d2 * s2) / den
    f = -dL / L
    return (f * (y0 - t0 * k) / L + (z0 - s0 * k - t0 * dk) / L,
            f * (y1 - t1 * k) / L + (z1 - s1 * k - t1 * dk) / L,
            f * (y2 - t2 * k) / L + (z2 - s2 * k - t2 * dk) / L)


# ---------------------------------------------------------------------------- the kinematics


@njit(cache=True)
def chain_kinematics(table, k, x, F, order, r, R, Jr, Jw, Hr, Hw):
    """:func:`chain_kinematics_into` of chain k into r (3), R (3 x 3), Jr, Jw (3, nc), Hr, Hw (3, nc, nc)
    (its arrays allocated here: for tests, front ends and differences, not for every step)."""
    nc = table.column_start[k + 1] - table.column_start[k]
    pose, jac, hess = np.empty((1, 3, 4)), np.empty((1, 2, 3, nc)), np.empty((1, 2, 3, nc, nc))
    chain_kinematics_into(table, np.int64(k), k + 1, x, F, np.int64(HESSIANS if order >= 2 else POSE),
                          np.full(1, HESSIANS, np.int64), pose, jac, hess, np.empty((nc, W_WIDTH)), table.free_links,
                          table.ancf_tips, table.ffr_tips, x, np.empty((1, 2, 3)), x.shape[0] < 0)
    P, J, H = pose[0], jac[0], hess[0]
    for i in range(3):
        r[i] = P[i, 0]
        for j in range(3):
            R[i, j] = P[i, 1 + j]
        for c in range(nc):
            Jr[i, c] = J[0, i, c]
            Jw[i, c] = J[1, i, c]
            if order >= 2:
                for l in range(nc):
                    Hr[i, c, l] = H[0, i, c, l]
                    Hw[i, c, l] = H[1, i, c, l]


@njit(cache=True, inline="always")
def _euler_rate_entry(e0, e1, e2, e3, a, i):
    """E[a, i] of :func:`euler_rate_matrix` (E is linear in e)."""
    if a == 0:
        return (-e1, e0, -e3, e2)[i]
    if a == 1:
        return (-e2, e3, e0, -e1)[i]
    return (-e3, -e2, e1, e0)[i]


@njit(cache=True, inline="always")
def _cross_columns(J, sa, ja, sb, jb, H, s, i, l, add):
    """H[s, :, i, l] (+)= J[sa, :, ja] x J[sb, :, jb] (no views: scalars only)."""
    a0, a1, a2 = J[sa, 0, ja], J[sa, 1, ja], J[sa, 2, ja]
    b0, b1, b2 = J[sb, 0, jb], J[sb, 1, jb], J[sb, 2, jb]
    c0, c1, c2 = a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0
    if add:
        H[s, 0, i, l] += c0
        H[s, 1, i, l] += c1
        H[s, 2, i, l] += c2
    else:
        H[s, 0, i, l] = c0
        H[s, 1, i, l] = c1
        H[s, 2, i, l] = c2


@njit(cache=True, inline="always")
def _root_translation(x, c0, col, P, J, work):
    """A root link's translation (a free body's, an ANCF tip node's): the origin P[:, 0] = x[c0 :
    c0 + 3] (m, global) and its three columns from col on, translations along the global axes
    (no rotation: J[1, :, col + j] = 0)."""
    for i in range(3):
        P[i, 0] = x[c0 + i]
    for j in range(3):
        for a in range(3):
            J[1, a, col + j] = 0.0
        work[col + j, W_TYPE] = TRANSLATION
        work[col + j, W_DIRECTION] = j


@njit(cache=True, _nrt=False)
def chain_kinematics_into(table, first, last, x, F, order, orders, pose, jac, hess, work, free_links, ancf_tips,
                          ffr_tips, v, products, with_products):
    """The poses of chains first, ..., last - 1 at the coordinates x (charts F for ANCF tips),
    chain k into pose[k - first], jac[k - first], hess[k - first], products[k - first]. What is
    evaluated of chain k (:data:`~hubbeam.system.chains.POSE`, ``PRODUCTS``, ``HESSIANS``):
    POSE where ``order`` or orders[k - first] is POSE; else orders[k - first] for ``order``
    PRODUCTS, HESSIANS for ``order`` HESSIANS (0: left as it was). Its pose P (3 x 4): origin r (column 0, m) and
    axes R (columns 1-3, global); for each of its nc coordinate columns (the chain's order:
    :attr:`ChainTable.columns`) J[0, :, i] = Jr[:, i] (m or m/rad per unit coordinate) and
    J[1, :, i] = Jw[:, i] (rad per unit coordinate, global axes). To order 2 also H[0, :, i, l]
    = Hr[:, i, l] = dJr[:, i]/dc_l and H[1, :, i, l] = Hw[:, i, l] = dJw[:, i]/dc_l (module
    docstring); with ``with_products`` (and the rates v of x) beyond POSE also the velocity
    products h_r = sum_il Hr[:, i, l] c'_i c'_l and h_w likewise (c' = v at the chain's columns)
    into products[k - first, 0] and [1]: where only they are asked (PRODUCTS) and the chain has
    neither an ANCF tip nor an FFR tip, in one pass over its columns without H (:func:`_direct_products`),
    else contracted from H. J (2, 3, >= nc) and H (2, 3, >= nc, >= nc) are overwritten on their first nc
    columns; ``work`` (>= nc, W_WIDTH): scratch (a column's type, a translation's axis, the
    point a rotation turns about, an FFR tip's axes). Scalars only: no allocation and, compiled
    without numba's reference counting, no count of the table's arrays (a step evaluates every
    chain in one call: :func:`evaluate_chains`). One compiled function holds the loop over the
    chains and the kinematics, called by every user (not inlined: numba's inliner copies an
    inlined function's IR block by block with all its variables, and inlining this one cost
    about 5 s of a first compile). ``free_links``, ``ancf_tips``, ``ffr_tips``: the table's
    (:class:`ChainTable`), so that numba prunes the code of a kind of link whose flag is None
    before it types and compiles it (exp1's chains, constants and revolutes only, compile in a
    fraction of the time)."""
    for k in range(first, last):
        level = orders[k - first]
        chain_order = level if (order == PRODUCTS or level <= POSE) else min(order, HESSIANS)
        if order == POSE:
            chain_order = POSE
        if chain_order <= 0:
            continue
        P, J, H = pose[k - first], jac[k - first], hess[k - first]
        l0, l1 = table.start[k], table.start[k + 1]
        nc = table.column_start[k + 1] - table.column_start[k]
        par = table.params
        maps = table.maps
        root_columns = 0  # the first link's own columns (their mutual derivatives are explicit)
        root_kind = -1
        col = 0
        slope_length = 1.0
        tau0 = tau1 = tau2 = 0.0  # an ANCF tip's section axis (later links turn P)
        shared = table.prefix[k]  # a chain evaluated before whose links begin this one's
        if shared >= first and (chain_order == POSE or (chain_order == PRODUCTS and with_products)):
            Ps, Js = pose[shared - first], jac[shared - first]
            for i in range(3):
                for j in range(4):
                    P[i, j] = Ps[i, j]
            col = table.column_start[shared + 1] - table.column_start[shared]
            for c in range(col):
                for i in range(3):
                    J[1, i, c] = Js[1, i, c]
            if free_links is not None and table.links[l0, KIND] == LinkKind.FREE:
                root_kind = LinkKind.FREE
                root_columns = 7
            l_start = l0 + table.start[shared + 1] - table.start[shared]
        else:
            shared = -1
            for i in range(3):
                P[i, 0] = 0.0
                for j in range(3):
                    P[i, 1 + j] = 1.0 if i == j else 0.0
            l_start = l0
        own = col  # the columns before own: the shared chain's (their Jr moved to this origin below)
        for li in range(l_start, l1):
            kind = table.links[li, KIND]
            c0 = table.links[li, COORD]
            pr = table.links[li, PARAM]
            if kind == LinkKind.CONSTANT:
                for i in range(3):
                    R0, R1, R2 = P[i, 1], P[i, 2], P[i, 3]
                    P[i, 0] += R0 * par[pr, 0] + R1 * par[pr, 1] + R2 * par[pr, 2]
                    P[i, 1] = R0 * par[pr, 3] + R1 * par[pr, 6] + R2 * par[pr, 9]
                    P[i, 2] = R0 * par[pr, 4] + R1 * par[pr, 7] + R2 * par[pr, 10]
                    P[i, 3] = R0 * par[pr, 5] + R1 * par[pr, 8] + R2 * par[pr, 11]
            elif kind == LinkKind.REVOLUTE:
                a0, a1, a2, sign = par[pr, 0], par[pr, 1], par[pr, 2], par[pr, 3]
                for i in range(3):
                    J[1, i, col] = sign * (P[i, 1] * a0 + P[i, 2] * a1 + P[i, 3] * a2)
                    work[col, W_ORIGIN + i] = P[i, 0]
                work[col, W_TYPE] = SCREW
                _rotate_about(P, a0, a1, a2, sign * x[c0])
                col += 1
            elif ffr_tips is not None and kind == LinkKind.FFR_TIP:
                length, off, nf = par[pr, 0], int(par[pr, 1]), int(par[pr, 2])
                v0 = v1 = v2 = v3 = v4 = v5 = 0.0  # the virtual coordinates M p
                for j in range(nf):
                    p = x[c0 + j]
                    v0 += maps[off + j] * p
                    v1 += maps[off + nf + j] * p
                    v2 += maps[off + 2 * nf + j] * p
                    v3 += maps[off + 3 * nf + j] * p
                    v4 += maps[off + 4 * nf + j] * p
                    v5 += maps[off + 5 * nf + j] * p
                for j in range(nf):  # the translations' part of Jr, along the current axes
                    m0, m1, m2 = maps[off + j], maps[off + nf + j], maps[off + 2 * nf + j]
                    for i in range(3):
                        J[0, i, col + j] = P[i, 1] * m0 + P[i, 2] * m1 + P[i, 3] * m2
                        J[1, i, col + j] = 0.0
                    work[col + j, W_TYPE] = TIP_COMBINATION
                    work[col + j, W_DIRECTION] = pr
                    work[col + j, W_INDEX] = j
                for i in range(3):
                    P[i, 0] += P[i, 1] * (length + v0) + P[i, 2] * v1 + P[i, 3] * v2
                    for j in range(nf):
                        work[col + j, W_ORIGIN + i] = P[i, 0]
                for a in range(3):  # the rotations about x, then y', then z'': Jw and the axes kept
                    for j in range(nf):
                        m = maps[off + (3 + a) * nf + j]
                        for i in range(3):
                            J[1, i, col + j] += P[i, 1 + a] * m
                    for i in range(3):
                        work[col, W_AXES + 3 * a + i] = P[i, 1 + a]
                    _rotate_about(P, 1.0 if a == 0 else 0.0, 1.0 if a == 1 else 0.0, 1.0 if a == 2 else 0.0,
                                  v3 if a == 0 else (v4 if a == 1 else v5))
                col += nf
            elif free_links is not None and kind == LinkKind.FREE:
                root_kind = kind
                root_columns = 7
                _root_translation(x, c0, col, P, J, work)
                e0, e1, e2, e3 = x[c0 + 3], x[c0 + 4], x[c0 + 5], x[c0 + 6]
                euler_rotation_into(e0, e1, e2, e3, P, 1)
                s = e0 * e0 + e1 * e1 + e2 * e2 + e3 * e3
                for a in range(4):
                    for i in range(3):
                        J[1, i, col + 3 + a] = 2.0 * _euler_rate_entry(e0, e1, e2, e3, i, a) / s
                        work[col + 3 + a, W_ORIGIN + i] = P[i, 0]
                    work[col + 3 + a, W_TYPE] = ROOT_ROTATION
                col += 7
            elif ancf_tips is not None:  # ANCF_TIP
                root_kind = kind
                root_columns = 7
                Fc = F[int(par[pr, 0])]
                _root_translation(x, c0, col, P, J, work)
                slope_length = _ancf_section(Fc, x, c0 + 3, P)
                tau0, tau1, tau2 = P[0, 1], P[1, 1], P[2, 1]
                for b in range(3):
                    o0, o1, o2 = _ancf_rate_column(Fc[0, 0], Fc[1, 0], Fc[2, 0], tau0, tau1, tau2, slope_length, b)
                    J[1, 0, col + 3 + b], J[1, 1, col + 3 + b], J[1, 2, col + 3 + b] = o0, o1, o2
                    for i in range(3):
                        work[col + 3 + b, W_ORIGIN + i] = P[i, 0]
                    work[col + 3 + b, W_TYPE] = ROOT_ROTATION
                J[1, 0, col + 6], J[1, 1, col + 6], J[1, 2, col + 6] = tau0, tau1, tau2
                for i in range(3):
                    work[col + 6, W_ORIGIN + i] = P[i, 0]
                work[col + 6, W_TYPE] = ROOT_ROTATION
                col += 7
        # origin velocities: a translation's axis, or a rotation's axis x (r - the point it turns
        # about) (added to an FFR tip column's translations)
        has_tip = False
        if shared >= 0:  # Jr_i = Jw_i x (r - o_i) = Jr_i of the shared chain + Jw_i x (r - its r)
            Ps, Js = pose[shared - first], jac[shared - first]
            d0, d1, d2 = P[0, 0] - Ps[0, 0], P[1, 0] - Ps[1, 0], P[2, 0] - Ps[2, 0]
            for i in range(own):
                w0, w1, w2 = J[1, 0, i], J[1, 1, i], J[1, 2, i]
                J[0, 0, i] = Js[0, 0, i] + (w1 * d2 - w2 * d1)
                J[0, 1, i] = Js[0, 1, i] + (w2 * d0 - w0 * d2)
                J[0, 2, i] = Js[0, 2, i] + (w0 * d1 - w1 * d0)
        for i in range(own, nc):
            if work[i, W_TYPE] == TRANSLATION:
                for a in range(3):
                    J[0, a, i] = 1.0 if a == work[i, W_DIRECTION] else 0.0
            else:
                d0 = P[0, 0] - work[i, W_ORIGIN]
                d1 = P[1, 0] - work[i, W_ORIGIN + 1]
                d2 = P[2, 0] - work[i, W_ORIGIN + 2]
                w0, w1, w2 = J[1, 0, i], J[1, 1, i], J[1, 2, i]
                if work[i, W_TYPE] == TIP_COMBINATION:
                    has_tip = True
                    J[0, 0, i] += w1 * d2 - w2 * d1
                    J[0, 1, i] += w2 * d0 - w0 * d2
                    J[0, 2, i] += w0 * d1 - w1 * d0
                else:
                    J[0, 0, i] = w1 * d2 - w2 * d1
                    J[0, 1, i] = w2 * d0 - w0 * d2
                    J[0, 2, i] = w0 * d1 - w1 * d0
        if chain_order < PRODUCTS:
            continue
        if with_products and chain_order == PRODUCTS and not has_tip and (ancf_tips is None
                                                                          or root_kind != LinkKind.ANCF_TIP):
            direct_products(table, k, x, v, P, J, nc, root_columns, products[k - first])
            continue
        for i in range(nc):
            for l in range(nc):
                if i < root_columns and l < root_columns:
                    continue  # below
                if (has_tip and work[i, W_TYPE] == TIP_COMBINATION and work[l, W_TYPE] == TIP_COMBINATION
                        and work[i, W_DIRECTION] == work[l, W_DIRECTION]):
                    continue  # the same FFR tip's columns: below
                if l <= i:
                    _cross_columns(J, 1, l, 1, i, H, 1, i, l, False)
                    _cross_columns(J, 1, l, 0, i, H, 0, i, l, False)
                else:
                    for a in range(3):
                        H[1, a, i, l] = 0.0
                    _cross_columns(J, 1, i, 0, l, H, 0, i, l, False)
        if ffr_tips is not None:
            if has_tip:
                tip_blocks(table, P, work, nc, H)
        if (free_links is not None or ancf_tips is not None) and root_columns > 0:
            # the first link's own columns among each other
            for i in range(root_columns):
                for l in range(root_columns):
                    for a in range(3):
                        H[1, a, i, l] = 0.0
                        H[0, a, i, l] = 0.0
            c0 = table.links[l0, COORD]
            dr0, dr1, dr2 = P[0, 0] - x[c0], P[1, 0] - x[c0 + 1], P[2, 0] - x[c0 + 2]
            if free_links is not None and root_kind == LinkKind.FREE:
                e0, e1, e2, e3 = x[c0 + 3], x[c0 + 4], x[c0 + 5], x[c0 + 6]
                s = e0 * e0 + e1 * e1 + e2 * e2 + e3 * e3
                for l in range(4):
                    # dE/de_l: E of the unit
                    u0, u1, u2, u3 = 1.0 * (l == 0), 1.0 * (l == 1), 1.0 * (l == 2), 1.0 * (l == 3)
                    el = x[c0 + 3 + l]
                    for i in range(4):
                        for a in range(3):
                            H[1, a, 3 + i, 3 + l] = (2.0 * _euler_rate_entry(u0, u1, u2, u3, a, i) / s
                                                     - 4.0 * el * _euler_rate_entry(e0, e1, e2, e3, a, i) / (s * s))
            elif ancf_tips is not None:  # ANCF_TIP: rotation columns r0' (3) and theta_1 (1)
                Fc = F[int(par[table.links[l0, PARAM], 0])]
                for i in range(3):  # d(A e_i)/du_b
                    for b in range(3):
                        o0, o1, o2 = _ancf_rate_derivative(Fc[0, 0], Fc[1, 0], Fc[2, 0], tau0, tau1, tau2, slope_length,
                                                           i, b)
                        H[1, 0, 3 + i, 3 + b], H[1, 1, 3 + i, 3 + b], H[1, 2, 3 + i, 3 + b] = o0, o1, o2
                tau = (tau0, tau1, tau2)
                for b in range(3):  # d tau / d u_b
                    for a in range(3):
                        H[1, a, 6, 3 + b] = ((1.0 if a == b else 0.0) - tau[a] * tau[b]) / slope_length
            # Hr of the first link's rotations: dHw x (r - r_root) + Jw_i x Jr_l
            for i in range(3, 7):
                for l in range(3, 7):
                    h0, h1, h2 = H[1, 0, i, l], H[1, 1, i, l], H[1, 2, i, l]
                    H[0, 0, i, l] = h1 * dr2 - h2 * dr1
                    H[0, 1, i, l] = h2 * dr0 - h0 * dr2
                    H[0, 2, i, l] = h0 * dr1 - h1 * dr0
                    _cross_columns(J, 1, i, 0, l, H, 0, i, l, True)
        if with_products:
            contracted_products(H[0], H[1], table.columns[table.column_start[k]:table.column_start[k + 1]], v,
                                products[k - first])


@njit(cache=True, inline="always")
def evaluate_chains(table, x, F, order):
    """Every chain's kinematics at the coordinates x (charts F) into the table's pose, jac and
    hess: once per evaluation of the system's functions of the state alone (powers, energies,
    momenta, tips: ``order`` 1, the poses and Jacobians), before its parts read them
    (:func:`chain_state`); ``order`` 2: the derivatives hess too of every chain the equations
    read beyond its Jacobians (:attr:`ChainTable.orders` PRODUCTS or HESSIANS: the controllers'
    inputs). No velocity products (:func:`evaluate_motion`: the equations'). A chain evaluated to
    a lower order leaves the rest as it was. Inlined into its callers, which call
    :func:`chain_kinematics_into` once for all chains with the table's flags of the link kinds it
    holds (:class:`ChainTable`) as arguments: numba compiles the kinematics of those kinds only;
    ``order`` as an int64 and the first chain as np.int64(0), not the literals that the callers
    write: numba compiles a function once more for every literal argument that a compiled caller
    passes (the powers and measures pass 1)."""
    level = np.int64(HESSIANS if order >= 2 else POSE)
    chain_kinematics_into(table, np.int64(0), table.orders.shape[0], x, F, level, table.orders, table.pose,
                          table.jac, table.hess, table.work, table.free_links, table.ancf_tips, table.ffr_tips, x,
                          table.products, x.shape[0] < 0)


@njit(cache=True, inline="always")
def evaluate_motion(table, x, v, F, hessians):
    """Every chain's kinematics at the coordinates x and rates v (charts F), as the system's
    equations read them (:attr:`ChainTable.orders`): the pose and Jacobians of every chain, the
    velocity products (table.products) of the chains marked PRODUCTS (the FFR beams' and the rigid
    bodies' frames: their accelerations, :func:`hubbeam.system.frame_motions.frame_motion`) and
    the derivatives hess and velocity products of those marked HESSIANS (the ANCF clamps' roots,
    the controllers' inputs); with ``hessians`` (statics and modes: the exact load stiffness) the
    derivatives of every chain marked PRODUCTS too. The velocity products of a chain of a free
    body and screws are summed in one pass over its columns, without its derivatives (case M's
    free bus, three of its five frames: 1.0 us to Hessians, measured by
    ``benchmarks/bus_cost.py``). Inlined, as :func:`evaluate_chains`."""
    level = np.int64(HESSIANS if hessians else PRODUCTS)
    chain_kinematics_into(table, np.int64(0), table.orders.shape[0], x, F, level, table.orders, table.pose,
                          table.jac, table.hess, table.work, table.free_links, table.ancf_tips, table.ffr_tips, v,
                          table.products, v.shape[0] >= 0)


@njit(cache=True, inline="always")
def chain_state(table, k):
    """(columns, r, R, Jr, Jw, Hr, Hw) of chain k as :func:`evaluate_chains` left them (views of
    the table's arrays: the chain's coordinate columns' x indices, its origin (m) and axes, the
    Jacobians (3, nc) and their derivatives (3, nc, nc))."""
    nc = table.column_start[k + 1] - table.column_start[k]
    P = table.pose[k]
    J = table.jac[k]
    H = table.hess[k]
    return (table.columns[table.column_start[k]:table.column_start[k + 1]], P[:, 0], P[:, 1:4], J[0, :, :nc],
            J[1, :, :nc], H[0, :, :nc, :nc], H[1, :, :nc, :nc])


@njit(cache=True, inline="always")
def chain_products(table, k):
    """The velocity products (h_r, h_w) of chain k (2, 3) as :func:`evaluate_motion` left them (a
    view of the table's)."""
    return table.products[k]


def chain_pose(table: ChainTable, k: int, x, F=None, order: int = 1):
    """(r, R, Jr, Jw, Hr, Hw) of chain k at x (Python front end; Hr, Hw zero unless ``order`` is
    2). ``F``: the charts (n, 3, 3) of ANCF tips (default none). The chain is evaluated into
    arrays of its own by the equations' own compiled :func:`chain_kinematics_into` (the same
    types as theirs), so that a run compiles no second copy of the kinematics for its Python
    front ends."""
    nc = table.width(k)
    pose, jac, hess = np.zeros((1,) + table.pose.shape[1:]), np.zeros((1,) + table.jac.shape[1:]), \
        np.zeros((1,) + table.hess.shape[1:])
    F = np.zeros((1, 3, 3)) if F is None else np.ascontiguousarray(F, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    chain_kinematics_into(table, k, k + 1, x, F, HESSIANS if int(order) >= 2 else POSE,
                          np.full(1, HESSIANS, dtype=np.int64), pose, jac, hess, np.zeros_like(table.work),
                          table.free_links, table.ancf_tips, table.ffr_tips, x, np.zeros((1, 2, 3)), False)
    P, J, H = pose[0], jac[0], hess[0]
    return (P[:, 0].copy(), P[:, 1:4].copy(), J[0, :, :nc].copy(), J[1, :, :nc].copy(), H[0, :, :nc, :nc].copy(),
            H[1, :, :nc, :nc].copy())
