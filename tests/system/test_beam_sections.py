"""An ANCF beam with span-wise sections, pretwist and structural damping: the element terms.

Independent checks: the pretwisted stress-free state carries no strain energy and rigid
motions of it none either; the internal force is the gradient of the energy; the tangent and
the damping matrix are differences of the force in q and in q_dot; the dissipated power is
the damping force's power; a uniform table is the prismatic beam."""

import numpy as np
import pytest

from hubbeam.elements.section import SectionForm, SpanSections
from hubbeam.system.assembly import add_element_blocks_dense
from hubbeam.system.beam import AncfBeam
from hubbeam.system.mount import Mount
from tests.conftest import central_difference, plate, rotation

LENGTH = 1.2
C_DAMP = 2e-3  # s


def blade(elements=3, damping=0.0):
    """A tapered rectangle, pretwisted 0 -> 15 -> 50 deg (a kink in the rate at x = 0.5 m)."""
    table = SpanSections(np.array([0.0, 0.5, LENGTH]), SectionForm.RECTANGLE,
                         [[0.06, 0.004], [0.05, 0.0035], [0.03, 0.002]], np.radians([0.0, 15.0, 50.0]),
                         material=plate())
    return AncfBeam(LENGTH, elements, plate(), sections=table, structural_damping=damping)


def dense(beam, blocks):
    K = np.zeros((beam.ndof, beam.ndof))
    add_element_blocks_dense(K, blocks, 0, 1.0)
    return K


def perturbed(beam, seed, amplitude=0.02):
    q, F = beam.straight_state(np.zeros(3), Mount(0.0, 0.3).frame(0.0))
    rng = np.random.default_rng(seed)
    return q + amplitude * rng.normal(size=q.size), F, rng


def test_the_straight_state_carries_the_pretwist():
    """The section at x is the root section turned by -pretwist(x) about the axis (the sense of
    the mount's twist); at the stations, where the node values are exact."""
    beam = blade(elements=12)  # node spacing 0.1 m: x = 0.5 and 1.2 are nodes
    root = Mount(0.0, 0.3).frame(0.0)
    q, F = beam.straight_state(np.zeros(3), root)
    for x, deg in ((0.5, 15.0), (LENGTH, 50.0)):
        expected = rotation(root[:, 0], -np.radians(deg)) @ root
        assert np.allclose(beam.frame_at(q, F, x), expected, atol=1e-12)


@pytest.mark.parametrize("axis,angle", [([0, 1, 0], 90), ([0, 0, 1], 180), ([1, 2, 3], 137)])
def test_rigid_motions_of_the_pretwisted_beam_carry_no_strain_energy(axis, angle):
    beam = blade()
    frame = rotation(axis, np.radians(angle)) @ Mount(0.0, np.radians(45)).frame(0.0)
    q, F = beam.straight_state(np.array([0.3, -2.0, 5.0]), frame)
    U, f, _ = beam.elastic(q, F)
    # compare: a twist of 1 % of the pretwist rate costs GJ (0.01 * 0.7 rad/m)^2 L / 2 ~ 3e-4 J
    assert abs(U) < 1e-20
    assert np.max(np.abs(f)) < 1e-6  # N; EA ~ 1e7 N
    # a beam without the reference strains would be loaded: the pretwist alone would cost energy
    untwisted = AncfBeam(LENGTH, 3, plate())
    assert untwisted.elastic(q, F)[0] > 1e-3


def test_internal_force_is_the_gradient_of_the_energy_of_a_pretwisted_tapered_beam():
    beam = blade()
    q, F, _ = perturbed(beam, 1)
    U, f, _ = beam.elastic(q, F)
    f_fd = central_difference(lambda p: [beam.elastic(p, F, tangent=False)[0]], q, 1e-7)[0]
    assert U > 0
    assert np.max(np.abs(f - f_fd)) < 1e-6 * np.max(np.abs(f))


def test_the_newton_matrix_of_the_damped_resultants_is_their_derivative():
    """blocks(coef_c, coef_k) = coef_k d(force)/dq + coef_c d(force)/d(qdot), force elastic plus damping."""
    beam = blade(damping=C_DAMP)
    q, F, rng = perturbed(beam, 2)
    qdot = 5.0 * rng.normal(size=q.size)
    K = dense(beam, beam.internal(q, qdot, F, 0.0, 1.0)[2])
    K_fd = central_difference(lambda p: beam.internal(p, qdot, F, 0.0, None)[1], q, 1e-7)
    assert np.max(np.abs(K - K_fd)) < 2e-6 * np.max(np.abs(K))
    C = dense(beam, beam.internal(q, qdot, F, 1.0, 0.0)[2])
    C_fd = central_difference(lambda v: beam.internal(q, v, F, 0.0, None)[1], qdot, 1e-3)
    assert np.max(np.abs(C)) > 0
    assert np.max(np.abs(C - C_fd)) < 1e-8 * np.max(np.abs(C))  # the force is linear in qdot
    assert np.allclose(C, C.T, atol=1e-12 * np.max(np.abs(C)))


