"""The laws of a moving base: its Euler parameters' norm, a table that drives its pose, and an
attitude control torque.

A base with coordinates (:class:`~hubbeam.system.base.Base`, free or following a table) has
x_b = [r_b (3), e (4)] (:mod:`hubbeam.system.frames`, link ``FREE``). Its kind "base laws"
(:data:`KIND`) adds:

- the **norm** of the Euler parameters, Phi_n = (e . e - 1) / 2 = 0. The base's rotation is
  that of e / |e|, so the norm carries no mass and no force: the constraint fixes the gauge
  and its multiplier stays zero;
- the **drive** of a table base (or of a free base held for statics): r_b - r_tab(t) = 0 and
  G(e_tab(t)) e = 0 (3 + 3 equations), G(q) = [-q_v, q_0 I - [q_v]x] the vector part of
  conj(q) (x) e, which vanishes where e = e_tab. Its multipliers are the forces and torques
  that move the base; their power lambda . Phi_t is the drive's work;
- the **attitude law** of a free base, a PD torque in base axes
  tau = -kp phi - kd (w - w_ref) (component-wise), phi the rotation vector of R_ref^T R (R the
  base's rotation, R_ref the reference's: a fixed target, or a slew about a fixed axis
  R_ref = R(0) exp(s(t) [a]x), s(t) the slew profile of :mod:`hubbeam.system.laws`), w and
  w_ref the base's and the reference's angular velocities in base axes. Its generalized force
  is Jw^T R tau on e; its power (R tau) . w.

The table (:class:`PoseTable`) is a not-a-knot cubic spline (C2) of the position and of the
rotation vector of the base axes through at least 4 rows from t = 0; after the last row the
base keeps its last velocity and angular velocity (constant-velocity extrapolation of the
position and the rotation vector). The rotation vector's Euler parameters
e = (cos(a/2), sin(a/2) phi / a), a = |phi|, and their first two time derivatives are written
out in smooth functions of u = a^2 (series near zero).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.system import terms
from hubbeam.system.assembly import add_entry
from hubbeam.system.frames import chain_state
from hubbeam.system.rotations import euler_parameters, rotation_vector_matrix
from hubbeam.system.law_kernels import drive_values, poly2, table_interval
from hubbeam.system.laws import DriveProfile

#: rows a pose table needs (a not-a-knot cubic spline through them)
MIN_POSE_ROWS = 4


class AttitudeKind(enum.IntEnum):
    """The attitude laws of a free base (the members are what compiled code compares)."""

    NONE = 0
    TARGET = 1
    SLEW = 2


@dataclass(frozen=True)
class PoseTable:
    """A base's prescribed pose: ``times`` (s, from 0, increasing, at least 4), ``positions``
    (m, of O_b, global) and ``rotations`` (rad, rotation vectors of the base axes)."""

    times: np.ndarray
    positions: np.ndarray
    rotations: np.ndarray
    knots: np.ndarray = field(init=False, repr=False, compare=False)
    coefs: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        from scipy.interpolate import CubicSpline

        t = np.asarray(self.times, dtype=float)
        pos = np.asarray(self.positions, dtype=float).reshape(-1, 3)
        rot = np.asarray(self.rotations, dtype=float).reshape(-1, 3)
        if t.ndim != 1 or t.size < MIN_POSE_ROWS or pos.shape[0] != t.size or rot.shape[0] != t.size:
            raise ValueError(f"a pose table needs at least {MIN_POSE_ROWS} rows of time, position and rotation")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(pos)) and np.all(np.isfinite(rot))):
            raise ValueError("a pose table's values must be finite")
        if t[0] != 0.0 or np.any(np.diff(t) <= 0.0):
            raise ValueError("a pose table's times must start at 0 and increase")
        values = np.hstack([pos, rot])
        spline = CubicSpline(t, values, bc_type="not-a-knot")
        # coefs[c, i, :] = the cubic of component c on [t_i, t_i+1], highest power first
        coefs = np.ascontiguousarray(np.transpose(spline.c, (2, 1, 0)))
        for name, value in (("times", t), ("positions", pos), ("rotations", rot), ("knots", t), ("coefs", coefs)):
            object.__setattr__(self, name, value)

    def pose(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """(position, rotation matrix) at time t (s)."""
        values = table_values(self.knots, self.coefs, float(t))
        return values[0].copy(), rotation_vector_matrix(values[3])


@dataclass(frozen=True)
class AttitudeLaw:
    """A free base's PD attitude law: gains ``kp`` (N m/rad) and ``kd`` (N m s/rad) per base axis,
    and the reference: a fixed ``target`` (rotation vector, rad) or, when ``slew_angle`` is set,
    a slew of ``slew_angle`` (rad) in ``slew_T`` (s) about ``slew_axis`` (base axes at t = 0)."""

    kp: tuple = (0.0, 0.0, 0.0)
    kd: tuple = (0.0, 0.0, 0.0)
    target: tuple = (0.0, 0.0, 0.0)
    slew_axis: tuple | None = None
    slew_angle: float = 0.0
    slew_T: float = 1.0

    def __post_init__(self) -> None:
        for name in ("kp", "kd", "target"):
            value = tuple(float(v) for v in np.ravel(getattr(self, name)))
            if len(value) != 3 or not all(math.isfinite(v) for v in value):
                raise ValueError(f"attitude {name}: three finite numbers")
            object.__setattr__(self, name, value)
        if min(self.kp) < 0.0 or min(self.kd) < 0.0:
            raise ValueError("attitude kp, kd: must be >= 0")
        if self.slew_axis is not None:
            axis = np.asarray(self.slew_axis, dtype=float)
            norm = float(np.linalg.norm(axis))
            if axis.shape != (3,) or not norm > 0.0:
                raise ValueError("attitude slew axis: a nonzero vector")
            object.__setattr__(self, "slew_axis", tuple(axis / norm))

    @property
    def kind(self) -> AttitudeKind:
        return AttitudeKind.SLEW if self.slew_axis is not None else AttitudeKind.TARGET

    def slew(self) -> DriveProfile:
        return DriveProfile.slew(self.slew_angle, self.slew_T) if self.slew_axis is not None else DriveProfile("rest")


# ---------------------------------------------------------------------------- compiled pieces
@njit(cache=True)
def table_values_into(knots, coefs, t, out):
    """(r, r', r'', phi, phi', phi'') of a pose table at t into the rows of out (6 x 3, or wider:
    columns 0-2): the splines' values and derivatives; after the last row, constant velocity
    (value + rate (t - t_end), no acceleration)."""
    n = knots.shape[0]
    t_end = knots[n - 1]
    i = n - 2 if t >= t_end else table_interval(knots, t)
    h = t_end - knots[n - 2] if t >= t_end else t - knots[i]
    for c in range(6):
        value, rate, accel = poly2(coefs[c], i, h)
        if t >= t_end:
            value += rate * (t - t_end)
            accel = 0.0
        row = 0 if c < 3 else 3
        out[row, c % 3] = value
        out[row + 1, c % 3] = rate
        out[row + 2, c % 3] = accel


@njit(cache=True)
def table_values(knots, coefs, t):
    """:func:`table_values_into` in a new (6, 3) array."""
    out = np.empty((6, 3))
    table_values_into(knots, coefs, t, out)
    return out


@njit(cache=True)
def rotation_vector_quaternion(phi, dphi, ddphi, q, dq, ddq):
    """The Euler parameters q = (cos(a/2), sin(a/2) phi/a) of the rotation vector phi (a = |phi|)
    and their first two time derivatives for phi's (module docstring), into q, dq, ddq (4)."""
    u = phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2]
    du = 2.0 * (phi[0] * dphi[0] + phi[1] * dphi[1] + phi[2] * dphi[2])
    ddu = 2.0 * (dphi[0] * dphi[0] + dphi[1] * dphi[1] + dphi[2] * dphi[2]
                 + phi[0] * ddphi[0] + phi[1] * ddphi[1] + phi[2] * ddphi[2])
    if u < 1e-4:  # series of S(u) = sin(sqrt(u)/2)/sqrt(u) and its derivatives
        S = 0.5 - u / 48.0 + u * u / 3840.0 - u * u * u / 645120.0
        S1 = -1.0 / 48.0 + u / 1920.0 - u * u / 215040.0
        S2 = 1.0 / 1920.0 - u / 107520.0
        C = 1.0 - u / 8.0 + u * u / 384.0 - u * u * u / 46080.0
    else:
        a = math.sqrt(u)
        S = math.sin(0.5 * a) / a
        C = math.cos(0.5 * a)
        S1 = (0.25 * C - 0.5 * S) / u
        S2 = (-S / 16.0 - 1.5 * S1) / u
    q[0] = C
    dq[0] = -0.25 * S * du
    ddq[0] = -0.25 * (S1 * du * du + S * ddu)
    for i in range(3):
        q[1 + i] = S * phi[i]
        dq[1 + i] = S1 * du * phi[i] + S * dphi[i]
        ddq[1 + i] = (S2 * du * du + S1 * ddu) * phi[i] + 2.0 * S1 * du * dphi[i] + S * ddphi[i]


