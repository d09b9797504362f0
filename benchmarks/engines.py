"""One benchmark run of one engine on one case, in this process; prints one JSON line.

    python benchmarks/engines.py ENGINE ELEMENTS T_END DT

Case A (issue 6): the reference plate (README, "Beam properties") clamped, gravity along its weak
axis, released from straight, generalized-alpha rho_inf = 0.8, no damping. Engines:
hubbeam (benchmarks/case_a.toml: ANCF with torsion, the product), exudyn-ge (Exudyn's
ObjectBeamGeometricallyExact, 3D with torsion) and exudyn-cable (ObjectANCFCable, 3D ANCF
without torsion). Case B: Kane's spin-up: hubbeam-kane (benchmarks/case_b.toml) and
exudyn-cable-kane. Case S: the spacecraft tumbling freely (benchmarks/case_s.toml): hubbeam-spacecraft and
exudyn-spacecraft (series of the bus's angular velocity and the panels' tips). Case R: case A
with modal reduction: hubbeam-ffr-modal (the FFR beam, its 4
lowest clamped modes) and exudyn-ffrf (Exudyn's ObjectFFRFreducedOrder on a Hex20 solid mesh
of the plate, benchmarks/solid_plate.py, its 4 lowest clamped modes; ELEMENTS counts the
hexahedra along the length). Case J (joints): exp1-ancf-hinge and exp1-ffr-hinge (experiment 1 with
the plate on a stiff flap hinge), chain (ELEMENTS counts the links of a chain on lag hinges,
4 elements each, every hinge started at 1 rad/s) and chain-first (only the first hinge started).
Output: integration wall time (s), steps, Newton iterations and LU
factorisations per step (when the engine reports them) and the tip deflection (case A:
vertical, case B: tangential, m) at the end and its minimum over the run, so that equal
accuracy can be checked. Exudyn's Newton tolerances are set as issue 6 prescribes.
"""

from __future__ import annotations

import argparse
import json
import time

L, B, H, E, RHO = 1.45, 0.05, 0.0025, 70e9, 2700.0


def _run_hubbeam_scenario(name: str, elements: int, t_end: float, dt: float, part: str,
                          extra_overrides: tuple[str, ...] = ()) -> dict:
    import os

    import numpy as np

    from hubbeam import api
    from hubbeam.io.scenario import load_scenario

    overrides = [*extra_overrides, f"beam.elements={elements}", f"analysis.t_end={t_end}", f"analysis.dt={dt}"]
    scenario = load_scenario(os.path.join(os.path.dirname(os.path.abspath(__file__)), name), overrides)
    api.run(scenario.model_copy(update={"analysis": scenario.analysis.model_copy(update={"t_end": 2 * dt})}))
    traj, failure = api.run(scenario)  # the line above loaded the compiled code from the numba cache
    if failure is not None:
        raise failure
    values = np.array([r[part] for r in traj.records["tip"]])
    return {"integration_s": traj.wall_time_s, "steps": traj.steps,
            "newton_per_step": traj.newton_iterations / traj.steps,
            "factorisations_per_step": traj.factorisations / traj.steps,
            "tip_end": float(values[-1]), "tip_min": float(values.min())}


def _run_exp1(elements: int, t_end: float, dt: float, overrides: list[str]) -> dict:
    """The paper's experiment 1 (the bundled exp1: free hub, drag, release under gravity) with
    ``overrides``; reports the P1 strain's peak and end value."""
    import numpy as np

    from hubbeam import api
    from hubbeam.io.scenario import load_example

    base = overrides + [f"beam.elements={elements}", f"analysis.dt={dt}"]
    api.run(load_example("exp1", base + [f"analysis.t_end={2 * dt}"]))  # loads the compiled code
    traj, failure = api.run(load_example("exp1", base + [f"analysis.t_end={t_end}"]))
    if failure is not None:
        raise failure
    p1 = np.array(traj.records["strain_P1"])
    return {"integration_s": traj.wall_time_s, "steps": traj.steps,
            "newton_per_step": traj.newton_iterations / traj.steps,
            "factorisations_per_step": traj.factorisations / traj.steps,
            "peak": float(p1.max()), "end": float(p1[-1])}


def run_exp1_ancf(elements: int, t_end: float, dt: float) -> dict:
    """Case F: exp1 with the ANCF beam."""
    return _run_exp1(elements, t_end, dt, [])


