"""Compiled FFR kernels (hubbeam.elements.ffr.kernels) against the Python FfrPart.

The Python part is the oracle: the kernels must give its forces and matrices to round-off,
and its central-difference stiffness (at rest and in steady rotation) to the differences'
accuracy. The Cardan derivative matrices are checked by differences of cardan.py."""

import numpy as np
import pytest

from hubbeam.elements.ffr import kernels as fk
from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.elements.ffr.cardan import angular_velocity_matrix, angular_velocity_matrix_rate, rotation_matrix
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.mount import Mount
from hubbeam.system.tip_body import TipBody
from tests.conftest import L, central_difference, plate, tapered_sections

BODY = TipBody(0.2, (1.0e-4, 2.0e-4, 2.5e-4), (0.01, 0.005, -0.003))
GRAVITY = np.array([0.3, -9.81, 0.7])


def make_part(stiffening=False, tip_loads=False, tip_body=None, elements=3, sections=None, structural_damping=0.0):
    beam = FfrBeam(L, elements, plate(), geometric_stiffening=stiffening, tip_body=tip_body, sections=sections,
                   structural_damping=structural_damping)
    loads = {}
    if tip_loads:
        loads = {"tip_force": np.array([3.0, -20.0, 12.0]), "tip_moment": np.array([0.4, -1.5, 2.0])}
    return FfrPart(beam, Mount(0.2, 0.1, 0.0, 0.05), **loads)


def random_state(part, rng, deform=2e-3, rate=3.0):
    n = part.ndof
    q = np.zeros(n)
    q[0:3] = rng.normal(size=3) * 0.3
    q[3:6] = rng.uniform(-1.2, 1.2, size=3)
    q[6:] = deform * rng.normal(size=n - 6)
    q[6::6] *= 0.05  # axial node displacements are much smaller than deflections
    v = rate * rng.normal(size=n)
    v[6:] *= 0.1
    acc = 10.0 * rng.normal(size=n)
    return q, v, acc


def close(a, b, tol):
    scale = max(np.max(np.abs(b)), 1e-300)
    return np.max(np.abs(a - b)) <= tol * scale


# ---------------------------------------------------------------------------- Cardan angles
@pytest.mark.parametrize("theta", [(0.3, -0.4, 1.1), (-2.0, 0.9, -0.6), (0.0, 0.0, 0.0), (1.3, 1.2, 2.9)])
def test_cardan_matrices_and_their_derivatives(theta):
    theta = np.array(theta)
    A, D = np.empty((3, 3)), np.empty((3, 3))
    fk.cardan(*theta, A, D)
    assert np.allclose(A, rotation_matrix(theta), rtol=0, atol=1e-15)
    assert np.allclose(D, angular_velocity_matrix(theta), rtol=0, atol=1e-15)
    dA, dD = np.empty((3, 3, 3)), np.empty((3, 3, 3))
    fk.cardan_derivatives(*theta, dA, dD)
    hstep = 1e-6
    for i in range(3):
        e = np.zeros(3)
        e[i] = hstep
        dA_fd = (rotation_matrix(theta + e) - rotation_matrix(theta - e)) / (2 * hstep)
        dD_fd = (angular_velocity_matrix(theta + e) - angular_velocity_matrix(theta - e)) / (2 * hstep)
        assert np.max(np.abs(dA[i] - dA_fd)) < 1e-9
        assert np.max(np.abs(dD[i] - dD_fd)) < 1e-9
    # the body angular velocity: A0^T dA0/dTheta_i = [D_i]x
    for i in range(3):
        Wi = A.T @ dA[i]
        assert np.allclose(Wi, -Wi.T, atol=1e-14)
        assert np.allclose([Wi[2, 1], Wi[0, 2], Wi[1, 0]], D[:, i], atol=1e-14)
    rates = np.array([0.7, -1.3, 2.1])
    t2, t3 = theta[1], theta[2]
    h = np.array(fk.cardan_rate(np.cos(t2), np.sin(t2), np.cos(t3), np.sin(t3), *rates))
    assert np.allclose(h, angular_velocity_matrix_rate(theta, rates), rtol=0, atol=1e-14)
    assert np.allclose(h, sum(dD[i] * rates[i] for i in range(3)) @ rates, rtol=0, atol=1e-14)


