"""The second adversarial pass of issue 15, over the commands and keys added after the first
(animate, vtk, linearize, modes --shapes/--plot, campbell --fmax/--frange, run --state and
--plot-vars, CSV tables of drives and torque laws): each test is a class of defect found
there, and fails without its fix."""

import os
import signal
import time

import numpy as np
import pytest

from tests.cli.helpers import assert_contract, cli, finish, hubbeam, no_temporary_files, popen, without_notes

TINY = """name = "tiny"
[beam]
formulation = "ancf"
elements = 2
length = 1.0
width = 0.05
thickness = 0.005
density = 2700.0
youngs_modulus = 70.0e9
poisson_ratio = 0.33
[hub]
{hub}
[analysis]
kind = "dynamic"
t_end = 0.06
dt = 0.01
output_dt = 0.02
[[sensors]]
name = "tip"
kind = "tip_deflection"
"""
TABLE_DRIVE = 'motion = "prescribed"\nradius = 0.1\n[hub.drive]\nprofile = "table"\nfile = "omega.csv"'
TABLE_TORQUE = 'motion = "free"\nradius = 0.1\ninertia = 1.0\n[hub.torque]\nlaw = "table"\nfile = "torque.csv"'
PD_TABLE = ('motion = "free"\nradius = 0.1\ninertia = 1.0\n[hub.torque]\nlaw = "pd"\nkp = 1.0\n'
            '[hub.torque.reference]\nprofile = "table"\nfile = "theta.csv"')
SPIN = 'motion = "prescribed"\nradius = 0.1\n[hub.drive]\nprofile = "spin_up"\nomega_s = 2.0\nT = 1.0'


def scenario(tmp_path, hub=SPIN):
    (tmp_path / "omega.csv").write_text("time,omega\n0,0\n0.1,0.5\n0.2,1\n0.4,1.2\n")
    (tmp_path / "theta.csv").write_text("time,theta\n0,0\n0.1,0.05\n0.2,0.1\n0.4,0.1\n")
    (tmp_path / "torque.csv").write_text("time,torque\n0,0\n0.1,1\n0.3,0.5\n")
    path = tmp_path / "s.toml"
    path.write_text(TINY.format(hub=hub))
    return path


# ------------------------------------------------------------- silent data corruption
@pytest.mark.parametrize("hub,table,option", [(TABLE_DRIVE, "omega.csv", "--csv"), (TABLE_TORQUE, "torque.csv", "-o"),
                                              (PD_TABLE, "theta.csv", "--plot")])
def test_no_target_overwrites_a_table_the_scenario_reads(tmp_path, hub, table, option):
    """`run tab.toml --csv omega.csv` replaced the drive table it had just read (exit 0)."""
    path = scenario(tmp_path, hub)
    before = (tmp_path / table).read_bytes()
    target = str(tmp_path / table) if option != "--plot" else str(tmp_path / "sub" / ".." / table)
    (tmp_path / "sub").mkdir()
    if option == "--plot":  # a figure target needs a figure extension: a link with one to the table
        os.symlink(tmp_path / table, tmp_path / "fig.png")
        target = str(tmp_path / "fig.png")
    code, out, err = cli("run", path, option, target)
    assert_contract(code, out, err)
    assert code == 2 and "is the table of hub." in err and "would be overwritten" in err, err
    assert (tmp_path / table).read_bytes() == before


def test_a_sweep_and_linearize_protect_the_tables_too(tmp_path):
    path = scenario(tmp_path, TABLE_DRIVE)
    code, out, err = cli("sweep", path, "--vary", "beam.thickness=0.004:0.005:2", "-o", tmp_path / "omega.csv")
    assert code == 2 and "table of hub.drive.file" in err, err
    code, out, err = cli("linearize", scenario(tmp_path, TABLE_TORQUE), "-o", tmp_path / "torque.csv")
    assert code == 2 and "table of hub.torque.file" in err, err


@pytest.mark.parametrize("where", ["name", "directory"])
def test_a_path_the_file_system_refuses_is_bad_input(tmp_path, where):
    """A name longer than the file system allows died as "internal error: OSError"."""
    long = "a" * 300
    target = tmp_path / (f"{long}.csv" if where == "name" else f"{long}/x.csv")
    code, out, err = cli("run", scenario(tmp_path), "--csv", target)
    assert_contract(code, out, err)
    assert code == 2 and without_notes(err).startswith("hubbeam: error: --csv"), err


