"""Clamp of an ANCF beam root to its frame (paper Eqs. 73-75, completed for any frame).

Eq. 73 as printed fixes five of the six freedoms of a rigid connection (the root
position, k_h . i_b = 0 and j_h . j_b = cos beta), and its twist equation has a zero
derivative at beta = 0 and two roots (+-beta). hubbeam clamps instead with six equations
that are linear in the beam coordinates and have unit-size Jacobians. The root frame is a
chain of the system (:mod:`hubbeam.system.frames`: the base, the hub angle, a mount, joint
angles, a parent beam's tip, then the twist): its origin r and its section axes
R = [tau_c m_c n_c]; a_2, a_3 are the axis frame's normals (the section axes before the twist
beta, R Rx(beta)):

    Phi_0..2 = r0(0) - r                      root position
    Phi_3    = a_2 . r0'(0)                   root tangent along the axis tau_c ...
    Phi_4    = a_3 . r0'(0)                   ... (two equations)
    Phi_5    = theta_1(0) - delta(R)          twist: the root section is R

while the root stretch |r0'(0)| and twist rate theta_1'(0) stay free. delta(R) is the chart
angle of the section frame R (tau = tau_c); turning R at the angular velocity w changes it at

    delta'(w) = w . tau + d . (w - tau (tau . w)) / (1 + d . tau)

(the chart's twist rate for a section turning at w; d the chart's director). With the
frame's velocity Jacobians Jr, Jw and their derivatives Hr, Hw
(:func:`~hubbeam.system.frames.chain_kinematics`) every first and second derivative of the
six equations with respect to the frame's coordinates follows (tests check them against
finite differences). The drive of a prescribed or fixed hub, theta - theta_p(t) = 0 (Eq. 82),
is the hub's constraint, not the clamp's.

Columns of the clamp's Jacobian and Hessian: c = [the chain's nc coordinate columns, r0 (3),
r0' (3), theta_1] at the root.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from hubbeam.elements.ancf.frame import section_frame
from hubbeam.system.assembly import add_entry

#: the root node's coordinates the clamp involves: r0 (3), r0' (3), theta_1
ROOT_COORDINATES = 7


@njit(cache=True)
def section_chart_angle(R, F, near=math.nan):
    """delta(R): theta_1 of the section frame R (columns tau, m, n; global) in chart F (the
    branch nearest ``near``; the principal one for nan)."""
    tau = np.empty(3)
    for i in range(3):
        tau[i] = F[0, i] * R[0, 0] + F[1, i] * R[1, 0] + F[2, i] * R[2, 0]
    _, m0, n0 = section_frame(tau, 0.0)
    cm = cn = 0.0
    for i in range(3):
        for k in range(3):
            cm += R[i, 1] * F[i, k] * m0[k]
            cn += R[i, 1] * F[i, k] * n0[k]
    delta = math.atan2(cn, cm)
    if not math.isnan(near):
        delta += 2.0 * math.pi * math.floor((near - delta) / (2.0 * math.pi) + 0.5)
    return delta


@njit(cache=True)
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True)
def _cross(a, b, out):
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@njit(cache=True)
def _chart_rate(w, tau, d):
    """delta'(w) of the module docstring."""
    dt = _dot(d, tau)
    return _dot(w, tau) + (_dot(d, w) - dt * _dot(tau, w)) / (1.0 + dt)


@njit(cache=True)
def _chart_rate_along_tau(w, tau, d, t):
    """d delta'(w) / d tau along t (w fixed)."""
    dt = _dot(d, tau)
    den = 1.0 + dt
    dtt = _dot(d, t)
    return (_dot(w, t) + (-dtt * _dot(tau, w) - dt * _dot(t, w)) / den
            - (_dot(d, w) - dt * _dot(tau, w)) * dtt / (den * den))


