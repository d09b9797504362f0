"""Compiled equations of motion of a hub and its beams (paper Eq. 77), residual and Newton
matrix in one call, for any number of ANCF and FFR beams, tip bodies and hub laws.

The unknowns are placed by :class:`hubbeam.system.layout.Layout`: z = [theta, mu_drive,
(mu_clamp_k, q_k) for each beam]; lambda = scale mu / coef_k. The Newton matrix is
stored bordered (:class:`hubbeam.system.assembly.BorderedBandMatrix`): the border (theta
and the drive multiplier) as dense rows, columns and corner, the rest -- block-diagonal
over the beams, each block banded -- in LAPACK band storage.

The physical terms come from their own kernels and are only added up here: elastic forces,
rotary inertia, translational mass, drag (:mod:`hubbeam.elements.ancf.kernels`), gravity and
tip loads (:func:`applied_load`, :mod:`hubbeam.system.loads`), tip bodies
(:mod:`hubbeam.system.tip_body`), the clamp of each root (:mod:`hubbeam.system.clamp`), the
drive and the torque law of the hub (:mod:`hubbeam.system.laws`); for every FFR beam the
body terms of :mod:`hubbeam.elements.ffr.kernels` (a dense block inside the band) and its
linear Cardan-angle clamp (:mod:`hubbeam.system.ffr_part`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.elements.ancf import kernels
from hubbeam.elements.ancf.strain import strain_measures
from hubbeam.elements.ffr.kernels import (cardan, ffr_body_terms, ffr_dissipated_power, ffr_energies,
                                          ffr_load_stiffness)
from hubbeam.system.assembly import add_element_blocks_banded, add_entry
from hubbeam.system.clamp import clamp_equations
from hubbeam.system.laws import drive_values, torque_values
from hubbeam.system.layout import Layout
from hubbeam.system.loads import tip_moment_terms
from hubbeam.system.mount import axis_frame, beam_hub_frame
from hubbeam.system.tip_body import ancf_tip_body_terms, has_tip_body

NODE_DOFS = kernels.NODE_DOFS
#: the hub angle's place in x (the layout's)
THETA = Layout.theta
#: below this value of 1 + d.tau a beam tangent is at the chart's singular direction
CHART_SINGULAR = 1e-6
#: half-bandwidth of an ANCF beam block (16 x 16 element blocks; the clamp rows reach 12 ahead)
BANDWIDTH = 15


def bandwidth_for(ffr_dofs) -> int:
    """Half-bandwidth of the Newton matrix: an ANCF block's, or an FFR beam's whole block
    (its six clamp rows and 6 + nf coordinates) when wider."""
    return max([BANDWIDTH] + [11 + n for n in ffr_dofs])


#: dimensions of the per-beam arrays of :class:`hubbeam.elements.ffr.kernels.FfrArrays`
FFR_FIELD_NDIM = {"m": 0, "c0": 1, "Sbar": 2, "I0": 2, "J": 3, "II": 4, "Mff": 2, "K": 2, "EAl": 1,
                  "mean_stretch": 2, "mean_slope2": 3, "stiffening": 0, "C_struct": 2, "damped": 0,
                  "tip_force": 1, "tip_moment": 1, "tip_rows": 2, "tip_rotation_rows": 2, "length": 0, "N_pts": 3,
                  "x_pts": 1, "w_pts": 1, "width": 1}


class FfrStack(NamedTuple):
    """The FFR beams' constants (:func:`hubbeam.elements.ffr.kernels.pack`), one row per FFR
    beam, zero-padded to the largest beam (the kernels read the leading nf entries)."""

    index: np.ndarray  # int64 (nb,): the beam's place among all beams
    x0: np.ndarray  # int64 (nb,): where q_k starts in x
    lambda0: np.ndarray  # int64 (nb,): where its clamp multipliers start in lambda
    nf: np.ndarray  # int64 (nb,): elastic coordinates
    mount: np.ndarray  # (nb, 4) radius, twist, azimuth, precone
    m: np.ndarray
    c0: np.ndarray
    Sbar: np.ndarray
    I0: np.ndarray
    J: np.ndarray
    II: np.ndarray
    Mff: np.ndarray
    K: np.ndarray
    EAl: np.ndarray
    mean_stretch: np.ndarray
    mean_slope2: np.ndarray
    stiffening: np.ndarray
    C_struct: np.ndarray  # (nb, nf, nf) structural damping c K (N s)
    damped: np.ndarray
    tip_force: np.ndarray
    tip_moment: np.ndarray
    tip_rows: np.ndarray
    tip_rotation_rows: np.ndarray
    length: np.ndarray
    N_pts: np.ndarray
    x_pts: np.ndarray
    w_pts: np.ndarray
    width: np.ndarray


class SystemModel(NamedTuple):
    """Everything constant that the compiled equations need (SI units). Per-beam arrays
    have one row per ANCF beam; ``beam_index`` gives the beam's place among all beams (its
    chart in the chart array); ``beam_x0``/``beam_lambda0`` where its coordinates and clamp
    multipliers start in x and lambda (from the layout)."""

    border: int
    z_of_x: np.ndarray  # int64 (nx,)
    z_of_lambda: np.ndarray  # int64 (n_lambda,)
    held: bool
    drive_lambda: int  # the drive multiplier's place in lambda (the layout's; -1 for a free hub)
    hub_inertia: float  # kg m^2
    drive: tuple  # CompiledDrive of hubbeam.system.laws
    torque: tuple  # CompiledTorque of hubbeam.system.laws
    beam_index: np.ndarray  # int64 (nb,)
    beam_x0: np.ndarray  # int64 (nb,)
    beam_lambda0: np.ndarray  # int64 (nb,)
    beam_elements: np.ndarray  # int64 (nb,)
    S: np.ndarray  # (nb, ng, 4) Hermite functions at the Gauss points, and derivatives (1/m, 1/m^2)
    dS: np.ndarray
    d2S: np.ndarray
    w: np.ndarray  # (nb, ng) Gauss weights on [0, 1] (0 on padding points)
    element_length: np.ndarray  # (nb,) m
    stiffness: np.ndarray  # (nb, n_el, ng, 4) EA, GJ_t, EI_y, EI_z at each Gauss point (N, N m^2)
    reference: np.ndarray  # (nb, n_el, ng, 4) strains of the stress-free (pretwisted) state (1, 1/m)
    structural_damping: np.ndarray  # (nb,) c of the Kelvin-Voigt resultants c D e_dot (s)
    trans_mass: np.ndarray  # (nb, n_el, 16, 16) translational element masses (kg)
    inertia: np.ndarray  # (nb, n_el, ng, 3) rho (I_y + I_z), rho I_y, rho I_z (kg m)
    width: np.ndarray  # (nb, n_el, ng) frontal width of the drag (m)
    mount: np.ndarray  # (nb, 4) radius, twist, azimuth, precone (m, rad)
    tip_force: np.ndarray  # (nb, 3) N
    tip_moment: np.ndarray  # (nb, 3) N m
    tip_body: np.ndarray  # (nb, 7) TipBody.params()
    gravity: np.ndarray  # (3,) m/s^2
    gravity_load: np.ndarray  # (nx,) generalized gravity force of the beams' own mass (N)
    drag: np.ndarray  # (2,) c1, c2 of Eq. 37
    ffr: FfrStack
    bandwidth: int


@njit(cache=True)
def drive_angle(model, t):
    """theta_p(t) of the driving constraint (a fixed hub has the profile 'rest')."""
    d = model.drive
    return drive_values(d[0], d[1], d[2], d[3], t)[0]


@njit(cache=True)
def applied_torque(model, t, theta, omega):
    """(T, dT/dtheta, dT/domega) of the hub's torque law (N m)."""
    tq = model.torque
    return torque_values(tq[0], tq[1], tq[2], tq[3], tq[4], tq[5], tq[6], tq[7], t, theta, omega)


