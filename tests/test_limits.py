"""hubbeam.limits on scenarios with several beams (each beam checked, named as written) and with a
recorded state."""

import pytest

from hubbeam.errors import ScenarioError
from hubbeam.io.scenario import load_example
from hubbeam.limits import check_magnitudes, check_run, state_values


@pytest.mark.parametrize("name", ["rotor3", "spacecraft", "arm", "exp1"])
def test_the_bundled_scenarios_pass(name):
    check_magnitudes(load_example(name))  # no exception: every derived quantity is in range


def test_an_absurd_value_of_one_beam_names_that_beam():
    with pytest.raises(ScenarioError, match=r"^beams\[1\]\.width: with beams\[1\]\.width = 5\.6e\+102"):
        check_magnitudes(load_example("rotor3", ["beams[1].width=5.6e102"]))


def test_a_single_beam_is_named_beam():
    with pytest.raises(ScenarioError, match=r"^beam\.width: with beam\.width = 5\.6e\+102"):
        check_magnitudes(load_example("exp1", ["beam.width=5.6e102"]))


def test_a_beam_s_own_radius_is_named():
    with pytest.raises(ScenarioError, match=r"beams\[0\]\.radius = 1e\+160"):
        check_magnitudes(load_example("rotor3", ["beams[0].radius=1e160"]))


def test_a_recorded_state_is_counted_in_the_run_size():
    scenario = load_example("rotor3")
    assert state_values(scenario) == 1 + 3 * 10 * (4 * 4 + 1)  # hub angle; 3 blades x 17 stations x 10 numbers
    plain, state = check_run(scenario), check_run(scenario, state=True)
    assert state.records == plain.records and state.record_bytes > plain.record_bytes


@pytest.mark.parametrize("override", ["beams[0].tip_body.mass=1e300", "hub.torque.kp=1e300",
                                      "hub.torque.reference.angle=-1e300", "beams[1].tip_body.offset=[1e300,0,0]"])
def test_any_number_beyond_the_range_is_refused_naming_its_key(override):
    """A tip body of 1e300 kg gave a wrong answer with exit 0, a gain or an angle of 1e300 a
    'non-finite Newton increment' after the start (found by the adversarial pass)."""
    key = override.split("=")[0]
    with pytest.raises(ScenarioError, match="^" + key.replace("[", r"\[").replace("]", r"\]").replace(".", r"\.")
                       + ": .* outside the range"):
        check_magnitudes(load_example("spacecraft", [override]))
