"""Span-wise section tables: the interpolation rule of docs/scenario.md against hand-computed
rectangle constants, and the uniform table against the prismatic section."""

import numpy as np
import pytest

from hubbeam.elements.section import COLUMN, Section, SectionForm, SpanSections, saint_venant_torsion_constant

E, G, RHO = 70e9, 70e9 / 2.66, 2700.0


def plate(b, h):
    return Section(b, h, RHO, E, G, saint_venant_torsion_constant(b, h))


def test_a_tapered_rectangle_interpolates_its_dimensions_not_its_constants():
    table = SpanSections(np.array([0.0, 2.0]), SectionForm.RECTANGLE, [[0.08, 0.004], [0.04, 0.002]], [0.0, 0.0],
                         material=plate(0.08, 0.004))
    row = table.at(0.5)  # a quarter of the way: b = 0.07, h = 0.0035
    b, h = 0.07, 0.0035
    assert row[COLUMN["width"]] == pytest.approx(b) and row[COLUMN["thickness"]] == pytest.approx(h)
    assert row[COLUMN["EA"]] == pytest.approx(E * b * h)
    assert row[COLUMN["EI_y"]] == pytest.approx(E * b * h**3 / 12)  # bending along the thin direction
    assert row[COLUMN["EI_z"]] == pytest.approx(E * h * b**3 / 12)
    assert row[COLUMN["GJ"]] == pytest.approx(G * b * h**3 / 3 * (1 - 0.63 * h / b))
    assert row[COLUMN["rho_A"]] == pytest.approx(RHO * b * h)
    assert row[COLUMN["I_tau"]] == pytest.approx(RHO * (b * h**3 + h * b**3) / 12)
    # the stiffness is not the mean of the end values (EI_y ~ h^3 is convex along a linear taper)
    ends = table.at([0.0, 2.0])[:, COLUMN["EI_y"]]
    assert row[COLUMN["EI_y"]] < 0.75 * ends[0] + 0.25 * ends[1]


def test_constants_and_pretwist_interpolate_linearly():
    rows = np.array([[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 0.1, 0.01], [3.0, 2.0, 1.0, 0.0, 5.0, 6.0, 7.0, 8.0, 0.3, 0.03]])
    table = SpanSections(np.array([0.0, 1.0, 3.0]), SectionForm.CONSTANTS, np.vstack([rows, rows[1]]),
                         np.radians([0.0, 10.0, 30.0]))
    assert table.at(0.25)[:10] == pytest.approx(0.75 * rows[0] + 0.25 * rows[1])
    assert table.at(2.0)[COLUMN["pretwist"]] == pytest.approx(np.radians(20.0))
    assert table.pretwist_rate([0.5, 2.0]) == pytest.approx(np.radians([10.0, 10.0]))
    assert not table.is_uniform


def test_the_uniform_table_is_the_prismatic_section():
    section = Section(0.05, 0.0025, RHO, E, G, 1.234e-10)  # a torsion constant given, not Saint-Venant's
    table = SpanSections.uniform(section, 1.45)
    assert table.is_uniform
    for row in table.at(np.linspace(0.0, 1.45, 7)):
        assert tuple(row[:4]) == section.stiffness
        assert row[COLUMN["rho_A"]] == section.mass_per_length and row[COLUMN["pretwist"]] == 0.0


@pytest.mark.parametrize("x", [[0.1, 1.0], [0.0, 1.0, 1.0], [0.0]])
def test_stations_must_start_at_the_root_and_increase(x):
    with pytest.raises(ValueError, match="stations"):
        SpanSections(np.array(x), SectionForm.CONSTANTS, np.ones((len(x), 10)), np.zeros(len(x)))