@njit(cache=True)
def ancf_beam(model, k, F, x, v):
    """ANCF beam k's place and state: (x0 (where its coordinates start in x), nq (their
    number), its chart, q, q') (the layout's offsets, read from the model)."""
    nq = NODE_DOFS * (model.beam_elements[k] + 1)
    x0 = model.beam_x0[k]
    return x0, nq, F[model.beam_index[k]], x[x0 : x0 + nq], v[x0 : x0 + nq]


@njit(cache=True)
def system_equations(model, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                     want_matrix, res, ab, brow, bcol, bb):
    """Scaled residual and (when ``want_matrix``) Newton matrix of the hub and its ANCF beams.

    Force rows: coef_k (M(q) acc + f_int - Q_ext - Q_v - Q_d + Phi_x^T lambda) on each beam's
    q, coef_k (J theta'' - T + Phi_theta^T lambda) on theta; constraint rows: scale Phi(x, t).
    ``load_factor`` scales the applied loads (gravity, tip loads, the hub torque) for load
    stepping; ``exact_stiffness`` adds the FFR beams' load stiffness (statics and modes; the
    ANCF matrix is exact at rest anyway). The matrix coef_m M + coef_c C + coef_k (K - dQ/dx + lambda . d2 Phi), with the
    constraint Jacobian scaled by ``scale`` in its rows and columns, is written into the
    bordered storage (``bb`` border x border, ``brow`` border rows, ``bcol`` border columns,
    ``ab`` the band of the rest in gbtrf layout with kl = ku = model.bandwidth). The small velocity
    derivative of the rotary-inertia force and the q-derivative of M(q) acc are left out
    (they slow Newton slightly and never change the answer). ``F`` holds every beam's chart.

    f_int of an ANCF beam holds its structural damping (Kelvin-Voigt resultants c D e_dot,
    :func:`hubbeam.elements.ancf.kernels.elastic_kernel`), whose damping matrix enters with coef_c.

    Returns (chart margin min(1 + d.tau) over all Gauss points, dissipated power W). A margin
    at or below :data:`CHART_SINGULAR` means the residual is not valid.
    """
    nb_border = model.border
    zx = model.z_of_x
    zl = model.z_of_lambda
    ku = 2 * model.bandwidth
    for i in range(res.shape[0]):
        res[i] = 0.0
    if want_matrix:
        ab[:, :] = 0.0
        brow[:, :] = 0.0
        bcol[:, :] = 0.0
        bb[:, :] = 0.0
    margin = 2.0
    power = 0.0
    # ---------------------------------------------------------------- hub
    z_theta = zx[THETA]
    theta, omega = x[THETA], v[THETA]
    torque, d_theta, d_omega = applied_torque(model, t, theta, omega)
    hub_row = model.hub_inertia * acc[THETA] - load_factor * torque
    if model.held:
        z_drive = zl[model.drive_lambda]
        hub_row += lam[model.drive_lambda]
        res[z_drive] = scale * (theta - drive_angle(model, t))
    if want_matrix:
        add_entry(ab, brow, bcol, bb, ku, z_theta, z_theta,
                  coef_m * model.hub_inertia - load_factor * (coef_k * d_theta + coef_c * d_omega))
        if model.held:
            add_entry(ab, brow, bcol, bb, ku, z_theta, z_drive, scale)
            add_entry(ab, brow, bcol, bb, ku, z_drive, z_theta, scale)
    # ---------------------------------------------------------------- ANCF beams
    phi = np.empty(6)
    jac = np.empty((6, 8))
    hess = np.empty((8, 8))
    lam_k = np.empty(6)
    c = np.empty(8)
    tip_jacobian = np.empty((4, 3))
    for k in range(model.beam_index.shape[0]):
        n_el = model.beam_elements[k]
        x0, nq, Fk, q, qd = ancf_beam(model, k, F, x, v)
        l0 = model.beam_lambda0[k]
        qa = acc[x0 : x0 + nq]
        S, dS, d2S, w, le = model.S[k], model.dS[k], model.d2S[k], model.w[k], model.element_length[k]
        blocks = np.zeros((n_el if want_matrix else 0, 16, 16))
        fq = np.empty(nq)
        _, mk, pk = kernels.elastic_kernel(q, qd, Fk, le, S, dS, d2S, w, model.stiffness[k], model.reference[k],
                                           model.structural_damping[k], coef_c, coef_k, fq, blocks)
        margin = min(margin, mk)
        power += pk
        if not mk > CHART_SINGULAR:
            return margin, 0.0
        term = np.empty(nq)
        kernels.rotary_inertia_kernel(q, qd, qa, Fk, le, S, dS, w, model.inertia[k], coef_m, term, blocks)
        for j in range(nq):
            fq[j] -= term[j]  # -(Q_v - M_rot acc)
        power += kernels.drag_kernel(qd, le, S, w, model.width[k], model.drag[0], model.drag[1], coef_c, term,
                                     blocks)
        for j in range(nq):
            fq[j] -= term[j]
        kernels.translational_mass_product(model.trans_mass[k], qa, fq)
        applied_load(model, k, q, Fk, load_factor, term, tip_jacobian)
        for j in range(nq):
            fq[j] -= term[j]
        tip = nq - NODE_DOFS
        if has_tip_body(model.tip_body[k]):
            g_tip = np.empty(3)
            for i in range(3):
                g_tip[i] = load_factor * model.gravity[i]
            force8 = np.zeros(8)
            nb8 = 8 if want_matrix else 0
            block8 = np.zeros((nb8, nb8))
            ancf_tip_body_terms(model.tip_body[k], Fk, q[tip : tip + 8], qd[tip : tip + 8], qa[tip : tip + 8],
                                g_tip, coef_m, coef_k, force8, block8)
            for i in range(8):
                fq[tip + i] += force8[i]
            if want_matrix:
                for i in range(8):
                    for j in range(8):
                        blocks[n_el - 1, 8 + i, 8 + j] += block8[i, j]
        # clamp of the root to the hub
        c[0] = theta
        for j in range(7):
            c[1 + j] = q[j]
        for i in range(6):
            lam_k[i] = lam[l0 + i]
        clamp_equations(c, model.mount[k], Fk, lam_k, phi, jac, hess)
        hub_row += clamp_residual(lam_k, phi, jac, 7, scale, zl, l0, fq, res)
        for j in range(nq):
            res[zx[x0 + j]] = coef_k * fq[j]
        if not want_matrix:
            continue
        # the tip moment's load stiffness on the tip's (r0', theta_1) rows and r0' columns
        for i in range(4):
            for j in range(3):
                blocks[n_el - 1, 11 + i, 11 + j] -= coef_k * tip_jacobian[i, j]
        kernels.add_translational_mass(model.trans_mass[k], n_el, coef_m, blocks)
        q_start = zx[x0]  # z index of the beam's first coordinate
        add_element_blocks_banded(ab, blocks, q_start - nb_border, ku, 1.0)
        # clamp: Jacobian in the multiplier rows and columns, Hessian on [theta, root coordinates]
        add_clamp_jacobian(ab, brow, bcol, bb, ku, jac, 7, scale, zl, l0, q_start, z_theta)
        add_entry(ab, brow, bcol, bb, ku, z_theta, z_theta, coef_k * hess[0, 0])
        for a in range(7):
            add_entry(ab, brow, bcol, bb, ku, z_theta, q_start + a, coef_k * hess[0, 1 + a])
            add_entry(ab, brow, bcol, bb, ku, q_start + a, z_theta, coef_k * hess[1 + a, 0])
            for b in range(7):
                add_entry(ab, brow, bcol, bb, ku, q_start + a, q_start + b, coef_k * hess[1 + a, 1 + b])
    # ---------------------------------------------------------------- FFR beams
    ff = model.ffr
    for k in range(ff.nf.shape[0]):
        n = 6 + ff.nf[k]
        x0 = ff.x0[k]
        l0 = ff.lambda0[k]
        q = x[x0 : x0 + n]
        force = np.empty(n)
        nbk = n if want_matrix else 0
        block = np.zeros((nbk, nbk))
        inv, tip, drag = ffr_arguments(model, k)
        power += ffr_body_terms(inv, q, v[x0 : x0 + n], acc[x0 : x0 + n], model.gravity, tip, drag, coef_m, coef_c,
                                coef_k, load_factor, want_matrix, force, block)
        for i in range(6):
            lam_k[i] = lam[l0 + i]
        ffr_clamp(ff.mount[k], theta, q, lam_k, phi, jac, hess)
        hub_row += clamp_residual(lam_k, phi, jac, 6, scale, zl, l0, force, res)
        for j in range(n):
            res[zx[x0 + j]] = coef_k * force[j]
        if not want_matrix:
            continue
        if exact_stiffness:
            load = np.empty((n, n))
            ffr_load_stiffness(inv, q, model.gravity, tip, load_factor, load)
            for i in range(n):
                for j in range(n):
                    block[i, j] += coef_k * load[i, j]
        q_start = zx[x0]
        for i in range(n):
            for j in range(n):
                add_entry(ab, brow, bcol, bb, ku, q_start + i, q_start + j, block[i, j])
        add_clamp_jacobian(ab, brow, bcol, bb, ku, jac, 6, scale, zl, l0, q_start, z_theta)
        add_entry(ab, brow, bcol, bb, ku, z_theta, z_theta, coef_k * hess[0, 0])
    res[z_theta] = coef_k * hub_row
    return margin, power


