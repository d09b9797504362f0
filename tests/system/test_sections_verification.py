"""Pretwisted, tapered and structurally damped ANCF beams against results computed here
independently: beam-theory quadrature of the tip compliance, MacNeal & Harder's twisted beam,
a Hermite finite-element model of a tapered cantilever, the decay rate of Kelvin-Voigt
damping and the energy balance."""

import numpy as np
import pytest
from scipy.linalg import eigh

from hubbeam.elements.section import (
    Section,
    SectionForm,
    SpanSections,
    saint_venant_torsion_constant,
)
from hubbeam.io.scenario import Sensor
from hubbeam.simulation import simulate
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers.modal import modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.multibody import single_beam_system
from hubbeam.system.laws import DriveProfile
from tests.conftest import plate

NO_GRAVITY = np.zeros(3)


def twisted(length, section, degrees, elements, damping=0.0):
    """A prismatic rectangle pretwisted linearly from 0 at the root to ``degrees`` at the tip."""
    b, h = section.width, section.thickness
    table = SpanSections(np.array([0.0, length]), SectionForm.RECTANGLE, [[b, h], [b, h]],
                         np.radians([0.0, degrees]), material=section)
    return AncfBeam(length, elements, section, sections=table, structural_damping=damping)


def tip_deflection(beam, force):
    system = single_beam_system(beam, motion="fixed", tip_force=force, gravity=NO_GRAVITY)
    sol = solve_static(system, load_steps=1 if np.linalg.norm(force) < 1e-3 else 10)
    part = system.beams[0]
    undeformed = part.mount.root(0.0) + beam.length * part.mount.frame(0.0)[:, 0]
    return system.tip_position(sol.x) - undeformed, part.mount.frame(0.0)


def beam_theory_tip(length, section, degrees, force, root):
    """u = int_0^L (L - x)^2 C(x) dx F, C(x) = m m^T / EI_z + n n^T / EI_y with the section frame
    at x the root frame [tau m0 n0] turned by -beta(x) about tau (Euler-Bernoulli bending)."""
    E = section.youngs_modulus
    b, h = section.width, section.thickness
    ei_weak, ei_strong = E * b * h**3 / 12, E * h * b**3 / 12
    m0, n0 = root[:, 1], root[:, 2]
    xs, ws = np.polynomial.legendre.leggauss(200)
    xs, ws = 0.5 * length * (xs + 1), 0.5 * length * ws
    C = np.zeros((3, 3))
    for x, w in zip(xs, ws):
        beta = np.radians(degrees) * x / length
        m = np.cos(beta) * m0 - np.sin(beta) * n0
        n = np.sin(beta) * m0 + np.cos(beta) * n0
        C += w * (length - x) ** 2 * (np.outer(m, m) / ei_strong + np.outer(n, n) / ei_weak)
    return C @ force


def test_a_small_tip_force_on_a_pretwisted_cantilever_bends_it_by_the_rotated_compliance():
    section = plate(width=0.05, thickness=0.005)
    length, degrees = 1.0, 60.0
    force = np.array([0.0, 1e-3, 1e-3])  # N, at 45 deg between the root's width and thickness
    errors = []
    for elements in (4, 8):
        u, root = tip_deflection(twisted(length, section, degrees, elements), force)
        expected = beam_theory_tip(length, section, degrees, force, root)
        errors.append(np.linalg.norm(u - expected) / np.linalg.norm(expected))
    # the twist couples the directions: the tip moves well off the load's line
    assert abs(expected @ np.cross(root[:, 0], force)) > 0.3 * np.linalg.norm(expected) * np.linalg.norm(force)
    # measured: 4.1e-3 with 4 elements, 3.3e-4 with 8 (2 elements: 3.4e-2), about h^3.6
    assert errors[1] < 5e-4 and errors[1] < errors[0] / 8


