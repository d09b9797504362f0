"""Output targets are checked before any computation (exit 2 naming the option) and written
atomically; a failed write is one line, exit 1, with the other results still written and no
half files (issue 15: "work thrown away", "silent data corruption")."""

import errno
import os
import time

import pytest

from hubbeam.io.scenario import ScenarioError
from hubbeam.io.targets import Target, check_outputs, write_all, write_one
from tests.cli.helpers import EXAMPLES, assert_contract, cli, hubbeam, no_temporary_files, without_notes

EXP1 = EXAMPLES / "exp1.toml"
SHORT = ["--set", "analysis.t_end=0.05", "--set", "beam.elements=2"]


@pytest.mark.parametrize("args,option,text", [
    (["-o", "{d}/nodir/x.nc"], "-o", "does not exist"),
    (["-o", "{d}"], "-o", "is a directory"),
    (["-o", "{d}/same.out", "--csv", "{d}/same.out"], "--csv", "also the target of -o"),
    (["-o", "{d}/a.nc", "--csv", "{d}/sub/../a.nc"], "--csv", "also the target of -o"),
    (["--plot", "{d}/x.txt"], "--plot", "cannot write .txt figures"),
    (["--plot", "{d}/noextension"], "--plot", "no file extension"),
    (["-o", "/dev/null"], "-o", "not a regular file"),
    (["-o", "{d}/plain/x.nc"], "-o", "is not a directory"),
    (["-o", str(EXP1)], "-o", "is the scenario file"),
    (["--csv", ""], "--csv", "empty file name"),
    (["-o", "{d}/" + "x" * 240 + ".nc"], "-o", "file name too long"),
])
def test_run_targets_are_checked_before_computing(tmp_path, args, option, text):
    (tmp_path / "sub").mkdir()
    (tmp_path / "plain").write_text("a file, not a directory")
    start = time.perf_counter()
    code, out, err = cli("run", EXP1, *SHORT, *[a.format(d=tmp_path) for a in args])
    assert code == 2, err
    assert_contract(code, out, err)
    assert without_notes(err).startswith(f"hubbeam: error: {option}") and text in err, err
    assert time.perf_counter() - start < 5  # refused up front, not after the run
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plain", "sub"]


def test_every_command_checks_its_targets_first(tmp_path):
    missing = tmp_path / "nodir"
    cases = [
        ("static", EXAMPLES / "cantilever.toml", "--plot", missing / "x.png"),
        ("campbell", EXP1, "--omega", "0:1:2", "--data", missing / "c.nc"),
        ("campbell", EXP1, "--omega", "0:1:2", "-o", tmp_path / "c.nc"),  # not a figure format
        ("sweep", EXP1, "--vary", "beam.thickness=0.001:0.002:2", "-o", missing / "s.nc"),
        ("sweep", EXP1, "--vary", "beam.thickness=0.001:0.002:2", "-o", tmp_path / "s.nc", "--plot", tmp_path / "s.nc"),
        ("applicability", "-o", EXP1),
        ("reproduce", "-o", missing / "deeper" / "report"),
    ]
    for args in cases:
        start = time.perf_counter()
        code, out, err = cli(*args)
        assert code == 2, (args, err)
        assert_contract(code, out, err)
        assert "-o" in err or "--plot" in err or "--data" in err, err
        assert time.perf_counter() - start < 5, args  # no Dask cluster, no computation
    assert sorted(os.listdir(tmp_path)) == []


