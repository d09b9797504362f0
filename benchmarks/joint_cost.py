"""Where a joint's cost goes (case J): the compiled time loop alone and its parts, per step.

    python benchmarks/joint_cost.py hinge [REPS]   # exp1 (6 elements, 10 s at 1 ms) clamped / on the stiff flap hinge
    python benchmarks/joint_cost.py chain [REPS]   # case J's chain of 1, 2, 4, 8 links (1 s at 1 ms), both starts
    python benchmarks/joint_cost.py newton [REPS]  # why the FFR beam on the hinge refactorises (about 2 minutes)
    python benchmarks/joint_cost.py columns [REPS] # exp1 clamped / on the hinge, joint columns updated or not
    python benchmarks/joint_cost.py stale          # where the FFR hinge's third Newton iterations come from
    python benchmarks/joint_cost.py loop [REPS] [ancf]  # as hinge on the FFR (or ANCF) plates, the loop alone
    python benchmarks/joint_cost.py pieces         # the joint's share of one residual and one call of the powers
    python benchmarks/joint_cost.py ages [MODES] [STEPS]  # third iterations by the age of a drifted patch
    python benchmarks/joint_cost.py powers [REPS]  # case R's plate on a spring hinge: the step's powers skipped or not

For each model: the time loop alone (:class:`hubbeam.simulation.CompiledSteps`, process time per
step, median and range of REPS runs that alternate with the other models in this one process: on a
loaded machine process time varies less than wall time), Newton iterations and LU factorisations
per step, column updates of the kept matrix per step ("patches",
:mod:`hubbeam.solvers.column_update`), and the cost of one call of each part of a step (process
time, best of 3): the residual, the residual with the Newton matrix, the band LU, a band solve
and the step's powers; "parts" adds them as a step spends them: (1 + N) residuals, LU x (matrix -
residual + factor), N solves, the powers, and patches x joint angles x (residual + solve). numba's cache must be warm (run case J once first).

``columns``: as ``hinge``, the hinged models run twice, alternating: with the column update of a
stale kept matrix (:mod:`hubbeam.solvers.column_update`, the default) and without
(``NewtonOptions(update_columns=False)``: refactorise it), and the tip deflection and root
strain of the two runs compared (10 s, every 10th step).

``loop``: as ``hinge`` on the FFR plates (with ``ancf``: the ANCF plate), without the parts' one-call costs (whose functions
compile in this process: minutes on a loaded machine), so that runs of two versions of the code
can alternate quickly.

``stale``: where the FFR plate's third Newton iterations on the hinge come from (:func:`stale`).

``pieces``: exp1 on 4 modes, clamped and on the hinge, each at its state after 2345 compiled
steps: one call (process time, best of 5) of the residual, the step's powers, the chains'
kinematics to order 2 and 1, and each part's equations and powers alone (:func:`pieces`).

``ages``: exp1 on the hinge (default 4 modes, 3000 steps) in Python steps: the steps that carry
a drifted patch, by its age, and how many of them took a third Newton iteration (:func:`ages`).

``powers``: case R's plate (4 modes, fixed hub, no drag) on case J's spring flap hinge, 10 s: the
compiled loop with the joint laws' declaration that a spring alone has no power (the time loop
then skips the step's powers) and with the declaration ignored (the kind's ``powers_possible``
unset: powers evaluated every step, as before it), alternating; the final states compared.

``newton``: exp1 with the nodal FFR beam, clamped and on the hinge. (1) The spectral radius of
I - A^-1 D at step 300 (t = 0.3 s), A the code's Newton matrix at step 300 - lag, D central
differences of the residual along the generalized-alpha correction at step 300: it bounds the
contraction of Newton iterations on a matrix kept from lag steps before (lag 0: the tangent's
own inexactness). (2) The first 1.5 s in Python steps with the code's matrix and with the
residual's differences as the iteration matrix (an exact tangent, rates' derivatives included):
Newton iterations and factorisations per step. (3) The compiled loop with the controller's
``refresh_iterations`` at 2 (the default) and 3, alternating.
"""

from __future__ import annotations

import os
import statistics
import sys
import time

import numpy as np
from numba import njit

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from engines import HINGE, chain_scenario

