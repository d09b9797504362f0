"""Identification of scenario parameters from a measured time series (least squares).

The model is the scenario simulated with the parameters set by ``--set``-style overrides,
its signal taken at the measured times themselves (:func:`schedule`): when every measured
time is a whole number of steps of ``analysis.dt`` the model records exactly there (its
``output_dt`` is the largest step that holds all of them); otherwise, when the times share a
common step (a record sampled every 0.0025 s with dt = 1 ms), ``analysis.dt`` is shortened to
the largest divisor of that step at or below it, and the model records there; only times
with no such common step (jittered time stamps) make the model's signal interpolated
linearly between its steps, with a note. (Interpolating between the scenario's
``output_dt`` records biased the fit: a record made at 2 ms fitted at output_dt 10 ms gave
damping.linear 3.97 +- 2.79 for a true 1.73.)

scipy.optimize.least_squares (trust-region reflective, bounds) minimises the residuals
scaled by the measurement's standard deviation, with forward-difference Jacobians (each
column one simulation). Confidence intervals come from a central-difference Jacobian at the
optimum: cov = s^2 (J^T J)^-1, s^2 = SSR / (n - p), and +- t(0.975, n - p) sqrt(cov_ii) (a
linearisation: reliable when the residuals are small, independent and the parameters well
determined; the correlation matrix says when they are not; on synthetic records with
Gaussian noise the 95 % interval covers the truth in about 95 % of draws, see
tests/studies/test_identify.py).

Three cases are reported as they are rather than as numbers that look precise:

- a (near) perfect fit, rms residual below :data:`RESIDUAL_FLOOR` times the measurement's
  standard deviation (synthetic data from the model itself): s is floored at that level,
  which is what the simulation's Newton tolerance and the optimiser's stopping rule
  resolve, so the interval is an upper bound of the numerical uncertainty, not a
  statistical statement; ``ci95_basis`` is then ``"floor"`` (else ``"residuals"``);
- a parameter the signal does not determine (J^T J singular): its interval and
  correlations are ``None`` (null in JSON) and ``notes`` says why;
- a parameter that stopped on the edge of the values it may take (the fit's lower bound,
  or a value the scenario refuses next to it, e.g. a tip body's inertia at J_tau = J_m +
  J_n), or whose interval would reach such values: no interval (``None``), and a note
  saying which edge; the others' intervals hold it at its value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from decimal import ROUND_CEILING, Decimal

import numpy as np
from scipy import stats
from scipy.optimize import least_squares

from hubbeam import api
from hubbeam.io.scenario import Scenario, ScenarioError, value_at
from hubbeam.errors import ComputationError
from hubbeam.studies.variants import variant


#: an rms residual below this times std(measured) is a perfect fit: s is floored here
RESIDUAL_FLOOR = 1e-6


def _finite_or_none(x):
    x = float(x)
    return x if math.isfinite(x) else None


@dataclass
class Identification:
    names: list[str]
    values: np.ndarray
    initial: np.ndarray
    ci95: np.ndarray  # half-widths (NaN: not determined, see notes)
    correlation: np.ndarray  # NaN where not determined
    rms: float
    evaluations: int
    times: np.ndarray
    measured: np.ndarray
    fitted: np.ndarray
    message: str
    ci95_basis: str = "residuals"  # or "floor" (a perfect fit, see the module doc)
    notes: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        """JSON-ready: no NaN or infinity (a value that is not determined is None, and
        ``notes`` says why)."""
        return {"parameters": {n: {"value": float(v), "ci95": _finite_or_none(c), "initial": float(i)}
                               for n, v, c, i in zip(self.names, self.values, self.ci95, self.initial)},
                "ci95_basis": self.ci95_basis,
                "correlation": [[_finite_or_none(c) for c in row] for row in np.asarray(self.correlation)],
                "rms_residual": float(self.rms), "simulations": self.evaluations, "message": self.message,
                "notes": list(self.notes)}


def check_measured(times, measured, what: str = "measured data", labels=("time", "signal"),
                   first_row: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The measured series as float arrays, or ScenarioError naming what is wrong: at least 5
    samples, finite, times >= 0 and strictly increasing, a signal that varies. ``labels``
    name the two columns and ``first_row`` the file row of sample 0 in the messages."""
    times, measured = np.asarray(times, dtype=float), np.asarray(measured, dtype=float)

    def at(i):
        return f"row {i + first_row}" if first_row is not None else f"sample {i}"

    if times.ndim != 1 or times.shape != measured.shape:
        raise ScenarioError(f"{what}: time and signal must be 1-D and of the same length")
    if times.size < 5:
        raise ScenarioError(f"{what}: {times.size} samples; at least 5 are needed")
    for label, values in zip(labels, (times, measured)):
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            raise ScenarioError(f"{what}: column {label!r}, {at(bad[0])}: not finite ({values[bad[0]]})")
    if times[0] < 0:
        raise ScenarioError(f"{what}: column {labels[0]!r} starts at {times[0]:g} s; the model starts at 0 s")
    steps = np.diff(times)
    bad = np.flatnonzero(~(steps > 0))
    if bad.size:
        i = bad[0] + 1
        kind = "repeats" if steps[bad[0]] == 0 else "goes back"
        raise ScenarioError(f"{what}: column {labels[0]!r} {kind} at {at(i)} ({times[i]:g} s after "
                            f"{times[i - 1]:g} s); it must increase strictly")
    if np.ptp(measured) <= 1e-12 * max(np.max(np.abs(measured)), 1e-300):
        raise ScenarioError(f"{what}: column {labels[1]!r} is constant ({measured[0]:g}); there is nothing to fit")
    return times, measured


