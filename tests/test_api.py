"""The plain-Python API: warnings about what a modally reduced FFR beam may miss."""

from hubbeam import api
from hubbeam.io.scenario import load_example

FFR = ['beam.formulation="ffr"']


def test_too_few_modes_are_reported_enough_are_not():
    few = api.reduction_warnings(load_example("exp1", FFR + ["beam.modes=1"]))
    assert len(few) == 1 and "beam1" in few[0] and "static tip deflection" in few[0] and "beam.modes" in few[0]
    assert api.reduction_warnings(load_example("exp1", FFR + ["beam.modes=8"])) == []
    assert api.reduction_warnings(load_example("exp1", FFR)) == []  # nodal: nothing is left out
    assert api.reduction_warnings(load_example("exp1")) == []  # ANCF


def test_a_fast_drive_above_the_kept_modes_is_reported():
    """exp2 spins up over T = 100 s (0.02 Hz): far below any mode; the same profile over 0.05 s
    excites up to about 40 Hz, above what two modes of the plate reach (about 6 Hz)."""
    slow = load_example("exp2", FFR + ["beam.modes=2"])
    assert not any("excites" in w for w in api.reduction_warnings(slow))
    fast = load_example("exp2", FFR + ["beam.modes=2", "hub.drive.T=0.05", "hub.drive.t1=0.04"])
    assert any("excites up to about 40 Hz" in w for w in api.reduction_warnings(fast))
