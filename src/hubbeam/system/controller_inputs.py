"""What a controller in the loop reads and where it acts: its inputs u(x, v) with their exact
derivatives, and the generalized-force directions of its outputs.

**Inputs** (:class:`ControllerInput`, one sensor column or its ``_rate``), each a function
u(x, v) evaluated with du/dx and du/dv in compiled code (:func:`input_values`) at the
instant and Newton iterate of the step. Five forms cover them:

- ``POLYNOMIAL``: u = c . x_S + x_S^T Q x_S / 2 over a few columns S of x, and its rate
  u = (c + Q x_S) . v_S (du/dx_S = Q v_S, du/dv_S = c + Q x_S): the hub angle theta
  (c = 1) and its rate theta' (``hub_angle_rate``, ``hub_angular_velocity``), a joint angle
  psi and its rate (``joint_angle``, ``joint_angle_rate``, ``joint_rate``), and the fibre
  strain of an FFR beam (nodal or modal), eps = c p + p^T Q p / 2 over its elastic
  coordinates p (:meth:`~hubbeam.elements.ffr.body.FfrBeam.strain_polynomial`: Q = 0 without
  geometric stiffening), and its rate;
- ``BASE_RATE``: the angular velocity of a moving base in base axes, w_b = R^T Jw v
  (component a, ``base_angular_velocity_x|y|z``): du/dv = (Jw^T R)[:, a] and
  du/dx_l = sum_c v_c (Hw[:, c, l] . R e_a + Jw_c . (Jw_l x R e_a)) (dR/dx_l = [Jw_l]x R),
  the frames' Jacobians and their derivatives as :mod:`hubbeam.system.frames` evaluated them;
- ``ANCF_STRAIN``: the fibre strain eps0 - y kappa3 + z kappa2 of an ANCF beam at a gauge
  (as :func:`hubbeam.system.equations.gauge_strains`), a function of the Gauss-point
  variables X = T^T (w1, w2 weights of the element's 16 coordinates) (chart F fixed during a
  step): du/dq = J^T g with g the strain's gradient in X (:func:`~hubbeam.elements.ancf.strain.strain_jet`)
  and J = dX/dq; its rate u = g . J q' has du/dq' = J^T g and du/dq = J^T H J q' (H the
  strain's Hessian in X);
- ``TIP_DEFLECTION``: component j (radial, vertical, tangential) of a beam's tip deflection
  (ANCF, FFR nodal or modal; on a hub, a moving base, a joint or a parent beam's tip, as the
  sensor measures it)
  and its rate, through the root and reference frames' chains
  (:func:`~hubbeam.system.pose_inputs.tip_deflection_input`);
- ``BASE_ROTATION``: component a of a moving base's rotation vector (global axes), a
  function of its 4 Euler parameters, and its rate T(phi)^-1 omega
  (:func:`~hubbeam.system.pose_inputs.base_rotation_input`).

A moving base's position (``base_position_x|y|z``) is its coordinate x_a, a ``POLYNOMIAL``
input; its rate is the base's velocity.

What is not an input: a sensor whose value (or rate) reads the accelerations or the
multipliers (:data:`ACCELERATION_RATES`), and the sensors not listed above
(:data:`SENSOR_INPUTS`); the scenario names them (exit 2).

**Outputs** (:class:`ControllerOutput`): a torque y (N m) with the generalized force y b(x)
(b the force per unit torque) and its power y b . v (drive work):

- ``hub_torque`` on a free hub: b = e_theta (about -j_h in the sense of theta, as the hub's
  torque law);
- ``joint_torque_NAME``: in the single-axis joint of beam NAME, on the beam about the axis
  (its reaction on the parent), as the joint's motor law: b = e_psi;
- ``base_torque_x|y|z`` on a free base, about its base axis a, as the base's attitude law
  (:mod:`hubbeam.system.base_laws`): b = Jw^T R e_a, db/dx as the base's angular velocity's
  (above); its power y w_b[a].
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np
from numba import njit

from hubbeam.elements.ancf import coordinates
from hubbeam.elements.ancf.strain import strain_jet
from hubbeam.system.frames import chain_state
from hubbeam.system.pose_inputs import TIP_NF, base_rotation_input, tip_columns, tip_deflection_input


class InputForm(enum.IntEnum):
    """How an input is computed (the members are what compiled code compares)."""

    POLYNOMIAL = 0
    BASE_RATE = 1
    ANCF_STRAIN = 2
    TIP_DEFLECTION = 3
    BASE_ROTATION = 4


class OutputKind(enum.IntEnum):
    """Where an output acts."""

    HUB_TORQUE = 0
    BASE_TORQUE = 1
    JOINT_TORQUE = 2


#: sensor kinds a controller input may read: (kind, is its ``_rate``) allowed
SENSOR_INPUTS = frozenset({("hub_angle", False), ("hub_angle", True), ("hub_angular_velocity", False),
                           ("joint_angle", False), ("joint_angle", True), ("joint_rate", False),
                           ("base_angular_velocity", False), ("surface_strain", False), ("surface_strain", True),
                           ("tip_deflection", False), ("tip_deflection", True), ("base_position", False),
                           ("base_position", True), ("base_rotation", False), ("base_rotation", True)})
#: the sensor kinds of a moving base (refused as inputs on a fixed base: constants)
BASE_INPUTS = ("base_angular_velocity", "base_position", "base_rotation")
#: sensor kinds whose time derivative reads the accelerations (or the multipliers)
ACCELERATION_RATES = frozenset({"hub_angular_velocity", "hub_torque", "applied_torque", "base_velocity",
                                "base_angular_velocity", "linear_momentum", "system_angular_momentum",
                                "angular_momentum", "base_torque", "energy", "joint_rate", "joint_torque"})
#: the base torque outputs' names, in axis order
BASE_TORQUES = ("base_torque_x", "base_torque_y", "base_torque_z")


@dataclass(frozen=True)
class ControllerInput:
    """One input: a sensor ``kind`` (a key of :data:`SENSOR_INPUTS`), or its ``rate``; the
    ``beam`` it measures (index; a joint, a strain gauge, a tip), ``part`` (a vector component
    0, 1, 2: x, y, z, or a tip deflection's radial, vertical, tangential; a joint's axis) and a
    strain gauge's ``station`` (m) and section point: ``surface`` ("upper" z = +h/2, "lower")
    or (``y``, ``z``) (m, section axes)."""

    kind: str
    rate: bool = False
    beam: int = 0
    part: int = 0
    station: float = 0.0
    surface: str | None = None
    y: float = 0.0
    z: float = 0.0

    def __post_init__(self) -> None:
        if (self.kind, bool(self.rate)) not in SENSOR_INPUTS:
            raise ValueError(f"a {self.kind} sensor{' rate' if self.rate else ''} is not a controller input")


@dataclass(frozen=True)
class ControllerOutput:
    """One output: ``kind`` and, for a joint torque, the ``beam`` (index) of the joint; for a base
    torque, its base ``axis`` (0, 1, 2)."""

    kind: OutputKind
    beam: int = 0
    axis: int = 0

    @classmethod
    def named(cls, name: str, beams=()) -> "ControllerOutput":
        """The output called ``name`` as ``linearize`` names its inputs: hub_torque,
        base_torque_x|y|z, joint_torque_NAME (``beams``: the beam names); ValueError otherwise."""
        if name == "hub_torque":
            return cls(OutputKind.HUB_TORQUE)
        if name in BASE_TORQUES:
            return cls(OutputKind.BASE_TORQUE, axis=BASE_TORQUES.index(name))
        beams = list(beams)
        if name.startswith("joint_torque_") and name[len("joint_torque_"):] in beams:
            return cls(OutputKind.JOINT_TORQUE, beam=beams.index(name[len("joint_torque_"):]))
        raise ValueError(f"{name!r} is not an output (hub_torque, base_torque_x|y|z, joint_torque_BEAM)")


def gauge_point(system, k: int, station: float, surface, y: float, z: float) -> tuple[float, float]:
    """(y, z) (m, section axes) of a strain gauge on beam k at ``station``: ``surface`` 'upper'
    is z = +h/2 (the face whose normal is +n), 'lower' -h/2, h the thickness there; else (y, z)."""
    if surface is None:
        return float(y), float(z)
    h = system.beams[k].section_size(station)[1]
    return 0.0, (h / 2 if surface == "upper" else -h / 2)


@dataclass
class InputRows:
    """The packed inputs (:func:`pack_inputs`)."""

    form: list
    rate: list
    axis: list
    cols: list
    coef: list
    quad: list
    gauges: list
    tips: list


def _resolve(system, spec: ControllerInput, rows: InputRows) -> None:
    layout = system.layout
    form, axis, cols, coef, quad, gauge = InputForm.POLYNOMIAL, 0, [], [], np.zeros((0, 0)), None
    rate = spec.rate or spec.kind in ("hub_angular_velocity", "joint_rate")
    if spec.kind in ("hub_angle", "hub_angular_velocity"):
        cols, coef = [layout.theta], [1.0]
    elif spec.kind in ("joint_angle", "joint_rate"):
        joint = system.beams[spec.beam].mount.joint
        if joint is None or not 0 <= spec.part < joint.count:
            raise ValueError(f"beam {system.beams[spec.beam].name!r} has no joint axis {spec.part}")
        cols, coef = [layout.joint_x(spec.beam).start + spec.part], [1.0]
    elif spec.kind in BASE_INPUTS:
        if not layout.base_moves:
            raise ValueError(f"{spec.kind}: the base does not move")
        if spec.kind == "base_angular_velocity":
            form, axis = InputForm.BASE_RATE, spec.part
        elif spec.kind == "base_position":
            cols, coef = [layout.base_x.start + spec.part], [1.0]
        else:  # its rotation vector, from its Euler parameters
            form, axis = InputForm.BASE_ROTATION, spec.part
            cols = list(range(layout.base_x.start + 3, layout.base_x.start + 7))
    elif spec.kind == "tip_deflection":
        form, axis, cols = InputForm.TIP_DEFLECTION, len(rows.tips), _tip(system, spec, rows)
    else:  # surface_strain
        k = spec.beam
        part = system.beams[k]
        y, z = gauge_point(system, k, spec.station, spec.surface, spec.y, spec.z)
        beam = part.beam
        if hasattr(beam, "strain_polynomial"):  # FFR (nodal or modal): a polynomial of p
            c, Q = beam.strain_polynomial(spec.station, y, z)
            used = np.flatnonzero((np.abs(c) > 0.0) | np.any(Q != 0.0, axis=0))
            cols = list(layout.beam_x(k).start + used)
            coef = list(c[used])
            quad = Q[np.ix_(used, used)] if np.any(Q) else np.zeros((0, 0))
        else:  # ANCF
            form = InputForm.ANCF_STRAIN
            e, S, dS, d2S, section = beam.gauge_rows(spec.station, y, z)
            start = layout.beam_x(k).start + beam.node_slice(e).start
            gauge = (k, start, S, dS, d2S, section)
            axis = len(rows.gauges)
            rows.gauges.append(gauge)
    if form in (InputForm.TIP_DEFLECTION, InputForm.BASE_ROTATION):
        coef = [0.0] * len(cols)  # coef runs beside cols (read by the polynomial inputs only)
    rows.form.append(int(form))
    rows.rate.append(int(rate))
    rows.axis.append(int(axis))
    rows.cols.append(np.asarray(cols, dtype=np.int64))
    rows.coef.append(np.asarray(coef, dtype=float))
    rows.quad.append(np.asarray(quad, dtype=float).ravel())


def _tip(system, spec: ControllerInput, rows: InputRows) -> list[int]:
    """The tip table's row of a tip deflection input (appended to ``rows.tips``) and the columns it reads."""
    k = spec.beam
    part = system.beams[k]
    frames = system.frames
    start = system.layout.beam_x(k).start
    node = part.tip_node()
    if node is not None:  # ANCF: the tip node's position coordinates
        first, nf, N = start + node.start, 0, np.zeros((3, 0))
        own = [first, first + 1, first + 2]
    else:  # FFR: the tip's displacement rows over the elastic coordinates
        N = np.asarray(part.beam.displacement_row(part.length), dtype=float)
        first, nf = start, N.shape[1]
        own = list(range(start, start + nf))
    root, reference = frames.root(k), frames.reference(k)
    rows.tips.append(((root, reference, spec.part, first, nf), N, part.length))
    return tip_columns(frames.table, root, reference, own)