@njit(cache=True)
def conjugate_product_matrix(q, G):
    """G (3 x 4) with vec(conj(q) (x) e) = G e: [-q_v, q_0 I - [q_v]x]."""
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    G[0, 0], G[0, 1], G[0, 2], G[0, 3] = -q1, q0, q3, -q2
    G[1, 0], G[1, 1], G[1, 2], G[1, 3] = -q2, -q3, q0, q1
    G[2, 0], G[2, 1], G[2, 2], G[2, 3] = -q3, q2, -q1, q0


@njit(cache=True)
def quaternion_product(a, b, out):
    """out = a (x) b (Hamilton product; scalar first)."""
    out[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3]
    out[1] = a[0] * b[1] + b[0] * a[1] + a[2] * b[3] - a[3] * b[2]
    out[2] = a[0] * b[2] + b[0] * a[2] + a[3] * b[1] - a[1] * b[3]
    out[3] = a[0] * b[3] + b[0] * a[3] + a[1] * b[2] - a[2] * b[1]


@njit(cache=True)
def _quaternion_matrix(q, R):
    """R of unit Euler parameters q."""
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    R[0, 0] = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3
    R[1, 1] = q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3
    R[2, 2] = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
    R[0, 1] = 2.0 * (q1 * q2 - q0 * q3)
    R[1, 0] = 2.0 * (q1 * q2 + q0 * q3)
    R[0, 2] = 2.0 * (q1 * q3 + q0 * q2)
    R[2, 0] = 2.0 * (q1 * q3 - q0 * q2)
    R[1, 2] = 2.0 * (q2 * q3 - q0 * q1)
    R[2, 1] = 2.0 * (q2 * q3 + q0 * q1)


