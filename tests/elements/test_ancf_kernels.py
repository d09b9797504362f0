"""Element kernels: internal force and tangent from the energy, mass from the kinetic energy."""

import numpy as np
import pytest

from hubbeam.elements.ancf.frame import frame_global
from hubbeam.system.beam import AncfBeam
from hubbeam.system.mount import Mount
from tests.conftest import central_difference, plate, rotation


def bent_state(beam, seed=0, amplitude=0.05):
    q, F = beam.straight_state(np.zeros(3), Mount(0.0, 0.3).frame(0.0))
    rng = np.random.default_rng(seed)
    return q + amplitude * rng.normal(size=q.size), F


@pytest.fixture
def beam():
    return AncfBeam(1.45, 3, plate())


def test_internal_force_is_gradient_of_strain_energy(beam):
    q, F = bent_state(beam)
    U, f, _ = beam.elastic(q, F)
    f_fd = central_difference(lambda q: [beam.elastic(q, F, tangent=False)[0]], q, 1e-7)[0]
    assert np.max(np.abs(f - f_fd)) < 1e-6 * np.max(np.abs(f))


def test_tangent_is_derivative_of_internal_force_and_symmetric(beam):
    from hubbeam.system.assembly import add_element_blocks_dense

    q, F = bent_state(beam, seed=1)
    _, _, blocks = beam.elastic(q, F)
    K = np.zeros((beam.ndof, beam.ndof))
    add_element_blocks_dense(K, blocks, 0, 1.0)
    K_fd = central_difference(lambda q: beam.elastic(q, F, tangent=False)[1], q, 1e-7)
    assert np.max(np.abs(K - K_fd)) < 2e-6 * np.max(np.abs(K))
    assert np.allclose(K, K.T, rtol=0, atol=1e-9 * np.max(np.abs(K)))


@pytest.mark.parametrize(
    "axis,angle",
    [([0, 1, 0], 90), ([0, 1, 0], 180), ([0, 1, 0], 270), ([0, 0, 1], 90), ([0, 0, 1], 180), ([0, 0, 1], 270),
     ([1, 2, 3], 137)],
)
def test_rigid_motion_has_no_strain_energy_and_no_force(axis, angle):
    beam = AncfBeam(1.45, 4, plate())
    Q = rotation(axis, np.radians(angle))
    frame = Q @ Mount(0.0, np.radians(45)).frame(0.0)
    q, F = beam.straight_state(np.array([0.3, -2.0, 5.0]), frame)
    U, f, _ = beam.elastic(q, F)
    assert abs(U) < 1e-18
    assert np.max(np.abs(f)) < 1e-6  # N; EA = 8.75e6 N, so this is round-off
    # the section frame along the beam is the rotated clamp frame
    for x in (0.0, 0.5, 1.45):
        assert np.allclose(beam.frame_at(q, F, x), frame, atol=1e-12)


def _kinetic_energy_by_sampling(beam, q, qdot, F, n_x=40, n_yz=4):
    """T = 1/2 int rho |dr/dt|^2 dV with r = r0 + y m + z n, sampled over the volume and
    differentiated in time by finite differences: shares nothing with Eq. 35."""
    sec = beam.section
    xs, wx = np.polynomial.legendre.leggauss(n_x)
    ys, wy = np.polynomial.legendre.leggauss(n_yz)
    T = 0.0
    h = 1e-6
    for e in range(beam.elements):
        for xi, w in zip(xs, wx):
            x = (e + 0.5 * (xi + 1)) * beam.element_length
            x = min(x, beam.length)

            def point(qq, y, z):
                r0, u, _, phi, _ = beam.interpolate(qq, x)
                R = frame_global(F, u, phi)
                return r0 + y * R[:, 1] + z * R[:, 2]

            for yy, wyy in zip(ys, wy):
                for zz, wzz in zip(ys, wy):
                    y, z = yy * sec.width / 2, zz * sec.thickness / 2
                    v = (point(q + h * qdot, y, z) - point(q - h * qdot, y, z)) / (2 * h)
                    dV = w * beam.element_length / 2 * wyy * sec.width / 2 * wzz * sec.thickness / 2
                    T += 0.5 * sec.density * (v @ v) * dV
    return T


