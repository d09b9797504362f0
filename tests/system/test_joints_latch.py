"""The latch (system/joints.py, simulation.py): the velocity projection against the kinetic
energy it removes (three ways), the angular momentum about the hub axis, the rigid-panel closed
form that bounds it; a damped panel deploying on a free hub ends at rest with the released
spring energy dissipated, the energy balance continuous through the event."""

from __future__ import annotations

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.elements.section import Section
from hubbeam.io.scenario import Sensor
from hubbeam.simulation import simulate
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.beam import AncfBeam
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.joints import Joint, latch_joints
from hubbeam.system.mount import Mount
from hubbeam.system.multibody import Hub, MultibodySystem

A = 0.04  # square section side (m)
SECTION = Section(A, A, 2700.0, 70e9, 26e9, 0.141 * A**4)
J, R, L = 0.8, 0.3, 1.2


def _rigid_closed_form(psi, rate):
    """The kinetic energy a lock removes from a rigid panel (a uniform rod of the section, turning
    on a lag hinge at radius R of a free hub of inertia J): rate^2 / (2 (M^-1)_psi,psi), M the
    two-body mass matrix over (theta, psi) written out from the rod's inertias."""
    m = SECTION.mass_per_length * L
    I_sec = SECTION.density * SECTION.i_y * L
    c = np.cos(psi)
    I_hinge = m * L**2 / 3 + I_sec
    I_hub = J + m * (R**2 + R * L * c + L**2 / 3) + I_sec
    coupling = m * (R * L / 2 * c + L**2 / 3) + I_sec
    M = np.array([[I_hub, -coupling], [-coupling, I_hinge]])
    return rate**2 / (2.0 * np.linalg.inv(M)[1, 1])


PANELS = {
    "ffr, 1 mode": lambda mount: FfrPart(FfrBeam(L, 2, SECTION, modes=1), mount),
    "ffr, 3 modes": lambda mount: FfrPart(FfrBeam(L, 2, SECTION, modes=3), mount),
    "ffr, 4 elements": lambda mount: FfrPart(FfrBeam(L, 4, SECTION), mount),
    "ancf, 1 element": lambda mount: AncfPart(AncfBeam(L, 1, SECTION), mount),
    "ancf, 2 elements": lambda mount: AncfPart(AncfBeam(L, 2, SECTION), mount),
    "ancf, 8 elements": lambda mount: AncfPart(AncfBeam(L, 8, SECTION), mount),
}


def _moving(panel, psi=0.7, omega=0.5, rate=2.0):
    """A free hub turning at omega carrying the panel, which turns on its hinge at ``rate``, rigid."""
    part = panel(Mount(R, joint=Joint.named("lag", initial_angle=(psi,), latch=1.0)))
    system = MultibodySystem([part], Hub("free", J))
    x, F = system.initial_state()
    v = np.zeros(system.nx)
    v[system.theta_index] = omega
    v[system.layout.joint_x(0).start] = rate
    r, _, v_root, w = system.root_motion(0, x, v, F)
    s = system.layout.beam_x(0)
    v[s] = part.rigid_rates(x[s], F[0], v_root, w, r)[0]
    return system, x, v, F


