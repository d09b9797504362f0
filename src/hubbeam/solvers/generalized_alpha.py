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

import numpy as np
from numba import njit

import enum

from hubbeam.errors import ConvergenceError
from hubbeam.solvers.column_update import PatchedMatrix, difference_step, joint_columns, matrix_column
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


class MatrixUpdate(enum.IntEnum):
    """When the iteration matrix is rebuilt and factorised (:attr:`NewtonOptions.update`,
    by name in lower case); the members are what compiled code compares."""

    ITERATION = 0
    STEP = 1
    ADAPTIVE = 2


#: the names of :class:`MatrixUpdate` that NewtonOptions.update takes
UPDATES = tuple(m.name.lower() for m in MatrixUpdate)


@dataclass(frozen=True)
class NewtonOptions:
    """Newton settings of a step.

    ``tolerance``: on the increment of the coordinates, relative to the beam length (an
    increment-based test: the force residual of a stiff axial beam is floored by round-off
    at EA * 1e-16 * |r'|, far above any fixed force tolerance), and on the multipliers'
    scaled increments (the clamps' as lengths, the drive's as a torque whose tolerance does
    not depend on the step: :func:`multiplier_weights`). When the matrix is reused the
    increment is multiplied by rate / (1 - rate), the estimate of the remaining error from
    the observed contraction rate, and compared with :data:`KAPPA` times the tolerance
    (Hairer and Wanner, IV.8).
    ``update``: when the iteration matrix is rebuilt and factorised:
    "iteration" (full Newton), "step" (once per step at the predictor, reused by the step's
    further iterations: each step costs one factorisation and, as the matrix is that of the
    current step, converges about as fast as full Newton), or "adaptive" (modified Newton:
    reused across iterations and steps, refreshed when the contraction rate exceeds
    ``refresh_rate`` or on the next step after a step that needed more than
    ``refresh_iterations``; after a kept matrix fails, steps start with fresh ones for a
    while, see :func:`use_kept_matrix`). "step" and "adaptive" refresh within a step too when the rate
    exceeds ``refresh_rate``. When an increment grows (rate >= 1) the fresh matrix is built
    at the previous iterate (the increment is taken back), or at the predictor when the
    matrix was from earlier steps.
    ``hold_torque``: whether the drive multiplier of a held hub is tested as a torque
    (:func:`multiplier_weight`), as a result must be (the ``hub_torque`` sensor, and the drive
    power lambda theta' of a prescribed hub). None (the default) means True, except that
    :func:`hubbeam.simulation.simulate` makes it False for a fixed hub whose holding torque no
    sensor reads: theta' = 0 exactly, so that torque does no work, and it is then an internal
    reaction tested as a length like the clamps' (case M's tumbling bus with modal panels took
    1.97 Newton iterations per step with the torque test, 1.00 without: benchmarks/run.py).
    ``update_columns``: with update "adaptive", a kept matrix that went stale is first
    patched in its joint angles' columns (:mod:`.column_update`: one residual per joint angle
    instead of a new matrix and its LU) and refactorised only when that does not help (False:
    always refactorised, as before the update existed; for comparisons).
    ``borrowed_rate_steps``: with a matrix kept from earlier steps, a step may stop after its
    first increment dx1 when |dx1| theta / (1 - theta) is below :data:`KAPPA` times the
    tolerance, the same test as after a second increment but with the contraction rate theta
    borrowed from earlier steps that iterated twice on the same kept matrix (the same factors
    and the same patch: a factorisation or a new patch drops it; the larger of the last two,
    scaled by the matrix's age: :func:`newton_decide`; Hairer and Wanner, IV.8; SUNDIALS IDA
    carries its rate between steps the same way). At most this many steps in a row stop so;
    the next iterates twice and measures theta again. 0 (the default): every step on a kept
    matrix iterates at least twice. Measured with 8 on experiment 1 with 4 modes (20 s at
    1 ms): 1.11 Newton iterations per step instead of 1.99, its strains within 2e-6
    (relative) of a run converged to a tolerance of 1e-12, where the step size's error is
    about 1e-3; but the leftovers of the borrowed steps have the same sign step after step, so
    conserved quantities drift: an undamped modal beam on a free hub drifts in energy by
    2.8e-5 of its kinetic energy in 20 s where it drifted by 4e-8, and a lag-hinged FFR blade's
    angular momentum on a free hub by 8.8e-8 where it stayed within 1.3e-8. That is why it is
    off by default (docs/dynamics.md).
    """

    tolerance: float = 1e-9
    #: 30 (25 before the drive's torque was tested as a torque and KAPPA was 0.01; the hardest
    #: step of tests/solvers/test_compiled_alpha.py, dt = 5 ms, then needs 26)
    max_iterations: int = 30
    update: str = "adaptive"
    refresh_rate: float = 0.25
    refresh_iterations: int = 2
    hold_torque: bool | None = None
    update_columns: bool = True
    borrowed_rate_steps: int = 0

    def __post_init__(self) -> None:
        if self.update not in UPDATES:
            raise ValueError(f"Newton matrix update {self.update!r}: choose one of {UPDATES}")
        if self.borrowed_rate_steps < 0:
            raise ValueError(f"borrowed_rate_steps {self.borrowed_rate_steps}: must be 0 or more")

    @property
    def tests_hold_torque(self) -> bool:
        """Whether the Newton test takes the held hub's drive multiplier as a torque (``hold_torque``
        True or still None)."""
        return self.hold_torque is not False

    @property
    def update_code(self) -> int:
        """The :class:`MatrixUpdate` of ``update`` as an int (for compiled code)."""
        return int(MatrixUpdate[self.update.upper()])


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


