"""Joints through the command line: a latch's record (--json "latches", the dataset's attributes,
the line on stderr), linearize's joint motor inputs, the hinge markers of vtk."""

from __future__ import annotations

import json

import pytest

from tests.cli.helpers import EXAMPLES, assert_contract, cli

PANEL = """
name = "hinge"
[[beams]]
name = "panel"
formulation = "ffr"
modes = 1
elements = 4
length = 1.0
width = 0.3
thickness = 0.01
density = 2700.0
youngs_modulus = 70.0e9
radius = 0.2
[beams.joint]
kind = "revolute"
axis = "lag"
stiffness = 4.0
neutral = 120.0
latch = 60.0
[hub]
motion = "free"
inertia = 2.0
[environment]
gravity = [0.0, 0.0, 0.0]
[analysis]
t_end = 1.5
dt = 0.002
output_dt = 0.01
[[sensors]]
name = "psi"
kind = "joint_angle"
[[sensors]]
name = "torque"
kind = "joint_torque"
"""


def test_a_latch_is_reported_in_the_json_the_dataset_and_on_stderr(tmp_path):
    import xarray as xr

    scenario = tmp_path / "hinge.toml"
    scenario.write_text(PANEL)
    code, out, err = cli("run", scenario, "-o", tmp_path / "r.nc", "--json")
    assert_contract(code, out, err, json_out=True)
    (latch,) = json.loads(out)["latches"]
    assert latch["beam"] == "panel" and latch["angle_deg"] == pytest.approx(60.0, abs=0.5)
    assert latch["energy"] > 0.0 and latch["impulse"] != 0.0
    assert "latch: beam 'panel' locked at t = " in err
    with xr.open_dataset(tmp_path / "r.nc") as ds:
        assert ds.attrs["latch_panel_time"] == latch["time"]
        assert ds.attrs["latch_panel_impulse"] == latch["impulse"] and ds.attrs["latch_panel_energy"] == latch["energy"]
        after = ds.time > latch["time"]
        assert float(abs(ds.psi[after] - ds.psi[after][0]).max()) == 0.0  # locked
        assert float(abs(ds.torque[after]).max()) > 4.0 * 1.0  # the lock's reaction rings above the spring's torque


@pytest.mark.slow  # the only test of its model (a two-motor arm): compiling it is most of a minute
def test_linearize_takes_each_joint_motor_as_an_input():
    code, out, err = cli("linearize", EXAMPLES / "arm2.toml", "--json")
    assert_contract(code, out, err, json_out=True)
    d = json.loads(out)
    assert d["inputs"] == ["tip_force_x_upper", "tip_force_y_upper", "tip_force_z_upper", "joint_torque_upper",
                           "joint_torque_fore"]
    code, out, err = cli("linearize", EXAMPLES / "arm2.toml", "--json", "--open-loop", "--inputs",
                         "joint_torque:fore")
    assert_contract(code, out, err, json_out=True)
    assert json.loads(out)["inputs"] == ["joint_torque_fore"]
    code, out, err = cli("linearize", EXAMPLES / "arm2.toml", "--inputs", "joint_torque:nobody")
    assert code == 2 and "inputs: 'joint_torque:nobody': needs a beam on a single-axis revolute joint" in err


def test_vtk_draws_each_hinge_as_a_vertex(tmp_path):
    import meshio

    scenario = tmp_path / "hinge.toml"
    scenario.write_text(PANEL.replace("t_end = 1.5", "t_end = 0.02"))
    assert cli("run", scenario, "-o", tmp_path / "r.nc", "--state")[0] == 0
    code, out, err = cli("vtk", tmp_path / "r.nc", "-o", tmp_path / "vtk")
    assert_contract(code, out, err)
    mesh = meshio.read(tmp_path / "vtk" / "hinge_00000.vtu")  # at t = 0, before the free hub turns
    (vertices,) = [c.data for c in mesh.cells if c.type == "vertex"]
    assert vertices.shape == (1, 1)
    root = mesh.points[vertices[0, 0]]
    assert root == pytest.approx([0.2, 0.0, 0.0], abs=1e-9)  # the hinge at the panel's root, 0.2 m out
