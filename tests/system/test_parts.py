"""The beam-part protocol's section kinematics and kinetic-energy split, for both formulations:
the angular velocity against differences of the section frames, the split against the
system's own mass matrix."""

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.multibody import single_beam_system
from hubbeam.system.tip_body import TipBody
from tests.conftest import L, plate, tapered_sections


@pytest.mark.parametrize("beam_class, rel, tapered", [(AncfBeam, 1e-9, False), (AncfBeam, 1e-9, True),
                                                      (FfrBeam, 1e-3, False)])
def test_split_adds_up_to_the_mass_matrix_energy(beam_class, rel, tapered):
    """About a bent, twisted, preconed beam with a tip body, prismatic or (ANCF) tapered and
    pretwisted, the four parts sum to u^T M u / 2 of the system's own mass matrix for any u (ANCF
    exactly; FFR to first order in the section's small rotation, which its angular velocity
    keeps). A pretwisted FFR beam leaves a gap of 2.5e-4 that does not vanish with the
    deformation: not yet explained, so not asserted here."""
    sections = tapered_sections() if tapered else None
    system = single_beam_system(beam_class(L, 6, plate(), sections=sections), radius=0.35, twist=np.radians(30), motion="fixed",
                                precone=np.radians(5), gravity=(0, -9.81, 0),
                                tip_body=TipBody(0.05, (1e-5, 2e-5, 2.5e-5), (0.01, 0.002, -0.001)))
    st = solve_static(system, load_steps=3)
    _, M, _ = system.linearised(st.x, st.multipliers, st.chart, 1.0, held=True)
    rng = np.random.default_rng(3)
    for _ in range(3):
        u = rng.standard_normal(system.nx)
        u[0] = 0.0
        total = sum(system.kinetic_energy_split(st.x, st.chart, u).values())
        assert total == pytest.approx(0.5 * u @ M @ u, rel=rel)


@pytest.mark.parametrize("beam_class", [AncfBeam, FfrBeam])
def test_section_angular_velocity_is_the_rate_of_the_section_frame(beam_class):
    """omega x = R' R^T: the frames at q +- h u by central differences."""
    system = single_beam_system(beam_class(L, 4, plate()), radius=0.35, twist=np.radians(30), motion="fixed")
    part = system.beams[0]
    x0, F = system.initial_state(0.0)
    q = x0[system.layout.beam_x(0)]
    rng = np.random.default_rng(1)
    u = rng.standard_normal(q.size) * 1e-2
    stations = np.array([0.3, 0.9, L])
    frame, still = system.root_pose(0, x0, F), (np.zeros(3), np.zeros(3))  # the root frame at rest
    R, vel, omega = part.section_motion(q, F[0], u, stations, frame, still)
    h = 1e-6
    Rp, _, _ = part.section_motion(q + h * u, F[0], u, stations, frame, still)
    Rm, _, _ = part.section_motion(q - h * u, F[0], u, stations, frame, still)
    for i in range(stations.size):
        W = (Rp[i] - Rm[i]) / (2 * h) @ R[i].T
        assert np.allclose(0.5 * (W - W.T), W, atol=1e-6 * np.abs(W).max())  # skew
        assert np.allclose([W[2, 1], W[0, 2], W[1, 0]], omega[i], rtol=1e-6, atol=1e-8)
    # the velocity is the rate of the centre line's points
    line = lambda qq: np.array([part.centre_line(qq, F[0], 1, frame)[-1]])
    assert np.allclose((line(q + h * u) - line(q - h * u)) / (2 * h), vel[-1], atol=1e-7)


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_undeformed_section_frames_follow_the_pretwist(formulation):
    """The bundled blade (root twist 85 deg, pretwist -25 deg at the tip) undeformed at theta = 0:
    each station's section axes are the mount's convention m = cos b j0 - sin b k0,
    n = sin b j0 + cos b k0 with b = twist + pretwist(x), in both formulations."""
    from hubbeam import api
    from hubbeam.io.scenario import load_example

    system = api.build_system(load_example("blade", [f'beam.formulation="{formulation}"']))
    x, charts = system.initial_state(0.0)
    part = system.beams[0]
    length = part.beam.length
    stations = np.array([0.0, 0.3 * length, length])
    frames = system.frames_at(x, charts, stations, 0)
    for frame, s in zip(frames, stations):
        b = np.radians(85.0 - 25.0 * s / length)
        assert frame[:, 0] == pytest.approx([1.0, 0.0, 0.0], abs=1e-12)
        assert frame[:, 1] == pytest.approx([0.0, np.cos(b), -np.sin(b)], abs=1e-9)
        assert frame[:, 2] == pytest.approx([0.0, np.sin(b), np.cos(b)], abs=1e-9)
