"""Campbell diagram: labels at every speed and MAC tracking through a crossing of a flap and a
lag branch, against Southwell's closed form of the rotating cantilever."""

import numpy as np
import pytest

from hubbeam import api
from hubbeam.studies.campbell import campbell

#: a near-square blade laid flat: at rest the first lag frequency is w/t = 1.1 times the first
#: flap frequency; flap stiffens as f^2 = f0^2 + K (Omega / 2 pi)^2, lag as f0^2 + (K - 1) (...)^2
CROSSING = """
name = "crossing"
[beam]
formulation = "ancf"
elements = 4
length = 1.0
width = 0.011
thickness = 0.010
density = 2700.0
youngs_modulus = 70.0e9
poisson_ratio = 0.33
[hub]
motion = "fixed"
radius = 0.0
twist = 90.0
[environment]
gravity = [0.0, 0.0, 0.0]
"""
#: Southwell coefficient of the first flap mode of a uniform cantilever on the axis (Wright et
#: al. 1982: 3.6816^2 - 3.5160^2 at lambda = 1)
SOUTHWELL = 3.6816**2 - 3.5160**2


@pytest.fixture(scope="module")
def crossing(tmp_path_factory):
    path = tmp_path_factory.mktemp("campbell") / "crossing.toml"
    path.write_text(CROSSING)
    speeds = np.linspace(0.0, 50.0, 6)
    return speeds, campbell(api.load_scenario(path), speeds, count=3, formulations=("ancf",))


def test_tracked_branches_keep_their_label_through_the_crossing(crossing):
    _, ds = crossing
    tracked = ds["tracked_frequency_hz"].sel(formulation="ancf").values
    labels = ds["tracked_label"].sel(formulation="ancf").values
    assert list(ds["branch_label"].sel(formulation="ancf").values) == ["flap", "lag", "flap"]
    assert all(set(labels[:, b]) == {name} for b, name in enumerate(("flap", "lag", "flap")))
    assert np.all(np.diff(tracked, axis=0) > 0)  # every branch rises with the speed
    assert np.all(ds["mac"].sel(formulation="ancf").values > 0.95)
    # the sorted modes swap: flap first at rest, lag first at the top speed
    sorted_labels = ds["label"].sel(formulation="ancf").values
    assert list(sorted_labels[0, :2]) == ["flap", "lag"] and list(sorted_labels[-1, :2]) == ["lag", "flap"]
    f_sorted = ds["frequency_hz"].sel(formulation="ancf").values
    assert np.allclose(f_sorted[-1, :2], tracked[-1, [1, 0]])


def test_tracked_branches_follow_southwell(crossing):
    speeds, ds = crossing
    f = ds["tracked_frequency_hz"].sel(formulation="ancf").values
    rev = speeds / (2 * np.pi)
    flap = np.sqrt(f[0, 0] ** 2 + SOUTHWELL * rev**2)
    lag = np.sqrt(f[0, 1] ** 2 + (SOUTHWELL - 1.0) * rev**2)
    assert np.allclose(f[:, 0], flap, rtol=1e-2)
    assert np.allclose(f[:, 1], lag, rtol=1e-2)
    assert f[0, 1] / f[0, 0] == pytest.approx(1.1, rel=2e-3)  # EI ratio (w/t)^2, frequency ratio w/t


def test_a_free_hub_with_a_torque_law_and_its_sensors_gets_a_diagram():
    """The bundled spacecraft (free hub, PD law, an applied-torque sensor) was refused: each
    speed's driven variant kept the free hub's sensors."""
    from hubbeam.io.scenario import load_example

    result = campbell(load_example("spacecraft"), np.array([0.0, 1.0]), count=2, formulations=("ancf",))
    first = result["frequency_hz"].values[0, :, 0]
    assert np.all(np.isfinite(first)) and first[1] > first[0]  # the spin stiffens the panels