@njit(cache=True)
def attitude_torque_into(pack, t, e, w_base, tau):
    """The PD law's torque (N m, base axes) into tau (3) for the Euler parameters e and the
    base's angular velocity w_base (rad/s, base axes); (0, 0, 0) without a law. Its
    quaternions and rotation are views of the pack's scratch (:class:`BaseLaws`): it allocates
    nothing."""
    for i in range(3):
        tau[i] = 0.0
    if pack.attitude == AttitudeKind.NONE:
        return
    a = pack.axis
    quaternions = pack.work[3]
    q_ref, e_unit, err, turn, conj = quaternions[0], quaternions[1], quaternions[2], quaternions[3], quaternions[4]
    known = quaternions[5]  # the time (NaN: none) whose reference q_ref holds, and its slew rate s'
    if not known[0] == t:  # the reference once per time: the step's residuals and powers share it
        s, ds = 0.0, 0.0
        if pack.attitude == AttitudeKind.SLEW:
            drv = pack.slew
            s, ds, _ = drive_values(drv[0], drv[1], drv[2], drv[3], t)
        turn[0] = math.cos(0.5 * s)
        for i in range(3):
            turn[1 + i] = math.sin(0.5 * s) * a[i]
        quaternion_product(pack.reference, turn, q_ref)
        known[0] = t
        known[1] = ds
    ds = known[1]
    norm = math.sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3])
    for i in range(4):
        e_unit[i] = e[i] / norm
    conj[0] = q_ref[0]
    for i in range(1, 4):
        conj[i] = -q_ref[i]
    quaternion_product(conj, e_unit, err)
    if err[0] < 0.0:  # the shorter way round: |phi| <= pi
        for i in range(4):
            err[i] = -err[i]
    vn = math.sqrt(err[1] * err[1] + err[2] * err[2] + err[3] * err[3])
    factor = 2.0 * math.atan2(vn, err[0]) / vn if vn > 1e-300 else 2.0
    Rerr = pack.work[4]
    _quaternion_matrix(err, Rerr)
    for i in range(3):
        # w_ref in base axes: R_err^T (s' a)
        w_ref = ds * (Rerr[0, i] * a[0] + Rerr[1, i] * a[1] + Rerr[2, i] * a[2])
        tau[i] = -pack.kp[i] * factor * err[1 + i] - pack.kd[i] * (w_base[i] - w_ref)