#: MacNeal & Harder (1985), twisted beam: L = 12, b = 1.1, h = 0.32, 90 deg, E = 29e6, nu = 0.22
MH = {"length": 12.0, "width": 1.1, "thickness": 0.32, "E": 29.0e6, "nu": 0.22}
#: the reference tip deflections along the load (beam theory; an in-plane load at the root is
#: along the width, the stiff direction there)
MH_PUBLISHED = {"in_plane": 1.754e-3, "out_of_plane": 5.424e-3}


def macneal_harder_beam(elements):
    E, nu = MH["E"], MH["nu"]
    b, h = MH["width"], MH["thickness"]
    section = Section(b, h, 1.0, E, E / (2 * (1 + nu)), saint_venant_torsion_constant(b, h))
    return twisted(MH["length"], section, 90.0, elements), section


def test_macneal_harder_twisted_beam():
    """Unit tip loads along the root's width (in-plane) and thickness (out-of-plane). The
    published reference values, 1.754e-3 and 5.424e-3, are beam theory as well (the test was set
    for shell and solid elements). The Euler-Bernoulli quadrature of the rotated compliance gives
    1.746e-3 and 5.426e-3; the model with 16 elements reproduces it to 2e-5 (8 elements: 3e-4). In-plane it is 0.45 % below the
    reference: the shear flexibility F L / (5/6 G A) = 3.4e-6 that the Euler-Bernoulli beam leaves
    out explains about half of that; out-of-plane (weak-axis bending dominates) they agree to 0.03 %."""
    beam, section = macneal_harder_beam(16)
    root = single_beam_system(beam).beams[0].mount.frame(0.0)
    for key, direction in (("in_plane", root[:, 1]), ("out_of_plane", root[:, 2])):
        u, _ = tip_deflection(beam, direction)
        theory = beam_theory_tip(MH["length"], section, 90.0, direction, root) @ direction
        assert u @ direction == pytest.approx(theory, rel=5e-5)
        assert u @ direction == pytest.approx(MH_PUBLISHED[key], rel={"in_plane": 6e-3, "out_of_plane": 1e-3}[key])


@pytest.mark.slow
def test_a_large_tip_force_on_a_pretwisted_cantilever_converges_under_refinement():
    section = plate(width=0.05, thickness=0.005)
    force = np.array([0.0, 20.0, 20.0])  # N: a tip deflection of about 20 % of the length
    tips = [tip_deflection(twisted(1.0, section, 60.0, n), force)[0] for n in (3, 6, 12)]
    assert np.linalg.norm(tips[2]) > 0.1
    coarse, fine = np.linalg.norm(tips[1] - tips[0]), np.linalg.norm(tips[2] - tips[1])
    # measured: 3.1e-3 m from 3 to 6 elements, 3.1e-4 m from 6 to 12 (of a 0.21 m deflection)
    assert fine < coarse / 4 and fine < 3e-3 * np.linalg.norm(tips[2])


# ---------------------------------------------------------------- tapered cantilever frequencies
def hermite_fe_frequencies(length, E, rho, width, thickness, along, elements=120):
    """Bending frequencies (Hz) of a cantilever with linearly varying width(x) and thickness(x)
    (callables), by cubic Hermite elements with 6-point Gauss integration of
    EI w''^2 and rho A w^2 + rho I w'^2 (rotary inertia); ``along`` = 'thickness' bends across the
    thickness (I = b h^3 / 12), 'width' across the width (I = h b^3 / 12)."""
    le = length / elements
    n = 2 * (elements + 1)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    xi, wi = np.polynomial.legendre.leggauss(6)
    xi, wi = 0.5 * (xi + 1), 0.5 * wi
    for e in range(elements):
        ke, me = np.zeros((4, 4)), np.zeros((4, 4))
        for s, w in zip(xi, wi):
            x = (e + s) * le
            b, h = width(x), thickness(x)
            inertia = b * h**3 / 12 if along == "thickness" else h * b**3 / 12
            N = np.array([1 - 3 * s**2 + 2 * s**3, le * (s - 2 * s**2 + s**3), 3 * s**2 - 2 * s**3, le * (s**3 - s**2)])
            dN = np.array([-6 * s + 6 * s**2, le * (1 - 4 * s + 3 * s**2), 6 * s - 6 * s**2, le * (3 * s**2 - 2 * s)]) / le
            d2N = np.array([-6 + 12 * s, le * (-4 + 6 * s), 6 - 12 * s, le * (6 * s - 2)]) / le**2
            ke += w * le * E * inertia * np.outer(d2N, d2N)
            me += w * le * rho * (b * h * np.outer(N, N) + inertia * np.outer(dN, dN))
        idx = slice(2 * e, 2 * e + 4)
        K[idx, idx] += ke
        M[idx, idx] += me
    K, M = K[2:, 2:], M[2:, 2:]  # clamped root
    return np.sqrt(eigh(K, M, eigvals_only=True)[:3]) / (2 * np.pi)