# ---------------------------------------------------------------------------- forces and matrices
CASES = {
    "plain": {},
    "stiffening": {"stiffening": True},
    "drag": {"damping": (0.4, 1.7)},
    "tip loads": {"tip_loads": True},
    "tip body": {"tip_body": BODY},
    "everything": {"stiffening": True, "damping": (0.4, 1.7), "tip_loads": True, "tip_body": BODY},
    "structural damping": {"structural_damping": 2e-3},
    "tapered, pretwisted, damped": {"sections": tapered_sections(), "structural_damping": 2e-3, "stiffening": True,
                                    "damping": (0.4, 1.7), "tip_loads": True, "tip_body": BODY},
}


@pytest.mark.parametrize("case", list(CASES))
def test_kernel_is_the_python_forces(case):
    opts = dict(CASES[case])
    damping = opts.pop("damping", (0.0, 0.0))
    part = make_part(**opts)
    arrays = fk.pack(part)
    rng = np.random.default_rng(list(CASES).index(case))
    for factor in (1.0, 0.6):
        q, v, acc = random_state(part, rng)
        f_py, (M_py, C_py, K_py) = part.forces(q, v, acc, GRAVITY, damping, tangent=True, factor=factor)
        f_k, (M_k, C_k, K_k), power = fk.forces(arrays, q, v, acc, GRAVITY, damping, tangent=True, factor=factor)
        # row blocks separately: the elastic force dwarfs the rest on p
        for rows in (slice(0, 3), slice(3, 6), slice(6, None)):
            assert close(f_k[rows], f_py[rows], 1e-12), rows
        assert close(M_k, M_py, 1e-12)
        assert close(K_k, K_py, 1e-12)
        if damping == (0.0, 0.0) and not part.beam.structural_damping:
            assert np.all(C_k == 0.0) and np.all(C_py == 0.0) and power == 0.0
        else:
            assert close(C_k, C_py, 1e-12)
            assert power == pytest.approx(part.dissipated_power(q, v, damping), rel=1e-12)
            assert power > 0.0
        # without the matrix, and the combined iteration matrix in one call
        f2, none, _ = fk.forces(arrays, q, v, acc, GRAVITY, damping, tangent=False, factor=factor)
        assert none is None and np.array_equal(f2, f_k)
        n = q.size
        block = np.full((n, n), np.nan)
        fk.ffr_body_terms(arrays.inv, q, v, acc, GRAVITY, arrays.tip, arrays.drag(damping), 2.0, 0.5, 0.25,
                          factor, True, np.empty(n), block)
        assert close(block, 2.0 * M_py + 0.5 * C_py + 0.25 * K_py, 1e-12)


def test_inertia_part_of_the_force_alone():
    """A soft beam at large rates: the inertia terms dominate and still agree to round-off."""
    from hubbeam.elements.section import Section

    beam = FfrBeam(L, 3, Section(0.05, 0.0025, 2700.0, 1.0, 0.4, 1e-9), tip_body=BODY)
    part = FfrPart(beam, Mount(0.1))
    arrays = fk.pack(part)
    rng = np.random.default_rng(5)
    q, v, acc = random_state(part, rng, deform=0.05, rate=8.0)
    v[6:] *= 10.0
    f_py, _ = part.forces(q, v, acc, np.zeros(3), (0.0, 0.0), tangent=False)
    f_k, _, _ = fk.forces(arrays, q, v, acc, np.zeros(3), tangent=False)
    assert close(f_k, f_py, 1e-12)