#: the rate-based error estimate must be below KAPPA * tolerance (Hairer and Wanner, IV.8,
#: take kappa between 0.01 and 0.1): with a reused matrix the error left after the last
#: increment is about the estimate itself, while full Newton leaves far less than its last
#: increment. Each step's leftover adds up over the steps in the lightly damped modes:
#: spacecraft (8 elements per panel, 20 s at dt = 1 ms) ended 1.2e-4 N m from full Newton's
#: torque and with its two identical panels 2.9e-8 m apart with kappa = 0.1; 0.01 takes that
#: to 1.1e-5 N m and 9e-10 m (at 0.5 ms: 1.4e-8 N m and 6e-12 m), for 7 % more iterations on
#: exp1 (0.03: 1.7e-5 N m and 2e-8 m; docs/dynamics.md has the measurements and the cost).
KAPPA = 0.01


@njit(cache=True)
def newton_error(size, previous, reused, kappa):
    """(error measure to compare with the tolerance, contraction rate) after an increment of
    max size ``size``; ``previous`` is the last increment since the matrix was refreshed
    (inf right after a refresh); ``reused``: the matrix is kept across iterations (update
    "step" or "adaptive"). With a rate the measure is size rate / (1 - rate) / kappa
    (:data:`KAPPA`, passed in: numba's cache of a caller in another module keeps the values
    of this module's constants it was compiled with)."""
    rate = size / previous
    if reused and np.isfinite(previous):
        return (size * rate / (1.0 - rate) / kappa if rate < 1.0 else np.inf), rate
    return size, rate


#: the reuse state of a kept iteration matrix, an int array shared with compiled code:
#: [matrix valid, back-off (steps to wait after the next failure), steps still to wait,
#: the next step patches the kept matrix's joint columns (:mod:`.column_update`), the kept
#: factors carry a patch, the patches' back-off (stale matrices to refactorise after the next
#: failed patch), stale matrices still to refactorise before the next patch, steps since the
#: kept factors' patch was made, steps between it and the patch before on the same factors (0:
#: none; the patch then drifts, :mod:`.column_update`), steps in a row that stopped after one
#: increment on a borrowed contraction rate (negative: minus the rates still to measure on the
#: kept matrix before one is borrowed), the kept matrix's age (steps that started with it since
#: it was factorised or patched; :func:`newton_decide`)]
(REUSE_VALID, REUSE_BACKOFF, REUSE_WAIT, REUSE_PATCH, REUSE_PATCHED, REUSE_PATCH_BACKOFF, REUSE_PATCH_WAIT,
 REUSE_PATCH_AGE, REUSE_DRIFT_STEPS, REUSE_BORROWED, REUSE_AGE) = range(11)
#: the contraction rates a kept matrix must show before a step borrows them (:func:`newton_decide`)
MEASURED_RATES = 2
#: longest wait (steps, or for patches stale matrices) before a kept matrix or a patch is tried again after failures
MAX_BACKOFF = 64


def reuse_state() -> np.ndarray:
    """A fresh reuse state: no matrix kept, back-offs 1, no contraction rate to borrow."""
    return np.array([0, 1, 0, 0, 0, 1, 0, 0, 0, -MEASURED_RATES, 0], dtype=np.int64)