def test_a_linearly_tapered_cantilever_has_the_frequencies_of_an_independent_hermite_model():
    length, (b0, h0), (b1, h1) = 1.0, (0.06, 0.006), (0.03, 0.003)
    mat = plate()
    table = SpanSections(np.array([0.0, length]), SectionForm.RECTANGLE, [[b0, h0], [b1, h1]], [0.0, 0.0],
                         material=mat)
    beam = AncfBeam(length, 10, mat, sections=table)
    system = single_beam_system(beam, motion="fixed", gravity=NO_GRAVITY)
    modes = modal_analysis(system, solve_static(system, load_steps=1), count=8)
    got = np.array(modes.frequencies_hz)

    def width(x):
        return b0 + (b1 - b0) * x / length

    def thickness(x):
        return h0 + (h1 - h0) * x / length

    flap = hermite_fe_frequencies(length, mat.youngs_modulus, mat.density, width, thickness, "thickness")
    lag = hermite_fe_frequencies(length, mat.youngs_modulus, mat.density, width, thickness, "width")
    # the taper raises the first frequency above the prismatic root section's (1.875^2 / 2 pi sqrt(EI / rho A) / L^2)
    prismatic = 1.8751**2 / (2 * np.pi) * np.sqrt(mat.youngs_modulus * h0**2 / 12 / mat.density) / length**2
    assert flap[0] > 1.2 * prismatic
    for f in np.concatenate([flap, lag[:2]]):
        nearest = got[np.argmin(np.abs(got - f))]
        # measured with 10 elements: 1.7e-6 (first flap) to 2.6e-4 (third flap); 20 elements: 1.8e-5 at most
        assert nearest == pytest.approx(f, rel=4e-4)


# ---------------------------------------------------------------- a uniform table is the prismatic beam
def test_a_uniform_table_gives_the_prismatic_statics_and_dynamics():
    section = plate()
    length = 1.45

    def system(beam):
        return single_beam_system(beam, radius=0.35, twist=np.pi / 4, motion="prescribed",
                                  drive=DriveProfile("spin_up", 3.0, 0.5), gravity=np.array([0, -9.81, 0]),
                                  damping=(1.0, 0.5), tip_force=(0.0, 0.0, 0.3))

    a = system(AncfBeam(length, 4, section))
    b = system(AncfBeam(length, 4, section, sections=SpanSections.uniform(section, length)))
    sa, sb = solve_static(a), solve_static(b)
    assert np.allclose(sa.x, sb.x, rtol=0, atol=1e-14) and sa.newton_iterations == sb.newton_iterations
    sensors = [Sensor(name="tip", kind="tip_deflection"), Sensor(name="e", kind="energy"),
               Sensor(name="s", kind="surface_strain", x=0.3, surface="upper")]
    ta, tb = (simulate(s, sensors, 0.05, 1e-3, output_dt=0.01) for s in (a, b))
    assert ta.newton_iterations == tb.newton_iterations and len(ta.times) == 6
    for name in ("tip", "e"):
        for ra, rb in zip(ta.records[name], tb.records[name]):
            for part in ra:
                assert rb[part] == pytest.approx(ra[part], rel=1e-12, abs=1e-15)
    assert tb.records["s"] == pytest.approx(ta.records["s"], rel=1e-12, abs=1e-15)


