"""Loads as inputs of the linear model (``load:NAME``: inputs ``load_NAME_x|y|z``) against the
centre line's Jacobian, beam theory and the static solution."""

import numpy as np
import pytest

from hubbeam import api
from hubbeam.analysis.state_space import input_columns
from hubbeam.errors import ScenarioError
from hubbeam.io.scenario import load_example
from hubbeam.solvers.static import solve_static
from hubbeam.system.span_loads import SpanLoad
from tests.conftest import central_difference

SMALL = ["beam.elements=4", "analysis.load_steps=2"]
NO_GRAVITY = ["environment.gravity=[0.0, 0.0, 0.0]"]


@pytest.mark.parametrize("form", ["ancf", "ffr"])
@pytest.mark.parametrize("axes", ["global", "section"])
def test_a_span_load_input_is_the_centre_lines_jacobian_transposed(form, axes, tmp_path):
    """A force of 1 N/m along axis a over the stations x_s (weights w_s) of a load on part of the
    span does the virtual work sum_s w_s e . d r(x_s), e = e_a (global) or R e_a (R the root
    section frame, section axes): its generalized force is sum_s w_s (d r(x_s)/dx)^T e, with
    the centre line differenced (independent of the load code). exp1: a free hub (its angle a
    coordinate the section load acts on) and a 45 deg twist, deformed by gravity."""
    (tmp_path / "part.csv").write_text("x,fx,fy,fz\n0.3,0,0,-1.0\n1.1,0,0,-2.0\n")
    sc = load_example("exp1", SMALL + [f'beam.formulation="{form}"', f'loads.span=[{{name = "gust", '
                                       f'axes = "{axes}", file = "{tmp_path / "part.csv"}"}}]'])
    system = api.build_system(sc)
    eq = solve_static(system, load_steps=2)
    zero = np.zeros(system.nx)
    lam = system.lambda_from_held(eq.multipliers, system.hub.held)
    B, names, units = input_columns(system, ["load:gust"], eq.x, zero, zero, lam, eq.chart)
    assert names == ["load_gust_x", "load_gust_y", "load_gust_z"] and units == ["N/m"] * 3
    load = next(a for a in system.attachments if isinstance(a, SpanLoad))
    assert load.stations[0] > 0.3 and load.stations[-1] < 1.1  # the table's range only
    J = central_difference(lambda x: system.centre_line_at(x, eq.chart, load.stations).ravel(), eq.x, 1e-6)
    J = J.reshape(load.stations.size, 3, system.nx)
    R = system.root_pose(0, eq.x, eq.chart)[1] if axes == "section" else np.eye(3)
    expected = np.einsum("s,sjn,ja->na", load.weights, J, R)
    assert np.max(np.abs(expected)) > 0.1
    np.testing.assert_allclose(B, expected, atol=1e-7)


def cantilever(*overrides):
    """The reference plate clamped to a fixed hub, twist 90 deg (weak axis along global y:
    EI = 70e9 0.05 0.0025^3 / 12 = 4.557 N m^2, L = 1.45 m), no gravity, a span load named
    span1."""
    return load_example("cantilever", NO_GRAVITY + ['analysis.kind="static"', "analysis.load_steps=1",
                                                    *overrides])


EI = 70e9 * 0.05 * 0.0025**3 / 12
L = 1.45


def test_the_dc_gain_of_load_inputs_is_beam_theory_and_the_static_run():
    """About the straight cantilever: the DC gain of ``load_span1_y`` (N/m) and ``load_tip_y``
    (N) on the tip's vertical deflection equals L^4 / (8 EI) and L^3 / (3 EI) (Euler-Bernoulli;
    the cubic elements are exact for these loads at the nodes), and the gain times a small load
    equals ``static`` with that load (the span load's force, the constant tip force)."""
    sc = cantilever("loads.span=[{force = [0.0, 0.0, 0.0]}]")
    model = api.linearize(sc, inputs=["load:span1", "load:tip"])
    assert model.inputs == ["load_span1_x", "load_span1_y", "load_span1_z", "load_tip_x", "load_tip_y", "load_tip_z"]
    assert model.input_units == ["N/m"] * 3 + ["N"] * 3
    gain = model.dc_gain()[model.outputs.index("tip_vertical")]
    assert gain[1] == pytest.approx(L**4 / (8 * EI), rel=1e-8)
    assert gain[4] == pytest.approx(L**3 / (3 * EI), rel=1e-8)
    q, P = 1e-4, 1e-4  # 12 um and 22 um at the tip: linear to ~1e-10 (measured 8e-12, 2e-10)
    span = api.static(cantilever(f"loads.span=[{{force = [0.0, {q}, 0.0]}}]")).to_dict()["tip_displacement"]["vertical"]
    tip = api.static(cantilever("loads.span=[{force = [0.0, 0.0, 0.0]}]",
                                f"loads.tip_force=[0.0, {P}, 0.0]")).to_dict()["tip_displacement"]["vertical"]
    assert span == pytest.approx(gain[1] * q, rel=1e-8)
    assert tip == pytest.approx(gain[4] * P, rel=1e-8)


def test_unknown_load_inputs_and_a_span_load_named_tip_are_refused():
    sc = cantilever("loads.span=[{name = 'gust', force = [0.0, 1.0, 0.0]}]")
    with pytest.raises(ScenarioError, match="load:wind: no load of that name .loads: tip, gust."):
        api.linearize(sc, inputs=["load:wind"])
    with pytest.raises(ScenarioError, match="'tip' names the tip loads"):
        cantilever("loads.span=[{name = 'tip', force = [0.0, 1.0, 0.0]}]")