def run_length(scenario: Scenario, last_time: float) -> float:
    """The model's t_end for a measurement ending at ``last_time``: the next multiple of
    analysis.dt (decimal arithmetic: 0.4 stays 0.4 at dt = 0.002)."""
    dt = Decimal(repr(float(scenario.analysis.dt)))
    n = (Decimal(repr(float(last_time))) / dt).to_integral_value(rounding=ROUND_CEILING)
    return float(max(n, 1) * dt)


#: the step of analysis.dt may be shortened to this fraction of it (at most) to land on the measured times
MIN_STEP_FRACTION = 0.25
#: measured times are taken as whole nanoseconds when they are within this many ns of one (float round-off)
NS_ROUNDING = 1e-3
#: divisors of the times' common step tried for a shorter analysis.dt (then: interpolation)
MAX_DIVISOR_TRIALS = 100_000


@dataclass(frozen=True)
class Schedule:
    """How the model is stepped to give its signal at the measured times: ``dt``,
    ``output_dt`` and ``t_end`` (s), and ``index``, the record of each measured time,
    or None when the signal is interpolated between the steps (``output_dt`` = ``dt``);
    ``note`` says what was changed or approximated."""

    dt: float
    output_dt: float
    t_end: float
    index: np.ndarray | None
    note: str | None = None


def _whole_ns(values) -> list[int] | None:
    """Each value (s) as a whole number of nanoseconds, or None if one is not (to NS_ROUNDING)."""
    out = []
    for v in values:
        ns = float(v) * 1e9
        if not abs(ns - round(ns)) <= NS_ROUNDING:
            return None
        out.append(int(round(ns)))
    return out


def _ns_to_s(ns: int) -> float:
    return float(Decimal(ns).scaleb(-9))