def run_exp1_ffr(elements: int, t_end: float, dt: float) -> dict:
    """Case F: exp1 with the nodal FFR beam (the paper's)."""
    return _run_exp1(elements, t_end, dt, ['beam.formulation="ffr"'])


def run_exp1_ffr_modal(elements: int, t_end: float, dt: float) -> dict:
    """Case F: exp1 with the FFR beam reduced to its 4 lowest clamped modes."""
    return _run_exp1(elements, t_end, dt, ['beam.formulation="ffr"', "beam.modes=4"])


def run_hubbeam(elements: int, t_end: float, dt: float) -> dict:
    """Case A with hubbeam (benchmarks/case_a.toml); reports the vertical tip deflection."""
    return _run_hubbeam_scenario("case_a.toml", elements, t_end, dt, "vertical")


def run_hubbeam_ffr_modal(elements: int, t_end: float, dt: float) -> dict:
    """Case R with hubbeam: case A (benchmarks/case_a.toml) with the FFR beam reduced to its 4
    lowest clamped modes; reports the vertical tip deflection."""
    return _run_hubbeam_scenario("case_a.toml", elements, t_end, dt, "vertical",
                                 ('beam.formulation="ffr"', "beam.modes=4"))


def run_exudyn_cable(elements: int, t_end: float, dt: float) -> dict:
    """Case A with Exudyn's ObjectANCFCable (3D ANCF, no torsion), weak-axis bending stiffness."""
    import exudyn as exu
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
    return _solve_exudyn(mbs, sensor, t_end, dt)


def run_exudyn_ge(elements: int, t_end: float, dt: float) -> dict:
    """Exudyn's ObjectBeamGeometricallyExact (3D, shear deformable, with torsion) on rigid-body
    nodes (Euler parameters), clamped by a GenericJoint to ground. Local x along the beam, y
    along the thickness (so gravity -y bends the weak axis), z along the width."""
    import exudyn as exu
    import numpy as np
    from exudyn.itemInterface import (GenericJoint, Gravity, MarkerBodyMass, MarkerNodeRigid, NodePointGround,
                                      NodeRigidBodyEP, ObjectBeamGeometricallyExact, SensorNode)
    from exudyn.rigidBodyUtilities import eulerParameters0

    from hubbeam.elements.section import saint_venant_torsion_constant

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    nu = 0.33
    G = E / (2 * (1 + nu))
    A = B * H
    i_y_local = B * H**3 / 12  # about local z (weak): thickness along y
    i_z_local = H * B**3 / 12  # about local y (strong)
    ks = 5.0 / 6.0  # shear correction of a rectangle
    section = exu.BeamSection()
    section.stiffnessMatrix = np.diag([E * A, ks * G * A, ks * G * A, G * saint_venant_torsion_constant(B, H),
                                       E * i_z_local, E * i_y_local])
    section.inertia = RHO * np.diag([i_y_local + i_z_local, i_z_local, i_y_local])
    section.massPerLength = RHO * A
    le = L / elements
    nodes = [mbs.AddNode(NodeRigidBodyEP(referenceCoordinates=[k * le, 0, 0] + list(eulerParameters0)))
             for k in range(elements + 1)]
    for k in range(elements):
        beam = mbs.AddObject(ObjectBeamGeometricallyExact(nodeNumbers=[nodes[k], nodes[k + 1]], length=le,
                                                          sectionData=section))
        mbs.AddLoad(Gravity(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=beam)), loadVector=[0, -9.81, 0]))
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    mbs.AddObject(GenericJoint(markerNumbers=[mbs.AddMarker(MarkerNodeRigid(nodeNumber=ground)),
                                              mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[0]))]))
    sensor = mbs.AddSensor(SensorNode(nodeNumber=nodes[-1], storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.Displacement))
    mbs.Assemble()
    return _solve_exudyn(mbs, sensor, t_end, dt)


