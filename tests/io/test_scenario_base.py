"""The ``[base]`` table's bad input through the command line: exit 2 and one line that names
the key (and, for a table, the file and the row), before anything is computed."""

from __future__ import annotations

import pytest

from tests.cli.helpers import assert_contract, cli

RIGID = """name = "rigid"
[base]
motion = "free"
mass = 100.0
inertia = [2.0, 3.0, 4.0]
[environment]
gravity = [0.0, 0.0, 0.0]
[analysis]
t_end = 0.01
dt = 0.01
"""

STRIP = """name = "strip"
[beam]
formulation = "ancf"
elements = 2
length = 1.0
width = 0.05
thickness = 0.004
density = 2700.0
youngs_modulus = 70.0e9
[analysis]
t_end = 0.01
dt = 0.01
"""

HEADER = "time,x,y,z,rx,ry,rz\n"
TABLES = {
    "three_rows.csv": HEADER + "0,0,0,0,0,0,0\n1,0,1,0,0,0,0\n2,0,2,0,0,0,0\n",
    "repeated.csv": HEADER + "0,0,0,0,0,0,0\n1,0,1,0,0,0,0\n1,0,2,0,0,0,0\n3,0,3,0,0,0,0\n",
    "unsorted.csv": HEADER + "0,0,0,0,0,0,0\n2,0,1,0,0,0,0\n1,0,2,0,0,0,0\n3,0,3,0,0,0,0\n",
    # 3.1 to -3.1 about z: the same attitudes as 3.1 to 3.18, written as a jump of 6.2 rad
    "jump.csv": HEADER + "0,0,0,0,0,0,3.0\n1,0,1,0,0,0,3.1\n2,0,2,0,0,0,-3.1\n3,0,3,0,0,0,-3.0\n",
    "late.csv": HEADER + "0.5,0,0,0,0,0,0\n1,0,1,0,0,0,0\n2,0,2,0,0,0,0\n3,0,3,0,0,0,0\n",
    "no_rz.csv": "time,x,y,z,rx,ry\n0,0,0,0,0,0\n1,0,1,0,0,0\n2,0,2,0,0,0\n3,0,3,0,0,0\n",
    "good.csv": HEADER + "0,0,0,0,0,0,0\n1,0,1,0,0,0,0\n2,0,2,0,0,0,0\n3,0,3,0,0,0,0\n",
}

#: (scenario, overrides, what the one line must contain: the key first, then the reason's words)
CASES = {
    # the base body
    "inertia above the triangle": (RIGID, ["base.inertia=[1, 1, 3]"], ["base.inertia: not a rigid body's",
                                                                         "3 exceeds the sum of the other two, 1 + 1"]),
    "inertia not positive": (RIGID, ["base.inertia=[1, -1, 1]"], ["base.inertia: not positive definite"]),
    "inertia matrix not positive": (RIGID, ["base.inertia=[[1, 2, 0], [2, 1, 0], [0, 0, 1]]"],
                                    ["base.inertia: not positive definite", "-1, 1, 3"]),
    "inertia not symmetric": (RIGID, ["base.inertia=[[1, 0.5, 0], [0.4, 1, 0], [0, 0, 1]]"],
                              ["base.inertia: the matrix is not symmetric"]),
    "inertia of two rows": (RIGID, ["base.inertia=[[1, 0, 0], [0, 1, 0]]"], ["base.inertia: three principal moments"]),
    "zero mass": (RIGID, ["base.mass=0"], ["base.mass: must be > 0"]),
    "negative mass": (RIGID, ["base.mass=-3"], ["base.mass: must be > 0"]),
    "no mass": (RIGID, ["base={motion='free', inertia=[1, 1, 1]}"], ["base.mass: required"]),
    "no inertia": (RIGID, ["base={motion='free', mass=1.0}"], ["base.inertia: required"]),
    # the hub's inertia on a free base
    "inertia of a hub fixed to a free base": (RIGID, ["hub.inertia=2"], ["hub.inertia: a hub fixed to a free base"]),
    "no inertia of a free hub on a free base": (RIGID, ["hub.motion='free'"],
                                                ["hub.inertia: required for a free hub on a free base"]),
    "no inertia of a prescribed hub on a free base": (
        RIGID, ["hub.motion='prescribed'", "hub.drive={profile='constant', omega_s=1.0}"],
        ["hub.inertia: required for a prescribed hub on a free base"]),
    # keys of another motion
    "mass of a fixed base": (STRIP, ["base={motion='fixed', mass=1.0}"], ["base.mass: only for base.motion = 'free'"]),
    "inertia of a table base": (STRIP, ["base={motion='table', file='good.csv', inertia=[1, 1, 1]}"],
                                ["base.inertia: only for base.motion = 'free'"]),
    "centre of mass of a fixed base": (STRIP, ["base={centre_of_mass=[1, 0, 0]}"],
                                       ["base.centre_of_mass: only for base.motion = 'free'"]),
    "torque on a fixed base": (STRIP, ["base={torque={law='pd', kp=[1, 1, 1], kd=[1, 1, 1]}}"],
                               ["base.torque: only for base.motion = 'free'"]),
    "file of a free base": (RIGID, ["base.file='good.csv'"], ["base.file: only for base.motion = 'table'"]),
    "file of a fixed base": (STRIP, ["base={file='good.csv'}"], ["base.file: only for base.motion = 'table'"]),
    "velocity of a fixed base": (STRIP, ["base={initial={velocity=[1, 0, 0]}}"],
                                 ["base.initial.velocity: a fixed base does not move"]),
    "initial state of a table base": (STRIP, ["base={motion='table', file='good.csv', initial={rotation=[0, 0, 1]}}"],
                                      ["base.initial.rotation: a table base starts where its table does"]),
    "table without a file": (STRIP, ["base={motion='table'}"], ["base.file: required for base.motion = 'table'"]),
    "base_torque without a law": (RIGID, ["sensors=[{name='tau', kind='base_torque'}]"],
                                  ["sensors[0].kind: base_torque needs an attitude law"]),
    "beam sensor without a beam": (RIGID, ["sensors=[{name='tip', kind='tip_deflection'}]"],
                                   ["sensors[0].kind: a tip_deflection sensor needs a beam"]),
    "no beam on a fixed base": (RIGID, ["base={motion='fixed'}"], ["beam: required key is missing"]),
    # the attitude law
    "slew about no axis": (RIGID, ["base.torque={law='pd', kp=[1, 1, 1], kd=[1, 1, 1], slew={axis=[0, 0, 0], "
                                   "angle=1.0, T=1.0}}"], ["base.torque.slew.axis: a zero vector"]),
    "target and slew": (RIGID, ["base.torque={law='pd', kp=[1, 1, 1], kd=[1, 1, 1], target=[0, 0, 0], "
                                "slew={axis=[0, 0, 1], angle=1.0, T=1.0}}"], ["base.torque.slew: give a fixed target"]),
    "negative gain": (RIGID, ["base.torque={law='pd', kp=[1, -1, 1], kd=[1, 1, 1]}"], ["base.torque.kp[1]: must be >= 0"]),
    "no gains": (RIGID, ["base.torque={law='pd', kp=[0, 0, 0], kd=[0, 0, 0]}"], ["base.torque.kp: kp and kd are all 0"]),
    # the hub's place
    "orientation of two numbers": (STRIP, ["hub.orientation=[0, 5]"], ["hub.orientation: must have exactly 3 entries"]),
}

