"""Identification of scenario parameters from a measured time series (least squares).

The model is the scenario simulated with the parameters set by ``--set``-style overrides;
its signal, interpolated linearly onto the measured times, is compared with the
measurement. scipy.optimize.least_squares (trust-region reflective, bounds) minimises the
residuals scaled by the measurement's standard deviation, with forward-difference
Jacobians (each column one simulation). Confidence intervals come from the Jacobian at
the optimum: cov = s^2 (J^T J)^-1, s^2 = SSR / (n - p), and +- t(0.975, n - p) sqrt(cov_ii)
(a linearisation: reliable when the residuals are small, independent and the parameters
well determined; the correlation matrix says when they are not).

Two cases are reported as they are rather than as numbers that look precise:

- a (near) perfect fit, rms residual below :data:`RESIDUAL_FLOOR` times the measurement's
  standard deviation (synthetic data from the model itself): s is floored at that level,
  which is what the simulation's Newton tolerance and the optimiser's stopping rule
  resolve, so the interval is an upper bound of the numerical uncertainty, not a
  statistical statement; ``ci95_basis`` is then ``"floor"`` (else ``"residuals"``);
- a parameter the signal does not determine (J^T J singular): its interval and
  correlations are ``None`` (null in JSON) and ``notes`` says why.
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


def check_fit_keys(scenario: Scenario, names: list[str]) -> np.ndarray:
    """The initial values of the fitted keys; ScenarioError for a key that is not a number
    of the scenario or cannot take a non-integral value."""
    if not names:
        raise ScenarioError("--fit: give at least one scenario key")
    if len(set(names)) != len(names):
        raise ScenarioError("--fit: a key is given twice")
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


def model_signal(scenario: Scenario, names, values, signal: str, times: np.ndarray) -> np.ndarray:
    """The scenario's ``signal`` with the parameters set, at ``times`` (s)."""
    t_end = run_length(scenario, float(times[-1]))
    sc = variant(scenario, [f"{n}={float(v)!r}" for n, v in zip(names, values)] + [f"analysis.t_end={t_end!r}"])
    traj, failure = api.run(sc)
    if failure is not None:
        raise failure
    t = np.array(traj.times)
    name, _, part = signal.rpartition("_")  # parts have no '_', sensor names may (tip_b_tangential)
    if signal in traj.records:
        y = np.array(traj.records[signal], dtype=float)
    elif name in traj.records and part:
        y = np.array([r[part] for r in traj.records[name]], dtype=float)
    else:
        raise ScenarioError(f"--signal {signal}: not a sensor of the scenario ({', '.join(traj.records)})")
    return np.interp(times, t, y)


def identify(scenario: Scenario, times, measured, names: list[str], signal: str = "strain_P1",
             lower: float = 0.0, progress=None) -> Identification:
    """Fit ``names`` (scenario keys) so that the simulated ``signal`` matches ``measured``."""
    times, measured = check_measured(times, measured)
    names = list(names)
    x0 = check_fit_keys(scenario, names)
    if signal not in signal_columns(scenario):
        raise ScenarioError(f"--signal {signal}: not a column of the scenario's sensors "
                            f"({', '.join(signal_columns(scenario)) or 'none'})")
    from hubbeam.limits import columns, run_size

    a = scenario.analysis
    run_size(run_length(scenario, float(times[-1])), a.dt, None, columns(scenario.sensors))
    low = [n for n, v in zip(names, x0) if v < lower]
    if low:
        raise ScenarioError(f"--fit {low[0]}: the fit keeps parameters >= {lower:g}, and its value in the scenario is "
                            f"{x0[names.index(low[0])]:g}")
    scale = float(np.std(measured))
    count = [0]

    def residual(p):
        count[0] += 1
        if progress:
            progress(count[0])
        try:
            return (model_signal(scenario, names, p, signal, times) - measured) / scale
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
    J = fit.jac * scale
    ssr = float(np.sum((fit.fun * scale) ** 2))
    s2 = ssr / max(n - p, 1)
    notes, basis = [], "residuals"
    floor = (RESIDUAL_FLOOR * scale) ** 2
    if s2 < floor:
        s2, basis = floor, "floor"
        notes.append(f"a perfect fit (rms residual {np.sqrt(ssr / n):.3g}, below {RESIDUAL_FLOOR:g} of the signal's "
                     "standard deviation): the intervals use that floor for the residual spread, an upper bound of "
                     "the numerical uncertainty, not a statistical interval")
    if n <= p:
        notes.append(f"{n} samples for {p} parameters: no residual degrees of freedom")
    JTJ = J.T @ J
    sd = np.full(p, np.nan)
    corr = np.full((p, p), np.nan)
    determined = np.abs(np.diag(JTJ)) > 0
    if np.all(np.isfinite(JTJ)) and np.linalg.matrix_rank(JTJ) == p:
        cov = s2 * np.linalg.inv(JTJ)
        sd = np.sqrt(np.abs(np.diag(cov)))
        corr = cov / np.outer(sd, sd)
    else:
        undetermined = [name for name, ok in zip(names, determined) if not ok]
        for name in undetermined:
            notes.append(f"{name}: the signal does not depend on it; no interval")
        if not undetermined:
            notes.append("the parameters are not determined independently of each other (J^T J is singular); "
                         "no intervals")
    half = stats.t.ppf(0.975, max(n - p, 1)) * sd
    fitted = measured + fit.fun * scale
    return Identification(names, fit.x, x0, half, corr, float(np.sqrt(ssr / n)), count[0], times, measured,
                          fitted, fit.message, basis, notes)
