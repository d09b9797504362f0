"""Mode labels from the kinetic-energy split, against closed-form families; span shapes against
the Euler-Bernoulli shape; the MAC and the matching."""

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.solvers.modal import modal_analysis
from hubbeam.solvers.mode_shapes import (CONFIDENT_MAC, eigenspaces, energy_fractions, follow, mac_matrix, match_modes,
                                         mode_label, span_shapes, subspace_mac)
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.multibody import single_beam_system
from tests.conftest import RHO, L, plate

BETA_L = np.array([1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349, 14.1371683910, 17.2787595321,
                   20.4203522457])


def _modes(beam_class, twist_deg, count, motion="fixed", elements=8, **kw):
    system = single_beam_system(beam_class(L, elements, plate()), radius=0.35, twist=np.radians(twist_deg), motion=motion,
                                **kw)
    st = solve_static(system, load_steps=1)
    return system, st, modal_analysis(system, st, count=count)


def _analytic_families(twist_deg):
    """Closed-form clamped-free frequencies (Hz) of the plate and their families, ascending:
    Euler-Bernoulli bending in each plane, St-Venant torsion, axial. The plate laid flat (twist
    90 deg) bends about its weak axis (EI_y) out of the hub plane (flap), about its strong axis
    (EI_z) in it (lag); at twist 0 the other way round."""
    sec = plate()
    EA, GJ, EIy, EIz = sec.stiffness
    rhoA = sec.mass_per_length
    weak = BETA_L**2 / (2 * np.pi) * np.sqrt(EIy / (rhoA * L**4))
    strong = BETA_L**2 / (2 * np.pi) * np.sqrt(EIz / (rhoA * L**4))
    k = np.arange(1, 4)
    torsion = (2 * k - 1) / (4 * L) * np.sqrt(GJ / (RHO * (sec.i_y + sec.i_z)))
    axial = (2 * k - 1) / (4 * L) * np.sqrt(EA / rhoA)
    flap, lag = (weak, strong) if twist_deg == 90 else (strong, weak)
    rows = [(f, "flap") for f in flap] + [(f, "lag") for f in lag] + [(f, "torsion") for f in torsion] + \
           [(f, "axial") for f in axial]
    rows.sort()
    return np.array([f for f, _ in rows]), [name for _, name in rows]


@pytest.mark.parametrize("beam_class", [AncfBeam, FfrBeam])
@pytest.mark.parametrize("twist_deg", [90, 0])
def test_labels_follow_the_closed_form_families(beam_class, twist_deg):
    """The clamped plate (0.05 x 0.0025, hub held): the label sequence of the lowest eight modes
    is the family sequence of the sorted closed-form frequencies, and each frequency is its
    family's closed form (to 1 %: rotary inertia and the 10-element mesh)."""
    f_ref, families = _analytic_families(twist_deg)
    system, st, modes = _modes(beam_class, twist_deg, count=8, elements=10)
    labels = [mode_label(energy_fractions(system, st.x, st.chart, u)) for u in modes.shapes.T]
    assert labels == families[:8]
    assert np.allclose(modes.frequencies_hz, f_ref[:8], rtol=1e-2)
    if twist_deg == 90:
        assert labels[:3] == ["flap"] * 3  # the thin direction bends first


@pytest.mark.parametrize("beam_class", [AncfBeam, FfrBeam])
def test_plate_at_45_deg_bends_in_flap_and_lag_alike(beam_class):
    system, st, modes = _modes(beam_class, 45, count=6)
    fractions = [energy_fractions(system, st.x, st.chart, u) for u in modes.shapes.T]
    labels = [mode_label(f) for f in fractions]
    assert labels == ["flap+lag"] * 5 + ["torsion"]
    for f in fractions[:5]:  # principal axes at 45 deg: half of the motion in each plane
        assert f["flap"] == pytest.approx(0.5, abs=1e-3) and f["lag"] == pytest.approx(0.5, abs=1e-3)


def test_free_hub_adds_hub_content_to_the_in_plane_modes_only():
    """Twist 0: the weak-axis bending is in the hub plane (lag) and turns a free hub of small
    inertia; the out-of-plane (flap) modes leave it at rest."""
    system, st, modes = _modes(AncfBeam, 0, count=4, motion="free", hub_inertia=0.2)
    fractions = [energy_fractions(system, st.x, st.chart, u) for u in modes.shapes.T]
    labels = [mode_label(f) for f in fractions]
    lag = [f for f, name in zip(fractions, labels) if "lag" in name]
    flap = [f for f, name in zip(fractions, labels) if name == "flap"]
    assert lag and flap
    assert lag[0]["hub"] > 0.01
    assert all(f["hub"] < 1e-10 for f in flap)
    # the split of a free-hub mode still adds up to the whole kinetic energy u^T M u / 2 = 1/2
    for u in modes.shapes.T:
        assert sum(system.kinetic_energy_split(st.x, st.chart, u).values()) == pytest.approx(0.5, rel=1e-9)


