"""Joints (system/joints.py): the named axes against plain rotations, the joint laws' forces
against differences of their energy and of the residual, the signs of the interface (a lag
motor's reaction on the hub), and the layout's lock slots."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.beam import AncfBeam
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.joints import Joint, latch_joints
from hubbeam.system.laws import DriveProfile, TorqueLaw
from hubbeam.system.layout import Layout
from hubbeam.system.mount import Mount
from hubbeam.system.multibody import Hub, MultibodySystem
from tests.conftest import newton_matrix_and_differences, plate, rotation


def _system(joint, formulation="ancf", hub=Hub("fixed"), gravity=(0.0, -9.81, 0.0), radius=0.3, twist=0.4,
            precone=0.1, elements=2):
    mount = Mount(radius, twist, 0.5, precone, joint=joint)
    if formulation == "ancf":
        part = AncfPart(AncfBeam(1.2, elements, plate()), mount)
    else:
        part = FfrPart(FfrBeam(1.2, elements, plate()), mount)
    return MultibodySystem([part], hub, gravity=gravity)


@pytest.mark.parametrize("name, angle", [("flap", 0.3), ("lag", -0.4), ("pitch", 0.5)])
def test_named_axes_turn_the_root_as_the_interface_says(name, angle):
    """flap = +c lifts the tip towards +b, lag = +b moves it towards -c, pitch = -a turns the
    section as a positive twist does; the joint frame (a, b, c) is the mount's axis frame."""
    system = _system(Joint.named(name, initial_angle=(angle,)), twist=0.2, precone=0.0)
    x, F = system.initial_state()
    _, R = system.root_pose(0, x, F)
    _, A = system.frames.pose(system.frames.joint(0), x)  # (a, b, c)
    a, b, c = A.T
    twist = rotation(a, -0.2)  # the mount's twist turns the section by -beta about a
    expected = {"flap": rotation(c, angle), "lag": rotation(b, angle), "pitch": rotation(-a, angle)}[name]
    assert np.allclose(R, twist @ expected @ A, atol=1e-12) or np.allclose(R, expected @ twist @ A, atol=1e-12)
    tip = R[:, 0]
    if name == "flap":
        assert tip @ b == pytest.approx(np.sin(angle))
    elif name == "lag":
        assert tip @ c == pytest.approx(-np.sin(angle))
    else:  # a pitch angle is a twist: the same section frame as the clamped beam with twist 0.2 + angle
        clamped = _system(None, twist=0.2 + angle, precone=0.0)
        x0, F0 = clamped.initial_state()
        assert np.allclose(clamped.root_pose(0, x0, F0)[1], R, atol=1e-12)


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_spring_damper_and_motor_rows_are_their_energy_and_power(formulation):
    """The joint row holds k (psi - psi_0) + c psi' - T_m: the spring's part equals the
    difference of the spring energy in the strain energy, the damper's the dissipated power
    over psi', the motor's the drive power over psi' (each from the energy sensors' sums)."""
    law = TorqueLaw.pd(3.0, 0.7, DriveProfile.slew(0.8, 2.0))
    joint = Joint.named("lag", stiffness=(12.0,), damping=(0.9,), neutral=(0.2,), initial_angle=(-0.1,), torque=law)
    system = _system(joint, formulation, gravity=(0.0, 0.0, 0.0))
    x, F = system.initial_state()
    c = system.layout.joint_x(0).start
    x[c] = 0.35
    v = np.zeros(system.nx)
    v[c] = 0.6
    t = 0.9
    h = 1e-6

    def strain(psi):
        y = x.copy()
        y[c] = psi
        return system.energies(y, v, F)["strain"]

    dU = (strain(x[c] + h) - strain(x[c] - h)) / (2 * h)
    assert dU == pytest.approx(12.0 * (0.35 - 0.2), rel=1e-7)
    dissipated, drive = system.step_powers(t, x, v, np.zeros(system.layout.n_lambda), F)
    ref, ref_rate, _ = DriveProfile.slew(0.8, 2.0)(t)
    motor = 3.0 * (-0.1 + ref - 0.35) + 0.7 * (ref_rate - 0.6)
    assert dissipated == pytest.approx(0.9 * 0.6**2, rel=1e-12)
    assert drive == pytest.approx(motor * 0.6, rel=1e-12)
    # the residual's psi row less the same beam's on a joint without laws: the laws' generalized force
    row = _joint_row(system, x, v, F, c, t)
    bare = system.with_beams([replace(system.beams[0], mount=replace(system.beams[0].mount, joint=Joint.named(
        "lag", initial_angle=(-0.1,))))])
    assert row - _joint_row(bare, x, v, F, c, t) == pytest.approx(dU + 0.9 * 0.6 - motor, rel=1e-9)


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_a_table_motor_row_and_power_in_the_compiled_equations(formulation):
    """A motor of a torque table (linear between its knots) on the joint angle: the residual's
    psi row less the bare joint's is -T(t) and the drive power T(t) psi', T(1.25 s) = 1.25 N m
    by hand between the knots (1 s, 2 N m) and (2 s, -1 N m). The joint's terms run inlined in
    the system's compiled equations and powers, which count no references: the table's slices
    of the joints' pack are read there (a wrong offset or a slice not read would break it)."""
    law = TorqueLaw.table([0.0, 1.0, 2.0], [0.0, 2.0, -1.0])
    system = _system(Joint.named("lag", torque=law), formulation, gravity=(0.0, 0.0, 0.0))
    x, F = system.initial_state()
    c = system.layout.joint_x(0).start
    v = np.zeros(system.nx)
    v[c] = 0.6
    t = 1.25
    assert law(t, 0.0, 0.0)[0] == pytest.approx(1.25, rel=1e-15)
    bare = system.with_beams([replace(system.beams[0], mount=replace(system.beams[0].mount, joint=Joint.named(
        "lag")))])
    assert _joint_row(system, x, v, F, c, t) - _joint_row(bare, x, v, F, c, t) == pytest.approx(-1.25, rel=1e-12)
    _, drive = system.step_powers(t, x, v, np.zeros(system.layout.n_lambda), F)
    _, bare_drive = bare.step_powers(t, x, v, np.zeros(system.layout.n_lambda), F)
    assert drive - bare_drive == pytest.approx(1.25 * 0.6, rel=1e-12)


