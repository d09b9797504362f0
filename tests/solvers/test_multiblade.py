"""Multi-blade coordinates: the Coleman transformation against travelling waves written out by
hand, the harmonics of an eigenspace recovered from any basis of it, and the fixed-frame reading
of each harmonic (frequencies and whirl sense; the time-domain check on a simulated rotor is in
tests/studies/test_campbell.py)."""

import numpy as np
import pytest

from hubbeam.solvers.multiblade import (check_azimuths, fixed_frame, harmonic_directions, harmonic_fractions,
                                        harmonic_label, harmonic_orders, to_multiblade)


@pytest.mark.parametrize("blades", [3, 4, 5, 6])
def test_orders_cover_the_blades_once(blades):
    orders = harmonic_orders(blades)
    assert len(orders) == blades and orders[0] == 0
    assert sorted(np.mod(orders, blades)) == list(range(blades))  # one of each residue: a complete DFT


@pytest.mark.parametrize("blades", [3, 4, 5])
def test_a_travelling_wave_whirls_at_omega_plus_or_minus_the_speed(blades):
    """Blade k at its place psi0_k = 0.3 + 2 pi k / N on the rotor moves as q_k = cos(w t - n psi0_k)
    in the rotating frame (a wave of n nodal diameters running forward over the blades); with the
    azimuths psi_k = Omega t + psi0_k its cyclic pair q_nc + i q_ns is exp(i (w + n Omega) t); the
    backward wave cos(w t + n psi0_k) gives exp(i (n Omega - w) t); written out by hand (MBC3)."""
    w, big_omega = 7.0, 3.0
    t = np.linspace(0.0, 2.0, 101)
    place = 0.3 + 2 * np.pi * np.arange(blades)[None, :] / blades
    psi = big_omega * t[:, None] + place
    for n in range(1, (blades - 1) // 2 + 1):
        forward = to_multiblade(np.cos(w * t[:, None] - n * place), psi)
        backward = to_multiblade(np.cos(w * t[:, None] + n * place), psi)
        column = 2 * n - 1
        assert np.allclose(forward[:, column] + 1j * forward[:, column + 1], np.exp(1j * (w + n * big_omega) * t))
        assert np.allclose(backward[:, column] + 1j * backward[:, column + 1], np.exp(1j * (n * big_omega - w) * t))
        assert np.allclose(forward[:, 0], 0.0) and np.allclose(backward[:, 0], 0.0)  # no collective


def test_collective_and_differential_are_the_blade_mean_and_alternating_mean():
    q = np.array([1.0, 2.0, 5.0, -3.0])
    psi = np.radians([10.0, 100.0, 190.0, 280.0])
    out = to_multiblade(q, psi)
    assert out[0] == pytest.approx(q.mean()) and out[-1] == pytest.approx(np.mean(q * [1, -1, 1, -1]))
    # and the transformation is invertible: the blades back from the coordinates
    back = out[0] + out[1] * np.cos(psi) + out[2] * np.sin(psi) + out[3] * np.array([1, -1, 1, -1])
    assert np.allclose(back, q)


def test_azimuths_must_be_evenly_spaced_in_order():
    assert np.allclose(check_azimuths(np.radians([30, 150, 270])), np.radians([30, 150, 270]))
    assert np.allclose(check_azimuths(np.radians([300, 60, 180])), np.radians([300, 60, 180]))  # across 360
    for bad in ([0, 240, 120], [0, 120, 250], [0, 90, 180]):
        with pytest.raises(ValueError, match="evenly spaced"):
            check_azimuths(np.radians(bad))


@pytest.mark.parametrize("blades", [3, 4, 5])
def test_the_harmonics_of_an_eigenspace_are_found_in_any_basis_of_it(blades):
    """N blades with one blade mode s (complex): the eigenspace is spanned by blade k moving
    alone; any mixture of those is a basis of it. The directions found are the N pure harmonics
    (patterns s e^{-i p psi_k}), each with purity 1, whatever the mixture."""
    rng = np.random.default_rng(blades)
    psi = 0.4 + 2 * np.pi * np.arange(blades) / blades
    shape = rng.normal(size=6) + 1j * rng.normal(size=6)
    alone = np.zeros((blades, blades, 6), dtype=complex)
    for k in range(blades):
        alone[k, k] = shape
    mix = rng.normal(size=(blades, blades)) + 1j * rng.normal(size=(blades, blades))
    modes = np.einsum("ij,jkm->ikm", mix, alone)  # mode i = sum_j mix_ij (blade j alone)
    found = harmonic_directions(modes, psi)
    assert sorted(p for p, _, _ in found) == sorted(harmonic_orders(blades))
    for p, c, purity in found:
        assert purity == pytest.approx(1.0, abs=1e-10)
        pattern = np.einsum("i,ikm->km", c, modes)
        fractions = harmonic_fractions(pattern, psi)
        assert fractions[p] == pytest.approx(1.0, abs=1e-10)
        # the pattern is the blade mode times e^{-i p psi_k}, up to one complex factor
        ratio = pattern / (np.exp(-1j * p * psi)[:, None] * shape[None, :])
        assert np.allclose(ratio, ratio[0, 0])


def test_a_mixed_pattern_is_not_a_harmonic():
    psi = 2 * np.pi * np.arange(3) / 3
    blade_one = np.zeros((1, 3, 2))
    blade_one[0, 0] = [1.0, 0.5]  # one blade alone: a third of each harmonic
    assert harmonic_directions(blade_one, psi) == []
    assert all(v == pytest.approx(1 / 3) for v in harmonic_fractions(blade_one[0], psi).values())


def test_fixed_frame_frequencies_and_whirl():
    omega = 2 * np.pi  # 1 Hz
    assert fixed_frame(3.0, 0, 3, omega)[0] == 3.0 and fixed_frame(3.0, 2, 4, omega)[0] == 3.0  # collective, differential
    f, whirl = fixed_frame(np.array([3.0, 0.4]), 1, 3, omega)
    assert np.allclose(f, [4.0, 1.4]) and list(whirl) == ["forward", "forward"]
    f, whirl = fixed_frame(np.array([3.0, 0.4]), -1, 3, omega)  # regressive: backward above 1P, forward below
    assert np.allclose(f, [2.0, 0.6]) and list(whirl) == ["backward", "forward"]
    f, whirl = fixed_frame(3.0, -2, 5, omega)
    assert f == pytest.approx(1.0) and whirl == "backward"
    assert [harmonic_label(p, 5, "fixed") for p in harmonic_orders(5)] == [
        "collective", "progressive", "regressive", "progressive cyclic-2", "regressive cyclic-2"]
    assert [harmonic_label(p, 4, "rotating") for p in harmonic_orders(4)] == ["collective", "cyclic", "cyclic",
                                                                              "differential"]