# ---------------------------------------------------------------- structural damping
def test_kelvin_voigt_damping_decays_the_first_mode_at_zeta_c_omega_over_2_and_balances_energy():
    """A cantilever released from a small static tip deflection (no gravity, no drag): the
    logarithmic decrement of the tip's swing gives zeta = c omega_1 / 2, and the total energy
    plus the dissipated work stays at its initial value."""
    c = 1.5e-3
    section = plate(width=0.05, thickness=0.005)
    beam = twisted(1.0, section, 30.0, 4, damping=c)
    loaded = single_beam_system(beam, motion="fixed", tip_force=(0.0, 0.0, 0.05), gravity=NO_GRAVITY)
    free = single_beam_system(beam, motion="fixed", gravity=NO_GRAVITY)
    start = solve_static(loaded, load_steps=1)
    omega = 2 * np.pi * modal_analysis(free, solve_static(free, load_steps=1), count=1).frequencies_hz[0]
    sensors = [Sensor(name="tip", kind="tip_deflection"), Sensor(name="e", kind="energy")]
    traj = simulate(free, sensors, 2.0, 5e-4, spectral_radius=1.0, output_dt=5e-4,
                    state=ga.init(free, start.x, start.chart))
    t = np.asarray(traj.times)
    tip = np.array([r["tangential"] for r in traj.records["tip"]])
    energy = traj.records["e"]
    # peaks of the swing (after the higher modes, damped at c omega_k / 2, have died out)
    peaks = [k for k in range(1, len(tip) - 1) if tip[k] > tip[k - 1] and tip[k] >= tip[k + 1] and t[k] > 0.3]
    amplitudes = tip[peaks]
    decrement = np.log(amplitudes[0] / amplitudes[-1]) / (len(peaks) - 1)
    zeta = decrement / np.sqrt(4 * np.pi**2 + decrement**2)
    assert zeta == pytest.approx(c * omega / 2, rel=0.03)
    total = np.array([e["total"] + e["dissipated"] for e in energy])
    assert energy[-1]["dissipated"] > 0.5 * energy[0]["total"]  # most of it is gone
    assert np.max(np.abs(total - total[0])) < 2e-3 * total[0]


# ---------------------------------------------------------------- sensors, rotating modes, the example
def test_the_upper_face_strain_of_a_tapered_cantilever_uses_the_local_thickness():
    """A small tip force F along the thickness: M(x) = F (L - x), and the upper face (z = +h(x)/2)
    reads -M h / (2 EI_y) = -6 F (L - x) / (E b(x) h(x)^2) (bending only; the face is the local one)."""
    from hubbeam.sensors import measure

    length, (b0, h0), (b1, h1) = 1.0, (0.06, 0.006), (0.03, 0.003)
    mat = plate()
    table = SpanSections(np.array([0.0, length]), SectionForm.RECTANGLE, [[b0, h0], [b1, h1]], [0.0, 0.0],
                         material=mat)
    force = 0.01  # N
    system = single_beam_system(AncfBeam(length, 16, mat, sections=table), motion="fixed",
                                tip_force=(0.0, 0.0, force), gravity=NO_GRAVITY)
    n_root = system.beams[0].mount.frame(0.0)[:, 2]
    assert np.allclose(n_root, [0.0, 0.0, 1.0])  # the force is along the root section's n
    sol = solve_static(system, load_steps=1)
    state = ga.init(system, sol.x, sol.chart)
    for x in (0.1, 0.45, 0.8):
        b, h = b0 + (b1 - b0) * x, h0 + (h1 - h0) * x
        expected = -6 * force * (length - x) / (mat.youngs_modulus * b * h**2)
        gauge = Sensor(name="g", kind="surface_strain", x=x, surface="upper")
        assert measure(gauge, system, state, {}) == pytest.approx(expected, rel=2e-3)


