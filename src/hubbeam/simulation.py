"""Time integration of a scenario: generalized-alpha steps, sensors sampled at output times."""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from decimal import Decimal

import numpy as np

from hubbeam import interrupt
from hubbeam.sensors import prepare_chunk, record_needs
from hubbeam.solvers import compiled_alpha
from hubbeam.solvers.column_update import joint_columns
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers import newton_control as nc
from hubbeam.errors import ChartSingularityError, ComputationError, ConvergenceError
from hubbeam.solvers.static import solve_static
from hubbeam.system.assembly import BorderedBandMatrix
from hubbeam.system.multibody import MultibodySystem

#: below this chart margin (1 + d.tau) the chart is replaced: a tangent within 60 deg of its singular direction
CHART_LIMIT = 0.5


@dataclass
class Trajectory:
    """Sensor records at output times, and the run's statistics; with a state recorder, the
    recorder and its snapshots (:mod:`hubbeam.snapshots`) at the same times."""

    times: list = field(default_factory=list)
    records: dict = field(default_factory=dict)
    recorder: object = None
    snapshots: list = field(default_factory=list)
    steps: int = 0
    newton_iterations: int = 0
    chart_switches: int = 0
    factorisations: int | None = None  # LU factorisations of the iteration matrix (counted by compiled steps)
    wall_time_s: float = 0.0
    #: the scenario the run was made with (set by :func:`hubbeam.api.run`; results check it)
    scenario: object = None
    latches: list = field(default_factory=list)  # the joints' latch events (:class:`hubbeam.system.joints.LatchEvent`)

    def extend(self, times, values, snapshots=None):
        """Add the records at ``times``: ``values`` {sensor name: its values, one per time},
        and the state recorder's ``snapshots`` (one per time) when given."""
        self.times.extend(times)
        for name, vals in values.items():
            self.records.setdefault(name, []).extend(vals)
        if snapshots is not None:
            self.snapshots.extend(snapshots)


@dataclass
class RecordChunk:
    """The records of a chunk of steps as arrays, row i for record i: ``states``, the integrator
    states stacked (an :class:`~hubbeam.solvers.generalized_alpha.AlphaState` whose t is (n,)
    (s) and x, v, xdd, a, lambda are (n, ...), in the one chart of the chunk), the dissipated
    and drive work up to each record (J), and what the compiled steps computed for the whole
    chunk (:meth:`MultibodySystem.record_measures`): ``energies`` = (hub (n, 3), beams (n, beams, 3))
    (J), ``tips`` (n, beams, 3) (m), ``strains`` {gauge: (n,)}. Sensors read it through
    :func:`hubbeam.sensors.prepare_chunk`."""

    states: ga.AlphaState
    dissipated: np.ndarray
    drive: np.ndarray
    energies: tuple | None = None
    tips: np.ndarray | None = None
    strains: dict = field(default_factory=dict)

    @classmethod
    def of_states(cls, records: list) -> RecordChunk | None:
        """The chunk of a list of (state, work) (None for an empty list)."""
        if not records:
            return None
        states = [st for st, _ in records]
        stack = lambda name: np.array([getattr(st, name) for st in states], dtype=float)  # noqa: E731
        return cls(ga.AlphaState(stack("t"), stack("x"), stack("v"), stack("xdd"), stack("a"), stack("lam"),
                                 states[0].chart),
                   np.array([w["dissipated"] for _, w in records], dtype=float),
                   np.array([w["drive"] for _, w in records], dtype=float))

    def __len__(self) -> int:
        return self.states.t.shape[0]

    def state(self, i: int) -> ga.AlphaState:
        """Record i as an integrator state."""
        s = self.states
        return ga.AlphaState(float(s.t[i]), s.x[i], s.v[i], s.xdd[i], s.a[i], s.lam[i], s.chart)

    def work(self, i: int) -> dict[str, float]:
        """The dissipated and drive work up to record i (J)."""
        return {"dissipated": float(self.dissipated[i]), "drive": float(self.drive[i])}


def decimal_units(*values: float) -> tuple[int, ...]:
    """The decimals that print as ``values`` (shortest repr) as integers over a common power of
    ten: (n_1, ..., n_k, scale) with value_i = n_i / scale exactly in decimal arithmetic."""
    decimals = [Decimal(repr(float(v))) for v in values]
    digits = max(0, *(-d.as_tuple().exponent for d in decimals))
    return (*(int(d.scaleb(digits)) for d in decimals), 10**digits)


def change_chart(system: MultibodySystem, state: ga.AlphaState, F_new: np.ndarray, eps: float = 1e-4) -> ga.AlphaState:
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


