"""Measured quantities of a system's state (the sensors of a scenario).

Sensors that belong to a beam (``surface_strain``, ``tip_deflection``, and ``energy`` when
it names one) measure the beam their ``beam`` key names (default: the first).
"""

from __future__ import annotations

from hubbeam.system.controller_inputs import gauge_point
from hubbeam.system.joints import joint_torques
from hubbeam.system.multibody import MultibodySystem, energy_sums

UNITS = {
    "surface_strain": "1", "hub_angle": "rad", "hub_angular_velocity": "rad/s", "hub_torque": "N m",
    "applied_torque": "N m", "tip_deflection": "m", "energy": "J", "angular_momentum": "N m s",
    "constraint_violation": "m", "base_position": "m", "base_rotation": "rad", "base_velocity": "m/s",
    "base_angular_velocity": "rad/s", "centre_of_mass": "m", "linear_momentum": "N s",
    "system_angular_momentum": "N m s", "base_torque": "N m", "joint_angle": "rad", "joint_rate": "rad/s",
    "joint_torque": "N m",
}

#: the sensors of a base and of the whole system in space: three components each
VECTOR_SENSORS = ("base_position", "base_rotation", "base_velocity", "base_angular_velocity", "centre_of_mass",
                  "linear_momentum", "system_angular_momentum", "base_torque")

#: the parts of a sensor that gives several values (its columns are NAME_PART)
PARTS = {"tip_deflection": ("radial", "vertical", "tangential"),
         "energy": ("kinetic", "strain", "gravity", "total", "dissipated", "drive"),
         **{kind: ("x", "y", "z") for kind in VECTOR_SENSORS}}


def columns(sensor) -> list[str]:
    """The result columns of a sensor: its name, or NAME_PART for each of its parts (the energy
    of one beam has no dissipated or drive part)."""
    parts = PARTS.get(sensor.kind)
    if sensor.kind in JOINT_SENSORS:
        parts = getattr(sensor, "parts", None)  # a multi-axis joint's axes (the scenario's sensor knows them)
    if parts is None:
        return [sensor.name]
    if sensor.kind == "energy" and getattr(sensor, "beam", None) is not None:
        parts = parts[:4]
    return [f"{sensor.name}_{part}" for part in parts]


def _beam(sensor, system: MultibodySystem) -> int:
    return system.beam_index(getattr(sensor, "beam", None))


def section_point(sensor, system: MultibodySystem) -> tuple[float, float]:
    """(y, z) of a strain gauge on the section axes of its station: 'upper' is z = +h/2 (the face
    whose normal is +n), h the thickness at the station."""
    return gauge_point(system, _beam(sensor, system), sensor.x, sensor.surface, sensor.y, sensor.z)


def _energy(sensor, system):
    beam = getattr(sensor, "beam", None)
    index = None if beam is None else system.beam_index(beam)

    def energy(state, work):
        e = system.energies(state.x, state.v, state.chart, index)
        e["total"] = e["kinetic"] + e["strain"] + e["gravity"]
        if beam is None:
            e["dissipated"] = work["dissipated"]
            e["drive"] = work["drive"]
        return e
    return energy


def gauge(sensor, system: MultibodySystem) -> tuple[int, float, float, float]:
    """(beam index, station (m), y, z (m)) of a surface_strain sensor."""
    return (_beam(sensor, system), float(sensor.x)) + section_point(sensor, system)


def record_needs(sensors, system: MultibodySystem) -> tuple[bool, bool, list]:
    """What the sensors read from the records' compiled measures (:meth:`MultibodySystem.record_measures`):
    (energies, tip displacements, the strain gauges (:func:`gauge`))."""
    kinds = {s.kind for s in sensors}
    return ("energy" in kinds, "tip_deflection" in kinds,
            [gauge(s, system) for s in sensors if s.kind == "surface_strain"])


def _surface_strain(sensor, system):
    beam, x, y, z = gauge(sensor, system)
    return lambda state, work: system.surface_strain(state.x, state.chart, x, y, z, beam)


def _tip_deflection(sensor, system):
    beam = _beam(sensor, system)
    return lambda state, work: system.tip_displacement(state.x, beam, state.chart)


