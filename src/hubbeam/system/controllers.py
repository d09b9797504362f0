"""Linear time-invariant controllers in the loop: the kind "controllers".

A controller (:class:`LinearController`) reads m inputs u and applies p torques y:

    s' = A s + B u,    y = C s + D u,    s(0) = 0

(A n x n, B n x m, C p x n, D p x m; n = 0: a static gain y = D u). Its states are unknowns of
the time step, solved in the same Newton iteration as the structure's coordinates and
evaluated at the same instant t_{n+1} as a PD torque law (:mod:`hubbeam.system.drives`).

**How the states are carried.** The integrator (:mod:`hubbeam.solvers.generalized_alpha`)
steps second-order coordinates x with their rates v and accelerations. Each state s_j is the
*rate* of a coordinate w_j (the state's time integral; nothing reads w itself), so that the
controller's equation is a force row of that coordinate,

    coef_k (w'' - A w' - B u(x, v)) = 0,

a "mass" I, a "damping" -A and no stiffness. Its Newton-matrix entries are coef_m I - coef_c A
on the controller's own columns and -B (coef_k du/dx + coef_c du/dv) on the coordinates the
inputs read; an output y_o adds -coef_k y_o b_o(x) to the rows of the coordinates it drives
(b_o its generalized force per unit torque), with -coef_k y_o db_o/dx, -coef_c C b_o on the
controller's columns and -b_o D (coef_k du/dx + coef_c du/dv). This is exact:
generalized-alpha's update of the rates, v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1}
with its algorithmic acceleration a, is the generalized-alpha method for first-order systems
(Jansen, Whiting and Hulbert 2000) applied to s' = A s + B u, second-order accurate, with the
equations enforced at t_{n+1} as the structure's; no extra approximation enters.

**Inputs and outputs**: :mod:`hubbeam.system.controller_inputs` (the sensors a controller
reads, with their exact derivatives; the hub, joint and base torques it applies). The
outputs' power y_o b_o . v is drive work in the energy balance (:func:`controller_drive_power`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.system import terms
from hubbeam.system.assembly import add_entry
from hubbeam.system.controller_inputs import (
    ControllerInput,
    ControllerOutput,
    InputForm,
    OutputKind,
    axis_force_columns,
    input_values,
    pack_inputs,
)
from hubbeam.system.frames import evaluate_chains


@dataclass(frozen=True)
class LinearController:
    """A linear controller s' = A s + B u, y = C s + D u (module docstring): ``inputs`` (m
    :class:`ControllerInput`) and ``outputs`` (p :class:`ControllerOutput`); the units of u and
    y are those of the inputs (rad, rad/s) and outputs (N m)."""

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    inputs: tuple
    outputs: tuple
    name: str = "controller"

    def __post_init__(self) -> None:
        m, p = len(self.inputs), len(self.outputs)
        D = np.asarray(self.D, dtype=float).reshape(p, m) if np.size(self.D) == p * m else None
        if D is None:
            raise ValueError(f"D: {p} x {m} (outputs x inputs), got shape {np.shape(self.D)}")
        A = np.asarray(self.A, dtype=float)
        n = A.shape[0] if A.ndim == 2 else -1
        shapes = {"A": (n, n), "B": (n, m), "C": (p, n)}
        arrays = {"A": A, "B": np.asarray(self.B, dtype=float), "C": np.asarray(self.C, dtype=float)}
        if A.ndim != 2 or A.shape[1] != n:
            raise ValueError(f"A: a square n x n matrix, got shape {A.shape}")
        for key, shape in shapes.items():
            value = arrays[key]
            if value.size == 0 and 0 in shape:
                value = np.zeros(shape)
            if value.shape != shape:
                raise ValueError(f"{key}: {shape[0]} x {shape[1]} (n = {n} states, m = {m} inputs, p = {p} outputs), "
                                 f"got shape {value.shape}")
            arrays[key] = value
        for key, value in {**arrays, "D": D}.items():
            if not np.all(np.isfinite(value)):
                raise ValueError(f"{key}: every entry must be finite")
            object.__setattr__(self, key, np.ascontiguousarray(value))
        for value in self.inputs:
            if not isinstance(value, ControllerInput):
                raise ValueError(f"inputs: ControllerInput values, got {value!r}")
        for value in self.outputs:
            if not isinstance(value, ControllerOutput):
                raise ValueError(f"outputs: ControllerOutput values, got {value!r}")
        object.__setattr__(self, "inputs", tuple(self.inputs))
        object.__setattr__(self, "outputs", tuple(self.outputs))

    @property
    def states(self) -> int:
        return self.A.shape[0]


@dataclass(frozen=True)
class ControllerLaw:
    """A Python controller law y = ``function``(t, u) (p numbers, N m) of its ``inputs`` u (m
    :class:`ControllerInput`) at time t (s), applied to its ``outputs`` (p
    :class:`ControllerOutput`): no states. Not compilable: a system with one takes the Python
    step path, the law's derivatives dy/du by central differences (as a Python torque law's),
    the inputs' du/dx, du/dv exact (:func:`law_terms`)."""

    function: object
    inputs: tuple
    outputs: tuple
    name: str = "law"
    states = 0

    def __call__(self, t: float, u) -> np.ndarray:
        """y (p,) at (t, u); ValueError when the function does not give p finite numbers."""
        y = np.asarray(self.function(float(t), np.array(u, dtype=float)), dtype=float).reshape(-1)
        if y.size != len(self.outputs) or not np.all(np.isfinite(y)):
            raise ValueError(f"controller law {self.name!r}: must return {len(self.outputs)} finite numbers of N m "
                             f"(got {y!r:.80})")
        return y