@njit(cache=True)
def clamp_residual(lam_k, phi, jac, n_root, scale, zl, l0, force, res):
    """A clamp's part of the residual: Phi_q^T lambda added to the first ``n_root`` entries of
    the beam's ``force``, scale Phi into its multiplier rows of ``res``; returns Phi_theta . lambda
    (its part of the hub row). ``jac`` (6 x (1 + n_root)) is on [theta, q_root]."""
    for j in range(n_root):
        acc_j = 0.0
        for i in range(6):
            acc_j += jac[i, 1 + j] * lam_k[i]
        force[j] += acc_j
    hub = 0.0
    for i in range(6):
        hub += jac[i, 0] * lam_k[i]
        res[zl[l0 + i]] = scale * phi[i]
    return hub


@njit(cache=True)
def add_clamp_jacobian(ab, brow, bcol, bb, ku, jac, n_root, scale, zl, l0, q_start, z_theta):
    """scale times a clamp's Jacobian (6 x (1 + n_root), on [theta, q_root]; theta at z_theta,
    q_root from q_start) in its multiplier rows and, transposed, in their columns."""
    for i in range(6):
        ri = zl[l0 + i]
        add_entry(ab, brow, bcol, bb, ku, ri, z_theta, scale * jac[i, 0])
        add_entry(ab, brow, bcol, bb, ku, z_theta, ri, scale * jac[i, 0])
        for j in range(n_root):
            add_entry(ab, brow, bcol, bb, ku, ri, q_start + j, scale * jac[i, 1 + j])
            add_entry(ab, brow, bcol, bb, ku, q_start + j, ri, scale * jac[i, 1 + j])


