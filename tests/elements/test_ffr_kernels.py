"""Compiled FFR kernels (hubbeam.elements.ffr.kernels) against the Python FfrPart, in v-space.

The Python part is the oracle: the kernels must give its v-space forces and matrices (on
v = [r_C', omega^b, p']) to round-off. The projection on the frame's coordinates is the
system's (tests/system/test_ffr_system.py)."""

import numpy as np
import pytest

from hubbeam.elements.ffr import constants as fc
from hubbeam.elements.ffr import kernels as fk
from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.system.rotations import rotation_vector_matrix
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.mount import Mount
from hubbeam.system.tip_body import TipBody
from tests.conftest import L, plate, tapered_sections

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
    """(A, p, vb, vdot): a body frame, elastic coordinates, v-space rates and accelerations."""
    nf = part.ndof
    A = rotation_vector_matrix(rng.uniform(-1.2, 1.2, size=3))
    p = deform * rng.normal(size=nf)
    p[::6] *= 0.05  # axial node displacements are much smaller than deflections
    vb = rate * rng.normal(size=6 + nf)
    vb[6:] *= 0.1
    vdot = 10.0 * rng.normal(size=6 + nf)
    return A, p, vb, vdot


def close(a, b, tol):
    scale = max(np.max(np.abs(b)), 1e-300)
    return np.max(np.abs(a - b)) <= tol * scale


def kernel(arrays, A, p, vb, vdot, gravity, damping=(0.0, 0.0), factor=1.0, want_matrix=True):
    """(fv, Mv, Cv, K_el, power) of the kernel."""
    n, nf = vb.size, p.size
    fv, Mv = np.empty(n), np.empty((n, n))
    Cv, K_el = (np.empty((n, n)), np.empty((nf, nf))) if want_matrix else (np.empty((0, 0)), np.empty((nf, nf)))
    power = fk.ffr_vspace_terms(arrays.inv, A, p, vb, vdot, np.asarray(gravity, dtype=float), arrays.tip,
                                arrays.drag(damping), float(factor), want_matrix, fv, Mv, Cv, K_el, arrays.work())
    return fv, Mv, Cv, K_el, power


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
    arrays = fc.pack(part)
    rng = np.random.default_rng(list(CASES).index(case))
    nf = part.ndof
    for factor in (1.0, 0.6):
        A, p, vb, vdot = random_state(part, rng)
        f_py, (M_py, C_py, K_py) = part.vspace_forces(A, p, vb, vdot, GRAVITY, damping, tangent=True, factor=factor)
        f_k, M_k, C_k, K_k, power = kernel(arrays, A, p, vb, vdot, GRAVITY, damping, factor)
        # row blocks separately: the elastic force dwarfs the rest on p
        for rows in (slice(0, 3), slice(3, 6), slice(6, None)):
            assert close(f_k[rows], f_py[rows], 1e-12), rows
        assert close(M_k, M_py, 1e-12)
        assert close(K_k, K_py[6:, 6:], 1e-12)
        C_k[6:, 6:] += part.beam.damping_matrix  # the system adds the structural damping on p
        if damping == (0.0, 0.0) and not part.beam.structural_damping:
            assert np.all(C_k == 0.0) and np.all(C_py == 0.0) and power == 0.0
        else:
            assert close(C_k, C_py, 1e-12)
            assert power == pytest.approx(part.dissipated_power(A, p, vb, damping), rel=1e-12)
            assert power > 0.0
        # without the matrix: the same force
        f2, *_ = kernel(arrays, A, p, vb, vdot, GRAVITY, damping, factor, want_matrix=False)
        assert np.array_equal(f2, f_k)
        assert nf == p.size


def test_inertia_part_of_the_force_alone():
    """A soft beam at large rates: the inertia terms dominate and still agree to round-off."""
    from hubbeam.elements.section import Section

    beam = FfrBeam(L, 3, Section(0.05, 0.0025, 2700.0, 1.0, 0.4, 1e-9), tip_body=BODY)
    part = FfrPart(beam, Mount(0.1))
    arrays = fc.pack(part)
    rng = np.random.default_rng(5)
    A, p, vb, vdot = random_state(part, rng, deform=0.05, rate=8.0)
    vb[6:] *= 10.0
    f_py, _ = part.vspace_forces(A, p, vb, vdot, np.zeros(3), (0.0, 0.0), tangent=False)
    f_k, *_ = kernel(arrays, A, p, vb, vdot, np.zeros(3), want_matrix=False)
    assert close(f_k, f_py, 1e-12)