class Controllers(NamedTuple):
    """Every controller of a system as one block-diagonal controller (their outputs add), with
    its inputs packed (:func:`~hubbeam.system.controller_inputs.pack_inputs`) and its outputs'
    places."""

    x0: int  # the first controller coordinate in x
    A: np.ndarray  # (n, n)
    B: np.ndarray  # (n, m)
    C: np.ndarray  # (p, n)
    D: np.ndarray  # (p, m)
    form: np.ndarray  # int64 (m,): InputForm
    rate: np.ndarray  # int64 (m,): 1 for a rate
    axis: np.ndarray  # int64 (m,): a base input's component, an ANCF input's gauge
    starts: np.ndarray  # int64 (m + 1, 2): each input's columns in cols/coef and its form in quad
    cols: np.ndarray  # int64: the polynomial inputs' columns in x
    coef: np.ndarray  # their linear coefficients
    quad: np.ndarray  # their quadratic forms, row-major
    gauges: tuple  # the ANCF gauges (where, S, dS, d2S, section)
    tips: tuple  # the tip deflections (ints (t, 5), FFR rows (t, 3, nf), lengths (t,))
    width: int  # the most columns an input reads
    base_chain: int  # the base frame's chain (-1: the base does not move)
    out_kind: np.ndarray  # int64 (p,): OutputKind
    out_index: np.ndarray  # int64 (p,): the x index of a hub or joint output's coordinate; a base output's axis


def combined(controllers) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, list, list]:
    """(A, B, C, D, inputs, outputs) of the controllers side by side: block-diagonal A, B, C, D."""
    from scipy.linalg import block_diag

    controllers = list(controllers)
    n = sum(c.states for c in controllers)
    m = sum(len(c.inputs) for c in controllers)
    p = sum(len(c.outputs) for c in controllers)
    A = block_diag(*[c.A for c in controllers]) if n else np.zeros((0, 0))
    B, C, D = np.zeros((n, m)), np.zeros((p, n)), np.zeros((p, m))
    i = j = k = 0
    for c in controllers:
        ni, mi, pi = c.states, len(c.inputs), len(c.outputs)
        B[i:i + ni, j:j + mi] = c.B
        C[k:k + pi, i:i + ni] = c.C
        D[k:k + pi, j:j + mi] = c.D
        i, j, k = i + ni, j + mi, k + pi
    inputs = [u for c in controllers for u in c.inputs]
    outputs = [y for c in controllers for y in c.outputs]
    return A.reshape(n, n), B, C, D, inputs, outputs


