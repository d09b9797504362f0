"""One benchmark run of one engine on one case, in this process; prints one JSON line.

    python benchmarks/engines.py ENGINE ELEMENTS T_END DT

ENGINE: hubbeam (ANCF with torsion, the product) | exudyn-cable (Exudyn's ObjectANCFCable,
3D ANCF without torsion). Case A of issue 6: the reference plate (conventions.md) clamped,
gravity along its weak axis (twist 90 deg), released from straight, generalized-alpha with
rho_inf = 0.8, no damping. Output: integration wall time (s), steps, Newton iterations
(when the engine reports them) and the tip's vertical displacement at the end and its
minimum over the run (m), so that equal accuracy can be checked.
"""

from __future__ import annotations

import json
import sys
import time

L, B, H, E, RHO = 1.45, 0.05, 0.0025, 70e9, 2700.0


def run_hubbeam(elements: int, t_end: float, dt: float) -> dict:
    import numpy as np

    from hubbeam import api
    from hubbeam.io.scenario import Sensor, load_example
    from hubbeam.simulation import simulate

    sc = load_example("cantilever", [f"beam.elements={elements}", 'analysis.kind="dynamic"',
                                     f"analysis.t_end={t_end}", f"analysis.dt={dt}", "analysis.spectral_radius=0.8",
                                     "damping.linear=0.0", "damping.quadratic=0.0"])
    system = api.build_system(sc)
    simulate(system, [], 2 * dt, dt)  # compile (numba cache) outside the timed run
    traj = simulate(system, [Sensor(name="tip", kind="tip_deflection")], t_end, dt, 0.8, 0.01)
    vertical = np.array([r["vertical"] for r in traj.records["tip"]])
    return {"integration_s": traj.wall_time_s, "steps": traj.steps,
            "newton_per_step": traj.newton_iterations / traj.steps,
            "tip_vertical_end": float(vertical[-1]), "tip_vertical_min": float(vertical.min())}


def run_exudyn_cable(elements: int, t_end: float, dt: float) -> dict:
    import exudyn as exu
    import numpy as np
    from exudyn.beams import GenerateBeamElementsAlongLine
    from exudyn.itemInterface import ObjectANCFCable, SensorNode

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    cable = ObjectANCFCable(physicsMassPerLength=RHO * B * H, physicsBendingStiffness=E * B * H**3 / 12,
                            physicsAxialStiffness=E * B * H)
    beam = GenerateBeamElementsAlongLine(mbs, positionStart=[0, 0, 0], positionEnd=[L, 0, 0],
                                         numberOfElements=elements, beamTemplate=cable, gravity=[0, -9.81, 0],
                                         groundConstraintsStart=[1, 1, 1, 0, 1, 1])
    tip = beam["nodes"][-1]
    sensor = mbs.AddSensor(SensorNode(nodeNumber=tip, storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.Displacement))
    mbs.Assemble()
    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = int(round(t_end / dt))
    s.timeIntegration.endTime = t_end
    s.timeIntegration.generalizedAlpha.spectralRadius = 0.8
    s.timeIntegration.newton.absoluteTolerance = 1e-6  # issue 6: Exudyn's 1e-10 default is below round-off here
    s.timeIntegration.newton.relativeTolerance = 1e-8
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 0.01
    start = time.perf_counter()
    exu.SolveDynamic(mbs, s)
    wall = time.perf_counter() - start
    y = np.array(mbs.GetSensorStoredData(sensor))[:, 2]
    return {"integration_s": wall, "steps": s.timeIntegration.numberOfSteps, "newton_per_step": None,
            "tip_vertical_end": float(y[-1]), "tip_vertical_min": float(y.min())}


ENGINES = {"hubbeam": run_hubbeam, "exudyn-cable": run_exudyn_cable}

if __name__ == "__main__":
    engine, elements, t_end, dt = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
    print(json.dumps(ENGINES[engine](elements, t_end, dt)))
