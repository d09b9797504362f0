"""The dominant-frequency estimator on signals of known frequency."""

import numpy as np
import pytest

from hubbeam.analysis.frequency import dominant_frequency


@pytest.mark.parametrize("f0", [0.37, 0.9766, 1.0052, 3.9])
def test_pure_sinusoid_off_the_bin_grid(f0):
    t = np.arange(0, 20, 0.01)
    est = dominant_frequency(t, 2.0 + 0.3 * np.sin(2 * np.pi * f0 * t + 0.4))
    assert est.frequency_hz == pytest.approx(f0, abs=0.01 * est.resolution_hz)
    assert est.resolution_hz == pytest.approx(0.05)
    assert est.amplitude == pytest.approx(0.3, rel=0.02)


def test_damped_oscillation_about_a_drifting_mean():
    """exp1-like: a decaying oscillation about a mean that settles (the beam sags): the
    damped frequency f_d = f_n sqrt(1 - zeta^2) is what the estimate must return."""
    fn, zeta = 1.02, 0.03
    fd = fn * np.sqrt(1 - zeta**2)
    t = np.arange(0, 20, 0.01)
    y = 3.7e-4 * (1 - np.exp(-t / 3)) + 3e-4 * np.exp(-zeta * 2 * np.pi * fn * t) * np.cos(2 * np.pi * fd * t)
    est = dominant_frequency(t, y)
    assert est.frequency_hz == pytest.approx(fd, abs=0.1 * est.resolution_hz)


def test_noisy_signal_and_a_weaker_second_mode():
    rng = np.random.default_rng(0)
    t = np.arange(0, 30, 0.005)
    y = np.sin(2 * np.pi * 0.98 * t) + 0.3 * np.sin(2 * np.pi * 6.1 * t) + 0.5 * rng.standard_normal(t.size)
    est = dominant_frequency(t, y)
    assert est.frequency_hz == pytest.approx(0.98, abs=0.2 * est.resolution_hz)


def test_bad_input_is_refused_clearly():
    with pytest.raises(ValueError, match="uniformly"):
        dominant_frequency(np.array([0, 1, 3, 4, 5, 6, 7, 8.0]), np.zeros(8))
    with pytest.raises(ValueError, match="too short"):
        dominant_frequency(np.arange(8) * 0.1, np.ones(8), min_hz=100.0)
