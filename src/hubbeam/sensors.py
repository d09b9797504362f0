"""Measured quantities of a hub-beam state (conventions.md, "Measured quantities")."""

from __future__ import annotations

import numpy as np

from hubbeam.api import tip_displacement
from hubbeam.system.model import AXIS, HubBeamSystem

UNITS = {
    "surface_strain": "1", "hub_angle": "rad", "hub_angular_velocity": "rad/s", "hub_torque": "N m",
    "tip_deflection": "m", "energy": "J", "angular_momentum": "N m s", "constraint_violation": "m",
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


def angular_momentum(system: HubBeamSystem, x, v, F) -> float:
    """Angular momentum about the hub axis (N m s), positive in the sense of theta' (about -j0).

    By Noether's theorem it is the generalized momentum p = M(q) v projected on the rigid
    rotation of the whole system about the axis (xi = rates of theta' = 1): J theta' +
    v_q^T M(q) xi_q. In the axis chart xi is exact; otherwise the system is first moved to it."""
    beam = system.beam
    if not np.allclose(F[:, 0], -AXIS, atol=1e-12):
        x_axis, F_axis = system.axis_chart(x, F)
        # velocities move with the chart's Jacobian; a central difference of the remap
        eps = 1e-6
        v = (system.remap(x + eps * v, F, F_axis) - system.remap(x - eps * v, F, F_axis)) / (2 * eps)
        x, F = x_axis, F_axis
    xi, _ = system.steady_rotation_rates(x, F, 1.0)
    Mb = beam.mass_blocks(x[1:], F)
    h = system.hub_inertia * v[0]
    qd, xq = v[1:], xi[1:]
    for e in range(beam.elements):
        sl = slice(8 * e, 8 * e + 16)
        h += qd[sl] @ Mb[e] @ xq[sl]
    return float(h)


def _energy(sensor, system, state, work):
    e = energies(system, state.x, state.v, state.chart)
    e["total"] = e["kinetic"] + e["strain"] + e["gravity"]
    e["dissipated"] = work["dissipated"]
    e["drive"] = work["drive"]
    return e


def _surface_strain(sensor, system, state, work):
    y, z = section_point(sensor, system)
    return system.beam.surface_strain(state.x[1:], state.chart, sensor.x, y, z)


def _constraint_violation(sensor, system, state, work):
    phi, _, _ = system.constraints(state.x, state.chart, system.drive_angle(state.t))
    return float(np.max(np.abs(phi[0:5])))


#: sensor kind -> function(sensor, system, state, work) giving a float or a dict of parts
MEASURES = {
    "surface_strain": _surface_strain,
    "hub_angle": lambda sensor, system, state, work: float(state.x[0]),
    "hub_angular_velocity": lambda sensor, system, state, work: float(state.v[0]),
    "hub_torque": lambda sensor, system, state, work: float(-state.lam[6]) if state.lam.shape[0] > 6 else 0.0,
    "tip_deflection": lambda sensor, system, state, work: tip_displacement(system, state.x),
    "energy": _energy,
    "angular_momentum": lambda sensor, system, state, work: angular_momentum(system, state.x, state.v, state.chart),
    "constraint_violation": _constraint_violation,
}


def measure(sensor, system: HubBeamSystem, state, work: dict[str, float]):
    """The value (float, or dict of parts) of one sensor at an integrator state."""
    return MEASURES[sensor.kind](sensor, system, state, work)
