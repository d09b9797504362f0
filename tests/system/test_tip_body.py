"""The rigid tip body on an ANCF tip node (hubbeam.system.tip_body).

Oracles that do not share the kernel's derivation: the body's orientation R(q) from
frame.frame_global only, its angular velocity and the velocity of its centre of mass from
finite differences of R(q) and r_cm(q) = r0 + R(q) c; the kinetic energy
T = 1/2 m |v_cm|^2 + 1/2 w.(R J R^T w) and the potential V = -m g.r_cm built from them;
Lagrange's equations by finite differences of that T along a smooth trajectory; Noether's
momentum for a rigid rotation of the tip state; and the closed-form frequency equation of an
Euler-Bernoulli cantilever carrying a tip mass with rotary inertia.
"""

import numpy as np
import pytest
from scipy.linalg import eigh, null_space
from scipy.optimize import brentq

from hubbeam.elements.ancf.frame import frame_global
from hubbeam.system.tip_body import TipBody, ancf_tip_body_terms
from tests.conftest import L, plate, rotation

BODY = TipBody(0.7, (0.02, 0.03, 0.04), (0.12, -0.05, 0.03))
GRAVITY = np.array([0.3, -9.81, 0.5])


# --------------------------------------------------------------------------- oracles
def derivative(fun, x, direction, h=1e-3):
    """Fourth-order central difference of ``fun`` at x along ``direction``."""
    d = np.asarray(direction, dtype=float)
    return (8.0 * (fun(x + h * d) - fun(x - h * d)) - (fun(x + 2 * h * d) - fun(x - 2 * h * d))) / (12.0 * h)


def axial(W):
    """w of the skew part of W (W ~ [w]x)."""
    S = 0.5 * (W - W.T)
    return np.array([S[2, 1], S[0, 2], S[1, 0]])


class RigidTip:
    """Independent kinematics of the tip body: R(q) from frame_global, rates by differences."""

    def __init__(self, body, F):
        self.m = body.mass
        self.J = np.diag(body.inertia)
        self.c = np.array(body.offset)
        self.F = F

    def R(self, q):
        return frame_global(self.F, q[3:6], q[6])

    def r_cm(self, q):
        return q[0:3] + self.R(q) @ self.c

    def rates(self, q, qd):
        """Velocity of the centre of mass and angular velocity (global) along qd."""
        dR = derivative(self.R, q, qd)
        return derivative(self.r_cm, q, qd), axial(dR @ self.R(q).T)

    def kinetic(self, q, qd):
        v, w = self.rates(q, qd)
        R = self.R(q)
        return 0.5 * self.m * v @ v + 0.5 * w @ R @ self.J @ R.T @ w

    def mass(self, q):
        """M(q) with T = 1/2 qd^T M qd, from the columns of the velocity Jacobians."""
        cols = [self.rates(q, e) for e in np.eye(8)]
        Jv = np.array([c[0] for c in cols]).T
        Jw = np.array([c[1] for c in cols]).T
        R = self.R(q)
        return self.m * Jv.T @ Jv + Jw.T @ R @ self.J @ R.T @ Jw

    def potential(self, q, g):
        return -self.m * g @ self.r_cm(q)


def random_tip_state(rng):
    """A chart F and a bent, stretched, twisted tip state with random rates."""
    F = rotation(rng.standard_normal(3), rng.uniform(0, np.pi))
    bend = rotation(rng.standard_normal(3), rng.uniform(0.2, 1.2))  # tangent 0.2 .. 1.2 rad from d
    q = np.empty(8)
    q[0:3] = rng.standard_normal(3)
    q[3:6] = (1.0 + 0.05 * rng.standard_normal()) * F @ bend[:, 0]
    q[6] = rng.uniform(-np.pi, np.pi)
    q[7] = rng.standard_normal()
    v, a = rng.standard_normal((2, 8))
    return F, q, v, a


# --------------------------------------------------------------------------- data
def test_parameters_and_validation():
    body = TipBody(2.0, (1.0, 2.0, 3.0), (0.1, 0.2, 0.3))
    p = body.params()
    assert p.dtype == np.float64 and p.shape == (7,)
    assert np.array_equal(p, [2.0, 1.0, 2.0, 3.0, 0.1, 0.2, 0.3])
    assert np.allclose(body.second_moments, [2.0, 1.0, 0.0])  # (J_m + J_n - J_tau) / 2 etc.
    assert np.array_equal(TipBody().params(), np.zeros(7))
    for bad in (dict(mass=-1.0), dict(mass=np.nan), dict(inertia=(1.0, 1.0, 2.5)), dict(inertia=(-1.0, 0, 0)),
                dict(inertia=(1.0, np.inf, 1.0)), dict(offset=(0.0, np.nan, 0.0)), dict(offset=(1.0, 2.0))):
        with pytest.raises(ValueError):
            TipBody(**{"mass": 1.0, **bad})


