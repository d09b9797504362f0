"""[beams.joint] and parent in scenario files (io/scenario/joints.py, beams.py, model.py): the keys
resolved in SI units, and every bad joint or chain refused with one line naming the key."""

from __future__ import annotations

import copy
import math

import pytest

from hubbeam.io.scenario import ScenarioError, validate

BEAM = {"formulation": "ancf", "elements": 2, "length": 0.5, "width": 0.05, "thickness": 0.004, "density": 2700.0,
        "youngs_modulus": 70.0e9}


def chain(*beams, sensors=()) -> dict:
    return {"name": "chain", "hub": {"motion": "fixed"}, "beams": [dict(BEAM, **b) for b in beams],
            "analysis": {"kind": "dynamic", "t_end": 0.1, "dt": 0.01}, "sensors": list(sensors)}


ARM = chain({"name": "upper", "radius": 0.1, "joint": {"kind": "revolute", "axis": "lag", "stiffness": 2.0,
                                                       "torque": {"law": "pd", "kp": 3.0, "kd": 1.0,
                                                                  "reference": {"profile": "slew", "angle": 1.0,
                                                                                "T": 2.0}}}},
            {"name": "fore", "parent": "upper", "twist": 10.0,
             "joint": {"kind": "revolute", "axis": ["flap", [0.0, 1.0, 1.0]], "damping": [0.1, 0.2],
                       "initial_angle": [5.0, -3.0], "initial_rate": 0.5}},
            sensors=[{"name": "elbow", "kind": "joint_angle", "beam": "fore"},
                     {"name": "shoulder", "kind": "joint_torque", "beam": "upper"}])


def test_joints_and_parents_resolve_in_si_units():
    sc = validate(ARM)
    upper, fore = sc.resolved_beams()
    assert upper.parent is None and fore.parent == 0
    assert fore.radius == 0.0 and fore.azimuth == 0.0 and fore.twist == pytest.approx(math.radians(10.0))
    assert upper.joint.axes == ("lag",) and upper.joint.stiffness == (2.0,) and upper.joint.torque.law == "pd"
    assert fore.joint.axes == ("flap", (0.0, 1.0, 1.0)) and fore.joint.names == ("flap", "axis2")
    assert fore.joint.initial_angle == pytest.approx((math.radians(5.0), math.radians(-3.0)))
    assert fore.joint.initial_rate == (0.5, 0.5) and fore.joint.damping == (0.1, 0.2)
    assert sc.columns == ["elbow_flap", "elbow_axis2", "shoulder"]
    assert validate(sc.to_dict()).to_dict() == sc.to_dict()  # round trip
    # a clamp is the default and writes nothing more
    plain = chain({"name": "a", "joint": {"kind": "clamp"}})
    assert validate(plain).resolved_beams()[0].joint is None


def _set(data, path, value):
    data = copy.deepcopy(data)
    node = data
    for part in path[:-1]:
        node = node[part]
    if value is None:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return data


@pytest.mark.parametrize("path, value, message", [
    (("beams", 1, "parent"), "ghost", "beams[1].parent: no beam named 'ghost'"),
    (("beams", 1, "parent"), "fore", "beams[1].parent: a beam cannot be its own parent"),
    (("beams", 1, "azimuth"), 30.0, "beams[1].azimuth: does not apply to a beam on a parent"),
    (("beams", 1, "radius"), 0.2, "beams[1].radius: does not apply to a beam on a parent"),
    (("beams", 0, "joint", "axis"), "yaw", "beams[0].joint.axis: must be one of"),
    (("beams", 0, "joint", "axis"), [0.0, 0.0, 0.0], "beams[0].joint.axis: a zero vector has no direction"),
    (("beams", 0, "joint", "axis"), ["flap", "lag", "pitch", "flap"], "beams[0].joint.axis: at most 3 axes"),
    (("beams", 0, "joint", "axis"), ["flap", "flap"], "beams[0].joint.axis: the same named axis twice"),
    (("beams", 0, "joint", "axis"), None, "beams[0].joint.axis: required for a revolute joint"),
    (("beams", 0, "joint", "stiffness"), -1.0, "beams[0].joint.stiffness: must be >= 0"),
    (("beams", 1, "joint", "damping"), [0.1], "beams[1].joint.damping: one value per axis (2 axes, got 1"),
    (("beams", 1, "joint", "latch"), 30.0, "beams[1].joint.latch: single-axis joints only"),
    (("beams", 0, "joint", "latch"), 0.0, "beams[0].joint.latch: 0.0 deg is the initial angle"),
    (("beams", 0, "joint", "kind"), "clamp", "beams[0].joint.axis: not a key of a clamped joint"),
    (("beams", 0, "joint", "torque", "kp"), -3.0, "beams[0].joint.torque.kp: must be >= 0"),
    (("beams", 0, "joint", "hinge"), 1.0, "beams[0].joint.hinge: unknown key"),
    (("sensors", 0, "beam"), "upper", None),  # upper's joint has one axis: a plain column, accepted
])
def test_bad_joints_and_chains_are_refused_naming_the_key(path, value, message):
    data = _set(ARM, path, value)
    if message is None:
        validate(data)
        return
    with pytest.raises(ScenarioError) as exc:
        validate(data)
    assert str(exc.value).startswith(message), str(exc.value)
    assert "\n" not in str(exc.value)


def test_a_parent_listed_after_its_child_and_joint_sensors_on_clamped_beams_are_refused():
    later = chain({"name": "fore", "parent": "upper"}, {"name": "upper"})
    with pytest.raises(ScenarioError, match=r"^beams\[0\]\.parent: the parent 'upper' must be listed before its "
                                            r"child 'fore'"):
        validate(later)
    clamped = chain({"name": "a"}, sensors=[{"name": "psi", "kind": "joint_rate"}])
    with pytest.raises(ScenarioError, match=r"^sensors\[0\]\.beam: a joint_rate sensor needs a beam on a revolute "
                                            r"joint"):
        validate(clamped)
    loop = _set(_set(ARM, ("beams", 0, "radius"), None), ("beams", 0, "parent"), "fore")
    with pytest.raises(ScenarioError, match=r"^beams\[0\]\.parent: the parents of 'upper' make a loop"):
        validate(loop)
    long = chain(*([{"name": "b0"}] + [{"name": f"b{i}", "parent": f"b{i - 1}"} for i in range(1, 100)]))
    validate(long)  # 100 beams in one chain: the most a scenario holds