@pytest.mark.skipif("modes" not in FfrBeam.__dataclass_fields__, reason="no modal reduction")
@pytest.mark.parametrize("stiffening, real_blade", [(False, False), (True, False), (True, True)])
def test_modally_reduced_beam(stiffening, real_blade):
    """A modally reduced beam (dense invariants over eta): the same numbers as FfrPart; also
    tapered, pretwisted, with structural damping."""
    extra = {"sections": tapered_sections(), "structural_damping": 2e-3} if real_blade else {}
    beam = FfrBeam(L, 4, plate(), geometric_stiffening=stiffening, tip_body=BODY, modes=5, **extra)
    part = FfrPart(beam, Mount(0.2, 0.1), tip_force=np.array([3.0, -20.0, 12.0]),
                   tip_moment=np.array([0.4, -1.5, 2.0]))
    arrays = fk.pack(part)
    q, v, acc = random_state(part, np.random.default_rng(1))
    f_py, mats_py = part.forces(q, v, acc, GRAVITY, (0.4, 1.7), tangent=True, factor=0.8)
    f_k, mats_k, _ = fk.forces(arrays, q, v, acc, GRAVITY, (0.4, 1.7), tangent=True, factor=0.8)
    assert close(f_k, f_py, 1e-12)
    for a, b in zip(mats_k, mats_py):
        assert close(a, b, 1e-12)
    q[3:6] = (0.3, 0.4, -0.2)
    assert close(fk.static_stiffness(arrays, q, GRAVITY, 0.8, 4.0), part.stiffness(q, GRAVITY, (0.0, 0.0), 0.8, 4.0),
                 1e-6)


def test_padded_arrays_give_the_same_numbers():
    """Arrays zero-padded beyond nf (stacking beams of different meshes) read only nf."""
    part = make_part(stiffening=True, tip_loads=True, tip_body=BODY, sections=tapered_sections(),
                     structural_damping=2e-3)
    a = fk.pack(part)
    nf, extra = part.beam.ndof, 6

    def pad(x, axes, rows=0):
        width = [(0, 0)] * x.ndim
        for ax in axes:
            width[ax] = (0, extra)
        if rows:
            width[0] = (0, rows)
        return np.ascontiguousarray(np.pad(x, width))

    b = a._replace(Sbar=pad(a.Sbar, [1]), J=pad(a.J, [2]), II=pad(a.II, [2, 3]), Mff=pad(a.Mff, [0, 1]),
                   K=pad(a.K, [0, 1]), C_struct=pad(a.C_struct, [0, 1]), EAl=pad(a.EAl, [], rows=2),
                   mean_stretch=pad(a.mean_stretch, [1], rows=2),
                   mean_slope2=pad(a.mean_slope2, [1, 2], rows=2), tip_rows=pad(a.tip_rows, [1]),
                   tip_rotation_rows=pad(a.tip_rotation_rows, [1]), N_pts=pad(a.N_pts, [2], rows=3),
                   x_pts=pad(a.x_pts, [], rows=3), w_pts=pad(a.w_pts, [], rows=3), width=pad(a.width, [], rows=3))
    q, v, acc = random_state(part, np.random.default_rng(2))
    n = 6 + nf
    outs = []
    for arr in (a, b):
        force, block = np.empty(n), np.empty((n + 4, n + 4))
        power = fk.ffr_body_terms(arr.inv, q, v, acc, GRAVITY, arr.tip, arr.drag((0.4, 1.7)), 1.0, 0.5, 0.25, 1.0,
                                  True, force, block)
        load = np.empty((n, n))
        fk.ffr_load_stiffness(arr.inv, q, GRAVITY, arr.tip, 1.0, load)
        outs.append((force, block[:n, :n], power, load))
    for x, y in zip(*outs):
        assert np.allclose(x, y, rtol=1e-14, atol=1e-14 * np.max(np.abs(y)))


# ---------------------------------------------------------------------------- exact stiffness
THETAS = [(0.0, 0.0, 0.0), (-0.4, 0.25, -0.1), (1.1, -0.6, 0.8), (-2.5, 1.0, 2.2)]


