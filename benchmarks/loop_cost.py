"""Where a modal step's time goes inside the compiled time loop, and what the first-iteration
Newton test saves (issue 26).

    python benchmarks/loop_cost.py parts CASE [REPS]
    python benchmarks/loop_cost.py first-iteration CASE [REPS] [M,M,...] [OVERRIDE ...]
    python benchmarks/loop_cost.py copies CASE [REPS]   # the loop's speed against copies of its source
    python benchmarks/loop_cost.py powers exp1_modal   # the step's powers by parts (us per call)
    python benchmarks/loop_cost.py rates exp1_modal [STEPS]   # Newton's increments, Python steps

CASE: exp1_modal (experiment 1 on 4 modes, 20 s at 1 ms), exp1_nodal (nodal FFR, 20 s),
exp1_ancf (ANCF, 5 s), R (case R: case A's plate on 4 modes, 10 s at 1 ms). Every run goes
through ``api.run``; the time is the process time spent in the compiled loop's calls alone (the
run's ~100 chunks; not the recording and sensors around them), per step, median and range of
REPS runs that alternate between the variants in this one process. numba's cache must be warm.

``parts``: the loop as it is (:func:`hubbeam.solvers.compiled_alpha.advance`), an uncached copy
of it (:func:`hubbeam.system.equations.uncached_twins`: the copies below compile as it does),
the copy without the step's powers (a function returning zeros in place of ``step_powers``), and
that copy again with every evaluation of the system's equations done twice (the second
evaluation's cost is the residuals' share of the step). The rest is the loop's own work:
predictor, band solves, increments, Newton control, records.

``first-iteration``: the solver's loop with ``NewtonOptions.borrowed_rate_steps`` = M for each M
given (default 0,1,3,8; 8 is the default, 0 the solver before the test existed): a step whose
iteration matrix is kept from earlier steps may stop after its first increment dx1 when
|dx1| theta / (1 - theta) / kappa <= tolerance, theta borrowed from earlier steps on the same
kept matrix (:func:`hubbeam.solvers.newton_control.newton_decide`), at most M such steps in a
row. Prints the loop's time per step, Newton iterations per step and the results (exp1: the P1
strain at 5 s, its peak and end; R: the vertical tip's minimum and end). OVERRIDEs are passed
to the scenario (e.g. analysis.tolerance=1e-12 for a reference converged further).

``copies``: the loop as it is against copies of its source compiled in this process: unchanged,
and with one more (unused) integer argument first: how much the compiled loop's speed moves
with code that does nothing.

``powers``: one call (process time, best of 5, as ``step_cost.py``) of the step's powers
(``step_powers``), of the frames' kinematics to order 1 and 2 (``evaluate_chains``: the powers
evaluate them to order 1, each residual to order 2) and of the FFR beams' dissipated power
(``ffr_beams._dissipated_power``: the drag and the structural damping), at the initial state with
every rate raised by 0.1.

``rates``: the first STEPS (default 2000) steps in Python (:func:`hubbeam.solvers.generalized_alpha.step`,
the controller the compiled loop shares) at M = 0 with the Newton controller's calls logged: the
first increments |dx1|, the contraction rates theta = |dx2| / |dx1| of the steps that iterated
twice, and how many steps a first-iteration test with the rate of the step before would have
accepted.
"""

from __future__ import annotations

import functools
import inspect
import os
import statistics
import sys
import textwrap
import time

import numpy as np
from numba import njit

import hubbeam.simulation as simulation
from hubbeam import api
from hubbeam.io.scenario import load_example, load_scenario
from hubbeam.solvers import compiled_alpha
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers import newton_control as nc
from hubbeam.simulation import initial_state
from hubbeam.system.equations import step_powers, system_equations, uncached_twins
from hubbeam.system.ffr_beams import FfrBeams, _dissipated_power
from hubbeam.system.frames import evaluate_chains

CASES = {"exp1_modal": (['beam.formulation="ffr"', "beam.modes=4"], 20.0),
         "exp1_nodal": (['beam.formulation="ffr"'], 20.0),
         "exp1_ancf": ([], 5.0),
         "R": (['beam.formulation="ffr"', "beam.modes=4", "beam.elements=8", "analysis.dt=0.001"], 10.0)}