def output_places(system, layout, outputs) -> tuple[np.ndarray, np.ndarray]:
    """(kind, index) of each output (:attr:`Controllers.out_kind`, :attr:`Controllers.out_index`);
    ValueError for an output the system cannot take."""
    kinds, index = [], []
    for out in outputs:
        if out.kind == OutputKind.HUB_TORQUE:
            if layout.held:
                raise ValueError("hub_torque: the hub is held (a controller's hub torque needs a free hub)")
            index.append(layout.theta)
        elif out.kind == OutputKind.JOINT_TORQUE:
            joint = system.beams[out.beam].mount.joint
            if joint is None or joint.count != 1:
                raise ValueError(f"joint_torque_{system.beams[out.beam].name}: needs a beam on a single-axis joint")
            index.append(layout.joint_x(out.beam).start)
        else:
            if not system.base.moves or system.base.table is not None:
                raise ValueError("base_torque_x|y|z: needs a free base")
            index.append(out.axis)
        kinds.append(int(out.kind))
    return np.array(kinds, dtype=np.int64), np.array(index, dtype=np.int64)


def linear_controllers(system) -> list:
    """The system's :class:`LinearController` (compiled), in order."""
    return [c for c in getattr(system, "controllers", ()) if isinstance(c, LinearController)]


def _pack(system, layout, A, B, C, D, inputs, outputs) -> Controllers:
    form, rate, axis, starts, cols, coef, quad, gauges, tips, width = pack_inputs(system, inputs)
    kinds, index = output_places(system, layout, outputs)
    return Controllers(layout.controllers_x.start, np.ascontiguousarray(A), B, C, D, form, rate, axis, starts, cols,
                       coef, quad, gauges, tips, width, system.frames.base if system.base.moves else -1, kinds, index)


def pack_controllers(system, layout) -> Controllers | None:
    controllers = linear_controllers(system)
    if not controllers:
        return None
    return _pack(system, layout, *combined(controllers))


def law_pack(system, layout, law: ControllerLaw) -> Controllers:
    """A pack of ``law``'s inputs and outputs (no states; D zero: :func:`law_terms` gives dy/du)."""
    m, p = len(law.inputs), len(law.outputs)
    return _pack(system, layout, np.zeros((0, 0)), np.zeros((0, m)), np.zeros((p, 0)), np.zeros((p, m)),
                 list(law.inputs), list(law.outputs))


@njit(cache=True)
def output_values(pack, u, v):
    """y = C w' + D u (N m) of every output."""
    A, C, D, x0 = pack.A, pack.C, pack.D, pack.x0
    y = np.zeros(D.shape[0])
    for o in range(D.shape[0]):
        for k in range(A.shape[0]):
            y[o] += C[o, k] * v[x0 + k]
        for i in range(D.shape[1]):
            y[o] += D[o, i] * u[i]
    return y


@njit(cache=True)
def _controller_outputs(pack, ctx, F, x, v):
    evaluate_chains(ctx.chains, x, F, 2)
    u = input_values(pack, ctx, F, x, v)[0]
    return u, output_values(pack, u, v)


def controller_values(system, x, v, F=None) -> tuple[np.ndarray, np.ndarray, list]:
    """(u, y, outputs): the controllers' inputs, their outputs' torques (N m) and the outputs
    (:class:`ControllerOutput`) at (x, v) (charts F, default the beams' initial ones)."""
    model = system.model()
    pack = next(p for p in model.parts if isinstance(p, Controllers))
    F = system.initial_charts() if F is None else F
    u, y = _controller_outputs(pack, model.context, np.ascontiguousarray(F, dtype=float),
                               np.ascontiguousarray(x, dtype=float), np.ascontiguousarray(v, dtype=float))
    return u, y, combined(linear_controllers(system))[5]


