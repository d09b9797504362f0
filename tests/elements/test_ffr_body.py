"""The FFR body (paper Sec. 3): stiffness, inertia invariants, M_v, Q_v and Q_g.

Oracles that do not share the invariants' algebra: Euler-Bernoulli, St-Venant and bar
frequencies; kinetic energy and accelerations of material points sampled over the volume
with an independent (finer) quadrature, the accelerations by finite differences in time
along an analytic trajectory."""

import numpy as np
import pytest
from scipy.linalg import eigh, expm

from hubbeam.elements.ffr.body import FfrBeam, skew
from hubbeam.elements.ffr.shape import displacement_matrix, line_shapes
from hubbeam.elements.hermite import gauss_legendre
from tests.conftest import L, plate

BETA_L = np.array([1.8751040687, 4.6940911330, 7.8547574382])


def clamped_frequencies(beam):
    w2 = eigh(beam.stiffness_matrix, beam.mass_matrix(np.zeros(beam.ndof), np.eye(3))[6:, 6:], eigvals_only=True)
    return np.sqrt(w2) / (2 * np.pi)


def test_clamped_frequencies_match_the_closed_forms():
    sec = plate()
    beam = FfrBeam(L, 10, sec)
    f = clamped_frequencies(beam)
    EA, GJ, EIy, EIz = sec.stiffness
    rhoA = sec.mass_per_length
    weak = BETA_L**2 / (2 * np.pi * L**2) * np.sqrt(EIy / rhoA)
    strong = BETA_L[:2] ** 2 / (2 * np.pi * L**2) * np.sqrt(EIz / rhoA)
    torsion = 1 / (4 * L) * np.sqrt(GJ / (sec.density * (sec.i_y + sec.i_z)))
    axial = 1 / (4 * L) * np.sqrt(EA / rhoA)
    for target, tol in [(w, 2e-3) for w in weak] + [(s, 3e-3) for s in strong] + [(torsion, 2e-3), (axial, 2e-3)]:
        assert np.min(np.abs(f / target - 1)) < tol, target


def random_state(beam, rng):
    nf = beam.ndof
    p = 1e-2 * rng.standard_normal(nf)
    A0 = expm(skew(rng.standard_normal(3)))
    v = rng.standard_normal(6 + nf)
    return p, A0, v


def volume_points(beam, nx=7, ns=3):
    """(element, xi, y, z, weight rho dV): a finer tensor Gauss rule than the body's."""
    sec = beam.section
    xg, wx = gauss_legendre(nx)
    sg, ws = gauss_legendre(ns)
    for e in range(beam.elements):
        for xi, wk in zip(xg, wx):
            for s, wy in zip(sg, ws):
                for t, wz in zip(sg, ws):
                    yield e, xi, (s - 0.5) * sec.width, (t - 0.5) * sec.thickness, \
                        sec.density * wk * beam.element_length * wy * sec.width * wz * sec.thickness


def point_rows(beam, e, xi, y, z):
    N = displacement_matrix(line_shapes(np.array([xi]), beam.element_length), 0, y, z)
    return beam._scatter(e, N), np.array([(e + xi) * beam.element_length, y, z])


def test_mass_matrix_gives_the_kinetic_energy_of_the_volume():
    beam = FfrBeam(L, 3, plate(thickness=0.01))
    rng = np.random.default_rng(1)
    p, A0, v = random_state(beam, rng)
    rdot_c, omega, pdot = v[0:3], v[3:6], v[6:]
    T = 0.0
    for e, xi, y, z, w in volume_points(beam):
        N, r0 = point_rows(beam, e, xi, y, z)
        rdot = rdot_c + A0 @ np.cross(omega, r0 + N @ p) + A0 @ (N @ pdot)  # Eq. 44
        T += 0.5 * w * rdot @ rdot
    assert 0.5 * v @ beam.mass_matrix(p, A0) @ v == pytest.approx(T, rel=1e-12)


def test_quadratic_velocity_force_and_gravity_against_sampled_accelerations():
    """Along r_C(t), A0(t) = expm(t W1) expm(t^2 W2) A, p(t) quadratic: the acceleration of
    every sampled material point by central differences of Eq. 42 gives s = r'' - S v'
    (Eq. 55); then -sum rho dV S^T s must equal Q_v, and sum rho dV S^T g must equal Q_g."""
    beam = FfrBeam(L, 2, plate(thickness=0.01))
    rng = np.random.default_rng(2)
    nf = beam.ndof
    a, b, c = rng.standard_normal((3, 3))
    W1, W2 = skew(rng.standard_normal(3)), skew(rng.standard_normal(3))
    A = expm(skew(rng.standard_normal(3)))
    p0, p1, p2 = 1e-2 * rng.standard_normal((3, nf))

    def at(t):
        return a + b * t + c * t * t, expm(t * W1) @ expm(t * t * W2) @ A, p0 + p1 * t + p2 * t * t

    def omega_body(t, h=1e-6):
        A0 = at(t)[1]
        dA = (at(t + h)[1] - at(t - h)[1]) / (2 * h)
        Wb = A0.T @ dA
        return np.array([Wb[2, 1], Wb[0, 2], Wb[1, 0]])

    t, h = 0.3, 1e-4
    rc, A0, p = at(t)
    pdot = p1 + 2 * p2 * t
    omega = omega_body(t)
    omega_dot = (omega_body(t + h) - omega_body(t - h)) / (2 * h)
    vdot = np.concatenate([2 * c, omega_dot, 2 * p2])
    g = np.array([0.3, -9.81, 0.5])
    Qv, Qg = np.zeros(6 + nf), np.zeros(6 + nf)
    for e, xi, y, z, w in volume_points(beam, nx=5, ns=2):
        N, r0 = point_rows(beam, e, xi, y, z)

        def position(tt):
            rc_, A_, p_ = at(tt)
            return rc_ + A_ @ (r0 + N @ p_)

        accel = (position(t + h) - 2 * position(t) + position(t - h)) / h**2
        S = np.hstack([np.eye(3), -A0 @ skew(r0 + N @ p), A0 @ N])
        s = accel - S @ vdot
        Qv -= w * S.T @ s
        Qg += w * S.T @ g
    scale = np.max(np.abs(Qv))
    assert np.max(np.abs(beam.quadratic_velocity(p, pdot, omega, A0) - Qv)) < 1e-5 * scale
    assert np.max(np.abs(beam.gravity(p, A0, g) - Qg)) < 1e-10 * np.max(np.abs(Qg))


