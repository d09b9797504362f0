"""Property-based tests of the command line's contract (hypothesis): whatever the scenario's
values, names or the arguments, a command exits 0, 1 or 2 with at most one line on stderr and
no traceback or internal error, and its files are either valid or absent (issue 15)."""

from __future__ import annotations

import json
import math
import os
import re
import string

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hubbeam import limits
from hubbeam.io.scenario import ScenarioError
from tests.cli.helpers import EXAMPLES, assert_contract, cli, no_temporary_files

pytestmark = pytest.mark.filterwarnings("ignore")

SETTINGS = settings(max_examples=int(os.environ.get("HUBBEAM_EXAMPLES", "150")), deadline=None,
                    derandomize=not os.environ.get("HUBBEAM_EXAMPLES"),
                    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])

#: a small, quick base scenario: exp1 with 2 elements for 20 steps
BASE = (EXAMPLES / "exp1.toml").read_text().replace("elements = 6", "elements = 2").replace(
    "t_end = 20.0", "t_end = 0.02")


def toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf") if math.isinf(value) else repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    return "[" + ", ".join(toml_value(v) for v in value) + "]"


weird_floats = st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                         st.sampled_from([0.0, -0.0, 1e-300, 1e300, -1.0, 5e-324, 1.7976931348623157e308]))
#: mostly valid but extreme numbers (so that many examples get past the validation into the model)
plausible = st.one_of(st.floats(min_value=1e-30, max_value=1e30), st.floats(min_value=-1e3, max_value=1e3))
values = st.one_of(plausible, plausible, plausible, st.lists(plausible, min_size=3, max_size=3), weird_floats,
                   st.integers(-3, 8), st.sampled_from([0, 10**9, 2**63]), st.booleans(), st.text(max_size=6),
                   st.lists(weird_floats, max_size=4))
#: keys that change the model (not its size in steps: that has its own property below)
KEYS = ["beam.formulation", "beam.elements", "beam.length", "beam.width", "beam.thickness", "beam.density",
        "beam.youngs_modulus", "beam.poisson_ratio", "beam.torsion_constant", "hub.motion", "hub.radius", "hub.twist",
        "hub.inertia", "hub.torque", "environment.gravity", "damping.linear", "damping.quadratic",
        "loads.tip_force", "loads.tip_moment", "analysis.spectral_radius", "analysis.kind", "analysis.newton",
        "analysis.tolerance", "name", "beam.nonsense"]
small_elements = st.integers(-3, 6) | st.sampled_from([0, 10**9, 2001])


@st.composite
def overrides(draw):
    chosen = draw(st.lists(st.sampled_from(KEYS), min_size=1, max_size=2, unique=True))
    out = []
    for key in chosen:
        value = draw(small_elements if key == "beam.elements" else values)
        if key in ("beam.formulation", "hub.motion", "analysis.kind", "analysis.newton") and draw(st.booleans()):
            value = draw(st.sampled_from({"beam.formulation": ["ancf", "ffr"], "hub.motion": ["free", "fixed", "prescribed"],
                                          "analysis.kind": ["dynamic", "static", "modes"],
                                          "analysis.newton": ["full", "step", "modified"]}[key]))
        out.append(f"{key}={toml_value(value)}")
    return out


def check_files(code, directory):
    """Files valid or absent: a NetCDF that exists opens and is marked complete or partial."""
    import xarray as xr

    assert no_temporary_files(directory)
    nc = directory / "r.nc"
    if nc.exists():
        with xr.open_dataset(nc) as ds:
            assert ds.attrs["partial"] == (0 if code == 0 else 1)
            assert float(ds["time"][-1]) == ds.attrs["time_reached"]
            times = ds["time"].values
            assert np.all(np.diff(times) > 0)
    elif code == 0:
        pytest.fail("a successful dynamic run wrote no NetCDF")


@SETTINGS
@given(sets=overrides())
def test_any_scenario_values_keep_the_contract(tmp_path_factory, sets):
    directory = tmp_path_factory.mktemp("values")
    scenario = directory / "s.toml"
    scenario.write_text(BASE)
    args = [a for s in sets for a in ("--set", s)]
    code, out, err = cli("run", scenario, *args, "--json", "-o", directory / "r.nc", "--csv", directory / "r.csv")
    assert_contract(code, out, err, json_out=True)
    if code == 0 and '"steps"' in out:
        check_files(code, directory)
    elif code == 2:
        assert not (directory / "r.nc").exists()
        key = err.removeprefix("hubbeam: error: ").split(":")[0]
        assert key, err  # names what is wrong


identifier = st.from_regex(r"\A[A-Za-z_][A-Za-z0-9_]{0,8}\Z", fullmatch=True)
names = st.one_of(identifier, st.sampled_from(["time", "tip_radial", "tip", "energy_total", "strain_P1"]),
                  st.text(max_size=8))