def test_rotating_modes_of_a_damped_pretwisted_blade_are_its_undamped_ones_and_tend_to_those_at_rest():
    from hubbeam.solvers.modal import rotating_modal_analysis

    section = plate(width=0.05, thickness=0.005)

    def system(damping, omega):
        beam = twisted(1.0, section, 30.0, 4, damping=damping)
        return single_beam_system(beam, radius=0.2, twist=np.radians(80.0), motion="prescribed",
                                  drive=DriveProfile("constant", omega), gravity=NO_GRAVITY)

    def rotating(damping, omega):
        s = system(damping, omega)
        return rotating_modal_analysis(s, solve_static(s, spin=omega), omega, count=4).frequencies_hz

    damped, undamped = rotating(3e-3, 8.0), rotating(0.0, 8.0)
    assert damped == pytest.approx(undamped, rel=1e-7)  # central differences of the residual
    at_rest = system(0.0, 1.0).with_hub(motion="fixed")
    slow = rotating(0.0, 1e-3)
    # (the rotating analysis differentiates the residual by central differences: 8e-5 measured)
    assert slow == pytest.approx(modal_analysis(at_rest, solve_static(at_rest), count=4).frequencies_hz, rel=3e-4)
    assert undamped[0] > slow[0] * 1.02  # centrifugal stiffening


def test_the_blade_example_runs_with_all_its_sensors():
    from hubbeam import api
    from hubbeam.io.scenario import load_example

    scenario = load_example("blade", ["analysis.t_end=0.1"])
    traj, failure = api.run(scenario)
    assert failure is None and traj.steps == 50
    assert set(traj.records) == {s.name for s in scenario.sensors}
    energy = traj.records["energy"]
    balance = [e["total"] + e["dissipated"] - e["drive"] for e in energy]
    # measured: 4e-11 J (the start is the equilibrium in the run's axis chart, so nothing rings)
    assert max(balance) - min(balance) < 1e-8 * abs(energy[0]["gravity"])
    assert all(np.isfinite(v) for v in traj.records["root_strain"])


def test_beams_of_different_meshes_and_tables_packed_together_keep_their_own_properties():
    """A held hub with a pretwisted, damped beam (3 elements, 4 Gauss points) and a prismatic one
    (5 elements, 5 points): the per-element and per-point arrays are padded to the larger beam; each
    beam's static sag and the energies equal those of the beam alone."""
    from hubbeam.system.ancf_part import AncfPart
    from hubbeam.system.multibody import Hub, MultibodySystem
    from hubbeam.system.mount import Mount

    section = plate(width=0.05, thickness=0.004)
    gravity = np.array([0.0, -9.81, 0.0])
    a = AncfBeam(1.0, 3, section, gauss_points=4, sections=twisted(1.0, section, 40.0, 3).sections,
                 structural_damping=2e-3)
    b = AncfBeam(0.8, 5, section)
    mounts = (Mount(0.2, np.radians(70.0), 0.0), Mount(0.2, np.radians(90.0), np.pi))
    parts = [AncfPart(beam, mount, name=name) for beam, mount, name in zip((a, b), mounts, ("a", "b"))]
    together = MultibodySystem(parts, Hub("fixed"), gravity=gravity)
    both = solve_static(together)
    for k, part in enumerate(parts):
        alone = MultibodySystem([part], Hub("fixed"), gravity=gravity)
        single = solve_static(alone)
        assert together.tip_displacement(both.x, k) == pytest.approx(alone.tip_displacement(single.x), rel=1e-9)
        e_both = together.energies(both.x, np.zeros_like(both.x), both.chart, beam=k)
        e_alone = alone.energies(single.x, np.zeros_like(single.x), single.chart)
        assert e_both["strain"] == pytest.approx(e_alone["strain"], rel=1e-8)
