"""``hubbeam modes`` (labels, energy fractions, --shapes, --plot) and ``hubbeam campbell``'s
tracked output and frequency zoom, through the command line in this process."""

import json

import numpy as np
import pytest

from tests.cli.helpers import EXAMPLES, assert_contract, cli

SMALL = ["--set", "beam.elements=4", "--set", "environment.gravity=[0.0, 0.0, 0.0]"]


@pytest.fixture(scope="module")
def modes_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("modes")
    code, stdout, stderr = cli("modes", EXAMPLES / "cantilever.toml", *SMALL, "--set", "analysis.count=5", "--json",
                               "--shapes", out / "s.nc", "--plot", out / "s.png")
    assert_contract(code, stdout, stderr, json_out=True)
    assert code == 0, stderr
    return out, json.loads(stdout)


def test_json_has_a_label_and_fractions_per_frequency(modes_run):
    _, d = modes_run
    assert len(d["labels"]) == len(d["energy_fractions"]) == len(d["frequencies_hz"]) == 5
    # the plate laid flat (twist 90 deg): three flap modes, then the first lag mode
    assert d["labels"][:4] == ["flap", "flap", "flap", "lag"]
    for shares in d["energy_fractions"]:
        assert set(shares) == {"flap", "lag", "axial", "torsion", "hub"}
        assert sum(shares.values()) == pytest.approx(1.0, abs=1e-12)


def test_shapes_file_holds_vectors_and_span_shapes(modes_run):
    import xarray as xr

    out, d = modes_run
    ds = xr.open_dataset(out / "s.nc")
    assert list(ds["label"].values) == d["labels"]
    assert np.allclose(ds["frequency_hz"].values, d["frequencies_hz"])
    assert ds["displacement"].dims == ("mode", "beam", "station", "component")
    assert ds["shape"].dims == ("mode", "coordinate")
    x = ds["x"].values[0]
    assert x[0] == 0.0 and x[-1] == pytest.approx(1.45)
    # clamped root, and the first mode's tip moves along flap
    disp = ds["displacement"].values[:, 0]
    assert np.allclose(disp[:, 0], 0.0, atol=1e-12)
    assert abs(disp[0, -1, 1]) > 100 * max(abs(disp[0, -1, 0]), abs(disp[0, -1, 2]))
    assert (out / "s.png").stat().st_size > 10000


def test_campbell_tracks_and_zooms(tmp_path):
    import xarray as xr

    code, stdout, stderr = cli("campbell", EXAMPLES / "cantilever.toml", *SMALL, "--omega", "0:4:3", "--count", "2",
                               "--formulations", "ancf", "--frange", "0:10", "-o", tmp_path / "c.png", "--data",
                               tmp_path / "c.nc", "--json")
    assert_contract(code, stdout, stderr, json_out=True)
    d = json.loads(stdout)
    assert d["tracked"]["ancf"]["labels"] == ["flap", "flap"]
    assert np.array(d["tracked"]["ancf"]["frequencies_hz"]).shape == (3, 2)
    ds = xr.open_dataset(tmp_path / "c.nc")
    assert ds["tracked_frequency_hz"].dims == ("formulation", "omega", "branch")
    assert (tmp_path / "c.png").stat().st_size > 10000


@pytest.mark.parametrize("option", [["--frange", "5:1"], ["--frange", "a:b"], ["--fmax", "-1"], ["--fmax", "nan"]])
def test_campbell_zoom_errors_name_the_option(option, tmp_path):
    code, stdout, stderr = cli("campbell", EXAMPLES / "cantilever.toml", "--omega", "0:4:3", *option, "-o",
                               tmp_path / "c.png")
    assert_contract(code, stdout, stderr)
    assert code == 2 and option[0] in stderr


def test_modes_checks_its_targets_before_computing(tmp_path):
    code, stdout, stderr = cli("modes", EXAMPLES / "cantilever.toml", "--shapes", tmp_path / "missing" / "s.nc")
    assert_contract(code, stdout, stderr)
    assert code == 2 and "--shapes" in stderr
    code, stdout, stderr = cli("modes", EXAMPLES / "cantilever.toml", "--plot", tmp_path / "s.nc")
    assert code == 2 and "--plot" in stderr