def controller_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor,
                         exact_stiffness, want_matrix, res, ab, brow, bcol, bb):
    """The controllers' rows coef_k (w'' - A w' - B u) and their outputs' -coef_k load_factor
    y b on the driven coordinates' rows (module docstring), with their Newton-matrix entries."""
    zx, ku = ctx.z_of_x, ctx.ku
    u, cols, dx, dv, count = input_values(pack, ctx, F, x, v)
    A, B, D, x0 = pack.A, pack.B, pack.D, pack.x0
    n, m = A.shape[0], B.shape[1]
    for j in range(n):
        zw = zx[x0 + j]
        row = acc[x0 + j]
        for k in range(n):
            row -= A[j, k] * v[x0 + k]
        for i in range(m):
            row -= B[j, i] * u[i]
        res[zw] += coef_k * row
        if want_matrix:
            for k in range(n):
                add_entry(ab, brow, bcol, bb, ku, zw, zx[x0 + k], (coef_m if j == k else 0.0) - coef_c * A[j, k])
            for i in range(m):
                if B[j, i] != 0.0:
                    for r in range(count[i]):
                        add_entry(ab, brow, bcol, bb, ku, zw, zx[cols[i, r]],
                                  -B[j, i] * (coef_k * dx[i, r] + coef_c * dv[i, r]))
    y = output_values(pack, u, v)
    apply_outputs(pack, ctx, y, D, cols, dx, dv, count, coef_c, coef_k, load_factor, want_matrix, res, ab, brow, bcol,
                  bb)
    return 2.0, 0.0


@njit(cache=True)
def apply_outputs(pack, ctx, y, J, cols, dx, dv, count, coef_c, coef_k, load_factor, want_matrix, res, ab, brow, bcol,
                  bb):
    """-coef_k load_factor y_o b_o on the rows the outputs drive, and the Newton-matrix entries
    -load_factor (coef_k y_o db_o/dx + coef_c C b_o (the controllers' columns) + b_o J (coef_k
    du/dx + coef_c du/dv)), J = dy/du (D, or a Python law's differences)."""
    zx, ku = ctx.z_of_x, ctx.ku
    C, x0 = pack.C, pack.x0
    n, m = C.shape[1], J.shape[1]
    has_base = pack.base_chain >= 0
    nbc = 7 if has_base else 1
    base_cols = np.zeros(nbc, dtype=np.int64)
    b_all = np.zeros((nbc, 3))
    dB = np.zeros((3, nbc, nbc))
    if has_base:
        base_cols, b_all, dB = axis_force_columns(ctx, pack.base_chain)
    for o in range(y.shape[0]):
        base = pack.out_kind[o] == OutputKind.BASE_TORQUE
        a = pack.out_index[o]
        nrows = base_cols.shape[0] if base else 1
        for c in range(nrows):
            xc = base_cols[c] if base else a
            bc = b_all[c, a] if base else 1.0
            zr = zx[xc]
            res[zr] -= coef_k * load_factor * y[o] * bc
            if not want_matrix:
                continue
            if base:
                for l in range(nrows):
                    add_entry(ab, brow, bcol, bb, ku, zr, zx[base_cols[l]], -load_factor * coef_k * y[o] * dB[a, c, l])
            for k in range(n):
                add_entry(ab, brow, bcol, bb, ku, zr, zx[x0 + k], -load_factor * coef_c * C[o, k] * bc)
            for i in range(m):
                if J[o, i] != 0.0:
                    for r in range(count[i]):
                        add_entry(ab, brow, bcol, bb, ku, zr, zx[cols[i, r]],
                                  -load_factor * bc * J[o, i] * (coef_k * dx[i, r] + coef_c * dv[i, r]))


@njit(cache=True)
def output_power(pack, ctx, y, v):
    """sum_o y_o b_o . v (W): the outputs' power (the chains evaluated at the state)."""
    power = 0.0
    has_base = pack.base_chain >= 0
    w = np.zeros(3)  # a moving base's angular velocity in its axes, b_a . v (the base outputs' rates)
    if has_base:
        cb, b, _ = axis_force_columns(ctx, pack.base_chain)
        for a in range(3):
            for c in range(cb.shape[0]):
                w[a] += b[c, a] * v[cb[c]]
    for o in range(y.shape[0]):
        if pack.out_kind[o] == OutputKind.BASE_TORQUE and has_base:
            power += y[o] * w[pack.out_index[o]]
        else:
            power += y[o] * v[pack.out_index[o]]
    return power


