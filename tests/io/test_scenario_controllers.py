"""The [[controllers]] tables (hubbeam.io.scenario.controllers): every bad table is exit 2 and one
line naming its key, before anything is computed."""

import json

import numpy as np
import pytest

from tests.cli.helpers import cli


def write(tmp_path, controller, hub_motion="free"):
    """spacecraft.toml (free hub) or cantilever.toml (fixed hub) with the sensors c_theta
    (hub_angle), c_omega (hub_angular_velocity) and c_torque (applied_torque) and one controller table."""
    from hubbeam.io.scenario import example_text

    text = example_text("spacecraft" if hub_motion == "free" else "cantilever")
    sensors = [("c_theta", "hub_angle"), ("c_omega", "hub_angular_velocity")]
    sensors += [("c_torque", "applied_torque")] if hub_motion == "free" else []
    text += "".join(f'\n[[sensors]]\nname = "{n}"\nkind = "{k}"\n' for n, k in sensors)
    text += "\n[[controllers]]\n" + "".join(f"{key} = {json.dumps(value)}\n" for key, value in controller.items())
    path = tmp_path / "sc.toml"
    path.write_text(text)
    return path


def gain(tmp_path, D=((-1.0,),), name="k.npz", **arrays):
    D = np.asarray(D, dtype=float)
    p, m = D.shape
    data = {"A": np.zeros((0, 0)), "B": np.zeros((0, m)), "C": np.zeros((p, 0)), "D": D}
    data.update(arrays)
    np.savez(tmp_path / name, **data)
    return str(tmp_path / name)


def refused(path) -> str:
    code, out, err = cli("run", path)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, (code, err)
    return lines[0]


@pytest.mark.parametrize("case, key, words", [
    ("missing file", "controllers[0].file", "no such file"),
    ("wrong shape", "controllers[0].file", "D: 1 x 1"),
    ("wrong A", "controllers[0].file", "B: 1 x 1"),
    ("no array C", "controllers[0].file", "no array C"),
    ("unknown sensor", "controllers[0].inputs[0]", "not a sensor column"),
    ("acceleration rate", "controllers[0].inputs[0]", "depends on the accelerations"),
    ("unsupported sensor", "controllers[0].inputs[0]", "not supported as a controller input"),
    ("unknown output", "controllers[0].outputs[0]", "not a supported output"),
    ("held hub", "controllers[0].outputs[0]", "needs a free hub"),
    ("fixed base", "controllers[0].outputs[0]", "base_torque_y needs a free base"),
    ("clamped beam", "controllers[0].outputs[0]", "is not on a single-axis joint"),
    ("not a matrix file", "controllers[0].file", ".npz or NetCDF"),
    ("non-finite gain", "controllers[0].file", "D[0, 0] is nan"),
    ("infinite state matrix", "controllers[0].file", "A[0, 0] is inf"),
])
def test_a_bad_controller_table_is_exit_2_naming_its_key(tmp_path, case, key, words):
    table = {"file": gain(tmp_path), "inputs": ["c_omega"], "outputs": ["hub_torque"]}
    motion = "free"
    if case == "missing file":
        table["file"] = str(tmp_path / "none.npz")
    elif case == "wrong shape":
        table["file"] = gain(tmp_path, D=((-1.0, 2.0),))
    elif case == "wrong A":
        table["file"] = gain(tmp_path, A=np.zeros((1, 1)))
    elif case == "no array C":
        np.savez(tmp_path / "noc.npz", A=np.zeros((0, 0)), B=np.zeros((0, 1)), D=np.ones((1, 1)))
        table["file"] = str(tmp_path / "noc.npz")
    elif case == "unknown sensor":
        table["inputs"] = ["nope"]
    elif case == "acceleration rate":
        table["inputs"] = ["c_omega_rate"]
    elif case == "unsupported sensor":
        table["inputs"] = ["c_torque"]
    elif case == "unknown output":
        table["outputs"] = ["thrust"]
    elif case == "held hub":
        motion = "fixed"
        table["inputs"] = ["c_theta"]
    elif case == "fixed base":
        table["outputs"] = ["base_torque_y"]
    elif case == "clamped beam":
        table["outputs"] = ["joint_torque_panel_b"]
    elif case == "non-finite gain":
        table["file"] = gain(tmp_path, D=((float("nan"),),))
    elif case == "infinite state matrix":
        table["file"] = gain(tmp_path, A=np.full((1, 1), np.inf), B=np.ones((1, 1)), C=np.ones((1, 1)))
    elif case == "not a matrix file":
        (tmp_path / "k.csv").write_text("a,b\n1,2\n")
        table["file"] = str(tmp_path / "k.csv")
    line = refused(write(tmp_path, table, hub_motion=motion))
    assert line.startswith(f"hubbeam: error: {key}: ") and words in line, line


