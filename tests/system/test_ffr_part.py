"""FFR beams with span-wise sections, pretwist and structural damping on the hub (FfrPart of
FfrBeam(sections=..., structural_damping=...)): statics, modes and dynamics through the system
and its solvers.

Oracles: the rotated-compliance quadrature of a pretwisted cantilever and an Euler-Bernoulli
model of a tapered one (written in tests/elements/test_ffr_sections.py); a mount twist is the
same beam as a constant pretwist; Kelvin-Voigt damping makes mode i decay with
zeta_i = c omega_i / 2 (logarithmic decrement of a free vibration); energy + dissipated work is
constant; the Newton matrix is the derivative of the residual."""

import numpy as np
import pytest
from scipy.linalg import eigh

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.elements.section import SpanSections
from hubbeam.io.scenario import Sensor
from hubbeam.sensors import measure
from hubbeam.simulation import simulate
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers.modal import modal_analysis, rotating_modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.multibody import Hub, MultibodySystem, single_beam_system
from hubbeam.system.laws import DriveProfile
from hubbeam.system.mount import Mount
from tests.conftest import B, E, H, L, RHO, newton_matrix_and_differences, plate, tapered_sections
from tests.elements.test_ffr_sections import euler_bernoulli_frequencies, rotated_compliance_deflection


def tip_vector(system, x):
    d = system.tip_displacement(x)
    return np.array([d["vertical"], d["tangential"]])


# ----------------------------------------------------------------------------- statics
def test_held_hub_static_tip_deflection_of_a_pretwisted_tapered_blade():
    """Hub held, no gravity, a small tip force: the static solution's tip deflection is the
    rotated-compliance quadrature (body y = j0, z = k_k for a beam at azimuth 0 without twist),
    and the upper-surface strain sensor reads the local section's face z' = +h(x)/2."""
    force = np.array([0.0, 0.02, -0.05])
    system = single_beam_system(FfrBeam(L, 32, plate(), sections=tapered_sections(pretwist_deg=90.0)), radius=0.3,
                                tip_force=force)
    sol = solve_static(system, load_steps=1)

    def dims(x):
        return np.interp(x, [0, L], [B, 0.6 * B]), np.interp(x, [0, L], [H, 0.6 * H])

    exact = rotated_compliance_deflection(L, lambda x: E * dims(x)[0] * dims(x)[1] ** 3 / 12,
                                          lambda x: E * dims(x)[1] * dims(x)[0] ** 3 / 12,
                                          lambda x: np.pi / 2 * x / L, force[1:])
    assert np.allclose(tip_vector(system, sol.x), exact, rtol=0, atol=1e-4 * np.linalg.norm(exact))
    state = ga.init(system, sol.x, sol.chart)
    sensor = Sensor(name="P", kind="surface_strain", x=0.5, surface="upper")
    part, q = system.beams[0], sol.x[system.layout.beam_x(0)]
    h = dims(0.5)[1]
    assert measure(sensor, system, state, {}) == pytest.approx(part.beam.surface_strain(q, 0.5, 0.0, h / 2),
                                                               rel=1e-14)


def test_a_mount_twist_is_a_constant_pretwist():
    """The pretwist turns the section in the sense of the mount's twist: a prismatic beam with
    mount twist 0.6 rad and one with twist 0 and a constant pretwist of 0.6 rad are the same beam
    (static tip deflection under gravity and a tip force, strain at a gauge, frequencies)."""
    beta = 0.6
    sec = plate(thickness=0.004)
    row = SpanSections.uniform(sec, L)
    turned = SpanSections(row.x, row.form, row.values, np.full(2, beta))
    kw = dict(radius=0.3, gravity=np.array([0.0, -9.81, 0.0]), tip_force=np.array([0.0, 0.1, 0.2]))
    systems = [single_beam_system(FfrBeam(L, 6, sec), twist=beta, **kw),
               single_beam_system(FfrBeam(L, 6, sec, sections=turned), **kw)]
    sols = [solve_static(s, load_steps=1) for s in systems]
    tips = [tip_vector(s, sol.x) for s, sol in zip(systems, sols)]
    assert np.linalg.norm(tips[0]) > 1e-3
    assert np.allclose(tips[1], tips[0], rtol=0, atol=1e-9 * np.linalg.norm(tips[0]))
    strains = [s.surface_strain(sol.x, sol.chart, 0.3, 0.01, sec.thickness / 2) for s, sol in zip(systems, sols)]
    assert strains[1] == pytest.approx(strains[0], rel=1e-8)
    freqs = [modal_analysis(s, sol, count=6).frequencies_hz for s, sol in zip(systems, sols)]
    assert np.allclose(freqs[1], freqs[0], rtol=1e-9)