def hessian_chains(system, specs) -> set[int]:
    """The chains whose derivatives Hr, Hw the inputs ``specs`` read
    (:meth:`~hubbeam.system.system_frames.Frames.needs_hessian`): a tip deflection's root section
    frame and its reference frame (:mod:`hubbeam.system.pose_inputs`; an FFR beam's root is
    otherwise evaluated to its velocity products only)."""
    frames = system.frames
    return {k for s in specs if s.kind == "tip_deflection" for k in (frames.root(s.beam), frames.reference(s.beam))}


def pack_inputs(system, specs) -> tuple:
    """(form, rate, axis, starts (m + 1, 2), cols, coef, quad, gauges, tips, width) of the inputs
    ``specs`` on ``system``: the arrays :func:`input_values` reads (``starts[i]``: where input
    i's columns and quadratic form start in ``cols``/``coef`` and ``quad``; ``gauges``: the
    ANCF gauges as :meth:`~hubbeam.system.multibody.MultibodySystem.gauge_table` packs them;
    ``tips``: the tip deflections' table (ints (t, 5), :mod:`~hubbeam.system.pose_inputs`),
    their FFR rows N_L (t, 3, nf) and lengths (t,) (m); a tip deflection's and a base
    rotation's columns are in ``cols``;
    ``width``: the most columns an input reads)."""
    rows = InputRows([], [], [], [], [], [], [], [])
    for spec in specs:
        _resolve(system, spec, rows)
    m = len(rows.form)
    starts = np.zeros((m + 1, 2), dtype=np.int64)
    starts[1:, 0] = np.cumsum([c.size for c in rows.cols])
    starts[1:, 1] = np.cumsum([q.size for q in rows.quad])
    g = len(rows.gauges)
    where = np.array([[r[0], r[1]] for r in rows.gauges], dtype=np.int64).reshape(g, 2)
    S, dS, d2S, section = (np.array([r[i] for r in rows.gauges], dtype=float).reshape(g, w)
                           for i, w in ((2, 4), (3, 4), (4, 4), (5, 6)))
    width = 1
    for i in range(m):
        width = max(width, coordinates.ELEMENT_DOFS if rows.form[i] == InputForm.ANCF_STRAIN else
                    7 if rows.form[i] == InputForm.BASE_RATE else rows.cols[i].size)
    ints = lambda v: np.array(v, dtype=np.int64)  # noqa: E731
    cat = lambda parts, dtype: np.concatenate(parts).astype(dtype) if parts else np.zeros(0, dtype)  # noqa: E731
    t = len(rows.tips)
    widest = max([r[0][TIP_NF] for r in rows.tips], default=0)
    tip_rows = np.zeros((t, 3, widest))
    for i, (_, N, _) in enumerate(rows.tips):
        tip_rows[i, :, :N.shape[1]] = N
    tips = (ints([r[0] for r in rows.tips]).reshape(t, 5), tip_rows, np.array([r[2] for r in rows.tips], dtype=float))
    return (ints(rows.form), ints(rows.rate), ints(rows.axis), starts, cat(rows.cols, np.int64),
            cat(rows.coef, float), cat(rows.quad, float), (where, S, dS, d2S, section), tips, width)