#: the sensors of a beam's joint (one part per axis of a multi-axis joint)
JOINT_SENSORS = ("joint_angle", "joint_rate", "joint_torque")


def _joint(sensor, system: MultibodySystem):
    """(the joint of the sensor's beam, where its angles start in x, the beam's index); ValueError
    for a clamped beam."""
    k = _beam(sensor, system)
    joint = system.beams[k].mount.joint
    if joint is None:
        raise ValueError(f"sensor {sensor.name!r}: beam {system.beams[k].name!r} is clamped (no joint to measure)")
    return joint, system.layout.joint_x(k).start, k


def _joint_values(joint, values):
    """One float, or {axis name: value} for a multi-axis joint."""
    if joint.count == 1:
        return float(values[0])
    return {name: float(v) for name, v in zip(joint.names, values)}


def _joint_coordinate(which: str):
    """joint_angle (x) or joint_rate (v) of the sensor's beam's joint axes."""
    def factory(sensor, system):
        joint, first, _ = _joint(sensor, system)
        return lambda state, work: _joint_values(joint, getattr(state, which)[first:first + joint.count])
    return factory


def _joint_torque(sensor, system):
    joint, _, k = _joint(sensor, system)
    return lambda state, work: _joint_values(joint, joint_torques(system, state.t, state.x, state.v, state.lam,
                                                                  state.chart)[k])


def _vector(measure):
    """A three-component sensor: the function(system, state) of a 3-vector as {x, y, z}."""
    def factory(sensor, system):
        def value(state, work):
            v = measure(system, state)
            return {"x": float(v[0]), "y": float(v[1]), "z": float(v[2])}
        return value
    return factory


def _system_angular_momentum(system, state):
    """About the system's centre of mass (N m s, global)."""
    mom = system.momenta(state.x, state.v, state.chart)
    import numpy as np

    return mom["angular"] - np.cross(mom["centre_of_mass"], mom["linear"])


#: sensor kind -> factory(sensor, system) of its measurement function(state, work), which
#: gives a float or a dict of parts; what depends on the sensor alone is found once
MEASURES = {
    "base_position": _vector(lambda system, st: system.base_motion(st.x, st.v)[0]),
    "base_rotation": _vector(lambda system, st: system.base_rotation_vector(st.x)),
    "base_velocity": _vector(lambda system, st: system.base_motion(st.x, st.v)[2]),
    "base_angular_velocity": _vector(lambda system, st: system.base_motion(st.x, st.v)[1].T
                                     @ system.base_motion(st.x, st.v)[3]),
    "centre_of_mass": _vector(lambda system, st: system.momenta(st.x, st.v, st.chart)["centre_of_mass"]),
    "linear_momentum": _vector(lambda system, st: system.momenta(st.x, st.v, st.chart)["linear"]),
    "system_angular_momentum": _vector(_system_angular_momentum),
    "base_torque": _vector(lambda system, st: system.base_torque(st.t, st.x, st.v, st.chart)),
    "surface_strain": _surface_strain,
    "hub_angle": lambda sensor, system: lambda state, work: float(state.x[system.theta_index]),
    "hub_angular_velocity": lambda sensor, system: lambda state, work: float(state.v[system.theta_index]),
    "hub_torque": lambda sensor, system: lambda state, work: system.drive_torque(state.lam),
    "applied_torque": lambda sensor, system: lambda state, work: system.applied_torque(state.t, state.x, state.v,
                                                                                          state.chart),
    "tip_deflection": _tip_deflection,
    "energy": _energy,
    "angular_momentum": lambda sensor, system: lambda state, work: system.angular_momentum(state.x, state.v,
                                                                                            state.chart),
    "constraint_violation": lambda sensor, system: lambda state, work: system.constraint_violation(
        state.x, state.chart, state.t),
    "joint_angle": _joint_coordinate("x"),
    "joint_rate": _joint_coordinate("v"),
    "joint_torque": _joint_torque,
}


def _per_state(measure):
    """A chunk measurement (:func:`prepare_chunk`) that reads each record's state alone."""
    return lambda chunk: [measure(chunk.state(i), chunk.work(i)) for i in range(len(chunk))]