# ----------------------------------------------------------------------------- modes
def test_held_hub_modes_of_a_tapered_blade_and_its_modal_reduction():
    """Fixed hub: the first flap frequency of a tapered blade (width and thickness halved) is the
    Euler-Bernoulli model's; with pretwist the system's frequencies are the clamped nodal beam's,
    and a reduced beam keeping 5 modes has the nodal system's lowest 5."""
    taper = tapered_sections(root=(B, H), tip=(0.5 * B, 0.5 * H), pretwist_deg=0.0)
    system = single_beam_system(FfrBeam(L, 12, plate(), sections=taper), radius=0.3)
    f = modal_analysis(system, solve_static(system, load_steps=1), count=3).frequencies_hz
    b = lambda x: np.interp(x, [0, L], [B, 0.5 * B])  # noqa: E731
    h = lambda x: np.interp(x, [0, L], [H, 0.5 * H])  # noqa: E731
    reference = euler_bernoulli_frequencies(lambda x: E * b(x) * h(x) ** 3 / 12, lambda x: RHO * b(x) * h(x), L,
                                            count=1)
    assert f[0] == pytest.approx(reference[0], rel=1e-4)

    twisted = tapered_sections(pretwist_deg=60.0)
    nodal = FfrBeam(L, 6, plate(), sections=twisted)
    w2 = eigh(nodal.stiffness_matrix, nodal.invariants["Mff"], eigvals_only=True)
    found = []
    for beam in (nodal, FfrBeam(L, 6, plate(), sections=twisted, modes=5)):
        system = single_beam_system(beam, radius=0.3)
        found.append(modal_analysis(system, solve_static(system, load_steps=1), count=5).frequencies_hz)
    assert np.allclose(found[0], np.sqrt(w2[:5]) / (2 * np.pi), rtol=1e-8)
    assert np.allclose(found[1], found[0], rtol=1e-8)


# ----------------------------------------------------------------------------- structural damping
def test_structural_damping_decrement_and_energy_balance():
    """A tapered, pretwisted blade on a fixed hub, no drag, no gravity, released from rest in its
    first clamped mode (tip 2 mm): the logarithmic decrement of the tip motion gives
    zeta = c omega_1 / 2 (Kelvin-Voigt), and kinetic + strain energy + dissipated work stays at
    its initial value."""
    sections = tapered_sections(pretwist_deg=45.0)
    probe = FfrBeam(L, 6, plate(), sections=sections)
    w2, phi = eigh(probe.stiffness_matrix, probe.invariants["Mff"], subset_by_index=[0, 0])
    omega = float(np.sqrt(w2[0]))
    zeta = 0.02
    c = 2 * zeta / omega
    system = single_beam_system(FfrBeam(L, 6, plate(), sections=sections, structural_damping=c), radius=0.3)
    x0, F0 = system.initial_state(0.0)
    tip = probe.displacement_row(L) @ phi[:, 0]
    q = system.layout.beam_x(0)
    x0[q] = 2e-3 / np.linalg.norm(tip) * phi[:, 0]
    period = 2 * np.pi / omega
    dt = period / 200
    sensors = [Sensor(name="tip", kind="tip_deflection"), Sensor(name="energy", kind="energy")]
    traj = simulate(system, sensors, t_end=8 * period, dt=dt, spectral_radius=1.0, output_dt=dt,
                    state=ga.init(system, x0, F0))
    d = np.array([[r["vertical"], r["tangential"]] for r in traj.records["tip"]])
    s = d @ d[0] / np.linalg.norm(d[0])  # along the mode's tip direction
    peaks = []
    for k in range(1, s.size - 1):
        if s[k] > s[k - 1] and s[k] >= s[k + 1] and s[k] > 0:
            a, b_, c_ = s[k - 1], s[k], s[k + 1]
            peaks.append(b_ - (a - c_) ** 2 / (8 * (a - 2 * b_ + c_)))  # parabola through three samples
    peaks = np.array([s[0]] + peaks)
    assert peaks.size >= 8
    delta = np.log(peaks[0] / peaks[-1]) / (peaks.size - 1)
    measured = delta / np.sqrt(4 * np.pi**2 + delta**2)
    assert measured == pytest.approx(zeta, rel=0.02)  # measured: 0.02000
    e = traj.records["energy"]
    balance = np.array([r["kinetic"] + r["strain"] + r["dissipated"] for r in e])
    assert e[-1]["dissipated"] > 0.8 * balance[0]  # most of it is gone
    # the trapezoidal rule on the dissipated power (simulation's work integral) exceeds the
    # integrator's own dissipation, dt v_mid^T cK v_mid, by (omega dt)^2 / 4 = 2.5e-4 of it here
    # (measured drift: 2.1e-4 of the initial energy)
    assert np.max(np.abs(balance - balance[0])) < 4e-4 * balance[0]
    print(f"zeta measured {measured:.5f} against c omega / 2 = {zeta}; energy drift "
          f"{np.max(np.abs(balance - balance[0])) / balance[0]:.2e}")