def borrowed_rate() -> np.ndarray:
    """Storage of the contraction rates a step may borrow (:func:`newton_decide`), carried
    between steps beside the reuse state: the last :data:`MEASURED_RATES` rates measured on the
    kept matrix, each divided by the matrix's age when it was measured (valid only while
    ``reuse[REUSE_BORROWED] >= 0``)."""
    return np.zeros(MEASURED_RATES)


@njit(cache=True)
def use_kept_matrix(reuse):
    """Whether a step starts with the kept matrix (update "adaptive"). After a kept matrix
    failed to contract, steps start with fresh matrices for a while (exponential back-off:
    1, 2, 4, ... up to MAX_BACKOFF steps), so a problem whose matrix changes quickly between
    steps (a stiff beam turning fast) pays little for trying; one where it does not keeps
    the matrix for many steps."""
    if reuse[REUSE_VALID] == 0:
        return False
    if reuse[REUSE_WAIT] > 0:
        reuse[REUSE_WAIT] -= 1
        return False
    return True


@njit(cache=True)
def kept_matrix_failed(reuse):
    reuse[REUSE_WAIT] = reuse[REUSE_BACKOFF]
    reuse[REUSE_BACKOFF] = min(2 * reuse[REUSE_BACKOFF], MAX_BACKOFF)


@njit(cache=True)
def kept_matrix_worked(reuse):
    reuse[REUSE_BACKOFF] = 1


@njit(cache=True)
def factorised(reuse):
    """The reuse state after a factorisation: the matrix is valid, carries no patch and has no
    contraction rate measured on it."""
    reuse[REUSE_VALID] = 1
    reuse[REUSE_PATCH] = 0
    reuse[REUSE_PATCHED] = 0
    reuse[REUSE_PATCH_AGE] = 0
    reuse[REUSE_DRIFT_STEPS] = 0
    reuse[REUSE_BORROWED] = -MEASURED_RATES
    reuse[REUSE_AGE] = 0


@njit(cache=True)
def patch_drifts(reuse, stale):
    """At a step's start (``stale``: it starts with the kept matrix): age the kept factors'
    patch by a step and say whether it drifts in this step (it is not replaced by a new patch
    and was made after another on the same factors: :mod:`.column_update`)."""
    if not (stale and reuse[REUSE_PATCHED] == 1):
        return False
    reuse[REUSE_PATCH_AGE] += 1
    return reuse[REUSE_PATCH] == 0 and reuse[REUSE_DRIFT_STEPS] > 0


@njit(cache=True)
def patch_made(reuse):
    """After a new patch: the steps since the one before on the same factors (0: none), which
    are now the steps its drift is measured over. A contraction rate measured on the matrix
    before the patch is dropped."""
    steps = reuse[REUSE_PATCH_AGE] if reuse[REUSE_PATCHED] == 1 else 0
    reuse[REUSE_BORROWED] = -MEASURED_RATES
    reuse[REUSE_AGE] = 0
    reuse[REUSE_DRIFT_STEPS] = steps
    reuse[REUSE_PATCH_AGE] = 0
    reuse[REUSE_PATCHED] = 1
    return steps


@njit(cache=True)
def patch_failed(reuse):
    """A patched matrix did not bring its step back to ``refresh_iterations``: refactorise
    the next stale matrices instead of patching them (exponential back-off, as
    :func:`use_kept_matrix`), so that a system whose matrix goes stale in other directions
    than its joint angles (an ANCF beam's own nonlinearity) pays little for trying."""
    reuse[REUSE_PATCH_WAIT] = reuse[REUSE_PATCH_BACKOFF]
    reuse[REUSE_PATCH_BACKOFF] = min(2 * reuse[REUSE_PATCH_BACKOFF], MAX_BACKOFF)


@njit(cache=True)
def patch_next(reuse, columns):
    """Whether a kept matrix that went stale is patched (its ``columns`` joint columns
    refreshed, :mod:`.column_update`) rather than refactorised."""
    if columns == 0:
        return False
    if reuse[REUSE_PATCH_WAIT] > 0:
        reuse[REUSE_PATCH_WAIT] -= 1
        return False
    return True


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


class NewtonAction(enum.IntEnum):
    """What the Newton controller asks for after an increment."""

    CONVERGED = 0
    KEEP = 1  # iterate with the same matrix
    REFRESH = 2  # build and factorise a new matrix at the current iterate
    TAKE_BACK = 3  # the increment grew: undo it, then refresh
    RESTART = 4  # a matrix of earlier steps diverged: restart from the predictor, then refresh