def _chunk_energy(sensor, system):
    beam = getattr(sensor, "beam", None)
    index = None if beam is None else system.beam_index(beam)
    each = _per_state(_energy(sensor, system))

    def energy(chunk):
        if chunk.energies is None:
            return each(chunk)
        e = energy_sums(*chunk.energies, index)  # every record at once
        kinetic, strain, gravity = e["kinetic"], e["strain"], e["gravity"]
        columns = {"kinetic": kinetic, "strain": strain, "gravity": gravity, "total": kinetic + strain + gravity}
        if index is None:
            columns.update(dissipated=chunk.dissipated, drive=chunk.drive)
        return [dict(zip(columns, row)) for row in zip(*(c.tolist() for c in columns.values()))]
    return energy


def _chunk_surface_strain(sensor, system):
    where = gauge(sensor, system)
    each = _per_state(_surface_strain(sensor, system))

    def strain(chunk):
        given = chunk.strains.get(where)
        return each(chunk) if given is None else given.tolist()
    return strain


def _chunk_tip_deflection(sensor, system):
    beam = _beam(sensor, system)
    each = _per_state(_tip_deflection(sensor, system))
    parts = PARTS["tip_deflection"]

    def tip(chunk):
        if chunk.tips is None:
            return each(chunk)
        return [dict(zip(parts, row)) for row in chunk.tips[:, beam].tolist()]
    return tip


def _chunk_base(component):
    """A base sensor over a chunk of records, the base frame's motion of every record in one
    compiled call (:meth:`MultibodySystem.base_motions`): ``component`` (r, R, vel, w) -> (n, 3)."""
    def factory(sensor, system):
        def measure(chunk):
            values = component(*system.base_motions(chunk.states.x, chunk.states.v))
            return [{"x": a, "y": b, "z": c} for a, b, c in values.tolist()]
        return measure
    return factory


#: sensor kind -> factory(sensor, system) of its measurement over a chunk of records, for the
#: kinds that read arrays computed for the whole chunk (the others read the records one by one)
CHUNK_MEASURES = {
    "base_position": _chunk_base(lambda r, R, vel, w: r),
    "base_velocity": _chunk_base(lambda r, R, vel, w: vel),
    "base_angular_velocity": _chunk_base(lambda r, R, vel, w: (R.transpose(0, 2, 1) @ w[:, :, None])[:, :, 0]),
    "surface_strain": _chunk_surface_strain,
    "hub_angle": lambda sensor, system: lambda chunk: chunk.states.x[:, system.theta_index].tolist(),
    "hub_angular_velocity": lambda sensor, system: lambda chunk: chunk.states.v[:, system.theta_index].tolist(),
    "tip_deflection": _chunk_tip_deflection,
    "energy": _chunk_energy,
}


def prepare_chunk(sensor, system: MultibodySystem):
    """The measurement function(chunk) of one sensor on ``system``: its values (floats, or dicts
    of parts, as :func:`prepare` gives them) at each record of a chunk, a list. A chunk
    (:class:`hubbeam.simulation.RecordChunk`) holds the records' states and work as
    arrays (row i: record i; ``state(i)`` and ``work(i)`` give one record as :func:`prepare`
    reads it) and, when the compiled steps computed them for the whole chunk, ``energies`` =
    (hub (n, 3), beams (n, beams, 3)) (J), ``tips`` (n, beams, 3) (m) and ``strains``
    ({gauge: (n,)}); the sensors that read those take them from there."""
    chunk_measure = CHUNK_MEASURES.get(sensor.kind)
    if chunk_measure is not None:
        return chunk_measure(sensor, system)
    return _per_state(prepare(sensor, system))


def prepare(sensor, system: MultibodySystem):
    """The measurement function(state, work) of one sensor on ``system``: the value (float, or
    dict of parts) at an integrator state; ``work`` holds the dissipated and drive work (J) up
    to it."""
    return MEASURES[sensor.kind](sensor, system)


def measure(sensor, system: MultibodySystem, state, work: dict[str, float]):
    """The value (float, or dict of parts) of one sensor at an integrator state."""
    return prepare(sensor, system)(state, work)
