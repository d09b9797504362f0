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


def test_a_python_torque_law_says_it_takes_the_python_steps():
    """Only a Python-callable torque law leaves the compiled path, and api.run says so; the
    same scenario with its own (compiled) PD law runs without a word."""
    import warnings

    import pytest

    from hubbeam.system.laws import TorqueLaw

    arm = load_example("arm", ["beam.elements=2", "analysis.t_end=0.02", 'analysis.start="rest"'])
    with pytest.warns(UserWarning, match="Python step path"):
        traj, failure = api.run(arm, torque=TorqueLaw.callable(lambda t, theta, omega: 1.0 - theta))
    assert failure is None and traj.factorisations is None  # the Python steps count no factorisations
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        traj, failure = api.run(arm)
    assert failure is None and traj.factorisations > 0