def run_exudyn_ffrf(elements: int, t_end: float, dt: float) -> dict:
    """Case R with Exudyn's ObjectFFRFreducedOrder: the plate as ``elements`` x 1 x 2 Hex20
    solids (benchmarks/solid_plate.py, ``elements`` along the length graded towards the clamp;
    x along the length, y along the thickness, z along the width; case R: 32), reduced to its
    4 lowest modes clamped at x = 0 (Hurty-Craig-Bampton, fixed-interface eigenmodes only;
    no NGsolve: the mesh's M and K are written by solid_plate.py); the floating frame clamped
    to ground by a GenericJoint, gravity -y (LoadMassProportional), sensor: the displacement of
    the tip-face centre node (L, 0, 0).
    Besides the timing and the tip, the mesh check: ``mesh_mass_kg`` (rho L b h = 0.489 kg) and
    ``f1_hz``, ``f2_hz`` against Euler-Bernoulli weak-axis bending ``f1_eb_hz``, ``f2_eb_hz``."""
    import exudyn as exu
    from exudyn.FEM import ObjectFFRFreducedOrderInterface
    from exudyn.itemInterface import GenericJoint, MarkerNodeRigid, NodePointGround, SensorSuperElement

    from solid_plate import check, plate_fem

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    fem, _, tip_node = plate_fem(elements, modes=4)
    mesh = check(fem)
    ffrf = ObjectFFRFreducedOrderInterface(fem).AddObjectFFRFreducedOrder(mbs, gravity=[0, -9.81, 0])
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    mbs.AddObject(GenericJoint(markerNumbers=[mbs.AddMarker(MarkerNodeRigid(nodeNumber=ground)),
                                              mbs.AddMarker(MarkerNodeRigid(nodeNumber=ffrf["nRigidBody"]))]))
    sensor = mbs.AddSensor(SensorSuperElement(bodyNumber=ffrf["oFFRFreducedOrder"], meshNodeNumber=tip_node,
                                              storeInternal=True,
                                              outputVariableType=exu.OutputVariableType.Displacement))
    mbs.Assemble()
    result = _solve_exudyn(mbs, sensor, t_end, dt)
    result.update(mesh_nodes=mesh["mesh_nodes"], mesh_mass_kg=mesh["mass_kg"], f1_hz=mesh["f_hz"][0],
                  f2_hz=mesh["f_hz"][1], f1_eb_hz=mesh["f_weak_eb_hz"][0], f2_eb_hz=mesh["f_weak_eb_hz"][1])
    return result


KANE = {"length": 10.0, "EI": 14000.0, "EA": 7e10 * 4e-4, "rhoA": 1.2, "omega_s": 4.0, "T": 15.0}


def kane_angle(t: float) -> float:
    """Hub angle of Kane's spin-up (rad): hubbeam.system.hub.DriveProfile('spin_up', 4, 15)."""
    import math

    w, T = KANE["omega_s"], KANE["T"]
    if t < T:
        return (w / T) * (t * t / 2.0 + (T / (2 * math.pi)) ** 2 * (math.cos(2 * math.pi * t / T) - 1.0))
    return w * (t - T / 2.0)


def run_hubbeam_kane(elements: int, t_end: float, dt: float) -> dict:
    """Case B with hubbeam (benchmarks/case_b.toml); reports the tangential tip deflection."""
    return _run_hubbeam_scenario("case_b.toml", elements, t_end, dt, "tangential")


def run_exudyn_cable_kane(elements: int, t_end: float, dt: float) -> dict:
    """Case B with Exudyn's ObjectANCFCable: the root node at the hub centre, its slope driven
    along i_h(theta(t)) = (cos theta, 0, sin theta) by coordinate constraints whose offsets
    are Python user functions (Exudyn's way of prescribing a motion of coordinates)."""
    import math

    import exudyn as exu
    import numpy as np
    from exudyn.beams import GenerateBeamElementsAlongLine
    from exudyn.itemInterface import (CoordinateConstraint, MarkerNodeCoordinate, NodePointGround, ObjectANCFCable,
                                      SensorNode)

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    cable = ObjectANCFCable(physicsMassPerLength=KANE["rhoA"], physicsBendingStiffness=KANE["EI"],
                            physicsAxialStiffness=KANE["EA"])
    beam = GenerateBeamElementsAlongLine(mbs, positionStart=[0, 0, 0], positionEnd=[KANE["length"], 0, 0],
                                         numberOfElements=elements, beamTemplate=cable,
                                         groundConstraintsStart=[1, 1, 1, 0, 1, 0])
    root = beam["nodes"][0]
    ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
    for coordinate, fun in ((3, math.cos), (5, math.sin)):
        mbs.AddObject(CoordinateConstraint(
            markerNumbers=[ground, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=root, coordinate=coordinate))],
            offsetUserFunction=lambda mbs, t, item, offset, fun=fun: fun(kane_angle(t)) - (1.0 if fun is math.cos else 0.0)))
    tip = beam["nodes"][-1]
    sensor = mbs.AddSensor(SensorNode(nodeNumber=tip, storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    result = _solve_exudyn(mbs, sensor, t_end, dt, component=None)
    data = np.array(mbs.GetSensorStoredData(sensor))
    theta = np.array([kane_angle(t) for t in data[:, 0]])
    tangential = -np.sin(theta) * data[:, 1] + np.cos(theta) * data[:, 3]
    result.update(tip_end=float(tangential[-1]), tip_min=float(tangential.min()))
    return result


def _case_s() -> dict:
    """benchmarks/case_s.toml (the spacecraft tumbling freely), read as plain TOML."""
    import os
    import tomllib

    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "case_s.toml"), "rb") as f:
        return tomllib.load(f)