ROTOR = ["--set", "beams[*].elements=1", "--set", "environment.gravity=[0.0, 0.0, 0.0]"]


def test_campbell_in_the_fixed_frame(tmp_path):
    """rotor3 (copies = 3): its own formulation only, the fixed frame in the JSON (omega x
    branch, per formulation) and in the data, multi-blade labels, the nP lines 1P..6P."""
    import xarray as xr

    code, stdout, stderr = cli("campbell", EXAMPLES / "rotor3.toml", *ROTOR, "--omega", "0:6:3", "--count", "3",
                               "--frame", "fixed", "-o", tmp_path / "c.png", "--data", tmp_path / "c.nc", "--json")
    assert_contract(code, stdout, stderr, json_out=True)
    d = json.loads(stdout)
    assert d["formulations"] == ["ancf"] and d["frame"] == "fixed" and d["blades"] == 3 and d["symmetric"]
    assert d["tracked"]["ancf"]["labels"] == ["collective flap", "cyclic flap", "cyclic flap"]
    fixed = d["fixed"]
    assert fixed["omega"] == [0.0, 3.0, 6.0] and np.array(fixed["frequencies_hz"]["ancf"]).shape == (3, 3)
    assert fixed["labels"]["ancf"][-1] == ["collective flap", "progressive flap", "regressive flap"]
    assert fixed["whirl"]["ancf"][-1] == ["", "forward", "backward"]
    rotating = np.array(d["tracked"]["ancf"]["frequencies_hz"])
    assert np.allclose(np.array(fixed["frequencies_hz"]["ancf"])[-1], rotating[-1] + [0.0, 6 / (2 * np.pi), -6 / (2 * np.pi)])
    assert d["np_lines"]["orders"] == [1, 2, 3, 4, 5, 6]
    ds = xr.open_dataset(tmp_path / "c.nc")
    assert ds["fixed_frequency_hz"].dims == ("formulation", "omega", "branch") and "np_line_hz" in ds
    assert (tmp_path / "c.png").stat().st_size > 10000


def test_campbell_fixed_frame_of_an_unequal_rotor_falls_back_and_says_so(tmp_path):
    code, stdout, stderr = cli("campbell", EXAMPLES / "rotor3.toml", *ROTOR, "--set", "beams.blade3.tip_body.mass=0.1",
                               "--omega", "0:6:2", "--count", "2", "--frame", "fixed", "--harmonics", "1,3", "--json")
    assert_contract(code, stdout, stderr, json_out=True)
    d = json.loads(stdout)
    assert d["frame"] == "rotating" and not d["symmetric"] and "fixed" not in d and d["np_lines"]["orders"] == [1, 3]
    assert "blade3 differs from blade1 in tip_body" in d["symmetry"]
    assert "--frame fixed: the rotor is not symmetric: blade3 differs from blade1 in tip_body" in stderr


@pytest.mark.parametrize("option", [["--harmonics", "0"], ["--harmonics", "1,x"], ["--harmonics", "2,2"],
                                    ["--frame", "inertial"]])
def test_campbell_frame_and_harmonics_errors_name_the_option(option):
    code, stdout, stderr = cli("campbell", EXAMPLES / "rotor3.toml", "--omega", "0:4:3", *option)
    assert_contract(code, stdout, stderr)
    assert code == 2 and option[0] in stderr


def test_an_uncertain_match_is_one_line_on_stderr_and_in_the_json():
    """The tapered blade from rest to 60 rad/s in one step: its fourth branch changes shape (MAC
    about 0.1), which is said with the speed, the branch and the measures."""
    code, stdout, stderr = cli("campbell", EXAMPLES / "blade.toml", "--set", "beam.elements=4", "--omega", "0:60:2",
                               "--count", "4", "--json")
    assert_contract(code, stdout, stderr, json_out=True)
    lines = [ln for ln in stderr.splitlines() if "uncertain match" in ln]
    assert lines and lines[0].startswith("hubbeam: note: campbell: ancf branch 4 at omega = 60 rad/s: uncertain match (MAC")
    assert json.loads(stdout)["uncertain"] == [ln.split("campbell: ", 1)[1] for ln in lines]