from hubbeam import api
from hubbeam.io.scenario import load_example
from hubbeam.simulation import CompiledSteps, initial_state
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers import newton_control as nc
from hubbeam.solvers.column_update import joint_columns
from hubbeam.system.assembly import BorderedBandMatrix, bordered_factor, bordered_solve
from hubbeam.system.equations import step_powers, system_equations
from hubbeam.system.frames import evaluate_chains
from hubbeam.system.terms import part_drive_power, part_equations, part_power


@njit
def _equations(n, want, model, F, x, v, a, lam, res, ab, brow, bcol, bb):
    s = 0.0
    for _ in range(n):
        s += system_equations(model, F, x, v, a, lam, 0.1, 1.0, 0.5, 0.3e-6, 1.0, 1.0, False, want, res, ab, brow,
                              bcol, bb)[1]
    return s


@njit
def _factor(n, ab0, ab, bw, ipiv, brow, bcol, bb, Y, schur, copy_only):
    s = 0
    for _ in range(n):
        ab[:] = ab0
        if not copy_only:
            s += bordered_factor(ab, bw, ipiv, brow, bcol, bb, Y, schur)
    return s


@njit
def _solve(n, ab, bw, ipiv, brow, Y, schur, rhs0, rhs, scratch):
    for _ in range(n):
        rhs[:] = rhs0
        bordered_solve(ab, bw, ipiv, brow, Y, schur, rhs, scratch)


@njit
def _powers(n, model, F, x, v, lam):
    s = 0.0
    for _ in range(n):
        s += step_powers(model, F, 0.1, x, v, lam)[0]
    return s


@njit
def _chains(n, model, F, x, order):
    for _ in range(n):
        evaluate_chains(model.context.chains, x, F, order)


@njit(_nrt=False)
def _part(n, pack, model, F, x, v, a, lam, res, ab, brow, bcol, bb):
    evaluate_chains(model.context.chains, x, F, 2)
    s = 0.0
    for _ in range(n):
        s += part_equations(pack, model.context, F, x, v, a, lam, 0.1, 1.0, 0.5, 0.3e-6, 1.0, 1.0, False, False, res, ab,
                            brow, bcol, bb)[1]
    return s


@njit(_nrt=False)
def _part_powers(n, pack, model, F, x, v, lam):
    evaluate_chains(model.context.chains, x, F, 1)
    s = 0.0
    for _ in range(n):
        s += part_power(pack, model.context, F, x, v) + part_drive_power(pack, model.context, F, 0.1, x, v, lam)
    return s


def _best(f, n):
    f(1)
    out = np.inf
    for _ in range(3):
        t = time.process_time()
        f(n)
        out = min(out, (time.process_time() - t) / n * 1e6)
    return out


def call_costs(system, state) -> dict:
    """One call of each part of a step (us): residual, matrix (residual with the Newton matrix),
    factor (the bordered band LU), solve, powers."""
    model, layout = system.model(), system.layout
    res = np.empty(layout.nz)
    m = BorderedBandMatrix.empty(layout.nz, layout.border, model.bandwidth)
    x, v, a, lam = state.x, state.v, state.xdd, state.lam
    F = np.ascontiguousarray(state.chart)
    args = (model, F, x, v, a, lam, res, m.ab, m.brow, m.bcol, m.bb)
    out = {"residual": _best(lambda n: _equations(n, False, *args), 5000),
           "matrix": _best(lambda n: _equations(n, True, *args), 2000),
           "powers": _best(lambda n: _powers(n, model, F, x, v, lam), 5000)}
    _equations(1, True, *args)
    ab0, ab = m.ab.copy(order="F"), m.ab.copy(order="F")  # LAPACK's column-major storage
    ipiv = np.zeros(ab.shape[1], dtype=np.int32)
    Y, schur = np.zeros((layout.border, ab.shape[1])), np.zeros((layout.border, layout.border))
    fargs = (ab0, ab, model.bandwidth, ipiv, m.brow, m.bcol, m.bb, Y, schur)
    out["factor"] = _best(lambda n: _factor(n, *fargs, False), 2000) - _best(lambda n: _factor(n, *fargs, True), 2000)
    _factor(1, *fargs, False)  # the factors for the solves
    rhs0 = np.ones(layout.nz)
    rhs = rhs0.copy()
    scratch = np.zeros(layout.border)
    out["solve"] = _best(lambda n: _solve(n, ab, model.bandwidth, ipiv, m.brow, Y, schur, rhs0, rhs, scratch), 5000)
    return out