@pytest.mark.parametrize("motion", ["free", "prescribed"])
def test_newton_matrix_with_structural_damping_is_the_derivative_of_the_residual(motion):
    """A tapered, pretwisted, damped FFR blade (with drag and gravity) beside a prismatic one: the
    compiled Newton matrix equals central differences of the compiled residual along the
    generalized-alpha correction (rates gamma' dz: the damping's coef_c c K is in it)."""
    blade = tapered_sections(root=(B, 0.01), tip=(0.6 * B, 0.006))
    parts = [FfrPart(FfrBeam(L, 3, plate(thickness=0.01), sections=blade, structural_damping=5e-3),
                     Mount(0.35, 0.4, 0.3, 0.1), tip_force=np.array([0.3, -1.0, 0.5]), name="blade"),
             FfrPart(FfrBeam(L, 2, plate(thickness=0.01), structural_damping=1e-3), Mount(0.35, -0.4, np.pi, 0.0),
                     name="plain")]
    system = MultibodySystem(parts, Hub(motion, 9.5, drive=DriveProfile("spin_up", 2.0, 1.0)), gravity=(0.0, -9.81, 0.0),
                       damping=(1.73, 1.4))
    A, A_fd, res, res_fd = newton_matrix_and_differences(system, seed=5, perturbation=0.01, stiffness="exact")
    assert np.allclose(res, res_fd, rtol=0, atol=1e-14 * np.max(np.abs(res)))
    layout = system.layout
    for k in range(2):
        z = layout.z_of_x[layout.beam_x(k)]
        block, block_fd = A[np.ix_(z, z)], A_fd[np.ix_(z, z)]
        assert np.max(np.abs(block - block_fd)) < 1e-6 * np.max(np.abs(block))
    assert np.max(np.abs(A - A_fd)) < 1e-6 * np.max(np.abs(A))


# ----------------------------------------------------------------------------- uniform table
def test_a_uniform_table_runs_as_the_prismatic_beam():
    """exp1's free hub (beta = 45 deg, gravity), 4 elements, 0.3 s: the beam given as a uniform
    table repeats the prismatic beam's strain and tip histories to round-off."""
    sensors = [Sensor(name="P1", kind="surface_strain", x=0.3, surface="upper"),
               Sensor(name="tip", kind="tip_deflection")]
    runs = []
    for sections in (None, SpanSections.uniform(plate(), L)):
        system = single_beam_system(FfrBeam(L, 4, plate(), sections=sections), radius=0.35, twist=np.pi / 4,
                                    motion="free", hub_inertia=9.557, gravity=np.array([0.0, -9.81, 0.0]))
        runs.append(simulate(system, sensors, 0.3, 1e-3, output_dt=0.01))
    a, b = (np.array(r.records["P1"]) for r in runs)
    assert np.ptp(a) > 1e-5
    assert np.max(np.abs(a - b)) < 1e-9 * np.ptp(a)
    ta, tb = (np.array([r["vertical"] for r in run.records["tip"]]) for run in runs)
    assert np.max(np.abs(ta - tb)) < 1e-9 * np.ptp(ta)


