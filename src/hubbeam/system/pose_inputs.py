"""Controller inputs that are functions of the frames' poses: a beam's tip deflection and the
rotation vector of a moving base, each with its exact derivatives (compiled; the forms
``TIP_DEFLECTION`` and ``BASE_ROTATION`` of :mod:`hubbeam.system.controller_inputs`).

Both are functions u(x) of the positions alone; the ``_rate`` of one is u' = g . v (g = du/dx,
v = dx/dt in the step's charts), with du'/dv = g and du'/dx_m = d(g . v)/dx_m at fixed v.

**Tip deflection** (the ``tip_deflection`` sensor, :func:`hubbeam.system.frame_motions.displacement_in_reference`):
component j of the tip centroid's displacement from its undeformed place, along the axes Q of
the beam's reference frame (its own hub frame; on a parent beam, the parent's tip frame),

    u = q_j . w,   q_j = Q e_j,   w = p_tip - r_a - L R_a e_1

(r_a, R_a the beam's root section frame, L its length). An ANCF beam's tip p_tip is its last
node's position coordinates; an FFR beam's is r_a + R_a ((L, 0, 0) + N_L p) (N_L its tip
displacement rows over the elastic coordinates p), so w = R_a N_L p. With the chains'
Jacobians (Jr, Jw: dr/dx_m = Jr_m, dR s/dx_m = Jw_m x R s) and their derivatives
(Hr, Hw[:, l, m] = dJ_l/dx_m) of :mod:`hubbeam.system.frames`:

    du/dx_m = (Jwb_m x q_j) . w + q_j . W_m          (W_m = dw/dx_m)
    u'      = (w_b x q_j) . w + q_j . w'              (w_b = Jwb v, the reference frame's rate)
    du'/dx_m = (Om_b,m x q_j + w_b x (Jwb_m x q_j)) . w + (w_b x q_j) . W_m
               + (Jwb_m x q_j) . w' + q_j . dw'/dx_m   (Om_m = sum_l Hw[:, l, m] v_l)

the reference frame's terms on its chain's columns m; for ANCF, W_m = e_c (the tip's position
column c) - Jra_m - L Jwa_m x tau_a, w' = v_tip - Jra v - L w_a x tau_a, dw'/dx_m = -sum_l
Hra[:, l, m] v_l - L (Om_a,m x tau_a + w_a x (Jwa_m x tau_a)); for FFR, W_m = Jwa_m x w (root
chain) or R_a N_f (elastic column f), w' = w_a x w + R_a N p', dw'/dx_m = Om_a,m x w +
w_a x (Jwa_m x w) + Jwa_m x R_a N p' (root chain) or w_a x R_a N_f (column f).

**Base rotation** (the ``base_rotation`` sensor, :func:`hubbeam.system.rotations.rotation_vector`):
the rotation vector (rad, |phi| <= pi, global axes) of the base's Euler parameters e (4,
not necessarily of unit norm): with s e = (a, b) (s = +-1 making a >= 0),

    phi = G(|b|^2, a) b,   G(q, a) = 2 atan2(sqrt q, a) / sqrt q

(G(0, a) = 2 / a), its gradient and Hessian in e written out below with G's partial
derivatives (a series in z = |b| / a where their closed forms cancel). Its rate is
T(phi)^-1 omega (omega the base's angular velocity, global): dphi/de annihilates e itself.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from hubbeam.system.frames import chain_state
from hubbeam.system.rotations import cross3

#: columns of a row of the tip table: root chain, reference chain, component, where the tip's
#: coordinates start in x, and nf (0: an ANCF beam, its tip's 3 position columns; else an FFR
#: beam's nf elastic coordinates)
TIP_ROOT, TIP_REFERENCE, TIP_PART, TIP_START, TIP_NF = range(5)
#: below this z = |b| / a the rotation vector's G-derivatives are summed as their series
SERIES_BELOW = 0.3
#: terms of those series (z^(2 SERIES_TERMS) < 1e-17 at z = SERIES_BELOW)
SERIES_TERMS = 24


def tip_columns(chains, root: int, reference: int, tip: list[int]) -> list[int]:
    """The x columns a tip deflection reads, each once: the root chain's, then the reference
    chain's not among them, then the tip's own (``chains``: the system's ChainTable)."""
    out: list[int] = []
    for k in (root, reference):
        for c in chains.columns[chains.column_start[k]:chains.column_start[k + 1]].tolist():
            if c not in out:
                out.append(int(c))
    return out + [int(c) for c in tip if c not in out]


@njit(cache=True)
def _places(ucols, chain_cols):
    """Where each of ``chain_cols`` sits in ``ucols``."""
    out = np.empty(chain_cols.shape[0], dtype=np.int64)
    for i in range(chain_cols.shape[0]):
        for k in range(ucols.shape[0]):
            if ucols[k] == chain_cols[i]:
                out[i] = k
                break
    return out


@njit(cache=True)
def _frame_rates(cols, Jw, Hw, v):
    """(w (3,), Om (3, nc)): the frame's angular velocity Jw v and Om[:, m] = sum_l Hw[:, l, m] v_l."""
    nc = cols.shape[0]
    w = np.zeros(3)
    Om = np.zeros((3, nc))
    for l in range(nc):
        vl = v[cols[l]]
        for a in range(3):
            w[a] += Jw[a, l] * vl
            for m in range(nc):
                Om[a, m] += Hw[a, l, m] * vl
    return w, Om


@njit(cache=True)
def tip_deflection_input(chains, tip, rows, length, ucols, x, v, rate, dx, dv):
    """u (m, or m/s for its ``rate``) of a tip deflection input (``tip``: its row of the tip
    table, ``rows`` (3, nf) an FFR beam's N_L, ``length`` L (m)), and du/dx, du/dv (or those
    of the rate) into dx, dv over the columns ``ucols`` (:func:`tip_columns`); the chains as
    :func:`~hubbeam.system.frames.evaluate_chains` left them (to order 2 for a rate)."""
    ca, ra, Ra, Jra, Jwa, Hra, Hwa = chain_state(chains, tip[TIP_ROOT])
    cb, _, Rb, _, Jwb, _, Hwb = chain_state(chains, tip[TIP_REFERENCE])
    j, start, nf = tip[TIP_PART], tip[TIP_START], tip[TIP_NF]
    n = ucols.shape[0]
    ia, ib = _places(ucols, ca), _places(ucols, cb)
    na, nb = ca.shape[0], cb.shape[0]
    it = n - (nf if nf > 0 else 3)  # the tip's own columns come last
    q0, q1, q2 = Rb[0, j], Rb[1, j], Rb[2, j]
    wa, Oa = _frame_rates(ca, Jwa, Hwa, v)
    W = np.zeros((3, n))  # dw/dx
    Wd = np.zeros((3, n))  # dw'/dx
    w, wd = np.zeros(3), np.zeros(3)
    if nf == 0:  # ANCF: w = p_tip - r_a - L tau_a
        t0, t1, t2 = Ra[0, 0], Ra[1, 0], Ra[2, 0]
        c0, c1, c2 = cross3(wa[0], wa[1], wa[2], t0, t1, t2)
        for a in range(3):
            w[a] = x[start + a] - ra[a] - length * Ra[a, 0]
            W[a, it + a] += 1.0
            s = 0.0
            for l in range(na):
                s += Jra[a, l] * v[ca[l]]
            wd[a] = v[start + a] - s - length * (c0, c1, c2)[a]
        for m in range(na):
            e0, e1, e2 = cross3(Jwa[0, m], Jwa[1, m], Jwa[2, m], t0, t1, t2)
            f0, f1, f2 = cross3(Oa[0, m], Oa[1, m], Oa[2, m], t0, t1, t2)
            g0, g1, g2 = cross3(wa[0], wa[1], wa[2], e0, e1, e2)
            col = ia[m]
            for a in range(3):
                hr = 0.0
                for l in range(na):
                    hr += Hra[a, l, m] * v[ca[l]]
                W[a, col] += -Jra[a, m] - length * (e0, e1, e2)[a]
                Wd[a, col] += -hr - length * ((f0, f1, f2)[a] + (g0, g1, g2)[a])
    else:  # FFR: w = R_a N p
        s, sd = np.zeros(3), np.zeros(3)  # N p, N p' (body axes)
        for f in range(nf):
            for a in range(3):
                s[a] += rows[a, f] * x[start + f]
                sd[a] += rows[a, f] * v[start + f]
        pd = np.zeros(3)  # R_a N p'
        for a in range(3):
            w[a] = Ra[a, 0] * s[0] + Ra[a, 1] * s[1] + Ra[a, 2] * s[2]
            pd[a] = Ra[a, 0] * sd[0] + Ra[a, 1] * sd[1] + Ra[a, 2] * sd[2]
        c0, c1, c2 = cross3(wa[0], wa[1], wa[2], w[0], w[1], w[2])
        wd[0], wd[1], wd[2] = c0 + pd[0], c1 + pd[1], c2 + pd[2]
        for m in range(na):
            e0, e1, e2 = cross3(Jwa[0, m], Jwa[1, m], Jwa[2, m], w[0], w[1], w[2])
            f0, f1, f2 = cross3(Oa[0, m], Oa[1, m], Oa[2, m], w[0], w[1], w[2])
            g0, g1, g2 = cross3(wa[0], wa[1], wa[2], e0, e1, e2)
            h0, h1, h2 = cross3(Jwa[0, m], Jwa[1, m], Jwa[2, m], pd[0], pd[1], pd[2])
            col = ia[m]
            W[0, col] += e0
            W[1, col] += e1
            W[2, col] += e2
            Wd[0, col] += f0 + g0 + h0
            Wd[1, col] += f1 + g1 + h1
            Wd[2, col] += f2 + g2 + h2
        for f in range(nf):
            n0 = Ra[0, 0] * rows[0, f] + Ra[0, 1] * rows[1, f] + Ra[0, 2] * rows[2, f]
            n1 = Ra[1, 0] * rows[0, f] + Ra[1, 1] * rows[1, f] + Ra[1, 2] * rows[2, f]
            n2 = Ra[2, 0] * rows[0, f] + Ra[2, 1] * rows[1, f] + Ra[2, 2] * rows[2, f]
            g0, g1, g2 = cross3(wa[0], wa[1], wa[2], n0, n1, n2)
            W[0, it + f] += n0
            W[1, it + f] += n1
            W[2, it + f] += n2
            Wd[0, it + f] += g0
            Wd[1, it + f] += g1
            Wd[2, it + f] += g2
    # u = q . w and its derivatives: the reference frame's turning, then w's
    for k in range(n):
        dx[k] = q0 * W[0, k] + q1 * W[1, k] + q2 * W[2, k]
        dv[k] = 0.0
    for m in range(nb):
        e0, e1, e2 = cross3(Jwb[0, m], Jwb[1, m], Jwb[2, m], q0, q1, q2)
        dx[ib[m]] += e0 * w[0] + e1 * w[1] + e2 * w[2]
    u = q0 * w[0] + q1 * w[1] + q2 * w[2]
    if not rate:
        return u
    wb, Ob = _frame_rates(cb, Jwb, Hwb, v)
    r0, r1, r2 = cross3(wb[0], wb[1], wb[2], q0, q1, q2)  # q_j'
    ud = r0 * w[0] + r1 * w[1] + r2 * w[2] + q0 * wd[0] + q1 * wd[1] + q2 * wd[2]
    for k in range(n):
        dv[k] = dx[k]  # du'/dv = du/dx
        dx[k] = r0 * W[0, k] + r1 * W[1, k] + r2 * W[2, k] + q0 * Wd[0, k] + q1 * Wd[1, k] + q2 * Wd[2, k]
    for m in range(nb):
        e0, e1, e2 = cross3(Jwb[0, m], Jwb[1, m], Jwb[2, m], q0, q1, q2)  # dq/dx_m
        f0, f1, f2 = cross3(Ob[0, m], Ob[1, m], Ob[2, m], q0, q1, q2)
        g0, g1, g2 = cross3(wb[0], wb[1], wb[2], e0, e1, e2)
        dx[ib[m]] += ((f0 + g0) * w[0] + (f1 + g1) * w[1] + (f2 + g2) * w[2]
                      + e0 * wd[0] + e1 * wd[1] + e2 * wd[2])
    return ud


@njit(cache=True)
def _angle_factors(q, a):
    """(G, G_a, G_q, G_aa, G_qa, G_qq) of G(q, a) = 2 atan2(sqrt q, a) / sqrt q (a >= 0,
    q + a^2 > 0; module docstring)."""
    d = q + a * a
    G_a = -2.0 / d
    G_aa = 4.0 * a / (d * d)
    G_qa = 2.0 / (d * d)
    s = math.sqrt(q)
    if s < SERIES_BELOW * a:
        # G_q = a^-3 sum_n>=1 c_n z^(2n-2), c_n = (-1)^n 2n / (2n + 1); G_qq = a^-5 sum_n>=2 c_n (n - 1) z^(2n-4)
        z2 = q / (a * a)
        G, G_q, G_qq = 0.0, 0.0, 0.0
        for n in range(SERIES_TERMS, 0, -1):  # Horner, the small terms first
            c = (-1.0) ** n * 2.0 * n / (2.0 * n + 1.0)
            G_q = G_q * z2 + c
            if n >= 2:
                G_qq = G_qq * z2 + c * (n - 1)
            G = G * z2 + (-1.0) ** (n - 1) / (2.0 * n - 1.0)  # atan(z) / z
        return 2.0 * G / a, G_a, G_q / a ** 3, G_aa, G_qa, G_qq / a ** 5
    angle = math.atan2(s, a)
    N = a * s / d - angle
    return 2.0 * angle / s, G_a, N / (s * q), G_aa, G_qa, -a / (q * d * d) - 1.5 * N / (q * q * s)


@njit(cache=True)
def base_rotation_input(e, ed, i, rate, dx, dv):
    """Component i of the rotation vector (rad) of the Euler parameters e (4,), or its rate
    (rad/s) at e' = ``ed``, and du/de, du/de' into dx, dv (4,) (module docstring)."""
    sign = 1.0 if e[0] >= 0.0 else -1.0
    a = sign * e[0]
    b = np.array([sign * e[1], sign * e[2], sign * e[3]])
    q = b[0] * b[0] + b[1] * b[1] + b[2] * b[2]
    G, G_a, G_q, G_aa, G_qa, G_qq = _angle_factors(q, a)
    bi = b[i]
    grad = np.zeros(4)  # d phi_i / d(a, b), then times sign for e
    grad[0] = G_a * bi
    for k in range(3):
        grad[1 + k] = 2.0 * G_q * bi * b[k] + (G if k == i else 0.0)
    for k in range(4):
        dv[k] = 0.0
        dx[k] = sign * grad[k]
    if not rate:
        return G * bi
    u = 0.0
    for k in range(4):
        u += dx[k] * ed[k]
        dv[k] = dx[k]
    hess = np.zeros((4, 4))  # d2 phi_i / d(a, b)^2
    hess[0, 0] = G_aa * bi
    for k in range(3):
        hess[0, 1 + k] = hess[1 + k, 0] = 2.0 * G_qa * bi * b[k] + (G_a if k == i else 0.0)
        for m in range(3):
            h = 4.0 * G_qq * bi * b[k] * b[m]
            h += 2.0 * G_q * ((b[m] if k == i else 0.0) + (b[k] if m == i else 0.0) + (bi if k == m else 0.0))
            hess[1 + k, 1 + m] = h
    for k in range(4):  # d/de_k of (sign grad(sign e)) . e' = (hess e')_k
        s = 0.0
        for m in range(4):
            s += hess[k, m] * ed[m]
        dx[k] = s
    return u
