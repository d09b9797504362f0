"""Two checkouts of hubbeam side by side: the compiled time loop's process time per step on exp1.

    python benchmarks/versions.py OLD_TREE NEW_TREE [MODELS] [REPS] [ROUNDS] [STEPS]

OLD_TREE and NEW_TREE are two checkouts (for example ``git worktree add ../old HEAD~1``), each
with its own numba cache (``__pycache__`` beside its sources: run each once first, or the
first round times compilation too). MODELS is a comma-separated list of :data:`MODELS` (default
``modal,modal_hinge``). In each of ROUNDS rounds (default 2), OLD then NEW runs in a process of
its own (its sources first on ``sys.path``), which times the compiled loop
(:class:`hubbeam.simulation.CompiledSteps`) REPS times (default 12) over STEPS steps (default
5000) for each model in turn and prints the fastest, first quartile and median process time per
step. On a machine shared with other jobs the runs of one process vary by up to 2x; compare
the fastest. Not a test: timings do not belong in tests.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

#: exp1 variants: overrides ("HINGE": case J's stiff flap hinge, benchmarks/engines.py)
MODELS = {
    "modal": ['beam.formulation="ffr"', "beam.modes=4"],
    "modal_hinge": ['beam.formulation="ffr"', "beam.modes=4", "HINGE"],
    "nodal": ['beam.formulation="ffr"'],
    "nodal_hinge": ['beam.formulation="ffr"', "HINGE"],
    "ancf": [],
    "ancf_hinge": ["HINGE"],
}


def time_models(labels: list[str], reps: int, steps: int) -> None:
    """In this process: REPS alternating timings of each model; prints one line per model."""
    import numpy as np
    from engines import HINGE

    from hubbeam import api
    from hubbeam.io.scenario import load_example
    from hubbeam.simulation import CompiledSteps, initial_state
    from hubbeam.solvers import generalized_alpha as ga
    from hubbeam.solvers import newton_control as nc

    built = {}
    for label in labels:
        system = api.build_system(load_example("exp1", [HINGE if o == "HINGE" else o for o in MODELS[label]]))
        built[label] = (system, initial_state(system))
    params = ga.AlphaParameters.from_spectral_radius(0.8)
    times: dict[str, list[float]] = {label: [] for label in labels}
    for _ in range(reps):
        for label in labels:
            system, state = built[label]
            loop = CompiledSteps(system, params, nc.NewtonOptions(), 1e-3, state)
            start = time.process_time()
            _, n, _, _, error, _ = loop.advance(state, steps, 0, 10, steps)
            if error is not None:
                raise error
            times[label].append((time.process_time() - start) / n * 1e6)
    for label in labels:
        t = np.array(times[label])
        print(f"  {label:12s} fastest {t.min():7.2f}  q25 {np.quantile(t, 0.25):7.2f}  "
              f"median {np.median(t):7.2f} us/step")


def main() -> None:
    if len(sys.argv) > 1 and sys.argv[1] == "--in-process":
        time_models(sys.argv[2].split(","), int(sys.argv[3]), int(sys.argv[4]))
        return
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    old, new = (os.path.abspath(t) for t in sys.argv[1:3])
    labels = sys.argv[3] if len(sys.argv) > 3 else "modal,modal_hinge"
    unknown = [label for label in labels.split(",") if label not in MODELS]
    if unknown:
        sys.exit(f"unknown models {unknown}: choose from {sorted(MODELS)}")
    reps, rounds, steps = (int(sys.argv[i]) if len(sys.argv) > i else d for i, d in ((4, 12), (5, 2), (6, 5000)))
    print(f"process time per step of the compiled loop on exp1, {reps} runs of {steps} steps per model and process; "
          f"load average {os.getloadavg()[0]:.1f}")
    for r in range(rounds):
        for tree in (old, new):
            print(f"round {r + 1}, {tree}:", flush=True)
            env = dict(os.environ, PYTHONPATH=os.pathsep.join([os.path.join(tree, "src"),
                                                              os.path.join(tree, "benchmarks")]))
            subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), "versions.py"),
                            "--in-process", labels, str(reps), str(steps)], env=env, cwd=tree, check=True)


if __name__ == "__main__":
    main()