KINDS = ["hub_angle", "hub_angular_velocity", "tip_deflection", "energy", "angular_momentum", "surface_strain"]


@SETTINGS
@given(name=st.text(max_size=12), sensors=st.lists(st.tuples(names, st.sampled_from(KINDS)), min_size=1, max_size=4))
def test_any_names_never_corrupt_the_results(tmp_path_factory, name, sensors):
    """Scenario and sensor names, valid or not, colliding with generated columns or not: either
    refused, or every column is written once with its own sensor's values."""
    import pandas as pd
    import xarray as xr

    directory = tmp_path_factory.mktemp("names")
    base = BASE.split("[[sensors]]")[0].replace('name = "exp1"', f"name = {toml_value(name)}")
    blocks = []
    for sensor, kind in sensors:
        station = '\nx = 0.3\nsurface = "upper"' if kind == "surface_strain" else ""
        blocks.append(f"[[sensors]]\nname = {toml_value(sensor)}\nkind = {toml_value(kind)}{station}\n")
    scenario = directory / "s.toml"
    scenario.write_text(base + "\n".join(blocks), encoding="utf-8")
    code, out, err = cli("run", scenario, "--json", "-o", directory / "r.nc", "--csv", directory / "r.csv")
    assert_contract(code, out, err, json_out=True)
    assert no_temporary_files(directory)
    if code != 0:
        return
    expected = []
    for sensor, kind in sensors:
        parts = limits.PART_NAMES.get(kind)
        expected += [f"{sensor}_{p}" for p in parts] if parts else [sensor]
    assert len(set(expected)) == len(expected) and "time" not in expected  # else it must not succeed
    with xr.open_dataset(directory / "r.nc") as ds:
        assert sorted(ds.data_vars) == sorted(expected)
    table = pd.read_csv(directory / "r.csv")
    assert list(table.columns) == ["time"] + [c for c in table.columns if c != "time"]
    assert sorted(table.columns[1:]) == sorted(expected)


TOKENS = ["-o", "--csv", "--plot", "--data", "--set", "--json", "--omega", "--count", "--fit", "--signal",
          "--formulations", "--vary", "--workers", "--help-me", "-x", "--"]
ARGUMENT_VALUES = ["{d}/a.nc", "{d}/a.csv", "{d}/a.png", "{d}/a.txt", "{d}/missing/a.nc", "{d}", "{s}", "/dev/null",
                   "", "-", "0:1:2", "0:5", "a:b:c", "1e400", "nan", "-3", "0", "3", "beam.elements=3",
                   "beam.elements", "=", "damping.linear", "tip", "ancf,ffr", "nope", "{m}", "x" * 300, "é\u2028"]


@SETTINGS
@given(command=st.sampled_from(["run", "static", "modes", "campbell", "identify", "example", "frobnicate", ""]),
       positional=st.lists(st.sampled_from(ARGUMENT_VALUES), max_size=2),
       options=st.lists(st.tuples(st.sampled_from(TOKENS), st.sampled_from(ARGUMENT_VALUES)), max_size=4))
def test_any_arguments_keep_the_contract(tmp_path_factory, command, positional, options):
    directory = tmp_path_factory.mktemp("args")
    scenario, measured = directory / "s.toml", directory / "m.csv"
    scenario.write_text(BASE)
    measured.write_text("time,strain_P1,tip\n" + "".join(f"{k * 0.004!r},{np.sin(k)},{k}\n" for k in range(6)))
    fill = {"d": directory, "s": scenario, "m": measured}
    args = [command] + [p.format(**fill) for p in positional]
    for token, value in options:
        args += [token, value.format(**fill)]
    code, out, err = cli(*args)
    if code == 0 and "--help" in args:
        return
    assert_contract(code, out, err, json_out="--json" in args)
    assert no_temporary_files(directory)


@settings(max_examples=200, deadline=None, derandomize=True)
@given(t_end=st.floats(min_value=5e-324, max_value=1e308), dt=st.floats(min_value=5e-324, max_value=1e308),
       output_dt=st.none() | st.floats(min_value=5e-324, max_value=1e308), columns=st.integers(1, 40))
def test_run_size_is_refused_or_bounded(t_end, dt, output_dt, columns):
    """Up-front estimates: a run is either refused naming an analysis key, or has at most
    MAX_STEPS steps and its records fit in MAX_RECORD_BYTES."""
    try:
        size = limits.run_size(t_end, dt, output_dt, columns)
    except ScenarioError as exc:
        assert re.match(r"analysis\.(dt|output_dt|t_end): ", str(exc)), exc
        assert "\n" not in str(exc)
        return
    assert size.steps <= limits.MAX_STEPS + 1 and size.record_bytes <= limits.MAX_RECORD_BYTES
    assert dt >= limits.MIN_DT


def test_printable_alphabet_is_covered():
    assert set(string.ascii_letters) <= set("".join(KEYS + ARGUMENT_VALUES)) | set(string.ascii_letters)
