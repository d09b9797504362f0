"""Static equilibrium by Newton's method with load stepping (hub held at theta = 0).

The applied loads (gravity, tip force and moment) grow linearly with a load factor from
0 to 1 in ``load_steps`` equal steps. Each step starts from the previous equilibrium;
a step whose Newton iteration does not converge is halved (up to ``max_cuts`` times)
before the solver gives up with a message naming the load step and the residual.
After every converged step the rotation chart is replaced when a tangent has come
within 60 degrees of its singular direction (see :mod:`hubbeam.elements.ancf.chart`).

Free joint angles (:mod:`hubbeam.system.joints`) have no stiffness of their own where the
loads that hold them vanish: a pendulum lying level under gravity, a hinged blade before the
centrifugal tension builds up. Newton's matrix is then singular along the hinge. For systems
with joints every iteration adds a relaxation r to each free joint angle's diagonal, r = |T| /
0.2 rad (T the torque left unbalanced about the hinge: the residual's forces along the rigid
rotation of the joint's beams about it, plus a floor of 1e-9 of the loads' torque), so a
joint with no stiffness turns by at most about 0.2 rad per iteration, like a damped descent
towards a stable equilibrium (the hanging one), while r vanishes with T and the last
iterations are Newton's. The increment test stays valid: an increment below the
tolerance with r of that size means T is below the tolerance times the joint's stiffness.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.linalg import LinAlgError

from hubbeam.errors import ChartSingularityError, ConvergenceError
from hubbeam.solvers.newton_control import (KAPPA, MatrixUpdate, NewtonAction, borrowed_rate, newton_decide,
                                            reuse_state)
from hubbeam.system.multibody import MultibodySystem

#: replace the chart when min(1 + d.tau) falls below this (tau within 60 deg of -d)
CHART_SWITCH_MARGIN = 0.5


@dataclass
class StaticSolution:
    """Equilibrium: coordinates x, multipliers lambda (N, N m) of the held layout, charts F."""

    x: np.ndarray
    multipliers: np.ndarray
    chart: np.ndarray
    load_factor: float
    newton_iterations: int
    load_steps: int
    chart_switches: int



def replace_chart_if_needed(system: MultibodySystem, x: np.ndarray, F: np.ndarray, force: bool = False):
    """(x, F, switched): x re-expressed in a better chart when the current one is near singular."""
    if not force and system.chart_margin(x, F) >= CHART_SWITCH_MARGIN:
        return x, F, False
    F_new = system.better_chart(x, F, None if force else CHART_SWITCH_MARGIN)
    return system.remap(x, F, F_new), F_new, True


#: a joint angle without stiffness turns by at most about this much per iteration (rad)
RELAXED_STEP = 0.2
#: the relaxation's floor, a share of the loads' torque per radian (keeps the matrix regular)
RELAXATION_FLOOR = 1e-9


def unbalanced_hinge_torques(system, x, F, res) -> list[tuple[int, float]]:
    """(z row, torque T (N m)) of every free joint angle: T = g . r, the static residual's
    forces r on x along the joint's rigid rotation g (its beam and the beams hanging on it
    turning with it about the axis: :meth:`MultibodySystem.hinge_generators`), the torque left
    unbalanced about the hinge whatever the clamps' multipliers are yet."""
    layout = system.layout_for(True, static=True)
    free = set(int(z) for z in joint_rows(system))
    forces = res[layout.z_of_x]
    out = []
    for _, c, g in system.hinge_generators(x, F):
        z = int(layout.z_of_x[c])
        if z in free:
            out.append((z, float(g @ forces)))
    return out


def joint_rows(system) -> np.ndarray:
    """The z rows (static layout) of the free joint angles (those not locked by a latch)."""
    layout = system.layout_for(True, static=True)
    rows = [layout.z_of_x[layout.joint_x(k).start + i] for k, b in enumerate(system.beams)
            if b.mount.joint is not None and b.mount.joint.locked_at is None for i in range(b.mount.joint.count)]
    return np.array(rows, dtype=np.int64)


def free_joints(system) -> str:
    """'; no equilibrium holds the free joint(s) NAME (axes), ...' for a system with free joints, else ''."""
    named = [f"{b.name} ({', '.join(b.mount.joint.names)})" for b in system.beams
             if b.mount.joint is not None and b.mount.joint.locked_at is None]
    if not named:
        return ""
    return f"; or no equilibrium holds the free joint{'s' if len(named) > 1 else ''} {', '.join(named)}"


