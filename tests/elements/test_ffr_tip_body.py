"""The FFR beam with a rigid tip body (FfrBeam(..., tip_body=TipBody(...))).

Oracles that do not share the invariants' algebra: the tip node's coordinates read
directly from p (u = (u0, v, w), small rotation (theta, -w', v')); a point mass's velocity
r_C' + A0 (omega x r + u'); a uniform box sampled by its own exact (2 x 2 x 2 Gauss)
quadrature with accelerations by finite differences in time; and the closed-form
frequency equation of a cantilever with a tip mass and rotary inertia.
"""

import numpy as np
from scipy.linalg import eigh, expm

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.elements.hermite import gauss_legendre
from hubbeam.system.tip_body import TipBody
from tests.conftest import L, plate
from tests.system.test_tip_body import (FREQUENCY_BODY, MESHES, TIP_J_M, TIP_MASS, check_convergence,
                                        tip_body_frequencies_hz)


def skew(a):
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def tip_rows(nf):
    """u_L = U p and phi_L = P p at the tip from the last node's [u0, v, v', w, w', theta]."""
    U, P = np.zeros((3, nf)), np.zeros((3, nf))
    o = nf - 6
    U[0, o], U[1, o + 1], U[2, o + 3] = 1.0, 1.0, 1.0
    P[0, o + 5], P[1, o + 4], P[2, o + 2] = 1.0, -1.0, 1.0
    return U, P


def box(mass, size, offset):
    """A uniform box (edges ``size`` along the section axes) centred at ``offset``: the tip
    body with its principal inertia, and its exact 2 x 2 x 2 Gauss sampling (weights, d)."""
    a = np.asarray(size, float)
    J = mass / 12.0 * np.array([a[1] ** 2 + a[2] ** 2, a[0] ** 2 + a[2] ** 2, a[0] ** 2 + a[1] ** 2])
    s, w = gauss_legendre(2)
    pts = [(np.asarray(offset) + (np.array([x, y, z]) - 0.5) * a, mass * wx * wy * wz)
           for x, wx in zip(s, w) for y, wy in zip(s, w) for z, wz in zip(s, w)]
    return TipBody(mass, tuple(J), tuple(offset)), pts


def point_jacobian(beam, d, p, A0):
    """S with r' = S [r_C', omega^b, p'] for the body point at rho0 = (L, 0, 0) + d, moving by
    u = u_L + phi_L x d."""
    U, P = tip_rows(beam.ndof)
    N = U - skew(d) @ P
    r = np.array([beam.length, 0.0, 0.0]) + d + N @ p
    return np.hstack([np.eye(3), -A0 @ skew(r), A0 @ N]), N, r


def test_no_tip_body_keeps_the_invariants():
    plain = FfrBeam(L, 3, plate())
    for other in (FfrBeam(L, 3, plate(), tip_body=None), FfrBeam(L, 3, plate(), tip_body=TipBody())):
        for key, value in plain.invariants.items():
            assert np.array_equal(other.invariants[key], value), key
        assert np.array_equal(other.stiffness_matrix, plain.stiffness_matrix)


def test_point_mass_at_the_tip():
    """Zero offset, zero inertia: M_v(with) - M_v(without) is the mass matrix m S_P^T S_P of a
    point with velocity r_C' + A0 (omega x r_P + N_P p')."""
    m = 0.37
    plain = FfrBeam(L, 4, plate())
    loaded = FfrBeam(L, 4, plate(), tip_body=TipBody(m))
    rng = np.random.default_rng(21)
    for _ in range(3):
        p = 0.05 * rng.standard_normal(plain.ndof)
        A0 = expm(skew(rng.standard_normal(3)))
        S, _, _ = point_jacobian(plain, np.zeros(3), p, A0)
        dM = loaded.mass_matrix(p, A0) - plain.mass_matrix(p, A0)
        assert np.max(np.abs(dM - m * S.T @ S)) < 1e-13 * np.max(np.abs(dM))
    assert loaded.invariants["m"] - plain.invariants["m"] == m