def compare(models: dict, steps: int, reps: int, dt: float = 1e-3, options: dict | None = None) -> dict:
    """{label: (us per step of each rep, Newton per step, LU per step, steps)} of the compiled loop
    alone, the models alternating within each repetition; ``options``: {label: NewtonOptions}
    where not the default."""
    p = ga.AlphaParameters.from_spectral_radius(0.8)
    built = {label: (s, initial_state(s)) for label, s in ((k, api.build_system(sc)) for k, sc in models.items())}
    out = {label: [] for label in models}
    options = options or {}
    for _ in range(reps):
        for label, (system, state) in built.items():
            loop = CompiledSteps(system, p, options.get(label, nc.NewtonOptions()), dt, state)
            t = time.process_time()
            _, n, its, _, err, _ = loop.advance(state, steps, 0, 10, steps)
            if err is not None:
                raise err
            out[label].append((1e6 * (time.process_time() - t) / n, its / n, loop.factorisations / n, n,
                               loop.patches / n))
    return {label: ([r[0] for r in rows], rows[0][1], rows[0][2], rows[0][3], built[label], rows[0][4])
            for label, rows in out.items()}


def report(results: dict) -> dict:
    per = {}
    for label, (times, newton, lu, steps, (system, state), patches) in results.items():
        c = call_costs(system, state)
        parts = (1 + newton) * c["residual"] + lu * (c["matrix"] - c["residual"] + c["factor"]) + newton * c["solve"] \
            + c["powers"] + patches * sum(system.layout.joint_dofs) * (c["residual"] + c["solve"])
        per[label] = statistics.median(times)
        print(f"{label:22s} {per[label]:7.1f} us/step ({min(times):.1f}-{max(times):.1f}; {steps} steps)  "
              f"Newton {newton:.3f}  LU {lu:.4f}  patches {patches:.4f}  | nz {system.layout.nz}, half-bandwidth {system.bandwidth}: "
              f"residual {c['residual']:.1f}, matrix {c['matrix']:.1f}, factor {c['factor']:.1f}, solve "
              f"{c['solve']:.2f}, powers {c['powers']:.2f} us; parts {parts:.1f} us/step", flush=True)
    return per


def _differences_matrix(system, state, h, p, equations=None):
    """(the code's Newton matrix (``equations``: default the system's dynamic_equations), central
    differences of the residual along the correction), dense."""
    am, af, beta, gamma = p.alpha_m, p.alpha_f, p.beta, p.gamma
    ck = beta * h * h
    bp, gp = (1 - am) / (ck * (1 - af)), gamma / (beta * h)
    s, layout = system.mass_scale, system.layout
    x, v, a, lam, F, t = state.x, state.v, state.xdd, state.lam, state.chart, state.t

    def residual(z):
        dx, dmu = layout.split_z(z)
        return system.dynamic_residual(x + dx, v + gp * dx, a + bp * dx, lam + s / ck * dmu, F, t, ck, s)

    A = (equations or system.dynamic_equations)(x, v, a, lam, F, t, ck * bp, ck * gp, ck, s)[1].to_dense()
    D = np.empty_like(A)
    for j in range(A.shape[0]):
        e = np.zeros(A.shape[0])
        e[j] = 1e-7
        D[:, j] = (residual(e) - residual(-e)) / 2e-7
    return A, D


class _Dense:
    """A dense iteration matrix with the factorise() of a BorderedBandMatrix."""

    def __init__(self, D):
        self.D = D

    def factorise(self):
        import scipy.linalg

        from hubbeam.system.assembly import Factorisation

        lu = scipy.linalg.lu_factor(self.D)
        return Factorisation(lambda rhs: scipy.linalg.lu_solve(lu, rhs))