def test_point_masses_carry_the_mass_and_its_moments():
    for body in (BODY, TipBody(1.0, (0.0, 0.5, 0.5), (0.0, 0.0, 0.2)), TipBody(0.0, (0.1, 0.1, 0.1))):
        for spread in (None, 0.3):
            w, d = body.point_masses(spread)
            c = np.array(body.offset)
            assert w.sum() == pytest.approx(body.mass, abs=1e-14)
            assert np.allclose(w @ d, body.mass * c, atol=1e-14)
            r = d - c
            J = np.einsum("p,pk,pl->kl", w, r, r)
            J = np.trace(J) * np.eye(3) - J
            assert np.allclose(J, np.diag(body.inertia), atol=1e-14)
        if body.mass > 0:
            assert np.all(body.point_masses()[0] >= 0.0)


# --------------------------------------------------------------------------- ANCF terms
def test_point_mass_limit():
    """c = 0, J = 0: exactly a point mass m on r0(L)."""
    rng = np.random.default_rng(5)
    F, q, v, a = random_tip_state(rng)
    m = 0.83
    force, M, K, T, V = TipBody(m).ancf_terms(F, q, v, a, GRAVITY)
    expected = np.zeros(8)
    expected[0:3] = m * (a[0:3] - GRAVITY)
    assert np.array_equal(force, expected)
    M_point = np.zeros((8, 8))
    M_point[0:3, 0:3] = m * np.eye(3)
    assert np.array_equal(M, M_point)
    assert np.array_equal(K, np.zeros((8, 8)))
    assert T == pytest.approx(0.5 * m * v[0:3] @ v[0:3], rel=1e-15)
    assert V == pytest.approx(-m * GRAVITY @ q[0:3], rel=1e-15)


def test_kinetic_energy_against_the_rigid_body():
    rng = np.random.default_rng(11)
    for _ in range(5):
        F, q, v, a = random_tip_state(rng)
        _, M, _, T, _ = BODY.ancf_terms(F, q, v, a, GRAVITY)
        T_ref = RigidTip(BODY, F).kinetic(q, v)
        assert T == pytest.approx(T_ref, rel=1e-10)
        assert 0.5 * v @ M @ v == pytest.approx(T_ref, rel=1e-10)
        assert np.allclose(M, M.T, atol=1e-14)
        assert np.all(M[7] == 0.0) and np.all(M[:, 7] == 0.0)  # theta_1' does not move the body


def test_inertia_force_is_lagranges_equation():
    """M a - Q_v = d/dt(dT/dqd) - dT/dq along q(t) = q0 + v t + a t^2 / 2 (g = 0)."""
    rng = np.random.default_rng(12)
    for _ in range(3):
        F, q0, v, a = random_tip_state(rng)
        tip = RigidTip(BODY, F)
        momentum_rate = derivative(lambda t: tip.mass(q0 + v * t + 0.5 * a * t * t) @ (v + a * t), 0.0, 1.0)
        dTdq = np.array([derivative(lambda q: tip.kinetic(q, v), q0, e) for e in np.eye(8)])
        lagrange = momentum_rate - dTdq
        force, M, _, _, _ = BODY.ancf_terms(F, q0, v, a, np.zeros(3))
        assert np.max(np.abs(force - lagrange)) < 1e-8 * np.max(np.abs(lagrange))
        # and the velocity part alone (a = 0): -Q_v
        force_v = BODY.ancf_terms(F, q0, v, np.zeros(8), np.zeros(3))[0]
        assert np.allclose(force - force_v, M @ a, rtol=0, atol=1e-12 * np.max(np.abs(force)))


def test_gravity_force_and_load_stiffness():
    """Q_g = -dV/dq of the independent V, and K = -dQ_g/dq by differences of Q_g."""
    rng = np.random.default_rng(13)
    zero = np.zeros(8)
    for _ in range(4):
        F, q, _, _ = random_tip_state(rng)
        tip = RigidTip(BODY, F)
        force, _, K, T, V = BODY.ancf_terms(F, q, zero, zero, GRAVITY)  # force = -Q_g
        assert T == 0.0
        assert V == pytest.approx(tip.potential(q, GRAVITY), rel=1e-14)
        dVdq = np.array([derivative(lambda x: tip.potential(x, GRAVITY), q, e) for e in np.eye(8)])
        assert np.max(np.abs(force - dVdq)) < 1e-11 * np.max(np.abs(dVdq))
        minus_Qg = lambda x: BODY.ancf_terms(F, x, zero, zero, GRAVITY)[0]  # noqa: E731
        K_fd = np.array([derivative(minus_Qg, q, e) for e in np.eye(8)]).T
        assert np.max(np.abs(K - K_fd)) < 1e-9 * np.max(np.abs(K_fd))
        assert np.max(np.abs(K_fd[3:7, 3:7])) > 0.05  # an offset body has a real load stiffness