def _joint_row(system, x, v, F, c, t):
    zero = np.zeros(system.nx)
    res = system.equations(x, v, zero, np.zeros(system.layout.n_lambda), F, t, 0.0, 0.0, 1.0, 1.0,
                           want_matrix=False)[0]
    return res[system.layout.z_of_x[c]]


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_newton_matrix_of_a_jointed_beam_is_the_residuals_derivative(formulation):
    """The Newton matrix (stiffness, damping, mass and the clamp's Hessian through the joint
    angles, the motor law's derivatives) against central differences of the residual along the
    generalized-alpha correction, at a perturbed state, hub free."""
    law = TorqueLaw.pd(3.0, 0.7, DriveProfile.slew(0.8, 2.0))
    joint = Joint.named("flap", stiffness=(12.0,), damping=(0.9,), neutral=(0.2,), torque=law)
    system = _system(joint, formulation, hub=Hub("free", 2.0))
    A, D, _, _ = newton_matrix_and_differences(system, perturbation=0.01, stiffness="exact")
    c = system.layout.z_of_x[system.layout.joint_x(0).start]
    scale = np.max(np.abs(D))
    # the joint angle's row and column: exact (the dynamic matrix leaves out only the beams'
    # inertia-force derivatives, not the joint's terms)
    assert np.max(np.abs(A[c] - D[c])) <= 1e-4 * scale
    assert np.max(np.abs(A[:, c] - D[:, c])) <= 1e-4 * scale