def newton(reps: int) -> None:
    h, p = 1e-3, ga.AlphaParameters.from_spectral_radius(0.8)
    ffr = ['beam.formulation="ffr"']
    for kind, extra in (("clamped", []), ("hinge", [HINGE])):
        system = api.build_system(load_example("exp1", ffr + extra))
        states, kept = [initial_state(system)], None
        for _ in range(300):
            state, _, kept = ga.step(system, states[-1], h, p, nc.NewtonOptions(), kept)
            states.append(state)
        _, D = _differences_matrix(system, states[300], h, p)
        radii = []
        for lag in (0, 1, 3, 10, 30):
            A, _ = _differences_matrix(system, states[300 - lag], h, p)
            radii.append(np.max(np.abs(np.linalg.eigvals(np.eye(len(A)) - np.linalg.solve(A, D)))))
        print(f"FFR nodal, {kind}: spectral radius of I - A^-1 D at step 300, A from lag 0 / 1 / 3 / 10 / 30 steps "
              "before: " + " / ".join(f"{r:.1e}" for r in radii), flush=True)
    system = api.build_system(load_example("exp1", ffr + [HINGE]))
    code, start = system.dynamic_equations, initial_state(system)
    for label in ("the code's matrix", "the residual's differences"):
        calls = [0]

        def matrix(x, v, a, lam, F, t, coef_m, coef_c, coef_k, s, exact=label != "the code's matrix", calls=calls):
            calls[0] += 1
            res, m = code(x, v, a, lam, F, t, coef_m, coef_c, coef_k, s)
            if not exact:
                return res, m
            state = ga.AlphaState(t, x, v, a, a, lam, F)
            return res, _Dense(_differences_matrix(system, state, h, p, code)[1])

        system.dynamic_equations = matrix
        state, kept, its = start, None, 0
        for _ in range(1500):
            state, n, kept = ga.step(system, state, h, p, nc.NewtonOptions(), kept)
            its += n
        print(f"FFR nodal, hinge, first 1.5 s with {label}: Newton {its / 1500:.3f}, LU {calls[0] / 1500:.4f} per step",
              flush=True)
    system.dynamic_equations = code
    runs = {}
    for _ in range(reps):
        for form, extra in (("FFR nodal", ffr), ("FFR 4 modes", ffr + ["beam.modes=4"])):
            system = api.build_system(load_example("exp1", extra + [HINGE]))
            state = initial_state(system)
            for ri in (2, 3):
                loop = CompiledSteps(system, p, nc.NewtonOptions(refresh_iterations=ri), h, state)
                t = time.process_time()
                _, n, its, _, _, _ = loop.advance(state, 10000, 0, 10, 10000)
                runs.setdefault((form, ri), []).append((1e6 * (time.process_time() - t) / n, its / n,
                                                        loop.factorisations / n))
    for (form, ri), rows in runs.items():
        times = [r[0] for r in rows]
        print(f"{form}, hinge, refresh_iterations {ri}: {statistics.median(times):.1f} us/step "
              f"({min(times):.1f}-{max(times):.1f}), Newton {rows[0][1]:.3f}, LU {rows[0][2]:.4f}")


def columns(reps: int) -> None:
    """The ``columns`` comparison (module docstring)."""
    forms = {"ANCF": [], "FFR nodal": ['beam.formulation="ffr"'],
             "FFR 4 modes": ['beam.formulation="ffr"', "beam.modes=4"]}
    models, options = {}, {}
    for name, extra in forms.items():
        models[f"{name}, clamped"] = load_example("exp1", extra)
        for update in (True, False):
            label = f"{name}, hinge, {'update' if update else 'refactorise'}"
            models[label] = load_example("exp1", extra + [HINGE])
            options[label] = nc.NewtonOptions(update_columns=update)
    per = report(compare(models, 10000, reps, options=options))
    for name, extra in forms.items():
        clamped = per[f"{name}, clamped"]
        print(f"{name}: hinge / clamped {per[f'{name}, hinge, update'] / clamped:.3f} with the column update, "
              f"{per[f'{name}, hinge, refactorise'] / clamped:.3f} refactorising")
        system = api.build_system(load_example("exp1", extra + [HINGE]))
        state, p = initial_state(system), ga.AlphaParameters.from_spectral_radius(0.8)
        x = []
        for update in (True, False):
            loop = CompiledSteps(system, p, nc.NewtonOptions(update_columns=update), 1e-3, state)
            *_, err, chunk = loop.advance(state, 10000, 0, 10, 10000)
            if err is not None:
                raise err
            x.append(chunk.states.x)
        print(f"  states every 10 ms over 10 s: largest |x_update - x_refactorise| {np.max(np.abs(x[0] - x[1])):.1e} "
              f"(largest |x| {np.max(np.abs(x[1])):.2f}; Newton tolerance 1e-9 x length)")


