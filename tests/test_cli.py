"""The command line: exit codes, JSON on stdout, one-line errors, never a traceback."""

import json
import subprocess
import sys

import numpy as np
import pytest


def hubbeam(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "hubbeam.cli", *args], capture_output=True, text=True, cwd=cwd,
                          timeout=600)


@pytest.fixture(scope="module")
def cantilever(tmp_path_factory):
    path = tmp_path_factory.mktemp("cli") / "cantilever.toml"
    out = hubbeam("example", "cantilever")
    assert out.returncode == 0
    path.write_text(out.stdout)
    return path


def test_static_json(cantilever, tmp_path):
    out = hubbeam("static", str(cantilever), "--json", "--plot", str(tmp_path / "c.png"))
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert set(d["tip_displacement"]) == {"radial", "vertical", "tangential"}
    assert d["tip_displacement"]["vertical"] < -0.3  # gravity on the weak axis: a large droop
    assert len(d["tip_position"]) == 3
    assert (tmp_path / "c.png").stat().st_size > 10000


def test_modes_json_and_set(cantilever):
    out = hubbeam("modes", str(cantilever), "--json", "--set", "environment.gravity=[0.0, 0.0, 0.0]")
    assert out.returncode == 0, out.stderr
    f = json.loads(out.stdout)["frequencies_hz"]
    assert f == sorted(f) and abs(f[0] - 0.978) < 1e-3


def test_run_dispatches_on_analysis_kind(cantilever):
    out = hubbeam("run", str(cantilever), "--json")
    assert out.returncode == 0 and "frequencies_hz" in json.loads(out.stdout)


@pytest.mark.parametrize(
    "args,code,text",
    [
        (("static", "missing.toml"), 2, "no such file"),
        (("static", "{c}", "--set", "beam.thickness=-1"), 2, "beam.thickness"),
        (("static", "{c}", "--set", "beam.nonsense=1"), 2, "beam.nonsense: unknown key"),
        (("static", "{c}", "--set", "nonsense"), 2, "KEY=VALUE"),
        (("example", "nope"), 2, "unknown example"),
        (("frobnicate",), 2, "invalid choice"),
        (("static", "{c}", "--set", "loads.tip_moment=[0.0, 0.0, 2000.0]", "--set", "analysis.load_steps=1"), 1,
         "load step"),
    ],
)
def test_errors_are_one_clear_line(cantilever, args, code, text):
    out = hubbeam(*[a.format(c=cantilever) for a in args])
    assert out.returncode == code, (out.stdout, out.stderr)
    assert text in out.stderr
    assert "Traceback" not in out.stderr
    assert out.stdout == ""


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_run_writes_netcdf_csv_and_plot(tmp_path, formulation):
    import xarray as xr

    scen = tmp_path / "exp1.toml"
    scen.write_text(hubbeam("example", "exp1").stdout)
    out = hubbeam("run", str(scen), "--set", "analysis.t_end=0.1", "--set", "beam.elements=3", "--json",
                  "--set", f'beam.formulation="{formulation}"',
                  "-o", str(tmp_path / "r.nc"), "--csv", str(tmp_path / "r.csv"), "--plot", str(tmp_path / "r.png"))
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert d["steps"] == 100 and d["wall_time_s"] > 0
    assert set(d["final"]["tip"]) == {"radial", "vertical", "tangential"}
    ds = xr.open_dataset(tmp_path / "r.nc")
    assert {"strain_P1", "hub_omega", "tip_tangential", "energy_total"} <= set(ds.data_vars)
    assert ds["time"].attrs["units"] == "s" and "beam" in ds.attrs["scenario"]
    assert (tmp_path / "r.csv").read_text().startswith("time,")
    assert (tmp_path / "r.png").stat().st_size > 10000


def test_campbell_writes_figure_and_data(tmp_path):
    import xarray as xr

    scen = tmp_path / "exp2.toml"
    scen.write_text(hubbeam("example", "exp2").stdout)
    out = hubbeam("campbell", str(scen), "--omega", "0:5:3", "--count", "2", "--set", "beam.elements=3",
                  "--formulations", "ancf,ffr", "-o", str(tmp_path / "c.png"), "--data", str(tmp_path / "c.nc"), "--json")
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    ancf, ffr = np.array(d["frequencies_hz"]["ancf"]), np.array(d["frequencies_hz"]["ffr"])
    assert ancf.shape == (3, 2)
    assert ancf[-1, 0] > ancf[0, 0] and ffr[-1, 0] < ffr[0, 0]  # stiffening vs the linear FFR's softening
    assert (tmp_path / "c.png").stat().st_size > 10000
    assert xr.open_dataset(tmp_path / "c.nc")["frequency_hz"].dims == ("formulation", "omega", "mode")
    bad = hubbeam("campbell", str(scen), "--omega", "0:5", "-o", str(tmp_path / "x.png"))
    assert bad.returncode == 2 and "--omega" in bad.stderr and "Traceback" not in bad.stderr


def test_identify_reads_a_csv_and_fits(tmp_path):
    scen = tmp_path / "exp1.toml"
    scen.write_text(hubbeam("example", "exp1").stdout)
    common = ["--set", "beam.elements=2", "--set", "analysis.dt=0.002"]
    made = hubbeam("run", str(scen), "--set", "analysis.t_end=0.4", "--csv", str(tmp_path / "m.csv"), *common)
    assert made.returncode == 0, made.stderr
    out = hubbeam("identify", str(scen), str(tmp_path / "m.csv"), "--fit", "damping.linear", "--set",
                  "damping.linear=1.0", *common, "-o", str(tmp_path / "fit.png"), "--json")
    assert out.returncode == 0, out.stderr
    p = json.loads(out.stdout)["parameters"]["damping.linear"]
    assert abs(p["value"] - 1.73) < 1e-3 and p["initial"] == 1.0
    assert (tmp_path / "fit.png").stat().st_size > 10000
    bad = hubbeam("identify", str(scen), str(tmp_path / "m.csv"), "--fit", "damping.linear", "--signal", "nope")
    assert bad.returncode == 2 and "no column 'nope'" in bad.stderr


def test_version():
    out = hubbeam("--version")
    assert out.returncode == 0 and out.stdout.strip() == "hubbeam 0.1.0" and not out.stderr