# ------------------------------------------------------------- ignored input
@pytest.mark.parametrize("args,option", [
    (["run", "{static}", "--plot", "{d}/p.png", "--plot-vars", "tip"], "--plot-vars"),
    (["linearize", "{dynamic}", "--open-loop"], "--open-loop"),
    (["linearize", "{dynamic}", "--inputs", "tip_force:"], "--inputs"),
    (["campbell", "{dynamic}", "--omega", "0:1:2", "--count", "1", "--formulations", "ancf", "--fmax", "5"], "--fmax"),
    (["campbell", "{dynamic}", "--omega", "0:1:2", "--count", "1", "--formulations", "ancf", "--frange", "1:5",
      "--data", "{d}/c.nc"], "--frange"),
])
def test_an_option_that_would_do_nothing_is_refused(tmp_path, args, option):
    """--plot-vars of a static run, --open-loop of a driven hub, an empty tip_force: beam
    name, a Campbell zoom without a figure: each was accepted and ignored (exit 0)."""
    dynamic = scenario(tmp_path)
    static = tmp_path / "static.toml"
    static.write_text(dynamic.read_text().replace('kind = "dynamic"', 'kind = "static"').replace(
        SPIN, 'motion = "fixed"\nradius = 0.1'))
    code, out, err = cli(*[a.format(d=tmp_path, static=static, dynamic=dynamic) for a in args])
    assert_contract(code, out, err)
    assert code == 2 and without_notes(err).startswith(f"hubbeam: error: {option}"), err
    assert not (tmp_path / "p.png").exists() and not (tmp_path / "c.nc").exists()


# ------------------------------------------------------------- animate and vtk
@pytest.fixture(scope="module")
def state_file(tmp_path_factory):
    d = tmp_path_factory.mktemp("state")
    code, _, err = cli("run", scenario(d), "-o", d / "r.nc", "--state")
    assert code == 0, err
    return d / "r.nc"


@pytest.mark.parametrize("fps", ["1e-9", "0.001", "101"])
def test_an_fps_a_movie_cannot_hold_is_refused_up_front(state_file, tmp_path, fps):
    """--fps 1e-9 failed while writing (OverflowError, exit 1)."""
    code, out, err = cli("animate", state_file, "-o", tmp_path / "m.gif", "--fps", fps)
    assert_contract(code, out, err)
    assert code == 2 and "--fps" in err, err


def test_a_gif_that_plays_at_another_rate_says_so(state_file, tmp_path):
    """A GIF stores whole hundredths of a second: --fps 30 plays at 33.3 (rounded without a word)."""
    code, out, err = cli("animate", state_file, "-o", tmp_path / "m.gif", "--fps", "30")
    assert code == 0, err
    assert "hubbeam: note: --fps 30" in err and "33.33" in err, err
    code, out, err = cli("animate", state_file, "-o", tmp_path / "n.gif", "--fps", "20")
    assert code == 0 and err == "", err


@pytest.mark.parametrize("command,target", [("animate", "m.gif"), ("vtk", "series")])
def test_a_state_that_is_not_finite_is_refused(state_file, tmp_path, command, target):
    """NaN in a stored state: vtk wrote it into the .vtu files (exit 0), animate failed while
    writing (exit 1)."""
    import xarray as xr

    with xr.open_dataset(state_file) as ds:
        ds = ds.load()
    name = next(v for v in ds.data_vars if v.endswith("_centre_line"))
    ds[name][1] = np.nan
    bad = tmp_path / "bad.nc"
    ds.to_netcdf(bad)
    code, out, err = cli(command, bad, "-o", tmp_path / target)
    assert_contract(code, out, err)
    assert code == 2 and f"{name} is not a finite number at t = 0.02 s" in err, err
    assert not (tmp_path / target).exists()


def test_sigint_stops_animate_at_once(tmp_path):
    """animate rendered every frame inside the held-signal block of the atomic write: a
    Ctrl-C took effect only after the whole movie (minutes), with exit 130."""
    long = scenario(tmp_path).read_text().replace("t_end = 0.06", "t_end = 20.0")
    (tmp_path / "long.toml").write_text(long)
    code, _, err = cli("run", tmp_path / "long.toml", "-o", tmp_path / "r.nc", "--state")
    assert code == 0, err
    proc = popen("animate", tmp_path / "r.nc", "-o", tmp_path / "m.gif")  # 1001 frames: minutes
    for _ in range(600):  # until it renders: its temporary movie file exists
        time.sleep(0.1)
        if [p for p in tmp_path.iterdir() if ".part" in p.name] or proc.poll() is not None:
            break
    time.sleep(1.0)
    sent = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    stdout, stderr = finish(proc)
    assert proc.returncode == 130, stderr
    assert_contract(proc.returncode, stdout, stderr)
    assert "interrupted by SIGINT; nothing written" in stderr, stderr
    assert time.perf_counter() - sent < 15  # not after the remaining frames
    assert not (tmp_path / "m.gif").exists() and no_temporary_files(tmp_path)