def test_box_tip_body_against_its_sampled_volume():
    """An offset box: the changes of M_v, Q_v and Q_g equal the sums over the box's own sample
    points of S^T S, -S^T s (s = r'' - S v', r'' by differences in time along a trajectory)
    and S^T g."""
    body, points = box(0.45, (0.06, 0.04, 0.03), (0.05, -0.02, 0.015))
    plain = FfrBeam(L, 3, plate())
    loaded = FfrBeam(L, 3, plate(), tip_body=body)
    nf = plain.ndof
    rng = np.random.default_rng(22)
    a, b, c = rng.standard_normal((3, 3))
    W1, W2 = skew(rng.standard_normal(3)), skew(rng.standard_normal(3))
    A = expm(skew(rng.standard_normal(3)))
    p0, p1, p2 = 0.05 * rng.standard_normal((3, nf))

    def at(t):
        return a + b * t + c * t * t, expm(t * W1) @ expm(t * t * W2) @ A, p0 + p1 * t + p2 * t * t

    def d1(f, t, h=1e-3):
        return (8 * (f(t + h) - f(t - h)) - (f(t + 2 * h) - f(t - 2 * h))) / (12 * h)

    def d2(f, t, h=1e-3):
        return (16 * (f(t + h) + f(t - h)) - (f(t + 2 * h) + f(t - 2 * h)) - 30 * f(t)) / (12 * h * h)

    def omega_body(t):
        Wb = at(t)[1].T @ d1(lambda s: at(s)[1], t)
        return np.array([Wb[2, 1], Wb[0, 2], Wb[1, 0]])

    t = 0.3
    rc, A0, p = at(t)
    pdot = p1 + 2 * p2 * t
    omega = omega_body(t)
    v = np.concatenate([b + 2 * c * t, omega, pdot])
    vdot = np.concatenate([2 * c, d1(omega_body, t), 2 * p2])
    g = np.array([0.3, -9.81, 0.5])
    M, Qv, Qg = np.zeros((6 + nf, 6 + nf)), np.zeros(6 + nf), np.zeros(6 + nf)
    for d, w in points:
        S, N, _ = point_jacobian(plain, d, p, A0)
        rho0 = np.array([L, 0.0, 0.0]) + d

        def position(tt):
            rc_, A_, p_ = at(tt)
            return rc_ + A_ @ (rho0 + N @ p_)

        M += w * S.T @ S
        Qv -= w * S.T @ (d2(position, t) - S @ vdot)
        Qg += w * S.T @ g
    dM = loaded.mass_matrix(p, A0) - plain.mass_matrix(p, A0)
    dQv = loaded.quadratic_velocity(p, pdot, omega, A0) - plain.quadratic_velocity(p, pdot, omega, A0)
    dQg = loaded.gravity(p, A0, g) - plain.gravity(p, A0, g)
    assert np.max(np.abs(dM - M)) < 1e-12 * np.max(np.abs(M))
    assert np.max(np.abs(dQv - Qv)) < 1e-8 * np.max(np.abs(Qv))
    assert np.max(np.abs(dQg - Qg)) < 1e-12 * np.max(np.abs(Qg))
    # the kinetic energy of the box is the rigid body's: 1/2 m |v_cm|^2 + rotational part > 0
    v_cm = point_jacobian(plain, np.array(body.offset), p, A0)[0] @ v
    assert 0.5 * v @ dM @ v > 0.5 * body.mass * v_cm @ v_cm


def ffr_weak_frequencies(elements, body):
    beam = FfrBeam(L, elements, plate(), tip_body=body)
    w2, V = eigh(beam.stiffness_matrix, beam.invariants["Mff"])
    along_n = np.array([6 * k + j for k in range(elements) for j in (3, 4)])  # w, w'
    weak = np.sum(V[along_n] ** 2, axis=0) > 0.5 * np.sum(V**2, axis=0)
    return np.sqrt(w2[weak][:2]) / (2 * np.pi)


def test_ffr_cantilever_with_tip_body_frequencies():
    """Body frame held fixed (K p = w^2 Mff p): the first two weak-axis frequencies against the
    closed form, converging under mesh refinement."""
    exact = tip_body_frequencies_hz(plate(), L, TIP_MASS, TIP_J_M)
    errors = [ffr_weak_frequencies(n, FREQUENCY_BODY) / exact - 1 for n in MESHES]
    check_convergence(errors)