@njit(cache=True)
def ffr_arguments(model, k):
    """(inv, tip, drag) of FFR beam k for :mod:`hubbeam.elements.ffr.kernels`."""
    ff = model.ffr
    inv = (ff.m[k], ff.c0[k], ff.Sbar[k], ff.I0[k], ff.J[k], ff.II[k], ff.Mff[k], ff.K[k], ff.EAl[k],
           ff.mean_stretch[k], ff.mean_slope2[k], ff.stiffening[k], ff.C_struct[k], ff.damped[k])
    tip = (ff.tip_force[k], ff.tip_moment[k], ff.tip_rows[k], ff.tip_rotation_rows[k], ff.length[k])
    drag = (ff.N_pts[k], ff.x_pts[k], ff.w_pts[k], ff.width[k], model.drag[0], model.drag[1])
    return inv, tip, drag


@njit(cache=True)
def ffr_clamp(mount, theta, q, lam, phi, jac, hess):
    """The six clamp equations of an FFR body frame (see :mod:`hubbeam.system.ffr_part`):
    r_C - R i_k(theta) = 0, Theta1 + theta + psi = 0, Theta2 - p = 0, Theta3 + beta = 0, with
    their Jacobian on [theta, r_C, Theta] (6 x 7, written into the leading columns of ``jac``)
    and the multiplier-weighted Hessian (only d2/dtheta2 of the position rows; hess[0, 0])."""
    radius, twist, azimuth, precone = mount[0], mount[1], mount[2], mount[3]
    a = theta + azimuth
    c, s = np.cos(a), np.sin(a)
    jac[:, :] = 0.0
    hess[:, :] = 0.0
    phi[0] = q[0] - radius * c
    phi[1] = q[1]
    phi[2] = q[2] - radius * s
    phi[3] = q[3] + a
    phi[4] = q[4] - precone
    phi[5] = q[5] + twist
    for i in range(3):
        jac[i, 1 + i] = 1.0
    jac[0, 0] = radius * s
    jac[2, 0] = -radius * c
    jac[3, 0] = 1.0
    jac[3, 4] = 1.0
    jac[4, 5] = 1.0
    jac[5, 6] = 1.0
    hess[0, 0] = radius * (lam[0] * c + lam[2] * s)


