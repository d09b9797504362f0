"""Speed benchmark: hubbeam against Exudyn on the same model (issue 6), run side by side.

    python benchmarks/run.py [--reps 3] [--t-end 10] [--scaling] [--quick]

Each run is a fresh process (benchmarks/engines.py), engines alternate within every
repetition, and the table shows medians: the integration alone (as each engine reports
it) and the whole process (start-up, model set-up and compilation with a warm numba
cache included), the ratios hubbeam / peer, and the tip deflection of both so that the
comparison is at equal accuracy. Needs `pip install exudyn` (the `.[peer]` extra).

Case A: the reference plate clamped, gravity along its weak axis, released from
straight, 8 elements, dt = 1 ms, generalized-alpha rho_inf = 0.8, no damping.
Peers: Exudyn's ObjectANCFCable (3D ANCF, no torsion). Not yet here: Exudyn's
ObjectBeamGeometricallyExact (3D set-up by hand) and case B (Kane's spin-up).
Case C (--scaling): case A with 4..64 elements, hubbeam's cost per step.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def one_run(engine: str, elements: int, t_end: float, dt: float) -> dict:
    start = time.perf_counter()
    out = subprocess.run([sys.executable, os.path.join(HERE, "engines.py"), engine, str(elements), str(t_end), str(dt)],
                         capture_output=True, text=True, check=True)
    result = json.loads(out.stdout.strip().splitlines()[-1])
    result["process_s"] = time.perf_counter() - start
    return result


def median(runs, key):
    return statistics.median(r[key] for r in runs)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--reps", type=int, default=3)
    p.add_argument("--t-end", type=float, default=10.0)
    p.add_argument("--dt", type=float, default=1e-3)
    p.add_argument("--scaling", action="store_true", help="also case C: 4..64 elements (hubbeam)")
    p.add_argument("--quick", action="store_true", help="1 s simulated, one repetition")
    a = p.parse_args()
    if a.quick:
        a.reps, a.t_end = 1, 1.0
    engines = ["hubbeam", "exudyn-cable"]
    one_run("hubbeam", 8, 2 * a.dt, a.dt)  # warm the numba cache
    runs = {e: [] for e in engines}
    for _ in range(a.reps):
        for e in engines:
            runs[e].append(one_run(e, 8, a.t_end, a.dt))
    print(f"Case A: reference plate, 8 elements, {a.t_end:g} s at dt = {a.dt:g} s, {os.cpu_count()} cores, "
          f"median of {a.reps}")
    print(f"{'engine':14s} {'integration s':>14s} {'process s':>10s} {'Newton/step':>12s} {'tip min (m)':>12s} "
          f"{'tip end (m)':>12s}")
    for e in engines:
        nps = runs[e][0]["newton_per_step"]
        print(f"{e:14s} {median(runs[e], 'integration_s'):14.3f} {median(runs[e], 'process_s'):10.3f} "
              f"{'—' if nps is None else f'{nps:.2f}':>12s} {runs[e][0]['tip_vertical_min']:12.5f} "
              f"{runs[e][0]['tip_vertical_end']:12.5f}")
    h = runs["hubbeam"]
    for e in engines[1:]:
        print(f"hubbeam / {e}: integration {median(h, 'integration_s') / median(runs[e], 'integration_s'):.2f}, "
              f"process {median(h, 'process_s') / median(runs[e], 'process_s'):.2f}, tip min differs by "
              f"{100 * abs(h[0]['tip_vertical_min'] / runs[e][0]['tip_vertical_min'] - 1):.3f} %")
    if a.scaling:
        print("Case C: hubbeam cost per step against elements (1 s simulated)")
        base = None
        for n in (4, 8, 16, 32, 64):
            r = one_run("hubbeam", n, 1.0, a.dt)
            per = r["integration_s"] / r["steps"]
            base = base or (per if n == 8 else None)
            print(f"  {n:3d} elements: {1e3 * per:.3f} ms per step" + (f" ({per / base:.1f}x the 8-element cost)" if base else ""))


if __name__ == "__main__":
    main()