# ----------------------------------------------------------------------------- Campbell
def rotating_flap_frequency(EI, rho_a, length, radius, spin):
    """First flap frequency (Hz) of a cantilever turning at ``spin`` about an axis parallel to the
    flap direction, root at ``radius``: the Euler-Bernoulli model with the centrifugal tension
    T(x) = spin^2 int_x^L rho_A(s) (radius + s) ds (40-point Gauss)."""
    s, ws = np.polynomial.legendre.leggauss(40)

    def tension(x):
        u = x + 0.5 * (length - x) * (s + 1)
        return spin**2 * 0.5 * (length - x) * np.sum(ws * rho_a(u) * (radius + u))

    return float(euler_bernoulli_frequencies(EI, rho_a, length, count=1, tension=tension)[0])


@pytest.mark.parametrize("modes", [None, 4])
def test_rotating_flap_frequency_of_a_tapered_stiffened_blade(modes):
    """The Campbell diagram's machinery (rotating_modal_analysis about solve_static(spin=...))
    on a tapered blade with geometric stiffening, weak axis along j0 (twist 90 deg), turning at
    twice its first flap frequency: the first frequency is the centrifugally stiffened flap
    frequency of an Euler-Bernoulli model with the tension of its own taper; with structural
    damping on the beam (left out of the undamped modes) and modal reduction (4 modes + axial)."""
    taper = tapered_sections(root=(B, H), tip=(0.5 * B, 0.5 * H), pretwist_deg=0.0)
    b = lambda x: np.interp(x, [0, L], [B, 0.5 * B])  # noqa: E731
    h = lambda x: np.interp(x, [0, L], [H, 0.5 * H])  # noqa: E731
    EI, rho_a = (lambda x: E * b(x) * h(x) ** 3 / 12), (lambda x: RHO * b(x) * h(x))
    radius = 0.3
    f0 = rotating_flap_frequency(EI, rho_a, L, radius, 0.0)
    spin = 2 * 2 * np.pi * f0
    reference = rotating_flap_frequency(EI, rho_a, L, radius, spin)
    beam = FfrBeam(L, 16, plate(), sections=taper, geometric_stiffening=True, structural_damping=1e-3, modes=modes)
    system = single_beam_system(beam, radius=radius, twist=np.pi / 2, motion="prescribed",
                                drive=DriveProfile("constant", spin))
    steady = solve_static(system, load_steps=4, spin=spin)
    f = rotating_modal_analysis(system, steady, spin, count=2).frequencies_hz
    assert reference > 1.8 * f0  # the stiffening is large
    # the element-mean axial strain carries a tension constant on each element: the error falls
    # like h^2 (measured, nodal: 7.8e-3, 2.4e-3, 6.3e-4 with 4, 8, 16 elements; prismatic 1.1e-3 with 8);
    # 4 kept modes add 5e-4 (1.2e-3 in all)
    assert f[0] == pytest.approx(reference, rel=1e-3 if modes is None else 2e-3)