def test_span_shape_of_the_first_flap_mode_is_the_euler_bernoulli_shape():
    """The first flap mode's deflection along the span against the closed-form clamped-free shape."""
    system, st, modes = _modes(AncfBeam, 90, count=1)
    xs, disp, twist = span_shapes(system, st.x, st.chart, modes.shapes)[0]
    w = disp[0, :, 1]
    b = BETA_L[0] / L
    sigma = (np.cosh(BETA_L[0]) + np.cos(BETA_L[0])) / (np.sinh(BETA_L[0]) + np.sin(BETA_L[0]))
    ref = np.cosh(b * xs) - np.cos(b * xs) - sigma * (np.sinh(b * xs) - np.sin(b * xs))
    assert np.allclose(w / w[-1], ref / ref[-1], atol=2e-4)
    assert np.max(np.abs(disp[0, :, 2])) < 1e-9 * np.max(np.abs(w)) and np.max(np.abs(twist)) < 1e-9


def test_label_rule():
    base = dict.fromkeys(("flap", "lag", "axial", "torsion", "hub"), 0.0)
    assert mode_label({**base, "flap": 0.6, "lag": 0.4}) == "flap"
    assert mode_label({**base, "lag": 0.55, "flap": 0.45}) == "flap+lag"  # the order of MOTIONS
    assert mode_label({**base, "torsion": 0.5, "hub": 0.3, "lag": 0.2}) == "torsion+hub"


def test_mac_and_matching_follow_shapes_not_order():
    rng = np.random.default_rng(0)
    Q, _ = np.linalg.qr(rng.standard_normal((12, 5)))
    assert np.allclose(mac_matrix(Q, Q), np.eye(5), atol=1e-12)
    # a complex scaling does not change a shape; a small perturbation keeps the match
    B = (Q[:, [2, 0, 4, 1, 3]] + 0.05 * rng.standard_normal((12, 5))) * np.exp(1j * rng.uniform(0, 6, 5))
    index, mac = match_modes(Q[:, :3], B)
    assert list(index) == [1, 3, 0]
    assert np.all(mac > 0.9)


def test_repeated_frequencies_form_one_eigenspace():
    groups = eigenspaces([1.0, 1.0 + 1e-9, 1.0 - 0.0 + 2e-9, 1.5, 2.0, 2.0 * (1 + 1e-4)])
    assert [list(g) for g in groups] == [[0, 1, 2], [3], [4], [5]]


def test_a_branch_follows_its_eigenspace_in_any_basis_and_keeps_its_shape():
    """Three branches in a three-fold eigenspace (identical blades) and one single mode: at the
    next speed the solver returns the eigenspace in another basis (a random unitary mixture),
    slightly perturbed. Single-vector MAC finds no good match for the branches (below 0.8); the
    subspace MAC is 1 and the Procrustes turn gives back vectors within the perturbation of the
    previous shapes, at the eigenspace's frequency."""
    rng = np.random.default_rng(3)
    Q, _ = np.linalg.qr(rng.standard_normal((20, 4)) + 1j * rng.standard_normal((20, 4)))
    space, single = Q[:, :3], Q[:, 3:]
    mix, _ = np.linalg.qr(rng.standard_normal((3, 3)) + 1j * rng.standard_normal((3, 3)))
    turned = space @ mix + 1e-4 * rng.standard_normal((20, 3))
    assert mac_matrix(space, turned).max(axis=1).min() < 0.8
    shapes, freqs, macs, where = follow(np.hstack([space, single]), np.array([2.0, 2.0, 2.0, 3.0]),
                                        [(single * 1j, np.array([3.01])), (turned, np.full(3, 2.02))], step_hz=0.1)
    assert list(where) == [1, 1, 1, 0] and np.allclose(freqs, [2.02, 2.02, 2.02, 3.01])
    assert np.all(macs > 1 - 1e-6)
    assert np.allclose(np.abs(np.sum(np.conj(shapes) * np.hstack([space, single]), axis=0)), 1.0, atol=1e-6)


def test_a_branch_does_not_jump_to_a_far_frequency_for_a_little_more_shape():
    """Two candidates whose shapes are both poor matches (MAC 0.45 and 0.55): the one at the
    plausible frequency wins over the one ten times higher, and the match is reported below
    the confidence threshold."""
    e = np.eye(3)
    previous = (e[:, :1] + e[:, 1:2] + 0.2 * e[:, 2:]) / np.sqrt(2.04)
    near, far = e[:, :1], (e[:, 1:2] + 0.3 * e[:, 2:])
    shares = [subspace_mac(previous, near)[0], subspace_mac(previous, far)[0]]
    assert shares[0] < shares[1] < CONFIDENT_MAC
    _, freqs, macs, where = follow(previous, np.array([2.6]), [(near, np.array([2.62])), (far, np.array([26.9]))],
                                   step_hz=0.08)
    assert where[0] == 0 and freqs[0] == pytest.approx(2.62) and macs[0] < CONFIDENT_MAC