def test_the_projection_removes_what_its_impulse_says_and_keeps_the_momentum():
    """For every panel model: the energy the event reports (psi' Lambda / 2, from the lock's
    impulse) equals dv^T M dv / 2 (M the mass matrix) and the drop of the kinetic energy
    (the energy sums); the angular momentum about the hub axis is kept to round-off; the
    locked angle's rate is zero after; the energy is at most the rigid panel's closed form and
    falls as the panel gets more elastic freedom (FFR 1 mode, 3 modes, 4 nodal elements; ANCF
    1, 2, 8 elements), the rest of the closed form staying in the panel's vibration."""
    closed = _rigid_closed_form(0.7, 2.0)
    removed = {}
    for name, panel in PANELS.items():
        system, x, v, F = _moving(panel)
        new, v_plus, (event,), drive = latch_joints(system, [0], 0.0, x, v, F)
        dv = v_plus - v
        M = system.mass_matrix(x, F)
        before, after = system.energies(x, v, F)["kinetic"], new.energies(x, v_plus, F)["kinetic"]
        assert event.energy == pytest.approx(0.5 * dv @ M @ dv, rel=1e-10), name
        assert event.energy == pytest.approx(before - after, rel=1e-10), name
        assert drive == pytest.approx(0.0, abs=1e-12 * before), name  # a free hub: no prescribed motion
        assert new.angular_momentum(x, v_plus, F) == pytest.approx(system.angular_momentum(x, v, F), abs=1e-13), name
        assert v_plus[system.layout.joint_x(0).start] == 0.0
        assert event.angle == 0.7 and event.kinetic_before == pytest.approx(before)
        # (equal to round-off when the panel's modes do not bend it in the hinge's plane: the
        # square section's one lowest mode bends along its y, which this hinge does not load)
        assert 0.0 < event.energy <= closed * (1.0 + 1e-12), name
        removed[name] = event.energy
    assert removed["ffr, 1 mode"] > removed["ffr, 3 modes"] > removed["ffr, 4 elements"]
    assert removed["ancf, 1 element"] > removed["ancf, 2 elements"] > removed["ancf, 8 elements"]
    assert removed["ffr, 1 mode"] > 0.3 * closed


def test_a_damped_panel_deploying_on_a_free_hub_ends_at_rest_with_the_spring_energy_dissipated():
    """A flat panel (FFR, 1 mode, structural damping) on a spring hinge with a damper, released
    from rest at 0 towards its spring's neutral 150 deg, latches at 90 deg and rings down. At the
    end everything is at rest (the angular momentum was zero) with the released spring energy
    k (150^2 - 60^2) deg^2 / 2 in ``dissipated``: the hinge damper's work before the latch, the
    projection's and the structural damping's after. The energy balance and the angular
    momentum hold to the integration error (rho_inf = 1, dt = 1 ms: 0.15 % and 3e-4 N m s,
    second order in dt)."""
    from hubbeam.elements.section import saint_venant_torsion_constant
    from hubbeam.solvers.newton_control import NewtonOptions

    k, c = 3.0, 0.05
    section = Section(0.3, 0.01, 2700.0, 70e9, 26e9, saint_venant_torsion_constant(0.3, 0.01))
    joint = Joint.named("lag", stiffness=(k,), damping=(c,), neutral=(np.radians(150.0),), latch=np.radians(90.0))
    panel = FfrPart(FfrBeam(L, 4, section, modes=1, structural_damping=0.01), Mount(R, joint=joint))
    system = MultibodySystem([panel], Hub("free", J))
    sensors = [Sensor(name="e", kind="energy"), Sensor(name="H", kind="angular_momentum"),
               Sensor(name="psi", kind="joint_angle")]
    traj = simulate(system, sensors, 2.0, 1e-3, 1.0, 0.01, newton=NewtonOptions(update="iteration"))
    (event,) = traj.latches
    assert event.angle == pytest.approx(np.radians(90.0), abs=3e-3)  # within one step of the latch angle
    assert 0.0 < event.energy < event.kinetic_before
    e = traj.records["e"]
    released = 0.5 * k * (np.radians(150.0) ** 2 - np.radians(60.0) ** 2)
    balance = np.array([r["total"] + r["dissipated"] - r["drive"] for r in e])
    assert np.max(np.abs(balance - balance[0])) < 2e-3 * released
    assert np.max(np.abs(traj.records["H"])) < 5e-4
    final = e[-1]
    assert final["kinetic"] < 1e-6 * released
    assert final["dissipated"] == pytest.approx(released, rel=3e-3)
    assert traj.records["psi"][-1] == event.angle
