"""The ``[[sensors]]`` tables: kinds, parts and result columns."""

from __future__ import annotations

from typing import Literal

from pydantic import (
    PrivateAttr,
    model_validator,
)

from hubbeam.io.scenario.common import Identifier, NonNegative, StrictTable


SensorKind = Literal[
    "surface_strain", "hub_angle", "hub_angular_velocity", "hub_torque", "tip_deflection", "energy",
    "angular_momentum", "constraint_violation", "applied_torque",
    "base_position", "base_rotation", "base_velocity", "base_angular_velocity", "centre_of_mass", "linear_momentum",
    "system_angular_momentum", "base_torque", "joint_angle", "joint_rate", "joint_torque",
]

#: the sensors of a base and of the whole system in space: three components each
VECTOR_SENSORS = ("base_position", "base_rotation", "base_velocity", "base_angular_velocity", "centre_of_mass",
                  "linear_momentum", "system_angular_momentum", "base_torque")

#: the sensors of a beam's joint: one value, or one part per axis of a multi-axis joint
JOINT_SENSORS = frozenset({"joint_angle", "joint_rate", "joint_torque"})
#: sensors that belong to one beam (``beam``: a beam name, default the first beam)
BEAM_SENSORS = frozenset({"surface_strain", "tip_deflection"}) | JOINT_SENSORS
#: sensors with an optional ``beam`` (without it, the whole system)
OPTIONAL_BEAM_SENSORS = frozenset({"energy"})
#: multi-part sensors -> their parts; the columns are NAME_PART
SENSOR_PARTS: dict[str, tuple[str, ...]] = {
    "tip_deflection": ("radial", "vertical", "tangential"),
    "energy": ("kinetic", "strain", "gravity", "total", "dissipated", "drive"),
    **{kind: ("x", "y", "z") for kind in VECTOR_SENSORS},
}
#: the parts of an energy sensor that names a beam (the work terms belong to the whole system)
BEAM_ENERGY_PARTS = ("kinetic", "strain", "gravity", "total")


class Sensor(StrictTable):
    name: Identifier
    kind: SensorKind
    beam: Identifier | None = None
    x: NonNegative | None = None
    surface: Literal["upper", "lower"] | None = None
    y: float | None = None
    z: float | None = None
    #: a joint sensor's axis names (the scenario's checks set them from the beam's joint)
    _axes: tuple = PrivateAttr(default=())

    def set_axes(self, names) -> None:
        """The axis names of the joint a joint sensor measures (its parts when there are several)."""
        self._axes = tuple(names)

    @model_validator(mode="after")
    def _station(self):
        if self.beam is not None and self.kind not in BEAM_SENSORS | OPTIONAL_BEAM_SENSORS:
            raise ValueError(f"beam: a {self.kind} sensor measures the hub or the whole system, not one beam")
        if self.kind == "surface_strain":
            if self.x is None:
                raise ValueError("x: required for a surface_strain sensor")
            if self.surface is not None and (self.y is not None or self.z is not None):
                raise ValueError("surface: give surface or y and z, not both")
            if self.surface is None and (self.y is None or self.z is None):
                raise ValueError("surface: give surface = 'upper' | 'lower', or both y and z")
        elif any(v is not None for v in (self.x, self.surface, self.y, self.z)):
            raise ValueError(f"x: station keys only apply to surface_strain sensors, not {self.kind}")
        return self

    @property
    def parts(self) -> tuple[str, ...] | None:
        """The parts of a multi-part sensor (None for a single value)."""
        if self.kind == "energy" and self.beam is not None:
            return BEAM_ENERGY_PARTS
        if self.kind in JOINT_SENSORS:
            return self._axes if len(self._axes) > 1 else None
        return SENSOR_PARTS.get(self.kind)

    @property
    def columns(self) -> tuple[str, ...]:
        """The result columns of this sensor: NAME, or NAME_PART for a multi-part sensor."""
        parts = self.parts
        return (self.name,) if parts is None else tuple(f"{self.name}_{p}" for p in parts)