def controller_drive_power(pack, ctx, F, t, x, v, lam):
    """The outputs' power y b . v (W): drive work in the energy balance (the chains evaluated at x)."""
    u = input_values(pack, ctx, F, x, v)[0]
    return output_power(pack, ctx, output_values(pack, u, v), v)


@njit(cache=True)
def law_inputs(pack, ctx, F, x, v):
    evaluate_chains(ctx.chains, x, F, 2)
    return input_values(pack, ctx, F, x, v)


def law_terms(law: ControllerLaw, pack: Controllers, ctx, F, x, v, t, coef_c, coef_k, load_factor,
              want_matrix, res, matrix) -> None:
    """Add a Python law's outputs to the residual ``res`` and the Newton ``matrix`` (as the
    compiled outputs, :func:`apply_outputs`, with J = dy/du by central differences of the
    law, steps 1e-6 max(1, |u_i|))."""
    u, cols, dx, dv, count = law_inputs(pack, ctx, F, x, v)
    y = law(t, u)
    J = np.zeros((y.size, u.size))
    if want_matrix:
        for i in range(u.size):
            h = 1e-6 * max(1.0, abs(float(u[i])))
            up, um = u.copy(), u.copy()
            up[i] += h
            um[i] -= h
            J[:, i] = (law(t, up) - law(t, um)) / (2.0 * h)
    apply_outputs(pack, ctx, y, J, cols, dx, dv, count, coef_c, coef_k, load_factor, want_matrix, res, matrix.ab,
                  matrix.brow, matrix.bcol, matrix.bb)


def law_power(law: ControllerLaw, pack: Controllers, ctx, F, x, v, t) -> float:
    """A Python law's outputs' power sum_o y_o b_o . v (W): drive work in the energy balance."""
    u = law_inputs(pack, ctx, F, x, v)[0]
    return float(output_power(pack, ctx, law(t, u), v))


def controller_bandwidth(system, layout) -> int:
    """Half-bandwidth the controllers' entries need off the border: an output's row (a joint
    angle's, or theta's without a border) and the columns its inputs read through D, or the
    controllers' columns."""
    width = 1
    linear = pack_controllers(system, layout)
    if linear is not None:
        width = _coupling_width(linear, layout, linear.D)
    for law in getattr(system, "controllers", ()):
        if isinstance(law, ControllerLaw):
            pack = law_pack(system, layout, law)
            width = max(width, _coupling_width(pack, layout, np.ones_like(pack.D)))
    return width


def _coupling_width(pack, layout, J) -> int:
    """The half-bandwidth of an output row's entries off the border (J: which outputs read which inputs)."""
    zx = layout.z_of_x
    border = layout.border
    width = 1
    where = pack.gauges[0]
    for o in range(pack.D.shape[0]):
        if pack.out_kind[o] == OutputKind.BASE_TORQUE:
            continue  # the base's rows are in the border
        zr = int(zx[pack.out_index[o]])
        reads = [int(zx[pack.x0 + k]) for k in range(pack.A.shape[0]) if pack.C[o, k] != 0.0]
        for i in range(J.shape[1]):
            if J[o, i] == 0.0:
                continue
            a, b = pack.starts[i, 0], pack.starts[i + 1, 0]
            if pack.form[i] in (InputForm.POLYNOMIAL, InputForm.TIP_DEFLECTION, InputForm.BASE_ROTATION):
                reads += [int(zx[c]) for c in pack.cols[a:b]]
            elif pack.form[i] == InputForm.ANCF_STRAIN:
                reads += [int(zx[where[pack.axis[i], 1] + j]) for j in range(16)]
        for zc in reads:
            if zr >= border and zc >= border:
                width = max(width, abs(zr - zc))
    return width


KIND = terms.register(Controllers, pack_controllers, controller_equations, drive_power=controller_drive_power,
                      bandwidth=controller_bandwidth)