def stale() -> None:
    """The ``stale`` diagnosis: (1) exp1's FFR plate on the hinge, 10 s compiled, with update
    "adaptive" (the default: kept and patched matrices) and "step" (a new matrix at every
    step's predictor): Newton iterations, factorisations and patches per step, and per second
    of the adaptive run. (2) Its first 0.3 s on 4 modes in Python steps: the median first
    increment and the median contraction rate of the second iteration (|dx2| / |dx1|) on steps
    that make a patch, that carry one (drifted, :mod:`hubbeam.solvers.column_update`) and, with
    update "step", on new matrices. A step converges in two iterations when |dx1| rate^2 /
    (1 - rate) / kappa <= 1e-9 x 1.45 m (kappa = 0.01)."""
    p = ga.AlphaParameters.from_spectral_radius(0.8)
    for form, extra in (("FFR nodal", []), ("FFR 4 modes", ["beam.modes=4"])):
        system = api.build_system(load_example("exp1", ['beam.formulation="ffr"', HINGE] + extra))
        state = initial_state(system)
        for update in ("adaptive", "step"):
            loop = CompiledSteps(system, p, nc.NewtonOptions(update=update), 1e-3, state)
            start, seconds = state, []
            for k in range(10):
                lu0, patches0 = loop.factorisations, loop.patches
                start, n, its, _, err, _ = loop.advance(start, 1000, 1000 * k, 1000, 10000)
                if err is not None:
                    raise err
                seconds.append((n, its / n, (loop.factorisations - lu0) / n, (loop.patches - patches0) / n))
            newton = sum(s[1] for s in seconds) / 10
            print(f"{form}, hinge, update {update}: Newton {newton:.4f}, LU {loop.factorisations / 1e4:.4f}, "
                  f"patches {loop.patches / 1e4:.4f} per step", flush=True)
            if update == "adaptive":
                print("  per second: Newton " + " ".join(f"{s[1]:.3f}" for s in seconds)
                      + "; patches " + " ".join(f"{s[3]:.3f}" for s in seconds))
    system = api.build_system(load_example("exp1", ['beam.formulation="ffr"', "beam.modes=4", HINGE]))
    decide = nc.newton_decide
    for update in ("adaptive", "step"):
        log, rates = [], {}
        nc.newton_decide = lambda size, previous, it, st, *a, log=log: log.append((size, previous, it, st, a[-1])) \
            or decide(size, previous, it, st, *a)
        state, kept = initial_state(system), None
        try:
            for _ in range(300):
                log.clear()
                reuse = kept.reuse.copy() if kept is not None else nc.reuse_state()
                state, _, kept = ga.step(system, state, 1e-3, p, nc.NewtonOptions(update=update), kept)
                if len(log) < 2 or log[1][3] != log[0][3]:
                    continue
                kind = ("new matrix" if not log[0][3] else "patch made" if log[0][4]
                        else "patch carried" if reuse[nc.REUSE_PATCHED] else "kept matrix")
                rates.setdefault(kind, []).append((log[0][0], log[1][0] / log[0][0]))
        finally:
            nc.newton_decide = decide
        print(f"FFR 4 modes, hinge, first 0.3 s, update {update}: " + "; ".join(
            f"{kind} ({len(r)} steps): |dx1| {statistics.median(a for a, _ in r):.1e}, rate "
            f"{statistics.median(b for _, b in r):.1e}" for kind, r in rates.items()))
    # the hinge angle's acceleration at steps 200 to 300, and the exact tangent's change per step
    psi = int(joint_columns(system.layout)[0])
    states, kept = [initial_state(system)], None
    for _ in range(300):
        state, _, kept = ga.step(system, states[-1], 1e-3, p, nc.NewtonOptions(update="step"), kept)
        states.append(state)
    acc = np.array([s.xdd[psi] for s in states[200:]])
    signs = int(np.sum(np.diff(np.sign(acc - acc.mean())) != 0))
    print(f"  the hinge angle's acceleration, steps 200 to 300: {signs} sign changes about its mean (a period of "
          f"{200 / signs:.1f} steps), range {acc.min():.1f} to {acc.max():.1f} rad/s^2")
    D = [_differences_matrix(system, states[k], 1e-3, p)[1] for k in (180, 181, 182)]
    print(f"  the exact tangent (the residual's differences) from step 180: largest change after 1 step "
          f"{np.max(np.abs(D[1] - D[0])):.1e}, after 2 steps {np.max(np.abs(D[2] - D[0])):.1e} (largest entry "
          f"{np.max(np.abs(D[0])):.1f})")


