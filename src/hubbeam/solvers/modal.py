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

from hubbeam.numerics import central_difference_jacobian, coupled_groups, relative_steps
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


def band_column_groups(z_of_x, bandwidth: int, border: int) -> list[np.ndarray]:
    """The columns of a Jacobian over x grouped so that no two columns of a group reach a
    common row of the system's bordered band (:class:`~hubbeam.system.assembly.BorderedBandMatrix`:
    z-entries farther apart than ``bandwidth`` do not couple, except through the first
    ``border`` entries of z): one residual evaluation then gives a whole group's columns, every
    row but the border's. A column in the border is a group of its own."""
    z_of_x = np.asarray(z_of_x)
    colours = 2 * int(bandwidth) + 1
    groups = [np.array([i]) for i in np.flatnonzero(z_of_x < border)]
    inner = np.flatnonzero(z_of_x >= border)
    for c in range(colours):
        members = inner[z_of_x[inner] % colours == c]
        if members.size:
            groups.append(members)
    return groups


def grouped_central_differences(fun, x: np.ndarray, steps: np.ndarray, groups, rows_of) -> np.ndarray:
    """d fun / dx by central differences, one pair of evaluations per group of columns
    (:func:`band_column_groups`): column i of a group is read on the rows ``rows_of(i)`` (the
    rows it can reach; the others stay zero), so the columns of a group must reach disjoint rows."""
    x = np.asarray(x, dtype=float)
    jac = None
    for group in groups:
        e = np.zeros_like(x)
        e[group] = steps[group]
        diff = np.asarray(fun(x + e)) - np.asarray(fun(x - e))
        if jac is None:
            jac = np.zeros((diff.shape[0], x.size))
        for i in group:
            rows = rows_of(i)
            jac[rows, i] = diff[rows] / (2.0 * steps[i])
    return jac


def rotating_matrices(system: MultibodySystem, x_s, lam, F, omega: float, held: bool = True, hub_row: bool = True):
    """(M, G, K, A) about the steadily rotating state x_s (multipliers ``lam`` of the layout with
    the hub ``held``, charts F, hub speed omega in rad/s), in the co-rotating coordinates of
    :func:`rotating_modal_analysis`: M the system's mass matrix (exact), G the gyroscopic,
    Coriolis and drag terms, K the elastic, centrifugal and constraint terms (central
    differences of the system's residual), A the constraint Jacobian.

    ``hub_row`` False: the rows of the layout's border (the hub's equation when several beams
    share it) are left zero, and the differences take one pair of residuals per colour of the
    band (:func:`band_column_groups`: 2 x (2 b + 1) + 2 for any number of beams) instead of one
    pair per coordinate. A held hub's modes do not need those rows: the drive constraint
    removes them (the null space of A has no theta)."""
    layout = system.layout_for(held)
    zx = layout.z_of_x

    def forces(x, v, a):
        res = system.equations(x, v, a, lam, F, 0.0, 0.0, 0.0, 1.0, 1.0, want_matrix=False, held=held)[0]
        return res[zx]

    def generator(y):
        return system.steady_rotation_rates(y, F, 1.0)[0]

    def steady_rates(y):
        return omega * generator(y), system.steady_rotation_rates(y, F, omega)[1]

    v_s, a_s = steady_rates(x_s)
    zero, unit = np.zeros(x_s.shape[0]), relative_steps(np.zeros(x_s.shape[0]))
    if hub_row:
        K = central_difference_jacobian(lambda y: forces(y, *steady_rates(y)), x_s, relative_steps(x_s))
        G = central_difference_jacobian(
            lambda e: forces(x_s, v_s + e, a_s + 2.0 * omega * _directional(generator, x_s, e)), zero, unit)
    else:
        band, border = system.bandwidth_for(layout), layout.border
        groups = band_column_groups(zx, band, border)

        def rows_of(i):  # the x-rows column i reaches (all for a border column), the border's left out
            near = (np.abs(zx - zx[i]) <= band) | (zx[i] < border)
            return np.flatnonzero(near & (zx >= border))

        # the steady rates' Jacobians once (each beam's rates depend on its own coordinates only);
        # K needs only the first derivative of the rates at x_s, so the rates linearised there give
        # the same K, and the Coriolis term 2 omega (dXi/dy) e is 2 (dv/dy) e
        n = x_s.shape[0]
        d_rates = grouped_central_differences(lambda y: np.concatenate(system.steady_rotation_rates(y, F, omega)), x_s,
                                              relative_steps(x_s), groups, lambda i: np.concatenate([rows_of(i), n + rows_of(i)]))
        d_v, d_a = d_rates[:n], d_rates[n:]
        K = grouped_central_differences(lambda y: forces(y, v_s + d_v @ (y - x_s), a_s + d_a @ (y - x_s)), x_s,
                                        relative_steps(x_s), groups, rows_of)
        G = grouped_central_differences(lambda e: forces(x_s, v_s + e, a_s + 2.0 * (d_v @ e)), zero, unit, groups, rows_of)
    Mz = system.equations(x_s, v_s, a_s, lam, F, 0.0, 1.0, 0.0, 0.0, 1.0, held=held)[1].to_dense()
    return Mz[np.ix_(zx, zx)], G, K, system.constraint_jacobian(x_s, F, held=held)