def test_identify_does_not_overwrite_its_measured_file(tmp_path):
    measured = tmp_path / "m.png"  # a figure name, so that only the input check can refuse it
    measured.write_text("time,strain_P1\n" + "".join(f"{t / 10},{t * t}\n" for t in range(8)))
    code, out, err = cli("identify", EXP1, measured, "--fit", "damping.linear", "-o", measured)
    assert code == 2 and "is the measured file" in err, err


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only directories")
def test_read_only_directory(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        code, out, err = cli("run", EXP1, *SHORT, "-o", ro / "x.nc")
    finally:
        ro.chmod(0o755)
    assert code == 2 and "cannot write in directory" in err, err


def test_a_directory_that_cannot_be_written_is_refused(tmp_path, monkeypatch):
    """The check creates (and removes) a file in the target's directory: a read-only file
    system or missing permission is found before the run (simulated here, as tests may run
    as root)."""
    import tempfile

    real = tempfile.mkstemp

    def mkstemp(*args, **kwargs):
        if str(kwargs.get("dir", "")).startswith(str(tmp_path)):
            raise PermissionError(errno.EACCES, "Permission denied")
        return real(*args, **kwargs)

    monkeypatch.setattr(tempfile, "mkstemp", mkstemp)
    with pytest.raises(ScenarioError, match=r"^-o .*x.nc: cannot write in directory .*Permission denied"):
        check_outputs([Target("-o", str(tmp_path / "x.nc"))])


def test_a_failed_write_keeps_the_old_file_and_leaves_no_half_file(tmp_path):
    target = tmp_path / "r.csv"
    target.write_text("the previous result\n")

    def half_then_full_disk(path):
        with open(path, "w") as f:
            f.write("half of a new result")
        raise OSError(errno.ENOSPC, "No space left on device")

    written, errors = write_all([(Target("--csv", str(target)), half_then_full_disk),
                                 (Target("-o", str(tmp_path / "ok.txt")), lambda p: open(p, "w").write("ok"))])
    assert written == [str(tmp_path / "ok.txt")]
    assert errors == [f"--csv {target}: cannot write (No space left on device)"]
    assert target.read_text() == "the previous result\n"
    assert no_temporary_files(tmp_path)


def test_atomic_write_respects_the_umask(tmp_path):
    mask = os.umask(0o027)
    try:
        write_one(Target("-o", str(tmp_path / "x")), lambda p: open(p, "w").write("x"))
    finally:
        os.umask(mask)
    assert (tmp_path / "x").stat().st_mode & 0o777 == 0o640


def test_run_with_a_failing_target_writes_the_others(tmp_path, monkeypatch):
    """A write failure after the run (a full disk) is exit 1, one line naming the target; the
    other results are written and valid."""
    import xarray as xr

    from hubbeam.io import results

    def full_disk(ds, path):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(results, "write_csv", full_disk)
    code, out, err = cli("run", EXP1, *SHORT, "-o", tmp_path / "r.nc", "--csv", tmp_path / "r.csv", "--json")
    assert code == 1, err
    assert_contract(code, out, err)
    assert out == ""
    assert "--csv" in err and "No space left on device" in err and "written: " in err, err
    with xr.open_dataset(tmp_path / "r.nc") as ds:
        assert float(ds["time"][-1]) == 0.05 and ds.attrs["partial"] == 0
    assert not (tmp_path / "r.csv").exists()
    assert no_temporary_files(tmp_path)


def test_a_really_full_disk(tmp_path):
    """A file-size limit (as a full disk: writes fail with an OS error) in a real process:
    HDF5 never sees the failing file (NetCDF is made in memory), so no crash and no noise."""
    import resource
    import signal

    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000))

    out = hubbeam("run", EXP1, "--set", "analysis.t_end=0.5", "--set", "beam.elements=2", "--set",
                  "analysis.output_dt=0.001", "-o", tmp_path / "r.nc", "--csv", tmp_path / "r.csv",
                  preexec_fn=limit)
    assert out.returncode == 1, out.stderr
    assert_contract(out.returncode, out.stdout, out.stderr)
    assert "-o" in out.stderr and "--csv" in out.stderr and "File too large" in out.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("kind,option", [("modes", "-o"), ("modes", "--csv"), ("modes", "--plot"),
                                         ("static", "-o"), ("static", "--csv")])
def test_run_of_a_static_or_modes_scenario_refuses_time_series_targets(tmp_path, kind, option):
    code, out, err = cli("run", EXAMPLES / "cantilever.toml", "--set", f'analysis.kind="{kind}"', option,
                         tmp_path / "x.png")
    assert code == 2 and without_notes(err).startswith(f"hubbeam: error: {option}: analysis.kind = '{kind}'"), err
    assert not list(tmp_path.iterdir())


def test_run_of_a_static_scenario_draws_its_plot(tmp_path):
    code, out, err = cli("run", EXAMPLES / "cantilever.toml", "--set", 'analysis.kind="static"',
                         "--set", "beam.elements=3", "--plot", tmp_path / "s.png", "--json")
    assert code == 0, err
    assert (tmp_path / "s.png").stat().st_size > 1000


def test_a_symbolic_link_target_is_written_through(tmp_path):
    real = tmp_path / "real.csv"
    real.write_text("old")
    (tmp_path / "link.csv").symlink_to(real)
    write_one(Target("--csv", str(tmp_path / "link.csv")), lambda p: open(p, "w").write("new"))
    assert (tmp_path / "link.csv").is_symlink() and real.read_text() == "new"


def test_reproduce_moves_a_complete_report_into_place(tmp_path, monkeypatch):
    """reproduce writes into a scratch directory inside DIR and moves the files at the end;
    a failure while writing leaves DIR without half a report."""
    from pathlib import Path

    from hubbeam.reproduce import pipeline

    def fake(directory, quick=False, jobs=None, progress=None):
        directory = Path(directory)
        (directory / "tables.json").write_text("{}")
        (directory / "report.md").write_text("# report\n")
        return directory / "report.md", {}

    monkeypatch.setattr(pipeline, "reproduce", fake)
    code, out, err = cli("reproduce", "-o", tmp_path / "rep")
    assert code == 0, err
    assert sorted(p.name for p in (tmp_path / "rep").iterdir()) == ["report.md", "tables.json"]
    assert out.strip() == f"report: {tmp_path / 'rep' / 'report.md'}"

    def failing(directory, quick=False, jobs=None, progress=None):
        (Path(directory) / "tables.json").write_text("{}")
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(pipeline, "reproduce", failing)
    code, out, err = cli("reproduce", "-o", tmp_path / "rep2")
    assert code == 1 and "No space left on device" in err, err
    assert_contract(code, out, err)
    assert list((tmp_path / "rep2").iterdir()) == []