def schedule(scenario: Scenario, times) -> Schedule:
    """The model's steps and records for a measurement at ``times`` (s, increasing, >= 0),
    so that its signal is taken at those very times (see the module doc): the scenario's
    analysis.dt when every time is a whole number of its steps; else the longest step, down
    to :data:`MIN_STEP_FRACTION` of it, that divides every time; the model then records at
    the longest multiple of its step that divides every time. Otherwise (times that are not
    whole nanoseconds, no such step) the scenario's dt with every step recorded and the
    signal interpolated between the steps (a note says so)."""
    dt = scenario.analysis.dt
    ns, (dt_ns,) = _whole_ns(times), (_whole_ns([dt]) or [None])
    step = None
    if ns is not None and dt_ns:
        common = 0
        for n in ns:
            common = math.gcd(common, n)
        if common % dt_ns == 0:
            step = dt_ns
        else:  # the longest divisor of the times' common step that is at most dt
            first = m = -(-common // dt_ns)
            while step is None and common // m >= MIN_STEP_FRACTION * dt_ns and m < first + MAX_DIVISOR_TRIALS:
                step = common // m if common % m == 0 else None
                m += 1
    if step is None:
        return Schedule(dt, dt, run_length(scenario, float(times[-1])), None,
                        f"the measured times are not whole numbers of a step of at least {MIN_STEP_FRACTION:g} "
                        f"analysis.dt (= {dt:g} s): the model's signal is interpolated linearly between its steps, an "
                        "error of about (dt^2 / 8) |d^2 signal / dt^2|")
    ks = [n // step for n in ns]
    every = 0
    for k in ks:
        every = math.gcd(every, k)
    every = max(every, 1)
    note = None
    if step != dt_ns:
        note = (f"analysis.dt {dt:g} s -> {_ns_to_s(step):.10g} s, so that the model's steps land on the measured times "
                f"(every one a whole number of {_ns_to_s(step):.10g} s)")
    return Schedule(_ns_to_s(step), _ns_to_s(step * every), _ns_to_s(step * max(ks[-1], 1)),
                    np.array([k // every for k in ks], dtype=np.int64), note)


def check_fit_keys(scenario: Scenario, names: list[str]) -> np.ndarray:
    """The initial values of the fitted keys; ScenarioError for a key that is not a number
    of the scenario or cannot take a non-integral value."""
    if not names:
        raise ScenarioError("--fit: give at least one scenario key")
    if len(set(names)) != len(names):
        raise ScenarioError("--fit: a key is given twice")
    for n in names:
        if n.split(".")[0].split("[")[0] == "analysis":
            raise ScenarioError(f"--fit {n}: an analysis setting, not a parameter of the model")
    data = scenario.to_dict()
    x0 = np.array([_lookup(data, n) for n in names])
    for n, v in zip(names, x0):
        errors = []
        for trial in (v * (1 + 1e-7) + 1e-12, v * (1 - 1e-7) - 1e-12):
            try:
                variant(scenario, [f"{n}={float(trial)!r}"])
                break
            except ScenarioError as exc:
                errors.append(str(exc))
        else:
            raise ScenarioError(f"--fit {n}: cannot be varied continuously ({errors[0]})")
    return x0


def signal_columns(scenario: Scenario) -> list[str]:
    """The columns a run of the scenario has (sensors, multi-part ones as NAME_PART; a beam's
    energy has no dissipated or drive part)."""
    from hubbeam.sensors import columns

    return [c for s in scenario.sensors for c in columns(s)]


def _lookup(data: dict, key: str) -> float:
    """The number a --fit key addresses (the --set addressing: beam.x, beams[1].x, beams.NAME.x)."""
    try:
        node = value_at(data, key)
    except ScenarioError as exc:
        raise ScenarioError(f"--fit {str(exc).removeprefix('--set ')}") from None
    if node is None:
        raise ScenarioError(f"--fit {key}: not a key of the scenario (or not set in it)")
    if isinstance(node, bool) or not isinstance(node, (int, float)):
        raise ScenarioError(f"--fit {key}: not a number ({node!r})")
    return float(node)


def signal_sensor(scenario: Scenario, signal: str):
    """(the sensor that makes the column ``signal``, its part or None); ScenarioError naming --signal."""
    for sensor in scenario.sensors:
        if signal in sensor.columns:
            return sensor, (None if sensor.parts is None else signal[len(sensor.name) + 1:])
    raise ScenarioError(f"--signal {signal}: not a column of the scenario's sensors "
                        f"({', '.join(signal_columns(scenario)) or 'none'})")


def model_signal(scenario: Scenario, names, values, signal: str, times: np.ndarray,
                 plan: Schedule | None = None) -> np.ndarray:
    """The scenario's ``signal`` with the parameters set, at ``times`` (s), stepped as
    ``plan`` says (default: :func:`schedule`); only the signal's sensor is recorded."""
    times = np.asarray(times, dtype=float)
    plan = schedule(scenario, times) if plan is None else plan
    sensor, part = signal_sensor(scenario, signal)
    sc = variant(scenario, [f"{n}={float(v)!r}" for n, v in zip(names, values)] +
                 [f"analysis.t_end={plan.t_end!r}", f"analysis.dt={plan.dt!r}", f"analysis.output_dt={plan.output_dt!r}"])
    traj, failure = api.run(sc, sensors=[sensor.name])
    if failure is not None:
        raise failure
    records = traj.records[sensor.name]
    y = np.array([r[part] for r in records] if part else records, dtype=float)
    t = np.array(traj.times)
    if plan.index is None:
        return np.interp(times, t, y)
    if plan.index[-1] >= y.size or not np.allclose(t[plan.index], times, rtol=1e-12, atol=1e-6 * plan.dt):
        raise ComputationError(f"the model's records do not fall on the measured times (internal: {t.size} records "
                               f"for {times.size} samples)")
    return y[plan.index]


#: the step of the central differences of the interval's Jacobian, relative to max(|value|, 1e-3)
JACOBIAN_STEP = 1e-3


def _valid(scenario: Scenario, name: str, value: float, lower: float) -> str | None:
    """None when ``value`` is a value the fit may give ``name``; else why not."""
    if value < lower:
        return f"the fit's lower bound {lower:g}"
    try:
        variant(scenario, [f"{name}={float(value)!r}"])
    except ScenarioError as exc:
        return str(exc)
    return None


def identify(scenario: Scenario, times, measured, names: list[str], signal: str = "strain_P1",
             lower: float = 0.0, progress=None) -> Identification:
    """Fit ``names`` (scenario keys) so that the simulated ``signal`` matches ``measured``
    (the model's signal at the measured times: :func:`schedule`)."""
    times, measured = check_measured(times, measured)
    names = list(names)
    x0 = check_fit_keys(scenario, names)
    sensor, _ = signal_sensor(scenario, signal)
    from hubbeam.limits import run_size

    plan = schedule(scenario, times)
    run_size(plan.t_end, plan.dt, plan.output_dt, 1 + len(sensor.columns))
    low = [n for n, v in zip(names, x0) if v < lower]
    if low:
        raise ScenarioError(f"--fit {low[0]}: the fit keeps parameters >= {lower:g}, and its value in the scenario is "
                            f"{x0[names.index(low[0])]:g}")
    scale = float(np.std(measured))
    count = [0]

    def simulate(p):
        count[0] += 1
        if progress:
            progress(count[0])
        return (model_signal(scenario, names, p, signal, times, plan) - measured) / scale

    def residual(p):
        try:
            return simulate(p)
        except ComputationError:
            return np.full(times.size, 1e3)  # a failed simulation: far from the data
        except ScenarioError:
            if count[0] == 1:
                raise
            return np.full(times.size, 1e3)  # a trial value outside the key's valid range

    x_scale = np.maximum(np.abs(x0), 1e-3)
    fit = least_squares(residual, x0, bounds=(lower, np.inf), x_scale=x_scale,
                        diff_step=1e-4, xtol=1e-6, ftol=1e-8)
    n, p = times.size, len(names)
    notes = [] if plan.note is None else [plan.note]
    # the interval's Jacobian: central differences at the optimum; a side the key may not take is an edge
    edges: dict[int, str] = {}
    J = np.zeros((n, p))
    for i, (name, value) in enumerate(zip(names, fit.x)):
        h = JACOBIAN_STEP * max(abs(value), 1e-3)
        sides = []
        for sign in (1.0, -1.0):
            trial = fit.x.copy()
            trial[i] = value + sign * h
            why = _valid(scenario, name, trial[i], lower)
            if why is not None:
                edges[i] = why
                continue
            try:
                sides.append((sign * h, simulate(trial)))
            except ComputationError as exc:
                edges[i] = f"a simulation at {name} = {trial[i]:.6g} fails ({str(exc)[:80]})"
        if len(sides) == 2:
            J[:, i] = (sides[0][1] - sides[1][1]) / (2.0 * h) * scale
    ssr = float(np.sum((fit.fun * scale) ** 2))
    s2 = ssr / max(n - p, 1)
    basis = "residuals"
    floor = (RESIDUAL_FLOOR * scale) ** 2
    if s2 < floor:
        s2, basis = floor, "floor"
        notes.append(f"a perfect fit (rms residual {np.sqrt(ssr / n):.3g}, below {RESIDUAL_FLOOR:g} of the signal's "
                     "standard deviation): the intervals use that floor for the residual spread, an upper bound of "
                     "the numerical uncertainty, not a statistical interval")
    if n <= p:
        notes.append(f"{n} samples for {p} parameters: no residual degrees of freedom")
    free = [i for i in range(p) if i not in edges]
    sd = np.full(p, np.nan)
    corr = np.full((p, p), np.nan)
    quantile = stats.t.ppf(0.975, max(n - p, 1))
    if free:
        Jf = J[:, free]
        JTJ = Jf.T @ Jf
        if np.all(np.isfinite(JTJ)) and np.linalg.matrix_rank(JTJ) == len(free):
            cov = s2 * np.linalg.inv(JTJ)
            sd[free] = np.sqrt(np.abs(np.diag(cov)))
            corr[np.ix_(free, free)] = cov / np.outer(sd[free], sd[free])
        else:
            undetermined = [names[i] for i in free if not np.abs(JTJ[free.index(i), free.index(i)]) > 0]
            for name in undetermined:
                notes.append(f"{name}: the signal does not depend on it; no interval")
            if not undetermined:
                notes.append("the parameters are not determined independently of each other (J^T J is singular); "
                             "no intervals")
    # an interval that reaches values the key may not take is no interval either
    for i in free:
        if np.isfinite(sd[i]):
            for end in (fit.x[i] - quantile * sd[i], fit.x[i] + quantile * sd[i]):
                why = _valid(scenario, names[i], end, lower)
                if why is not None:
                    notes.append(f"{names[i]}: its 95 % interval (+- {quantile * sd[i]:.3g}) would reach "
                                 f"{end:.6g}, a value it may not take ({why}); no interval")
                    sd[i] = np.nan
                    corr[i, :] = corr[:, i] = np.nan
                    break
    for i, why in edges.items():
        notes.append(f"{names[i]}: the fit stopped at the edge of the values it may take ({why}); no interval (the "
                     "data may favour values beyond it)" + ("; the other intervals hold it at its value" if free else ""))
    half = quantile * sd
    fitted = measured + fit.fun * scale
    return Identification(names, fit.x, x0, half, corr, float(np.sqrt(ssr / n)), count[0], times, measured,
                          fitted, fit.message, basis, notes)