def run_hubbeam_spacecraft(elements: int, t_end: float, dt: float) -> dict:
    """Case S with hubbeam (benchmarks/case_s.toml: a free bus, two ANCF panels with tip bodies);
    reports the series at the output times: the bus's angular velocity (bus axes, rad/s) and
    each panel's tip deflection (radial, vertical, tangential in its hub frame, m)."""
    import os

    from hubbeam import api
    from hubbeam.io.scenario import load_scenario

    overrides = [f"beams[*].elements={elements}", f"analysis.t_end={t_end}", f"analysis.dt={dt}"]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "case_s.toml")
    api.run(load_scenario(path, overrides[:1] + [f"analysis.t_end={2 * dt}", f"analysis.dt={dt}",
                                                 f"analysis.output_dt={dt}"]))  # loads the compiled code
    traj, failure = api.run(load_scenario(path, overrides))
    if failure is not None:
        raise failure
    rec = traj.records
    parts = ("radial", "vertical", "tangential")
    return {"integration_s": traj.wall_time_s, "steps": traj.steps,
            "newton_per_step": traj.newton_iterations / traj.steps,
            "factorisations_per_step": traj.factorisations / traj.steps, "time": [float(t) for t in traj.times],
            "rate": [[float(r[c]) for c in "xyz"] for r in rec["rate"]],
            "tip_a": [[float(r[p]) for p in parts] for r in rec["tip_a"]],
            "tip_b": [[float(r[p]) for p in parts] for r in rec["tip_b"]]}


def case_m_text(free_base: bool, slew: bool = False) -> str:
    """The scenario text of case M (:func:`_spacecraft_cost`): case S's panels (ANCF, 8
    elements, before overrides) on the free bus (``free_base``) or on a free 1-DOF hub, turned
    by the tumble and a constant hub torque, or by the same PD slew (``slew``)."""
    import os
    import re

    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "case_s.toml"), encoding="utf-8") as f:
        text = f.read()
    slew_table = "angle = 0.5235987755982988\nT = 20.0\n"
    if slew and free_base:
        text = re.sub(r"\[base\].*?(?=\[hub\])",
                      "[base]\nmotion = \"free\"\nmass = 400.0\ninertia = [150.0, 120.0, 160.0]\n\n"
                      "[base.torque]\nlaw = \"pd\"\nkp = [25.0, 138.0, 145.0]\nkd = [100.0, 550.0, 580.0]\n\n"
                      f"[base.torque.slew]\naxis = [0.0, 1.0, 0.0]\n{slew_table}\n", text, flags=re.S)
    if not free_base:  # the [base] tables and the bus's sensor out, the hub free about its axis
        text = re.sub(r"\[base\].*?(?=\[hub\])", "", text, flags=re.S)
        law = ("torque = 2.0\n" if not slew else
               f"\n[hub.torque]\nlaw = \"pd\"\nkp = 138.0\nkd = 550.0\n\n[hub.torque.reference]\nprofile = \"slew\"\n{slew_table}\n")
        text = text.replace("[hub]\n", "[hub]\nmotion = \"free\"\ninertia = 120.0\n" + ("" if slew else law))
        if slew:  # the hub's torque tables after its keys
            text = text.replace("[[beams]]", law + "\n[[beams]]", 1)
        text = text.replace('[[sensors]]\nname = "rate"\nkind = "base_angular_velocity"\n', "")
    return text


