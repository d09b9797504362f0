"""CSV time series for hub drive and torque tables."""

import re

import numpy as np
import pytest

from hubbeam.io.scenario import ScenarioError
from hubbeam.io.tables import read_drive_table, read_series, read_torque_table
from hubbeam.system.laws import DriveKind, DriveProfile, TorqueKind

KEY = "hub.drive.file"


def write(tmp_path, text, name="series.csv", mode="w"):
    p = tmp_path / name
    if mode == "w":
        p.write_text(text)
    else:
        p.write_bytes(text)
    return p


def test_reads_the_requested_alternative(tmp_path):
    p = write(tmp_path, "time,omega\n0,0\n0.5,1.0\n1.0,1.5\n")
    t, cols = read_series(p, KEY, ("omega", "theta"))
    assert list(cols) == ["omega"]
    assert t.dtype == np.float64 and np.array_equal(t, [0.0, 0.5, 1.0])
    assert np.array_equal(cols["omega"], [0.0, 1.0, 1.5])
    p = write(tmp_path, "theta,time\n0,0\n0.1,1\n0.3,2\n", "angle.csv")
    t, cols = read_series(p, KEY, ("omega", "theta"))
    assert list(cols) == ["theta"] and np.array_equal(cols["theta"], [0.0, 0.1, 0.3])


def test_header_forms_comments_and_extra_columns(tmp_path):
    text = "\ufeff# measured on the rig\nTime (s), note, Torque [N m]\n\n0, a, 1.5\n 1 , b , -2e-1\n# end\n"
    p = write(tmp_path, text.encode("utf-8"), mode="b")
    t, cols = read_series(p, "hub.torque.file", ("torque",))
    assert np.array_equal(t, [0.0, 1.0]) and np.array_equal(cols["torque"], [1.5, -0.2])
    p = write(tmp_path, "time;omega\n0;1\n1;2\n", "semi.csv")
    assert np.array_equal(read_series(p, KEY, ("omega",))[1]["omega"], [1.0, 2.0])
    p = write(tmp_path, "time\tomega\n0\t1\n1\t2\n", "tab.csv")
    assert np.array_equal(read_series(p, KEY, ("omega",))[0], [0.0, 1.0])


def test_relative_path_against_base_dir(tmp_path):
    (tmp_path / "data").mkdir()
    write(tmp_path / "data", "time,torque\n0,1\n2,3\n", "torque.csv")
    law = read_torque_table("data/torque.csv", "hub.torque.file", base_dir=tmp_path)
    assert law.torque_kind is TorqueKind.TABLE
    assert law(1.0, 0.0, 0.0) == (2.0, 0.0, 0.0)


def test_drive_tables(tmp_path):
    spin = DriveProfile("spin_up", 4.0, 15.0)
    rows = "\n".join(f"{float(t)!r},{spin(t)[1]!r}" for t in np.arange(0.0, 15.0 + 1e-9, 0.1))
    d = read_drive_table(write(tmp_path, "time,omega\n" + rows + "\n"), KEY)
    assert d.drive_kind is DriveKind.TABLE and d.quantity == "omega"
    assert d(7.0) == pytest.approx(spin(7.0), rel=2e-3, abs=1e-3)
    d = read_drive_table(write(tmp_path, "time,theta\n0,0\n1,0.5\n2,2\n3,4\n", "th.csv"), KEY)
    assert d.quantity == "theta" and d(2.0)[0] == pytest.approx(2.0)


def _error(tmp_path, text, columns=("omega", "theta"), mode="w", **kw):
    p = write(tmp_path, text, mode=mode) if text is not None else tmp_path / "missing.csv"
    with pytest.raises(ScenarioError) as info:
        read_series(p, KEY, columns, **kw)
    msg = str(info.value)
    assert "\n" not in msg
    assert msg.startswith(f"{KEY}: {p}: "), msg
    return msg.split(f"{p}: ", 1)[1]


