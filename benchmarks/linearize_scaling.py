"""How ``hubbeam linearize`` scales with the number of beams (issue 29, class 7).

    OPENBLAS_NUM_THREADS=1 python benchmarks/linearize_scaling.py   # 1, 10, 20, 40 one-element beams; 1 beam of 40 elements
    python benchmarks/linearize_scaling.py --command modes   # the same models through hubbeam modes
    python benchmarks/linearize_scaling.py --beams 40 --reps 1

Each case is one fresh ``hubbeam linearize FILE --json`` process (a warm numba cache: one
untimed run first), timed by its wall clock and by its CPU time (user + system, which the
other load of a shared machine disturbs less); ``--command modes`` times ``hubbeam modes``
on the same files instead, the analysis linearize should scale like. One BLAS thread
(OPENBLAS_NUM_THREADS=1) keeps the CPU time honest on a shared machine: waiting BLAS threads
spin and count as CPU time.

The models: N one-element ANCF beams on a free hub (spread
evenly in azimuth, each with a tip-deflection and a root-strain sensor, plus the hub angle,
speed, energy and angular momentum), against one beam of 40 elements (646 states, against
802: about as many). Printed per case: wall and CPU time (medians of ``--reps``).
"""

from __future__ import annotations

import argparse
import json
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

BEAM = """
[[beams]]
name = "b{k}"
azimuth = {azimuth}
elements = {elements}
length = 1.0
width = 0.05
thickness = 0.003
density = 2700.0
youngs_modulus = 70.0e9
poisson_ratio = 0.33
"""
SENSORS = """
[[sensors]]
name = "tip_{name}"
kind = "tip_deflection"
beam = "{name}"

[[sensors]]
name = "strain_{name}"
kind = "surface_strain"
beam = "{name}"
x = 0.02
surface = "upper"
"""
HEAD = """name = "scaling"
[hub]
motion = "free"
radius = 0.3
inertia = 5.0
[environment]
gravity = [0.0, 0.0, 0.0]
[analysis]
kind = "dynamic"
t_end = 1.0
dt = 1.0e-3
[[sensors]]
name = "theta"
kind = "hub_angle"
[[sensors]]
name = "omega"
kind = "hub_angular_velocity"
[[sensors]]
name = "energy"
kind = "energy"
[[sensors]]
name = "momentum"
kind = "angular_momentum"
"""


def scenario(beams: int, elements: int) -> str:
    text = HEAD
    for k in range(beams):
        text += BEAM.format(k=k, azimuth=360.0 * k / beams, elements=elements)
    for k in range(beams):
        text += SENSORS.format(name=f"b{k}")
    return text


def timed(path: Path, command: str = "linearize") -> tuple[float, float, dict]:
    """(wall s, CPU s, the JSON) of one fresh process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "hubbeam.cli", command, str(path), "--json"], capture_output=True,
                         text=True, check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, json.loads(out.stdout)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--beams", type=int, nargs="+", default=[1, 10, 20, 40])
    p.add_argument("--reps", type=int, default=1)
    p.add_argument("--command", choices=("linearize", "modes"), default="linearize")
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        cases = [(f"{n} beams x 1 element", n, 1) for n in args.beams]
        cases.append((f"1 beam x {max(args.beams)} elements", 1, max(args.beams)))
        warm = Path(tmp) / "warm.toml"
        warm.write_text(scenario(2, 1))
        timed(warm, args.command)  # numba's cache loaded once before timing
        print(f"{args.command}: {'case':28s} {'wall (s)':>9s} {'CPU (s)':>8s}")
        for label, beams, elements in cases:
            path = Path(tmp) / f"case_{beams}_{elements}.toml"
            path.write_text(scenario(beams, elements))
            walls, cpus = [], []
            for _ in range(args.reps):
                wall, cpu, _ = timed(path, args.command)
                walls.append(wall)
                cpus.append(cpu)
            print(f"{args.command}: {label:28s} {statistics.median(walls):9.2f} {statistics.median(cpus):8.2f}",
                  flush=True)


if __name__ == "__main__":
    main()