def pieces() -> None:
    """The ``pieces`` costs (module docstring)."""
    best = lambda f, n: min(_best(f, n) for _ in range(2))  # noqa: E731 (best of 2 x 3)
    p = ga.AlphaParameters.from_spectral_radius(0.8)
    for kind in ("clamped", "hinge"):
        system = api.build_system(load_example("exp1", ['beam.formulation="ffr"', "beam.modes=4"]
                                               + ([HINGE] if kind == "hinge" else [])))
        state = initial_state(system)
        state = CompiledSteps(system, p, nc.NewtonOptions(), 1e-3, state).advance(state, 2345, 0, 10000, 10000)[0]
        model, layout = system.model(), system.layout
        res = np.empty(layout.nz)
        m = BorderedBandMatrix.empty(layout.nz, layout.border, model.bandwidth)
        x, v, a, lam, F = state.x, state.v, state.xdd, state.lam, np.ascontiguousarray(state.chart)
        args = (model, F, x, v, a, lam, res, m.ab, m.brow, m.bcol, m.bb)
        line = [f"residual {best(lambda n: _equations(n, False, *args), 20000):.3f}",
                f"powers {best(lambda n: _powers(n, model, F, x, v, lam), 20000):.3f}",
                f"chains to order 2 {best(lambda n: _chains(n, model, F, x, 2), 50000):.3f}",
                f"order 1 {best(lambda n: _chains(n, model, F, x, 1), 50000):.3f}"]
        for pack in model.parts:
            line.append(f"{type(pack).__name__} {best(lambda n: _part(n, pack, *args), 20000):.3f} / "
                        f"{best(lambda n: _part_powers(n, pack, model, F, x, v, lam), 20000):.3f}")
        print(f"FFR 4 modes, {kind}, us per call: " + ", ".join(line) + " (each part: equations / powers)",
              flush=True)


def ages(modes: int, steps: int) -> None:
    """The ``ages`` counts (module docstring)."""
    from hubbeam.solvers.column_update import PatchedMatrix

    system = api.build_system(load_example("exp1", ['beam.formulation="ffr"', HINGE]
                                           + ([f"beam.modes={modes}"] if modes else [])))
    p, log, drift = ga.AlphaParameters.from_spectral_radius(0.8), [], PatchedMatrix.drift
    PatchedMatrix.drift = lambda self, age: log.append(age) or drift(self, age)
    bounds = (1, 2, 3, 4, 5, 10, 20, 50, 100, 1000, 10**9)
    counts = {b: [0, 0] for b in bounds}
    try:
        state, kept = initial_state(system), None
        for _ in range(steps):
            log.clear()
            state, n, kept = ga.step(system, state, 1e-3, p, nc.NewtonOptions(), kept)
            if log:
                row = counts[next(b for b in bounds if log[-1] <= b)]
                row[0] += 1
                row[1] += n > 2
    finally:
        PatchedMatrix.drift = drift
    print(f"FFR {modes or 'nodal'}{' modes' if modes else ''}, hinge, {steps} Python steps: steps on a drifted "
          "patch by its age (up to), those with a third iteration")
    for b, (count, third) in counts.items():
        if count:
            print(f"  age <= {b:4d}: {count:5d} steps, {third:4d} ({third / count:.3f})")