def scenario(case: str, t_end: float, overrides: list[str]):
    base, _ = CASES[case]
    if case == "R":
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "case_a.toml")
        return load_scenario(path, base + overrides + [f"analysis.t_end={t_end}"])
    return load_example("exp1", base + overrides + [f"analysis.t_end={t_end}"])


@njit(_nrt=False)
def _no_powers(model, F, t, x, v, lam):
    return 0.0, 0.0


@njit(_nrt=False)
def _equations_twice(model, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact, want, res, ab,
                     brow, bcol, bb):
    system_equations(model, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact, want, res, ab,
                     brow, bcol, bb)
    return system_equations(model, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact, want, res,
                            ab, brow, bcol, bb)


def _loop_source():
    return textwrap.dedent(inspect.getsource(compiled_alpha.advance.py_func)).replace("@njit(cache=True)\n", "")


def _compile_copy(src, name):
    namespace = dict(compiled_alpha.__dict__)
    exec(src, namespace)
    return njit(namespace[name])


class TimedLoop:
    """Replaces the compiled loop that api.run's steps call by ``loop`` and sums its process time."""

    def __init__(self):
        self.loop, self.seconds = None, 0.0
        simulation.compiled_alpha.loop_for = lambda system: self

    def __call__(self, *args):
        start = time.process_time()
        out = self.loop(*args)
        self.seconds += time.process_time() - start
        return out


def results(case, traj):
    if case == "R":
        tip = np.array([r["vertical"] for r in traj.records["tip"]])
        return f"tip min {tip.min():.12f} m, end {tip[-1]:.12f} m"
    p1 = np.array(traj.records["strain_P1"])
    i5 = int(np.argmin(abs(np.array(traj.times) - 5.0)))
    return f"P1 at 5 s {p1[i5]:.12e}, peak {p1.max():.12e}, end {p1[-1]:.12e}"


def _run(sc, borrowed_steps):
    """api.run(sc), with NewtonOptions.borrowed_rate_steps = ``borrowed_steps`` (None: the default)."""
    if borrowed_steps is None:
        return api.run(sc)
    options = nc.NewtonOptions  # api.run imports it when called
    nc.NewtonOptions = functools.partial(options, borrowed_rate_steps=borrowed_steps)
    try:
        return api.run(sc)
    finally:
        nc.NewtonOptions = options


def measure(case, variants, reps, overrides, borrowed=None):
    """{name: (us per step of each rep, Newton per step, results)} with the variants alternating;
    ``borrowed``: {name: NewtonOptions.borrowed_rate_steps} (default: the default)."""
    borrowed = borrowed or {}
    timed = TimedLoop()
    t_end = CASES[case][1]
    for name, loop in variants.items():  # compile or load each before timing
        timed.loop = loop
        _run(scenario(case, 0.002, overrides), borrowed.get(name))
    out = {name: [[], None, None] for name in variants}
    for _ in range(reps):
        for name, loop in variants.items():
            timed.loop, timed.seconds = loop, 0.0
            traj, failure = _run(scenario(case, t_end, overrides), borrowed.get(name))
            if failure is not None:
                raise failure
            out[name][0].append(timed.seconds / traj.steps * 1e6)
            out[name][1] = traj.newton_iterations / traj.steps
            out[name][2] = results(case, traj)
    return out


@njit
def _calls(n, which, model, pack, F, x, v, lam):
    """n calls of one function of the step's powers: 0 step_powers, 1 and 2 evaluate_chains to
    that order, 3 the FFR beams' dissipated power (the chains evaluated once before)."""
    s = 0.0
    if which == 3:
        evaluate_chains(model.context.chains, x, F, 1)
    for _ in range(n):
        if which == 0:
            p, q = step_powers(model, F, 0.1, x, v, lam)
            s += p + q
        elif which == 3:
            s += _dissipated_power(pack, model.context, v, x)
        else:
            evaluate_chains(model.context.chains, x, F, which)
    return s