@pytest.mark.parametrize("modes", [None, 3])
def test_what_the_ffr_matrix_leaves_out_on_a_hinge_is_linear_in_the_rates(modes):
    """An FFR beam (nodal and modal) on a stiff flap hinge, hub turning at Omega, the joint's
    and the beam's rates 0.05 Omega times fixed normal numbers: the Newton matrix's joint row
    and column against central differences of the residual along the generalized-alpha
    correction. The dynamic matrix leaves out only the rates' derivatives of the inertia
    forces, which are bilinear in the rates (Coriolis, centrifugal), so the mismatch vanishes
    at rest (to the differences' round-off) and grows linearly with Omega (doubling Omega
    doubles it); a term of the joint's rows that were wrong at any state would break either.
    (Measured: relative 3e-8 at rest; nodal 2.9e-6 per rad/s, modal 1.1e-5.)"""
    from tests.conftest import ALPHA_COEFS, central_difference

    ck, gp, bp = ALPHA_COEFS
    part = FfrPart(FfrBeam(1.2, 3, plate(), modes=modes), Mount(0.3, 0.4, 0.5, 0.1, joint=Joint.named(
        "flap", stiffness=(1.0e4,))))
    system = MultibodySystem([part], Hub("free", 2.0), gravity=(0.0, -9.81, 0.0))
    layout, s = system.layout, system.mass_scale
    x0, F = system.initial_state(0.3)
    rng = np.random.default_rng(3)
    x0[1:] += 0.01 * rng.normal(size=x0.size - 1)
    lam0 = rng.normal(size=layout.n_lambda)
    rates = 0.05 * rng.normal(size=x0.size)
    rates[layout.theta] = 1.0
    c = layout.z_of_x[layout.joint_x(0).start]

    def mismatch(omega):
        v0, a0 = omega * rates, np.zeros_like(x0)

        def residual(z):
            dx, dmu = layout.split_z(z)
            return system.equations(x0 + dx, v0 + gp * dx, a0 + bp * dx, lam0 + s / ck * dmu, F, 0.3, 0.0, 0.0, ck, s,
                                    want_matrix=False)[0]

        A = system.equations(x0, v0, a0, lam0, F, 0.3, ck * bp, ck * gp, ck, s)[1].to_dense()
        D = central_difference(residual, np.zeros(A.shape[0]), 1e-7)
        return max(np.max(np.abs(A[c] - D[c])), np.max(np.abs(A[:, c] - D[:, c]))) / np.max(np.abs(D))

    at_rest, one, two = mismatch(0.0), mismatch(8.0), mismatch(16.0)
    assert at_rest <= 1e-7
    assert one >= 100.0 * at_rest  # the left-out terms are there in motion (else the next line tests noise)
    assert two / one == pytest.approx(2.0, rel=0.02)


def test_a_positive_lag_motor_torque_reacts_on_the_hub_as_a_positive_hub_torque():
    """A lag torque is positive about +j0, a hub torque about -j0: a constant lag motor torque T
    on a stiff blade of a free hub at rest turns the hub forward (theta > 0) and the blade back
    (psi > 0) as the rigid two-body closed form says, M [theta'', psi''] = [0, T] with M from
    the blade's inertias about the hub axis and about the hinge (written out here; theta turns
    about -j0 and psi about +j0, so their coupling enters with a minus sign), and the system's
    angular momentum stays zero."""
    from hubbeam.elements.section import Section
    from hubbeam.io.scenario import Sensor
    from hubbeam.simulation import simulate

    T, J, R, Lb, a = 0.1, 0.8, 0.3, 1.2, 0.04  # psi stays below 0.03 rad: the inertias stay those at psi = 0
    section = Section(a, a, 2700.0, 70e9, 26e9, 0.141 * a**4)
    part = FfrPart(FfrBeam(Lb, 2, section), Mount(R, joint=Joint.named("lag", torque=TorqueLaw.constant(T))))
    system = MultibodySystem([part], Hub("free", J))
    m = section.mass_per_length * Lb
    I_sec = section.density * section.i_y * Lb  # the sections turning about j0 (their m axis)
    I_hinge = m * Lb**2 / 3.0 + I_sec
    I_hub = J + m * (R**2 + R * Lb + Lb**2 / 3.0) + I_sec
    coupling = m * (R * Lb / 2.0 + Lb**2 / 3.0) + I_sec
    acc = np.linalg.solve([[I_hub, -coupling], [-coupling, I_hinge]], [0.0, T])
    t = 0.3
    traj = simulate(system, [Sensor(name="H", kind="angular_momentum"), Sensor(name="th", kind="hub_angle"),
                             Sensor(name="psi", kind="joint_angle")], t, 1e-3, 1.0, t)
    theta, psi = traj.records["th"][-1], traj.records["psi"][-1]
    assert theta > 0.0 and psi > 0.0
    assert theta == pytest.approx(0.5 * acc[0] * t**2, rel=2e-3)
    assert psi == pytest.approx(0.5 * acc[1] * t**2, rel=2e-3)
    assert np.max(np.abs(traj.records["H"])) < 1e-6 * T * t


