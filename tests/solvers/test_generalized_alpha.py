"""Generalized-alpha on the hub-beam DAE: energy balance, constraint satisfaction, parameters."""

import numpy as np
import pytest

from hubbeam.io.scenario import Sensor
from hubbeam.simulation import simulate
from hubbeam.solvers.generalized_alpha import AlphaParameters
from hubbeam.system.beam import AncfBeam
from hubbeam.system.model import HubBeamSystem
from tests.conftest import L, plate

SENSORS = [Sensor(name="energy", kind="energy"), Sensor(name="violation", kind="constraint_violation"),
           Sensor(name="omega", kind="hub_angular_velocity")]


def free_hub(damping=(0.0, 0.0), elements=4):
    return HubBeamSystem(AncfBeam(L, elements, plate()), radius=0.35, twist=np.pi / 4, motion="free",
                         hub_inertia=9.557, gravity=np.array([0, -9.81, 0]), damping=damping)


def test_chung_hulbert_parameters():
    p = AlphaParameters.from_spectral_radius(1.0)
    assert (p.alpha_m, p.alpha_f, p.gamma, p.beta) == pytest.approx((0.5, 0.5, 0.5, 0.25))
    p = AlphaParameters.from_spectral_radius(0.8)
    assert p.gamma == pytest.approx(0.5 + p.alpha_f - p.alpha_m)


def test_free_hub_without_damping_conserves_energy():
    traj = simulate(free_hub(), SENSORS, t_end=0.6, dt=2e-3, spectral_radius=1.0, output_dt=0.02)
    e = traj.records["energy"]
    total = np.array([r["total"] for r in e])
    scale = max(r["kinetic"] for r in e)
    assert scale > 0.05  # the beam falls and the hub turns: energy is exchanged
    assert np.max(np.abs(total - total[0])) < 1e-4 * scale
    assert np.max(traj.records["violation"]) < 1e-10
    assert max(abs(w) for w in traj.records["omega"]) > 1e-3


def test_with_damping_total_plus_dissipated_is_constant():
    traj = simulate(free_hub(damping=(1.73, 1.4)), SENSORS, t_end=0.6, dt=2e-3, spectral_radius=1.0, output_dt=0.02)
    e = traj.records["energy"]
    balance = np.array([r["total"] + r["dissipated"] for r in e])
    assert e[-1]["dissipated"] > 1e-3
    assert np.max(np.abs(balance - balance[0])) < 1e-3 * e[-1]["dissipated"] + 1e-6
