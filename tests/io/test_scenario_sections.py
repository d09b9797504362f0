"""Scenario keys of span-wise sections and structural damping: [[beams.sections]] and
[beams.damping]; their resolution into SpanSections and their errors (one line naming the key)."""

import copy
import math

import numpy as np
import pytest

from hubbeam.elements.section import COLUMN, SectionForm
from hubbeam.io.scenario import ScenarioError, apply_overrides, validate

BEAM = {"formulation": "ancf", "elements": 3, "length": 1.0, "width": 0.05, "thickness": 0.004, "density": 2700.0,
        "youngs_modulus": 70.0e9, "poisson_ratio": 0.25}
RECTANGLES = [{"x": 0.0, "width": 0.08, "thickness": 0.004}, {"x": 0.4, "width": 0.06, "thickness": 0.003, "pretwist": 8.0},
              {"x": 1.0, "width": 0.04, "thickness": 0.002, "pretwist": 20.0}]
CONSTANTS = [{"x": 0.0, "EA": 8.75e6, "GJ": 6.6, "EI_y": 4.56, "EI_z": 1823.0, "rho_A": 0.3375,
              "rho_I": [7.05e-5, 1.76e-7, 7.03e-5]},
             {"x": 1.0, "EA": 4.0e6, "GJ": 3.0, "EI_y": 2.0, "EI_z": 900.0, "rho_A": 0.2,
              "rho_I": [4e-5, 1e-7, 4e-5], "width": 0.03, "pretwist": -10.0}]


def scenario(sections=RECTANGLES, damping=None, many=True) -> dict:
    beam = dict(BEAM, sections=copy.deepcopy(sections))
    if damping is not None:
        beam["damping"] = {"stiffness_proportional": damping}
    data = {"name": "s", "hub": {"motion": "fixed"}, "analysis": {"kind": "static"},
            "sensors": [{"name": "g", "kind": "surface_strain", "x": 0.7, "surface": "upper"}]}
    data["beams" if many else "beam"] = [beam] if many else beam
    return data


def error_of(data, overrides=()) -> str:
    with pytest.raises(ScenarioError) as info:
        validate(apply_overrides(data, list(overrides)))
    msg = str(info.value)
    assert "\n" not in msg
    return msg


def test_rectangle_stations_resolve_to_a_table_with_the_beam_material():
    spec = validate(scenario(damping=2e-3)).resolved_beams()[0]
    table = spec.sections
    assert table.form is SectionForm.RECTANGLE
    assert list(table.x) == [0.0, 0.4, 1.0]
    assert table.pretwist == pytest.approx(np.radians([0.0, 8.0, 20.0]))
    row = table.at(0.2)  # halfway to the second station: b = 0.07, h = 0.0035
    assert row[COLUMN["EI_y"]] == pytest.approx(70e9 * 0.07 * 0.0035**3 / 12)
    assert row[COLUMN["GJ"]] == pytest.approx(70e9 / 2.5 * 0.07 * 0.0035**3 / 3 * (1 - 0.63 * 0.0035 / 0.07))
    assert spec.structural_damping == 2e-3


def test_constant_stations_take_the_beam_width_and_thickness_where_not_given():
    spec = validate(scenario(CONSTANTS, many=False)).resolved_beams()[0]
    table = spec.sections
    assert table.form is SectionForm.CONSTANTS
    assert table.at(0.0)[COLUMN["width"]] == 0.05 and table.at(1.0)[COLUMN["width"]] == 0.03
    assert table.at(1.0)[COLUMN["thickness"]] == 0.004
    assert table.at(0.5)[COLUMN["EI_z"]] == pytest.approx((1823.0 + 900.0) / 2)
    assert table.at(1.0)[COLUMN["I_m"]] == 1e-7
    assert spec.structural_damping == 0.0


def test_a_beam_without_stations_has_none():
    spec = validate(scenario(None) | {"beams": [BEAM]}).resolved_beams()[0]
    assert spec.sections is None and spec.structural_damping == 0.0


@pytest.mark.parametrize("change,key", [
    ({2: {"x": 0.3}}, "beams[0].sections[2].x"),  # not ascending
    ({0: {"x": 0.1}}, "beams[0].sections[0].x"),  # not at the root
    ({2: {"x": 0.9}}, "beams[0].sections[2].x"),  # not at the length
    ({0: {"pretwist": 5.0}}, "beams[0].sections[0].pretwist"),
    ({1: {"width": -0.01}}, "beams[0].sections[1].width"),
    ({1: {"thickness": None}}, "beams[0].sections[1].thickness"),
    ({1: {"EA": 1e6}}, "beams[0].sections[1].GJ"),  # a constants station missing its other constants
    ({2: {"width": float("nan")}}, "beams[0].sections[2].width"),
    ({1: {"colour": "red"}}, "beams[0].sections[1].colour"),
])
def test_bad_stations_name_their_key(change, key):
    sections = copy.deepcopy(RECTANGLES)
    for i, values in change.items():
        for k, v in values.items():
            if v is None:
                sections[i].pop(k)
            else:
                sections[i][k] = v
    assert error_of(scenario(sections)).startswith(f"{key}:")


def test_one_form_per_beam():
    mixed = [RECTANGLES[0], dict(CONSTANTS[1])]
    assert error_of(scenario(mixed)).startswith("beams[0].sections[1]:")


def test_one_station_is_not_a_table():
    assert error_of(scenario(RECTANGLES[:1])).startswith("beams[0].sections:")


def test_damping_must_be_non_negative_and_known():
    assert error_of(scenario(damping=-1.0)).startswith("beams[0].damping.stiffness_proportional:")
    data = scenario()
    data["beams"][0]["damping"] = {"mass_proportional": 1.0}
    assert error_of(data).startswith("beams[0].damping.mass_proportional:")


def test_a_rectangle_table_refuses_a_torsion_constant():
    data = scenario()
    data["beams"][0]["torsion_constant"] = 1e-10
    assert error_of(data).startswith("beams[0].torsion_constant:")


def test_sensor_bounds_use_the_section_at_the_station():
    data = scenario()
    data["sensors"] = [{"name": "g", "kind": "surface_strain", "x": 1.0, "y": 0.0, "z": 0.0015}]  # h(1) = 2 mm
    assert error_of(data).startswith("sensors[0].z:")
    data["sensors"][0]["x"] = 0.0  # h(0) = 4 mm
    validate(data)


def test_set_reaches_a_station():
    spec = validate(apply_overrides(scenario(), ["beams[0].sections[1].width=0.03",
                                                 "beams[0].damping.stiffness_proportional=1e-3"])).resolved_beams()[0]
    assert spec.sections.values[1, 0] == 0.03 and spec.structural_damping == 1e-3
    assert error_of(scenario(), ["beams[0].sections[1].x=2.0"]).startswith("beams[0].sections[1].x:")
    single = validate(apply_overrides(scenario(many=False), ["beam.sections[2].pretwist=30"])).resolved_beams()[0]
    assert single.sections.pretwist[2] == pytest.approx(math.radians(30.0))
