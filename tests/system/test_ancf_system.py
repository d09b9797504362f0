"""The hub-beam system: steady rotation rates, the centrifugal load and the rotating steady state."""

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from hubbeam.api import tip_displacement
from hubbeam.elements.section import Section
from hubbeam.solvers.generalized_alpha import init
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.laws import DriveProfile
from hubbeam.system.multibody import single_beam_system
from tests.conftest import L, plate, rotation


def spinning(section, omega, twist=np.pi / 4, radius=0.35, gravity=(0, -9.81, 0), elements=4):
    return single_beam_system(AncfBeam(L, elements, section), radius=radius, twist=twist, motion="prescribed",
                         drive=DriveProfile("constant", omega), gravity=np.array(gravity))


def test_steady_rotation_rates_turn_the_section_frames_rigidly():
    """Advance x by (rates) * eps: every section frame along the bent beam must be the old
    frame turned by eps about -j0 (checked through frame_at, which knows nothing of the rates)."""
    system = spinning(plate(), 3.0)
    sol = solve_static(system, spin=3.0)
    x, F = sol.x, sol.chart
    eps = 1e-6
    v, _ = system.steady_rotation_rates(x, F, 1.0)
    R = rotation([0, -1, 0], eps)
    for station in (0.0, 0.4, 1.1, L):
        turned = system.beam.frame_at(x[1:] + eps * v[1:], F[0], station)
        assert np.max(np.abs(turned - R @ system.beam.frame_at(x[1:], F[0], station))) < 1e-11


def test_rates_refuse_a_chart_not_on_the_axis():
    system = spinning(plate(), 3.0)
    x, F = system.initial_state(0.0)
    with pytest.raises(ValueError, match="axis chart"):
        system.steady_rotation_rates(x, F, 1.0)


def test_centrifugal_stretch_of_a_straight_beam_matches_the_axial_solution():
    """No gravity, no twist: u(L) = rho w^2 / (2 E) ((R + L)^2 L - ((R + L)^3 - R^3) / 3)."""
    soft = Section(0.05, 0.0025, 2700.0, 7e7, 2.6e7, 1e-10)  # a soft material: a measurable stretch
    omega, R = 4.0, 0.35
    system = spinning(soft, omega, twist=0.0, radius=R, gravity=(0, 0, 0), elements=8)
    sol = solve_static(system, spin=omega)
    u = tip_displacement(system, sol.x)
    exact = 2700.0 * omega**2 / (2 * 7e7) * ((R + L) ** 2 * L - ((R + L) ** 3 - R**3) / 3)
    assert u["radial"] == pytest.approx(exact, rel=2e-3)  # linear axial theory; the stretch is 0.5 %
    assert abs(u["vertical"]) < 1e-12 and abs(u["tangential"]) < 1e-12


def test_centrifugal_stiffening_of_the_gravity_sag_matches_the_rotating_beam_equation():
    """Weak axis vertical (twist 90 deg), a stiff section so that the sag is small: the tip sag
    against EI w'''' - (N w')' = -rho A g, N = rho A w^2 ((R + L)^2 - (R + x)^2) / 2 (scipy BVP)."""
    section = plate(thickness=0.01)
    omega, R, g = 6.0, 0.35, 9.81
    system = spinning(section, omega, twist=np.pi / 2, radius=R, gravity=(0, -g, 0), elements=8)
    sol = solve_static(system, spin=omega)
    sag = tip_displacement(system, sol.x)["vertical"]
    EI, rhoA = section.stiffness[2], section.mass_per_length

    def rhs(x, y):
        N = rhoA * omega**2 * ((R + L) ** 2 - (R + x) ** 2) / 2
        return np.vstack([y[1], y[2] / EI, y[3] + N * y[1], -rhoA * g * np.ones_like(x)])

    xs = np.linspace(0, L, 60)
    bvp = solve_bvp(rhs, lambda a, b: np.array([a[0], a[1], b[2], b[3]]), xs, np.zeros((4, xs.size)), tol=1e-10)
    still = solve_static(spinning(section, omega, twist=np.pi / 2, radius=R, elements=8))
    assert sag == pytest.approx(bvp.sol(L)[0], rel=2e-3)
    assert abs(sag) < 0.95 * abs(tip_displacement(system, still.x)["vertical"])  # 9 %, well above the tolerance


def test_consistent_accelerations_of_the_steady_state_are_the_rigid_ones():
    """At the steadily rotating equilibrium the equations of motion, solved for xdd, must give
    back the centripetal accelerations of rigid rotation."""
    system = spinning(plate(), 3.0)
    sol = solve_static(system, spin=3.0)
    v, acc = system.steady_rotation_rates(sol.x, sol.chart, 3.0)
    state = init(system, sol.x, sol.chart, v0=v)
    assert np.max(np.abs(state.xdd - acc)) < 1e-5 * np.max(np.abs(acc))
