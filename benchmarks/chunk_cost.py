"""What a run's returns to Python between chunks of compiled steps cost (issue 26): the whole
time loop of ``simulate`` (its wall time, the benchmarks' *integration* column, and its process
time, steadier beside other jobs) with
chunks of at least ``simulation.MIN_CHUNK_SECONDS`` of computing (today's) and with 1 % chunks
(MIN_CHUNK_SECONDS = 0, the loop before), alternating in this one process; least of REPS runs
each, the records compared bit for bit.

    python benchmarks/chunk_cost.py R|F|N|A [REPS]

R: case R (case A's plate on 4 modes, 10 s at 1 ms); F: experiment 1 on 4 modes (20 s);
N: experiment 1, nodal FFR (20 s); A: experiment 1, ANCF (20 s). numba's cache must be warm.
"""
import os
import sys
import time

import numpy as np

import hubbeam.simulation as simulation
from hubbeam import api
from hubbeam.io.scenario import load_example, load_scenario

HERE = os.path.dirname(os.path.abspath(__file__))


def scenario(case: str, t_end: float):
    if case == "R":
        return load_scenario(os.path.join(HERE, "case_a.toml"), ['beam.formulation="ffr"', "beam.modes=4",
                                                                 "beam.elements=8", "analysis.dt=0.001",
                                                                 f"analysis.t_end={t_end}"])
    formulation = {"F": ['beam.formulation="ffr"', "beam.modes=4"], "N": ['beam.formulation="ffr"'], "A": []}[case]
    return load_example("exp1", formulation + ["beam.elements=6", "analysis.dt=0.001", f"analysis.t_end={t_end}"])


def main(case: str, reps: int) -> None:
    simulate = simulation.simulate
    spent = []

    def timed(*args, **kwargs):
        cpu = time.process_time()
        traj = simulate(*args, **kwargs)
        spent.append(time.process_time() - cpu)
        return traj

    simulation.simulate = timed  # api.run imports it when called
    api.run(scenario(case, 0.002))  # loads the compiled code
    sc = scenario(case, 10.0 if case == "R" else 20.0)
    default = simulation.MIN_CHUNK_SECONDS
    times = {default: [], 0.0: []}
    records = {}
    for _ in range(reps):
        for least in times:
            simulation.MIN_CHUNK_SECONDS = least
            calls = []
            traj, failure = api.run(sc, progress=calls.append)
            assert failure is None
            times[least].append((traj.wall_time_s, spent[-1], len(calls)))
            records[least] = {k: np.asarray([list(r.values()) if isinstance(r, dict) else r for r in v])
                              for k, v in traj.records.items()}
    simulation.MIN_CHUNK_SECONDS = default
    simulation.simulate = simulate
    same = all(np.array_equal(records[default][k], records[0.0][k]) for k in records[0.0])
    for least, rows in times.items():
        wall = min(r[0] for r in rows)
        cpu = min(r[1] for r in rows)
        print(f"{case} MIN_CHUNK_SECONDS = {least:<5} chunks {rows[0][2]:4d}  integration {wall:.4f} s, "
              f"process time {cpu:.4f} s ({cpu / traj.steps * 1e6:.2f} us per step)")
    print(f"records bit-identical: {same}; load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 3)
