"""The generalized-alpha loop of :mod:`.generalized_alpha` in compiled code, for the ANCF system.

:func:`advance` runs many steps without returning to Python: predictor, Newton iterations
on the compiled equations of motion (:func:`hubbeam.system.ancf_equations.equations_of_motion`),
band LU from LAPACK (:func:`hubbeam.system.assembly.band_factor`), optional reuse of the factorisation (modified
Newton), and the work integrals of the energy balance. It uses the same predictor,
correction and convergence test as :func:`.generalized_alpha.step` (the functions are
shared), so the two give the same steps; tests compare them.

The equations are imported rather than passed in because numba cannot cache a function
that takes another compiled function as an argument, and a cold compile costs seconds.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.solvers.generalized_alpha import (REUSE_VALID, UPDATE_ADAPTIVE, UPDATE_ITERATION,
                                               algorithmic_acceleration, apply_increment,
                                               kept_matrix_failed, kept_matrix_worked, newton_error, predict,
                                               use_kept_matrix)
from hubbeam.system.ancf_equations import CHART_SINGULAR, dissipated_power, equations_of_motion, n_constraints
from hubbeam.system.assembly import band_factor, band_solve

#: what :func:`advance` returns as its status
DONE, CHART_LIMIT_REACHED, NOT_CONVERGED, NOT_FINITE, SINGULAR_MATRIX, CHART_SINGULARITY = 0, 1, 2, 3, 4, 5


@njit(cache=True)
def drive_power(model, lam, v):
    """Power of the drive and the external hub torque on the hub (W)."""
    torque = model.hub_torque
    if n_constraints(model) > 6:
        torque -= lam[6]
    return torque * v[0]


@njit(cache=True)
def advance(model, F, t, x, v, xdd, a, lam, h, n_steps, alpha, newton, mass_scale, chart_limit,
            lu, ipiv, reuse, work, power, counters, schedule, records):
    """Take up to ``n_steps`` steps of length h from (t, x, v, xdd, a, lam) in chart F.

    The state arrays are updated in place after every converged step, so on any failure
    they hold the last good state. ``alpha`` = (alpha_m, alpha_f, beta, gamma); ``newton``
    = (tolerance on |dx| (m), max iterations, NewtonOptions.update_code, refresh rate,
    refresh iterations).
    ``lu`` (band storage, Fortran order), ``ipiv`` and ``reuse`` (the reuse state of
    :func:`hubbeam.solvers.generalized_alpha.reuse_state`; valid means ``lu`` holds factors
    for this h and chart) carry the factorisation between calls. ``work`` (2)
    accumulates the dissipated and the drive work (J) by the trapezoidal rule from the
    powers in ``power`` (2, at the current state; updated).
    ``counters`` (int, 4) accumulates steps, Newton iterations, LU factorisations and
    records. ``schedule`` = (steps before this call, record every so many steps, total
    steps of the run): the state after global step k is copied into row counters[3] of
    ``records`` = (t, x, v, xdd, a, lambda, work) when k is a multiple of the interval or
    the last step.

    Returns (status, last |dx|, time of the state arrays): status DONE, or CHART_LIMIT_REACHED after a step that
    brought a tangent within ``chart_limit`` of the chart's singular direction
    (1 + d.tau < chart_limit; the caller changes the chart), or a failure (NOT_CONVERGED,
    NOT_FINITE, SINGULAR_MATRIX, CHART_SINGULARITY).
    """
    am, af, beta, gamma = alpha
    tol, max_iterations, update, refresh_rate, refresh_iterations = newton
    reused = update != UPDATE_ITERATION  # the matrix serves several iterations
    step0, every, total = schedule
    bw = model.bandwidth
    n = lu.shape[1]
    ck = beta * h * h
    bprime = (1.0 - am) / (ck * (1.0 - af))
    gprime = gamma / (beta * h)
    coef_m, coef_c = ck * bprime, ck * gprime
    x1 = np.empty_like(x)
    v1 = np.empty_like(x)
    xdd1 = np.empty_like(x)
    lam1 = np.empty_like(lam)
    res = np.empty(n)
    empty = np.empty((0, 0)).T  # Fortran layout like lu, so both calls share one compiled version
    size = 0.0
    for k in range(n_steps):
        t1 = t + h
        predict(x, v, xdd, a, h, am, af, beta, gamma, x1, v1, xdd1)
        _copy(lam1, lam)
        stale = update == UPDATE_ADAPTIVE and use_kept_matrix(reuse)  # the matrix is from earlier steps
        fresh = not stale
        margin, _ = equations_of_motion(model, F, x1, v1, xdd1, lam1, t1, coef_m, coef_c, ck, mass_scale,
                                        fresh, res, lu if fresh else empty)
        previous = np.inf
        converged = False
        for it in range(1, max_iterations + 1):
            if not margin > CHART_SINGULAR:
                return CHART_SINGULARITY, size, t
            if fresh:
                reuse[REUSE_VALID] = 0
                counters[2] += 1
                if band_factor(lu, bw, bw, ipiv) != 0:
                    return SINGULAR_MATRIX, size, t
                reuse[REUSE_VALID] = 1
            for i in range(n):
                res[i] = -res[i]
            band_solve(lu, bw, bw, ipiv, res)
            counters[1] += 1
            if not np.all(np.isfinite(res)):
                reuse[REUSE_VALID] = 0
                return NOT_FINITE, size, t
            size = apply_increment(res, gprime, bprime, mass_scale / ck, x1, v1, xdd1, lam1)
            error, rate = newton_error(size, previous, reused)
            if error <= tol:
                converged = True
                if stale:
                    kept_matrix_worked(reuse)
                if update != UPDATE_ADAPTIVE or it > refresh_iterations:
                    reuse[REUSE_VALID] = 0
                break
            fresh = not reused or rate > refresh_rate
            if stale and fresh:
                kept_matrix_failed(reuse)
            if reused and fresh and rate >= 1.0:  # the increment grew: not the place for the matrix
                if stale:  # a matrix from earlier steps: restart from the predictor
                    predict(x, v, xdd, a, h, am, af, beta, gamma, x1, v1, xdd1)
                    _copy(lam1, lam)
                else:  # take the increment back
                    for i in range(n):
                        res[i] = -res[i]
                    apply_increment(res, gprime, bprime, mass_scale / ck, x1, v1, xdd1, lam1)
            if fresh:
                stale = False
            margin, _ = equations_of_motion(model, F, x1, v1, xdd1, lam1, t1, coef_m, coef_c, ck, mass_scale,
                                            fresh, res, lu if fresh else empty)
            previous = np.inf if fresh else size
        if not converged:
            reuse[REUSE_VALID] = 0
            return NOT_CONVERGED, size, t
        for i in range(x.shape[0]):
            a[i] = algorithmic_acceleration(xdd1[i], xdd[i], a[i], am, af)
        _copy(x, x1)
        _copy(v, v1)
        _copy(xdd, xdd1)
        _copy(lam, lam1)
        t = t1
        p_d = dissipated_power(model, v)
        p_h = drive_power(model, lam, v)
        work[0] += 0.5 * h * (power[0] + p_d)
        work[1] += 0.5 * h * (power[1] + p_h)
        power[0] = p_d
        power[1] = p_h
        counters[0] += 1
        step = step0 + k + 1
        if step % every == 0 or step == total:
            _record(records, counters[3], t, x, v, xdd, a, lam, work)
            counters[3] += 1
        if margin < chart_limit:
            return CHART_LIMIT_REACHED, size, t
    return DONE, size, t


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
