"""The FFR body with span-wise sections, pretwist and structural damping (FfrBeam(sections=...,
structural_damping=...)).

Oracles written here, independent of the package: the cantilever compliance of a pretwisted beam
as a quadrature of the rotated section compliance along the span, MacNeal & Harder's twisted
beam (1985), an Euler-Bernoulli Hermite finite-element model of a tapered cantilever (numpy's
Gauss rule, its own shape functions), the inertia of the sections sampled over their rotated
rectangles with a finer rule."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.linalg import eigh, expm

from hubbeam.elements.ffr.body import FfrBeam, skew
from hubbeam.elements.section import COLUMN, Section, SectionForm, SpanSections, saint_venant_torsion_constant
from hubbeam.elements.ffr.shape import displacement_matrix, line_shapes
from tests.conftest import E, H, L, RHO, B, plate, tapered_sections


# ----------------------------------------------------------------------------- uniform tables
@pytest.mark.parametrize("table", ["uniform", "two rectangles"])
def test_a_uniform_table_is_the_prismatic_beam(table):
    sec = plate()
    sections = (SpanSections.uniform(sec, L) if table == "uniform" else
                SpanSections(np.array([0.0, L]), SectionForm.RECTANGLE, np.array([[B, H], [B, H]]), np.zeros(2), sec))
    for stiffening in (False, True):
        a = FfrBeam(L, 4, sec, geometric_stiffening=stiffening)
        b = FfrBeam(L, 4, sec, geometric_stiffening=stiffening, sections=sections)
        for key, value in a.invariants.items():
            assert np.allclose(b.invariants[key], value, rtol=0, atol=1e-14 * np.max(np.abs(value))), key
        assert np.allclose(b.stiffness_matrix, a.stiffness_matrix, rtol=0, atol=1e-14 * np.max(a.stiffness_matrix))
        assert np.allclose(b.axial_integrals, sec.stiffness[0] * a.element_length, rtol=1e-14)
        assert np.allclose(b.centre_line_table["b"], B, rtol=1e-15)
        p = 1e-3 * np.random.default_rng(0).standard_normal(a.ndof)
        Ua, fa, Ka = a.elastic(p)
        Ub, fb, Kb = b.elastic(p)
        assert Ub == pytest.approx(Ua, rel=1e-13)
        assert np.allclose(fb, fa, rtol=0, atol=1e-13 * np.max(np.abs(fa)))
        assert b.surface_strain(p, 0.3, 0.0, H / 2) == pytest.approx(a.surface_strain(p, 0.3, 0.0, H / 2), rel=1e-13)


# ----------------------------------------------------------------------------- inertia
def test_inertia_invariants_are_the_volume_integrals_of_the_twisted_tapered_sections():
    """The kinetic energy M_v gives equals the kinetic energy of the volume sampled with a finer
    rule over every section's own rectangle, turned by its pretwist (m' = cos b j - sin b k)."""
    sections = tapered_sections(pretwist_deg=70.0, root=(0.05, 0.01), tip=(0.03, 0.004))
    beam = FfrBeam(L, 3, plate(), sections=sections, gauss_points=6)
    rng = np.random.default_rng(4)
    p, A0 = 1e-2 * rng.standard_normal(beam.ndof), expm(skew(rng.standard_normal(3)))
    v = rng.standard_normal(6 + beam.ndof)
    xg, wx = np.polynomial.legendre.leggauss(8)
    xg, wx = 0.5 * (xg + 1), 0.5 * wx
    sg, ws = np.polynomial.legendre.leggauss(3)
    sg, ws = 0.5 * sg, 0.5 * ws  # on [-1/2, 1/2]
    l = beam.element_length
    T = 0.0
    for e in range(beam.elements):
        for xi, wk in zip(xg, wx):
            x = (e + xi) * l
            b = np.interp(x, [0, L], [0.05, 0.03])
            h = np.interp(x, [0, L], [0.01, 0.004])
            beta = np.radians(70.0) * x / L
            m_axis, n_axis = np.array([np.cos(beta), -np.sin(beta)]), np.array([np.sin(beta), np.cos(beta)])
            shapes = line_shapes(np.array([xi]), l)
            for s, wy in zip(sg, ws):
                for t, wz in zip(sg, ws):
                    y, z = s * b * m_axis + t * h * n_axis
                    N = beam._scatter(e, displacement_matrix(shapes, 0, y, z))
                    r0 = np.array([x, y, z])
                    rdot = v[0:3] + A0 @ np.cross(v[3:6], r0 + N @ p) + A0 @ (N @ v[6:])
                    T += 0.5 * RHO * b * h * wk * l * wy * wz * rdot @ rdot
    assert 0.5 * v @ beam.mass_matrix(p, A0) @ v == pytest.approx(T, rel=1e-9)


# ----------------------------------------------------------------------------- pretwisted cantilever
def rotated_compliance_deflection(length, EI_y, EI_z, pretwist, force):
    """Tip deflection (y, z) of a cantilever under a tip force (F_y, F_z) in the root frame:
    u = int_0^L (L - x)^2 C(x) dx F with C = m' m'^T / EI_z + n' n'^T / EI_y, the section's
    axes m' = (cos b, -sin b), n' = (sin b, cos b) turned by the pretwist b(x) (the mount's
    sense); EI_y, EI_z, pretwist: functions of x."""
    def entry(i, j):
        def f(x):
            b = pretwist(x)
            m, n = np.array([np.cos(b), -np.sin(b)]), np.array([np.sin(b), np.cos(b)])
            return (length - x) ** 2 * (m[i] * m[j] / EI_z(x) + n[i] * n[j] / EI_y(x))
        return quad(f, 0.0, length, epsabs=0, epsrel=1e-13, limit=200)[0]

    C = np.array([[entry(0, 0), entry(0, 1)], [entry(1, 0), entry(1, 1)]])
    return C @ np.asarray(force, dtype=float)


def ffr_tip_deflection(beam, force):
    """The clamped FFR beam (body frame held) under a tip force (0, F_y, F_z): K p = T^T F, u = T p."""
    T = beam.displacement_row(beam.length)
    F = np.array([0.0, *force])
    p = np.linalg.solve(beam.stiffness_matrix, T.T @ F)
    return (T @ p)[1:]


@pytest.mark.parametrize("force", [(1.0, 0.0), (0.0, 1.0), (0.6, -0.8)])
def test_pretwisted_cantilever_deflection_converges_to_the_rotated_compliance(force):
    sections = tapered_sections(pretwist_deg=90.0)
    mat = plate()

    def dims(x):
        return np.interp(x, [0, L], [B, 0.6 * B]), np.interp(x, [0, L], [H, 0.6 * H])

    exact = rotated_compliance_deflection(L, lambda x: E * dims(x)[0] * dims(x)[1] ** 3 / 12,
                                          lambda x: E * dims(x)[1] * dims(x)[0] ** 3 / 12,
                                          lambda x: np.pi / 2 * x / L, force)
    errors = []
    for n in (2, 4, 8, 16, 32):
        u = ffr_tip_deflection(FfrBeam(L, n, mat, sections=sections), force)
        errors.append(np.linalg.norm(u - exact) / np.linalg.norm(exact))
    assert all(b < a for a, b in zip(errors, errors[1:]))
    # measured, force (1, 0): 1.1e-1, 2.8e-2, 4.7e-3, 4.8e-4, 3.6e-5 (about h^3.5)
    assert errors[-1] < 1e-4
    # the bending planes couple: a force along y moves the tip along z too
    if force == (1.0, 0.0):
        assert abs(exact[1]) > 0.1 * abs(exact[0])


def macneal_harder():
    """MacNeal & Harder (1985) twisted beam: L = 12, width 1.1, thickness 0.32, 90 deg pretwist,
    E = 29e6, nu = 0.22 (consistent units)."""
    E_, nu, b, h = 29.0e6, 0.22, 1.1, 0.32
    material = Section(b, h, 1.0, E_, E_ / (2 * (1 + nu)), saint_venant_torsion_constant(b, h))
    return SpanSections(np.array([0.0, 12.0]), SectionForm.RECTANGLE, np.array([[b, h], [b, h]]),
                        np.radians([0.0, 90.0]), material), material


def test_macneal_harder_twisted_beam():
    """Unit tip loads in the tip section's plane (along the root's z, the tip's width) and out of
    it (along the root's y, the tip's thickness): the published 5.424e-3 and 1.754e-3 come from
    shell and solid models with shear; the Euler-Bernoulli beam gives 5.4259e-3 (+0.03 %) and
    1.7462e-3 (-0.45 %; its shear flexibility L / (k G A) = 3.4e-6 would bring it to -0.25 %)."""
    sections, material = macneal_harder()
    beam = FfrBeam(12.0, 16, material, sections=sections)
    in_plane = ffr_tip_deflection(beam, (0.0, 1.0))[1]
    out_of_plane = ffr_tip_deflection(beam, (1.0, 0.0))[0]
    assert in_plane == pytest.approx(5.424e-3, rel=2e-3)
    assert out_of_plane == pytest.approx(1.754e-3, rel=6e-3)
    assert in_plane == pytest.approx(5.42588e-3, rel=1e-4)
    assert out_of_plane == pytest.approx(1.74618e-3, rel=1e-4)


# ----------------------------------------------------------------------------- tapered cantilever
def euler_bernoulli_frequencies(EI, rho_a, length, elements=60, count=3, tension=None):
    """Clamped-free bending frequencies (Hz) of EI(x), rho_A(x) (and an axial tension T(x), N:
    (EI w'')'' - (T w')' + rho_A w_tt = 0): cubic Hermite elements, 5-point Gauss (numpy), written
    here (60 elements: the three lowest converged to about 1e-7; more elements only add
    round-off, the stiffness's condition growing like elements^4)."""
    g, wg = np.polynomial.legendre.leggauss(5)
    xi, wg = 0.5 * (g + 1), 0.5 * wg
    l = length / elements
    n = 2 * (elements + 1)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    N = np.stack([1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3,
                  l * (-xi**2 + xi**3)], 1)
    N1 = np.stack([-6 * xi + 6 * xi**2, l * (1 - 4 * xi + 3 * xi**2), 6 * xi - 6 * xi**2,
                   l * (-2 * xi + 3 * xi**2)], 1) / l
    N2 = np.stack([-6 + 12 * xi, l * (-4 + 6 * xi), 6 - 12 * xi, l * (-2 + 6 * xi)], 1) / l**2
    for e in range(elements):
        x = (e + xi) * l
        d = slice(2 * e, 2 * e + 4)
        K[d, d] += l * np.einsum("q,qi,qj->ij", wg * EI(x), N2, N2)
        if tension is not None:
            K[d, d] += l * np.einsum("q,qi,qj->ij", wg * np.array([tension(v) for v in x]), N1, N1)
        M[d, d] += l * np.einsum("q,qi,qj->ij", wg * rho_a(x), N, N)
    w2 = eigh(K[2:, 2:], M[2:, 2:], eigvals_only=True, subset_by_index=[0, count - 1])
    return np.sqrt(w2) / (2 * np.pi)


def ffr_clamped_modes(beam):
    w2, phi = eigh(beam.stiffness_matrix, beam.invariants["Mff"])
    return np.sqrt(np.abs(w2)) / (2 * np.pi), phi


def test_tapered_cantilever_frequencies_against_an_euler_bernoulli_model():
    """Width 50 -> 25 mm and thickness 2.5 -> 1.25 mm linearly: the flap (w) modes of the FFR beam
    against a 60-element Euler-Bernoulli model of EI_y(x) = E b h^3 / 12, rho A = rho b h."""
    sections = tapered_sections(root=(B, H), tip=(0.5 * B, 0.5 * H), pretwist_deg=0.0)
    b = lambda x: np.interp(x, [0, L], [B, 0.5 * B])  # noqa: E731
    h = lambda x: np.interp(x, [0, L], [H, 0.5 * H])  # noqa: E731
    reference = euler_bernoulli_frequencies(lambda x: E * b(x) * h(x) ** 3 / 12, lambda x: RHO * b(x) * h(x), L)
    prismatic = euler_bernoulli_frequencies(lambda x: E * B * H**3 / 12 + 0 * x, lambda x: RHO * B * H + 0 * x, L)
    assert abs(reference[0] / prismatic[0] - 1) > 0.2  # the taper matters
    f, phi = ffr_clamped_modes(FfrBeam(L, 12, plate(), sections=sections))
    w_dofs = np.zeros(phi.shape[0], bool)
    w_dofs[3::6] = w_dofs[4::6] = True
    flap = [k for k in range(f.size) if np.sum(phi[w_dofs, k] ** 2) > 0.99 * np.sum(phi[:, k] ** 2)]
    # measured, 12 elements: 3.9e-7, 1.7e-5, 1.3e-4 (4 elements: 4.5e-5, 9.9e-4, 6.1e-3; 24: 3.5e-7, 6.4e-7, 4.0e-6)
    assert np.allclose(f[flap[:3]], reference, rtol=2e-4)


def test_modal_reduction_keeps_the_nodal_frequencies_of_a_tapered_pretwisted_beam():
    sections = tapered_sections(pretwist_deg=45.0)
    nodal = FfrBeam(L, 4, plate(), sections=sections)
    f_nodal, _ = ffr_clamped_modes(nodal)
    red = FfrBeam(L, 4, plate(), sections=sections, modes=24)
    assert np.allclose(red.frequencies_hz, f_nodal, rtol=1e-10)
    few = FfrBeam(L, 4, plate(), sections=sections, modes=5)
    assert np.allclose(few.frequencies_hz, f_nodal[:5], rtol=1e-10)


# ----------------------------------------------------------------------------- structural damping
def test_structural_damping_is_c_times_the_material_stiffness_nodal_and_modal():
    """c K on the elastic coordinates, also with geometric stiffening (its stiffness at the
    unstressed state); a reduced beam's is c diag(omega^2) over its Mff-normalised modes."""
    sections = tapered_sections()
    c = 3e-3
    for stiffening in (False, True):
        beam = FfrBeam(L, 4, plate(), sections=sections, geometric_stiffening=stiffening, structural_damping=c)
        K0 = beam.elastic(np.zeros(beam.ndof))[2]
        assert np.allclose(beam.damping_matrix, c * K0, rtol=0, atol=1e-14 * np.max(K0))
    red = FfrBeam(L, 4, plate(), sections=sections, structural_damping=c, modes=6)
    w2 = (2 * np.pi * red.frequencies_hz) ** 2
    assert np.allclose(red.damping_matrix, c * np.diag(w2), rtol=0, atol=1e-10 * c * w2.max())
    assert np.all(FfrBeam(L, 2, plate()).damping_matrix == 0.0)


def test_bad_tables_and_damping_are_refused():
    with pytest.raises(ValueError, match="sections"):
        FfrBeam(L, 2, plate(), sections=SpanSections.uniform(plate(), 1.0))
    with pytest.raises(ValueError, match="structural_damping"):
        FfrBeam(L, 2, plate(), structural_damping=-1e-3)


# ----------------------------------------------------------------------------- strain
def test_surface_strain_of_a_pretwisted_tapered_cantilever_under_a_tip_force():
    """At station x the bending moment is (L - x) F; on the local axes the fibre at the upper
    face (y', z') = (0, h(x)/2) strains eps = -(h/2)(L - x)(n' . F) / EI_y(x) (n' = (sin b, cos b)).
    Error measured on the strain of the whole force, (h/2)(L - x)|F| / EI_y: 64 elements 1.6e-4
    (the Hermite curvature is linear on an element, the exact one is not)."""
    sections = tapered_sections(pretwist_deg=90.0)
    beam = FfrBeam(L, 64, plate(), sections=sections)
    force = np.array([0.0, 0.3, -0.7])
    p = np.linalg.solve(beam.stiffness_matrix, beam.displacement_row(L).T @ force)
    for x in (0.2, 0.5, 1.0):
        b, h = np.interp(x, [0, L], [B, 0.6 * B]), np.interp(x, [0, L], [H, 0.6 * H])
        beta = np.pi / 2 * x / L
        n_axis = np.array([np.sin(beta), np.cos(beta)])
        expected = -(h / 2) * (L - x) * (n_axis @ force[1:]) / (E * b * h**3 / 12)
        assert beam.properties(x)[COLUMN["thickness"]] == pytest.approx(h, rel=1e-14)
        scale = (h / 2) * (L - x) * np.linalg.norm(force) / (E * b * h**3 / 12)
        assert abs(beam.surface_strain(p, x, 0.0, h / 2) - expected) < 1e-3 * scale
