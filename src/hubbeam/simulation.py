"""Time integration of a scenario: generalized-alpha steps, sensors sampled at output times."""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from hubbeam.elements.ancf.chart import frame_from_director, remap_chart
from hubbeam.sensors import measure
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers.errors import ComputationError, ConvergenceError
from hubbeam.system.beam import NODE_DOFS, ChartSingularityError
from hubbeam.system.model import HubBeamSystem

#: below this chart margin (1 + d.tau) the run stops: a tangent within 60 deg of the chart's singular direction
CHART_LIMIT = 0.5


@dataclass
class Trajectory:
    """Sensor records at output times, and the run's statistics."""

    times: list = field(default_factory=list)
    records: dict = field(default_factory=dict)
    steps: int = 0
    newton_iterations: int = 0
    wall_time_s: float = 0.0

    def append(self, t, values):
        self.times.append(t)
        for name, val in values.items():
            self.records.setdefault(name, []).append(val)


def dynamic_chart(system: HubBeamSystem, x: np.ndarray, F: np.ndarray):
    """Re-express the initial state in the chart d = -j0 for a turning hub.

    The beam stays near the horizontal plane while the hub sweeps it through every
    horizontal direction; with d = -j0 every horizontal tangent is 90 deg from the
    singular direction (straight up), so no chart replacement is needed in such runs."""
    if system.motion == "fixed":
        return x, F
    beam = system.beam
    F_new = frame_from_director(np.array([0.0, -1.0, 0.0]), hint=np.array([1.0, 0.0, 0.0]))
    q = x[1:]
    nodes = remap_chart(q.reshape(beam.nodes, NODE_DOFS), beam.node_tangent_rates(q), F, F_new)
    return np.concatenate([[x[0]], nodes.ravel()]), F_new


def simulate(system: HubBeamSystem, sensors, t_end: float, dt: float, spectral_radius: float = 0.8,
             output_dt: float | None = None, progress=None) -> Trajectory:
    """Integrate from rest (the straight clamped beam at theta = 0) to t_end.

    ``progress(t)`` is called after every step when given. On failure a ComputationError
    names the time and step and carries the trajectory so far in ``partial``.
    """
    if system.motion == "prescribed" and system.drive(0.0)[1] != 0.0:
        raise ComputationError(
            f"hub.drive.profile = {system.drive.kind!r} starts at omega = {system.drive(0.0)[1]:g} rad/s at t = 0, "
            "but runs start from rest and a start in steady rotation is not supported yet; use 'exponential' "
            "or 'spin_up', which start from rest"
        )
    params = ga.AlphaParameters.from_spectral_radius(spectral_radius)
    x0, F0 = system.initial_state(0.0)
    x0, F0 = dynamic_chart(system, x0, F0)
    state = ga.init(system, x0, F0)
    n_steps = int(round(t_end / dt))
    every = max(1, int(round((output_dt or dt) / dt)))
    traj = Trajectory()
    work = {"dissipated": 0.0, "drive": 0.0}

    def power(st):
        p_d = system.beam.drag(st.v[1:], *system.damping)[0]
        torque = (-st.lam[6] if st.lam.shape[0] > 6 else 0.0) + system.hub_torque
        return p_d, torque * st.v[0]

    def record(st):
        traj.append(st.t, {s.name: measure(s, system, st, work) for s in sensors})

    record(state)
    p_prev = power(state)
    start = time.perf_counter()
    for k in range(1, n_steps + 1):
        try:
            state_new, its = ga.step(system, state, dt, params)
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
        if system.beam.chart_margin(state.x[1:], state.chart) < CHART_LIMIT:
            traj.wall_time_s = time.perf_counter() - start
            raise ComputationError(
                f"at t = {state.t:.6g} s (step {k}) a beam tangent came within 60 deg of straight up, the "
                "singular direction of the rotation chart; replacing the chart during time integration is "
                "not supported yet", partial=traj)
        if progress is not None:
            progress(state.t)
    traj.wall_time_s = time.perf_counter() - start
    return traj
