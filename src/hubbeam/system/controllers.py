"""Linear time-invariant controllers in the loop: the kind "controllers".

A controller (:class:`LinearController`) reads m sensor inputs u and applies p torques y:

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
on the controller's own columns and -coef_k B du/dx - coef_c B du/dv on the coordinates the
inputs read; its output adds -coef_k y on the rows of the coordinates it drives, with
-coef_c C on the controller's columns and -coef_k D du/dx - coef_c D du/dv. This is exact:
generalized-alpha's update of the rates, v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1}
with its algorithmic acceleration a, is the generalized-alpha method for first-order systems
(Jansen, Whiting and Hulbert 2000) applied to s' = A s + B u, second-order accurate, with the
equations enforced at t_{n+1} as the structure's; no extra approximation enters.

**Inputs** (:data:`INPUTS`): the hub angle theta, its rate (``hub_angle`` with ``_rate``) and
the hub's angular velocity theta' (``hub_angular_velocity``). A ``_rate`` of the angular
velocity would read the acceleration: not allowed (:data:`ACCELERATION_RATES`).
**Outputs** (:data:`OUTPUTS`): ``hub_torque``, a torque on a free hub's angle about -j_h in
the sense of theta, added to its torque law. Its power y theta' is drive work in the energy
balance (:func:`controller_drive_power`).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.system import terms
from hubbeam.system.assembly import add_entry


class ControllerInput(enum.IntEnum):
    """What an input reads (the members are what compiled code compares)."""

    HUB_ANGLE = 0  # theta (rad)
    HUB_SPEED = 1  # theta' (rad/s)


class ControllerOutput(enum.IntEnum):
    """Where an output acts."""

    HUB_TORQUE = 0  # N m on theta (free hub)


#: (sensor kind, is a ``_rate``) -> the input it gives
INPUTS = {
    ("hub_angle", False): ControllerInput.HUB_ANGLE,
    ("hub_angle", True): ControllerInput.HUB_SPEED,
    ("hub_angular_velocity", False): ControllerInput.HUB_SPEED,
}
#: sensor kinds whose time derivative reads the accelerations (or the multipliers)
ACCELERATION_RATES = frozenset({"hub_angular_velocity", "hub_torque", "applied_torque", "base_velocity",
                                "base_angular_velocity", "linear_momentum", "system_angular_momentum",
                                "angular_momentum", "base_torque", "energy"})
#: output names -> where they act
OUTPUTS = {"hub_torque": ControllerOutput.HUB_TORQUE}


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
        object.__setattr__(self, "inputs", tuple(ControllerInput(i) for i in self.inputs))
        object.__setattr__(self, "outputs", tuple(ControllerOutput(o) for o in self.outputs))

    @property
    def states(self) -> int:
        return self.A.shape[0]


class Controllers(NamedTuple):
    """Every controller of a system as one block-diagonal controller (their outputs add)."""

    x0: int  # the first controller coordinate in x
    A: np.ndarray  # (n, n)
    B: np.ndarray  # (n, m)
    C: np.ndarray  # (p, n)
    D: np.ndarray  # (p, m)
    inputs: np.ndarray  # int64 (m,): ControllerInput
    outputs: np.ndarray  # int64 (p,): ControllerOutput


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
    inputs = [int(u) for c in controllers for u in c.inputs]
    outputs = [int(y) for c in controllers for y in c.outputs]
    return A.reshape(n, n), B, C, D, inputs, outputs


def pack_controllers(system, layout) -> Controllers | None:
    controllers = getattr(system, "controllers", ())
    if not controllers:
        return None
    A, B, C, D, inputs, outputs = combined(controllers)
    return Controllers(layout.controllers_x.start, np.ascontiguousarray(A), B, C, D,
                       np.array(inputs, dtype=np.int64), np.array(outputs, dtype=np.int64))


@njit(cache=True)
def input_values(pack, theta, omega):
    """(u, du/dtheta, du/dtheta') of the inputs (compiled where called)."""
    m = pack.inputs.shape[0]
    u, du_x, du_v = np.zeros(m), np.zeros(m), np.zeros(m)
    for i in range(m):
        if pack.inputs[i] == ControllerInput.HUB_ANGLE:
            u[i] = theta
            du_x[i] = 1.0
        else:
            u[i] = omega
            du_v[i] = 1.0
    return u, du_x, du_v


def hub_torque(pack: Controllers, theta: float, omega: float, rates: np.ndarray) -> float:
    """The controllers' torque on the hub (N m) at theta (rad), theta' (rad/s) and their states
    ``rates`` (the rates of their coordinates)."""
    u = input_values(pack, theta, omega)[0]
    y = pack.C @ rates + pack.D @ u
    return float(np.sum(y[pack.outputs == ControllerOutput.HUB_TORQUE]))


def controller_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor,
                         exact_stiffness, want_matrix, res, ab, brow, bcol, bb):
    """The controllers' rows coef_k (w'' - A w' - B u) and their outputs' -coef_k load_factor y
    on the driven coordinates' rows (module docstring), with their Newton-matrix entries."""
    zx, ku = ctx.z_of_x, ctx.ku
    z_theta = zx[ctx.theta]
    u, du_x, du_v = input_values(pack, x[ctx.theta], v[ctx.theta])
    A, B, C, D, x0 = pack.A, pack.B, pack.C, pack.D, pack.x0
    n, m, p = A.shape[0], B.shape[1], D.shape[0]
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
            g = 0.0
            for i in range(m):
                g += B[j, i] * (coef_k * du_x[i] + coef_c * du_v[i])
            add_entry(ab, brow, bcol, bb, ku, zw, z_theta, -g)
    for o in range(p):
        y = 0.0
        for k in range(n):
            y += C[o, k] * v[x0 + k]
        for i in range(m):
            y += D[o, i] * u[i]
        # every output is ControllerOutput.HUB_TORQUE: on theta's row
        res[z_theta] -= coef_k * load_factor * y
        if want_matrix:
            for k in range(n):
                add_entry(ab, brow, bcol, bb, ku, z_theta, zx[x0 + k], -load_factor * coef_c * C[o, k])
            g = 0.0
            for i in range(m):
                g += D[o, i] * (coef_k * du_x[i] + coef_c * du_v[i])
            add_entry(ab, brow, bcol, bb, ku, z_theta, z_theta, -load_factor * g)
    return 2.0, 0.0


def controller_drive_power(pack, ctx, F, t, x, v, lam):
    """The outputs' power y theta' (W): drive work in the energy balance."""
    u, _, _ = input_values(pack, x[ctx.theta], v[ctx.theta])
    A, C, D, x0 = pack.A, pack.C, pack.D, pack.x0
    power = 0.0
    for o in range(D.shape[0]):
        y = 0.0
        for k in range(A.shape[0]):
            y += C[o, k] * v[x0 + k]
        for i in range(D.shape[1]):
            y += D[o, i] * u[i]
        power += y * v[ctx.theta]
    return power


KIND = terms.register(Controllers, pack_controllers, controller_equations, drive_power=controller_drive_power)