def _spacecraft_cost(elements: int, t_end: float, dt: float, free_base: bool, modes: int = 0,
                     slew: bool = False) -> dict:
    """Case M: the panels of case S (benchmarks/case_s.toml, released turning) on the free bus
    (``free_base``) or, the same panels, elements, steps and Newton settings, on a free 1-DOF
    hub (no [base]; hub inertia 120 kg m^2, the bus's about its y axis, spun up from rest by a
    constant 2 N m: a free hub has no initial speed);
    ANCF panels, or FFR on ``modes`` clamped modes. Output every 10 ms.

    ``slew``: the same motion on both instead: the bus with its principal inertia (150, 120,
    160 kg m^2, no products) starts at rest and a PD law turns it by 30 deg in 20 s about the
    hub axis y (spacecraft3d's gains about y: kp = 138 N m/rad, kd = 550 N m s/rad; the other
    axes held at rest), and the free hub (120 kg m^2) follows the same slew under the same PD
    law: the two models then move alike and differ only in the base's other five degrees of
    freedom, which stay at rest."""
    import os
    import tempfile

    from hubbeam import api
    from hubbeam.io.scenario import load_scenario

    text = case_m_text(free_base, slew)
    overrides = [f"beams[*].elements={elements}", f"analysis.dt={dt}", "analysis.output_dt=0.01"]
    if modes:
        overrides += ['beams[*].formulation="ffr"', f"beams[*].modes={modes}"]
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "case_m.toml")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        api.run(load_scenario(path, [*overrides, f"analysis.t_end={2 * dt}"]))  # loads the compiled code
        traj, failure = api.run(load_scenario(path, [*overrides, f"analysis.t_end={t_end}"]))
    if failure is not None:
        raise failure
    return {"integration_s": traj.wall_time_s, "steps": traj.steps,
            "newton_per_step": traj.newton_iterations / traj.steps,
            "factorisations_per_step": traj.factorisations / traj.steps}


def run_spacecraft_free_base(elements: int, t_end: float, dt: float) -> dict:
    """Case M: case S's two ANCF panels on the free bus."""
    return _spacecraft_cost(elements, t_end, dt, True)


def run_spacecraft_free_hub(elements: int, t_end: float, dt: float) -> dict:
    """Case M: the same two ANCF panels on a free 1-DOF hub."""
    return _spacecraft_cost(elements, t_end, dt, False)


def run_spacecraft_modal_free_base(elements: int, t_end: float, dt: float) -> dict:
    """Case M: case S's two panels as FFR beams on 4 modes each, on the free bus."""
    return _spacecraft_cost(elements, t_end, dt, True, modes=4)


def run_spacecraft_modal_free_hub(elements: int, t_end: float, dt: float) -> dict:
    """Case M: the same two 4-mode FFR panels on a free 1-DOF hub."""
    return _spacecraft_cost(elements, t_end, dt, False, modes=4)


def run_slew_free_base(elements: int, t_end: float, dt: float) -> dict:
    """Case M, the same motion: two ANCF panels on the free bus slewed about the hub axis."""
    return _spacecraft_cost(elements, t_end, dt, True, slew=True)


def run_slew_free_hub(elements: int, t_end: float, dt: float) -> dict:
    """Case M, the same motion: the same two ANCF panels on a free hub under the same slew law."""
    return _spacecraft_cost(elements, t_end, dt, False, slew=True)


def run_slew_modal_free_base(elements: int, t_end: float, dt: float) -> dict:
    """Case M, the same motion: two 4-mode FFR panels on the free bus slewed about the hub axis."""
    return _spacecraft_cost(elements, t_end, dt, True, modes=4, slew=True)


def run_slew_modal_free_hub(elements: int, t_end: float, dt: float) -> dict:
    """Case M, the same motion: two 4-mode FFR panels on a free hub under the same slew law."""
    return _spacecraft_cost(elements, t_end, dt, False, modes=4, slew=True)