def initial_state(system: MultibodySystem, load_steps: int = 20, start: str = "rest") -> ga.AlphaState:
    """Where a run starts: at rest in the straight clamped state at theta = 0 (``start`` =
    "rest") or at rest in the static equilibrium under gravity and loads with the hub at
    theta = 0 ("equilibrium"); for a drive that already turns at t = 0 (profile 'constant'),
    in the steadily rotating equilibrium (static analysis with the centrifugal load) with its
    rigid-rotation velocities. A turning hub gets the axis charts (see MultibodySystem.axis_chart).
    Controllers' states start at 0; the start state is that of the system without them."""
    plant = system.without_controllers() if system.controllers else system
    x0, F0, v0 = _start_point(plant, load_steps, start)
    if plant is not system:  # the controllers' coordinates (last in x) and their rates start at 0
        pad = system.nx - plant.nx
        x0, v0 = np.concatenate([x0, np.zeros(pad)]), np.concatenate([v0, np.zeros(pad)])
    return ga.init(system, x0, F0, v0=v0)


def _start_point(system: MultibodySystem, load_steps: int, start: str):
    """(x0, charts, v0) of :func:`initial_state`."""
    omega0 = system.drive(0.0)[1] if system.motion == "prescribed" else 0.0
    if omega0:
        try:
            sol = solve_static(system, load_steps=load_steps, spin=omega0)
        except ConvergenceError as exc:
            raise ComputationError(f"the steadily rotating start state (omega = {omega0:g} rad/s) was not found: {exc}") from exc
        v0, _ = system.steady_rotation_rates(sol.x, sol.chart, omega0)
        return sol.x, sol.chart, v0
    if start == "equilibrium":
        try:
            # a turning hub's run is in the axis charts: solve there (a remap after the solve would
            # move a bent beam off its equilibrium by the remap's interpolation error)
            sol = solve_static(system, load_steps=load_steps, spin=None if system.motion == "fixed" else 0.0)
        except ConvergenceError as exc:
            raise ComputationError(f"the static start state (analysis.start = 'equilibrium') was not found: {exc}") \
                from exc
        x0, F0 = sol.x, sol.chart
    else:
        x0, F0 = system.initial_state(0.0)
    if system.motion != "fixed":
        x0, F0 = system.axis_chart(x0, F0)
    return x0, F0, system.initial_rates(x0, F0)


class PythonSteps:
    """Steps of :func:`hubbeam.solvers.generalized_alpha.step` (any system), with the work
    integrals of the energy balance (trapezoidal rule on the dissipated and drive power).

    :meth:`advance` takes a chunk of steps and returns the states at the output steps in
    it, each with the work done up to then."""

    def __init__(self, system: MultibodySystem, params, newton, dt, state: ga.AlphaState,
                 measures: tuple[bool, bool, list] = (False, False, []), work: dict | None = None) -> None:
        self.system, self.params, self.newton, self.dt = system, params, newton, dt
        # (energies, tip displacements, strain gauges) (:func:`hubbeam.sensors.record_needs`):
        # the compiled steps compute them for a chunk's records (:class:`RecordChunk`), where the sensors read them
        self.measures = measures
        self.work = dict(work) if work is not None else {"dissipated": 0.0, "drive": 0.0}
        self.kept = None  # the iteration matrix kept between steps
        # at rest both powers are exactly 0 (drag ~ |v| v, structural damping ~ e', hub power
        # ~ theta'): no call then (each is a compiled function loaded from numba's cache)
        self.power = (0.0, 0.0) if not np.any(state.v) else self._power(state)
        self.factorisations = None  # counted by the compiled steps only
        self.event = False  # the last advance stopped at an event (a joint at its latch angle)

    def _power(self, st):
        return self.system.step_powers(st.t, st.x, st.v, st.lam, st.chart)

    def advance(self, state, n_steps, step0, every, total):
        """Up to n_steps steps after step0 of total; states after steps that are multiples of
        ``every`` (and the last) are returned. Returns (state, steps taken, Newton
        iterations, chart limit reached, error or None, the records' :class:`RecordChunk` or None);
        :attr:`event` says whether the last step reached an event (a joint at its latch angle)."""
        iterations = 0
        records = []
        self.event = False
        for k in range(n_steps):
            try:
                state, its, self.kept = ga.step(self.system, state, self.dt, self.params, self.newton, self.kept)
            except (ConvergenceError, ChartSingularityError) as exc:
                return state, k, iterations, False, exc, RecordChunk.of_states(records)
            iterations += its
            p_new = self._power(state)
            self.work["dissipated"] += 0.5 * self.dt * (self.power[0] + p_new[0])
            self.work["drive"] += 0.5 * self.dt * (self.power[1] + p_new[1])
            self.power = p_new
            step = step0 + k + 1
            if step % every == 0 or step == total:
                records.append((state, dict(self.work)))
            if self.system.event_reached(state.x):
                self.event = True
                return state, k + 1, iterations, False, None, RecordChunk.of_states(records)
            if self.system.chart_margin(state.x, state.chart) < CHART_LIMIT:
                return state, k + 1, iterations, True, None, RecordChunk.of_states(records)
        return state, n_steps, iterations, False, None, RecordChunk.of_states(records)

    def chart_changed(self):
        self.kept = None