def test_mass_matrix_gives_the_kinetic_energy_of_the_section(beam):
    from hubbeam.system.assembly import add_element_blocks_dense

    # rotary inertia large enough to matter; 8 points integrate its rational terms to 1e-7
    fat = AncfBeam(1.45, 3, plate(width=0.3, thickness=0.2), gauss_points=8)
    q, F = bent_state(fat, seed=2, amplitude=0.1)
    M = np.zeros((fat.ndof, fat.ndof))
    add_element_blocks_dense(M, fat.mass_blocks(q, F), 0, 1.0)
    rng = np.random.default_rng(5)
    for _ in range(3):
        qdot = rng.normal(size=q.size)
        T_ref = _kinetic_energy_by_sampling(fat, q, qdot, F)
        assert np.isclose(0.5 * qdot @ M @ qdot, T_ref, rtol=2e-6)
    assert np.all(np.linalg.eigvalsh(M) > 0)


def test_gravity_load_is_gradient_of_potential(beam):
    g = np.array([0.0, -9.81, 0.0])
    Q = beam.distributed_load(beam.section.mass_per_length * g)
    q, F = bent_state(beam)

    def potential(qq):
        xs = np.linspace(0, beam.length, 2001)
        r = np.array([beam.interpolate(qq, s)[0] for s in xs])
        return -beam.section.mass_per_length * np.trapezoid(r @ g, xs)

    Q_fd = -central_difference(lambda qq: [potential(qq)], q, 1e-4)[0]
    assert np.allclose(Q, Q_fd, atol=1e-5 * np.max(np.abs(Q)))
    assert np.isclose(Q[1::8].sum(), beam.section.mass_per_length * beam.length * g[1])


def _dense(beam, blocks):
    from hubbeam.system.assembly import add_element_blocks_dense

    A = np.zeros((beam.ndof, beam.ndof))
    add_element_blocks_dense(A, blocks, 0, 1.0)
    return A


def test_quadratic_velocity_force_follows_from_lagrange_with_the_mass_matrix():
    """Q_v = -(dM/dt qdot - d(1/2 qdot^T M qdot)/dq), M from AncfBeam.mass_blocks (checked above against
    the sampled kinetic energy), both derivatives by finite differences."""
    fat = AncfBeam(1.45, 2, plate(width=0.3, thickness=0.2), gauss_points=6)
    q, F = bent_state(fat, seed=4, amplitude=0.1)
    rng = np.random.default_rng(9)
    qdot = rng.normal(size=q.size)
    M = lambda qq: _dense(fat, fat.mass_blocks(qq, F))
    h = 1e-6
    Mdot = (M(q + h * qdot) - M(q - h * qdot)) / (2 * h)
    dT_dq = central_difference(lambda qq: [0.5 * qdot @ M(qq) @ qdot], q, h)[0]
    # the translational mass is constant, so all of this is rotary inertia
    Qv_ref = -(Mdot @ qdot - dT_dq)
    T_rot, Qv = fat.rotary_inertia(q, qdot, F)
    assert np.max(np.abs(Qv - Qv_ref)) < 1e-6 * np.max(np.abs(Qv_ref))
    T_total = 0.5 * qdot @ M(q) @ qdot
    T_trans = 0.5 * fat.section.mass_per_length * qdot @ _dense(fat, _trans_blocks(fat)) @ qdot
    assert np.isclose(T_rot, T_total - T_trans, rtol=1e-9)


def _trans_blocks(beam):
    """Translational Hermite mass blocks per unit rho A (independent closed form)."""
    l = beam.element_length
    m = l / 420 * np.array([[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l],
                            [54, 13 * l, 156, -22 * l], [-13 * l, -3 * l * l, -22 * l, 4 * l * l]])
    idx = [0, 3, 8, 11]
    blk = np.zeros((16, 16))
    for a in range(4):
        for b in range(4):
            blk[idx[a]:idx[a] + 3, idx[b]:idx[b] + 3] = m[a, b] * np.eye(3)
    return np.repeat(blk[None], beam.elements, axis=0)