def powers(reps: int) -> None:
    """The ``powers`` comparison (module docstring)."""
    from hubbeam.io.scenario import load_scenario
    from hubbeam.system import joints, terms

    kind = next(k for k in terms.KINDS if k.pack is joints.JointLaws)
    declared = kind.powers_possible
    scenario = load_scenario(os.path.join(os.path.dirname(os.path.abspath(__file__)), "case_a.toml"),
                             ['beam.formulation="ffr"', "beam.modes=4", HINGE])
    p, built = ga.AlphaParameters.from_spectral_radius(0.8), {}
    try:
        for label, possible in (("declared", declared), ("ignored", None)):
            object.__setattr__(kind, "powers_possible", possible)  # a frozen dataclass: the benchmark's switch
            system = api.build_system(scenario)
            built[label] = (system, initial_state(system), system.model().powers)
    finally:
        object.__setattr__(kind, "powers_possible", declared)
    runs = {label: [] for label in built}
    for _ in range(reps):
        for label, (system, state, _) in built.items():
            loop = CompiledSteps(system, p, nc.NewtonOptions(), 1e-3, state)
            t = time.process_time()
            end, n, _, _, err, _ = loop.advance(state, 10000, 0, 10, 10000)
            if err is not None:
                raise err
            runs[label].append((1e6 * (time.process_time() - t) / n, end.x.copy(), loop.work_done.copy()))
    for label, rows in runs.items():
        times = [r[0] for r in rows]
        print(f"joint powers {label}: model.powers {built[label][2]}, {statistics.median(times):.2f} us/step "
              f"({min(times):.2f}-{max(times):.2f}), dissipated / drive work {rows[0][2][0]:.3g} / "
              f"{rows[0][2][1]:.3g} J")
    a, b = (rows[0][1] for rows in runs.values())
    print(f"final states identical: {bool(np.array_equal(a, b))}")


def main() -> None:
    what = sys.argv[1] if len(sys.argv) > 1 else "hinge"
    reps = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    print(f"{what}: " + ("" if what in ("stale", "pieces", "ages") else f"the compiled loop alone, process time, median (range) of "
                                                     f"{reps} alternating runs; ")
          + f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    if what == "newton":
        newton(reps)
    elif what == "stale":
        stale()
    elif what == "pieces":
        pieces()
    elif what == "powers":
        powers(reps)
    elif what == "ages":
        ages(int(sys.argv[2]) if len(sys.argv) > 2 else 4, int(sys.argv[3]) if len(sys.argv) > 3 else 3000)
    elif what == "loop":
        forms = {"FFR nodal": ['beam.formulation="ffr"'], "FFR 4 modes": ['beam.formulation="ffr"', "beam.modes=4"]}
        if sys.argv[3:] == ["ancf"]:
            forms = {"ANCF": []}
        models = {f"{name}, {kind}": load_example("exp1", extra + ([HINGE] if kind == "hinge" else []))
                  for name, extra in forms.items() for kind in ("clamped", "hinge")}
        per = {}
        for label, (times, iterations, lu, steps, _, patches) in compare(models, 10000, reps).items():
            per[label] = statistics.median(times)
            print(f"{label:22s} {per[label]:7.2f} us/step ({min(times):.2f}-{max(times):.2f}; {steps} steps)  "
                  f"Newton {iterations:.4f}  LU {lu:.4f}  patches {patches:.4f}")
        for name in forms:
            print(f"{name}: hinge / clamped {per[f'{name}, hinge'] / per[f'{name}, clamped']:.3f}")
        print(f"load average at the end {os.getloadavg()[0]:.1f}")
    elif what == "columns":
        columns(reps)
    elif what == "hinge":
        forms = {"ANCF": [], "FFR nodal": ['beam.formulation="ffr"'],
                 "FFR 4 modes": ['beam.formulation="ffr"', "beam.modes=4"]}
        models = {f"{name}, {kind}": load_example("exp1", extra + ([HINGE] if kind == "hinge" else []))
                  for name, extra in forms.items() for kind in ("clamped", "hinge")}
        per = report(compare(models, 10000, reps))
        for name in forms:
            print(f"{name}: hinge / clamped {per[f'{name}, hinge'] / per[f'{name}, clamped']:.3f}")
    else:
        for every in (True, False):
            start = "every hinge at 1 rad/s" if every else "only the first hinge started"
            print(start)
            models = {f"{n} link{'s' if n > 1 else ''}": chain_scenario(n, 1.0, 1e-3, every) for n in (1, 2, 4, 8)}
            per = report(compare(models, 1000, reps))
            one = per["1 link"]
            ratios = [per[label] / (n * one) for n, label in zip((1, 2, 4, 8), per)]
            print("  x n times one link: " + ", ".join(f"{n}: {r:.2f}" for n, r in zip((1, 2, 4, 8), ratios)))


if __name__ == "__main__":
    main()
