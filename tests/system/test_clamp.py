"""Clamp constraints: Jacobian and multiplier Hessian against finite differences, and meaning,
for beams at any azimuth, precone and twist."""

import numpy as np
import pytest

from hubbeam.elements.ancf.chart import frame_from_director
from hubbeam.system.beam import AncfBeam
from hubbeam.system.clamp import clamp_constraints, clamp_twist_angle
from hubbeam.system.hub import hub_frame
from hubbeam.system.hub_system import single_beam_system
from hubbeam.system.mount import Mount
from tests.conftest import central_difference, plate, rotation

R, BETA = 0.35, np.radians(45)
MOUNTS = [Mount(R, BETA), Mount(R, BETA, azimuth=2.1, precone=0.3), Mount(0.2, -0.4, azimuth=-1.0, precone=-0.5)]


@pytest.mark.parametrize("mount", MOUNTS)
@pytest.mark.parametrize("director", [[1, 0, 0], [0.2, 0.9, -0.3], [0, -1, 0]])
def test_twist_angle_rate_matches_finite_difference(director, mount):
    F = frame_from_director(np.array(director, float))
    p = mount.params()
    for theta in (0.1, 1.3, 2.9):
        fd = (clamp_twist_angle(p, theta + 1e-6, F, 0) - clamp_twist_angle(p, theta - 1e-6, F, 0)) / 2e-6
        c = np.zeros(8)
        c[0] = theta
        c[7] = clamp_twist_angle(p, theta, F)
        _, jac, _ = clamp_constraints(c, p, F)
        assert np.isclose(-jac[5, 0], fd, atol=1e-7)


@pytest.mark.parametrize("mount", MOUNTS)
def test_constraint_jacobian_and_hessian_match_finite_differences(mount):
    F = frame_from_director(np.array([0.3, 0.5, 0.8]))
    p = mount.params()
    rng = np.random.default_rng(0)
    c = rng.normal(size=8)
    c[7] = clamp_twist_angle(p, c[0], F) + 0.1
    phi, jac, hess = clamp_constraints(c, p, F)
    fun = lambda c: clamp_constraints(c, p, F)[0]
    assert np.allclose(central_difference(fun, c, 1e-6), jac, atol=1e-8)
    lam = rng.normal(size=phi.size)
    H_fd = central_difference(lambda c: clamp_constraints(c, p, F)[1].T @ lam, c, 1e-6)
    assert np.allclose(H_fd, hess(lam), atol=1e-7)


@pytest.mark.parametrize("theta", [0.0, 1.0, np.pi, 4.5])
def test_straight_clamped_state_satisfies_the_clamp(theta):
    system = single_beam_system(AncfBeam(1.45, 3, plate()), radius=R, twist=BETA, motion="free")
    x, F = system.initial_state(theta)
    assert np.allclose(system.beams[0].clamp(x[1:], F[0], theta)[0], 0, atol=1e-12)
    # the root section: tangent i_h, and n = sin(beta) j_h + cos(beta) k_h (conventions.md)
    A = hub_frame(theta)
    frame = system.beam.frame_at(x[1:], F[0], 0.0)
    assert np.allclose(frame[:, 0], A[:, 0])
    assert np.allclose(frame[:, 2], np.sin(BETA) * A[:, 1] + np.cos(BETA) * A[:, 2])
    assert np.allclose(frame, Mount(R, BETA).frame(theta))


def test_mount_frame_is_the_hub_frame_turned_by_azimuth_precone_and_twist():
    """Built independently by Rodrigues rotations: the beam axis is i_h(theta + psi) tilted by
    p towards +j0, the section turned by -beta about that axis."""
    theta, psi, p, beta = 0.4, 2.0, 0.3, 0.7
    A = hub_frame(theta + psi)
    axis = np.cos(p) * A[:, 0] + np.sin(p) * A[:, 1]
    assert axis[1] > 0  # tilted towards +j0
    m0 = -np.sin(p) * A[:, 0] + np.cos(p) * A[:, 1]  # the width direction before the twist, in the axis-j0 plane
    m = rotation(axis, -beta) @ m0
    frame = Mount(R, beta, psi, p).frame(theta)
    assert np.allclose(frame[:, 0], axis) and np.allclose(frame[:, 1], m)
    assert np.allclose(np.cross(frame[:, 0], frame[:, 1]), frame[:, 2])
    assert np.allclose(Mount(R, beta, psi, p).root(theta), R * A[:, 0])


def test_mirror_mount_is_the_mirror_image():
    """Azimuth 180 deg with twist -beta mirrors azimuth 0 with +beta in the plane through j0 and k_h."""
    theta, beta = 0.3, 0.6
    a, b = Mount(R, beta).frame(theta), Mount(R, -beta, np.pi).frame(theta)
    i_h = hub_frame(theta)[:, 0]
    P = np.eye(3) - 2 * np.outer(i_h, i_h)  # reflection across the plane normal to i_h
    assert np.allclose(P @ a[:, 0], b[:, 0])  # the axes mirror
    assert np.allclose(P @ a[:, 1], b[:, 1]) or np.allclose(P @ a[:, 1], -b[:, 1])  # the width line mirrors
    assert np.allclose(P @ Mount(R, beta).root(theta), Mount(R, -beta, np.pi).root(theta))


def test_upper_surface_faces_up_for_beta_45():
    n = Mount(R, np.radians(45)).frame(0.0)[:, 2]
    assert n[1] > 0.7
