"""The Newton controller of a generalized-alpha step, shared by the Python step
(:func:`hubbeam.solvers.generalized_alpha.step`), the compiled time loop
(:func:`hubbeam.solvers.compiled_alpha.advance`) and the static solver: its options
(:class:`NewtonOptions`), the error estimate from the contraction rate (Hairer and Wanner,
IV.8), the reuse state of an iteration matrix kept across iterations and steps (with its
back-offs, joint-column patches and borrowed rates) and the decision after each increment
(:func:`newton_decide`, :class:`NewtonAction`).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np
from numba import njit


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
    not depend on the step: :func:`.generalized_alpha.multiplier_weights`). When the matrix is reused the
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
    (:func:`.generalized_alpha.multiplier_weight`), as a result must be (the ``hub_torque`` sensor, and the drive
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
    if it == 2 and kept and borrowed_steps > 0:  # measured only where a later step may borrow it
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