# ---------------------------------------------------------------------------- compiled
@njit(cache=True)
def axis_force_columns(ctx, chain):
    """(columns, Jw^T R (nc, 3), dB (3, nc, nc)): the generalized force per unit torque about
    each axis a of chain ``chain``'s frame, b_a = Jw^T R e_a, on the chain's columns, and its
    derivatives dB[a, c, l] = d b_a[c] / dx_l = Hw[:, c, l] . R e_a + Jw_c . (Jw_l x R e_a)
    (dR/dx_l = [Jw_l]x R; module docstring)."""
    cols, r, R, Jr, Jw, Hr, Hw = chain_state(ctx.chains, chain)
    nc = cols.shape[0]
    b = np.zeros((nc, 3))
    dB = np.zeros((3, nc, nc))
    for a in range(3):
        e0, e1, e2 = R[0, a], R[1, a], R[2, a]
        for c in range(nc):
            b[c, a] = Jw[0, c] * e0 + Jw[1, c] * e1 + Jw[2, c] * e2
        for l in range(nc):
            t0 = Jw[1, l] * e2 - Jw[2, l] * e1
            t1 = Jw[2, l] * e0 - Jw[0, l] * e2
            t2 = Jw[0, l] * e1 - Jw[1, l] * e0
            for c in range(nc):
                dB[a, c, l] = (Hw[0, c, l] * e0 + Hw[1, c, l] * e1 + Hw[2, c, l] * e2
                               + Jw[0, c] * t0 + Jw[1, c] * t1 + Jw[2, c] * t2)
    return cols, b, dB