def test_kernel_adds_scaled_blocks_and_forces():
    rng = np.random.default_rng(14)
    F, q, v, a = random_tip_state(rng)
    force, M, K, T, V = BODY.ancf_terms(F, q, v, a, GRAVITY)
    f = np.full(8, 1.5)
    block = np.full((8, 8), -2.0)
    T2, V2 = ancf_tip_body_terms(BODY.params(), F, q, v, a, GRAVITY, 0.25, 4.0, f, block)
    assert (T2, V2) == (T, V)
    assert np.allclose(f, 1.5 + force, rtol=0, atol=1e-14)
    assert np.allclose(block, -2.0 + 0.25 * M + 4.0 * K, rtol=0, atol=1e-13)
    f = np.zeros(8)
    assert ancf_tip_body_terms(BODY.params(), F, q, v, a, GRAVITY, 1.0, 1.0, f, np.empty((0, 0))) == (T, V)
    assert np.array_equal(f, force)


def test_momentum_about_the_hub_axis_is_noethers():
    """axis . H equals the generalized momentum v^T M xi on the rigid rotation xi of the
    tip state about the axis (r0, r0' turned, theta_1 chosen so that R turns with them)."""
    rng = np.random.default_rng(15)
    for point, axis in ((np.zeros(3), np.array([0.0, -1.0, 0.0])), (rng.standard_normal(3), rng.standard_normal(3))):
        F, q, v, _ = random_tip_state(rng)

        def turned(eps):
            Q = rotation(axis, eps)
            out = q.copy()
            out[0:3] = point + Q @ (q[0:3] - point)
            out[3:6] = Q @ q[3:6]
            m_new = Q @ frame_global(F, q[3:6], q[6])[:, 1]
            base = frame_global(F, out[3:6], 0.0)  # [tau m0 n0]
            out[6] = np.arctan2(m_new @ base[:, 2], m_new @ base[:, 1])
            out[6] += 2 * np.pi * np.round((q[6] - out[6]) / (2 * np.pi))
            return out

        xi = derivative(turned, 0.0, 1.0)
        M = BODY.ancf_terms(F, q, v, v, GRAVITY)[1]
        H = BODY.ancf_momentum_about_axis(F, q, v, point, axis)
        assert H == pytest.approx(v @ M @ xi, rel=1e-9)
    assert BODY.ancf_momentum_about_axis(F, q, v) == pytest.approx(
        BODY.ancf_momentum_about_axis(F, q, v, np.zeros(3), np.array([0.0, -2.0, 0.0])))


# --------------------------------------------------------------------------- frequencies
def tip_body_frequency_function(lam, mu, j):
    """Cantilever with a tip mass (mu = M / (rho A L)) and rotary inertia (j = J / (rho A L^3)),
    lam = beta L (Laura, Pombo & Susemihl 1974, J. Sound Vib. 37: 161-168):
    1 + cos cosh + mu lam (cos sinh - sin cosh) - j lam^3 (cosh sin + sinh cos)
      + mu j lam^4 (1 - cos cosh) = 0."""
    c, s, ch, sh = np.cos(lam), np.sin(lam), np.cosh(lam), np.sinh(lam)
    return 1 + c * ch + mu * lam * (c * sh - s * ch) - j * lam**3 * (ch * s + sh * c) + mu * j * lam**4 * (1 - c * ch)


def boundary_determinant(lam, mu, j):
    """The same equation derived here: w = A (cosh - cos) + B (sinh - sin) (clamped at 0) and at
    x = L: EI w'' = J w^2 w', EI w''' = -M w^2 w (from the variation of the Lagrangian), in
    units of beta; half the 2 x 2 determinant."""
    c, s, ch, sh = np.cos(lam), np.sin(lam), np.cosh(lam), np.sinh(lam)
    rows = np.array([[(ch + c) - j * lam**3 * (sh + s), (sh + s) - j * lam**3 * (ch - c)],
                     [(sh - s) + mu * lam * (ch - c), (ch + c) + mu * lam * (sh - s)]])
    return 0.5 * np.linalg.det(rows)