# ----------------------------------------------------------------------------- tip loads
@pytest.mark.parametrize("modes", [None, 3])
def test_tip_force_does_the_virtual_work_of_a_force_at_the_deformed_tip(modes):
    """A constant tip force F is conservative: its generalized force on v = [r_C', omega^b, p']
    is the gradient of F . r_P, r_P the tip point's position (point_position: r_C + A0 ((L, 0, 0)
    + u(L))), taken here by central differences at a deformed, turned state: along r_C, along a
    small turn of the body frame about its own axes, and along p. The lever arm of the moment
    on the body rotation is the deformed one: with the undeformed (L, 0, 0) the omega rows miss
    (T p) x F. The compiled residual is held to the Python rows by
    tests/elements/test_ffr_kernels.py."""
    from hubbeam.system.rotations import rotation_vector_matrix

    force = np.array([3.0, -20.0, 12.0])
    beam = FfrBeam(L, 4, plate(), modes=modes)
    loaded, free = (FfrPart(beam, Mount(0.2, 0.1, 0.3, -0.2), tip_force=f) for f in (force, np.zeros(3)))
    rng = np.random.default_rng(7)
    r_C, A = rng.normal(scale=0.1, size=3), rotation_vector_matrix(rng.normal(scale=0.5, size=3))
    p = rng.normal(scale=1e-2, size=beam.ndof)
    zero = np.zeros(6 + beam.ndof)
    generalized = free.vspace_forces(A, p, zero, zero, np.zeros(3), (0.0, 0.0), tangent=False)[0] - \
        loaded.vspace_forces(A, p, zero, zero, np.zeros(3), (0.0, 0.0), tangent=False)[0]
    eps = 1e-6

    def work(dr=np.zeros(3), dphi=np.zeros(3), dp=0.0):
        return force @ loaded.tip_position(p + dp, (r_C + dr, A @ rotation_vector_matrix(dphi)))

    gradient = np.concatenate([
        [(work(dr=eps * e) - work(dr=-eps * e)) / (2 * eps) for e in np.eye(3)],
        [(work(dphi=eps * e) - work(dphi=-eps * e)) / (2 * eps) for e in np.eye(3)],
        [(work(dp=eps * e) - work(dp=-eps * e)) / (2 * eps) for e in np.eye(beam.ndof)]])
    assert np.allclose(generalized, gradient, rtol=0, atol=1e-7 * np.abs(gradient).max())


# ----------------------------------------------------------------------------- the compiled pack
def test_the_stacked_pack_gives_each_beam_its_own_terms():
    """FfrBeams stacks every FFR beam's constants zero-padded to the largest (II by its nonzero
    entries in compressed rows, the drag points' spans): a nodal beam of 4 elements beside one
    of 2 (different numbers of entries, rows and coordinates). Each beam's kernel terms from the
    stacked pack are bit for bit those from its own constants (constants.pack), which the kernel
    tests hold against the dense Python FfrPart."""
    from hubbeam import api
    from hubbeam.elements.ffr import constants as fc
    from hubbeam.elements.ffr import kernels as fk
    from hubbeam.io.scenario import load_example
    from hubbeam.system.ffr_beams import FfrBeams, ffr_arguments

    system = api.build_system(load_example("spacecraft3d", [
        'beams[0].formulation="ffr"', "beams[0].elements=4", 'beams[1].formulation="ffr"', "beams[1].elements=2"]))
    pack = next(p for p in system.model().parts if isinstance(p, FfrBeams))
    assert pack.places.shape[0] == 2 and pack.places[0, 2] != pack.places[1, 2]
    rng = np.random.default_rng(5)
    drag_c = (0.4, 1.7)
    for k in range(2):
        part = system.beams[pack.places[k, 0]]
        own = fc.pack(part)
        nf, npts = part.ndof, own.x_pts.size
        n = 6 + nf
        A = np.linalg.qr(rng.standard_normal((3, 3)))[0]
        p, vb, vdot = 1e-3 * rng.standard_normal(nf), rng.standard_normal(n), rng.standard_normal(n)
        out = []
        for inv, tip, drag in (ffr_arguments(pack, k, drag_c), (own.inv, own.tip, own.drag(drag_c))):
            fv, Mv, Cv, K_el = np.empty(n), np.empty((n, n)), np.empty((n, n)), np.empty((nf, nf))
            power = fk.ffr_vspace_terms(inv, A, p, vb, vdot, np.array([0.0, -9.81, 0.0]), tip, drag, 1.0, True,
                                        fv, Mv, Cv, K_el, fk.kernel_work(nf, npts))
            out.append((fv, Mv, Cv, K_el, power))
        for a, b in zip(*out):
            np.testing.assert_array_equal(a, b)
        assert np.any(out[0][2][6:, 6:] != 0.0)  # the drag reached the elastic coordinates