@njit(cache=True)
def applied_load(model, k, q, F, factor, Q, tip_jacobian):
    """Q = ``factor`` times the applied generalized force on beam k's coordinates q: gravity
    on its own mass (Eq. 32), the tip force and the tip moment
    (:func:`hubbeam.system.loads.tip_moment_terms`), and tip_jacobian (4 x 3) = ``factor``
    d Q / d r0'(L) of the moment on the tip's (r0', theta_1) rows (zero without a moment)."""
    nq = q.shape[0]
    tip = nq - NODE_DOFS
    x0 = model.beam_x0[k]
    for j in range(nq):
        Q[j] = factor * model.gravity_load[x0 + j]
    for i in range(3):
        Q[tip + i] += factor * model.tip_force[k, i]
    tip_jacobian[:, :] = 0.0
    moment = model.tip_moment[k]
    if moment[0] == 0.0 and moment[1] == 0.0 and moment[2] == 0.0:
        return
    tQ = np.empty(4)
    tip_moment_terms(q[tip + 3 : tip + 6], moment, F, tQ, tip_jacobian)
    for i in range(4):
        Q[tip + 3 + i] += factor * tQ[i]
        for j in range(3):
            tip_jacobian[i, j] *= factor


@njit(cache=True)
def dissipated_power(model, F, x, v):
    """Power of the drag of Eq. 37 on every beam and of the beams' structural damping (ANCF and
    FFR) at the state (x, v) in the charts F (W, >= 0)."""
    power = 0.0
    ff = model.ffr
    for k in range(ff.nf.shape[0]):
        n = 6 + ff.nf[k]
        x0 = ff.x0[k]
        inv, _, drag = ffr_arguments(model, k)
        power += ffr_dissipated_power(x[x0 : x0 + n], v[x0 : x0 + n], inv, drag)
    for k in range(model.beam_index.shape[0]):
        _, nq, Fk, q, qd = ancf_beam(model, k, F, x, v)
        force = np.empty(nq)
        power += kernels.drag_kernel(qd, model.element_length[k], model.S[k], model.w[k], model.width[k],
                                     model.drag[0], model.drag[1], 0.0, force, np.empty((0, 16, 16)))
        if model.structural_damping[k] > 0.0:
            power += kernels.elastic_kernel(q, qd, Fk, model.element_length[k],
                                            model.S[k], model.dS[k], model.d2S[k], model.w[k], model.stiffness[k],
                                            model.reference[k], model.structural_damping[k], 0.0, 0.0, force,
                                            np.empty((0, 16, 16)))[2]
    return power