def test_drag_force_and_damping_matrix():
    beam = AncfBeam(1.45, 3, plate())
    rng = np.random.default_rng(2)
    qdot = rng.normal(size=beam.ndof)
    c1, c2 = 1.73, 1.4
    power, Qd, blocks = beam.drag(qdot, c1, c2)
    # the force at a uniform velocity V is -(c1 + c2 |V|) V b L in total
    V = np.array([0.3, -0.2, 0.5])
    uniform = np.zeros(beam.ndof)
    for k in range(beam.nodes):
        uniform[8 * k:8 * k + 3] = V
    _, Qu, _ = beam.drag(uniform, c1, c2)
    total = np.array([Qu[i::8].sum() for i in range(3)])
    assert np.allclose(total, -(c1 + c2 * np.linalg.norm(V)) * V * beam.section.width * beam.length, rtol=1e-10)
    C = _dense(beam, blocks)
    C_fd = -central_difference(lambda v: beam.drag(v, c1, c2)[1], qdot, 1e-7)
    assert np.allclose(C, C_fd, atol=1e-6 * np.max(np.abs(C)))
    assert np.isclose(power, -Qd @ qdot)


def test_rotary_inertia_force_subtracts_the_rotary_mass_times_acceleration():
    """The kernel's force with an acceleration is Q_v - M_rot acc, M_rot = M - M_trans."""
    from hubbeam.elements.ancf import inertia

    fat = AncfBeam(1.45, 2, plate(width=0.3, thickness=0.2), gauss_points=6)
    q, F = bent_state(fat, seed=6, amplitude=0.1)
    rng = np.random.default_rng(11)
    qdot, acc = rng.normal(size=q.size), rng.normal(size=q.size)
    _, Qv = fat.rotary_inertia(q, qdot, F)
    M_rot = _dense(fat, fat.mass_blocks(q, F)) - fat.section.mass_per_length * _dense(fat, _trans_blocks(fat))
    S, dS, _, w = fat._tables
    out = np.empty(q.size)
    inertia.rotary_inertia_kernel(q, qdot, acc, F, fat.element_length, S, dS, w, fat._inertia, 0.0, out,
                                  np.empty((0, 16, 16)))
    assert np.allclose(out, Qv - M_rot @ acc, atol=1e-10 * np.max(np.abs(M_rot @ acc)))


def test_elastic_rotary_kernel_adds_the_rotary_mass_to_the_elastic_matrix():
    """The fused matrix path: elastic blocks plus coef_m M_rot (the rotary kernel's blocks), the
    force the elastic kernel's alone."""
    from hubbeam.elements.ancf import elastic, inertia

    fat = AncfBeam(1.45, 3, plate(width=0.3, thickness=0.2), gauss_points=5)
    q, F = bent_state(fat, seed=4, amplitude=0.1)
    F = rotation([1, 2, 3], 0.4) @ F  # a chart with general entries
    qdot = np.random.default_rng(5).normal(size=q.size)
    S, dS, d2S, w = fat._tables
    coef_m, coef_c, damping = 3.0e4, 20.0, 0.01
    args = (q, qdot, F, fat.element_length, S, dS, d2S, w, fat._stiffness, fat._reference, damping)
    f_el, b_el = np.empty(q.size), np.zeros((fat.elements, 16, 16))
    out_el = elastic.elastic_kernel(*args, coef_c, 1.0, f_el, b_el)
    inertia.rotary_inertia_kernel(q, qdot, np.zeros(q.size), F, fat.element_length, S, dS, w, fat._inertia, coef_m,
                                  np.empty(q.size), b_el)
    f, b = np.empty(q.size), np.zeros((fat.elements, 16, 16))
    out = elastic.elastic_rotary_kernel(*args, fat._inertia, coef_m, coef_c, 1.0, f, b)
    assert out == out_el
    assert np.array_equal(f, f_el)
    assert np.max(np.abs(b - b_el)) < 1e-13 * np.max(np.abs(b_el))