def run_exudyn_spacecraft(elements: int, t_end: float, dt: float) -> dict:
    """Case S with Exudyn, the model of benchmarks/case_s.toml: the bus an ObjectRigidBody on an
    Euler-parameter node (its inertia tensor as [J_xx, J_yy, J_zz, J_yz, J_xz, J_xy]); each panel
    ``elements`` ObjectBeamGeometricallyExact on Euler-parameter nodes (local x along the panel,
    y along its width (the hub axis), z across its thickness; section stiffness EA, kGA (k =
    5/6), GJ_t (St-Venant, as hubbeam), EI about y (weak) and z; inertia rho diag(I_y + I_z,
    I_y, I_z)), its root node held to the bus by a GenericJoint at (+-radius, 0, 0), its tip
    node carrying the tip body's ObjectRigidBody; every node starting with the rigid velocity
    field of the bus's w0. Newton's relative tolerance 1e-7 (below). Reports the same series as :func:`run_hubbeam_spacecraft`: the bus's
    angular velocity (AngularVelocityLocal) and each tip's displacement from its place carried
    by the bus, in the panel's own hub frame (panel b's turned by 180 deg about y)."""
    import exudyn as exu
    import numpy as np
    from exudyn.itemInterface import (GenericJoint, MarkerBodyRigid, MarkerNodeRigid, NodeRigidBodyEP,
                                      ObjectBeamGeometricallyExact, ObjectRigidBody, SensorBody, SensorNode)
    from exudyn.rigidBodyUtilities import AngularVelocity2EulerParameters_t, RotationMatrix2EulerParameters

    from hubbeam.elements.section import saint_venant_torsion_constant

    case = _case_s()
    base, beam, tip = case["base"], case["beams"][0], case["beams"][0]["tip_body"]
    radius = case["hub"]["radius"]
    length, width, thickness = beam["length"], beam["width"], beam["thickness"]
    E, rho, nu = beam["youngs_modulus"], beam["density"], beam["poisson_ratio"]
    G = E / (2 * (1 + nu))
    J = np.array(base["inertia"], dtype=float)
    w0 = np.array(base["initial"]["angular_velocity"], dtype=float)

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()

    def node(position, R):
        ep = np.array(RotationMatrix2EulerParameters(R))
        v = np.cross(w0, position)  # the rigid velocity field of the bus turning about its centre
        return mbs.AddNode(NodeRigidBodyEP(referenceCoordinates=list(position) + list(ep),
                                           initialVelocities=list(v) + list(AngularVelocity2EulerParameters_t(w0, ep))))

    bus_node = node(np.zeros(3), np.eye(3))
    bus = mbs.AddObject(ObjectRigidBody(mass=base["mass"], nodeNumber=bus_node,
                                        inertia=[J[0, 0], J[1, 1], J[2, 2], J[1, 2], J[0, 2], J[0, 1]]))
    A = width * thickness
    i_weak, i_strong = width * thickness**3 / 12, thickness * width**3 / 12  # about local y, about local z
    section = exu.BeamSection()
    section.stiffnessMatrix = np.diag([E * A, 5 / 6 * G * A, 5 / 6 * G * A,
                                       G * saint_venant_torsion_constant(width, thickness), E * i_weak, E * i_strong])
    section.inertia = rho * np.diag([i_weak + i_strong, i_weak, i_strong])
    section.massPerLength = rho * A
    le = length / elements
    tips = []
    for side in (1.0, -1.0):  # panel a on +x, panel b on -x (turned by 180 deg about y)
        R = np.diag([side, 1.0, side])
        nodes = [node(np.array([side * (radius + k * le), 0.0, 0.0]), R) for k in range(elements + 1)]
        for k in range(elements):
            mbs.AddObject(ObjectBeamGeometricallyExact(nodeNumbers=[nodes[k], nodes[k + 1]], length=le,
                                                       sectionData=section))
        mount = exu.HT(rotation=R, translation=[side * radius, 0.0, 0.0])  # the root node's frame on the bus
        mbs.AddObject(GenericJoint(markerNumbers=[mbs.AddMarker(MarkerBodyRigid(bodyNumber=bus, localHT=mount)),
                                                  mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[0]))]))
        mbs.AddObject(ObjectRigidBody(mass=tip["mass"], nodeNumber=nodes[-1],
                                      inertia=list(tip["inertia"]) + [0.0, 0.0, 0.0]))
        tips.append((nodes[-1], side))
    every = case["analysis"]["output_dt"]

    def sensor(item):
        return mbs.AddSensor(item)

    rate = sensor(SensorBody(bodyNumber=bus, storeInternal=True, writeToFile=False,
                             outputVariableType=exu.OutputVariableType.AngularVelocityLocal))
    position = sensor(SensorBody(bodyNumber=bus, storeInternal=True, writeToFile=False,
                                 outputVariableType=exu.OutputVariableType.Position))
    rotation = sensor(SensorBody(bodyNumber=bus, storeInternal=True, writeToFile=False,
                                 outputVariableType=exu.OutputVariableType.RotationMatrix))
    tip_sensors = [sensor(SensorNode(nodeNumber=n, storeInternal=True, writeToFile=False,
                                     outputVariableType=exu.OutputVariableType.Position)) for n, _ in tips]
    mbs.Assemble()
    # relative 1e-8 (issue 6's) is below this model's round-off floor: Exudyn's Newton then stalls (33
    # iterations and 17 Jacobians per step over 10 s: 148 s); at 1e-7 it converges in 6.5 iterations
    # and its series equal those at 1e-6 to 1e-9 rad/s
    result = _solve_exudyn(mbs, rate, t_end, dt, component=None, write_period=every, counts=True,
                           relative_tolerance=1e-7)
    data = {s: np.array(mbs.GetSensorStoredData(s)) for s in (rate, position, rotation, *tip_sensors)}
    t = data[rate][:, 0]
    rotations = data[rotation][:, 1:].reshape(-1, 3, 3)
    result.update(time=t.tolist(), rate=data[rate][:, 1:].tolist())
    for name, s, (_, side) in zip(("tip_a", "tip_b"), tip_sensors, tips):
        local = np.einsum("nji,nj->ni", rotations, data[s][:, 1:] - data[position][:, 1:])
        d = local - np.array([side * (radius + length), 0.0, 0.0])
        result[name] = (d * np.array([side, 1.0, side])).tolist()  # radial, vertical, tangential
    return result