def test_a_rate_of_the_hub_angle_is_an_input(tmp_path):
    from hubbeam.io.scenario import load_scenario

    path = write(tmp_path, {"file": gain(tmp_path), "inputs": ["c_theta_rate"], "outputs": ["hub_torque"]})
    scenario = load_scenario(str(path))
    assert scenario.controllers[0].inputs == ["c_theta_rate"]


def test_no_output_overwrites_a_controllers_file(tmp_path):
    """A controller's matrices are an input of the scenario, as its CSV tables: `linearize -o k.npz`
    onto the file the controller reads is exit 2, and the file is kept."""
    path = write(tmp_path, {"file": gain(tmp_path), "inputs": ["c_omega"], "outputs": ["hub_torque"]})
    before = (tmp_path / "k.npz").read_bytes()
    code, out, err = cli("linearize", path, "-o", tmp_path / "k.npz")
    assert code == 2 and "matrices of controllers[0].file" in err and len(err.strip().splitlines()) == 1, err
    assert (tmp_path / "k.npz").read_bytes() == before


def with_sensor(tmp_path, kind, column, beam=None):
    """spacecraft.toml (fixed base) with one more sensor ``s`` of ``kind`` and a controller reading ``column``."""
    path = write(tmp_path, {"file": gain(tmp_path), "inputs": [column], "outputs": ["hub_torque"]})
    extra = f'\n[[sensors]]\nname = "s"\nkind = "{kind}"\n' + (f'beam = "{beam}"\n' if beam else "")
    text = path.read_text()
    at = text.index("\n[[controllers]]")
    path.write_text(text[:at] + extra + text[at:])
    return path


@pytest.mark.parametrize("kind, column", [("base_position", "s_x"), ("base_rotation", "s_z_rate")])
def test_a_base_input_on_a_fixed_base_is_exit_2(tmp_path, kind, column):
    line = refused(with_sensor(tmp_path, kind, column))
    assert line.startswith("hubbeam: error: controllers[0].inputs[0]: ") and "needs a base that moves" in line, line


def test_an_unsupported_sensor_names_every_accepted_input(tmp_path):
    # the refusal of a sensor that is not an input (the centre of mass: the whole system's mass
    # distribution) lists exactly what the inputs accept
    from hubbeam.system.controller_inputs import SENSOR_INPUTS

    line = refused(with_sensor(tmp_path, "centre_of_mass", "s_x"))
    assert "'s_x': a centre_of_mass sensor is not supported as a controller input" in line, line
    listed = line.split("(supported: ")[1].rstrip(")").split(", ")
    assert sorted(listed) == sorted(k + ("_rate" if r else "") for k, r in SENSOR_INPUTS)
    assert {"tip_deflection", "tip_deflection_rate", "base_rotation_rate", "base_position"} <= set(listed)


@pytest.mark.parametrize("column", ["s_tangential", "s_radial_rate"])
def test_a_tip_deflection_and_its_rate_are_inputs(tmp_path, column):
    from hubbeam.io.scenario import load_scenario

    scenario = load_scenario(str(with_sensor(tmp_path, "tip_deflection", column, beam="panel_b")))
    assert scenario.controllers[0].inputs == [column]