def test_the_dissipated_power_is_the_power_of_the_damping_force():
    beam = blade(damping=C_DAMP)
    q, F, rng = perturbed(beam, 3)
    qdot = rng.normal(size=q.size)
    _, f_damped, _, power = beam.internal(q, qdot, F, 0.0, None)
    f_elastic = beam.elastic(q, F, tangent=False)[1]
    assert power > 0
    assert power == pytest.approx((f_damped - f_elastic) @ qdot, rel=1e-10)
    # about the stress-free state the damping force is c K qdot (Kelvin-Voigt: c times the stiffness)
    q0, F0 = beam.straight_state(np.zeros(3), Mount(0.0, 0.3).frame(0.0))
    K0 = dense(beam, beam.elastic(q0, F0)[2])
    f0 = beam.internal(q0, qdot, F0, 0.0, None)[1]
    assert f0 == pytest.approx(C_DAMP * K0 @ qdot, rel=1e-9, abs=1e-9 * np.max(np.abs(C_DAMP * K0 @ qdot)))


def test_rigid_velocities_dissipate_nothing():
    beam = blade(damping=C_DAMP)
    q, F = beam.straight_state(np.zeros(3), Mount(0.0, 0.2).frame(0.0))
    # a translation and a rotation about the beam axis (d theta_1/dt = w, r0' fixed)
    qdot = np.tile([0.3, -0.2, 0.5, 0.0, 0.0, 0.0, 0.7, 0.0], beam.nodes)
    power = beam.internal(q, qdot, F, 0.0, None)[3]
    assert abs(power) < 1e-20


def test_a_uniform_table_is_the_prismatic_beam():
    section = plate()
    prismatic = AncfBeam(LENGTH, 4, section)
    table = AncfBeam(LENGTH, 4, section, sections=SpanSections.uniform(section, LENGTH))
    q, F, rng = perturbed(prismatic, 4)
    qdot = rng.normal(size=q.size)
    for a, b in zip(prismatic.elastic(q, F), table.elastic(q, F)):
        assert np.array_equal(a, b) if np.ndim(a) else a == b
    assert np.array_equal(prismatic.mass_blocks(q, F), table.mass_blocks(q, F))
    assert np.array_equal(prismatic.rotary_inertia(q, qdot, F)[1], table.rotary_inertia(q, qdot, F)[1])
    for a, b in zip(prismatic.drag(qdot, 1.0, 2.0), table.drag(qdot, 1.0, 2.0)):
        assert np.array_equal(a, b)
    g = np.array([0.0, -9.81, 0.0])
    assert np.array_equal(prismatic.gravity_load(g), table.gravity_load(g))
    assert np.array_equal(prismatic.gravity_load(g), prismatic.distributed_load(section.mass_per_length * g))


def test_tapered_mass_and_gravity_integrate_the_table():
    """Total mass from the translational mass matrix and the weight from the gravity load:
    int rho A dx of the linear taper, by hand."""
    b0, h0, b1, h1 = 0.06, 0.004, 0.03, 0.002
    table = SpanSections(np.array([0.0, LENGTH]), SectionForm.RECTANGLE, [[b0, h0], [b1, h1]], [0.0, 0.0],
                         material=plate())
    beam = AncfBeam(LENGTH, 5, plate(), sections=table)
    # int_0^L b(x) h(x) dx, b and h linear: L (b0 h0 + b1 h1 + (b0 h1 + b1 h0) / 2) / 3
    mass = 2700.0 * LENGTH * (b0 * h0 + b1 * h1 + (b0 * h1 + b1 * h0) / 2) / 3
    q, F = beam.straight_state(np.zeros(3), np.eye(3))
    M = dense(beam, beam.mass_blocks(q, F))
    translation = np.tile([0, 1.0, 0, 0, 0, 0, 0, 0], beam.nodes)
    assert translation @ M @ translation == pytest.approx(mass, rel=1e-12)
    assert beam.gravity_load(np.array([0, -9.81, 0])) @ translation == pytest.approx(-9.81 * mass, rel=1e-12)


def test_sections_must_span_the_beam():
    table = SpanSections.uniform(plate(), 1.0)
    with pytest.raises(ValueError, match="length"):
        AncfBeam(1.2, 3, plate(), sections=table)
    with pytest.raises(ValueError, match="structural_damping"):
        AncfBeam(1.0, 3, plate(), structural_damping=-1.0)


def test_surface_strain_is_measured_from_the_pretwisted_state():
    """The stress-free pretwisted state, wherever it is placed, reads zero strain."""
    beam = blade(elements=5)  # stations between nodes too
    q, F = beam.straight_state(np.array([1.0, 2.0, 3.0]), rotation([1, 1, 0], 0.7))
    for x in (0.0, 0.3, 0.5, 0.9, LENGTH):
        for y, z in ((0.0, 0.002), (0.02, -0.001)):
            assert abs(beam.surface_strain(q, F, x, y, z)) < 1e-12


def test_a_change_of_chart_keeps_the_pretwisted_beam_stress_free():
    """Remapping theta_1 to another chart moves no section: the stress-free state stays so."""
    from hubbeam.elements.ancf.chart import frame_from_director
    from hubbeam.system.ancf_part import AncfPart

    part = AncfPart(blade(elements=4), Mount(0.0, 0.4))
    q, F = part.initial_state(np.zeros(3), part.mount.frame(0.0), np.eye(3))
    F_new = frame_from_director(np.array([0.3, -0.8, 0.5]) / np.linalg.norm([0.3, -0.8, 0.5]))
    q_new = part.remap(q, F, F_new)
    assert not np.allclose(q_new, q)  # the twist coordinates did change
    assert abs(part.beam.elastic(q_new, F_new)[0]) < 1e-20
    for x in (0.2, 0.7, LENGTH):
        assert np.allclose(part.frame_at(q_new, F_new, x), part.frame_at(q, F, x), atol=1e-12)