@njit(cache=True)
def attitude_torque(pack, t, e, w_base):
    """:func:`attitude_torque_into` in a new array (3)."""
    tau = np.empty(3)
    attitude_torque_into(pack, t, e, w_base, tau)
    return tau


# ---------------------------------------------------------------------------- the kind
class BaseLaws(NamedTuple):
    """A moving base's laws (module docstring)."""

    x0: int  # where the base's coordinates start in x
    chain: int  # the base frame's chain
    norm_lambda: int  # the norm constraint's place in lambda
    drive_lambda: int  # the first of the six drive multipliers (-1: not driven)
    knots: np.ndarray  # the pose table's times (s); a held base: (0,)
    coefs: np.ndarray  # (6, n - 1, 4) the table's cubics; a held base: (6, 0, 4)
    held: np.ndarray  # (7,) the pose a base held for statics keeps: r_b, e
    attitude: int  # AttitudeKind
    kp: np.ndarray  # (3,) N m/rad
    kd: np.ndarray  # (3,) N m s/rad
    reference: np.ndarray  # (4,) Euler parameters of R_ref at t = 0 (target, or R(0) for a slew)
    axis: np.ndarray  # (3,) the slew's axis, base axes
    slew: tuple  # CompiledDrive of the slew profile
    #: (6, 6, 4) scratch of the terms (they allocate nothing: compiled into the system's
    #: equations, which count no references, :func:`hubbeam.system.terms.register`):
    #: [0] the drive's pose, rows r, r', r'', q, q', q'' (r's in columns 0-2; :func:`driven_pose_into`);
    #: [1] the pose table's values (:func:`table_values_into`); [2] G (rows 0-2) and the attitude
    #: law's Newton-matrix product R^T Jw on e (rows 3-5); [3] the attitude law's quaternions (its
    #: reference q_ref in row 0 for the time in [5, 0], NaN before the first, with its slew rate in [5, 1]) and
    #: [4] its R_err (:func:`attitude_torque_into`); [5] w, w_base, tau and R tau (rows 0-3)
    work: np.ndarray


def pack_base_laws(system, layout) -> BaseLaws | None:
    base = system.base
    if not base.moves:
        return None
    law = base.torque
    reference = np.array([1.0, 0.0, 0.0, 0.0])
    if law is not None:
        reference = euler_parameters(rotation_vector_matrix(law.target) if law.kind == AttitudeKind.TARGET
                                     else base.initial_rotation)
    table = base.table
    return BaseLaws(
        layout.base_x.start, system.frames.base, layout.norm_lambda,
        -1 if layout.base_lambda is None else layout.base_lambda.start,
        table.knots if table is not None else np.zeros(1), table.coefs if table is not None else np.zeros((6, 0, 4)),
        base.initial_coordinates(), int(AttitudeKind.NONE if law is None else law.kind),
        np.array(law.kp if law is not None else (0.0,) * 3, dtype=float),
        np.array(law.kd if law is not None else (0.0,) * 3, dtype=float), reference,
        np.array(law.slew_axis if law is not None and law.slew_axis is not None else (1.0, 0.0, 0.0), dtype=float),
        tuple((law.slew() if law is not None else DriveProfile("rest")).compiled()), _scratch())


