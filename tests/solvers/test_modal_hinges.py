"""Hinged rotating blades (solvers/modal.py with joints): the rigid-blade hinge frequencies of
helicopter theory, an independent finite-element model of a hinged rotating Euler-Bernoulli beam
(written here: centrifugal tension, in-plane softening for lag), the lag damper's damping ratio,
and the hinge labels."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import eigh

from hubbeam.elements.section import Section, saint_venant_torsion_constant
from hubbeam.solvers.modal import rotating_modal_analysis
from hubbeam.solvers.mode_shapes import energy_fractions, mode_label
from hubbeam.solvers.static import solve_static
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.beam import AncfBeam
from hubbeam.system.joints import Joint
from hubbeam.system.laws import DriveProfile
from hubbeam.system.mount import Mount
from hubbeam.system.multibody import Hub, MultibodySystem

RHO, E = 2700.0, 70e9


def _blade(length, width, thickness, elements, joint, offset, omega, twist=0.0):
    section = Section(width, thickness, RHO, E, E / 2.6, saint_venant_torsion_constant(width, thickness))
    part = AncfPart(AncfBeam(length, elements, section), Mount(offset, twist, 0.0, 0.0, joint=joint))
    return MultibodySystem([part], Hub("prescribed", 1.0, drive=DriveProfile.constant(omega)))


def _rotating_modes(system, omega, count):
    steady = solve_static(system, load_steps=4, spin=omega)
    modes = rotating_modal_analysis(system, steady, omega, count=count)
    labels = [mode_label(energy_fractions(system, steady.x, steady.chart, u)) for u in modes.shapes.T]
    return modes.frequencies_hz, labels


@pytest.mark.parametrize("axis", ["flap", "lag"])
def test_a_stiff_blade_on_a_hinge_has_the_rigid_blade_frequencies(axis):
    """A stiff uniform blade of length L (a 30 mm square bar) hinged at radius e with a hinge
    spring k, at three speeds: the rigid body's hinge frequency, omega_beta^2 = (Omega^2 (I_b - I_a
    + e S) + k) / I_c (flap, about c) and omega_zeta^2 = (Omega^2 e S + k) / I_b (lag, about b), with
    S = m L / 2 and the blade's moments of inertia about the hinge I_c = m L^2 / 3 + rho I_n L,
    I_b = m L^2 / 3 + rho I_m L, I_a = rho (I_m + I_n) L (about its axis); for a thin blade these are
    omega_beta^2 = Omega^2 (1 + 3 e / (2 L)) + k / I and omega_zeta^2 = Omega^2 3 e / (2 L) + k / I.
    To 2e-4 (the blade's own flexibility in series with the spring), labelled by the hinge."""
    L, e, k, a = 1.0, 0.15, 2.0, 0.03
    m = RHO * a * a * L
    rotary = RHO * a**4 / 12 * L  # rho I L about either section axis of the square
    S, I_b, I_c, I_a = m * L / 2, m * L**2 / 3 + rotary, m * L**2 / 3 + rotary, 2 * rotary
    for omega in (5.0, 15.0, 30.0):
        system = _blade(L, a, a, 4, Joint.named(axis, stiffness=(k,)), e, omega)
        f, labels = _rotating_modes(system, omega, 1)
        if axis == "flap":
            w2 = (omega**2 * (I_b - I_a + e * S) + k) / I_c
        else:
            w2 = (omega**2 * e * S + k) / I_b
        assert f[0] == pytest.approx(np.sqrt(w2) / (2 * np.pi), rel=2e-4), omega
        assert labels[0] == f"{axis} hinge"
        thin = omega**2 * ((1.0 if axis == "flap" else 0.0) + 1.5 * e / L) + k / (m * L**2 / 3)
        assert np.sqrt(w2 / thin) == pytest.approx(1.0, abs=3e-4)  # the thin-blade formula


def _hinged_beam_fe(length, offset, omega, EI, rho_a, spring, softening, elements=40, count=4):
    """The lowest ``count`` frequencies (Hz) of a rotating uniform Euler-Bernoulli beam (EI, rho A),
    inextensible, pinned at radius ``offset`` with a torsional spring ``spring`` on its root slope:
    cubic Hermite elements, the centrifugal tension T(s) = rho A Omega^2 ((e + L)^2 - (e + s)^2) / 2
    as geometric stiffness int T w' dw' ds, and for in-plane (lag) bending the centrifugal softening
    -Omega^2 rho A int w dw ds (``softening``)."""
    h = length / elements
    n = 2 * (elements + 1)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    xg, wg = np.polynomial.legendre.leggauss(6)
    for el in range(elements):
        idx = slice(2 * el, 2 * el + 4)
        for xi, w in zip(xg, wg):
            t = 0.5 * (xi + 1.0)
            N = np.array([1 - 3 * t**2 + 2 * t**3, h * (t - 2 * t**2 + t**3), 3 * t**2 - 2 * t**3, h * (t**3 - t**2)])
            dN = np.array([-6 * t + 6 * t**2, h * (1 - 4 * t + 3 * t**2), 6 * t - 6 * t**2, h * (3 * t**2 - 2 * t)]) / h
            d2N = np.array([-6 + 12 * t, h * (-4 + 6 * t), 6 - 12 * t, h * (6 * t - 2)]) / h**2
            s = (el + t) * h
            T = 0.5 * rho_a * omega**2 * ((offset + length) ** 2 - (offset + s) ** 2)
            jac = 0.5 * w * h
            K[idx, idx] += jac * (EI * np.outer(d2N, d2N) + T * np.outer(dN, dN))
            M[idx, idx] += jac * rho_a * np.outer(N, N)
            if softening:
                K[idx, idx] -= jac * rho_a * omega**2 * np.outer(N, N)
    K[1, 1] += spring
    keep = np.arange(1, n)  # w(0) = 0: the hinge; the slope w'(0) is the hinge angle
    w2 = eigh(K[np.ix_(keep, keep)], M[np.ix_(keep, keep)], eigvals_only=True)
    return np.sqrt(w2[:count]) / (2 * np.pi)


@pytest.mark.parametrize("axis", ["flap", "lag"])
def test_a_flexible_hinged_blade_matches_an_independent_rotating_beam_model(axis):
    """A flexible blade (its first elastic mode at 2 to 3 times its hinge mode) hinged at radius
    e, turning at 12 rad/s: its hinge mode and first two elastic modes in the hinge's plane
    against the finite-element model above (40 elements), to 0.5 % (the ANCF beam is extensible
    and has the sections' rotary inertia; the model has neither)."""
    L, e, k, omega = 1.0, 0.1, 2.0, 12.0
    # twist 0: the width along j0; flap bends across the width (EI = E h b^3 / 12), lag across the
    # thickness (E b h^3 / 12): the blade thin in its hinge's plane
    width, thickness = (0.004, 0.05) if axis == "flap" else (0.05, 0.004)
    system = _blade(L, width, thickness, 10, Joint.named(axis, stiffness=(k,)), e, omega, twist=0.0)
    f, labels = _rotating_modes(system, omega, 8)
    EI = E * thickness * width**3 / 12 if axis == "flap" else E * width * thickness**3 / 12
    reference = _hinged_beam_fe(L, e, omega, EI, RHO * width * thickness, k, softening=axis == "lag", count=3)
    mine = [fi for fi, label in zip(f, labels) if axis in label][:3]
    assert np.allclose(mine, reference, rtol=5e-3), (mine, reference, labels)
    assert labels[0] == f"{axis} hinge"


def test_the_lag_damper_damps_the_lag_mode_as_the_rigid_blade_says():
    """A stiff blade on a lag hinge with a damper c, turning at 20 rad/s: linearize's damping ratio
    of the lag mode is c / (2 I omega_zeta), omega_zeta^2 = Omega^2 e S / I (to 1e-3)."""
    from hubbeam.analysis.state_space import linearise

    L, e, c, omega = 1.0, 0.15, 0.05, 20.0
    system = _blade(L, 0.004, 0.03, 4, Joint.named("lag", damping=(c,)), e, omega)  # deep in the hub plane
    steady = solve_static(system, load_steps=4, spin=omega)
    model = linearise(system, steady, omega, inputs=["tip_force"], sensors=[])
    f, zeta = model.modal_summary()
    m = RHO * 0.004 * 0.03 * L
    S, I = m * L / 2, m * L**2 / 3
    w_zeta = omega * np.sqrt(e * S / I)
    assert f[0] == pytest.approx(w_zeta / (2 * np.pi), rel=1e-3)
    assert zeta[0] == pytest.approx(c / (2 * I * w_zeta), rel=1e-3)