@njit(cache=True)
def beam_energies(model, F, x, v, out):
    """Kinetic, strain and gravity energy (J) of every beam at (x, v) in the charts F, tip
    bodies included: out[k] = (T, U, V) of beam k (its place among all beams). Returns the
    hub's kinetic energy J theta'^2 / 2 (J)."""
    z8 = np.zeros(8)
    force8 = np.empty(8)
    no_block = np.empty((0, 0))
    for k in range(model.beam_index.shape[0]):
        x0, nq, Fk, q, qd = ancf_beam(model, k, F, x, v)
        S, dS, d2S, w, le = model.S[k], model.dS[k], model.d2S[k], model.w[k], model.element_length[k]
        term = np.zeros(nq)
        kernels.translational_mass_product(model.trans_mass[k], qd, term)
        kinetic = 0.0
        potential = 0.0
        for j in range(nq):
            kinetic += 0.5 * qd[j] * term[j]
            potential -= model.gravity_load[x0 + j] * q[j]
        kinetic += kernels.rotary_inertia_kernel(q, qd, np.zeros(nq), Fk, le, S, dS, w, model.inertia[k], 0.0, term,
                                                 np.empty((0, 16, 16)))
        strain = kernels.elastic_kernel(q, qd, Fk, le, S, dS, d2S, w, model.stiffness[k], model.reference[k], 0.0, 0.0,
                                        0.0, term, np.empty((0, 16, 16)))[0]
        tb = model.tip_body[k]
        if has_tip_body(tb):
            tip = nq - NODE_DOFS
            t_tb, v_tb = ancf_tip_body_terms(tb, Fk, q[tip : tip + 8], qd[tip : tip + 8], z8, model.gravity, 0.0, 0.0,
                                             force8, no_block)
            kinetic += t_tb
            potential += v_tb
        i = model.beam_index[k]
        out[i, 0] = kinetic
        out[i, 1] = strain
        out[i, 2] = potential
    ff = model.ffr
    for k in range(ff.nf.shape[0]):
        n = 6 + ff.nf[k]
        x0 = ff.x0[k]
        inv, _, _ = ffr_arguments(model, k)
        kinetic, strain, potential = ffr_energies(inv, x[x0 : x0 + n], v[x0 : x0 + n], model.gravity)
        i = ff.index[k]
        out[i, 0] = kinetic
        out[i, 1] = strain
        out[i, 2] = potential
    return 0.5 * model.hub_inertia * v[THETA] * v[THETA]