@pytest.mark.parametrize("text, kw, match", [
    (None, {}, "file not found"),
    (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR", {"mode": "b"}, "not a CSV text file"),
    ("", {}, "empty file"),
    ("# only a comment\n\n", {}, "empty file"),
    ("t,omega\n0,1\n1,2\n", {}, "no 'time' column"),
    ("time,speed\n0,1\n1,2\n", {}, "no 'omega' or 'theta' column"),
    ("time,omega,theta\n0,1,0\n1,2,1\n", {}, "not both"),
    ("time,omega,omega\n0,1,0\n1,2,1\n", {}, "appears twice"),
    ("time,omega\n0,1\n1,fast\n2,3\n", {}, r"row 2 \(line 3\), column 'omega': 'fast' is not a number"),
    ("time,omega\n0,1\n\n1,\n", {}, r"row 2 \(line 4\), column 'omega': '' is not a number"),
    ("time,omega\n0,1\n1,2,3\n", {}, r"row 2 \(line 3\) has 3 cells, the header has 2"),
    ("time,omega\n0,1\n1,nan\n", {}, r"row 2 \(line 3\), column 'omega': 'nan' is not finite"),
    ("time,omega\n0,1\ninf,2\n", {}, "not finite"),
    ("time,omega\n0,1\n2,2\n1,3\n", {}, r"row 3 \(line 4\): times are not increasing"),
    ("time,omega\n0,1\n1,2\n1,3\n", {}, "a duplicate time"),
    ("time,omega\n0,1\n", {}, "at least 2 rows, found 1"),
    ("time,omega\n0,1\n1,2\n", {"min_rows": 3}, "at least 3 rows, found 2"),
    ("time,omega\n0.5,1\n1,2\n", {"start_at_zero": True}, "first time must be 0"),
    ("time,omega\n" + "0,1\n" * 100, {"max_bytes": 100}, "larger than the"),
])
def test_errors_are_one_line_with_key_and_path(tmp_path, text, kw, match):
    columns = kw.pop("columns", ("omega", "theta"))
    msg = _error(tmp_path, text, columns, **kw)
    assert re.search(match, msg), msg


def test_directory_and_torque_column(tmp_path):
    with pytest.raises(ScenarioError, match="not a file"):
        read_series(tmp_path, KEY, ("omega",))
    p = write(tmp_path, "time,omega\n0,1\n1,2\n")
    with pytest.raises(ScenarioError, match=r"hub.torque.file: .*no 'torque' column"):
        read_torque_table(p, "hub.torque.file")


def test_drive_table_errors(tmp_path):
    with pytest.raises(ScenarioError, match="at least 3 rows"):
        read_drive_table(write(tmp_path, "time,omega\n0,1\n1,2\n"), KEY)
    with pytest.raises(ScenarioError, match="first time must be 0"):
        read_drive_table(write(tmp_path, "time,omega\n1,1\n2,2\n3,3\n"), KEY)
    with pytest.raises(ScenarioError, match="first theta must be 0"):
        read_drive_table(write(tmp_path, "time,theta\n0,1\n1,2\n2,3\n"), KEY)


def test_drive_table_options_name_their_key(tmp_path):
    theta = write(tmp_path, "time,theta\n0,0\n1,0.5\n2,2\n3,4\n", "th.csv")
    with pytest.raises(ScenarioError, match=r"^hub.drive.interpolation: 'linear' is for an omega table, and .*th.csv"):
        read_drive_table(theta, "hub.drive.file", interpolation="linear")
    short = write(tmp_path, "time,omega\n0,0\n1,1\n2,2\n3,3\n", "short.csv")
    with pytest.raises(ScenarioError, match=r"^hub.torque.reference.smoothing: .*short.csv has 4 rows; smoothing needs at "
                                            r"least 5"):
        read_drive_table(short, "hub.torque.reference.file", smoothing=2.0)
    d = read_drive_table(short, "hub.drive.file", interpolation="linear")
    assert d.interpolation == "linear" and d(1.5)[1] == pytest.approx(1.5)
