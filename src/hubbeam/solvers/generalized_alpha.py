"""Generalized-alpha for the index-3 DAE of the hub-beam system (paper refs. [31, 32]).

Chung-Hulbert parameters from the spectral radius at infinity rho:
alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1), gamma = 1/2 + alpha_f - alpha_m,
beta = (gamma + 1/2)^2 / 4. Arnold and Bruels's form for constrained systems: the
equations of motion and the constraints Phi(x, t) = 0 are enforced at t_{n+1}, with the
algorithmic acceleration a:

    (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) xdd_{n+1} + alpha_f xdd_n
    x_{n+1} = x_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}
    v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1}

Newton corrects x with dv = gamma' dx, dxdd = beta' dx, beta' = (1 - alpha_m)/(beta h^2
(1 - alpha_f)), gamma' = gamma/(beta h). The force rows are scaled by beta h^2 and the
constraint rows by a mass scale (Bottasso et al.), so the iteration matrix
(1 - alpha_m)/(1 - alpha_f) M + gamma h C + beta h^2 K has entries of one size.
Integrators are plain ``init``/``step`` pairs on an explicit :class:`AlphaState`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import enum

import numpy as np
from numba import njit

from hubbeam.errors import ConvergenceError
from hubbeam.solvers.column_update import PatchedMatrix, difference_step, joint_columns, matrix_column
from hubbeam.solvers.newton_control import (KAPPA, REUSE_PATCH, REUSE_PATCH_AGE, REUSE_VALID, NewtonAction,
                                            NewtonOptions, borrowed_rate, factorised, newton_decide, newton_start,
                                            patch_drifts, patch_made, reuse_state)
from hubbeam.system.assembly import Factorisation
from hubbeam.system.multibody import MultibodySystem


@dataclass(frozen=True)
class AlphaParameters:
    alpha_m: float
    alpha_f: float
    beta: float
    gamma: float

    @classmethod
    def from_spectral_radius(cls, rho: float) -> "AlphaParameters":
        if not 0.0 <= rho <= 1.0:
            raise ValueError("spectral radius must lie in [0, 1]")
        am = (2.0 * rho - 1.0) / (rho + 1.0)
        af = rho / (rho + 1.0)
        gamma = 0.5 + af - am
        return cls(am, af, 0.25 * (gamma + 0.5) ** 2, gamma)


@dataclass(frozen=True)
class AlphaState:
    """Explicit integrator state: time, coordinates, velocities, accelerations, multipliers, chart."""

    t: float
    x: np.ndarray
    v: np.ndarray
    xdd: np.ndarray
    a: np.ndarray
    lam: np.ndarray
    chart: np.ndarray


@dataclass(frozen=True)
class IterationMatrix:
    """A factorised iteration matrix and what it was built for (step size, chart); ``columns``
    (k x n): its joint angles' columns before the factorisation, for a column update
    (:mod:`.column_update`)."""

    lu: Factorisation
    h: float
    chart: np.ndarray
    columns: np.ndarray | None = None

    def valid_for(self, h: float, chart: np.ndarray) -> bool:
        return self.h == h and self.chart is chart

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return self.lu.solve(rhs)


def factorise(matrix, h: float, chart: np.ndarray, z_columns: np.ndarray | None = None) -> IterationMatrix:
    """LU of a system matrix (a BorderedBandMatrix) for step size h in ``chart``, keeping its
    columns ``z_columns`` (default none)."""
    columns = np.zeros((0 if z_columns is None else z_columns.shape[0], matrix.ab.shape[1] + matrix.border))
    for a in range(columns.shape[0]):
        matrix_column(matrix.ab, matrix.brow, matrix.bcol, matrix.bb, matrix.bandwidth, z_columns[a], columns[a])
    try:
        return IterationMatrix(matrix.factorise(), h, chart, columns)
    except np.linalg.LinAlgError as exc:
        raise ConvergenceError(f"singular iteration matrix (a constraint lost rank or a mass vanished): {exc}") from exc


def init(system: MultibodySystem, x0: np.ndarray, F: np.ndarray, t0: float = 0.0,
         v0: np.ndarray | None = None) -> AlphaState:
    """Consistent accelerations and multipliers at (x0, v0): M xdd + Phi_x^T lam = Q - f,
    Phi_x xdd = -Phi_tt - (d/dt Phi_x) v (the drive's prescribed angular acceleration and the
    velocity terms of the clamps, which are linear in the beam coordinates and so contribute
    only through theta). ``v0`` defaults to rest and must satisfy Phi_x v0 + Phi_t = 0."""
    v0 = np.zeros_like(x0) if v0 is None else np.asarray(v0, dtype=float)
    s = system.mass_scale
    layout = system.layout
    zero = np.zeros_like(x0)
    lam0 = np.zeros(layout.n_lambda)
    # force rows (unscaled) at xdd = 0, lambda = 0; constraint rows: the acceleration terms
    rhs = -system.dynamic_residual(x0, v0, zero, lam0, F, t0, 1.0, s)
    rhs[layout.z_of_lambda] = -s * system.constraint_acceleration_terms(x0, v0, F, t0)
    # the matrix [[M, s Phi_x^T], [s Phi_x, 0]] (coef_k = 0 drops stiffness and the Hessian)
    _, matrix = system.dynamic_equations(x0, v0, zero, lam0, F, t0, 1.0, 0.0, 0.0, s)
    z = factorise(matrix, 0.0, F).solve(rhs)
    xdd, mu = layout.split_z(z)
    return AlphaState(t0, x0.copy(), v0.copy(), xdd, xdd.copy(), s * mu, F)


@njit(cache=True)
def algorithmic_acceleration(xdd, xdd_n, a_n, am, af):
    """a_{n+1} from (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) xdd_{n+1} + alpha_f xdd_n."""
    return ((1.0 - af) * xdd + af * xdd_n - am * a_n) / (1.0 - am)


@njit(cache=True)
def predict(x_n, v_n, xdd_n, a_n, h, am, af, beta, gamma, x, v, xdd):
    """Predictor: xdd_{n+1} = xdd_n, and x_{n+1}, v_{n+1} consistent with it (written into x, v, xdd)."""
    for i in range(x_n.shape[0]):
        xdd[i] = xdd_n[i]
        a = algorithmic_acceleration(xdd_n[i], xdd_n[i], a_n[i], am, af)
        v[i] = v_n[i] + h * (1.0 - gamma) * a_n[i] + h * gamma * a
        x[i] = x_n[i] + h * v_n[i] + h * h * (0.5 - beta) * a_n[i] + h * h * beta * a


#: the reference time of the drive multiplier's test (s): its increments are tested as a torque against
#: tolerance * mass_scale * L / MULTIPLIER_TIME^2, whatever the step (:func:`multiplier_weight`)
MULTIPLIER_TIME = 0.01
#: the weight of the multipliers' increments is at most tolerance / (ROUND_OFF_MARGIN * machine epsilon):
#: the weighted round-off of mu (a relative 1e-17 of L, measured) then stays far below the tolerance
ROUND_OFF_MARGIN = 16.0


def multiplier_weight(h: float, beta: float, tolerance: float) -> float:
    """The factor on the drive multiplier's |dmu| in the Newton test (:func:`apply_increment`,
    :func:`multiplier_weights`), so that its test does not loosen as the step h shrinks.

    mu = beta h^2 lambda / mass_scale, and comparing |dmu| with tolerance * L (as the
    coordinates) lets the drive's torque lambda err by tolerance * L * mass_scale / (beta h^2):
    a tolerance that grows as 1/h^2. Modified Newton's stop leaves such an error every step,
    and it fed a lightly damped blade mode: rotor3 (8 or 16 elements) at dt = 1 ms carried a
    211 Hz oscillation of +-0.02 N m in hub_torque, 760 times its time-discretisation error.
    Weighted by MULTIPLIER_TIME^2 / (beta h^2), the test is |dlambda| <= tolerance *
    mass_scale * L / MULTIPLIER_TIME^2 (in the units the length test gave it), for every h
    below MULTIPLIER_TIME * sqrt(1 / beta) (above it the length test is the stricter and
    stays). The weight is capped at tolerance / (ROUND_OFF_MARGIN eps) so that round-off in mu
    never fails the test (steps below about 30 us at the default tolerance)."""
    weight = MULTIPLIER_TIME**2 / (beta * h * h)
    return float(min(max(weight, 1.0), max(tolerance / (ROUND_OFF_MARGIN * np.finfo(float).eps), 1.0)))


def multiplier_weights(layout, h: float, beta: float, tolerance: float, hold_torque: bool = True) -> np.ndarray:
    """The weight of each multiplier's increment in the Newton test (:func:`apply_increment`):
    :func:`multiplier_weight` for the drive's multiplier of a held hub (1 with ``hold_torque``
    False: see :class:`NewtonOptions`), 1 for the clamps'.

    The drive's multiplier is a result: the torque that holds or drives the hub (the
    ``hub_torque`` sensor) and, times the hub speed, the drive power of the energy balance;
    it is tested as a force whatever the step. The clamps' multipliers are internal forces
    that act on the motion only through the step's accelerations, so that their scaled
    increment, a length, is what they move the beams by in the step: the length test bounds
    it as it bounds the coordinates. Weighting them too changed neither rotor3's hub torque
    nor spacecraft's panels measurably, and (while FFR beams were clamped by multipliers) cost
    FFR 30 times the factorisations (exp1: 0.18 per step against 0.006; docs/dynamics.md).
    The base's multipliers (its norm, a table-driven base's drives) keep the length test."""
    weights = np.ones(layout.n_lambda)
    if layout.drive_lambda is not None and hold_torque:
        weights[layout.drive_lambda] = multiplier_weight(h, beta, tolerance)
    return weights


@njit(cache=True)
def apply_increment(dz, z_of_x, z_of_lambda, gprime, bprime, lam_factor, mu_weight, x, v, xdd, lam):
    """Newton correction from dz (placed by the layout maps ``z_of_x``, ``z_of_lambda``):
    x += dx, v += gamma' dx, xdd += beta' dx, lambda += lam_factor dmu. Returns max(|dx|,
    mu_weight |dmu|) (``mu_weight`` per multiplier, :func:`multiplier_weights`): the
    multipliers converge with the coordinates (testing dx alone left the drive's reaction, and
    so the drive work, off by 1e-4 on an FFR beam on a driven hub), the drive's as a torque
    whose tolerance does not depend on the step."""
    size = 0.0
    for i in range(x.shape[0]):
        d = dz[z_of_x[i]]
        x[i] += d
        v[i] += gprime * d
        xdd[i] += bprime * d
        size = max(size, abs(d))
    for i in range(lam.shape[0]):
        d = dz[z_of_lambda[i]]
        lam[i] += lam_factor * d
        size = max(size, mu_weight[i] * abs(d))
    return size


class Outcome(enum.IntEnum):
    """How a run of steps ended (compiled and Python steps alike)."""

    DONE = 0
    CHART_LIMIT_REACHED = 1  # a tangent came near its chart's singular direction: change the chart
    NOT_CONVERGED = 2
    NOT_FINITE = 3
    SINGULAR_MATRIX = 4
    CHART_SINGULARITY = 5
    EVENT_REACHED = 6  # a part's event (a joint at its latch angle): Python changes the system


#: what a failed outcome means, for messages
OUTCOME_MESSAGES = {
    Outcome.NOT_CONVERGED: "Newton did not converge in {its} iterations (last |dx| = {size:.2e})",
    Outcome.NOT_FINITE: "non-finite Newton increment",
    Outcome.SINGULAR_MATRIX: "singular iteration matrix (a constraint lost rank or a mass vanished)",
    Outcome.CHART_SINGULARITY: "a beam tangent is at the singular direction of the rotation chart",
}


@dataclass
class KeptMatrix:
    """The iteration matrix kept between steps (update "adaptive"), its reuse state and the
    contraction rate measured on it (:func:`borrowed_rate`)."""

    matrix: IterationMatrix | None = None
    reuse: np.ndarray = field(default_factory=reuse_state)
    rate: np.ndarray = field(default_factory=borrowed_rate)


def step(system: MultibodySystem, state: AlphaState, h: float, p: AlphaParameters,
         options: NewtonOptions = NewtonOptions(), kept: KeptMatrix | None = None
         ) -> tuple[AlphaState, int, KeptMatrix]:
    """One step of length h in Python (any :class:`MultibodySystem`; systems that compile run the
    same controller in :func:`hubbeam.solvers.compiled_alpha.advance`).

    Returns the new state, the Newton iterations it took and the matrix kept for the next
    step (pass it back in; it is only used with update "adaptive").
    """
    am, af, beta, gamma = p.alpha_m, p.alpha_f, p.beta, p.gamma
    t1 = state.t + h
    x, v, xdd = np.empty_like(state.x), np.empty_like(state.x), np.empty_like(state.x)
    predict(state.x, state.v, state.xdd, state.a, h, am, af, beta, gamma, x, v, xdd)
    lam = state.lam.copy()
    bprime = (1.0 - am) / (beta * h * h * (1.0 - af))
    gprime = gamma / (beta * h)
    ck = beta * h * h
    s = system.mass_scale
    tol = options.tolerance * max(system.length_scale, 1.0)
    weight = multiplier_weights(system.layout, h, beta, options.tolerance, options.tests_hold_torque)
    coefs = (ck * bprime, ck * gprime, ck, s)
    zx, zl = system.layout.z_of_x, system.layout.z_of_lambda
    update = options.update_code
    kept = KeptMatrix() if kept is None else kept
    reuse = kept.reuse
    if kept.matrix is None or not kept.matrix.valid_for(h, state.chart):
        reuse[REUSE_VALID] = 0

    def evaluate(fresh, matrix):
        if not fresh:
            return system.dynamic_residual(x, v, xdd, lam, state.chart, t1, ck, s), matrix
        res, new = system.dynamic_equations(x, v, xdd, lam, state.chart, t1, *coefs)
        factorised(reuse)
        return res, factorise(new, h, state.chart, z_columns)

    columns = joint_columns(system.layout, options.update_columns)
    z_columns = system.layout.z_of_x[columns]
    stale = bool(newton_start(update, reuse))
    res, matrix = evaluate(not stale, kept.matrix)
    patched = False
    drifts = patch_drifts(reuse, stale)
    try:
        if stale and reuse[REUSE_PATCH]:
            reuse[REUSE_PATCH] = 0
            previous = matrix
            matrix = _patched(system, matrix, columns, res, x, v, xdd, lam, t1, gprime, bprime, ck, s)
            steps = patch_made(reuse)
            if steps > 0:
                matrix.follow(previous, steps)
            patched = True
        elif drifts:
            matrix.drift(reuse[REUSE_PATCH_AGE])
    except np.linalg.LinAlgError:
        stale = patched = False
        res, matrix = evaluate(True, None)
    previous = np.inf
    size = np.inf
    for it in range(1, options.max_iterations + 1):
        dz = matrix.solve(-res)
        if not np.all(np.isfinite(dz)):
            reuse[REUSE_VALID] = 0
            raise ConvergenceError(OUTCOME_MESSAGES[Outcome.NOT_FINITE])
        size = apply_increment(dz, zx, zl, gprime, bprime, s / ck, weight, x, v, xdd, lam)
        action = newton_decide(size, previous, it, stale, update, options.refresh_rate, options.refresh_iterations,
                               options.borrowed_rate_steps, tol, reuse, kept.rate, KAPPA, columns.shape[0], patched)
        if action == NewtonAction.CONVERGED:
            a_new = algorithmic_acceleration(xdd, state.xdd, state.a, am, af)
            return AlphaState(t1, x, v, xdd, a_new, lam, state.chart), it, KeptMatrix(matrix, reuse, kept.rate)
        if action == NewtonAction.RESTART:
            predict(state.x, state.v, state.xdd, state.a, h, am, af, beta, gamma, x, v, xdd)
            lam[:] = state.lam
        elif action == NewtonAction.TAKE_BACK:
            apply_increment(-dz, zx, zl, gprime, bprime, s / ck, weight, x, v, xdd, lam)
        fresh = action != NewtonAction.KEEP
        if fresh:
            stale = patched = False
        res, matrix = evaluate(fresh, matrix)
        previous = np.inf if fresh else size
    reuse[REUSE_VALID] = 0
    raise ConvergenceError(OUTCOME_MESSAGES[Outcome.NOT_CONVERGED].format(its=options.max_iterations, size=size))


def _patched(system, matrix, columns, res, x, v, xdd, lam, t, gprime, bprime, ck, s) -> PatchedMatrix:
    """The kept matrix (or the matrix under its patch) with the joint angles' ``columns`` (x
    indices) replaced by the residual's forward differences at (x, v, xdd, lam), ``res`` the
    residual there, and their rows changed by the transpose (:mod:`.column_update`; the
    compiled loop does the same)."""
    base = matrix.base if isinstance(matrix, PatchedMatrix) else matrix
    z_columns = system.layout.z_of_x[columns]
    C = np.empty((res.shape[0], columns.shape[0]))
    for a, j in enumerate(columns):
        d = difference_step(x[j])
        xp, vp, ap = x.copy(), v.copy(), xdd.copy()
        xp[j] += d
        vp[j] += gprime * d
        ap[j] += bprime * d
        C[:, a] = (system.dynamic_residual(xp, vp, ap, lam, base.chart, t, ck, s) - res) / d
    return PatchedMatrix(base, C, z_columns)
