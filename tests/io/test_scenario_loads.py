"""The ``[loads]`` table's span loads and tip load tables: what validates, and one line naming
the key (and the file's row) for what does not."""

import subprocess
import sys

import numpy as np
import pytest

from hubbeam.io.scenario import ScenarioError, validate
from hubbeam.io.tables import read_span_table

BEAM = {"formulation": "ancf", "elements": 3, "length": 1.0, "width": 0.05, "thickness": 0.004, "density": 2700.0,
        "youngs_modulus": 70.0e9}


def scenario(**loads) -> dict:
    return {"name": "loads", "beams": [dict(BEAM, name="blade1"), dict(BEAM, name="blade2", length=0.8)],
            "hub": {"motion": "fixed"}, "analysis": {"kind": "static"}, "loads": loads}


@pytest.fixture
def tables(tmp_path):
    files = {"good.csv": "x,fx,fy,fz\n0,1,2,3\n1.0,4,5,6\n",
             "timed.csv": "time,x,fx,fy,fz,mx,my,mz\n0,0,1,0,0,0,0,0\n0,0.8,1,0,0,0,0,0\n"
                          "1,0,2,0,0,0,0,1\n1,0.8,3,0,0,0,0,1\n",
             "no_fz.csv": "x,fx,fy\n0,1,2\n1,1,2\n",
             "unsorted.csv": "x,fx,fy,fz\n0,1,2,3\n0.7,1,2,3\n0.4,1,2,3\n",
             "long.csv": "x,fx,fy,fz\n0,1,2,3\n1.2,1,2,3\n",
             "stations.csv": "time,x,fx,fy,fz\n0,0,1,0,0\n0,0.5,1,0,0\n1,0,1,0,0\n1,0.6,1,0,0\n",
             "back.csv": "time,x,fx,fy,fz\n1,0,1,0,0\n1,0.5,1,0,0\n0,0,1,0,0\n0,0.5,1,0,0\n",
             "two_moments.csv": "x,fx,fy,fz,mx,my\n0,1,2,3,0,0\n1,1,2,3,0,0\n",
             "tip.csv": "time,fx,fy,fz\n0,1,2,3\n0.5,1,2,3\n",
             "tip_bad.csv": "time,fx,fy,fz\n0,1,2,3\n0.5,1,x,3\n"}
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    return tmp_path


def test_span_loads_and_tip_tables_validate(tables):
    s = validate(scenario(span=[{"force": [0.0, -1.0, 0.0]}, {"file": "timed.csv", "beam": "blade2", "axes": "section",
                                                              "name": "gust"}],
                          tip_force_file="tip.csv"), tables)
    assert s.loads.span_names == ["span1", "gust"]
    assert s.loads.span[1].file == str(tables / "timed.csv")
    assert validate(s.to_dict()) == s  # what results store gives the scenario back


def test_a_timed_span_table_reads_as_blocks_of_stations(tables):
    x, times, values = read_span_table(tables / "timed.csv", "loads.span[0].file", 0.8)
    assert np.array_equal(x, [0.0, 0.8]) and np.array_equal(times, [0.0, 1.0])
    assert values.shape == (2, 2, 6) and values[1, 1, 0] == 3.0 and values[1, 0, 5] == 1.0


@pytest.mark.parametrize("loads,message", [
    ({"span": [{"file": "no_fz.csv"}]}, r"^loads\.span\[0\]\.file: .*no_fz\.csv: no 'fz' column in the header"),
    ({"span": [{"file": "unsorted.csv"}]},
     r"^loads\.span\[0\]\.file: .*: row 3 \(line 4\): x values are not increasing \(0\.4 after 0\.7\)$"),
    ({"span": [{"file": "long.csv"}]},
     r"^loads\.span\[0\]\.file: .*: row 2 \(line 3\): x = 1\.2 m is outside the beam's span \[0, 1\] m$"),
    ({"span": [{"file": "good.csv", "beam": "blade2"}]}, r"^loads\.span\[0\]\.file: .*row 2 \(line 3\): x = 1\.0 m is "
                                                         r"outside the beam's span \[0, 0\.8\] m$"),
    ({"span": [{"file": "stations.csv"}]},
     r"^loads\.span\[0\]\.file: .*row 3 \(line 4\): every time needs the stations \(x values\) of the first time"),
    ({"span": [{"file": "back.csv"}]}, r"^loads\.span\[0\]\.file: .*row 3 \(line 4\): times are not increasing"),
    ({"span": [{"file": "two_moments.csv"}]}, r"^loads\.span\[0\]\.file: .*give the moment columns mx, my and mz "
                                              r"together \(missing mz\)$"),
    ({"span": [{"force": [1.0, 0.0, 0.0]}, {"force": [0.0, 1.0, 0.0], "beam": "blade3"}]},
     r"^loads\.span\[1\]\.beam: no beam named 'blade3' \(beams: blade1, blade2\)$"),
    ({"span": [{"force": [1.0, 0.0, 0.0], "file": "good.csv"}]},
     r"^loads\.span\[0\]\.force: give either a file or force and moment, not both$"),
    ({"span": [{"axes": "section"}]}, r"^loads\.span\[0\]\.force: give force \(N/m\) and/or moment \(N m/m\), or a file$"),
    ({"span": [{"force": [1.0, 0.0]}]}, r"^loads\.span\[0\]\.force: "),
    ({"span": [{"force": [1.0, 0.0, 0.0], "axes": "body"}]}, r"^loads\.span\[0\]\.axes: "),
    ({"span": [{"file": "nowhere.csv"}]}, r"^loads\.span\[0\]\.file: no such file .*nowhere\.csv$"),
    ({"span": [{"force": [1.0, 0.0, 0.0], "name": "a"}, {"moment": [1.0, 0.0, 0.0], "name": "a"}]},
     r"^loads\.span\[1\]\.name: 'a' names two span loads$"),
    ({"tip_force": [1.0, 0.0, 0.0], "tip_force_file": "tip.csv"},
     r"^loads\.tip_force_file: give either tip_force or tip_force_file, not both$"),
    ({"tip_moment_file": "tip.csv"}, r"^loads\.tip_moment_file: .*tip\.csv: no 'mx' column in the header"),
    ({"tip_force_file": "tip_bad.csv"}, r"^loads\.tip_force_file: .*row 2 \(line 3\), column 'fy': 'x' is not a number$"),
])
def test_bad_loads_are_one_line_naming_the_key(tables, loads, message):
    with pytest.raises(ScenarioError, match=message) as info:
        validate(scenario(**loads), tables)
    assert "\n" not in str(info.value)


def test_the_command_line_exits_2_on_a_bad_span_table(tables):
    (tables / "s.toml").write_text('name = "s"\n[beam]\nformulation = "ancf"\nelements = 2\nlength = 1.0\n'
                                   'width = 0.05\nthickness = 0.004\ndensity = 2700.0\nyoungs_modulus = 7e10\n'
                                   '[analysis]\nkind = "static"\n[[loads.span]]\nfile = "unsorted.csv"\n')
    out = subprocess.run([sys.executable, "-m", "hubbeam.cli", "static", str(tables / "s.toml")], capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 2
    assert out.stderr.strip().count("\n") == 0 and "loads.span[0].file" in out.stderr and "row 3" in out.stderr
