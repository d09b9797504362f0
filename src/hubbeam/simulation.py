"""Time integration of a scenario: generalized-alpha steps, sensors sampled at output times."""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from hubbeam.sensors import measure
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers.errors import ComputationError, ConvergenceError
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import ChartSingularityError
from hubbeam.system.model import HubSystem

#: below this chart margin (1 + d.tau) the chart is replaced: a tangent within 60 deg of its singular direction
CHART_LIMIT = 0.5


@dataclass
class Trajectory:
    """Sensor records at output times, and the run's statistics."""

    times: list = field(default_factory=list)
    records: dict = field(default_factory=dict)
    steps: int = 0
    newton_iterations: int = 0
    chart_switches: int = 0
    wall_time_s: float = 0.0

    def append(self, t, values):
        self.times.append(t)
        for name, val in values.items():
            self.records.setdefault(name, []).append(val)


def change_chart(system: HubSystem, state: ga.AlphaState, F_new: np.ndarray, eps: float = 1e-4) -> ga.AlphaState:
    """The integrator state re-expressed in chart F_new.

    The remap x -> g(x) changes only theta_1 and theta_1' (by functions of the tangent),
    so velocities map by the Jacobian of g and accelerations pick up its second
    derivative along v: v' = g_x v, xdd' = g_x xdd + v^T g_xx v (both by central
    differences of g along v and xdd; g is smooth away from the chart singularities).
    The algorithmic acceleration a transforms like xdd."""
    F = state.chart

    def g(x):
        return system.remap(x, F, F_new)

    x, v = state.x, state.v
    g0, gp, gm = g(x), g(x + eps * v), g(x - eps * v)
    v_new = (gp - gm) / (2.0 * eps)
    curvature = (gp - 2.0 * g0 + gm) / eps**2

    def along(u):
        if not np.any(u):
            return np.zeros_like(u)
        scale = eps / max(np.max(np.abs(u)), 1e-300)
        return (g(x + scale * u) - g(x - scale * u)) / (2.0 * scale)

    return replace(state, x=g0, v=v_new, xdd=along(state.xdd) + curvature, a=along(state.a) + curvature, chart=F_new)


def initial_state(system: HubSystem, load_steps: int = 20) -> ga.AlphaState:
    """Where a run starts: at rest in the straight clamped state at theta = 0, or, for a
    drive that already turns at t = 0 (profile 'constant'), in the steadily rotating
    equilibrium (static analysis with the centrifugal load) with its rigid-rotation
    velocities. A turning hub gets the axis chart (see HubSystem.axis_chart)."""
    omega0 = system.drive(0.0)[1] if system.motion == "prescribed" else 0.0
    if omega0:
        try:
            sol = solve_static(system, load_steps=load_steps, spin=omega0)
        except ConvergenceError as exc:
            raise ComputationError(f"the steadily rotating start state (omega = {omega0:g} rad/s) was not found: {exc}") from exc
        v0, _ = system.steady_rotation_rates(sol.x, sol.chart, omega0)
        return ga.init(system, sol.x, sol.chart, v0=v0)
    x0, F0 = system.initial_state(0.0)
    if system.motion != "fixed":
        x0, F0 = system.axis_chart(x0, F0)
    return ga.init(system, x0, F0)


def simulate(system: HubSystem, sensors, t_end: float, dt: float, spectral_radius: float = 0.8,
             output_dt: float | None = None, progress=None, newton: ga.NewtonOptions = ga.NewtonOptions(),
             state: ga.AlphaState | None = None) -> Trajectory:
    """Integrate from ``state`` (default: :func:`initial_state`) to t_end.

    ``progress(t)`` is called after every step when given. On failure a ComputationError
    names the time and step and carries the trajectory so far in ``partial``. When a beam
    tangent comes within 60 deg of the chart's singular direction the state is moved to a
    better chart (counted in ``Trajectory.chart_switches``).
    """
    params = ga.AlphaParameters.from_spectral_radius(spectral_radius)
    if state is None:
        state = initial_state(system)
    n_steps = int(round((t_end - state.t) / dt))
    every = max(1, int(round((output_dt or dt) / dt)))
    traj = Trajectory()
    work = {"dissipated": 0.0, "drive": 0.0}

    def power(st):
        p_d = system.dissipated_power(st.x, st.v, st.chart)
        torque = system.drive_torque(st.lam) + system.hub_torque
        return p_d, torque * st.v[0]

    def record(st):
        traj.append(st.t, {s.name: measure(s, system, st, work) for s in sensors})

    record(state)
    p_prev = power(state)
    matrix = None
    start = time.perf_counter()
    for k in range(1, n_steps + 1):
        try:
            state_new, its, matrix = ga.step(system, state, dt, params, newton, matrix)
        except (ConvergenceError, ChartSingularityError) as exc:
            traj.wall_time_s = time.perf_counter() - start
            raise ComputationError(
                f"time integration failed at t = {state.t + dt:.6g} s (step {k}): {exc}. "
                f"Try a smaller analysis.dt (now {dt:g} s), more beam.elements or a smaller analysis.spectral_radius.",
                partial=traj,
            ) from exc
        state = state_new
        traj.steps = k
        traj.newton_iterations += its
        p_new = power(state)
        work["dissipated"] += 0.5 * dt * (p_prev[0] + p_new[0])
        work["drive"] += 0.5 * dt * (p_prev[1] + p_new[1])
        p_prev = p_new
        if k % every == 0 or k == n_steps:
            record(state)
        if system.chart_margin(state.x, state.chart) < CHART_LIMIT:
            state = change_chart(system, state, system.better_chart(state.x))
            traj.chart_switches += 1
        if progress is not None:
            progress(state.t)
    traj.wall_time_s = time.perf_counter() - start
    return traj
