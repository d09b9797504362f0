"""Joints at beam roots: revolute axes, their springs, dampers and motors, and latches.

A beam's root is clamped to its frame (the hub, or its parent beam's tip) unless its mount
carries a :class:`Joint`: up to three revolute axes in sequence between the joint frame
(a, b, c) and the beam's twist (:mod:`hubbeam.system.mount`). Each axis adds one coordinate,
the joint angle psi (rad), to x (:class:`~hubbeam.system.layout.Layout`); the joint frame turns
by psi about the axis by the right-hand rule, each axis as turned by the ones before. Named
axes: ``flap`` = +c, ``lag`` = +b, ``pitch`` = -a.

The kind "joint laws" (:data:`KIND`) holds what acts on the joint angles:

- the spring, damper and motor of each axis: the torque on the beam about the axis
  T = -k (psi - psi_0) - c psi' + T_m(t, psi - psi_i, psi'), with equal and opposite torque on
  the parent (psi is a relative coordinate: its generalized force is the torque, the reaction
  follows); T_m is any torque law of :mod:`hubbeam.system.laws`, a PD law tracking
  psi_ref = psi_i + theta_p(t) (psi_i the initial angle). The spring's energy k (psi - psi_0)^2 / 2
  is in its beam's strain energy, the damper's c psi'^2 is dissipated power, the motor's
  T_m psi' drive power;
- the lock of a latched joint (:meth:`Joint.locked`): the constraint psi - psi_L = 0 with its
  multiplier lambda (the layout's lock), whose torque on the beam is -lambda (the joint's
  torque after the latch); a locked axis has no spring, damper or motor (the clamp holds it);
- the latch event: an unlocked axis with a latch angle reaches it when its angle, coming from
  its initial side, first reaches the latch angle (:func:`joint_events`): the time loop stops
  after that step and the simulation locks it at the angle reached
  (:mod:`hubbeam.simulation`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.system import terms
from hubbeam.system.assembly import add_entry
from hubbeam.system.chains import Link, revolute
from hubbeam.system.law_kernels import torque_values
from hubbeam.system.laws import TorqueLaw

#: the named axes in the joint frame (a, b, c)
NAMED_AXES = {"flap": (0.0, 0.0, 1.0), "lag": (0.0, 1.0, 0.0), "pitch": (-1.0, 0.0, 0.0)}
#: most axes of one joint
MAX_AXES = 3
#: the coefficients of a drive polynomial (quartic: an omega table's antiderivative), padded to this many
COEFFICIENTS = 5


@dataclass(frozen=True)
class Joint:
    """A revolute joint of one to three axes at a beam's root (SI units, angles in rad).

    ``axes``: unit vectors in the joint frame (a, b, c) (normalised here), in sequence;
    ``names``: one per axis (the named axis, or "axis1", ...: sensor parts and mode labels);
    per axis ``stiffness`` (N m/rad), ``damping`` (N m s/rad), ``neutral`` (rad, the spring's
    unloaded angle), ``initial_angle`` (rad) and ``initial_rate`` (rad/s); ``latch`` (rad, a
    single-axis joint: the angle at which it locks), ``torque`` (a single-axis joint's motor
    law); ``locked_at`` (rad): the angle a latch locked it at (a latched joint, see
    :meth:`locked`)."""

    axes: tuple
    names: tuple
    stiffness: tuple = ()
    damping: tuple = ()
    neutral: tuple = ()
    initial_angle: tuple = ()
    initial_rate: tuple = ()
    latch: float | None = None
    torque: TorqueLaw | None = None
    locked_at: float | None = None

    def __post_init__(self) -> None:
        n = len(self.axes)
        if not 1 <= n <= MAX_AXES:
            raise ValueError(f"a joint has 1 to {MAX_AXES} axes (got {n})")
        axes = []
        for axis in self.axes:
            a = np.asarray(axis, dtype=float).reshape(3)
            norm = float(np.linalg.norm(a))
            if not (norm > 0.0 and math.isfinite(norm)):
                raise ValueError(f"axis: {list(a)} is not a direction")
            axes.append(tuple(float(v) for v in a / norm))
        object.__setattr__(self, "axes", tuple(axes))
        if len(self.names) != n or len(set(self.names)) != n:
            raise ValueError("one distinct name per axis")
        for key in ("stiffness", "damping", "neutral", "initial_angle", "initial_rate"):
            values = getattr(self, key) or (0.0,) * n
            if len(values) != n:
                raise ValueError(f"{key}: one value per axis ({n}, got {len(values)})")
            object.__setattr__(self, key, tuple(float(v) for v in values))
        if n > 1 and (self.latch is not None or self.torque is not None or self.locked_at is not None):
            raise ValueError("latch and torque: single-axis joints only")
        if self.torque is not None and not self.torque.compilable:
            raise ValueError("torque: a joint's motor law must be compilable (not a Python function)")
        if self.latch is not None and self.latch == self.initial_angle[0]:
            raise ValueError("latch: equal to the initial angle (the joint would start latched)")

    @classmethod
    def named(cls, *names: str, **values) -> "Joint":
        """A joint about named axes ("flap", "lag", "pitch") in sequence."""
        return cls(tuple(NAMED_AXES[n] for n in names), tuple(names), **values)

    @property
    def count(self) -> int:
        """Joint angles (coordinates) of this joint."""
        return len(self.axes)

    @property
    def locks(self) -> int:
        """Lock multipliers: 1 for a latched joint, else 0."""
        return int(self.locked_at is not None)

    def links(self, first: int) -> tuple[Link, ...]:
        """The revolute links of the axes, their angles at x[first], x[first + 1], ..."""
        return tuple(revolute(first + i, axis, 1.0) for i, axis in enumerate(self.axes))

    def locked(self, angle: float) -> "Joint":
        """The same joint locked at ``angle`` (rad) by its latch."""
        return replace(self, locked_at=float(angle))

    def label(self, i: int) -> str:
        """The mode label of axis i: "flap hinge", "lag hinge", "pitch hinge" or "hinge"."""
        name = self.names[i]
        return f"{name} hinge" if name in NAMED_AXES else "hinge"


def beam_joints(system):
    """(beam index k, its joint, the x index of its first angle) of every beam on a joint."""
    out = []
    for k, part in enumerate(system.beams):
        joint = part.mount.joint
        if joint is not None:
            out.append((k, joint, system.layout.joint_x(k).start))
    return out


# ================================================================ compiled terms: the kind "joint laws"
class JointLaws(NamedTuple):
    """Every joint axis of a system, one row each: its place, spring, damper, motor and latch.
    Four arrays, not one per field: a compiled call that counts references counts every array of
    every pack it is given (about 10 ns each; a pack of ten arrays cost a 4-mode FFR beam on a
    hinge 0.15 to 0.25 us of its 3.9 us residual, ``benchmarks/joint_cost.py``). The kind's
    terms of the time step (equations, powers, events) allocate nothing and take no array from
    a call, so they are registered without reference counting (:data:`KIND`): inlined into the
    system's compiled equations, powers and events instead of called with the pack, the context
    and the state's arrays counted at every residual and every call of the step's powers."""

    places: np.ndarray  # int64 (n, 11): x index of psi, its beam (energy row), its lock in lambda (-1: none),
    #                     the motor's TorqueKind (-1: no motor) and its reference's kind, and where the motor's
    #                     tables are: the torque table's knots (first index in ``tables``, count; its values follow
    #                     them), the reference's knots (first, count) and pieces (first row of ``ref_coefs``, count)
    constants: np.ndarray  # (n, 15): stiffness, damping, neutral, initial angle, latch angle, latch side
    #                        (+1 / -1 from below / above, 0 none), locked angle (nan: not locked), the motor's
    #                        params (4), the reference's params (4)
    tables: np.ndarray  # (m,): the torque tables' times and values and the references' knots, concatenated
    ref_coefs: np.ndarray  # (p, COEFFICIENTS): the references' pieces, left-padded with zeros


#: columns of :attr:`JointLaws.places` and :attr:`JointLaws.constants`
COORD, BEAM, LOCK, MOTOR, REFERENCE, KNOTS, KNOT_COUNT, REF_KNOTS, REF_KNOT_COUNT, PIECES, PIECE_COUNT = range(11)
STIFFNESS, DAMPING, NEUTRAL, INITIAL, LATCH, SIDE, LOCKED, MOTOR_PARAMS, REF_PARAMS = 0, 1, 2, 3, 4, 5, 6, 7, 11


def pack_joint_laws(system, layout) -> JointLaws | None:
    """The :class:`JointLaws` of ``system`` placed by ``layout`` (None without joints)."""
    places, constants, tables, rcoefs = [], [], [], []
    for k, joint, first in beam_joints(system):
        lock = layout.lock_lambda(k)
        for i in range(joint.count):
            latch = joint.latch if joint.latch is not None else math.nan
            side = 0.0 if joint.latch is None else math.copysign(1.0, joint.latch - joint.initial_angle[i])
            locked = joint.locked_at if joint.locked_at is not None else math.nan
            law = joint.torque
            c = (law if law is not None else TorqueLaw()).compiled()
            knots = len(tables)
            tables += list(c.knots) + list(c.values)
            ref_knots = len(tables)
            tables += list(c.ref_knots)
            pieces = len(rcoefs)
            for row in c.ref_coefs:
                rcoefs.append([0.0] * (COEFFICIENTS - len(row)) + list(row))
            places.append((first + i, k, lock.start if joint.locked_at is not None else -1,
                           int(c.kind) if law is not None else -1, int(c.ref_kind), knots, len(c.knots), ref_knots,
                           len(c.ref_knots), pieces, len(c.ref_coefs)))
            constants.append([joint.stiffness[i], joint.damping[i], joint.neutral[i], joint.initial_angle[i], latch,
                              side, locked] + list(c.params) + list(c.ref_params))
    if not places:
        return None
    return JointLaws(np.array(places, dtype=np.int64), np.array(constants, dtype=float),
                     np.array(tables, dtype=float), np.array(rcoefs, dtype=float).reshape(len(rcoefs), COEFFICIENTS))


@njit(cache=True)
def motor_torque(pack, j, t, psi, rate):
    """(T_m, dT_m/dpsi, dT_m/dpsi') of axis j's motor (N m; zero without one): its torque law at
    (t, psi - initial angle, psi')."""
    place = pack.places[j]
    kind = place[MOTOR]
    if kind < 0:
        return 0.0, 0.0, 0.0
    const = pack.constants[j]
    tables = pack.tables
    a, n = place[KNOTS], place[KNOT_COUNT]
    ra, rn = place[REF_KNOTS], place[REF_KNOT_COUNT]
    pa, pn = place[PIECES], place[PIECE_COUNT]
    return torque_values(kind, const[MOTOR_PARAMS:MOTOR_PARAMS + 4], tables[a:a + n], tables[a + n:a + 2 * n],
                         place[REFERENCE], const[REF_PARAMS:REF_PARAMS + 4], tables[ra:ra + rn],
                         pack.ref_coefs[pa:pa + pn], t, psi - const[INITIAL], rate)


def joint_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                    want_matrix, res, ab, brow, bcol, bb):
    """-coef_k T on each free axis's row (the spring and damper in full, the motor scaled by
    ``load_factor`` like every applied torque) and its matrix coef_k k + coef_c c - load_factor
    (coef_k dT_m/dpsi + coef_c dT_m/dpsi'); a locked axis: scale (psi - psi_L) in its lock's row
    and coef_k lambda on psi's."""
    zx, zl, ku = ctx.z_of_x, ctx.z_of_lambda, ctx.ku
    power = 0.0
    for j in range(pack.places.shape[0]):
        c = pack.places[j, COORD]
        z = zx[c]
        psi, rate = x[c], v[c]
        const = pack.constants[j]
        lock = pack.places[j, LOCK]
        if lock >= 0:
            zlock = zl[lock]
            res[zlock] = scale * (psi - const[LOCKED])
            res[z] += coef_k * lam[lock]
            if want_matrix:
                add_entry(ab, brow, bcol, bb, ku, zlock, z, scale)
                add_entry(ab, brow, bcol, bb, ku, z, zlock, scale)
            continue
        k, d = const[STIFFNESS], const[DAMPING]
        motor, d_psi, d_rate = motor_torque(pack, j, t, psi, rate)
        res[z] += coef_k * (k * (psi - const[NEUTRAL]) + d * rate - load_factor * motor)
        power += d * rate * rate
        if want_matrix:
            add_entry(ab, brow, bcol, bb, ku, z, z,
                      coef_k * k + coef_c * d - load_factor * (coef_k * d_psi + coef_c * d_rate))
    return 2.0, power


def joint_energies(pack, ctx, F, x, v, beams):
    """Each spring's energy k (psi - psi_0)^2 / 2 (J) in its beam's strain energy."""
    for j in range(pack.places.shape[0]):
        stretch = x[pack.places[j, COORD]] - pack.constants[j, NEUTRAL]
        terms.add_beam_energy(beams, pack.places[j, BEAM], 0.0, 0.5 * pack.constants[j, STIFFNESS] * stretch * stretch,
                              0.0)
    return 0.0, 0.0, 0.0


def joint_power(pack, ctx, F, x, v):
    """The dampers' dissipated power c psi'^2 (W) of the free axes."""
    power = 0.0
    for j in range(pack.places.shape[0]):
        if pack.places[j, LOCK] < 0:
            rate = v[pack.places[j, COORD]]
            power += pack.constants[j, DAMPING] * rate * rate
    return power


def joint_drive_power(pack, ctx, F, t, x, v, lam):
    """The motors' power T_m psi' (W) of the free axes."""
    power = 0.0
    for j in range(pack.places.shape[0]):
        if pack.places[j, LOCK] < 0 and pack.places[j, MOTOR] >= 0:
            c = pack.places[j, COORD]
            power += motor_torque(pack, j, t, x[c], v[c])[0] * v[c]
    return power


def joint_events(pack, ctx, x):
    """Whether a free axis with a latch has reached its latch angle from its initial side."""
    for j in range(pack.places.shape[0]):
        const = pack.constants[j]
        if pack.places[j, LOCK] < 0 and const[SIDE] != 0.0:
            if const[SIDE] * (x[pack.places[j, COORD]] - const[LATCH]) >= 0.0:
                return True
    return False


def joint_bandwidth(system, layout) -> int:
    """Half-bandwidth of the locks' entries: a lock's row and its angle's column."""
    width = 1
    zx, zl = layout.z_of_x, layout.z_of_lambda
    for k, joint, first in beam_joints(system):
        if joint.locked_at is not None:
            width = max(width, abs(int(zl[layout.lock_lambda(k).start]) - int(zx[first])))
    return width


def joint_latches_pending(pack) -> bool:
    """Whether a free axis of ``pack`` has a latch (else :func:`joint_events` can never be true)."""
    return bool(np.any((pack.places[:, LOCK] < 0) & (pack.constants[:, SIDE] != 0.0)))


def joint_powers_possible(pack, ctx) -> bool:
    """Whether a free axis of ``pack`` has a damper or a motor (else :func:`joint_power` and
    :func:`joint_drive_power` are zero at every state: a spring stores, a lock does no work, its
    rate being zero), so that a system whose other parts have no power either skips the step's
    powers (:func:`hubbeam.system.terms.with_powers`)."""
    free = pack.places[:, LOCK] < 0
    return bool(np.any(free & ((pack.constants[:, DAMPING] != 0.0) | (pack.places[:, MOTOR] >= 0))))


KIND = terms.register(JointLaws, pack_joint_laws, joint_equations, joint_energies, joint_power,
                      bandwidth=joint_bandwidth, drive_power=joint_drive_power, events=joint_events,
                      events_possible=joint_latches_pending, powers_possible=joint_powers_possible,
                      counts_references=False)


# ================================================================ Python: what the sensors and the latch read
def joint_torques(system, t: float, x, v, lam, F=None) -> dict[int, np.ndarray]:
    """{beam k: the torque on the beam about each of its joint's axes (N m)}: spring, damper,
    motor and controllers together (charts F, default the initial ones); a locked axis's lock
    reaction -lambda."""
    out = {}
    controlled = system.controller_torques(t, x, v, F)[1]
    for k, joint, first in beam_joints(system):
        values = np.empty(joint.count)
        for i in range(joint.count):
            psi, rate = float(x[first + i]), float(v[first + i])
            if joint.locked_at is not None:
                values[i] = -float(lam[system.layout.lock_lambda(k).start])
                continue
            motor = joint.torque(t, psi - joint.initial_angle[i], rate)[0] if joint.torque is not None else 0.0
            values[i] = -joint.stiffness[i] * (psi - joint.neutral[i]) - joint.damping[i] * rate + motor \
                + controlled.get(k, 0.0)
        out[k] = values
    return out


def reached_latches(system, x) -> list[int]:
    """The beams whose joint's latch angle the state x has reached (from the initial side), not yet locked."""
    out = []
    for k, joint, first in beam_joints(system):
        if joint.latch is None or joint.locked_at is not None:
            continue
        side = math.copysign(1.0, joint.latch - joint.initial_angle[0])
        if side * (float(x[first]) - joint.latch) >= 0.0:
            out.append(k)
    return out


@dataclass(frozen=True)
class LatchEvent:
    """A latch that locked a joint: the ``beam`` (name), the ``time`` (s: the end of the step in
    which the angle reached the latch), the ``angle`` it locked at (rad), the torque ``impulse``
    of the lock on the beam about the axis (N m s) and the kinetic ``energy`` the projection
    removed (J), with ``kinetic_before`` (J)."""

    beam: str
    time: float
    angle: float
    impulse: float
    energy: float
    kinetic_before: float

    def to_dict(self) -> dict:
        return {"beam": self.beam, "time": self.time, "angle_deg": math.degrees(self.angle),
                "impulse": self.impulse, "energy": self.energy}


def latch_joints(system, beams, t: float, x, v, F):
    """Lock the joints of ``beams`` (indices) at their angles in x: (the system with those joints
    locked, the velocities projected onto its constraints, their :class:`LatchEvent`, the drive's
    impulsive work (J)).

    The projection is a plastic impact in the kinetic-energy metric with every constraint of the
    locked system kept: M dv + G^T Lambda = 0, G dv = -G v (only the locks' rows are nonzero: v
    satisfies the others), solved as the bordered system [[M, s G^T], [s G, 0]] of the
    equations (s: the mass scale), v+ = v + dv. Lambda holds each lock's impulse; the energy
    removed is dv^T M dv / 2 (the kinetic energy's loss less the impulsive work of prescribed
    motions, the drive's, returned separately: zero unless a drive or a table holds the hub or
    the base)."""
    locked = list(system.beams)
    for k in beams:
        part = locked[k]
        first = system.layout.joint_x(k).start
        locked[k] = replace(part, mount=replace(part.mount, joint=part.mount.joint.locked(float(x[first]))))
    new = system.with_beams(locked)
    layout = new.layout
    s = new.mass_scale
    zero = np.zeros(new.nx)
    _, matrix = new.dynamic_equations(x, v, zero, np.zeros(layout.n_lambda), F, t, 1.0, 0.0, 0.0, s)
    rhs = np.zeros(layout.nz)
    for k in beams:
        rhs[layout.z_of_lambda[layout.lock_lambda(k).start]] = -s * float(v[layout.joint_x(k).start])
    dz = matrix.factorise().solve(rhs)
    dv, mu = layout.split_z(dz)
    v_plus = v + dv
    M = new.mass_matrix(x, F)
    removed = 0.5 * float(dv @ M @ dv)
    before = system.energies(x, v, F)["kinetic"]
    after = new.energies(x, v_plus, F)["kinetic"]
    events = []
    for k in beams:
        lock = layout.lock_lambda(k).start
        first = layout.joint_x(k).start
        share = 0.5 * float(v[first]) * s * float(mu[lock])  # this lock's part of dv^T M dv / 2
        events.append(LatchEvent(system.beams[k].name, float(t), float(x[first]), -s * float(mu[lock]), share,
                                 before))
    return new, v_plus, events, after - before + removed
