"""Loads from Python functions along the span (:mod:`hubbeam.system.load_functions`) against
the built-in air drag they reproduce and against beam theory."""

import warnings

import numpy as np
import pytest

from hubbeam import api
from hubbeam.errors import ScenarioError
from hubbeam.io.results import to_dataset
from hubbeam.io.scenario import load_example
from hubbeam.system.load_functions import LoadFunction

SHORT = ["beam.elements=4", "analysis.t_end=0.03", "analysis.dt=1e-3"]
STILL_AIR = ["damping.linear=0", "damping.quadratic=0"]


def records(scenario, loads=None) -> dict:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the Python step path's warning
        trajectory, failure = api.run(scenario, loads=loads)
    assert failure is None, failure
    ds = to_dataset(trajectory, scenario)
    return {name: ds[name].values for name in ds.data_vars}


@pytest.mark.parametrize("form", ["ancf", "ffr"])
def test_a_load_function_that_is_the_air_drag_gives_the_drag_run(form):
    """exp1 (a free hub spun up by its torque, a plate sagging under gravity) with the built-in
    drag of Eq. 37, and with the drag off and a load function f = -b (c1 + c2 |v|) v on the
    centre-line velocity instead: the same run to the Newton tolerance (measured: 1e-15 of the
    signals on ANCF, the function at the beam's own Gauss points as the drag's; 2e-17 on FFR),
    while leaving the drag out changes it by much more. The function's work is the drive's (its
    negative is the drag's dissipated energy)."""
    dragged = load_example("exp1", SHORT + [f'beam.formulation="{form}"'])
    c1, c2, b = dragged.damping.linear, dragged.damping.quadratic, dragged.beam.width

    def drag(t, x, position, velocity, frame):
        speed = np.linalg.norm(velocity, axis=1)[:, None]
        return -b * (c1 + c2 * speed) * velocity, np.zeros(3)

    still = load_example("exp1", SHORT + STILL_AIR + [f'beam.formulation="{form}"'])
    reference, ours, without = records(dragged), records(still, [drag]), records(still)
    for name in ("strain_P1", "hub_omega", "tip_vertical", "tip_tangential", "energy_total"):
        size = np.max(np.abs(reference[name]))
        assert np.max(np.abs(ours[name] - reference[name])) < 1e-9 * size, name
    assert np.max(np.abs(without["hub_omega"] - reference["hub_omega"])) > 1e-6 * np.max(np.abs(reference["hub_omega"]))
    np.testing.assert_allclose(ours["energy_drive"], -reference["energy_dissipated"], rtol=1e-9,
                               atol=1e-12 * np.max(reference["energy_dissipated"]))


def test_a_uniform_load_function_bends_the_cantilever_as_beam_theory():
    """``static`` with a function returning a uniform q along global y (the reference
    cantilever, weak axis along y, no gravity): the tip deflection q L^4 / (8 EI)."""
    sc = load_example("cantilever", ["environment.gravity=[0.0, 0.0, 0.0]", "analysis.load_steps=1"])
    q, EI, L = -0.00825, 70e9 * 0.05 * 0.0025**3 / 12, 1.45
    result = api.static(sc, loads=[LoadFunction(lambda t, x, r, v, frame: ([0.0, q, 0.0], [0.0, 0.0, 0.0]))])
    assert result.to_dict()["tip_displacement"]["vertical"] == pytest.approx(q * L**4 / (8 * EI), rel=1e-5)


def test_bad_load_functions_are_named():
    sc = load_example("cantilever", ["environment.gravity=[0.0, 0.0, 0.0]", "analysis.load_steps=1"])
    with pytest.raises(ValueError, match="function1: the load function must return .force, moment."):
        api.static(sc, loads=lambda t, x, r, v, frame: 1.0)
    with pytest.raises(ValueError, match="gust: the load function returned a value that is not finite"):
        api.static(sc, loads=LoadFunction(lambda t, x, r, v, frame: (np.full(3, np.nan), np.zeros(3)), name="gust"))
    with pytest.raises(TypeError, match=r"loads\[0\]: expected a LoadFunction or a function"):
        api.static(sc, loads=[3.0])
    with pytest.raises(ScenarioError, match="no beam named 'blade9'"):
        api.static(sc, loads=LoadFunction(lambda *a: (np.zeros(3), np.zeros(3)), beam="blade9"))
