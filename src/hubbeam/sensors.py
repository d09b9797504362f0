"""Measured quantities of a hub-beam state (conventions.md, "Measured quantities")."""

from __future__ import annotations

from hubbeam.system.model import HubSystem

UNITS = {
    "surface_strain": "1", "hub_angle": "rad", "hub_angular_velocity": "rad/s", "hub_torque": "N m",
    "tip_deflection": "m", "energy": "J", "angular_momentum": "N m s", "constraint_violation": "m",
}


def section_point(sensor, system: HubSystem) -> tuple[float, float]:
    """(y, z) of a strain gauge: 'upper' is z = +h/2 (the face whose normal is +n)."""
    h = system.beam.section.thickness
    if sensor.surface == "upper":
        return 0.0, h / 2
    if sensor.surface == "lower":
        return 0.0, -h / 2
    return sensor.y, sensor.z


def _energy(sensor, system, state, work):
    e = system.energies(state.x, state.v, state.chart)
    e["total"] = e["kinetic"] + e["strain"] + e["gravity"]
    e["dissipated"] = work["dissipated"]
    e["drive"] = work["drive"]
    return e


def _surface_strain(sensor, system, state, work):
    y, z = section_point(sensor, system)
    return system.surface_strain(state.x, state.chart, sensor.x, y, z)


def _constraint_violation(sensor, system, state, work):
    return system.constraint_violation(state.x, state.chart, state.t)


#: sensor kind -> function(sensor, system, state, work) giving a float or a dict of parts
MEASURES = {
    "surface_strain": _surface_strain,
    "hub_angle": lambda sensor, system, state, work: float(state.x[0]),
    "hub_angular_velocity": lambda sensor, system, state, work: float(state.v[0]),
    "hub_torque": lambda sensor, system, state, work: system.drive_torque(state.lam),
    "tip_deflection": lambda sensor, system, state, work: system.tip_displacement(state.x),
    "energy": _energy,
    "angular_momentum": lambda sensor, system, state, work: system.angular_momentum(state.x, state.v, state.chart),
    "constraint_violation": _constraint_violation,
}


def measure(sensor, system: HubSystem, state, work: dict[str, float]):
    """The value (float, or dict of parts) of one sensor at an integrator state."""
    return MEASURES[sensor.kind](sensor, system, state, work)