# ------------------------------------------------------------- work thrown away, stray lines
def test_a_run_whose_variables_are_all_zero_still_gets_its_figure(tmp_path):
    """--plot failed after the run ("nothing to plot", exit 1) when every variable was zero."""
    code, out, err = cli("run", scenario(tmp_path), "--plot", tmp_path / "p.png", "--set", "hub.drive.omega_s=0.0",
                         "--set", "sensors=[{name='theta',kind='hub_angle'}]")
    assert code == 0, err
    assert (tmp_path / "p.png").stat().st_size > 0


def test_a_library_warning_is_not_a_stray_line(tmp_path):
    """scipy's RuntimeWarning (two lines, with its source line) came before the error line."""
    path = scenario(tmp_path, TABLE_DRIVE)
    (tmp_path / "omega.csv").write_text("time,omega\n0,0\n0.1,1e300\n0.2,1e308\n")
    done = hubbeam("run", path)  # a real process: pytest catches the warnings of tests run in its own
    assert_contract(done.returncode, done.stdout, done.stderr)
    assert done.returncode == 2 and without_notes(done.stderr).startswith("hubbeam: error: hub.drive.file"), done.stderr


@pytest.fixture(scope="module")
def long_state(tmp_path_factory):
    """A state of 10 001 output times (seconds to run, tens of seconds to write as .vtu files)."""
    d = tmp_path_factory.mktemp("long")
    path = scenario(d)
    path.write_text(path.read_text().replace("t_end = 0.06", "t_end = 100.0").replace("output_dt = 0.02", "output_dt = 0.01"))
    code, _, err = cli("run", path, "-o", d / "r.nc", "--state")
    assert code == 0, err
    return d / "r.nc"


def test_sigint_during_vtk_says_which_files_it_left(long_state, tmp_path):
    """vtk stopped between chunks of .vtu files said "interrupted after the results were
    written" with a third of the series there and no .pvd."""
    out = tmp_path / "series"
    proc = popen("vtk", long_state, "-o", out)
    for _ in range(600):
        time.sleep(0.1)
        if (out.is_dir() and len(list(out.iterdir())) > 10) or proc.poll() is not None:
            break
    proc.send_signal(signal.SIGINT)
    stdout, stderr = finish(proc)
    assert proc.returncode == 130, stderr
    assert_contract(proc.returncode, stdout, stderr)
    files = sorted(p.name for p in out.iterdir())
    assert "tiny.pvd" not in files and no_temporary_files(out)
    beams = [f for f in files if "_bodies_" not in f]  # each time step: the beams' file, then the bodies'
    assert len(files) - len(beams) in (len(beams), len(beams) - 1)
    steps = len(files) // 2
    assert f"after {steps} of 10001 time steps" in stderr and f"to {beams[steps - 1]} (and their bodies' files) but no " \
        "tiny.pvd" in stderr, stderr


def test_animate_and_vtk_say_a_state_is_partial(state_file, tmp_path):
    """A partial (interrupted or failed) run's state was drawn and exported without a word."""
    import xarray as xr

    with xr.open_dataset(state_file) as ds:
        ds = ds.load()
    ds.attrs.update(partial=1, time_reached=0.06, t_end=5.0, partial_reason="interrupted by SIGINT")
    ds.to_netcdf(tmp_path / "partial.nc")
    for command, target in (("animate", "m.gif"), ("vtk", "series")):
        code, out, err = cli(command, tmp_path / "partial.nc", "-o", tmp_path / target)
        assert code == 0, err
        assert "hubbeam: note:" in err and "stopped at t = 0.06 s of 5 s (interrupted by SIGINT)" in err, err


def test_fewer_modes_than_asked_are_said(tmp_path):
    """modes with analysis.count = 500 printed the 10 a one-element model has, and campbell
    --count 50 filled the rest with null, without a word."""
    path = scenario(tmp_path)
    code, out, err = cli("modes", path, "--set", "analysis.count=500", "--set", "beam.elements=1")
    assert code == 0 and "hubbeam: note: analysis.count = 500, but the model has only 10" in err, err
    code, out, err = cli("campbell", path, "--omega", "0:1:2", "--count", "50", "--formulations", "ancf",
                         "--set", "beam.elements=1")
    assert code == 0 and "hubbeam: note: --count 50, but the model has only" in err, err


