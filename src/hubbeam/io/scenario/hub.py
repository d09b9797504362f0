"""The ``[hub]`` table: its motion, drive profile and torque law."""

from __future__ import annotations

import math
from typing import Annotated, Any, ClassVar, Literal, Union

from pydantic import (
    Discriminator,
    Field,
    Tag,
    model_serializer,
    model_validator,
)

from hubbeam.io.scenario.common import KeyedChoice, NonNegative, Positive, StrictTable, Vector3


#: drive profile -> (its keys besides `profile`, the required ones)
DRIVE_KEYS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "constant": (("omega_s",), ("omega_s",)),
    "exponential": (("omega_s", "T", "t1"), ("omega_s", "T")),
    "spin_up": (("omega_s", "T"), ("omega_s", "T")),
    "slew": (("angle", "T"), ("angle", "T")),
    "table": (("file", "interpolation", "smoothing"), ("file",)),
}

#: torque law -> (its keys besides `law`, the required ones)
TORQUE_KEYS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "constant": (("value",), ("value",)),
    "table": (("file",), ("file",)),
    "pd": (("kp", "kd", "reference"), ("reference",)),
}



class Drive(KeyedChoice):
    """A drive profile theta(t): ``[hub.drive]`` or ``[hub.torque.reference]`` (:data:`DRIVE_KEYS`)."""

    _choice: ClassVar[str] = "profile"
    _keys: ClassVar[dict] = DRIVE_KEYS

    profile: Literal["exponential", "constant", "spin_up", "slew", "table"] = "exponential"
    omega_s: float = 0.0  # rad/s
    T: Positive = 1.0  # s
    t1: Positive = math.inf  # s (exponential: omega_s from t1 on; default never)
    angle: float = 0.0  # rad (slew)
    file: Annotated[str, Field(min_length=1)] | None = None  # CSV: time, omega (rad/s) or theta (rad)
    interpolation: Literal["spline", "linear"] = "spline"  # table: between the rows
    smoothing: Annotated[float, Field(gt=0.0)] | None = None  # table: Hz, zero-phase smoothing above it


class HubTorque(KeyedChoice):
    """A free hub's torque law ``[hub.torque]`` (:data:`TORQUE_KEYS`): constant ``value`` (N m);
    ``table`` ``file`` (CSV: time (s), torque (N m)); ``pd``: kp (N m/rad), kd (N m s/rad) and a
    ``reference`` drive profile, torque = kp (theta_ref - theta) + kd (omega_ref - omega)."""

    _choice: ClassVar[str] = "law"
    _keys: ClassVar[dict] = TORQUE_KEYS

    law: Literal["constant", "table", "pd"]
    value: float = 0.0
    file: Annotated[str, Field(min_length=1)] | None = None
    kp: NonNegative = 0.0
    kd: NonNegative = 0.0
    reference: Drive | None = None

    @model_validator(mode="after")
    def _gains(self):
        if self.law == "pd" and self.kp == 0.0 and self.kd == 0.0:
            raise ValueError("kp: kp and kd are both 0, so the law applies no torque (give kp > 0 or kd > 0)")
        return self


def _torque_tag(value: Any) -> str | None:
    if isinstance(value, HubTorque) or isinstance(value, dict):
        return "<table>"
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return "<number>"
    return None


TorqueSpec = Annotated[
    Union[Annotated[float, Tag("<number>")], Annotated[HubTorque, Tag("<table>")]],
    Discriminator(_torque_tag, custom_error_type="torque_type",
                  custom_error_message="must be a number (N m) or a table with law = 'constant' | 'table' | 'pd'"),
]


class Hub(StrictTable):
    """The hub. ``radius`` and ``twist`` are the defaults of every beam. ``inertia`` is required
    for a free hub (elsewhere it only enters a prescribed hub's drive torque; default 1 kg m^2);
    ``torque`` applies to a free hub only; ``drive`` to a prescribed one only."""

    motion: Literal["free", "prescribed", "fixed"] = "fixed"
    radius: NonNegative = 0.0  # m
    twist: float = 0.0  # deg
    inertia: Positive = 1.0  # kg m^2
    torque: TorqueSpec = 0.0  # N m, or a law
    drive: Drive | None = None
    orientation: Vector3 = [0.0, 0.0, 0.0]  # deg: rotation vector turning the base axes into the hub's at theta = 0
    position: Vector3 = [0.0, 0.0, 0.0]  # m, base axes: the hub origin O on its axis

    @model_validator(mode="before")
    @classmethod
    def _for_its_motion(cls, data: Any) -> Any:
        """A drive or a torque that the hub's motion does not take is the error to report, before
        whatever the drive's or the torque's own table lacks."""
        motion = data.get("motion", "fixed") if isinstance(data, dict) else None
        if motion not in ("free", "prescribed", "fixed"):
            return data  # not a table, or a motion of its own error
        if motion != "prescribed" and "drive" in data:
            raise ValueError(f"drive: only with hub.motion = 'prescribed' (motion is {motion!r})")
        if motion != "free" and "torque" in data:
            raise ValueError(f"torque: only for hub.motion = 'free' (motion is {motion!r}); remove it")
        return data

    @property
    def torque_law(self) -> HubTorque | None:
        """The free hub's torque law (a number becomes law = 'constant'); None for other motions."""
        if self.motion != "free":
            return None
        if isinstance(self.torque, HubTorque):
            return self.torque
        return HubTorque(law="constant", value=float(self.torque))

    @model_serializer(mode="wrap")
    def _dump(self, handler):
        out = handler(self)
        for key in ("inertia", "torque", "orientation", "position"):
            if key not in self.model_fields_set:
                out.pop(key, None)
        return out