def _scratch() -> np.ndarray:
    """The terms' scratch (:attr:`BaseLaws.work`), with no attitude reference known yet."""
    work = np.zeros((6, 6, 4))
    work[3, 5, 0] = np.nan
    return work


@njit(cache=True)
def driven_pose_into(pack, t, pose):
    """The base's drive at t into the rows of pose (6 x 4): r, r', r'' (columns 0-2), q, q',
    q'': its table's (through the pack's scratch), or the held pose."""
    if pack.coefs.shape[1] == 0:
        for i in range(3):
            pose[0, i] = pack.held[i]
            pose[1, i] = 0.0
            pose[2, i] = 0.0
        for i in range(4):
            pose[3, i] = pack.held[3 + i]
            pose[4, i] = 0.0
            pose[5, i] = 0.0
        return
    v = pack.work[1]
    table_values_into(pack.knots, pack.coefs, t, v)
    for i in range(3):
        pose[0, i], pose[1, i], pose[2, i] = v[0, i], v[1, i], v[2, i]
    rotation_vector_quaternion(v[3], v[4], v[5], pose[3], pose[4], pose[5])


@njit(cache=True)
def driven_pose(pack, t):
    """(r, r', r'', q, q', q'') of the base's drive at t in new arrays (:func:`driven_pose_into`)."""
    pose = np.empty((6, 4))
    driven_pose_into(pack, t, pose)
    return (pose[0, :3].copy(), pose[1, :3].copy(), pose[2, :3].copy(), pose[3].copy(), pose[4].copy(),
            pose[5].copy())


@njit(cache=True)
def _base_state(pack, ctx, F, x, v, w, wb):
    """(columns, R, Jw (3, 7)) of the base frame at (x, v), its angular velocity into w (global
    axes) and wb (base axes)."""
    cols, r, R, Jr, Jw, Hr, Hw = chain_state(ctx.chains, pack.chain)
    nc = cols.shape[0]
    for a in range(3):
        w[a] = 0.0
        for j in range(nc):
            w[a] += Jw[a, j] * v[cols[j]]
    for i in range(3):
        wb[i] = R[0, i] * w[0] + R[1, i] * w[1] + R[2, i] * w[2]
    return cols, R, Jw


