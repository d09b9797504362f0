"""Scenario loading: the bundled examples validate; malformed input gives one clear line."""

import copy
import math
import tomllib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hubbeam.cli import EXAMPLES, example_text
from hubbeam.io.scenario import ScenarioError, apply_overrides, load_scenario, validate

BASE = tomllib.loads(example_text("exp1"))


@pytest.mark.parametrize("name", EXAMPLES)
def test_bundled_examples_are_valid(name):
    sc = validate(tomllib.loads(example_text(name)))
    assert sc.beam.length == 1.45


def test_overrides_use_toml_values_and_bare_words():
    sc = validate(apply_overrides(BASE, ["beam.elements=8", "beam.formulation=ancf", "hub.twist=30", 'name="x"']))
    assert sc.beam.elements == 8 and sc.hub.twist == 30.0 and sc.name == "x"


@pytest.mark.parametrize(
    "override,key",
    [
        ("beam.thickness=-1", "beam.thickness"),
        ("beam.thickness=0", "beam.thickness"),
        ("beam.length=nan", "beam.length"),
        ("beam.length=inf", "beam.length"),
        ("beam.elements=2.5", "beam.elements"),
        ("beam.poisson_ratio=0.5", "beam.poisson_ratio"),
        ("beam.poisson_ratio=-1", "beam.poisson_ratio"),
        ("beam.colour=1", "beam.colour"),
        ("hub.motion=spinning", "hub.motion"),
        ("hub.motion=prescribed", "hub.drive"),
        ("sensors=[{name='a', kind='surface_strain', x=2.0, surface='upper'}]", "sensors[0].x"),
        ("sensors=[{name='a', kind='surface_strain', x=-0.1, surface='upper'}]", "sensors[0].x"),
        ("environment.gravity=[0, 1]", "environment.gravity"),
        ("analysis.spectral_radius=1.5", "analysis.spectral_radius"),
        ("beam.shear_modulus=26e9", "beam.shear_modulus"),
        ("beam.geometric_stiffening=true", "beam.geometric_stiffening"),
        ("analysis=3", "analysis"),
    ],
)
def test_bad_values_name_their_key(override, key):
    with pytest.raises(ScenarioError) as info:
        validate(apply_overrides(BASE, [override]))
    msg = str(info.value)
    assert msg.startswith(key + ":"), msg
    assert "\n" not in msg


def test_missing_required_key():
    data = copy.deepcopy(BASE)
    del data["beam"]["length"]
    with pytest.raises(ScenarioError, match=r"^beam.length: required key is missing"):
        validate(data)


def test_file_errors(tmp_path):
    with pytest.raises(ScenarioError, match="no such file"):
        load_scenario(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[beam\nlength = 1")
    with pytest.raises(ScenarioError, match="malformed TOML"):
        load_scenario(bad)
    with pytest.raises(ScenarioError, match="directory"):
        load_scenario(tmp_path)


def _paths(data, prefix=()):
    for k, v in data.items():
        if isinstance(v, dict):
            yield from _paths(v, prefix + (k,))
        else:
            yield prefix + (k,)


PATHS = [p for p in _paths(BASE) if p != ("name",)]
JUNK = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**6, 10**6), st.text(max_size=5), st.booleans(),
    st.lists(st.floats(allow_nan=True), max_size=4), st.none(), st.dictionaries(st.text(max_size=3), st.integers(), max_size=2),
)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(path=st.sampled_from(PATHS), value=JUNK, drop=st.booleans())
def test_mutated_scenarios_fail_cleanly_or_validate(path, value, drop):
    data = copy.deepcopy(BASE)
    node = data
    for part in path[:-1]:
        node = node[part]
    if drop:
        del node[path[-1]]
    elif value is None:
        node[path[-1] + "_x"] = 1
    else:
        node[path[-1]] = value
    try:
        sc = validate(data)
    except ScenarioError as exc:
        msg = str(exc)
        assert "\n" not in msg and ": " in msg and len(msg) < 300
        root = msg.split(":")[0].split("[")[0].split(".")[0]
        assert root in {"beam", "hub", "environment", "damping", "loads", "analysis", "sensors", "name", "scenario",
                        path[-1] + "_x"}
        return
    # what validates is physically meaningful
    assert sc.beam.length > 0 and sc.beam.thickness > 0 and sc.beam.elements >= 1
    assert all(math.isfinite(g) for g in sc.environment.gravity)


@settings(max_examples=100, deadline=None)
@given(text=st.text(max_size=200))
def test_arbitrary_text_never_crashes_the_loader(tmp_path_factory, text):
    path = tmp_path_factory.mktemp("s") / "s.toml"
    path.write_text(text, encoding="utf-8")
    try:
        load_scenario(path)
    except ScenarioError as exc:
        assert "\n" not in str(exc).strip() or "malformed TOML" in str(exc)