class CompiledSteps(PythonSteps):
    """The same steps in compiled code (:func:`hubbeam.solvers.compiled_alpha.advance`) for
    systems whose every term compiles (every beam ANCF): a chunk of steps is one call."""

    def __init__(self, system, params, newton, dt, state, measures: tuple[bool, bool, list] = (False, False, []),
                 work: dict | None = None) -> None:
        super().__init__(system, params, newton, dt, state, measures, work)
        self.gauges, self.gauge_list = system.gauge_table(measures[2])
        # the gauges the compiled measures leave out (FFR beams'): read over a chunk's records at once
        self.other_gauges = [g for g in dict.fromkeys(measures[2]) if g not in self.gauge_list]
        self.model = system.model()
        layout = system.layout
        storage = BorderedBandMatrix.empty(layout.nz, layout.border, system.bandwidth)
        m = storage.ab.shape[1]
        self.matrix = (storage.ab, np.zeros(m, dtype=np.int32), storage.brow, storage.bcol, storage.bb,
                       np.zeros((layout.border, m)), np.zeros((layout.border, layout.border)), np.zeros(layout.border))
        self.reuse = nc.reuse_state()
        self.rate = nc.borrowed_rate()
        columns = joint_columns(layout, newton.update_columns)
        k = columns.shape[0]
        rows = (np.zeros((k, layout.nz)) for _ in range(8))  # the kept columns, G, H, Ut, the last patch's, drifts
        self.patch = (columns, layout.z_of_x[columns].astype(np.int64), *rows, np.zeros((2 * k, 2 * k)),
                      np.zeros((2 * k, 2 * k)), np.zeros(2 * k), np.zeros(2 * k), np.zeros(layout.nz))
        self.factorisations = 0
        self.patches = 0  # column updates of the kept matrix (hubbeam.solvers.column_update)
        self.work_done = np.array([self.work["dissipated"], self.work["drive"]], dtype=float)
        self.alpha = (params.alpha_m, params.alpha_f, params.beta, params.gamma)
        tol = newton.tolerance * max(system.length_scale, 1.0)
        self.options = (tol, newton.max_iterations, newton.update_code, newton.refresh_rate, newton.refresh_iterations,
                        ga.multiplier_weights(system.layout, dt, params.beta, newton.tolerance, newton.tests_hold_torque),
                        nc.KAPPA, newton.borrowed_rate_steps)
        self.loop = compiled_alpha.loop_for(system)
        self.advance(state, 0, 0, 1, 1)  # compile or load the loop now, not inside the timed run

    def advance(self, state, n_steps, step0, every, total):
        x, v, xdd, a, lam = (np.array(u, dtype=float) for u in (state.x, state.v, state.xdd, state.a, state.lam))
        rows = n_steps // every + 2
        records = (np.empty(rows), np.empty((rows, x.size)), np.empty((rows, x.size)), np.empty((rows, x.size)),
                   np.empty((rows, x.size)), np.empty((rows, lam.size)), np.empty((rows, 2)))
        power = np.array(self.power, dtype=float)
        counters = np.zeros(5, dtype=np.int64)
        chart = np.ascontiguousarray(state.chart)
        with interrupt.deferred():  # a signal handler must not raise inside compiled code; see simulate
            status, size, t = self.loop(
                self.model, chart, state.t, x, v, xdd, a, lam, self.dt, n_steps, self.alpha, self.options,
                self.system.mass_scale, CHART_LIMIT, self.matrix, self.reuse, self.rate, self.patch, self.work_done, power,
                counters, (step0, every, total), records)
        steps, its, factorisations, n_rec, patches = (int(c) for c in counters)
        self.power = (power[0], power[1])
        self.factorisations += factorisations
        self.patches += patches
        self.work = {"dissipated": self.work_done[0], "drive": self.work_done[1]}
        rt, rx, rv, rxdd, ra, rlam, rwork = records
        chunk = None
        if n_rec:
            chunk = RecordChunk(ga.AlphaState(rt[:n_rec], rx[:n_rec], rv[:n_rec], rxdd[:n_rec], ra[:n_rec], rlam[:n_rec],
                                              state.chart), rwork[:n_rec, 0], rwork[:n_rec, 1])
            energies, tips, _ = self.measures
            if energies or tips or self.gauge_list:
                measured = self.system.record_measures(rx, rv, chart, n_rec, energies, self.gauges)
                chunk.tips = measured["tips"] if tips else None
                chunk.strains = {g: measured["strains"][:, i] for i, g in enumerate(self.gauge_list)}
                if energies:
                    chunk.energies = (measured["hub"], measured["beams"])
            chunk.strains.update((g, self.system.surface_strains_of_states(rx[:n_rec], chart, g[1], g[2], g[3], g[0]))
                                 for g in self.other_gauges)
        new = ga.AlphaState(t, x, v, xdd, a, lam, state.chart)
        message = ga.OUTCOME_MESSAGES.get(ga.Outcome(status))
        error = None
        if message is not None:
            text = message.format(its=self.newton.max_iterations, size=size)
            error = (ChartSingularityError if status == ga.Outcome.CHART_SINGULARITY else ConvergenceError)(text)
        self.event = status == ga.Outcome.EVENT_REACHED
        return new, steps, its, status == ga.Outcome.CHART_LIMIT_REACHED, error, chunk

    def chart_changed(self):
        self.reuse[nc.REUSE_VALID] = 0


