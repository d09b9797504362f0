"""The generalized-alpha loop of :mod:`.generalized_alpha` in compiled code.

:func:`advance` runs many steps without returning to Python: predictor, Newton iterations
on the compiled equations of the hub and its beams
(:func:`hubbeam.system.equations.equations_at`, the model passed by reference), the bordered band LU
(:func:`hubbeam.system.assembly.bordered_factor`), and the work integrals of the energy
balance. Its Newton control is the shared controller (:func:`.newton_control.newton_start`,
:func:`.newton_control.newton_decide`), as is the Python step's, so the two give the same
steps; tests compare them.

The equations are imported rather than passed in because numba cannot cache a function
that takes another compiled function as an argument, and a cold compile costs seconds.
"""

from __future__ import annotations

from functools import cache

import numpy as np
from numba import njit

from hubbeam.solvers.column_update import (capacitance, column_change, difference_step, drifted, matrix_column,
                                           patch_solve, record_drift, unit_rows)
from hubbeam.solvers.generalized_alpha import Outcome, algorithmic_acceleration, apply_increment, predict
from hubbeam.solvers.newton_control import (REUSE_PATCH, REUSE_PATCH_AGE, REUSE_PATCHED, REUSE_VALID, NewtonAction,
                                            factorised, newton_decide, newton_start, patch_drifts, patch_made)
from hubbeam.system.assembly import bordered_factor, bordered_solve
from hubbeam.system.by_reference import address_of
from hubbeam.system.equations import CHART_SINGULAR, equations_at, events_at, powers_at


def cache_is_cold(function=None) -> bool:
    """True when ``function`` (a ``cache=True`` numba function; default :func:`advance`) has no
    usable compiled code in numba's on-disk cache: its index file (``*.nbi`` in the module's
    ``__pycache__`` or numba's cache directory) is missing or was made for other sources or
    another numba, so that its first call compiles it -- for :func:`advance`, the time loop and
    the equations: about a minute. False if that cannot be told."""
    try:
        return not (advance if function is None else function)._cache._cache_file._load_index()
    except (AttributeError, OSError, EOFError, ValueError):  # numba's internals changed: say nothing
        return False


