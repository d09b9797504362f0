"""Chains of beams (a beam on another's tip): two links clamped to each other are one beam of
their total length (statics and frequencies), for every pair of formulations, with twist,
precone and pretwist; a chain's Newton matrix is its residual's derivative."""

from __future__ import annotations

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.elements.section import SectionForm, SpanSections
from hubbeam.solvers.modal import modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.beam import AncfBeam
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.joints import Joint
from hubbeam.system.mount import Mount
from hubbeam.system.multibody import Hub, MultibodySystem
from tests.conftest import newton_matrix_and_differences, plate

TWIST, PRECONE, RADIUS = 0.3, 0.2, 0.2


def _part(formulation, length, elements, mount, sections=None):
    if formulation == "ancf":
        return AncfPart(AncfBeam(length, elements, plate(0.05, 0.01), sections=sections), mount)
    return FfrPart(FfrBeam(length, elements, plate(0.05, 0.01), sections=sections), mount)


def _pretwisted(length, start, end):
    """A uniform rectangle pretwisted linearly from ``start`` to ``end`` (rad, relative to its root)."""
    return SpanSections(np.array([0.0, length]), SectionForm.RECTANGLE, np.array([[0.05, 0.01]] * 2),
                        np.array([0.0, end - start]), plate(0.05, 0.01))


def _one_and_two(parent, child, gravity=(0.0, -9.81, 0.0), pretwist=0.0):
    """A 1 m beam of 8 elements, and two 0.5 m links of 4 clamped to each other (the second on
    the first's tip, its twist the first's plus the first's tip pretwist)."""
    one = MultibodySystem([_part(parent, 1.0, 8, Mount(RADIUS, TWIST, 0.0, PRECONE), _pretwisted(1.0, 0.0, pretwist))],
                          Hub("fixed"), gravity=gravity)
    first = _part(parent, 0.5, 4, Mount(RADIUS, TWIST, 0.0, PRECONE), _pretwisted(0.5, 0.0, 0.5 * pretwist))
    second = _part(child, 0.5, 4, Mount(0.0, TWIST + 0.5 * pretwist, 0.0, 0.0, parent=0),
                   _pretwisted(0.5, 0.5 * pretwist, pretwist))
    two = MultibodySystem([first, second], Hub("fixed"), gravity=gravity)
    return one, two


def test_two_ancf_links_clamped_are_one_beam():
    """Statics and the six lowest frequencies equal to the solver's tolerance (the same nodes, the same
    element matrices: the child's root clamped to the parent's tip node is the shared node),
    with twist, precone and a pretwist of 40 deg along the beam."""
    one, two = _one_and_two("ancf", "ancf", pretwist=np.radians(40.0))
    s1, s2 = solve_static(one), solve_static(two)
    tip1, tip2 = one.tip_position(s1.x, 0, s1.chart), two.tip_position(s2.x, 1, s2.chart)
    sag = np.linalg.norm(tip1 - one.tip_position(one.initial_state()[0], 0))
    assert sag > 1e-3
    assert np.max(np.abs(tip1 - tip2)) < 1e-7 * sag  # the static solver's tolerance
    f1 = modal_analysis(one, s1, count=6).frequencies_hz
    f2 = modal_analysis(two, s2, count=6).frequencies_hz
    assert np.allclose(f1, f2, rtol=1e-7)
    # the child's section at its root is the parent's tip section
    F1 = one.frames_at(s1.x, s1.chart, [0.5], 0)[0]
    F2 = two.frames_at(s2.x, s2.chart, [0.0], 1)[0]
    assert np.allclose(F1, F2, atol=1e-9)


# slow: a long validation run (CI runs it: python -m pytest -q -m slow)
@pytest.mark.slow
@pytest.mark.parametrize("parent, child", [("ancf", "ffr"), ("ffr", "ancf"), ("ffr", "ffr")])
def test_links_of_other_formulations_clamped_are_one_beam_in_the_linear_limit(parent, child):
    """FFR is linear in its elastic coordinates on its own frame, so two FFR-linked links differ
    from one beam by terms of second order in the deflection: the tip's difference, relative to
    the sag, falls in proportion to the load (gravity 1 and 0.1 m/s^2), and the frequencies about
    a small sag agree to 1e-4."""
    gaps = []
    for g in (1.0, 0.1):
        one, two = _one_and_two(parent, child, gravity=(0.0, -g, 0.0))
        ref, _ = _one_and_two("ancf", "ancf", gravity=(0.0, -g, 0.0))
        s1, s2 = solve_static(ref), solve_static(two)
        tip1, tip2 = ref.tip_position(s1.x, 0, s1.chart), two.tip_position(s2.x, 1, s2.chart)
        sag = np.linalg.norm(tip1 - ref.tip_position(ref.initial_state()[0], 0))
        gaps.append(np.max(np.abs(tip1 - tip2)) / sag)
    assert gaps[1] < 0.2 * gaps[0] + 1e-7
    assert gaps[1] < 1e-4
    f1 = modal_analysis(ref, s1, count=4).frequencies_hz
    f2 = modal_analysis(two, s2, count=4).frequencies_hz
    assert np.allclose(f1, f2, rtol=1e-4)


