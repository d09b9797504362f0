"""Identification of scenario parameters from a measured time series (least squares).

The model is the scenario simulated with the parameters set by ``--set``-style overrides;
its signal, interpolated linearly onto the measured times, is compared with the
measurement. scipy.optimize.least_squares (trust-region reflective, bounds) minimises the
residuals scaled by the measurement's standard deviation, with forward-difference
Jacobians (each column one simulation). Confidence intervals come from the Jacobian at
the optimum: cov = s^2 (J^T J)^-1, s^2 = SSR / (n - p), and +- t(0.975, n - p) sqrt(cov_ii)
(a linearisation: reliable when the residuals are small, independent and the parameters
well determined; the correlation matrix says when they are not).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats
from scipy.optimize import least_squares

from hubbeam import api
from hubbeam.io.scenario import Scenario, ScenarioError
from hubbeam.errors import ComputationError
from hubbeam.studies.variants import variant


@dataclass
class Identification:
    names: list[str]
    values: np.ndarray
    initial: np.ndarray
    ci95: np.ndarray  # half-widths
    correlation: np.ndarray
    rms: float
    evaluations: int
    times: np.ndarray
    measured: np.ndarray
    fitted: np.ndarray
    message: str

    def to_dict(self) -> dict:
        return {"parameters": {n: {"value": float(v), "ci95": float(c), "initial": float(i)}
                               for n, v, c, i in zip(self.names, self.values, self.ci95, self.initial)},
                "correlation": self.correlation.tolist(), "rms_residual": self.rms,
                "simulations": self.evaluations, "message": self.message}


def _lookup(data: dict, key: str) -> float:
    node = data
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            raise ScenarioError(f"--fit {key}: not a key of the scenario (or not set in it)")
        node = node[part]
    if isinstance(node, bool) or not isinstance(node, (int, float)):
        raise ScenarioError(f"--fit {key}: not a number ({node!r})")
    return float(node)


def model_signal(scenario: Scenario, names, values, signal: str, times: np.ndarray) -> np.ndarray:
    """The scenario's ``signal`` with the parameters set, at ``times`` (s)."""
    dt = scenario.analysis.dt
    t_end = dt * int(np.ceil(float(times[-1]) / dt - 1e-9))  # the measured span, in whole steps
    sc = variant(scenario, [f"{n}={float(v)!r}" for n, v in zip(names, values)] + [f"analysis.t_end={t_end!r}"])
    traj, failure = api.run(sc)
    if failure is not None:
        raise failure
    t = np.array(traj.times)
    name, _, part = signal.partition("_")
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
    times, measured = np.asarray(times, float), np.asarray(measured, float)
    if times.ndim != 1 or times.shape != measured.shape or times.size < 5:
        raise ScenarioError("measured data: need at least 5 samples of time and signal")
    x0 = np.array([_lookup(scenario.to_dict(), n) for n in names])
    scale = max(np.std(measured), 1e-300)
    count = [0]

    def residual(p):
        count[0] += 1
        if progress:
            progress(count[0])
        try:
            return (model_signal(scenario, names, p, signal, times) - measured) / scale
        except ComputationError:
            return np.full(times.size, 1e3)  # a failed simulation: far from the data

    x_scale = np.maximum(np.abs(x0), 1e-3)
    fit = least_squares(residual, np.maximum(x0, lower), bounds=(lower, np.inf), x_scale=x_scale,
                        diff_step=1e-4, xtol=1e-6, ftol=1e-8)
    n, p = times.size, len(names)
    J = fit.jac * scale
    ssr = float(np.sum((fit.fun * scale) ** 2))
    s2 = ssr / max(n - p, 1)
    try:
        cov = s2 * np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov = np.full((p, p), np.inf)
    sd = np.sqrt(np.abs(np.diag(cov)))
    corr = cov / np.outer(sd, sd) if np.all(sd > 0) and np.all(np.isfinite(sd)) else np.full((p, p), np.nan)
    half = stats.t.ppf(0.975, max(n - p, 1)) * sd
    fitted = measured + fit.fun * scale
    return Identification(list(names), fit.x, x0, half, corr, float(np.sqrt(ssr / n)), count[0], times, measured,
                          fitted, fit.message)