def _at_rest(part, theta, rng, deform=5e-3):
    q, _, _ = random_state(part, rng, deform=deform)
    q[3:6] = theta
    return q


@pytest.mark.parametrize("theta", THETAS)
def test_load_stiffness_is_the_derivative_of_the_static_loads(theta):
    part = make_part(stiffening=True, tip_loads=True, tip_body=BODY)
    arrays = fk.pack(part)
    rng = np.random.default_rng(int(1000 * (theta[0] + 3)))
    q = _at_rest(part, theta, rng)
    n, factor = q.size, 0.8
    load = np.empty((n, n))
    fk.ffr_load_stiffness(arrays.inv, q, GRAVITY, arrays.tip, factor, load)
    z = np.zeros(n)

    def load_rows(qq):  # the Python static force without its elastic part
        f = part.forces(qq, z, z, GRAVITY, (0.0, 0.0), tangent=False, factor=factor)[0]
        f[6:] -= part.beam.elastic(qq[6:])[1]
        return f

    load_fd = central_difference(load_rows, q, 1e-6)
    assert close(load, load_fd, 1e-6)
    assert np.max(np.abs(load)) > 1.0  # the check is not void
    # K_el + load stiffness is FfrPart.stiffness (central differences of everything)
    K_exact = fk.static_stiffness(arrays, q, GRAVITY, factor)
    K_py = part.stiffness(q, GRAVITY, (0.0, 0.0), factor)
    assert close(K_exact, K_py, 1e-6)


@pytest.mark.parametrize("theta", THETAS[1:3])
def test_spin_stiffness_is_the_derivative_in_steady_rotation(theta):
    part = make_part(stiffening=True, tip_loads=True, tip_body=BODY)
    arrays = fk.pack(part)
    rng = np.random.default_rng(7)
    q = _at_rest(part, theta, rng)
    q[0:3] = part.mount.radius * np.array([np.cos(-theta[0]), 0.0, np.sin(-theta[0])]) + 0.01 * rng.normal(size=3)
    n, factor, spin = q.size, 0.7, 6.0
    w = -np.sqrt(factor) * spin * np.array([0.0, 1.0, 0.0])
    S = np.empty((n, n))
    fk.ffr_spin_stiffness(arrays.inv, q, w, S)
    z = np.zeros(n)

    def spin_rows(qq):
        vel, acc = part.steady_rotation_rates(qq, None, spin)
        moving = part.forces(qq, np.sqrt(factor) * vel, factor * acc, GRAVITY, (0.0, 0.0), tangent=False,
                             factor=factor)[0]
        return moving - part.forces(qq, z, z, GRAVITY, (0.0, 0.0), tangent=False, factor=factor)[0]

    assert close(S, central_difference(spin_rows, q, 1e-6), 1e-6)
    K_exact = fk.static_stiffness(arrays, q, GRAVITY, factor, spin)
    assert close(K_exact, part.stiffness(q, GRAVITY, (0.0, 0.0), factor, spin), 1e-6)


@pytest.mark.parametrize("structural", [0.0, 2e-3])
@pytest.mark.parametrize("damping", [(0.0, 0.0), (0.4, 1.7), (0.0, 2.5)])
def test_dissipated_power_alone_is_the_python_dissipated_power(damping, structural):
    """ffr_dissipated_power (the energy balance after each compiled step: drag and structural
    damping) gives FfrPart's dissipated power without evaluating the rest of the body terms."""
    part = make_part(stiffening=True, tip_body=BODY, structural_damping=structural)
    arrays = fk.pack(part)
    rng = np.random.default_rng(7)
    for _ in range(3):
        q, v, _ = random_state(part, rng)
        power = fk.ffr_dissipated_power(q, v, arrays.C_struct, arrays.damped, arrays.drag(damping))
        if damping == (0.0, 0.0) and not structural:
            assert power == 0.0
        else:
            assert power == pytest.approx(part.dissipated_power(q, v, damping), rel=1e-12)
            assert power > 0.0
