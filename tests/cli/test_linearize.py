"""hubbeam linearize: the JSON summary, the NetCDF file, and bad input."""

import json

import numpy as np
import xarray as xr

from hubbeam import api
from hubbeam.io.scenario import load_example
from tests.cli.helpers import EXAMPLES, assert_contract, cli, without_notes

SMALL = ["--set", "beam.elements=4", "--set", "analysis.load_steps=4"]


def test_json_summary_equals_modes_without_damping(tmp_path):
    undamped = SMALL + ["--set", "damping.linear=0", "--set", "damping.quadratic=0"]
    code, out, err = cli("linearize", EXAMPLES / "exp1.toml", *undamped, "--json")
    assert_contract(code, out, err, json_out=True)
    d = json.loads(out)
    assert set(d) >= {"states", "inputs", "outputs", "frequencies_hz", "damping_ratios"}
    assert d["inputs"] == ["hub_torque"]
    assert d["outputs"][:3] == ["strain_P1", "strain_P2", "hub_omega"]
    code, out_modes, _ = cli("modes", EXAMPLES / "exp1.toml", *undamped, "--json")
    modes = json.loads(out_modes)["frequencies_hz"]
    np.testing.assert_allclose(d["frequencies_hz"][: len(modes)], modes, rtol=1e-6)
    assert d["frequencies_hz"] == sorted(d["frequencies_hz"])
    # n states: twice the coordinates less the constraints (4 ANCF elements: 40 + theta, 6 clamp rows)
    assert d["states"] == 2 * (41 - 6)


def test_netcdf_holds_the_named_matrices(tmp_path):
    path = tmp_path / "ss.nc"
    code, out, err = cli("linearize", EXAMPLES / "exp1.toml", *SMALL, "-o", path)
    assert_contract(code, out, err)
    assert "70 states" in out
    with xr.open_dataset(path) as ds:
        assert ds["A"].dims == ("state_rate", "state")
        assert ds["B"].dims == ("state_rate", "input") and list(ds["input"].values) == ["hub_torque"]
        assert ds["D"].dims == ("output", "input")
        model = api.linearize(load_example("exp1", ["beam.elements=4", "analysis.load_steps=4"]))
        np.testing.assert_array_equal(ds["A"].values, model.A)
        np.testing.assert_array_equal(ds["C"].values, model.C)
        assert list(ds["output"].values) == model.outputs
        assert ds.attrs["name"] == "exp1"
    # the drag's damping: every elastic mode decays
    code, out, err = cli("linearize", EXAMPLES / "exp1.toml", *SMALL, "--json")
    assert all(z > 0 for z in json.loads(out)["damping_ratios"])


def test_tip_force_inputs_on_a_held_hub():
    code, out, err = cli("linearize", EXAMPLES / "cantilever.toml", *SMALL, "--inputs", "tip_force:beam1", "--json")
    assert_contract(code, out, err, json_out=True)
    d = json.loads(out)
    assert d["inputs"] == ["tip_force_x_beam1", "tip_force_y_beam1", "tip_force_z_beam1"]
    assert d["outputs"] == ["tip_radial", "tip_vertical", "tip_tangential"]


def test_load_inputs_from_the_command_line():
    """``--inputs load:NAME,load:tip``: the load channels load_NAME_x|y|z (a span load's force
    per length, the tip loads' force); an unknown load is exit 2 naming it and the loads there are."""
    span = ["--set", "loads.span=[{name = 'gust', force = [0.0, -0.01, 0.0]}]"]
    code, out, err = cli("linearize", EXAMPLES / "cantilever.toml", *SMALL, *span, "--inputs", "load:gust,load:tip",
                         "--json")
    assert_contract(code, out, err, json_out=True)
    assert json.loads(out)["inputs"] == ["load_gust_x", "load_gust_y", "load_gust_z", "load_tip_x", "load_tip_y",
                                         "load_tip_z"]
    code, out, err = cli("linearize", EXAMPLES / "cantilever.toml", *SMALL, *span, "--inputs", "load:wind")
    assert code == 2 and "--inputs: load:wind: no load of that name (loads: tip, gust)" in err


def test_bad_input_is_one_line_naming_the_option(tmp_path):
    code, out, err = cli("linearize", EXAMPLES / "cantilever.toml", *SMALL, "--inputs", "hub_torque")
    assert_contract(code, out, err)
    assert code == 2 and without_notes(err).startswith("hubbeam: error: --inputs: hub_torque needs a free hub")
    code, out, err = cli("linearize", EXAMPLES / "exp1.toml", *SMALL, "--inputs", "tip_force:blade9")
    assert code == 2 and "--inputs: tip_force:blade9" in err
    code, out, err = cli("linearize", EXAMPLES / "exp1.toml", *SMALL, "-o", tmp_path / "no" / "ss.nc")
    assert code == 2 and without_notes(err).startswith("hubbeam: error: -o ")


def test_reduced_models_from_the_command_line(tmp_path):
    """--reduce, --balanced, --fmax and --outputs on the bundled spacecraft (PD slew, two panels)."""
    sc = EXAMPLES / "spacecraft.toml"
    code, out, err = cli("linearize", sc, "--reduce", "3", "--json")
    assert_contract(code, out, err, json_out=True)
    d = json.loads(out)
    assert d["states"] == 6 and d["reduction"]["method"] == "modal" and len(d["frequencies_hz"]) == 3
    assert "no input reaches" in err  # the symmetric panel modes, said
    path = tmp_path / "bal.nc"
    code, out, err = cli("linearize", sc, "--balanced", "4", "--outputs", "theta,root_strain_a", "-o", path, "--json")
    assert_contract(code, out, err, json_out=True)
    d = json.loads(out)
    assert d["outputs"] == ["theta", "root_strain_a"] and d["states"] == 4
    sigma = d["hankel_singular_values"]
    assert sigma == sorted(sigma, reverse=True) and d["reduction"]["error_bound"] == 2 * sum(sigma[4:])
    with xr.open_dataset(path) as ds:
        assert ds["projection"].dims == ("full_state", "state") and ds.sizes["full_state"] == d["reduction"]["full_states"]
        np.testing.assert_array_equal(ds["hankel_singular_value"].values, sigma)
    code, out, err = cli("linearize", sc, "--fmax", "5", "--json")
    assert code == 0 and max(json.loads(out)["frequencies_hz"]) < 5
    code, out, err = cli("linearize", sc, "--reduce", "3")  # the text summary says what it is
    assert code == 0 and "6 states (reduced from" in out


def test_bad_reduction_options_are_one_line():
    sc = EXAMPLES / "spacecraft.toml"
    for args, start in ((["--reduce", "0"], "--reduce: must be >= 1"), (["--fmax", "nan"], "--fmax: a frequency > 0"),
                        (["--outputs", "theta,nope"], "--outputs: unknown 'nope'"),
                        (["--reduce", "2", "--balanced", "2"], "argument --balanced: not allowed with")):
        code, out, err = cli("linearize", sc, *args)
        assert code == 2 and err.splitlines()[-1].startswith("hubbeam: error: " + start), err
    code, out, err = cli("linearize", EXAMPLES / "cantilever.toml", *SMALL, "--set", "damping.linear=0",
                         "--set", "damping.quadratic=0", "--balanced", "2")
    assert code == 2 and "--balanced: the model has no stable part" in err