@njit(cache=True)
def tip_displacements(model, x, out):
    """Each beam's tip centroid displacement from its undeformed place along its own hub
    frame i_k (radial), j0 (vertical), k_k (tangential) at x (m): out[k] for beam k (its place
    among all beams)."""
    theta = x[THETA]
    tip_at = np.empty(3)
    for k in range(model.beam_index.shape[0]):
        tip = model.beam_x0[k] + NODE_DOFS * model.beam_elements[k]
        for i in range(3):
            tip_at[i] = x[tip + i]
        _tip_from_mount(model.mount[k], theta, model.element_length[k] * model.beam_elements[k], tip_at,
                        out[model.beam_index[k]])
    ff = model.ffr
    A = np.empty((3, 3))
    D = np.empty((3, 3))
    for k in range(ff.nf.shape[0]):
        x0 = ff.x0[k]
        nf = ff.nf[k]
        cardan(x[x0 + 3], x[x0 + 4], x[x0 + 5], A, D)
        rows = ff.tip_rows[k]
        local = np.empty(3)
        for i in range(3):
            s = 0.0
            for f in range(nf):
                s += rows[i, f] * x[x0 + 6 + f]
            local[i] = s
        local[0] += ff.length[k]
        for i in range(3):
            tip_at[i] = x[x0 + i] + A[i, 0] * local[0] + A[i, 1] * local[1] + A[i, 2] * local[2]
        _tip_from_mount(ff.mount[k], theta, ff.length[k], tip_at, out[ff.index[k]])