@njit(cache=True)
def advance(model, F, t, x, v, xdd, a, lam, h, n_steps, alpha, newton, mass_scale, chart_limit,
            matrix, reuse, rate, patch, work, power, counters, schedule, records):
    """Take up to ``n_steps`` steps of length h from (t, x, v, xdd, a, lam) in the charts F.

    The state arrays are updated in place after every converged step, so on any failure
    they hold the last good state. ``alpha`` = (alpha_m, alpha_f, beta, gamma); ``newton``
    = (tolerance on |dx| (m), max iterations, NewtonOptions.update_code, refresh rate,
    refresh iterations, the multipliers' weights of
    :func:`~hubbeam.solvers.generalized_alpha.multiplier_weights`, the factor kappa of the
    rate-based error estimate, NewtonOptions.borrowed_rate_steps). ``matrix`` = (ab, ipiv,
    brow, bcol, bb, Y, schur, scratch): the bordered storage, its factors
    (:func:`hubbeam.system.assembly.bordered_factor`) and the solves' scratch (border), and ``reuse``
    (the reuse state of :func:`hubbeam.solvers.newton_control.reuse_state`; valid means
    the factors are for this h and these charts) carry the factorisation between calls, and
    ``rate`` (1) the contraction rate measured on it
    (:func:`hubbeam.solvers.newton_control.borrowed_rate`).
    ``patch`` = (columns (x indices of the joint angles, int), their z indices, the kept
    matrix's columns, G, H, Ut, G and Ut of the last patch, their drifts per step, K^-1, S, w,
    s, residual): the storage of a column update of the kept factors
    (:mod:`hubbeam.solvers.column_update`: eight k x n, two 2k x 2k, two 2k, one n), carried
    between calls with ``reuse``.
    ``work`` (2) accumulates the dissipated and the drive work (J) by the trapezoidal rule
    from the powers in ``power`` (2, at the current state; updated). ``counters`` (int, 5)
    accumulates steps, Newton iterations, LU factorisations, records and column updates. ``schedule`` =
    (steps before this call, record every so many steps, total steps of the run): the state
    after global step k is copied into row counters[3] of ``records`` = (t, x, v, xdd, a,
    lambda, work) when k is a multiple of the interval or the last step.

    Returns (outcome (:class:`~hubbeam.solvers.generalized_alpha.Outcome`), last |dx|, time of
    the state arrays): DONE, or EVENT_REACHED after a step that reached a part's event (a joint
    at its latch angle: the caller changes the system), or CHART_LIMIT_REACHED after a step that
    brought a tangent within ``chart_limit`` of its chart's singular direction (1 + d.tau <
    chart_limit; the caller changes the chart), or a failure.
    """
    am, af, beta, gamma = alpha
    tol, max_iterations, update, refresh_rate, refresh_iterations, mu_weight, kappa, borrowed_steps = newton
    ab, ipiv, brow, bcol, bb, Y, schur, scratch = matrix
    columns, z_columns, kept, G, H, Ut, G_last, Ut_last, G_drift, Ut_drift, K_inverse, S, w_patch, s_patch, res_patch \
        = patch
    n_columns = columns.shape[0]
    step0, every, total = schedule
    zx, zl = model.context.z_of_x, model.context.z_of_lambda
    n = zx.shape[0] + zl.shape[0]
    ck = beta * h * h
    bprime = (1.0 - am) / (ck * (1.0 - af))
    gprime = gamma / (beta * h)
    coef_m, coef_c = ck * bprime, ck * gprime
    x1 = np.empty_like(x)
    v1 = np.empty_like(x)
    xdd1 = np.empty_like(x)
    lam1 = np.empty_like(lam)
    res = np.empty(n)
    size = 0.0
    # run-time booleans, not the literals False and True: numba compiles a function once per
    # literal argument, and equations_at is the largest compile of all (each literal passed
    # to it below compiled it once more: ~8 s of CPU each on the first run)
    exact = n < 0  # no exact load stiffness in a time step
    no_matrix = n < 0  # the patch's difference quotients need the residual only
    new_matrix = n >= 0
    # the model by reference: passed by value, every call of the equations copied its ~550 words
    # (on exp1; hubbeam.system.by_reference)
    model_at = address_of(model)
    for k in range(n_steps):
        t1 = t + h
        predict(x, v, xdd, a, h, am, af, beta, gamma, x1, v1, xdd1)
        _copy(lam1, lam)
        stale = newton_start(update, reuse)
        fresh = not stale
        margin, _ = equations_at(model_at, F, x1, v1, xdd1, lam1, t1, coef_m, coef_c, ck, mass_scale, 1.0, exact,
                                 fresh, res, ab, brow, bcol, bb)
        patched = False
        drifts = patch_drifts(reuse, stale)
        if stale and reuse[REUSE_PATCH] == 1:
            # the joint angles' columns by forward differences of the residual, then G = A^-1 C
            # (hubbeam.solvers.column_update; generalized_alpha._patched is the same in Python)
            reuse[REUSE_PATCH] = 0
            for c in range(n_columns):
                j = columns[c]
                xj, vj, aj = x1[j], v1[j], xdd1[j]
                d = difference_step(xj)
                x1[j] = xj + d
                v1[j] = vj + gprime * d
                xdd1[j] = aj + bprime * d
                equations_at(model_at, F, x1, v1, xdd1, lam1, t1, coef_m, coef_c, ck, mass_scale, 1.0, exact,
                             no_matrix, res_patch, ab, brow, bcol, bb)
                x1[j], v1[j], xdd1[j] = xj, vj, aj
                for i in range(n):
                    G[c, i] = (res_patch[i] - res[i]) / d
            column_change(G, kept, z_columns, Ut)
            unit_rows(H, z_columns)
            for c in range(n_columns):
                bordered_solve(ab, model.bandwidth, ipiv, brow, Y, schur, G[c], scratch)
                bordered_solve(ab, model.bandwidth, ipiv, brow, Y, schur, H[c], scratch)
            if capacitance(G, H, Ut, z_columns, S, K_inverse) == 0:
                record_drift(G, Ut, G_last, Ut_last, G_drift, Ut_drift, patch_made(reuse))
                patched = True
                counters[4] += 1
            else:  # the patched matrix is singular: refactorise
                stale = False
                fresh = True
                margin, _ = equations_at(model_at, F, x1, v1, xdd1, lam1, t1, coef_m, coef_c, ck, mass_scale, 1.0,
                                         exact, new_matrix, res, ab, brow, bcol, bb)
        elif drifts:  # the patch, extrapolated to this step (hubbeam.solvers.column_update)
            drifted(G_last, Ut_last, G_drift, Ut_drift, reuse[REUSE_PATCH_AGE], G, Ut)
            if capacitance(G, H, Ut, z_columns, S, K_inverse) != 0:  # singular: refactorise
                stale = False
                fresh = True
                margin, _ = equations_at(model_at, F, x1, v1, xdd1, lam1, t1, coef_m, coef_c, ck, mass_scale, 1.0,
                                         exact, new_matrix, res, ab, brow, bcol, bb)
        previous = np.inf
        converged = False
        for it in range(1, max_iterations + 1):
            if not margin > CHART_SINGULAR:
                return Outcome.CHART_SINGULARITY, size, t
            if fresh:
                reuse[REUSE_VALID] = 0
                counters[2] += 1
                for c in range(n_columns):
                    matrix_column(ab, brow, bcol, bb, model.bandwidth, z_columns[c], kept[c])
                if bordered_factor(ab, model.bandwidth, ipiv, brow, bcol, bb, Y, schur) != 0:
                    return Outcome.SINGULAR_MATRIX, size, t
                factorised(reuse)
            for i in range(n):
                res[i] = -res[i]
            bordered_solve(ab, model.bandwidth, ipiv, brow, Y, schur, res, scratch)
            if reuse[REUSE_PATCHED] == 1:
                patch_solve(G, H, Ut, K_inverse, z_columns, res, w_patch, s_patch)
            counters[1] += 1
            if not _all_finite(res):
                reuse[REUSE_VALID] = 0
                return Outcome.NOT_FINITE, size, t
            size = apply_increment(res, zx, zl, gprime, bprime, mass_scale / ck, mu_weight, x1, v1, xdd1, lam1)
            action = newton_decide(size, previous, it, stale, update, refresh_rate, refresh_iterations, borrowed_steps,
                                   tol, reuse, rate, kappa, n_columns, patched)
            if action == NewtonAction.CONVERGED:
                converged = True
                break
            if action == NewtonAction.RESTART:
                predict(x, v, xdd, a, h, am, af, beta, gamma, x1, v1, xdd1)
                _copy(lam1, lam)
            elif action == NewtonAction.TAKE_BACK:
                for i in range(n):
                    res[i] = -res[i]
                apply_increment(res, zx, zl, gprime, bprime, mass_scale / ck, mu_weight, x1, v1, xdd1, lam1)
            fresh = action != NewtonAction.KEEP
            if fresh:
                stale = False
                patched = False
            margin, _ = equations_at(model_at, F, x1, v1, xdd1, lam1, t1, coef_m, coef_c, ck, mass_scale, 1.0,
                                     exact, fresh, res, ab, brow, bcol, bb)
            previous = np.inf if fresh else size
        if not converged:
            reuse[REUSE_VALID] = 0
            return Outcome.NOT_CONVERGED, size, t
        for i in range(x.shape[0]):
            a[i] = algorithmic_acceleration(xdd1[i], xdd[i], a[i], am, af)
        _copy(x, x1)
        _copy(v, v1)
        _copy(xdd, xdd1)
        _copy(lam, lam1)
        t = t1
        p_d, p_h = 0.0, 0.0
        if model.powers:  # else no part can have a power (a call costs ~0.2-0.5 us)
            p_d, p_h = powers_at(model_at, F, t, x, v, lam)
        work[0] += 0.5 * h * (power[0] + p_d)
        work[1] += 0.5 * h * (power[1] + p_h)
        power[0] = p_d
        power[1] = p_h
        counters[0] += 1
        step = step0 + k + 1
        if step % every == 0 or step == total:
            _record(records, counters[3], t, x, v, xdd, a, lam, work)
            counters[3] += 1
        if model.events and events_at(model_at, x):  # a call costs ~0.3-1 us: skipped where no event can happen
            return Outcome.EVENT_REACHED, size, t
        if margin < chart_limit:
            return Outcome.CHART_LIMIT_REACHED, size, t
    return Outcome.DONE, size, t