def latch(system: MultibodySystem, state: ga.AlphaState, work: dict, time: float | None = None):
    """The joints whose latch angle ``state`` reached, locked (:func:`hubbeam.system.joints.latch_joints`):
    (the locked system, its state (velocities projected, accelerations and multipliers
    consistent with them), the :class:`~hubbeam.system.joints.LatchEvent` of each, the work so
    far with the energy the projection removed added to ``dissipated`` and the impulsive work
    of prescribed motions to ``drive``). ``time``: the event's time as the records give it (the
    decimal time of its step; default the state's)."""
    from hubbeam.system.joints import latch_joints, reached_latches

    new, v_plus, events, drive = latch_joints(system, reached_latches(system, state.x), state.t, state.x, state.v,
                                              state.chart)
    if time is not None:
        events = [replace(e, time=float(time)) for e in events]
    work = {"dissipated": float(work["dissipated"]) + sum(e.energy for e in events),
            "drive": float(work["drive"]) + drive}
    return new, ga.init(new, state.x, state.chart, state.t, v_plus), events, work


#: a run reports progress (and takes a chunk of compiled steps) about this many times
PROGRESS_UPDATES = 100
#: ... and returns to Python at least about this often (s), so that a signal is noticed
CHUNK_SECONDS = 0.25
#: ... but a chunk lasts at least about this long (s) once the speed is known: a short run (a
#: 10 s modal model takes 0.04 s) is not cut into 100 chunks whose returns to Python (the
#: records' measures, the calls' argument checks: about 60 us each) cost 15 % of its time
MIN_CHUNK_SECONDS = 0.05