@njit(cache=True)
def frame_clamp(r, R, Jr, Jw, Hr, Hw, root, F, twist, lam, order, phi, jac, hess):
    """Phi (6), dPhi/dc (6 x (nc + 7)) and, with ``order`` 2, sum_i lambda_i d2 Phi_i / dc2
    ((nc + 7) square) of the clamp of an ANCF root (``root`` = [r0, r0', theta_1]) to the frame
    (r, R) of a chain with Jacobians Jr, Jw (3, nc) and derivatives Hr, Hw (3, nc, nc); ``twist``
    (rad) turns the section axes R back to the axis frame. Written into phi, jac, hess."""
    nc = Jr.shape[1]
    n = nc + ROOT_COORDINATES
    c, s = math.cos(twist), math.sin(twist)
    a2 = np.empty(3)
    a3 = np.empty(3)
    tau = np.empty(3)
    d = np.empty(3)
    for i in range(3):
        a2[i] = c * R[i, 1] + s * R[i, 2]
        a3[i] = -s * R[i, 1] + c * R[i, 2]
        tau[i] = R[i, 0]
        d[i] = F[i, 0]
    u = root[3:6]
    for i in range(6):
        for j in range(n):
            jac[i, j] = 0.0
    for i in range(3):
        phi[i] = root[i] - r[i]
        jac[i, nc + i] = 1.0
        for j in range(nc):
            jac[i, j] = -Jr[i, j]
    phi[3] = _dot(a2, u)
    phi[4] = _dot(a3, u)
    phi[5] = root[6] - section_chart_angle(R, F, root[6])
    jac[5, nc + 6] = 1.0
    t = np.empty(3)
    for j in range(nc):
        w = Jw[:, j]
        _cross(w, a2, t)
        jac[3, j] = _dot(t, u)
        _cross(w, a3, t)
        jac[4, j] = _dot(t, u)
        jac[5, j] = -_chart_rate(w, tau, d)
    for i in range(3):
        jac[3, nc + 3 + i] = a2[i]
        jac[4, nc + 3 + i] = a3[i]
    if order < 2:
        return
    for i in range(n):
        for j in range(n):
            hess[i, j] = 0.0
    la2 = np.empty(3)  # lambda_3 a_2 + lambda_4 a_3: the tangent equations together
    for i in range(3):
        la2[i] = lam[3] * a2[i] + lam[4] * a3[i]
    t2 = np.empty(3)
    t3 = np.empty(3)
    for i in range(nc):
        wi = Jw[:, i]
        # d2 Phi_tangent / dc_i du = Jw_i x a
        _cross(wi, la2, t)
        for k in range(3):
            hess[i, nc + 3 + k] += t[k]
            hess[nc + 3 + k, i] += t[k]
        for l in range(nc):
            wl = Jw[:, l]
            val = 0.0
            for a in range(3):  # position: -Hr
                val -= lam[a] * Hr[a, i, l]
            # tangent: (Hw_il x a + Jw_i x (Jw_l x a)) . u
            _cross(Hw[:, i, l], la2, t)
            _cross(wl, la2, t2)
            _cross(wi, t2, t3)
            val += _dot(t, u) + _dot(t3, u)
            # twist: -(delta'(Hw_il) + d delta'(Jw_i)/d tau . (Jw_l x tau))
            _cross(wl, tau, t2)
            val -= lam[5] * (_chart_rate(Hw[:, i, l], tau, d) + _chart_rate_along_tau(wi, tau, d, t2))
            hess[i, l] += val


def frame_clamp_equations(r, R, Jr, Jw, Hr, Hw, root, F, twist, lam=None, order: int = 2):
    """(Phi, Jacobian, lambda-weighted Hessian) of :func:`frame_clamp` (Python front end)."""
    nc = Jr.shape[1]
    phi, jac, hess = np.empty(6), np.empty((6, nc + 7)), np.empty((nc + 7, nc + 7))
    lam = np.zeros(6) if lam is None else np.asarray(lam, dtype=float)
    frame_clamp(*(_strided(a) for a in (r, R, Jr, Jw, Hr, Hw)), np.ascontiguousarray(root, dtype=float),
                np.ascontiguousarray(F, dtype=float), float(twist), lam, order, phi, jac, hess)
    return phi, jac, hess


def _strided(a):
    """A copy of ``a`` (as floats) in a view with every stride doubled, which numba types as
    not contiguous (layout "A"), as the views of the chains' state
    (:func:`hubbeam.system.frames.chain_state`) that the compiled equations pass: so that a run
    compiles :func:`frame_clamp` once, not once more for contiguous arrays (~1 s)."""
    a = np.asarray(a, dtype=float)
    buffer = np.zeros(a.shape + (2,))
    buffer[..., 0] = a
    return buffer[..., 0]


@njit(cache=True)
def clamp_residual(lam_k, phi, jac, nc, scale, zl, l0, rows, res, coef_k):
    """A clamp's part of the residual: coef_k Phi_c^T lambda added to the rows of the clamp's
    columns (``rows[j]``: the z row of column j, the nc chain columns first, then the 7 root
    coordinates) and scale Phi into its multiplier rows of ``res``."""
    n = nc + ROOT_COORDINATES
    for j in range(n):
        acc_j = 0.0
        for i in range(6):
            acc_j += jac[i, j] * lam_k[i]
        res[rows[j]] += coef_k * acc_j
    for i in range(6):
        res[zl[l0 + i]] = scale * phi[i]


@njit(cache=True)
def add_clamp_matrix(ab, brow, bcol, bb, ku, jac, hess, rows, nc, scale, coef_k, zl, l0):
    """scale times a clamp's Jacobian in its multiplier rows and, transposed, in their columns,
    and coef_k times its multiplier-weighted Hessian on its columns (z rows ``rows``)."""
    n = nc + ROOT_COORDINATES
    for i in range(6):
        ri = zl[l0 + i]
        for j in range(n):
            value = scale * jac[i, j]
            if value != 0.0:
                add_entry(ab, brow, bcol, bb, ku, ri, rows[j], value)
                add_entry(ab, brow, bcol, bb, ku, rows[j], ri, value)
    if coef_k == 0.0:
        return
    for i in range(n):
        for j in range(n):
            value = hess[i, j]
            if value != 0.0:
                add_entry(ab, brow, bcol, bb, ku, rows[i], rows[j], coef_k * value)
