"""hubbeam.limits on scenarios with several beams and with a recorded state."""

import pytest

from hubbeam.errors import ScenarioError
from hubbeam.io.scenario import load_example
from hubbeam.limits import check_magnitudes, check_run, state_values


def test_every_beam_of_several_is_checked_and_named():
    check_magnitudes(load_example("rotor3"))  # three sound blades pass
    with pytest.raises(ScenarioError, match=r"^beams\[1\]\.width: .*beams\[1\]\.width = 1e\+102"):
        check_magnitudes(load_example("rotor3", ["beams[1].width=1e102"]))
    with pytest.raises(ScenarioError, match=r"^beam\.width: "):
        check_magnitudes(load_example("exp1", ["beam.width=1e102"]))


def test_a_recorded_state_is_counted_in_the_run_size():
    scenario = load_example("rotor3")
    assert state_values(scenario) == 1 + 3 * 10 * (4 * 4 + 1)  # hub angle; 3 blades x 17 stations x 10 numbers
    plain, state = check_run(scenario), check_run(scenario, state=True)
    assert state.records == plain.records and state.record_bytes > plain.record_bytes
