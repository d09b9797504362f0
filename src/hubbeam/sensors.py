"""Measured quantities of a hub-beam state (the sensors of a scenario).

Sensors that belong to a beam (``surface_strain``, ``tip_deflection``, and ``energy`` when
it names one) measure the beam their ``beam`` key names (default: the first).
"""

from __future__ import annotations

from hubbeam.system.hub_system import HubSystem, energy_sums

UNITS = {
    "surface_strain": "1", "hub_angle": "rad", "hub_angular_velocity": "rad/s", "hub_torque": "N m",
    "applied_torque": "N m", "tip_deflection": "m", "energy": "J", "angular_momentum": "N m s",
    "constraint_violation": "m",
}

#: the parts of a sensor that gives several values (its columns are NAME_PART)
PARTS = {"tip_deflection": ("radial", "vertical", "tangential"),
         "energy": ("kinetic", "strain", "gravity", "total", "dissipated", "drive")}


def columns(sensor) -> list[str]:
    """The result columns of a sensor: its name, or NAME_PART for each of its parts (the energy
    of one beam has no dissipated or drive part)."""
    parts = PARTS.get(sensor.kind)
    if parts is None:
        return [sensor.name]
    if sensor.kind == "energy" and getattr(sensor, "beam", None) is not None:
        parts = parts[:4]
    return [f"{sensor.name}_{part}" for part in parts]


def _beam(sensor, system: HubSystem) -> int:
    return system.beam_index(getattr(sensor, "beam", None))


def section_point(sensor, system: HubSystem) -> tuple[float, float]:
    """(y, z) of a strain gauge on the section axes of its station: 'upper' is z = +h/2 (the face
    whose normal is +n), h the thickness at the station."""
    h = system.beams[_beam(sensor, system)].section_size(sensor.x)[1]
    if sensor.surface == "upper":
        return 0.0, h / 2
    if sensor.surface == "lower":
        return 0.0, -h / 2
    return sensor.y, sensor.z


def _energy(sensor, system):
    beam = getattr(sensor, "beam", None)
    index = None if beam is None else system.beam_index(beam)

    def energy(state, work):
        given = work.get("energies")  # (hub, beams) computed for a whole chunk of records
        e = (energy_sums(*given, index) if given is not None
             else system.energies(state.x, state.v, state.chart, index))
        e["total"] = e["kinetic"] + e["strain"] + e["gravity"]
        if beam is None:
            e["dissipated"] = work["dissipated"]
            e["drive"] = work["drive"]
        return e
    return energy


def gauge(sensor, system: HubSystem) -> tuple[int, float, float, float]:
    """(beam index, station (m), y, z (m)) of a surface_strain sensor."""
    return (_beam(sensor, system), float(sensor.x)) + section_point(sensor, system)


def record_needs(sensors, system: HubSystem) -> tuple[bool, bool, list]:
    """What the sensors read from the records' compiled measures (:meth:`HubSystem.record_measures`):
    (energies, tip displacements, the strain gauges (:func:`gauge`))."""
    kinds = {s.kind for s in sensors}
    return ("energy" in kinds, "tip_deflection" in kinds,
            [gauge(s, system) for s in sensors if s.kind == "surface_strain"])


def _surface_strain(sensor, system):
    where = gauge(sensor, system)
    beam, x, y, z = where

    def strain(state, work):
        given = work.get("strains")  # the gauges' strains computed for a whole chunk of records
        if given is not None and where in given:
            return given[where]
        return system.surface_strain(state.x, state.chart, x, y, z, beam)
    return strain


def _tip_deflection(sensor, system):
    beam = _beam(sensor, system)

    def tip(state, work):
        given = work.get("tips")  # computed for a whole chunk of records
        if given is None:
            return system.tip_displacement(state.x, beam)
        return {part: float(value) for part, value in zip(PARTS["tip_deflection"], given[beam])}
    return tip


#: sensor kind -> factory(sensor, system) of its measurement function(state, work), which
#: gives a float or a dict of parts; what depends on the sensor alone is found once
MEASURES = {
    "surface_strain": _surface_strain,
    "hub_angle": lambda sensor, system: lambda state, work: float(state.x[0]),
    "hub_angular_velocity": lambda sensor, system: lambda state, work: float(state.v[0]),
    "hub_torque": lambda sensor, system: lambda state, work: system.drive_torque(state.lam),
    "applied_torque": lambda sensor, system: lambda state, work: system.applied_torque(state.t, state.x, state.v),
    "tip_deflection": _tip_deflection,
    "energy": _energy,
    "angular_momentum": lambda sensor, system: lambda state, work: system.angular_momentum(state.x, state.v,
                                                                                            state.chart),
    "constraint_violation": lambda sensor, system: lambda state, work: system.constraint_violation(
        state.x, state.chart, state.t),
}


def prepare(sensor, system: HubSystem):
    """The measurement function(state, work) of one sensor on ``system``: the value (float, or
    dict of parts) at an integrator state; ``work`` holds the dissipated and drive work (J) up
    to it and, optionally, what :meth:`HubSystem.record_measures` gave for the state:
    ``energies`` = (hub, beams), ``tips`` and ``strains`` ({gauge: strain})."""
    return MEASURES[sensor.kind](sensor, system)


def measure(sensor, system: HubSystem, state, work: dict[str, float]):
    """The value (float, or dict of parts) of one sensor at an integrator state."""
    return prepare(sensor, system)(state, work)