@njit(cache=True)
def _ancf_strain(where, S, dS, d2S, section, g, F, x, v, rate, cols, dx, dv):
    """u of ANCF gauge g (its rate when ``rate``) at (x, v), its derivatives into cols, dx, dv (16)."""
    w1, w2 = np.empty(16), np.empty(16)
    Y, X = np.empty(8), np.empty(8)
    coordinates.dof_weights(S, dS, d2S, g, w1, w2)
    Fc = F[where[g, 0]]
    o = where[g, 1]
    coordinates.gauss_variables(x, o, Fc, w1, w2, Y, X)
    J = np.zeros((8, 16))  # dX/dq: X = T^T Y, Y[first] += w1 q, Y[second] += w2 q
    for j in range(16):
        for which in range(2):
            slot = coordinates.DOF_FIRST[j] if which == 0 else coordinates.DOF_SECOND[j]
            w = w1[j] if which == 0 else w2[j]
            if slot >= 6:
                J[slot, j] += w
            else:
                blk, comp = slot // 3, slot % 3
                for i in range(3):
                    J[3 * blk + i, j] += Fc[comp, i] * w
    e, G, H = np.empty(4), np.empty((4, 8)), np.empty((4, 8, 8))
    strain_jet(X, e, G, H, rate)
    sec = section[g]
    y, z = sec[0], sec[1]
    grad = np.empty(8)
    for p in range(8):
        grad[p] = G[0, p] - y * G[3, p] + z * G[2, p]
    gq = np.zeros(16)
    for j in range(16):
        for p in range(8):
            gq[j] += J[p, j] * grad[p]
        cols[j] = o + j
    if not rate:
        for j in range(16):
            dx[j] = gq[j]
            dv[j] = 0.0
        return (e[0] - sec[2]) - y * (e[3] - sec[5]) + z * (e[2] - sec[4])
    Xd = np.zeros(8)  # J q'
    for p in range(8):
        for j in range(16):
            Xd[p] += J[p, j] * v[o + j]
    u = 0.0
    HX = np.zeros(8)
    for p in range(8):
        u += grad[p] * Xd[p]
        for q in range(8):
            HX[p] += (H[0, p, q] - y * H[3, p, q] + z * H[2, p, q]) * Xd[q]
    for j in range(16):
        s = 0.0
        for p in range(8):
            s += J[p, j] * HX[p]
        dx[j] = s
        dv[j] = gq[j]
    return u


