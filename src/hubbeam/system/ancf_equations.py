"""Compiled equations of motion of the hub with an ANCF beam (paper Eq. 77), residual and
band-stored Newton matrix in one call.

The unknowns of a Newton iteration are z = [theta, mu, q] (hub angle, scaled
multipliers mu = coef_k lambda / scale, ANCF coordinates); with this order the matrix is
banded with half-bandwidth max(15, m + 8) (m constraints). The terms come from the
element kernels of :mod:`hubbeam.elements.ancf.kernels` (one per physical term), the
clamp of :mod:`hubbeam.system.clamp`, the tip loads of :mod:`hubbeam.system.loads` and
the drive of :mod:`hubbeam.system.hub`; this module only adds them up.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.elements.ancf import kernels
from hubbeam.system.assembly import add_element_blocks_banded
from hubbeam.system.clamp import clamp_equations
from hubbeam.system.hub import drive_values
from hubbeam.system.loads import tip_moment_terms

NODE_DOFS = kernels.NODE_DOFS
#: hub motions inside compiled code
FREE, PRESCRIBED, FIXED = 0, 1, 2
#: below this value of 1 + d.tau a beam tangent is at the chart's singular direction
CHART_SINGULAR = 1e-6


class AncfModel(NamedTuple):
    """Everything constant that the compiled equations need (SI units)."""

    S: np.ndarray  # Hermite functions at the Gauss points (ng, 4), and derivatives (1/m, 1/m^2)
    dS: np.ndarray
    d2S: np.ndarray
    w: np.ndarray  # Gauss weights on [0, 1]
    length: float  # element length (m)
    stiffness: np.ndarray  # EA, GJ_t, EI_y, EI_z (N, N m^2)
    trans_mass: np.ndarray  # translational element mass (16, 16)
    inertia: np.ndarray  # rho (I_y + I_z), rho I_y, rho I_z (kg m)
    width: float  # frontal width of the drag (m)
    drag_linear: float  # c1 of Eq. 37 (N s / m^3)
    drag_quadratic: float  # c2 (N s^2 / m^4)
    gravity_load: np.ndarray  # generalized gravity force on q (N)
    tip_force: np.ndarray  # N
    tip_moment: np.ndarray  # N m
    radius: float  # hub radius (m)
    twist: float  # beta (rad)
    hub_inertia: float  # kg m^2
    hub_torque: float  # N m
    motion: int  # FREE, PRESCRIBED or FIXED
    drive: tuple  # (profile code, omega_s, T, t1) of hubbeam.system.hub.drive_values
    bandwidth: int


@njit(cache=True)
def n_constraints(model):
    return 6 if model.motion == FREE else 7


@njit(cache=True)
def drive_angle(model, t):
    """theta_p(t) of the driving constraint (0 for a fixed hub, unused for a free one)."""
    if model.motion == PRESCRIBED:
        code, w, T, t1 = model.drive
        return drive_values(code, w, T, t1, t)[0]
    return 0.0


@njit(cache=True)
def equations_of_motion(model, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, want_matrix, res, ab):
    """Scaled residual and (when ``want_matrix``) Newton matrix of the equations of motion.

    Force rows: coef_k (M(q) acc + f_int - Q_ext - Q_v - Q_d + Phi_x^T lambda) on q, and
    coef_k (J theta'' - T + Phi_theta^T lambda) on theta; constraint rows: scale Phi(x, t).
    The matrix coef_m M + coef_c C + coef_k (K - dQ/dq + lambda . d2 Phi) on z, with the
    constraint Jacobian scaled by ``scale`` in its rows and columns, is written into ``ab``
    (LAPACK gbtrf layout, kl = ku = model.bandwidth, A[i, j] at ab[2 bw + i - j, j]). The
    small velocity derivative of the rotary-inertia force Q_v and the q-derivative of
    M(q) acc are left out (they slow Newton slightly and never change the answer).

    Returns (chart margin min(1 + d.tau) over the Gauss points, dissipated power W). A margin
    at or below :data:`CHART_SINGULAR` means the residual is not valid.
    """
    S, dS, d2S, w, le = model.S, model.dS, model.d2S, model.w, model.length
    nq = x.shape[0] - 1
    n_el = (nq - NODE_DOFS) // NODE_DOFS
    m = n_constraints(model)
    kq = 1 + m
    q = x[1:]
    qd = v[1:]
    blocks = np.zeros((n_el if want_matrix else 0, 16, 16))
    fq = np.empty(nq)
    _, margin = kernels.elastic_kernel(q, F, le, S, dS, d2S, w, model.stiffness, coef_k, fq, blocks)
    if not margin > CHART_SINGULAR:
        return margin, 0.0
    term = np.empty(nq)
    kernels.rotary_inertia_kernel(q, qd, acc[1:], F, le, S, dS, w, model.inertia, coef_m, term, blocks)
    for j in range(nq):
        fq[j] -= term[j]  # -(Q_v - M_rot acc)
    power = kernels.drag_kernel(qd, le, S, w, model.width, model.drag_linear, model.drag_quadratic, coef_c,
                                term, blocks)
    for j in range(nq):
        fq[j] -= term[j]
    kernels.translational_mass_product(model.trans_mass, acc[1:], fq)
    load = np.empty(nq)
    tip_jacobian = np.empty((4, 3))
    applied_load(model, q, F, 1.0, load, tip_jacobian)
    for j in range(nq):
        fq[j] -= load[j]
    phi = np.empty(m)
    jac = np.empty((m, 8))
    hess = np.empty((8, 8))
    clamp_equations(x[0:8], model.radius, model.twist, F, m == 7, drive_angle(model, t), lam, phi, jac, hess)
    for j in range(7):
        acc_j = 0.0
        for i in range(m):
            acc_j += jac[i, 1 + j] * lam[i]
        fq[j] += acc_j
    hub_row = model.hub_inertia * acc[0] - model.hub_torque
    for i in range(m):
        hub_row += jac[i, 0] * lam[i]
    res[0] = coef_k * hub_row
    for i in range(m):
        res[1 + i] = scale * phi[i]
    for j in range(nq):
        res[kq + j] = coef_k * fq[j]
    if not want_matrix:
        return margin, power

    kernels.add_translational_mass(model.trans_mass, n_el, coef_m, blocks)
    assemble_newton_matrix(ab, blocks, kq, 2 * model.bandwidth, tip_jacobian, jac, scale, hess, coef_k,
                           coef_m * model.hub_inertia)
    return margin, power


@njit(cache=True)
def applied_load(model, q, F, factor, Q, tip_jacobian):
    """Q = ``factor`` times the applied generalized force on q: gravity (Eq. 32), the tip force
    and the tip moment (:func:`hubbeam.system.loads.tip_moment_terms`), and tip_jacobian
    (4 x 3) = ``factor`` d Q / d r0'(L) of the moment on the tip's (r0', theta_1) rows (zero
    without a moment)."""
    nq = q.shape[0]
    tip = nq - NODE_DOFS
    for j in range(nq):
        Q[j] = factor * model.gravity_load[j]
    for k in range(3):
        Q[tip + k] += factor * model.tip_force[k]
    tip_jacobian[:, :] = 0.0
    moment = model.tip_moment
    if moment[0] == 0.0 and moment[1] == 0.0 and moment[2] == 0.0:
        return
    tQ = np.empty(4)
    tip_moment_terms(q[tip + 3 : tip + 6], moment, F, tQ, tip_jacobian)
    for k in range(4):
        Q[tip + 3 + k] += factor * tQ[k]
        for j in range(3):
            tip_jacobian[k, j] *= factor


@njit(cache=True)
def assemble_newton_matrix(ab, blocks, kq, ku, tip_jacobian, jac, scale, hess, coef_k, theta_diag):
    """The band-stored Newton matrix on z = [theta, mu, q] (q from z-index kq), written into
    ``ab`` (LAPACK gbtrf layout, A[i, j] at ab[ku + i - j, j]): the element blocks (n_el,
    16, 16), minus coef_k ``tip_jacobian`` (4 x 3) on the tip's (r0', theta_1) rows and r0'
    columns, ``scale`` times the constraint Jacobian ``jac`` (m x 8 on the clamp coordinates
    [theta, q_root[0:7]]) in the multiplier rows 1 .. m and, transposed, in their columns,
    coef_k ``hess`` (lambda . d2 Phi, 8 x 8) on the clamp coordinates and ``theta_diag`` on
    theta-theta. Used by the dynamics and the statics alike."""
    ab[:, :] = 0.0
    add_element_blocks_banded(ab, blocks, kq, ku, 1.0)
    tip = ab.shape[1] - NODE_DOFS  # z-index of the tip node
    for i in range(4):
        for j in range(3):
            r = tip + 3 + i
            c = tip + 3 + j
            ab[ku + r - c, c] -= coef_k * tip_jacobian[i, j]
    # clamp coordinates c = [theta, q_root[0:7]] sit at z-indices 0 and kq .. kq + 6
    m = jac.shape[0]
    for a in range(8):
        ca = 0 if a == 0 else kq + a - 1
        for i in range(m):
            ab[ku + (1 + i) - ca, ca] += scale * jac[i, a]
            ab[ku + ca - (1 + i), 1 + i] += scale * jac[i, a]
        for b in range(8):
            cb = 0 if b == 0 else kq + b - 1
            ab[ku + ca - cb, cb] += coef_k * hess[a, b]
    ab[ku, 0] += theta_diag


@njit(cache=True)
def dissipated_power(model, v):
    """Power of the drag of Eq. 37 at velocities v (W, >= 0)."""
    qd = v[1:]
    force = np.empty(qd.shape[0])
    return kernels.drag_kernel(qd, model.length, model.S, model.w, model.width, model.drag_linear,
                               model.drag_quadratic, 0.0, force, np.empty((0, 16, 16)))