@njit(cache=True)
def _tip_from_mount(mount, theta, length, tip_at, out):
    """out = A_k^T (tip_at - R i_k - L a_1): the tip's displacement on the beam's hub frame."""
    A = beam_hub_frame(mount, theta)
    a = axis_frame(mount, theta)
    d = np.empty(3)
    for i in range(3):
        d[i] = tip_at[i] - mount[0] * A[i, 0] - length * a[i, 0]
    for j in range(3):
        out[j] = A[0, j] * d[0] + A[1, j] * d[1] + A[2, j] * d[2]


@njit(cache=True)
def gauge_strains(model, F, x, gauges, out):
    """Fibre strains eps0 - y kappa3 + z kappa2 (measured from the stress-free state's) at the
    strain gauges of ANCF beams at x, into out[i] for gauge i. ``gauges`` = (where (n, 2) int:
    the beam's ANCF row in the model and the element; S, dS, d2S (n, 4): the Hermite functions
    at the gauge's station and their derivatives (1/m, 1/m^2); section (n, 6): y, z (m) and the
    stress-free strains (eps0, kappa1, kappa2, kappa3) there) (:meth:`AncfBeam.gauge_rows`)."""
    where, S, dS, d2S, section = gauges
    w1 = np.empty(16)
    w2 = np.empty(16)
    Y = np.empty(8)
    X = np.empty(8)
    for i in range(where.shape[0]):
        k, el = where[i, 0], where[i, 1]
        kernels.dof_weights(S, dS, d2S, i, w1, w2)
        kernels.gauss_variables(x, model.beam_x0[k] + NODE_DOFS * el, F[model.beam_index[k]], w1, w2, Y, X)
        eps0, _, kappa2, kappa3 = strain_measures(X[0:3], X[3:6], X[6], X[7])
        sec = section[i]
        out[i] = (eps0 - sec[2]) - sec[0] * (kappa3 - sec[5]) + sec[1] * (kappa2 - sec[4])


@njit(cache=True)
def record_measures(model, F, xs, vs, count, energies, gauges, hub, beams, tips, strains):
    """For the first ``count`` rows of xs, vs (one state each): when ``energies``, the hub's
    kinetic energy into hub[r] and the beams' (:func:`beam_energies`) into beams[r] (J); the
    beams' tip displacements (:func:`tip_displacements`) into tips[r] (m); the ANCF strain
    gauges' strains (:func:`gauge_strains`) into strains[r]."""
    for r in range(count):
        if energies:
            hub[r] = beam_energies(model, F, xs[r], vs[r], beams[r])
        tip_displacements(model, xs[r], tips[r])
        gauge_strains(model, F, xs[r], gauges, strains[r])


@njit(cache=True)
def hub_power(model, t, x, v, lam):
    """Power of the drive and the applied torque on the hub (W): (T_applied - lambda_drive) theta'."""
    torque = applied_torque(model, t, x[THETA], v[THETA])[0]
    if model.held:
        torque -= lam[model.drive_lambda]
    return torque * v[THETA]
