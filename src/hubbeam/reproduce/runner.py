"""Run the cases of a plan, in parallel processes; every result is an xarray Dataset."""

from __future__ import annotations

import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

from hubbeam.reproduce.plan import Case


@dataclass
class Outcome:
    """A run's dataset (None if it failed before its first output), the failure message if
    any (the dataset then holds the results up to it) and its wall time (s)."""

    case: Case
    dataset: object
    failure: str | None
    wall_time_s: float


def run_case(case: Case) -> Outcome:
    """Simulate one case (in a worker process)."""
    from hubbeam import api
    from hubbeam.io.results import to_dataset
    from hubbeam.io.scenario import load_example

    start = time.perf_counter()
    scenario = load_example(case.example, case.overrides())
    traj, error = api.run(scenario)
    failure = None if error is None else str(error)
    ds = to_dataset(traj, scenario) if traj is not None and traj.times else None
    return Outcome(case, ds, failure, time.perf_counter() - start)


def run_cases(cases: list[Case], jobs: int = 1, progress=None) -> dict[str, Outcome]:
    """All cases, ``jobs`` at a time; ``progress(done, total, outcome)`` after each."""
    results: dict[str, Outcome] = {}
    if jobs <= 1:
        for k, case in enumerate(cases, 1):
            results[case.key] = outcome = run_case(case)
            if progress:
                progress(k, len(cases), outcome)
        return results
    from hubbeam import interrupt

    pool = ProcessPoolExecutor(max_workers=jobs, initializer=_worker_start)
    try:
        with interrupt.children_spared():  # the workers start here (see _worker_start)
            futures = [pool.submit(run_case, case) for case in cases]
        for k, fut in enumerate(as_completed(futures), 1):
            outcome = fut.result()
            results[outcome.case.key] = outcome
            if progress:
                progress(k, len(cases), outcome)
    except BaseException:  # interrupted (or a worker died): stop the workers now, not after their runs
        _stop(pool)
        raise
    pool.shutdown()
    return results


def _worker_start() -> None:
    """Workers leave SIGINT to the parent (a Ctrl-C reaches the whole process group), which
    stops them; no traceback from each of them. A forked worker inherits the parent's
    handlers (hubbeam.interrupt's turn SIGTERM into an exception a worker would catch and
    go on): SIGTERM and SIGHUP get their default action back, so that terminate() stops it."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for name in ("SIGTERM", "SIGHUP"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), signal.SIG_DFL)


def _stop(pool: ProcessPoolExecutor) -> None:
    processes = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for p in processes:
        p.terminate()
    for p in processes:
        p.join(timeout=2)
        if p.is_alive():
            p.kill()
            p.join(timeout=2)
