"""limits.check_magnitudes on scenarios with several beams (each beam checked, named as written)."""

import pytest

from hubbeam.errors import ScenarioError
from hubbeam.io.scenario import load_example
from hubbeam.limits import check_magnitudes


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