def test_a_campbell_zoom_on_an_empty_range_is_said(tmp_path):
    code, out, err = cli("campbell", scenario(tmp_path), "--omega", "0:1:2", "--count", "2", "--formulations", "ancf",
                         "-o", tmp_path / "c.png", "--frange", "5000:6000")
    assert code == 0 and "hubbeam: note: --frange: no frequency lies in 5000 to 6000 Hz" in err, err


def test_vtk_on_a_full_disk_is_one_short_line(state_file, tmp_path):
    """Each of the 100 .vtu files of a chunk added its own "cannot write" to the line (6 kB)."""
    import resource

    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (2000, 2000))

    out = hubbeam("vtk", state_file, "-o", tmp_path / "series", preexec_fn=limit)
    assert out.returncode == 1, out.stderr
    assert_contract(out.returncode, out.stdout, out.stderr)
    assert "File too large" in out.stderr and "after 0 of 4 time steps" in out.stderr and len(out.stderr) < 400, out.stderr
    assert no_temporary_files(tmp_path / "series")


def test_a_link_to_nowhere_is_refused_before_computing(tmp_path):
    """-o LINK where LINK points into a directory that does not exist passed the checks and
    failed after the run (the result is written through the link)."""
    path = scenario(tmp_path)
    os.symlink(tmp_path / "nodir" / "r.nc", tmp_path / "link.nc")
    os.symlink(tmp_path / "nodir", tmp_path / "linkdir")
    code, out, err = cli("run", path, "-o", tmp_path / "link.nc")
    assert_contract(code, out, err)
    assert code == 2 and "does not exist" in err and "is a link to" in err, err
    code, out, err = cli("vtk", tmp_path / "whatever.nc", "-o", tmp_path / "linkdir")
    assert code == 2 and "is a link to" in err, err
    os.symlink(tmp_path / "real.nc", tmp_path / "good.nc")  # a link to a new file in a directory that exists: fine
    code, out, err = cli("run", path, "-o", tmp_path / "good.nc")
    assert code == 0 and (tmp_path / "real.nc").is_file() and (tmp_path / "good.nc").is_symlink(), err


def test_a_file_a_directory_target_will_hold_is_checked_first(state_file, tmp_path):
    """applicability -o DIR with DIR/applicability.png a directory failed after the whole
    map; vtk --force with DIR/NAME.pvd a directory was an internal error."""
    (tmp_path / "app" / "applicability.png").mkdir(parents=True)
    start = time.perf_counter()
    code, out, err = cli("applicability", scenario(tmp_path), "--thickness", "0.004:0.005:2", "--ratio", "0:0.2:2",
                         "-o", tmp_path / "app", "--workers", "1")
    assert_contract(code, out, err)
    assert code == 2 and "applicability.png is there already and is a directory" in err, err
    assert time.perf_counter() - start < 10 and not (tmp_path / "app" / "applicability.nc").exists()
    (tmp_path / "series" / "tiny.pvd").mkdir(parents=True)
    code, out, err = cli("vtk", state_file, "-o", tmp_path / "series", "--force")
    assert_contract(code, out, err)
    assert code == 2 and "tiny.pvd is there already and is a directory" in err, err


def test_reproduce_keeps_a_complete_report_it_cannot_move(tmp_path, monkeypatch):
    """A report file that could not be moved into DIR was an internal error, and the scratch
    directory holding the whole report was deleted."""
    import hubbeam.reproduce.pipeline as pipeline

    def fake(work, **kwargs):
        (work / "report.md").write_text("# report\n")
        (work / "fig1.png").write_bytes(b"png")
        return work / "report.md", None

    monkeypatch.setattr(pipeline, "reproduce", fake)
    (tmp_path / "fig1.png").mkdir()
    code, out, err = cli("reproduce", "-o", tmp_path, "--quick")
    assert_contract(code, out, err)
    assert code == 1 and "cannot move fig1.png into place" in err and "kept in" in err, err
    kept = [p for p in tmp_path.iterdir() if p.name.startswith(".reproduce-")]
    assert len(kept) == 1 and (kept[0] / "fig1.png").read_bytes() == b"png"


def test_a_state_too_large_for_memory_names_state(tmp_path):
    """The refusal named only analysis.output_dt, though the run fits without --state."""
    path = scenario(tmp_path)
    args = ["--set", "beam.elements=100", "--set", "analysis.t_end=100.0", "--set", "analysis.output_dt=0.001",
            "--set", "analysis.dt=0.001"]  # 10^5 records: 40 MB of sensors, 6.4 GB with the state
    code, out, err = cli("run", path, "-o", tmp_path / "r.nc", "--state", *args)
    assert_contract(code, out, err)
    assert code == 2 and without_notes(err).startswith("hubbeam: error: --state: analysis.output_dt:") and "recorded state" in err, err