def simulate(system: MultibodySystem, sensors, t_end: float, dt: float, spectral_radius: float = 0.8,
             output_dt: float | None = None, progress=None, newton: nc.NewtonOptions = nc.NewtonOptions(),
             state: ga.AlphaState | None = None, recorder=None) -> Trajectory:
    """Integrate from ``state`` (default: :func:`initial_state`) to t_end.

    Steps run in compiled code, in chunks of about 1/100 of the run (but of at least about
    MIN_CHUNK_SECONDS of computing) and of at most about CHUNK_SECONDS, when the system has a
    compiled model (:class:`CompiledSteps`), else step by step in Python (:class:`PythonSteps`); sensors are evaluated at the output
    times from the states the steps kept, output time k being the double nearest the decimal
    t0 + k output_dt. ``progress(t)`` is called after every chunk when given. On failure a
    ComputationError names the time and step and carries the trajectory so far in
    ``partial``; so does any other exception out of the loop (an interruption). When a beam
    tangent comes within 60 deg of the chart's singular direction the state is moved to a
    better chart (counted in ``Trajectory.chart_switches``). ``recorder``: a
    :class:`hubbeam.snapshots.StateRecorder` whose snapshots are kept at the output times too.
    """
    params = ga.AlphaParameters.from_spectral_radius(spectral_radius)
    if state is None:
        state = initial_state(system)
    n_steps = int(round((t_end - state.t) / dt))
    every = max(1, int(round((output_dt or dt) / dt)))
    traj = Trajectory(recorder=recorder)
    # exact time axis: record r is the state after step min(r * every, n_steps); its time is
    # the double nearest the decimal t0 + step * dt (not the sum of steps, which drifts: 20.00000000000146)
    # (as exact integers: t0 + step * dt = (t0_units + step * dt_units) / scale, and int / int is correctly rounded)
    t0_units, dt_units, scale = decimal_units(state.t, dt)

    measures = [(s.name, prepare_chunk(s, system)) for s in sensors]
    if newton.hold_torque is None:  # tested as a torque where it is read or does work (NewtonOptions)
        newton = replace(newton, hold_torque=system.hub.motion != "fixed" or any(s.kind == "hub_torque" for s in sensors))

    def record(chunk):
        if chunk is None:
            return
        first = len(traj.times)
        times = [(t0_units + dt_units * min((first + i) * every, n_steps)) / scale for i in range(len(chunk))]
        chunk.states = replace(chunk.states, t=np.array(times))
        traj.extend(times, {name: measure(chunk) for name, measure in measures},
                    None if recorder is None else [recorder(system, chunk.state(i)) for i in range(len(chunk))])

    record(RecordChunk.of_states([(state, {"dissipated": 0.0, "drive": 0.0})]))
    steps_class = CompiledSteps if system.compiled else PythonSteps
    stepper = steps_class(system, params, newton, dt, state, record_needs(sensors, system))
    chunk_size = max(1, -(-n_steps // PROGRESS_UPDATES))
    chunk = min(chunk_size, 8)  # the first chunks are short; later ones last about CHUNK_SECONDS
    start = time.perf_counter()
    k = 0
    earlier = 0  # factorisations of the steppers before a latch changed the system
    try:  # interruption: see the except clause below
        while k < n_steps:
            chunk_start = time.perf_counter()
            state, done, its, chart_limit, error, records = stepper.advance(state, min(chunk, n_steps - k), k,
                                                                            every, n_steps)
            # control comes back to Python at least every ~2 CHUNK_SECONDS (a signal is noticed
            # between chunks); the chunk boundaries do not change the steps, so runs stay bit-for-bit repeatable
            seconds = time.perf_counter() - chunk_start
            if done:
                rate = done / max(seconds, 1e-9)  # steps per second
                chunk = max(1, min(max(chunk_size, int(MIN_CHUNK_SECONDS * rate)), 2 * chunk, int(CHUNK_SECONDS * rate)))
            record(records)
            k += done
            traj.steps = k
            traj.newton_iterations += its
            interrupt.raise_pending(detail="")  # a signal held during the compiled chunk
            if error is not None:
                traj.wall_time_s = time.perf_counter() - start
                raise ComputationError(
                    f"time integration failed at t = {state.t + dt:.6g} s (step {k + 1}): {error}. "
                    f"Try a smaller analysis.dt (now {dt:g} s), more beam.elements or a smaller analysis.spectral_radius.",
                    partial=traj,
                ) from error
            if stepper.event:  # a joint reached its latch: the system changes (its lock), the stepper with it
                system, state, latches, work = latch(system, state, stepper.work, (t0_units + dt_units * k) / scale)
                traj.latches.extend(latches)
                measures = [(s.name, prepare_chunk(s, system)) for s in sensors]
                if stepper.factorisations is not None:
                    earlier += stepper.factorisations
                stepper = steps_class(system, params, newton, dt, state, record_needs(sensors, system), work)
                chart_limit = system.chart_margin(state.x, state.chart) < CHART_LIMIT
            if chart_limit:
                state = change_chart(system, state, system.better_chart(state.x, state.chart, CHART_LIMIT))
                stepper.chart_changed()
                traj.chart_switches += 1
            if progress is not None:
                progress(state.t)
    # interruption: any exception out of the loop (a signal raised as an exception, a failed
    # chart change, KeyboardInterrupt) carries the trajectory so far in ``partial``
    except BaseException as exc:
        traj.wall_time_s = time.perf_counter() - start
        traj.factorisations = None if stepper.factorisations is None else earlier + stepper.factorisations
        if getattr(exc, "partial", None) is None:
            try:
                exc.partial = traj
            except AttributeError:
                pass
        raise
    traj.wall_time_s = time.perf_counter() - start
    traj.factorisations = None if stepper.factorisations is None else earlier + stepper.factorisations
    return traj