@pytest.mark.parametrize("parent, child", [
    ("ancf", "ffr"), ("ancf", "ancf"),
    # each the only test of its model (compiling it is most of a minute): with the slow runs
    pytest.param("ffr", "ancf", marks=pytest.mark.slow), pytest.param("ffr", "ffr", marks=pytest.mark.slow),
])
def test_newton_matrix_of_a_chain_on_joints_is_the_residuals_derivative(parent, child):
    """A child on a two-axis joint on the parent's tip, the parent on a flap hinge of a free
    hub: the Newton matrix's rows and columns of the joint angles and of the child's own
    coordinates against central differences of the residual."""
    first = _part(parent, 0.6, 2, Mount(RADIUS, TWIST, 0.0, PRECONE, joint=Joint.named("flap", stiffness=(5.0,))))
    second = _part(child, 0.5, 2, Mount(0.0, 0.2, 0.0, 0.1, parent=0,
                                        joint=Joint.named("lag", "pitch", damping=(0.3, 0.1))))
    system = MultibodySystem([first, second], Hub("free", 1.5), gravity=(0.0, -9.81, 0.0))
    A, D, _, _ = newton_matrix_and_differences(system, perturbation=0.01, stiffness="exact")
    layout = system.layout
    rows = [layout.z_of_x[layout.joint_x(k).start + i] for k in (0, 1) for i in range(layout.joint_dofs[k])]
    scale = np.max(np.abs(D))
    for r in rows:
        assert np.max(np.abs(A[r] - D[r])) <= 2e-4 * scale, r
        assert np.max(np.abs(A[:, r] - D[:, r])) <= 2e-4 * scale, r


@pytest.mark.parametrize("joint", [None, ("lag", "pitch")])
@pytest.mark.parametrize("stiffness", ["dynamic", "exact"])
def test_the_band_holds_every_entry_of_a_chain_junction(joint, stiffness):
    """Three ANCF links on each other's tips (clamped to the tip, or on a two-axis joint), the
    first on a flap hinge of a free hub: the Newton matrix assembled in the band that
    ancf_bandwidth sizes (the clamp's Jacobian and Hessian pairs only: 17 or so at a junction,
    not the 21 of its whole span) equals the one assembled in a band as wide as the matrix, at
    a generic state (coordinates, rates and multipliers perturbed at random): no entry falls
    outside the band."""

    def system():
        def mount(parent, twist):
            return Mount(0.0, twist, 0.0, 0.1, parent=parent, joint=Joint.named(*joint) if joint else None)

        parts = [_part("ancf", 0.6, 2, Mount(RADIUS, TWIST, 0.0, PRECONE, joint=Joint.named("flap", stiffness=(5.0,)))),
                 _part("ancf", 0.5, 2, mount(0, 0.2)), _part("ancf", 0.4, 2, mount(1, -0.3))]
        return MultibodySystem(parts, Hub("free", 1.5), gravity=(0.0, -9.81, 0.0))

    tight, wide = system(), system()
    wide.bandwidth_for = lambda layout: layout.nz - layout.border - 1
    assert tight.bandwidth < wide.bandwidth
    x, F = tight.initial_state(0.3)
    rng = np.random.default_rng(7)
    x[1:] += 0.02 * rng.normal(size=x.size - 1)
    v, acc = rng.normal(size=x.size), rng.normal(size=x.size)
    lam = rng.normal(size=tight.layout.n_lambda)
    matrices = [s.equations(x, v, acc, lam, F, 0.3, 1.0, 0.5, 0.3e-6, s.mass_scale, stiffness=stiffness)[1].to_dense()
                for s in (tight, wide)]
    assert np.max(np.abs(matrices[0] - matrices[1])) <= 1e-14 * np.max(np.abs(matrices[1]))
