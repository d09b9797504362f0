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
from hubbeam.solvers.generalized_alpha import NewtonOptions
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