@njit(cache=True)
def input_values(pack, ctx, F, x, v):
    """(u (m,), cols (m, width), dx, dv (m, width), count (m,)): the inputs at (x, v) and their
    derivatives du_i/dx[cols[i, k]] = dx[i, k], du_i/dv[cols[i, k]] = dv[i, k] for
    k < count[i] (a column may repeat: the entries add). ``pack``: a controllers' pack
    (:class:`~hubbeam.system.controllers.Controllers`), the chains evaluated at x."""
    m = pack.form.shape[0]
    u = np.zeros(m)
    cols = np.zeros((m, pack.width), dtype=np.int64)
    dx, dv = np.zeros((m, pack.width)), np.zeros((m, pack.width))
    count = np.zeros(m, dtype=np.int64)
    where, S, dS, d2S, section = pack.gauges
    cb, base_b, base_dB = np.zeros(1, dtype=np.int64), np.zeros((1, 3)), np.zeros((3, 1, 1))
    for i in range(m):
        if pack.form[i] == InputForm.BASE_RATE:  # the base frame's force columns, once for every base input
            cb, base_b, base_dB = axis_force_columns(ctx, pack.base_chain)
            break
    for i in range(m):
        form = pack.form[i]
        rate = pack.rate[i] != 0
        if form == InputForm.POLYNOMIAL:
            a, b = pack.starts[i, 0], pack.starts[i + 1, 0]
            k = b - a
            qa = pack.starts[i, 1]
            has_quad = pack.starts[i + 1, 1] > qa
            value = 0.0
            for r in range(k):
                c = pack.cols[a + r]
                slope = pack.coef[a + r]  # c + Q x_S
                curv = 0.0  # (Q v_S)
                half = 0.0
                if has_quad:
                    for s in range(k):
                        qrs = pack.quad[qa + r * k + s]
                        slope += qrs * x[pack.cols[a + s]]
                        curv += qrs * v[pack.cols[a + s]]
                        half += 0.5 * qrs * x[pack.cols[a + s]]
                cols[i, r] = c
                if rate:
                    value += slope * v[c]
                    dx[i, r] = curv
                    dv[i, r] = slope
                else:
                    value += (pack.coef[a + r] + half) * x[c]
                    dx[i, r] = slope
            u[i] = value
            count[i] = k
        elif form == InputForm.BASE_RATE:
            a = pack.axis[i]
            nc = cb.shape[0]
            value = 0.0
            for c in range(nc):
                value += base_b[c, a] * v[cb[c]]
                cols[i, c] = cb[c]
                dv[i, c] = base_b[c, a]
                s = 0.0
                for l in range(nc):
                    s += v[cb[l]] * base_dB[a, l, c]
                dx[i, c] = s
            u[i] = value
            count[i] = nc
        elif form == InputForm.ANCF_STRAIN:
            u[i] = _ancf_strain(where, S, dS, d2S, section, pack.axis[i], F, x, v, rate, cols[i], dx[i], dv[i])
            count[i] = 16
        else:  # the frames' poses: a tip deflection, a base's rotation vector
            a, b = pack.starts[i, 0], pack.starts[i + 1, 0]
            ucols = pack.cols[a:b]
            k = b - a
            if form == InputForm.TIP_DEFLECTION:
                t = pack.axis[i]
                ints, rows, lengths = pack.tips
                u[i] = tip_deflection_input(ctx.chains, ints[t], rows[t], lengths[t], ucols, x, v, rate, dx[i], dv[i])
            else:
                e, ed = np.empty(4), np.empty(4)
                for r in range(4):
                    e[r] = x[ucols[r]]
                    ed[r] = v[ucols[r]]
                u[i] = base_rotation_input(e, ed, pack.axis[i], rate, dx[i], dv[i])
            for r in range(k):
                cols[i, r] = ucols[r]
            count[i] = k
    return u, cols, dx, dv, count
