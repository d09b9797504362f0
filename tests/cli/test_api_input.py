"""The Python API takes a Scenario or the path of a scenario file, and nothing else; a wrong
argument is a ScenarioError with a clear message, not an AttributeError (issue 15)."""

from pathlib import Path

import pytest

import hubbeam
from hubbeam import api
from hubbeam.io.scenario import Scenario, ScenarioError, load_example
from tests.cli.helpers import EXAMPLES

CANTILEVER = EXAMPLES / "cantilever.toml"


def test_the_package_exports_its_api_lazily():
    assert set(hubbeam.__all__) == {"load_scenario", "static", "modes", "run", "build_system", "ScenarioError"}
    assert hubbeam.ScenarioError is ScenarioError and hubbeam.static is api.static
    with pytest.raises(AttributeError):
        hubbeam.nonsense  # noqa: B018


@pytest.mark.parametrize("source", [str(CANTILEVER), CANTILEVER])
def test_static_and_modes_take_a_path(source):
    # a small model so that the solves are quick
    sc = hubbeam.load_scenario(source, ["beam.elements=2"])
    assert isinstance(sc, Scenario)
    assert hubbeam.static(source).to_dict()["tip_displacement"]["vertical"] < 0
    assert hubbeam.modes(sc).to_dict()["frequencies_hz"]


@pytest.mark.parametrize("function", ["static", "modes", "run", "build_system"])
@pytest.mark.parametrize("bad,text", [(42, "got int 42"), (None, "got NoneType"), ({"beam": {}}, "got dict"),
                                      (b"f.toml", "got bytes")])
def test_anything_else_is_a_scenario_error(function, bad, text):
    with pytest.raises(ScenarioError, match=f"scenario: expected a Scenario or the path of a scenario file \\({text}"):
        getattr(hubbeam, function)(bad)


def test_a_missing_or_unreadable_path(tmp_path):
    with pytest.raises(ScenarioError, match="no such file"):
        hubbeam.static(tmp_path / "missing.toml")
    with pytest.raises(ScenarioError, match="is a directory"):
        hubbeam.modes(tmp_path)
    with pytest.raises(ScenarioError, match="not a regular file"):
        hubbeam.run("/dev/zero")


def test_load_scenario_wants_a_list_of_overrides():
    with pytest.raises(ScenarioError, match="overrides: expected a list of 'KEY=VALUE' strings \\(got str"):
        hubbeam.load_scenario(CANTILEVER, "beam.elements=3")
    with pytest.raises(ScenarioError, match="overrides: expected a list"):
        hubbeam.load_scenario(CANTILEVER, [3])
    with pytest.raises(ScenarioError, match="scenario: expected the path"):
        hubbeam.load_scenario(42)
    assert hubbeam.load_scenario(CANTILEVER, ("beam.elements=3",)).beam.elements == 3


def test_a_scenario_copied_with_invalid_values_is_validated_again():
    sc = load_example("cantilever")
    bad = sc.model_copy(update={"single_beam": sc.beam.model_copy(update={"elements": -3})})
    with pytest.raises(ScenarioError, match="beam.elements"):
        hubbeam.static(bad)
    worse = sc.model_copy(update={"beam": "not a beam"})
    with pytest.raises(ScenarioError, match="beam"):
        hubbeam.modes(worse)


def test_run_refuses_absurd_sizes_up_front():
    sc = load_example("exp1", ["analysis.t_end=1000000.0", "analysis.dt=1e-6"])
    with pytest.raises(ScenarioError, match=r"analysis.dt: .* 1e\+12 steps"):
        hubbeam.run(sc)
    sc = load_example("exp1", ["analysis.dt=1e-300", "analysis.t_end=1e-299"])
    with pytest.raises(ScenarioError, match="analysis.dt: 1e-300 s is below"):
        hubbeam.run(sc)
    sc = load_example("exp1", ["analysis.t_end=5000.0", "analysis.dt=0.0001", "analysis.output_dt=0.0001"])
    with pytest.raises(ScenarioError, match="analysis.output_dt: .* GiB"):
        hubbeam.run(sc)


def test_an_output_step_longer_than_the_run_records_start_and_end():
    sc = load_example("exp1", ["beam.elements=2", "analysis.t_end=0.01", "analysis.output_dt=1e300"])
    traj, failure = hubbeam.run(sc)
    assert failure is None and traj.times == [0.0, 0.01]


def test_a_large_static_load_fails_with_what_to_try():
    """A 10 kN tip force on 2 elements crushed a nodal slope to zero length, and the chart
    replacement then divided by zero (issue 15): now a ComputationError that says what to try."""
    from hubbeam.errors import ComputationError

    sc = load_example("cantilever", ["loads.tip_force=[0.0, -1e4, 0.0]", "beam.elements=2"])
    with pytest.raises(ComputationError, match="try more beam.elements"):
        hubbeam.static(sc)


def test_path_like_objects_are_paths(tmp_path):
    class Custom:
        def __fspath__(self):
            return str(CANTILEVER)

    assert hubbeam.load_scenario(Custom(), ["beam.elements=2"]).beam.elements == 2
    assert isinstance(Path(CANTILEVER), Path)