#: (table file, what the one line must contain)
TABLE_CASES = {
    "fewer than 4 rows": ("three_rows.csv", ["base.file: ", "three_rows.csv: the table needs at least 4 rows, found 3"]),
    "repeated time": ("repeated.csv", ["base.file: ", "repeated.csv: row 3 (line 4): a duplicate time (1.0 after 1.0)"]),
    "unsorted times": ("unsorted.csv", ["base.file: ", "row 3 (line 4): times are not increasing (1.0 after 2.0)"]),
    "a jump of the rotation vector": ("jump.csv", ["base.file: ", "jump.csv: row 3: the rotation vector jumps by 6.2 rad"]),
    "a late start": ("late.csv", ["base.file: ", "the first time must be 0 s (found 0.5)"]),
    "a missing column": ("no_rz.csv", ["base.file: ", "no 'rz' column"]),
    "no such file": ("missing.csv", ["base.file: no such file"]),
}


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for name, text in TABLES.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    (tmp_path / "rigid.toml").write_text(RIGID, encoding="utf-8")
    (tmp_path / "strip.toml").write_text(STRIP, encoding="utf-8")
    return tmp_path


def refused(folder, scenario: str, overrides: list[str]) -> str:
    """The one line of ``hubbeam run`` refusing the scenario with exit 2."""
    path = folder / ("rigid.toml" if scenario is RIGID else "strip.toml")
    args = ["run", path, "--json"]
    for override in overrides:
        args += ["--set", override]
    code, out, err = cli(*args)
    assert_contract(code, out, err)
    assert code == 2 and out == "", err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    return lines[0].removeprefix("hubbeam: error: ")


@pytest.mark.parametrize("case", CASES)
def test_bad_base_input_is_refused_naming_the_key(folder, case):
    scenario, overrides, expected = CASES[case]
    line = refused(folder, scenario, overrides)
    assert line.startswith(expected[0]), line
    for words in expected[1:]:
        assert words in line, line


@pytest.mark.parametrize("case", TABLE_CASES)
def test_a_bad_pose_table_is_refused_naming_the_key_file_and_row(folder, case):
    table, expected = TABLE_CASES[case]
    line = refused(folder, STRIP, [f"base={{motion='table', file='{table}'}}"])
    assert line.startswith(expected[0]), line
    for words in expected[1:]:
        assert words in line, line


def test_the_good_table_and_the_rigid_body_alone_run(folder):
    """The same files with the good table, and the rigid body without a beam, exit 0."""
    for path, overrides in ((folder / "strip.toml", ["base={motion='table', file='good.csv'}"]),
                            (folder / "rigid.toml", [])):
        args = ["run", path, "--json"] + [a for o in overrides for a in ("--set", o)]
        code, out, err = cli(*args)
        assert code == 0, err
