"""CPU and wall time of a bundled example's first run, numba's cache empty, then warm.

    python benchmarks/first_compile.py [EXAMPLE] [KEY=VALUE ...]   # default: exp1

Runs the example (default ``exp1``; by default for one output step, or as long as an
``analysis.t_end=...`` given) through ``api.run`` with numba's on-disk cache pointed at a new
empty directory, so that everything it needs compiles, and prints the process's CPU and wall
time from before hubbeam's import; then runs it again in a new process on that cache (the
warm run: loading the compiled functions). CPU time is the number to compare on a machine
shared with other jobs. Not a test: timings do not belong in tests.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time


def run(example: str, overrides: list[str]) -> None:
    start_cpu, start_wall = time.process_time(), time.perf_counter()
    from hubbeam import api
    from hubbeam.io.scenario import load_example

    if not any(o.split("=", 1)[0].strip() == "analysis.t_end" for o in overrides):  # one output step
        overrides = overrides + [f"analysis.t_end={load_example(example, overrides).output_dt}"]
    _, failure = api.run(load_example(example, overrides))
    print(f"{example} {' '.join(overrides)}: {time.process_time() - start_cpu:.1f} s CPU, "
          f"{time.perf_counter() - start_wall:.1f} s wall" + (f" ({failure})" if failure else ""))


def main(argv: list[str]) -> None:
    if argv and argv[0] == "--one":  # a single run in this process, on the cache the caller set
        run(argv[1], argv[2:])
        return
    example = argv[0] if argv and "=" not in argv[0] else "exp1"
    overrides = [a for a in argv if "=" in a]
    env = dict(os.environ, NUMBA_CACHE_DIR=tempfile.mkdtemp(prefix="hubbeam-first-"))
    for label in ("empty cache", "warm cache"):
        print(label, end=": ", flush=True)
        subprocess.run([sys.executable, os.path.abspath(__file__), "--one", example, *overrides], env=env, check=True)


if __name__ == "__main__":
    main(sys.argv[1:])