def coupled_blocks(A: np.ndarray, *matrices: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """The independent blocks of the linear system ``matrices`` (n x n) with the constraints
    A dx = 0: coordinates that a constraint row fixes alone (a held hub's angle) are left out,
    the others grouped into the connected components of the coupling graph (an entry of any
    matrix, or two coordinates in one constraint row). Returns (coordinates, constraint rows) per
    block, in the order of their first coordinate. A hub held at its drive carrying beams that
    touch nothing but the hub falls apart into one block per beam."""
    A = np.asarray(A)
    n = A.shape[1]
    touched = A != 0.0
    single = touched.sum(axis=1) == 1
    fixed = np.zeros(n, dtype=bool)
    fixed[np.flatnonzero(touched[single].any(axis=0))] = True
    free = np.flatnonzero(~fixed)
    pattern = np.zeros((n, n), dtype=bool)
    for m in matrices:
        pattern |= np.asarray(m) != 0.0
    rows = np.flatnonzero(~single)
    link = touched[rows][:, ~fixed].astype(float)
    pattern = pattern[np.ix_(free, free)] | ((link.T @ link) != 0.0)
    blocks = []
    for group in coupled_groups(pattern):  # free is ascending: the blocks in the order of their first coordinate
        coords = free[group]
        blocks.append((coords, rows[touched[np.ix_(rows, coords)].any(axis=1)]))
    return blocks


def rotating_modal_analysis(system: MultibodySystem, steady: StaticSolution, omega: float, count: int | None = 6,
                            include_damping: bool = False, same: float = 0.0) -> Modes:
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
    forces nor the gyroscopic matrix. The quadratic eigenproblem is solved in state space on
    the null space of A, block by block (:func:`coupled_blocks`: on a held hub every beam is a
    block of its own, so the cost grows with the number of beams, not with its cube); the
    frequencies are |Im s| / (2 pi). ``count`` None: every mode. ``same`` (relative): modes
    beyond ``count`` whose frequency is within ``same`` of the last one kept are kept too, so
    that a repeated frequency (identical beams) is never cut in the middle of its eigenspace.
    ``include_damping``: keep the drag's and the beams' structural damping's velocity terms
    (then the modes are damped).
    """
    if not include_damping:
        system = system.without_damping()
    M, G, K, A = rotating_matrices(system, steady.x, steady.multipliers, steady.chart, omega, hub_row=False)
    freqs, vectors, places = [], [], []
    for coords, rows in coupled_blocks(A, M, G, K):
        N = null_space(A[np.ix_(rows, coords)]) if rows.size else np.eye(coords.size)
        sub = np.ix_(coords, coords)
        Mr, Gr, Kr = (N.T @ X[sub] @ N for X in (M, G, K))
        n = Mr.shape[0]
        if n == 0:
            continue
        Minv = np.linalg.inv(0.5 * (Mr + Mr.T))
        state = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ Kr, -Minv @ Gr]])
        s, V = eig(state)
        keep = np.flatnonzero(s.imag > 1e-9)
        freqs.append(np.abs(s[keep].imag) / (2.0 * np.pi))
        vectors.append(_normalised(N @ V[:n, keep], M[sub]))
        places += [(len(vectors) - 1, j, coords) for j in range(keep.size)]
    if not freqs:
        return Modes(np.array([]), np.zeros((steady.x.shape[0], 0)), np.array([]))
    f = np.concatenate(freqs)
    order = np.argsort(f, kind="stable")
    kept = order.size if count is None else min(count, order.size)
    while kept < order.size and count is not None and f[order[kept]] <= f[order[kept - 1]] * (1.0 + same):
        kept += 1
    order = order[:kept]
    shapes = np.zeros((steady.x.shape[0], order.size), dtype=complex)
    for col, i in enumerate(order):
        block, j, coords = places[i]
        shapes[coords, col] = vectors[block][:, j]
    return Modes(f[order], shapes, np.array([]))


def _normalised(shapes: np.ndarray, M: np.ndarray) -> np.ndarray:
    """Columns scaled to u^H M u = 1, each turned so that its largest entry is real and positive."""
    out = np.array(shapes, dtype=complex if np.iscomplexobj(shapes) else float)
    if not out.shape[1]:
        return out
    big = out[np.argmax(np.abs(out), axis=0), np.arange(out.shape[1])]
    mass = np.real(np.sum(np.conj(out) * ((0.5 * (M + M.T)) @ out), axis=0))
    return out * (np.abs(big) / big) / np.sqrt(np.maximum(mass, 1e-300))


def _directional(fun, x, e, h=1e-6):
    """(d fun / dx) e by a central difference (fun is smooth; affine for ANCF)."""
    size = max(np.max(np.abs(e)), 1e-300)
    return (fun(x + (h / size) * e) - fun(x - (h / size) * e)) * (size / (2.0 * h))