def powers(case):
    system = api.build_system(scenario(case, 1.0, []))
    state = initial_state(system)
    model = system.model()
    x, v, lam, F = state.x, state.v + 0.1, state.lam, np.ascontiguousarray(state.chart)
    pack = next(part for part in model.parts if isinstance(part, FfrBeams))

    def best(f, n=100000):
        f(1)
        times = []
        for _ in range(5):
            start = time.process_time()
            f(n)
            times.append((time.process_time() - start) / n * 1e6)
        return min(times)

    us = [best(lambda n: _calls(n, which, model, pack, F, x, v, lam)) for which in range(4)]
    print(f"{case}: step_powers {us[0]:.3f} us; evaluate_chains order 1 {us[1]:.3f} us, order 2 {us[2]:.3f} us; "
          f"FFR dissipated power {us[3]:.3f} us "
          f"(load average {os.getloadavg()[0]:.1f})")


def rates(case, n_steps):
    log = []
    decide = nc.newton_decide

    def logged(size, previous, it, *rest):
        log[-1].append(size)
        return decide(size, previous, it, *rest)

    sc = scenario(case, 1.0, [])
    system = api.build_system(sc)
    state = initial_state(system)
    p = ga.AlphaParameters.from_spectral_radius(sc.analysis.spectral_radius)
    options = nc.NewtonOptions(tolerance=sc.analysis.tolerance, borrowed_rate_steps=0)
    kept = None
    nc.newton_decide = logged
    try:
        for _ in range(n_steps):
            log.append([])
            state, _, kept = ga.step(system, state, sc.analysis.dt, p, options, kept)
    finally:
        nc.newton_decide = decide
    twice = [(s[0], s[1] / s[0]) for s in log if len(s) >= 2 and s[0] > 0.0]
    theta = np.array([r for _, r in twice])
    first = np.array([d for d, _ in twice])
    tol = options.tolerance * max(system.length_scale, 1.0)
    accepted = sum(1 for k in range(1, len(log)) if len(log[k - 1]) >= 2 and log[k - 1][0] > 0.0
                   and log[k][0] * (t := log[k - 1][1] / log[k - 1][0]) / (1.0 - t) / nc.KAPPA <= tol)
    print(f"{case}, {n_steps} Python steps: {len(twice)} iterated twice or more; |dx1| median {np.median(first):.2e} "
          f"max {first.max():.2e} m; theta median {np.median(theta):.2e}, min {theta.min():.2e}, max {theta.max():.2e}; "
          f"tolerance {tol:.3e}; the first-iteration test with the step before's rate would accept "
          f"{accepted} of {len(log) - 1} steps")


def main(argv):
    mode, case = argv[0], argv[1]
    if mode == "powers":
        powers(case)
        return
    if mode == "rates":
        rates(case, int(argv[2]) if len(argv) > 2 else 2000)
        return
    reps = int(argv[2]) if len(argv) > 2 else 3
    if mode == "parts":
        copy = {"advance": compiled_alpha.advance}
        variants = {"as is": compiled_alpha.advance,
                    "uncached copy": uncached_twins(copy)["advance"],
                    "without the powers": uncached_twins(copy, {"step_powers": _no_powers})["advance"],
                    "without the powers, equations twice": uncached_twins(
                        copy, {"step_powers": _no_powers, "system_equations": _equations_twice})["advance"]}
        out = measure(case, variants, reps, [])
    elif mode == "first-iteration":
        ms = [int(m) for m in argv[3].split(",")] if len(argv) > 3 else [0, 1, 3, 8]
        variants = {f"M = {m}": compiled_alpha.advance for m in ms}
        out = measure(case, variants, reps, argv[4:], {f"M = {m}": m for m in ms})
    elif mode == "copies":
        src = _loop_source()
        copy = _compile_copy(src, "advance")
        with_argument = _compile_copy(src.replace("def advance(model,", "def advance_argument(unused, model,"),
                                      "advance_argument")
        variants = {"the loop as it is": compiled_alpha.advance, "a copy of its source": copy,
                    "the copy with an unused argument": lambda *args: with_argument(0, *args)}
        out = measure(case, variants, reps, [])
    else:
        raise SystemExit(__doc__)
    for name, (times, newton, result) in out.items():
        print(f"{case} {name:36s} {statistics.median(times):7.3f} us/step ({min(times):.3f}-{max(times):.3f}), "
              f"Newton/step {newton:.5f}, {result}")
    print(f"load average {os.getloadavg()[0]:.1f} {os.getloadavg()[1]:.1f} {os.getloadavg()[2]:.1f}")


if __name__ == "__main__":
    main(sys.argv[1:])