def test_fibre_strain_of_a_bent_element():
    """v0 = k x^2 / 2 (v0'' = k) is exact in the cubic element: eps(y) = -k y at every station."""
    beam = FfrBeam(L, 4, plate())
    k = 0.1
    p = np.zeros(beam.ndof)
    for node in range(1, 5):
        x = node * beam.element_length
        p[6 * (node - 1) + 1], p[6 * (node - 1) + 2] = k * x * x / 2, k * x
    for x in (0.1, 0.77, L):
        assert beam.strain_row(x, 0.02, 0.0) @ p == pytest.approx(-k * 0.02, rel=1e-12)
        assert beam.displacement_row(x)[1] @ p == pytest.approx(k * x * x / 2, rel=1e-12)


def test_cardan_angular_velocity_and_its_rate_by_differences():
    """omega^b~ = A0^T dA0/dt by central differences along Theta(t); D' Theta' likewise."""
    from hubbeam.elements.ffr.cardan import angular_velocity_matrix, angular_velocity_matrix_rate, rotation_matrix

    th0, th1 = np.array([0.4, -0.7, 1.1]), np.array([0.3, 0.5, -0.8])

    def omega(t):
        h = 1e-6
        A = rotation_matrix(th0 + t * th1)
        W = A.T @ (rotation_matrix(th0 + (t + h) * th1) - rotation_matrix(th0 + (t - h) * th1)) / (2 * h)
        return np.array([W[2, 1], W[0, 2], W[1, 0]])

    assert np.allclose(angular_velocity_matrix(th0) @ th1, omega(0.0), atol=1e-9)
    h = 1e-5
    rate = (angular_velocity_matrix(th0 + h * th1) - angular_velocity_matrix(th0 - h * th1)) @ th1 / (2 * h)
    assert np.allclose(angular_velocity_matrix_rate(th0, th1), rate, atol=1e-9)


def test_stiffened_elastic_force_and_tangent_are_derivatives_of_the_energy():
    from tests.conftest import central_difference

    beam = FfrBeam(L, 3, plate(), geometric_stiffening=True)
    p = 0.05 * np.random.default_rng(3).standard_normal(beam.ndof)
    U, f, K = beam.elastic(p)
    f_fd = central_difference(lambda q: np.array([beam.elastic(q)[0]]), p, 1e-6)[0]
    K_fd = central_difference(lambda q: beam.elastic(q)[1], p, 1e-7)
    assert np.max(np.abs(f - f_fd)) < 1e-6 * np.max(np.abs(f))
    assert np.max(np.abs(K - K_fd)) < 1e-6 * np.max(np.abs(K))
    linear = FfrBeam(L, 3, plate())
    assert linear.elastic(p)[0] == pytest.approx(0.5 * p @ linear.stiffness_matrix @ p)
    # for a pure stretch the two agree
    stretch = np.zeros(beam.ndof)
    stretch[0::6] = 1e-4 * np.arange(1, 4)
    assert beam.elastic(stretch)[0] == pytest.approx(linear.elastic(stretch)[0], rel=1e-12)


@pytest.mark.parametrize("stiffening, modes", [(False, None), (True, None), (True, 3)])
def test_the_strain_polynomial_is_the_surface_strain(stiffening, modes):
    """c . p + p^T Q p / 2 of strain_polynomial is surface_strain at random states (nodal and
    modal, with and without the stiffened element-mean strain, whose Q is not zero)."""
    extra = {} if modes is None else {"modes": modes}
    beam = FfrBeam(L, 3, plate(), geometric_stiffening=stiffening, **extra)
    rng = np.random.default_rng(2)
    c, Q = beam.strain_polynomial(0.61, 0.01, -0.002)
    assert (np.max(np.abs(Q)) > 0.0) == stiffening
    for _ in range(3):
        p = 0.05 * rng.normal(size=beam.ndof)
        assert c @ p + 0.5 * p @ Q @ p == pytest.approx(beam.surface_strain(p, 0.61, 0.01, -0.002), rel=1e-12)