def tip_body_roots(mu, j, count=2):
    """The lowest ``count`` roots lam = beta L."""
    fun = lambda x: tip_body_frequency_function(x, mu, j) / np.cosh(x)  # noqa: E731
    grid = np.linspace(0.05, 15.0, 3000)
    vals = fun(grid)
    brackets = np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))
    roots = [brentq(fun, grid[i], grid[i + 1], xtol=1e-15) for i in brackets]
    return np.array(roots[:count])


def tip_body_frequencies_hz(section, length, mass, inertia, count=2):
    rho_a = section.mass_per_length
    lam = tip_body_roots(mass / (rho_a * length), inertia / (rho_a * length**3), count)
    return lam**2 / length**2 * np.sqrt(section.stiffness[2] / rho_a) / (2 * np.pi)


#: the frequency tests' tip body: mass about the beam's (0.489 kg), rotary inertia about m
#: that lowers the second weak-axis frequency from 4.52 Hz (mass only) to 3.14 Hz
TIP_MASS, TIP_J_M = 0.5, 0.02
FREQUENCY_BODY = TipBody(TIP_MASS, (0.6 * TIP_J_M, TIP_J_M, 0.8 * TIP_J_M))


def test_frequency_equation():
    rng = np.random.default_rng(16)
    for lam, mu, j in zip(rng.uniform(0.5, 10, 20), rng.uniform(0, 2, 20), rng.uniform(0, 0.1, 20)):
        expected = boundary_determinant(lam, mu, j)
        assert tip_body_frequency_function(lam, mu, j) == pytest.approx(expected, rel=1e-9, abs=1e-9)
    # limits: the bare cantilever (1 + cos cosh = 0) and Blevins' tip-mass table (M = rho A L: 1.24792)
    assert np.allclose(tip_body_roots(0.0, 0.0, 3), [1.8751040687, 4.6940911330, 7.8547574382], atol=1e-9)
    assert tip_body_roots(1.0, 0.0, 1)[0] == pytest.approx(1.24792, abs=2e-5)


def ancf_weak_frequencies(elements, body):
    """The single-beam system (fixed hub, no gravity) linearised about the straight state, the
    tip body's mass block added on the tip node's 8 coordinates, modes on the null space of
    the constraint Jacobian."""
    from hubbeam.system.beam import AncfBeam
    from hubbeam.system.multibody import single_beam_system

    beam = AncfBeam(L, elements, plate())
    system = single_beam_system(beam, radius=0.0, twist=0.0, motion="fixed")
    x, charts = system.initial_state(0.0)
    F = charts[0]
    K, M, A = system.linearised(x, np.zeros(system.n_constraints(True)), charts, held=True)
    tip = 1 + beam.node_slice(-1).start
    zero = np.zeros(8)
    M[tip : tip + 8, tip : tip + 8] += body.ancf_terms(F, x[tip : tip + 8], zero, zero, np.zeros(3))[1]
    N = null_space(A)
    w2, V = eigh(N.T @ K @ N, N.T @ M @ N)
    shapes = (N @ V)[1:]
    # weak axis: the deflection is along n = k_h = z at theta = 0, twist 0 (r_z, r'_z)
    along_n = np.array([8 * k + j for k in range(beam.nodes) for j in (2, 5)])
    weak = np.sum(shapes[along_n] ** 2, axis=0) > 0.5 * np.sum(shapes**2, axis=0)
    return np.sqrt(w2[weak][:2]) / (2 * np.pi)


#: meshes of the convergence studies
MESHES = (2, 4, 8, 16)


def check_convergence(errors):
    """Relative errors (mesh x mode): shrinking until they reach the 1e-6 floor set by the
    sections' own rotary inertia (rho I_y, which the closed form leaves out: ~1e-7 here),
    and below 0.1 % (in fact 1e-5) on the finest mesh."""
    errors = np.abs(np.asarray(errors))
    assert np.all(errors[-1] < 1e-5)
    for coarse, fine in zip(errors[:-1], errors[1:]):
        assert np.all((fine < 0.5 * coarse) | (fine < 1e-6))
    assert np.all(errors[0] > 1e-5)  # the study starts from a visibly unconverged mesh


def test_ancf_cantilever_with_tip_body_frequencies():
    exact = tip_body_frequencies_hz(plate(), L, TIP_MASS, TIP_J_M)
    bare = tip_body_frequencies_hz(plate(), L, TIP_MASS, 0.0)
    assert exact[1] < 0.75 * bare[1]  # the rotary inertia matters
    errors = [ancf_weak_frequencies(n, FREQUENCY_BODY) / exact - 1 for n in MESHES]
    check_convergence(errors)
