"""Natural frequencies of the hub-beam system linearised about an equilibrium.

The linearised constrained system M dx'' + K dx = 0 with A dx = 0 is reduced to the
null space N of the constraint Jacobian A (scipy.linalg.null_space), and the
generalized eigenproblem (N^T K N) v = omega^2 (N^T M N) v is solved with scipy's
symmetric solver (eigh) when the reduced stiffness is symmetric, with eig otherwise
(a fixed-direction tip moment makes the load stiffness non-symmetric).
Rigid-body modes are left out: with a free hub exactly one (the rotation of hub and
beam about j0). For a straight beam its frequency is zero to round-off; about a bent
equilibrium the discrete model gives it a small non-zero frequency, because the twist
relative to a fixed chart that a rigid rotation needs is not a cubic along a bent element
(the paper's Cardan-angle element shares this); it vanishes under mesh refinement
(tests/solvers/test_modal.py) and is reported as ``rigid_frequencies_hz`` (sqrt(|omega^2|) / 2 pi:
for a straight beam round-off gives omega^2 either sign, never a negative frequency).

Mode shapes are mass-normalised: with x = x_s + u eta the kinetic energy is eta'^2 / 2 (J),
u^H M u = 1; a complex shape (the gyroscopic modes about a rotating state) is turned in
phase so that its largest entry is real and positive, a real one so that it is positive.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import eig, eigh, null_space

from hubbeam.numerics import central_difference_jacobian, relative_steps
from hubbeam.solvers.static import StaticSolution
from hubbeam.system.multibody import MultibodySystem


@dataclass
class Modes:
    """Natural frequencies (Hz, ascending), mode shapes (columns over x) and rigid-mode count."""

    frequencies_hz: np.ndarray
    shapes: np.ndarray
    rigid_frequencies_hz: np.ndarray

    @property
    def rigid_modes(self) -> int:
        return int(self.rigid_frequencies_hz.shape[0])


def modal_analysis(
    system: MultibodySystem, equilibrium: StaticSolution, count: int = 6, free_hub: bool | None = None,
    rigid_tol_hz: float = 1e-3,
) -> Modes:
    """Lowest ``count`` elastic natural frequencies about ``equilibrium``.

    ``free_hub`` (default: the system's motion is "free") releases the hub angle so the
    rigid rotation of hub and beams is a zero mode, which is left out unless the hub's torque
    law has a stiffness (a PD law); modes below ``rigid_tol_hz`` are left out as rigid in any case.
    """
    if free_hub is None:
        free_hub = system.motion == "free"
    K, M, A = system.linearised(
        equilibrium.x, equilibrium.multipliers, equilibrium.chart, equilibrium.load_factor, held=not free_hub
    )
    N = null_space(A)
    Kr = N.T @ K @ N
    Mr = N.T @ M @ N
    asym = np.max(np.abs(Kr - Kr.T)) / max(np.max(np.abs(Kr)), 1e-300)
    if asym < 1e-9:
        w2, V = eigh(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T))
    else:
        w2, V = eig(Kr, Mr)
        order = np.argsort(w2.real)
        w2, V = w2.real[order], V.real[:, order]
    f = np.sqrt(np.abs(w2)) * np.sign(w2) / (2.0 * np.pi)
    rigid = np.abs(f) < rigid_tol_hz
    if free_hub and system.hub.torque(0.0, equilibrium.x[system.theta_index], 0.0)[1] == 0.0:
        # the rigid rotation of hub and beams; a torque law with a stiffness (PD, kp > 0) makes
        # it the servo mode, an elastic mode like the others
        rigid[np.argmin(np.abs(f))] = True
    elastic = np.flatnonzero(~rigid)[:count]
    # a rigid mode's omega^2 is zero but for the discretisation (about a bent state) and
    # round-off, of either sign: its frequency is reported as sqrt(|omega^2|) / 2 pi, never negative
    return Modes(f[elastic], _normalised(N @ V[:, elastic], M), np.abs(f[rigid]))


def rotating_matrices(system: MultibodySystem, x_s, lam, F, omega: float, held: bool = True):
    """(M, G, K, A) about the steadily rotating state x_s (multipliers ``lam`` of the layout with
    the hub ``held``, charts F, hub speed omega in rad/s), in the co-rotating coordinates of
    :func:`rotating_modal_analysis`: M the system's mass matrix (exact), G the gyroscopic,
    Coriolis and drag terms, K the elastic, centrifugal and constraint terms (central
    differences of the system's residual), A the constraint Jacobian."""
    zx = system.layout_for(held).z_of_x

    def forces(x, v, a):
        res = system.equations(x, v, a, lam, F, 0.0, 0.0, 0.0, 1.0, 1.0, want_matrix=False, held=held)[0]
        return res[zx]

    def generator(y):
        return system.steady_rotation_rates(y, F, 1.0)[0]

    def steady_rates(y):
        return omega * generator(y), system.steady_rotation_rates(y, F, omega)[1]

    v_s, a_s = steady_rates(x_s)
    zero, unit = np.zeros(x_s.shape[0]), relative_steps(np.zeros(x_s.shape[0]))
    K = central_difference_jacobian(lambda y: forces(y, *steady_rates(y)), x_s, relative_steps(x_s))
    G = central_difference_jacobian(
        lambda e: forces(x_s, v_s + e, a_s + 2.0 * omega * _directional(generator, x_s, e)), zero, unit)
    Mz = system.equations(x_s, v_s, a_s, lam, F, 0.0, 1.0, 0.0, 0.0, 1.0, held=held)[1].to_dense()
    return Mz[np.ix_(zx, zx)], G, K, system.constraint_jacobian(x_s, F, held=held)


def rotating_modal_analysis(system: MultibodySystem, steady: StaticSolution, omega: float, count: int = 6,
                            include_damping: bool = False) -> Modes:
    """Lowest ``count`` natural frequencies (Hz) about the state that turns steadily with the
    hub at theta' = omega (rad/s), ``steady`` from ``solve_static(system, spin=omega)``.

    Co-rotating description: x(t) = G(omega t) y(t), G the rigid rotation of the whole system
    about the axis (a symmetry of the equations), so y obeys the time-invariant
    r(y, omega Xi(y) + y', omega^2 a_r(y) + 2 omega (dXi/dy) y' + y'') = 0 with Xi the
    rotation's generator (``steady_rotation_rates``). Linearised at y = y_s:
    M dy'' + G dy' + K dy = 0 with A dy = 0 (hub held; the drive is theta_y = 0), where K
    holds the elastic, centrifugal (softening and pre-stress) and constraint terms, G the
    gyroscopic (Coriolis) terms. M is the system's mass matrix (exact); K and G are central
    differences of the system's own residual (independent of how the residual was derived):
    the compiled equations give neither the stiffness of the rotary inertia's steady-rotation
    forces nor the gyroscopic matrix. The quadratic eigenproblem is solved in
    state space on the null space of A; the frequencies are |Im s| / (2 pi).
    ``include_damping``: keep the drag's and the beams' structural damping's velocity terms (then the modes are damped).
    """
    if not include_damping:
        system = system.without_damping()
    M, G, K, A = rotating_matrices(system, steady.x, steady.multipliers, steady.chart, omega)
    N = null_space(A)
    Mr, Gr, Kr = (N.T @ X @ N for X in (M, G, K))
    n = Mr.shape[0]
    Minv = np.linalg.inv(0.5 * (Mr + Mr.T))
    state = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ Kr, -Minv @ Gr]])
    s, V = eig(state)
    keep = np.flatnonzero(s.imag > 1e-9)
    order = keep[np.argsort(np.abs(s[keep].imag))]
    f = np.abs(s[order].imag) / (2.0 * np.pi)
    shapes = _normalised(N @ V[:n, order[:count]], M)
    return Modes(f[:count], shapes, np.array([]))


def _normalised(shapes: np.ndarray, M: np.ndarray) -> np.ndarray:
    """Columns scaled to u^H M u = 1, each turned so that its largest entry is real and positive."""
    out = np.array(shapes, dtype=complex if np.iscomplexobj(shapes) else float)
    for i in range(out.shape[1]):
        u = out[:, i]
        big = u[np.argmax(np.abs(u))]
        mass = float(np.real(np.conj(u) @ (0.5 * (M + M.T)) @ u))
        out[:, i] = u * (np.abs(big) / big) / np.sqrt(max(mass, 1e-300))
    return out


def _directional(fun, x, e, h=1e-6):
    """(d fun / dx) e by a central difference (fun is smooth; affine for ANCF)."""
    size = max(np.max(np.abs(e)), 1e-300)
    return (fun(x + (h / size) * e) - fun(x - (h / size) * e)) * (size / (2.0 * h))