@pytest.mark.parametrize("stiffening, real_blade", [(False, False), (True, False), (True, True)])
def test_modally_reduced_beam(stiffening, real_blade):
    """A modally reduced beam (dense invariants over eta): the same numbers as FfrPart; also
    tapered, pretwisted, with structural damping."""
    extra = {"sections": tapered_sections(), "structural_damping": 2e-3} if real_blade else {}
    beam = FfrBeam(L, 4, plate(), geometric_stiffening=stiffening, tip_body=BODY, modes=5, **extra)
    part = FfrPart(beam, Mount(0.2, 0.1), tip_force=np.array([3.0, -20.0, 12.0]),
                   tip_moment=np.array([0.4, -1.5, 2.0]))
    arrays = fc.pack(part)
    A, p, vb, vdot = random_state(part, np.random.default_rng(1))
    f_py, (M_py, C_py, K_py) = part.vspace_forces(A, p, vb, vdot, GRAVITY, (0.4, 1.7), tangent=True, factor=0.8)
    f_k, M_k, C_k, K_k, _ = kernel(arrays, A, p, vb, vdot, GRAVITY, (0.4, 1.7), 0.8)
    C_k[6:, 6:] += part.beam.damping_matrix
    assert close(f_k, f_py, 1e-12)
    for a, b in ((M_k, M_py), (C_k, C_py), (K_k, K_py[6:, 6:])):
        assert close(a, b, 1e-12)


@pytest.mark.parametrize("modes", [None, 5])
def test_moments_of_every_entry_are_the_sparse_moments(modes):
    """A modal beam's II holds every entry (9 nf^2 of them): the kernels contract it without the
    column indices (kernels._dense_moments), which must give the sparse loops' numbers to the last
    bit (the same sums, term for term) and both the dense contraction of II (3, 3, nf, nf) with p
    and p' to rounding; a nodal beam's II (about 6 % of its entries) takes the sparse loops."""
    beam = FfrBeam(L, 4, plate(), tip_body=BODY, modes=modes)
    II = beam.invariants["II"]
    start, column, value = fk.sparse_entries(II)
    nf = II.shape[2]
    assert (start[-1] == 9 * nf * nf) == (modes is not None)
    rng = np.random.default_rng(3)
    p, pd = rng.normal(size=nf), rng.normal(size=nf)
    Q2, Q2d, Q2s, Q2ds = (np.zeros((3, 3, nf)) for _ in range(4))
    fk._sparse_moments(start, column, value, p, pd, True, nf, Q2s, Q2ds)
    if modes is not None:
        fk._dense_moments(value, p, pd, True, nf, Q2, Q2d)
        assert np.array_equal(Q2, Q2s) and np.array_equal(Q2d, Q2ds)
    off = ~np.eye(3, dtype=bool)
    assert close(Q2s, np.einsum("klfg,f->klg", II, p), 1e-14)
    assert close(Q2ds[off], np.einsum("klfg,f->klg", II, pd)[off], 1e-14)


def test_padded_arrays_give_the_same_numbers():
    """Arrays zero-padded beyond nf (stacking beams of different meshes) read only nf."""
    part = make_part(stiffening=True, tip_loads=True, tip_body=BODY, sections=tapered_sections(),
                     structural_damping=2e-3)
    a = fc.pack(part)
    extra = 6

    def pad(x, axes, rows=0):
        width = [(0, 0)] * x.ndim
        for ax in axes:
            width[ax] = (0, extra)
        if rows:
            width[0] = (0, rows)
        return np.ascontiguousarray(np.pad(x, width))

    b = a._replace(Sbar=pad(a.Sbar, [1]), J=pad(a.J, [2]), II_column=pad(a.II_column, [], rows=extra),
                   II_value=pad(a.II_value, [], rows=extra), Mff=pad(a.Mff, [0, 1]),
                   K=pad(a.K, [0, 1]), C_struct=pad(a.C_struct, [0, 1]), EAl=pad(a.EAl, [], rows=2),
                   mean_stretch=pad(a.mean_stretch, [1], rows=2),
                   mean_slope2=pad(a.mean_slope2, [1, 2], rows=2), tip_rows=pad(a.tip_rows, [1]),
                   tip_rotation_rows=pad(a.tip_rotation_rows, [1]), N_pts=pad(a.N_pts, [2], rows=3),
                   N_span=pad(a.N_span, [], rows=3),
                   x_pts=pad(a.x_pts, [], rows=3), w_pts=pad(a.w_pts, [], rows=3), width=pad(a.width, [], rows=3))
    A, p, vb, vdot = random_state(part, np.random.default_rng(2))
    outs = [kernel(arr, A, p, vb, vdot, GRAVITY, (0.4, 1.7)) for arr in (a, b)]
    for x, y in zip(*outs):
        assert np.allclose(x, y, rtol=1e-14, atol=1e-14 * np.max(np.abs(y)))


@pytest.mark.parametrize("structural", [0.0, 2e-3])
@pytest.mark.parametrize("damping", [(0.0, 0.0), (0.4, 1.7), (0.0, 2.5)])
def test_dissipated_power_alone_is_the_python_dissipated_power(damping, structural):
    """ffr_dissipated_power (the energy balance after each compiled step: drag and structural
    damping) gives FfrPart's dissipated power without evaluating the rest of the body terms."""
    part = make_part(stiffening=True, tip_body=BODY, structural_damping=structural)
    arrays = fc.pack(part)
    rng = np.random.default_rng(7)
    for _ in range(3):
        A, p, vb, _ = random_state(part, rng)
        power = fk.ffr_dissipated_power(A, p, vb, arrays.C_struct, arrays.damped, arrays.drag(damping))
        if damping == (0.0, 0.0) and not structural:
            assert power == 0.0
        else:
            assert power == pytest.approx(part.dissipated_power(A, p, vb, damping), rel=1e-12)
            assert power > 0.0
