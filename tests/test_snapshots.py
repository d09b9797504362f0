"""The recorded state (hubbeam.snapshots) against geometry and beam theory known without the code:
the straight start, the mount's section frame, the tangent of the centre line, and the
surface strain of a cantilever under a tip force."""

from types import SimpleNamespace

import numpy as np
import pytest

from hubbeam import api
from hubbeam.io.scenario import load_example
from hubbeam.snapshots import POINTS_PER_ELEMENT, StateRecorder


def _run(name, overrides):
    scenario = load_example(name, overrides)
    traj, failure = api.run(scenario, state=True)
    assert failure is None
    return scenario, traj


def test_the_state_at_t0_is_the_undeformed_beam_of_exp1():
    """exp1 starts straight: root at R i_h, tip at R + L along it, stations evenly spaced,
    section frame of the 45 deg twist: m = (j0 - k_h)/sqrt 2, n = (j0 + k_h)/sqrt 2."""
    _, traj = _run("exp1", ["beam.elements=2", "analysis.t_end=0.02", "analysis.output_dt=0.01"])
    assert len(traj.snapshots) == len(traj.times) == 3
    first = traj.snapshots[0]
    assert first.hub_angle == 0.0
    beam = first.beams[0]
    R, L = 0.35, 1.45
    n = 2 * POINTS_PER_ELEMENT + 1
    expected = np.column_stack([np.linspace(R, R + L, n), np.zeros(n), np.zeros(n)])
    np.testing.assert_allclose(beam.centre_line, expected, atol=1e-12)
    s = np.sqrt(0.5)
    np.testing.assert_allclose(beam.m, np.tile([0.0, s, -s], (n, 1)), atol=1e-12)
    np.testing.assert_allclose(beam.n, np.tile([0.0, s, s], (n, 1)), atol=1e-12)
    np.testing.assert_allclose(beam.strain, 0.0, atol=1e-12)
    rec = traj.recorder
    np.testing.assert_allclose(rec.stations[0], np.linspace(0.0, L, n))
    np.testing.assert_allclose(rec.widths[0], 0.05)
    np.testing.assert_allclose(rec.thicknesses[0], 0.0025)
    # later: the beam falls under gravity (y < 0 at the tip), the root stays clamped at the hub
    last = traj.snapshots[-1].beams[0]
    assert last.centre_line[-1, 1] < -1e-4
    theta = traj.snapshots[-1].hub_angle
    np.testing.assert_allclose(last.centre_line[0], [R * np.cos(theta), 0.0, R * np.sin(theta)], atol=1e-9)


def test_every_blade_of_rotor3_starts_along_its_azimuth():
    """rotor3 from rest (not its gravity sag): blade k's root at R (cos psi, 0, sin psi), its tip at
    R + L along the same direction; laid flat (twist 90 deg): n = j0 and m = -k_k."""
    _, traj = _run("rotor3", ['analysis.start="rest"', "analysis.t_end=0.02", "analysis.output_dt=0.01"])
    R, L = 0.2, 1.0
    for beam, psi in zip(traj.snapshots[0].beams, np.radians([0.0, 120.0, 240.0])):
        i_k = np.array([np.cos(psi), 0.0, np.sin(psi)])
        k_k = np.array([-np.sin(psi), 0.0, np.cos(psi)])
        np.testing.assert_allclose(beam.centre_line[0], R * i_k, atol=1e-12)
        np.testing.assert_allclose(beam.centre_line[-1], (R + L) * i_k, atol=1e-12)
        np.testing.assert_allclose(beam.n, np.tile([0.0, 1.0, 0.0], (beam.n.shape[0], 1)), atol=1e-12)
        np.testing.assert_allclose(beam.m, np.tile(-k_k, (beam.m.shape[0], 1)), atol=1e-12)
    assert traj.recorder.names == ("blade1", "blade2", "blade3")


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_cantilever_strain_and_frames_follow_beam_theory(formulation):
    """A cantilever (thickness vertical) under a small downward tip force F: the upper surface
    strain is F (L - x) (h/2) / (E I) (Euler-Bernoulli), the section frames are orthonormal and
    their tangent is the centre line's direction (a difference quotient of the stored points)."""
    F, L, b, h, E = 0.005, 1.45, 0.05, 0.0025, 70e9  # a tip slope of 1.2e-3 rad: linear theory holds
    scenario = load_example("cantilever", ['analysis.kind="static"', f'beam.formulation="{formulation}"',
                                           "beam.elements=4", "environment.gravity=[0.0, 0.0, 0.0]",
                                           f"loads.tip_force=[0.0, {-F}, 0.0]"])
    result = api.static(scenario)
    system, sol = result.system, result.solution
    recorder = StateRecorder(system, points_per_element=8)
    snap = recorder(system, SimpleNamespace(x=sol.x, chart=sol.chart))
    beam = snap.beams[0]
    xs = recorder.stations[0]
    expected = F * (L - xs) * (h / 2) / (E * b * h**3 / 12)
    assert np.max(np.abs(beam.strain - expected)) < 2e-3 * expected[0]
    assert beam.centre_line[-1, 1] < 0  # it bends down
    tau = np.cross(beam.m, beam.n)
    for a, c in ((beam.m, beam.m), (beam.n, beam.n), (tau, tau)):
        np.testing.assert_allclose(np.sum(a * c, axis=1), 1.0, atol=1e-12)
    np.testing.assert_allclose(np.sum(beam.m * beam.n, axis=1), 0.0, atol=1e-12)
    chord = np.diff(beam.centre_line, axis=0)
    chord /= np.linalg.norm(chord, axis=1)[:, None]
    mid = 0.5 * (tau[:-1] + tau[1:])
    EI = E * b * h**3 / 12
    slope = F * L**2 / (2 * EI)
    assert tau[-1, 1] == pytest.approx(-slope, rel=1e-2)  # the tip section's slope
    assert np.max(np.linalg.norm(np.cross(chord, mid), axis=1)) < 1e-3 * slope