def _solve_exudyn(mbs, sensor, t_end: float, dt: float, component: int | None = 2, write_period: float = 0.01,
                  counts: bool = False, relative_tolerance: float = 1e-8) -> dict:
    """Generalized-alpha (rho_inf 0.8), Newton tolerances of issue 6 (absolute 1e-6, relative
    ``relative_tolerance``); the tip's y displacement (``component`` None: none; the sensors
    are written every ``write_period`` s); ``counts``: also Exudyn's Newton iterations and
    Jacobians per step."""
    import exudyn as exu
    import numpy as np

    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = int(round(t_end / dt))
    s.timeIntegration.endTime = t_end
    s.timeIntegration.generalizedAlpha.spectralRadius = 0.8
    s.timeIntegration.newton.absoluteTolerance = 1e-6  # issue 6: Exudyn's 1e-10 default is below round-off here
    s.timeIntegration.newton.relativeTolerance = relative_tolerance
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = write_period
    start = time.perf_counter()
    exu.SolveDynamic(mbs, s)
    wall = time.perf_counter() - start
    result = {"integration_s": wall, "steps": s.timeIntegration.numberOfSteps, "newton_per_step": None}
    if counts:
        it = mbs.sys["dynamicSolver"].it
        result.update(newton_per_step=it.newtonStepsCount / s.timeIntegration.numberOfSteps,
                      factorisations_per_step=it.newtonJacobiCount / s.timeIntegration.numberOfSteps)
    if component is not None:
        y = np.array(mbs.GetSensorStoredData(sensor))[:, component]
        result.update(tip_end=float(y[-1]), tip_min=float(y.min()))
    return result


#: case J's hinge: a flap joint at the plate's root with a spring stiff enough that the motion is
#: the clamped one to 1e-3 (the gravity moment turns it by 4e-4 rad)
HINGE = 'beam.joint={kind="revolute", axis="flap", stiffness=1.0e4}'


def run_exp1_ancf_hinge(elements: int, t_end: float, dt: float) -> dict:
    """Case J: exp1 with the ANCF beam on a stiff flap hinge (:data:`HINGE`) instead of clamped."""
    return _run_exp1(elements, t_end, dt, [HINGE])


def run_exp1_ffr_hinge(elements: int, t_end: float, dt: float) -> dict:
    """Case J: exp1 with the nodal FFR beam on the stiff flap hinge."""
    return _run_exp1(elements, t_end, dt, ['beam.formulation="ffr"', HINGE])


