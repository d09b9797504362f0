"""Measured quantities of a hub-beam state (conventions.md, "Measured quantities")."""

from __future__ import annotations

import numpy as np

from hubbeam.api import tip_displacement
from hubbeam.system.model import HubBeamSystem

UNITS = {
    "surface_strain": "1", "hub_angle": "rad", "hub_angular_velocity": "rad/s", "hub_torque": "N m",
    "tip_deflection": "m", "energy": "J", "constraint_violation": "m",
}


def section_point(sensor, system: HubBeamSystem) -> tuple[float, float]:
    """(y, z) of a strain gauge: 'upper' is z = +h/2 (the face whose normal is +n)."""
    h = system.beam.section.thickness
    if sensor.surface == "upper":
        return 0.0, h / 2
    if sensor.surface == "lower":
        return 0.0, -h / 2
    return sensor.y, sensor.z


def energies(system: HubBeamSystem, x, v, F) -> dict[str, float]:
    """Kinetic (hub and beam, with the sections' rotary inertia), strain and gravity energy (J)."""
    beam = system.beam
    q, qd = x[1:], v[1:]
    Mb = beam.mass_blocks(q, F)
    kinetic = 0.5 * system.hub_inertia * v[0] ** 2
    for e in range(beam.elements):
        ve = qd[8 * e : 8 * e + 16]
        kinetic += 0.5 * ve @ Mb[e] @ ve
    strain = beam.elastic(q, F, tangent=False)[0]
    gravity = -system.gravity_load @ q
    return {"kinetic": kinetic, "strain": strain, "gravity": gravity}


def measure(sensor, system: HubBeamSystem, state, work: dict[str, float]):
    """The value (float, or dict of parts) of one sensor at an integrator state."""
    kind = sensor.kind
    x, v, F = state.x, state.v, state.chart
    if kind == "surface_strain":
        y, z = section_point(sensor, system)
        return system.beam.surface_strain(x[1:], F, sensor.x, y, z)
    if kind == "hub_angle":
        return float(x[0])
    if kind == "hub_angular_velocity":
        return float(v[0])
    if kind == "hub_torque":
        return float(-state.lam[6]) if state.lam.shape[0] > 6 else 0.0
    if kind == "tip_deflection":
        return tip_displacement(system, x)
    if kind == "energy":
        e = energies(system, x, v, F)
        e["total"] = e["kinetic"] + e["strain"] + e["gravity"]
        e["dissipated"] = work["dissipated"]
        e["drive"] = work["drive"]
        return e
    if kind == "constraint_violation":
        phi, _, _ = system.constraints(x, F, system.drive_angle(state.t))
        return float(np.max(np.abs(phi[0:5])))
    raise ValueError(kind)
