"""Speed benchmark: hubbeam against Exudyn on the same models (issue 6), run side by side.

    python benchmarks/run.py [--reps 3] [--t-end 10] [--cases A,B,C,P,F,R,S,M,J] [--quick]

Every run is a fresh process (benchmarks/engines.py; ``hubbeam run`` for case P), the
engines of a case alternate within each repetition, and the tables show medians: the
integration alone (as each engine reports it, after its compiled code is loaded) and the
whole process (interpreter start-up, imports, model set-up, loading compiled code from
the warm numba cache), the ratios hubbeam / peer, Newton iterations and LU
factorisations per step where the engine reports them, and the tip deflections of both
so that the comparison is at equal accuracy. Needs `pip install exudyn` (the `.[peer]`
extra). The machine's core count is printed with the tables.

Case A (benchmarks/case_a.toml): the reference plate clamped, gravity along its weak axis,
released from straight, 8 elements, dt = 1 ms, generalized-alpha rho_inf = 0.8, no
damping. Peers: Exudyn's ObjectBeamGeometricallyExact (3D, with torsion, shear
deformable) and ObjectANCFCable (3D ANCF, no torsion).
Case B (benchmarks/case_b.toml): Kane's spin-up, 20 elements. Peer: ObjectANCFCable on a
clamp whose slope is driven by coordinate constraints (Python user functions).
Case C: case A with 4 .. 64 elements, hubbeam's cost per step (it should grow linearly).
Case P: the whole ``hubbeam run benchmarks/case_a.toml -o OUT.nc`` (wall clock).
Case F: the three formulations on the same model, experiment 1 (6 elements, 20 s at 1 ms):
ANCF, the paper's nodal FFR and FFR reduced to 4 modes, with the P1 strain's peak and end
value for their accuracy (no peer needed).
Case R: case A with modal reduction to 4 clamped modes: hubbeam's FFR beam (8 elements)
against Exudyn's ObjectFFRFreducedOrder on a 32 x 1 x 2 Hex20 solid mesh of the plate
(benchmarks/solid_plate.py), with the mesh's mass and first two frequencies against
Euler-Bernoulli.
Case S (benchmarks/case_s.toml, issue 24): a spacecraft tumbling freely: a free 400 kg bus
with products of inertia and two 4 m x 1 m x 4 mm panels with 1 kg tip bodies, released
straight while turning at (0.1, 0.3, 0.2) rad/s, no gravity; 8 elements per panel, 10 s at
dt = 2 ms. Peer: Exudyn's ObjectBeamGeometricallyExact panels on an ObjectRigidBody bus. The
same time series side by side: the bus's angular velocity (bus axes) and panel a's tip
deflection, with their differences.
Case M (issue 24, issue 26): case S's panels on the free bus against the same panels on a free
1-DOF hub, ANCF and FFR on 4 modes, 60 s at 1 ms (what a moving base costs; the modal
spacecraft's time per step): both slewed alike by the same PD law about the hub axis (slew-*),
and case S's tumbling bus against a hub spun up by a constant torque (spacecraft-*).

Case J (joints): experiment 1 (free hub, 6 elements) clamped against the same plate on a revolute
(flap) joint with a stiff spring (its motion the clamped one's), ANCF and nodal FFR, alternating,
medians: what a joint adds to the integration time; and a chain of 1, 2, 4 and 8 equal links (4 ANCF elements each) on
lag hinges, its cost per step against n times one link's, with every hinge started at 1 rad/s (link k turns at
k rad/s) and with only the first (every link at 1 rad/s). No peer needed.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
RHO_LBH = 2700.0 * 1.45 * 0.05 * 0.0025  # the plate's mass (kg), for case R's mesh check


def one_run(engine: str, elements: int, t_end: float, dt: float) -> dict:
    start = time.perf_counter()
    out = subprocess.run([sys.executable, os.path.join(HERE, "engines.py"), engine, str(elements), str(t_end), str(dt)],
                         capture_output=True, text=True)
    if out.returncode != 0:
        last = (out.stderr.strip().splitlines() or ["no message"])[-1]
        sys.exit(f"benchmarks/run.py: {engine} with {elements} elements failed: {last}")
    result = json.loads(out.stdout.strip().splitlines()[-1])
    result["process_s"] = time.perf_counter() - start
    return result


def cli_run(t_end: float) -> float:
    """Wall time of `hubbeam run benchmarks/case_a.toml -o OUT.nc` in a fresh process (s)."""
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "hubbeam.cli", "run", os.path.join(HERE, "case_a.toml"), "-o",
                        os.path.join(tmp, "case_a.nc"), "--set", f"analysis.t_end={t_end}"],
                       capture_output=True, text=True, check=True)
        return time.perf_counter() - start


def alternate(engines: dict, reps: int, t_end: float, dt: float) -> dict:
    """{engine: [one_run's result per repetition]}: every engine (with its number of elements)
    run once per repetition, in turn, so that a machine's changing load falls on all alike."""
    runs = {e: [] for e in engines}
    for _ in range(reps):
        for e, elements in engines.items():
            runs[e].append(one_run(e, elements, t_end, dt))
    return runs


def median(runs, key):
    return statistics.median(r[key] for r in runs)


def compare(title: str, engines: list[str], elements: int, reps: int, t_end: float, dt: float, tip: str) -> None:
    runs = alternate({e: elements for e in engines}, reps, t_end, dt)
    print(f"\n{title}: {elements} elements, {t_end:g} s at dt = {dt:g} s; median of {reps}, {os.cpu_count()} cores")
    print(f"{'engine':18s} {'integration s':>13s} {'process s':>10s} {'steps':>6s} {'Newton/step':>11s} "
          f"{'LU/step':>8s} {'tip min (m)':>12s} {'tip end (m)':>12s}   ({tip})")
    for e in engines:
        first = runs[e][0]
        nps, fps = first.get("newton_per_step"), first.get("factorisations_per_step")
        print(f"{e:18s} {median(runs[e], 'integration_s'):13.3f} {median(runs[e], 'process_s'):10.3f} "
              f"{int(first['steps']):6d} {'-' if nps is None else f'{nps:.2f}':>11s} "
              f"{'-' if fps is None else f'{fps:.2f}':>8s} {first['tip_min']:12.5f} {first['tip_end']:12.5f}")
    ours = runs[engines[0]]
    for e in engines[1:]:
        peer = runs[e][0]
        print(f"{engines[0]} / {e}: integration {median(ours, 'integration_s') / median(runs[e], 'integration_s'):.2f}, "
              f"process {median(ours, 'process_s') / median(runs[e], 'process_s'):.2f}; tip min differs by "
              f"{100 * abs(ours[0]['tip_min'] / peer['tip_min'] - 1):.3f} %, tip end by "
              f"{100 * abs(ours[0]['tip_end'] / peer['tip_end'] - 1):.3f} %")


def exp1_runs(engines, reps: int, t_end: float, dt: float) -> dict:
    """{engine: its runs} of experiment 1 (6 elements), the engines alternating in each of ``reps`` rounds."""
    return alternate({e: 6 for e in engines}, reps, t_end, dt)


def print_exp1_runs(runs: dict, process: bool) -> None:
    """One row per engine of experiment 1's runs: median integration (and process) time, the first
    run's Newton iterations and factorisations per step and its P1 strain peak and end."""
    head = f" {'process s':>10s}" if process else ""
    print(f"{'engine':18s} {'integration s':>13s}{head} {'Newton/step':>11s} {'LU/step':>8s} {'P1 peak':>11s} "
          f"{'P1 end':>11s}")
    for e, done in runs.items():
        first = done[0]
        cell = f" {median(done, 'process_s'):10.3f}" if process else ""
        print(f"{e:18s} {median(done, 'integration_s'):13.3f}{cell} {first['newton_per_step']:11.2f} "
              f"{first['factorisations_per_step']:8.2f} {first['peak']:11.4e} {first['end']:11.4e}")


def formulations(reps: int, t_end: float, dt: float) -> None:
    """Case F: ANCF, nodal FFR and modal FFR on experiment 1, alternating, medians."""
    engines = ["exp1-ancf", "exp1-ffr", "exp1-ffr-modal4"]
    runs = exp1_runs(engines, reps, t_end, dt)
    print(f"\nCase F (exp1, three formulations): 6 elements, {t_end:g} s at dt = {dt:g} s; median of {reps}, "
          f"{os.cpu_count()} cores")
    print_exp1_runs(runs, process=True)

    base = median(runs["exp1-ancf"], "integration_s")
    for e in engines[1:]:
        print(f"{e} / exp1-ancf: integration {median(runs[e], 'integration_s') / base:.2f}")


def reduced_order(reps: int, t_end: float, dt: float) -> None:
    """Case R: case A with modal reduction, hubbeam's FFR beam (8 elements, 4 clamped modes)
    against Exudyn's ObjectFFRFreducedOrder (32 x 1 x 2 Hex20 solids, 4 clamped modes),
    alternating, medians; with the solid mesh's check (mass, first two frequencies)."""
    engines = {"hubbeam-ffr-modal": 8, "exudyn-ffrf": 32}
    one_run("hubbeam-ffr-modal", 8, 2 * dt, dt)  # warm the numba cache of the FFR code
    runs = alternate(engines, reps, t_end, dt)
    print(f"\nCase R (case A, modal reduction to 4 clamped modes): {t_end:g} s at dt = {dt:g} s; median of {reps}, "
          f"{os.cpu_count()} cores")
    print(f"{'engine':18s} {'mesh':>22s} {'integration s':>13s} {'process s':>10s} {'tip min (m)':>12s} "
          f"{'tip end (m)':>12s}   (vertical)")
    meshes = {"hubbeam-ffr-modal": "8 FFR beam elements", "exudyn-ffrf": "32 x 1 x 2 Hex20"}
    for e in engines:
        first = runs[e][0]
        print(f"{e:18s} {meshes[e]:>22s} {median(runs[e], 'integration_s'):13.3f} {median(runs[e], 'process_s'):10.3f} "
              f"{first['tip_min']:12.5f} {first['tip_end']:12.5f}")
    ours, peer = runs["hubbeam-ffr-modal"], runs["exudyn-ffrf"]
    print(f"hubbeam-ffr-modal / exudyn-ffrf: integration "
          f"{median(ours, 'integration_s') / median(peer, 'integration_s'):.2f}, process "
          f"{median(ours, 'process_s') / median(peer, 'process_s'):.2f}; tip min differs by "
          f"{100 * abs(ours[0]['tip_min'] / peer[0]['tip_min'] - 1):.3f} %, tip end by "
          f"{100 * abs(ours[0]['tip_end'] / peer[0]['tip_end'] - 1):.3f} %")
    mesh = peer[0]
    print(f"exudyn-ffrf mesh ({mesh['mesh_nodes']} nodes): mass {mesh['mesh_mass_kg']:.6f} kg "
          f"(rho L b h = {RHO_LBH:.6f}); f1 {mesh['f1_hz']:.4f} Hz, f2 {mesh['f2_hz']:.4f} Hz against "
          f"Euler-Bernoulli {mesh['f1_eb_hz']:.4f}, {mesh['f2_eb_hz']:.4f} Hz "
          f"({100 * (mesh['f1_hz'] / mesh['f1_eb_hz'] - 1):+.2f} %, "
          f"{100 * (mesh['f2_hz'] / mesh['f2_eb_hz'] - 1):+.2f} %)")


def spacecraft(reps: int, t_end: float, dt: float, elements: int = 8) -> None:
    """Case S: the tumbling spacecraft, hubbeam against Exudyn, alternating, medians; the two
    engines' series side by side (every 1 s) with their differences."""
    engines = ["hubbeam-spacecraft", "exudyn-spacecraft"]
    one_run(engines[0], elements, 2 * dt, dt)  # warm the numba cache of the free base's code
    runs = alternate({e: elements for e in engines}, reps, t_end, dt)
    print(f"\nCase S (a spacecraft tumbling freely): {elements} elements per panel, {t_end:g} s at dt = {dt:g} s; "
          f"median of {reps}, {os.cpu_count()} cores")
    print(f"{'engine':18s} {'integration s':>13s} {'process s':>10s} {'steps':>6s} {'Newton/step':>11s} {'LU/step':>8s}")
    for e in engines:
        first = runs[e][0]
        print(f"{e:18s} {median(runs[e], 'integration_s'):13.3f} {median(runs[e], 'process_s'):10.3f} "
              f"{int(first['steps']):6d} {first['newton_per_step']:11.2f} {first['factorisations_per_step']:8.2f}")
    ours, peer = runs[engines[0]], runs[engines[1]]
    print(f"hubbeam / exudyn: integration {median(ours, 'integration_s') / median(peer, 'integration_s'):.3f}, "
          f"process {median(ours, 'process_s') / median(peer, 'process_s'):.3f}")
    h, x = ours[0], peer[0]
    t = h["time"]
    step = max(1, round(1.0 / (t[1] - t[0])))
    print(f"{'t (s)':>6s} | {'bus w_x, w_y, w_z (rad/s): hubbeam':>36s} | {'exudyn':>29s} | "
          f"{'tip a tangential (mm): hubbeam':>30s} {'exudyn':>9s}")
    for k in range(0, len(t), step):
        print(f"{t[k]:6.1f} | {h['rate'][k][0]:11.6f} {h['rate'][k][1]:11.6f} {h['rate'][k][2]:11.6f} | "
              f"{x['rate'][k][0]:9.6f} {x['rate'][k][1]:9.6f} {x['rate'][k][2]:9.6f} | "
              f"{1e3 * h['tip_a'][k][2]:30.4f} {1e3 * x['tip_a'][k][2]:9.4f}")
    for name, index, unit, scale in (("bus angular velocity", None, "rad/s", 1.0), ("tip a tangential", 2, "mm", 1e3),
                                     ("tip b tangential", 2, "mm", 1e3)):
        key = "rate" if index is None else name.split()[0] + "_" + name.split()[1]
        a = [v if index is None else [v[index]] for v in h[key]]
        b = [v if index is None else [v[index]] for v in x[key]]
        diff = max(abs(p - q) for u, w in zip(a, b) for p, q in zip(u, w))
        size = max(abs(p) for u in a for p in u)
        print(f"{name}: largest difference {scale * diff:.4g} {unit} ({100 * diff / size:.2f} % of the largest value, "
              f"{scale * size:.4g} {unit})")


def moving_base(reps: int, t_end: float, dt: float, elements: int = 8) -> None:
    """Case M: what a free base costs. Case S's two panels (8 elements) on the free bus against
    the same panels on a free 1-DOF hub (issue 24: at most 1.3x), ANCF and FFR on 4 modes each
    (issue 26: the modal spacecraft, 60 s at 1 ms, output every 10 ms, within 0.5 s),
    alternating, medians. Two motions: ``slew``, the same PD slew about the hub axis on both
    (the like-for-like comparison: the base's other five degrees of freedom stay at rest), and
    ``spacecraft``, case S's tumbling bus against a hub spun up by a constant torque (different
    motions: the tumbling bus turns its ANCF panels through their charts)."""
    engines = ["slew-free-base", "slew-free-hub", "slew-modal-free-base", "slew-modal-free-hub",
               "spacecraft-free-base", "spacecraft-free-hub", "spacecraft-modal-free-base", "spacecraft-modal-free-hub"]
    runs = alternate({e: elements for e in engines}, reps, t_end, dt)
    print(f"\nCase M (case S's panels on a free base and on a free 1-DOF hub): {elements} elements per panel, "
          f"{t_end:g} s at dt = {dt:g} s, output every 10 ms; median of {reps}, {os.cpu_count()} cores")
    print(f"{'engine':28s} {'integration s':>13s} {'us/step':>8s} {'Newton/step':>11s} {'LU/step':>8s}")
    for e in engines:
        first = runs[e][0]
        seconds = median(runs[e], "integration_s")
        print(f"{e:28s} {seconds:13.3f} {1e6 * seconds / first['steps']:8.1f} {first['newton_per_step']:11.2f} "
              f"{first['factorisations_per_step']:8.3f}")
    for motion in ("slew", "spacecraft"):
        for kind in ("", "modal-"):
            ratio = median(runs[f"{motion}-{kind}free-base"], "integration_s") / median(
                runs[f"{motion}-{kind}free-hub"], "integration_s")
            print(f"{motion}-{kind}free-base / {motion}-{kind}free-hub: integration {ratio:.2f}")


def joints(reps: int, t_end: float, dt: float) -> None:
    """Case J: a joint's cost against the same beam clamped, and chains of n links."""
    pairs = [("exp1-ancf", "exp1-ancf-hinge"), ("exp1-ffr", "exp1-ffr-hinge")]
    for e in ("exp1-ancf-hinge", "exp1-ffr-hinge"):
        one_run(e, 6, 2 * dt, dt)  # warm the numba cache of the joints' code
    runs = exp1_runs([e for pair in pairs for e in pair], reps, t_end, dt)
    print(f"\nCase J (joints): exp1, 6 elements, {t_end:g} s at dt = {dt:g} s, clamped against a stiff flap hinge; "
          f"median of {reps}, {os.cpu_count()} cores")
    print_exp1_runs(runs, process=False)
    for clamped, hinged in pairs:
        ratio = median(runs[hinged], "integration_s") / median(runs[clamped], "integration_s")
        print(f"{hinged} / {clamped}: integration {ratio:.3f}")
    for engine, started in (("chain", "every hinge started at 1 rad/s: link k turns at k rad/s"),
                            ("chain-first", "only the first hinge started: every link at 1 rad/s")):
        print(f"\nCase J ({engine}): n links on lag hinges, 4 ANCF elements each, {started}, 1 s at dt = {dt:g} s; "
              f"best of {reps}")
        one = None
        for n in (1, 2, 4, 8):
            best = min((one_run(engine, n, 1.0, dt) for _ in range(reps)), key=lambda r: r["integration_s"])
            per = best["integration_s"] / best["steps"]
            one = per if n == 1 else one
            print(f"  {n} link{'s' if n > 1 else ' '}: {1e3 * per:.3f} ms per step, {best['newton_per_step']:.2f} "
                  f"Newton / {best['factorisations_per_step']:.2f} LU per step ({per / (n * one):.2f} x n times one "
                  f"link)")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--reps", type=int, default=3)
    p.add_argument("--t-end", type=float, default=10.0)
    p.add_argument("--dt", type=float, default=1e-3)
    p.add_argument("--cases", default="A,B,C,P,F,R,S,M,J", help="comma-separated subset of A, B, C, P, F, R, S, M, J")
    p.add_argument("--quick", action="store_true", help="1 s simulated, one repetition")
    a = p.parse_args()
    if a.quick:
        a.reps, a.t_end = 1, 1.0
    cases = {c.strip().upper() for c in a.cases.split(",")}
    if cases & {"A", "B", "R", "S"} and importlib.util.find_spec("exudyn") is None:
        sys.exit("benchmarks/run.py: the peer is missing; install it with: pip install \".[peer]\"")
    one_run("hubbeam", 8, 2 * a.dt, a.dt)  # warm the numba cache
    if "A" in cases:
        compare("Case A (plate under gravity)", ["hubbeam", "exudyn-ge", "exudyn-cable"], 8, a.reps, a.t_end, a.dt,
                "vertical")
    if "B" in cases:
        compare("Case B (Kane's spin-up)", ["hubbeam-kane", "exudyn-cable-kane"], 20, a.reps, a.t_end, a.dt,
                "tangential")
    if "C" in cases:
        print(f"\nCase C: hubbeam cost per step against elements (case A, 1 s simulated, best of {a.reps})")
        base = None
        for n in (4, 8, 16, 32, 64):
            per = min(one_run("hubbeam", n, 1.0, a.dt)["integration_s"] for _ in range(a.reps)) / round(1.0 / a.dt)
            base = per if n == 8 else base
            print(f"  {n:3d} elements: {1e3 * per:.3f} ms per step"
                  + (f" ({per / base:.1f}x the 8-element cost)" if base else ""))
    if "F" in cases:
        formulations(a.reps, 20.0 if not a.quick else 1.0, a.dt)
    if "R" in cases:
        reduced_order(a.reps, a.t_end, a.dt)
    if "S" in cases:
        spacecraft(a.reps, 10.0 if not a.quick else 1.0, 2e-3)
    if "M" in cases:
        moving_base(a.reps, 60.0 if not a.quick else 1.0, 1e-3)
    if "J" in cases:
        joints(a.reps, a.t_end, a.dt)
    if "P" in cases:
        times = [cli_run(a.t_end) for _ in range(a.reps)]
        print(f"\nCase P: `hubbeam run benchmarks/case_a.toml -o OUT.nc` ({a.t_end:g} s simulated), whole process: "
              f"median {statistics.median(times):.2f} s of {a.reps}, range {min(times):.2f}-{max(times):.2f} s "
              f"(warm numba cache)")


if __name__ == "__main__":
    main()