def chain_scenario(links: int, t_end: float, dt: float, every_hinge: bool = True):
    """The scenario of :func:`run_chain` (a validated Scenario), the last link's tip_deflection as ``tip``."""
    from hubbeam.io.scenario import validate

    beams = []
    for k in range(links):
        beam = {"name": f"link{k}", "elements": 4, "length": 0.4, "width": B, "thickness": H, "density": RHO,
                "youngs_modulus": E, "twist": 90.0,
                "joint": {"kind": "revolute", "axis": "lag", "stiffness": 5.0,
                          "initial_rate": 1.0 if every_hinge or k == 0 else 0.0}}
        beam.update({"parent": f"link{k - 1}"} if k else {"radius": 0.35})
        beams.append(beam)
    return validate({"name": "chain", "hub": {"motion": "fixed"}, "beams": beams,
                     "analysis": {"kind": "dynamic", "t_end": t_end, "dt": dt, "spectral_radius": 0.8},
                     "sensors": [{"name": "tip", "kind": "tip_deflection", "beam": f"link{links - 1}"}]})


def run_chain(links: int, t_end: float, dt: float, every_hinge: bool = True) -> dict:
    """Case J: a chain of ``links`` equal links of the plate's section (0.4 m, 4 ANCF elements each,
    laid flat: gravity bends the weak axis) on a fixed hub, the first on the hub, each next on the
    tip of the one before, every root on a lag hinge (about the vertical) with a spring of
    5 N m/rad, every hinge started at 1 rad/s (so that link k turns at k rad/s), or with
    ``every_hinge`` False only the first (the chain starts turning as one body, every link at
    1 rad/s); the last link's vertical tip deflection."""
    import numpy as np

    from hubbeam import api

    api.run(chain_scenario(links, 2 * dt, dt, every_hinge))  # loads the compiled code
    traj, failure = api.run(chain_scenario(links, t_end, dt, every_hinge))
    if failure is not None:
        raise failure
    values = np.array([r["vertical"] for r in traj.records["tip"]])
    return {"integration_s": traj.wall_time_s, "steps": traj.steps,
            "newton_per_step": traj.newton_iterations / traj.steps,
            "factorisations_per_step": traj.factorisations / traj.steps,
            "tip_end": float(values[-1]), "tip_min": float(values.min())}


def run_chain_first(links: int, t_end: float, dt: float) -> dict:
    """Case J: :func:`run_chain` with only the first hinge started: every link turns at the same speed."""
    return run_chain(links, t_end, dt, every_hinge=False)


ENGINES = {"hubbeam": run_hubbeam, "exudyn-cable": run_exudyn_cable, "exudyn-ge": run_exudyn_ge,
           "hubbeam-kane": run_hubbeam_kane, "exudyn-cable-kane": run_exudyn_cable_kane,
           "exp1-ancf": run_exp1_ancf, "exp1-ffr": run_exp1_ffr, "exp1-ffr-modal4": run_exp1_ffr_modal,
           "hubbeam-ffr-modal": run_hubbeam_ffr_modal, "exudyn-ffrf": run_exudyn_ffrf,
           "hubbeam-spacecraft": run_hubbeam_spacecraft, "exudyn-spacecraft": run_exudyn_spacecraft,
           "spacecraft-free-base": run_spacecraft_free_base, "spacecraft-free-hub": run_spacecraft_free_hub,
           "spacecraft-modal-free-base": run_spacecraft_modal_free_base,
           "spacecraft-modal-free-hub": run_spacecraft_modal_free_hub,
           "slew-free-base": run_slew_free_base, "slew-free-hub": run_slew_free_hub,
           "slew-modal-free-base": run_slew_modal_free_base, "slew-modal-free-hub": run_slew_modal_free_hub,
           "exp1-ancf-hinge": run_exp1_ancf_hinge, "exp1-ffr-hinge": run_exp1_ffr_hinge, "chain": run_chain,
           "chain-first": run_chain_first}

if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("engine", choices=sorted(ENGINES))
    p.add_argument("elements", type=int)
    p.add_argument("t_end", type=float)
    p.add_argument("dt", type=float)
    a = p.parse_args()
    print(json.dumps(ENGINES[a.engine](a.elements, a.t_end, a.dt)))