@njit(cache=True)
def newton_start(update, reuse):
    """Whether a step starts with the matrix kept from earlier steps (update "adaptive"); if
    so, the matrix ages by a step."""
    if update == MatrixUpdate.ADAPTIVE and use_kept_matrix(reuse):
        reuse[REUSE_AGE] += 1
        return True
    return False


@njit(cache=True)
def max_rate(rate):
    """The largest entry of ``rate`` (:func:`borrowed_rate`)."""
    largest = rate[0]
    for i in range(1, rate.shape[0]):
        largest = max(largest, rate[i])
    return largest


@njit(cache=True)
def newton_decide(size, previous, it, stale, update, refresh_rate, refresh_iterations, borrowed_steps, tol, reuse,
                  rate, kappa, columns, patched):
    """The Newton controller, shared by every integration path: after an increment of max
    size ``size`` (``previous``: the last one since the matrix was refreshed, inf right after
    a refresh; ``stale``: the matrix is from earlier steps; ``patched``: and its joint
    columns were refreshed at this step's start) decide what comes next
    (:class:`NewtonAction`) and update the reuse state (see :class:`NewtonOptions`); ``kappa``
    the factor of the rate-based error estimate (:data:`KAPPA`); ``columns`` the number of
    joint angles whose columns a patch refreshes (:mod:`.column_update`; 0: never patch).

    A kept matrix that needed more than ``refresh_iterations`` is patched at the next step
    (:func:`patch_next`), or refactorised there if this step's matrix was patched already
    (:func:`patch_failed`) or patches are backing off.

    The first increment on a stale matrix that was not patched at this step is accepted when
    the error estimate with a contraction rate borrowed from earlier steps on the same matrix
    is below the tolerance, at most ``borrowed_steps`` steps in a row
    (:attr:`NewtonOptions.borrowed_rate_steps`); the second increment on such a matrix measures
    the rate anew. The borrowed rate is the larger of the last :data:`MEASURED_RATES` measured
    on the matrix since its factorisation or its last patch (``rate``: each divided by the
    matrix's age then), times the matrix's age now. The larger of several: one pair of
    increments measures the contraction along the direction of that step's first error only,
    and on a hinge one such rate came out 2e-6 where the matrix contracted other steps' errors
    at 5e-3 (the borrowed steps then left 1e-8 m, a thousand times the estimate). Times the
    age: the rate grows as the exact tangent drifts away from the kept matrix, about linearly
    in the steps since it was made, so a matrix that goes stale within a few steps (a hinge)
    is not trusted with the smaller rate of its first steps. ``reuse[REUSE_BORROWED]`` counts
    the steps in a row that borrowed (negative: rates still to measure)."""
    reused = update != MatrixUpdate.ITERATION
    kept = stale and not patched
    age = reuse[REUSE_AGE]
    if it == 1 and kept and 0 <= reuse[REUSE_BORROWED] < borrowed_steps:
        theta = age * max_rate(rate)
        if theta < refresh_rate and size * theta / (1.0 - theta) / kappa <= tol:
            kept_matrix_worked(reuse)
            reuse[REUSE_BORROWED] += 1
            return NewtonAction.CONVERGED
    error, rate_now = newton_error(size, previous, reused, kappa)
    if it == 2 and kept:
        for i in range(rate.shape[0] - 1, 0, -1):
            rate[i] = rate[i - 1]
        rate[0] = rate_now / age
        reuse[REUSE_BORROWED] = reuse[REUSE_BORROWED] + 1 if reuse[REUSE_BORROWED] < 0 else 0
    if error <= tol:
        if stale:
            kept_matrix_worked(reuse)
        if update != MatrixUpdate.ADAPTIVE or it > refresh_iterations:
            if patched:
                patch_failed(reuse)
                reuse[REUSE_VALID] = 0
            elif stale and update == MatrixUpdate.ADAPTIVE and patch_next(reuse, columns):
                reuse[REUSE_PATCH] = 1
            else:
                reuse[REUSE_VALID] = 0
        elif patched:
            reuse[REUSE_PATCH_BACKOFF] = 1
        return NewtonAction.CONVERGED
    fresh = not reused or rate_now > refresh_rate
    if stale and fresh:
        kept_matrix_failed(reuse)
        if patched:
            patch_failed(reuse)
    if reused and fresh and rate_now >= 1.0:
        return NewtonAction.RESTART if stale else NewtonAction.TAKE_BACK
    return NewtonAction.REFRESH if fresh else NewtonAction.KEEP


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