@njit(cache=True)
def _all_finite(a):
    """np.all(np.isfinite(a)) without the temporary boolean array."""
    for i in range(a.shape[0]):
        if not np.isfinite(a[i]):
            return False
    return True


@njit(cache=True)
def _copy(dst, src):
    """dst[:] = src as a plain loop (slice assignment compiles to much more code)."""
    for i in range(src.shape[0]):
        dst[i] = src[i]


@njit(cache=True)
def _record(records, row, t, x, v, xdd, a, lam, work):
    rt, rx, rv, rxdd, ra, rlam, rwork = records
    rt[row] = t
    for i in range(x.shape[0]):
        rx[row, i] = x[i]
        rv[row, i] = v[i]
        rxdd[row, i] = xdd[i]
        ra[row, i] = a[i]
    for i in range(lam.shape[0]):
        rlam[row, i] = lam[i]
    rwork[row, 0] = work[0]
    rwork[row, 1] = work[1]


def loop_for(system):
    """The compiled loop for ``system``: :func:`advance`, or for a system with a kind of part
    defined outside hubbeam an uncached copy of it that calls the uncached equations
    (:func:`hubbeam.system.equations.uncached_twins`)."""
    functions = system.functions
    if functions.equations_at is equations_at:
        return advance
    return _uncached_loop(functions)


@cache
def _uncached_loop(functions):
    """An uncached copy of :func:`advance` calling ``functions`` (uncached equations)."""
    from hubbeam.system.equations import uncached_twins

    return uncached_twins({"advance": advance}, functions._asdict())["advance"]