def _newton(system, x, mu, F, factor, tol_force, tol_step, max_iter, spin=0.0, relax=0.0):
    """Full Newton iterations at one load factor; returns (x, mu, iterations, residual norm)
    or raises. Converged when the shared controller (:func:`newton_decide`, matrix rebuilt
    every iteration) accepts the increment (relative to the length scale) or the residual is
    below ``tol_force`` (N). ``relax`` (N m/rad): the relaxation's floor on the free joint
    angles (module docstring; 0: none)."""
    layout = system.layout_for(True, static=True)
    scale_x = max(system.length_scale, 1e-12)
    reuse = reuse_state()
    rate = borrowed_rate()
    norm = np.inf
    relaxing = relax > 0.0
    for it in range(1, max_iter + 1):
        res, matrix = system.static_equations(x, mu, F, factor, spin=spin)
        norm = np.max(np.abs(res))
        if relaxing:
            for z, torque in unbalanced_hinge_torques(system, x, F, res):
                matrix.add(z, z, relax + abs(torque) / RELAXED_STEP)
        try:
            dz = matrix.factorise().solve(-res)
        except (LinAlgError, ValueError) as exc:
            raise ConvergenceError(f"singular Newton matrix ({exc})") from exc
        if not np.all(np.isfinite(dz)):
            raise ConvergenceError("non-finite Newton increment")
        dx, dmu = layout.split_z(dz)
        x = x + dx
        mu = mu + dmu
        step = np.max(np.abs(dx[layout.beams_x])) / scale_x
        action = newton_decide(step, np.inf, it, False, int(MatrixUpdate.ITERATION), 1.0, max_iter, 0, tol_step,
                               reuse, rate, KAPPA, 0, False)
        if norm <= tol_force or action == NewtonAction.CONVERGED:
            return x, mu, it, norm
    raise ConvergenceError(f"residual {norm:.3e} N after {max_iter} iterations")


def solve_static(
    system: MultibodySystem,
    load_steps: int = 20,
    max_iterations: int = 30,
    max_cuts: int = 8,
    x0: np.ndarray | None = None,
    chart: np.ndarray | None = None,
    spin: float | None = None,
) -> StaticSolution:
    """Equilibrium under the system's loads with the hub held at theta = 0.

    ``spin`` (rad/s): solve instead for the state that turns steadily with the hub at
    theta' = spin, in the hub frame (centrifugal load and drag); the solution is expressed
    in the axis chart (also for spin = 0).

    Raises :class:`ConvergenceError` (with the last equilibrium in ``partial``) when a
    load step cannot be completed even after ``max_cuts`` halvings.
    """
    if x0 is None:
        x, F = system.initial_state(0.0)
    else:
        x, F = np.array(x0, dtype=float), np.array(chart, dtype=float)
    if spin is not None:
        x, F = system.axis_chart(x, F)
    spin = spin or 0.0
    mu = np.zeros(system.n_constraints(held=True, static=True))
    # force and step tolerances: relative to the loads, above the round-off floor of EA
    f_ref = system.static_force_scale(x, F, spin)
    tol_force = 1e-9 * f_ref + 1e-13 * max(b.section.stiffness[0] for b in system.beams)
    tol_step = 1e-12
    # free joints: the relaxation's floor, a small share of the loads' torque per radian
    relax = RELAXATION_FLOOR * f_ref * system.length_scale if joint_rows(system).size else 0.0
    factor = 0.0
    dfac = 1.0 / load_steps
    iterations = 0
    switches = 0
    steps = 0
    cuts = 0
    while factor < 1.0 - 1e-14:
        target = min(1.0, factor + dfac)
        try:
            x_new, mu_new, it, _ = _newton(system, x, mu, F, target, tol_force, tol_step, max_iterations, spin,
                                           relax)
        except (ConvergenceError, ChartSingularityError) as exc:
            if cuts >= max_cuts:
                partial = StaticSolution(x, system.constraint_scale * mu, F, factor, iterations, steps, switches)
                raise ConvergenceError(
                    f"static equilibrium failed at load step {steps + 1} (load factor {target:.4g}, "
                    f"last equilibrium at {factor:.4g}): {exc}. Try more load steps "
                    f"(--set analysis.load_steps={4 * load_steps}) or more elements{free_joints(system)}.",
                    partial=partial,
                ) from exc
            dfac /= 2.0
            cuts += 1
            continue
        iterations += it
        steps += 1
        x, mu, factor = x_new, mu_new, target
        x, F, switched = replace_chart_if_needed(system, x, F)
        if switched and spin:
            raise ConvergenceError(
                f"the steadily rotating beam bent to within 60 deg of the hub axis at load factor {factor:.4g}; "
                "a steady state that far from the plane of rotation is not supported",
                partial=StaticSolution(x, system.constraint_scale * mu, F, factor, iterations, steps, switches))
        if switched:
            switches += 1
            x, mu, it, _ = _newton(system, x, mu, F, factor, tol_force, tol_step, max_iterations, spin, relax)
            iterations += it
        if it <= 4 and cuts:
            dfac = min(2.0 * dfac, 1.0 / load_steps)
    return StaticSolution(x, system.constraint_scale * mu, F, factor, iterations, steps, switches)
