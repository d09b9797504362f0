"""The reproduction's plan: the formulations of its columns (the modal FFR one beside nodal FFR and
ANCF) and the runs each table needs."""

import pytest

from hubbeam.io.scenario import load_example
from hubbeam.reproduce import tables
from hubbeam.reproduce.plan import FORMULATIONS, MODAL_MODES, Case, Plan


@pytest.mark.parametrize("form, expected", [("ancf", ("ancf", False, None)), ("ffr", ("ffr", False, None)),
                                            ("ffr+", ("ffr", True, None)), ("ffr-modal", ("ffr", True, MODAL_MODES))])
def test_each_formulation_makes_its_beam(form, expected):
    beam = load_example("exp2", Case("exp2", form, 7).overrides()).resolved_beams()[0]
    assert (beam.formulation, beam.geometric_stiffening, beam.modes) == expected
    assert beam.elements == 7


def test_modal_column_beside_nodal_ffr_in_every_table():
    plan = Plan.quick()
    fine = plan.fine["ffr"]
    assert ("ffr-modal", fine) in plan.table2_cases() and ("ffr-modal", fine) in plan.table5_cases()
    assert {form for _, form in plan.table3_cases()} == {"ancf", "ffr", "ffr+", "ffr-modal"}
    assert {(omega, "ffr-modal") for omega in plan.speeds} <= set(plan.table6_cases())
    # the modal FFR runs reduce the fine nodal FFR mesh
    assert all(c.elements == fine for (_, form), c in plan.table6_cases().items() if form.startswith("ffr"))
    keys = [c.key for c in plan.cases()]
    assert len(keys) == len(set(keys)) == 46  # 34 before: + exp1 x 3 thicknesses x 2 + exp2 x 6 speeds
    assert set(FORMULATIONS) == {"ancf", "ffr", "ffr+", "ffr-modal"}


def test_modal_dof_counts_the_models_elastic_coordinates():
    from hubbeam import api

    for n in (3, 7):
        system = api.build_system(load_example("exp1", Case("exp1", "ffr-modal", n).overrides()))
        assert system.beams[0].ndof == tables._dof("ffr-modal", n)  # its elastic coordinates alone
    assert tables._dof("ffr", 7) == 42 and tables._dof("ancf", 6) == 56  # the paper's counts