def base_law_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor,
                       exact_stiffness, want_matrix, res, ab, brow, bcol, bb):
    """The norm, the drive and the attitude law (module docstring)."""
    zx, zl, ku = ctx.z_of_x, ctx.z_of_lambda, ctx.ku
    e0 = pack.x0 + 3
    # norm: (e . e - 1) / 2
    ln = lam[pack.norm_lambda]
    z_norm = zl[pack.norm_lambda]
    ee = 0.0
    for i in range(4):
        ee += x[e0 + i] * x[e0 + i]
        res[zx[e0 + i]] += coef_k * ln * x[e0 + i]
    res[z_norm] = scale * 0.5 * (ee - 1.0)
    if want_matrix:
        for i in range(4):
            add_entry(ab, brow, bcol, bb, ku, z_norm, zx[e0 + i], scale * x[e0 + i])
            add_entry(ab, brow, bcol, bb, ku, zx[e0 + i], z_norm, scale * x[e0 + i])
            add_entry(ab, brow, bcol, bb, ku, zx[e0 + i], zx[e0 + i], coef_k * ln)
    # the drive: r_b - r(t) and G(q(t)) e
    if pack.drive_lambda >= 0:
        pose, G = pack.work[0], pack.work[2]
        driven_pose_into(pack, t, pose)
        conjugate_product_matrix(pose[3], G)
        l0 = pack.drive_lambda
        for i in range(3):
            res[zl[l0 + i]] = scale * (x[pack.x0 + i] - pose[0, i])
            res[zx[pack.x0 + i]] += coef_k * lam[l0 + i]
            g = 0.0
            for j in range(4):
                g += G[i, j] * x[e0 + j]
                res[zx[e0 + j]] += coef_k * G[i, j] * lam[l0 + 3 + i]
            res[zl[l0 + 3 + i]] = scale * g
        if want_matrix:
            for i in range(3):
                add_entry(ab, brow, bcol, bb, ku, zl[l0 + i], zx[pack.x0 + i], scale)
                add_entry(ab, brow, bcol, bb, ku, zx[pack.x0 + i], zl[l0 + i], scale)
                for j in range(4):
                    add_entry(ab, brow, bcol, bb, ku, zl[l0 + 3 + i], zx[e0 + j], scale * G[i, j])
                    add_entry(ab, brow, bcol, bb, ku, zx[e0 + j], zl[l0 + 3 + i], scale * G[i, j])
    # the attitude law: -Jw^T R tau on e
    if pack.attitude != AttitudeKind.NONE:
        vectors = pack.work[5]
        w, wb, tau, tg = vectors[0], vectors[1], vectors[2], vectors[3]
        cols, R, Jw = _base_state(pack, ctx, F, x, v, w, wb)
        attitude_torque_into(pack, t, x[e0:e0 + 4], wb, tau)
        for i in range(3):  # tg = R tau, written out: R is a view of the chain table's pose (not contiguous)
            tg[i] = R[i, 0] * tau[0] + R[i, 1] * tau[1] + R[i, 2] * tau[2]
        for j in range(3, 7):
            res[zx[cols[j]]] -= coef_k * load_factor * (Jw[0, j] * tg[0] + Jw[1, j] * tg[1] + Jw[2, j] * tg[2])
        if want_matrix:
            # Jw^T R diag(coef_k kp + coef_c kd) R^T Jw (exact about the reference, where tau = 0)
            B = pack.work[2]  # rows 3-5: (R^T Jw)[a, j] in B[3 + a, j - 3], j = 3..6 (e's columns)
            for a in range(3):
                for j in range(3, 7):
                    B[3 + a, j - 3] = R[0, a] * Jw[0, j] + R[1, a] * Jw[1, j] + R[2, a] * Jw[2, j]
            for i in range(3, 7):
                for j in range(3, 7):
                    value = 0.0
                    for a in range(3):
                        value += B[3 + a, i - 3] * (coef_k * pack.kp[a] + coef_c * pack.kd[a]) * B[3 + a, j - 3]
                    add_entry(ab, brow, bcol, bb, ku, zx[cols[i]], zx[cols[j]], load_factor * value)
    return 2.0, 0.0


def base_law_drive_power(pack, ctx, F, t, x, v, lam):
    """The drive's power lambda . Phi_t and the attitude torque's (R tau) . w (W)."""
    power = 0.0
    e0 = pack.x0 + 3
    if pack.drive_lambda >= 0:
        pose, Gd = pack.work[0], pack.work[2]
        driven_pose_into(pack, t, pose)
        conjugate_product_matrix(pose[4], Gd)
        l0 = pack.drive_lambda
        for i in range(3):
            g = 0.0
            for j in range(4):
                g += Gd[i, j] * x[e0 + j]
            power += lam[l0 + i] * (-pose[1, i]) + lam[l0 + 3 + i] * g
    if pack.attitude != AttitudeKind.NONE:
        vectors = pack.work[5]
        w, wb, tau = vectors[0], vectors[1], vectors[2]
        _base_state(pack, ctx, F, x, v, w, wb)
        attitude_torque_into(pack, t, x[e0:e0 + 4], wb, tau)
        power += tau[0] * wb[0] + tau[1] * wb[1] + tau[2] * wb[2]
    return power


KIND = terms.register(BaseLaws, pack_base_laws, base_law_equations, drive_power=base_law_drive_power,
                      counts_references=False)