def test_the_time_loop_looks_for_latch_events_only_when_a_free_axis_has_a_latch():
    """A hinge without a latch, or one already locked, cannot reach an event: the compiled model
    then skips the per-step look (about 0.3 us per step on a 4-mode FFR beam); a latch that can
    still be reached keeps it."""
    assert not _system(Joint.named("flap", stiffness=(1.0,))).model().events
    latched = _system(Joint.named("flap", initial_angle=(0.1,), latch=0.5))
    assert latched.model().events
    x, F = latched.initial_state()
    locked, _, _, _ = latch_joints(latched, [0], 0.0, x, np.zeros(latched.nx), F)
    assert not locked.model().events


@pytest.mark.parametrize("law", ["spring", "damper", "motor", "locked damper"])
def test_the_time_loop_skips_the_powers_only_where_no_joint_can_have_one(law):
    """An FFR beam without drag, damping or tip load on a fixed hub has no power; on a hinge with a
    spring alone neither (``model.powers`` False: the time loop skips the step's powers); with a
    damper or a motor it has, and a locked joint's damper none (its rate is held at zero). The flag
    against the powers computed in full (the model with the flag forced on) at a state with random
    coordinates, rates and multipliers (the fixed hub's and the lock's rates zero): both exactly
    zero where the flag is off, not both zero where it is on, so that a damper or a motor declared
    powerless fails here."""
    values = {"spring": {"stiffness": (50.0,)}, "damper": {"stiffness": (50.0,), "damping": (3.0,)},
              "motor": {"torque": TorqueLaw.constant(2.0)}, "locked damper": {"damping": (3.0,)}}[law]
    joint = Joint.named("flap", **values)
    system = _system(joint, "ffr", gravity=(0.0, 0.0, 0.0))
    if law == "locked damper":
        x, F = system.initial_state()
        system = latch_joints(system, [0], 0.0, x, np.zeros(system.nx), F)[0]
    model = system.model()
    x, F = system.initial_state()
    rng = np.random.default_rng(25)
    x, v, lam = x + 1e-3 * rng.normal(size=x.shape), rng.normal(size=x.shape), rng.normal(size=system.layout.n_lambda)
    v[system.layout.theta] = 0.0
    if law == "locked damper":
        v[system.layout.joint_x(0)] = 0.0
    dissipated, drive = system.functions.step_powers(model._replace(powers=True), np.ascontiguousarray(F), 0.5, x,
                                                     v, lam)
    assert model.powers == (law in ("damper", "motor"))
    if model.powers:
        assert abs(dissipated) + abs(drive) > 1e-3, (dissipated, drive)
    else:
        assert dissipated == 0.0 and drive == 0.0


def test_layout_places_locks_between_joint_angles_and_clamps():
    layout = Layout((16, 24), True, joint_dofs=(2, 1), clamped=(True, False), locks=(0, 1))
    assert layout.n_lambda == 1 + 6 + 1
    assert layout.lock_lambda(1) == slice(7, 8) and layout.clamp_lambda(0) == slice(1, 7)
    z0, z1 = layout.beam_z(0), layout.beam_z(1)
    assert list(layout.z_of_x[layout.joint_x(0)]) == [z0.start, z0.start + 1]
    assert layout.z_of_lambda[layout.clamp_lambda(0).start] == z0.start + 2
    assert layout.z_of_x[layout.joint_x(1).start] == z1.start
    assert layout.z_of_lambda[layout.lock_lambda(1).start] == z1.start + 1
    assert layout.z_of_x[layout.beam_x(1).start] == z1.start + 2
    assert sorted(np.concatenate([layout.z_of_x, layout.z_of_lambda])) == list(range(layout.nz))
    with pytest.raises(ValueError, match="more locks"):
        Layout((16,), True, joint_dofs=(0,), locks=(1,))


def test_joint_refuses_what_it_cannot_be():
    with pytest.raises(ValueError, match="single-axis"):
        Joint.named("flap", "lag", latch=0.5)
    with pytest.raises(ValueError, match="start latched"):
        Joint.named("flap", latch=0.0)
    with pytest.raises(ValueError, match="not a direction"):
        Joint(((0.0, 0.0, 0.0),), ("axis1",))
    with pytest.raises(ValueError, match="one value per axis"):
        Joint.named("flap", "lag", stiffness=(1.0,))
