"""Joints in time (system/joints.py through simulation.py): a free hub carrying a two-link arm
whose elbow motor slews keeps zero angular momentum, and the energy balance holds with the
motor's work, the spring and the damper; the compiled loop takes the Python step's steps on a
chain of joints."""

from __future__ import annotations

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.io.scenario import Sensor
from hubbeam.simulation import simulate
from hubbeam.solvers.newton_control import NewtonOptions
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.beam import AncfBeam
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.joints import Joint
from hubbeam.system.laws import DriveProfile, TorqueLaw
from hubbeam.system.mount import Mount
from hubbeam.system.multibody import Hub, MultibodySystem
from tests.conftest import assert_compiled_steps_are_python_steps, plate


def _arm(forearm="ancf"):
    """A free hub (no torque) with an upper arm clamped to it and a forearm on an elbow (lag) joint
    with a spring (unloaded at the start: a torque that jumps at t = 0 rings the beam root's
    fastest modes at the step's frequency), a damper and a PD motor slewing it by 0.8 rad in 1 s;
    no gravity."""
    section = plate(0.04, 0.006)
    upper = AncfPart(AncfBeam(0.6, 3, section), Mount(0.05), name="upper")
    motor = TorqueLaw.pd(2.0, 0.6, DriveProfile.slew(0.8, 1.0))
    elbow = Joint.named("lag", stiffness=(0.3,), damping=(0.05,), neutral=(0.2,), initial_angle=(0.2,), torque=motor)
    mount = Mount(0.0, 0.0, 0.0, 0.0, parent=0, joint=elbow)
    fore = (AncfPart(AncfBeam(0.5, 3, section), mount, name="fore") if forearm == "ancf"
            else FfrPart(FfrBeam(0.5, 3, section), mount, name="fore"))
    return MultibodySystem([upper, fore], Hub("free", 0.3))


# slow: a long validation run (CI runs it: python -m pytest -q -m slow)
@pytest.mark.slow
@pytest.mark.parametrize("forearm", ["ancf", "ffr"])
def test_an_elbow_motor_on_a_free_hub_keeps_the_angular_momentum_and_the_energy_balance(forearm):
    """The motor's torque acts between the links: the angular momentum about the hub axis stays
    at zero (to 1e-7 N m s, 1e-6 of the forearm's own, about 0.1 N m s: the integration error);
    total + dissipated - drive stays at
    its start, the drive being the motor's work and dissipated the damper's (full Newton, dt = 1 ms,
    rho_inf = 1: 1e-5 of the motor's work); the hub turns against the elbow."""
    system = _arm(forearm)
    sensors = [Sensor(name="H", kind="angular_momentum"), Sensor(name="e", kind="energy"),
               Sensor(name="th", kind="hub_angle"), Sensor(name="psi", kind="joint_angle", beam="fore"),
               Sensor(name="T", kind="joint_torque", beam="fore")]
    traj = simulate(system, sensors, 1.5, 1e-3, 1.0, 0.01, newton=NewtonOptions(update="iteration"))
    e = traj.records["e"]
    drive = np.array([r["drive"] for r in e])
    balance = np.array([r["total"] + r["dissipated"] - r["drive"] for r in e])
    assert np.max(np.abs(drive)) > 0.05 and e[-1]["dissipated"] > 1e-4
    assert np.max(np.abs(balance - balance[0])) < 1e-5 * np.max(np.abs(drive))
    assert np.max(np.abs(traj.records["H"])) < 1e-7
    assert traj.records["psi"][-1] > 0.2 + 0.5  # the elbow turned most of the way
    assert traj.records["th"][-1] > 0.01  # the hub the other way: theta turns it about -j0, the lag about +j0


def test_the_compiled_loop_takes_the_python_steps_on_a_chain_of_joints():
    """A free hub, an upper arm on a flap hinge, a forearm on a two-axis elbow with a motor: the
    compiled loop and the Python step take the same steps and iterations."""
    section = plate(0.04, 0.006)
    upper = AncfPart(AncfBeam(0.6, 2, section), Mount(0.05, joint=Joint.named("flap", stiffness=(20.0,))))
    fore = FfrPart(FfrBeam(0.5, 2, section), Mount(0.0, parent=0, joint=Joint.named("lag", damping=(0.05,),
                                                                                     torque=TorqueLaw.constant(0.3))))
    system = MultibodySystem([upper, fore], Hub("free", 0.3), gravity=(0.0, -9.81, 0.0))
    assert_compiled_steps_are_python_steps(system, "adaptive")


@pytest.mark.slow  # a validation run that compiles its own models (minutes on a cold cache)
def test_hinged_panels_on_a_free_base_keep_the_momenta():
    """A free base (the hub fixed to it) with an ANCF panel on a lag hinge and an FFR panel (2
    modes) on a flap-lag joint hanging on its tip, hinges started turning: no external force,
    so the linear momentum and the angular momentum about the centre of mass stay at their
    start (the base carries the joints' reactions), and the centre of mass moves on a line. The
    momenta's drift is the integration error: second order in dt (the angular momentum's largest
    change 1.1e-4, 2.6e-5, 7.1e-6 N m s at dt = 4, 2, 1 ms against 11.2; the linear momentum's
    4.2e-5, 1.0e-5, 2.3e-6), so 1e-5 of their sizes at dt = 2 ms; a lost joint reaction or a
    wrong chain Jacobian moves them by orders more."""
    from hubbeam.system.base import Base

    section = plate(0.3, 0.01)
    base = Base("free", mass=40.0, inertia=((6.0, 0.0, 0.0), (0.0, 8.0, 0.0), (0.0, 0.0, 7.0)),
                velocity=(0.1, 0.0, -0.05), angular_velocity=(0.0, 0.2, 0.0))
    first = AncfPart(AncfBeam(0.8, 2, section), Mount(0.4, joint=Joint.named("lag", stiffness=(2.0,),
                                                                             initial_rate=(1.0,))))
    second = FfrPart(FfrBeam(0.6, 3, section, modes=2),
                     Mount(0.0, parent=0, joint=Joint.named("flap", "lag", damping=(0.05, 0.0), initial_rate=(0.5, -0.8))))
    system = MultibodySystem([first, second], Hub("fixed", 0.0), base=base)
    sensors = [Sensor(name="P", kind="linear_momentum"), Sensor(name="H", kind="system_angular_momentum"),
               Sensor(name="c", kind="centre_of_mass")]
    traj = simulate(system, sensors, 0.4, 2e-3, 1.0, 0.02, newton=NewtonOptions(update="iteration"))
    P = np.array([[r[a] for a in "xyz"] for r in traj.records["P"]])
    H = np.array([[r[a] for a in "xyz"] for r in traj.records["H"]])
    c = np.array([[r[a] for a in "xyz"] for r in traj.records["c"]])
    assert np.max(np.abs(P - P[0])) < 1e-5 * np.max(np.abs(P[0]))
    assert np.max(np.abs(H - H[0])) < 1e-5 * np.max(np.abs(H[0]))
    t = np.array(traj.times)
    mass = system.momenta(*_start(system))["mass"]
    line = c[0] + np.outer(t, P[0] / mass)
    assert np.max(np.abs(c - line)) < 1e-6 * np.max(np.abs(c - c[0]))


def _start(system):
    from hubbeam.simulation import initial_state

    st = initial_state(system)
    return st.x, st.v, st.chart
