"""The ``[beams.joint]`` table: a beam's root clamped (default) or on a revolute joint of one to
three axes, with springs, dampers, a motor law (``[beams.joint.torque]``) and a latch
(docs/joints.md); and the resolved joint (SI units, radians) that model code reads."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

from pydantic import model_serializer, model_validator

from hubbeam.io.scenario.common import StrictTable
from hubbeam.io.scenario.hub import HubTorque

#: the named axes of a joint (docs/joints.md: flap = +c, lag = +b, pitch = -a)
AXIS_NAMES = ("flap", "lag", "pitch")
#: most axes of one joint
MAX_JOINT_AXES = 3
#: the keys that take one value per axis
PER_AXIS = ("stiffness", "damping", "neutral", "initial_angle", "initial_rate")


def _one_axis(value: Any, where: str) -> str | tuple[float, float, float]:
    """A named axis or a direction [a, b, c]; ValueError naming ``where`` otherwise."""
    if isinstance(value, str):
        if value not in AXIS_NAMES:
            raise ValueError(f"{where}: must be one of {AXIS_NAMES} or [a, b, c] in the joint frame (got {value!r})")
        return value
    if isinstance(value, (list, tuple)) and len(value) == 3 and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
        vector = tuple(float(v) for v in value)
        if not all(math.isfinite(v) for v in vector):
            raise ValueError(f"{where}: must be finite numbers (got {list(value)})")
        if not math.hypot(*vector) > 0.0:
            raise ValueError(f"{where}: a zero vector has no direction")
        return vector
    raise ValueError(f"{where}: must be 'flap', 'lag', 'pitch' or a vector [a, b, c] (got {value!r})")


def parse_axes(value: Any) -> tuple:
    """The axes of ``[beams.joint] axis``: one (a name or a vector) or a list of up to three."""
    if isinstance(value, str) or (isinstance(value, (list, tuple)) and len(value) == 3
                                  and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
        return (_one_axis(value, "axis"),)
    if not isinstance(value, (list, tuple)) or not value:
        raise ValueError(f"axis: must be 'flap', 'lag', 'pitch', a vector [a, b, c] or a list of up to "
                         f"{MAX_JOINT_AXES} of these (got {value!r})")
    if len(value) > MAX_JOINT_AXES:
        raise ValueError(f"axis: at most {MAX_JOINT_AXES} axes (got {len(value)})")
    axes = tuple(_one_axis(v, f"axis[{i}]") for i, v in enumerate(value))
    names = [a for a in axes if isinstance(a, str)]
    if len(set(names)) != len(names):
        raise ValueError(f"axis: the same named axis twice ({list(value)})")
    return axes


class JointTorque(HubTorque):
    """``[beams.joint.torque]``: a motor in a single-axis joint, the torque laws of ``[hub.torque]``
    on the joint angle; a ``pd`` law tracks psi_ref = initial_angle + theta_p(t) of its reference."""


class Joint(StrictTable):
    """``[beams.joint]``: ``kind`` "clamp" (default) or "revolute" about ``axis``; per axis
    ``stiffness`` (N m/rad), ``damping`` (N m s/rad), ``neutral`` and ``initial_angle`` (deg),
    ``initial_rate`` (rad/s), a number or a list of one per axis; ``latch`` (deg) and a motor
    ``torque`` for a single-axis joint."""

    kind: Literal["clamp", "revolute"] = "clamp"
    axis: Any = None
    stiffness: float | list[float] = 0.0
    damping: float | list[float] = 0.0
    neutral: float | list[float] = 0.0
    initial_angle: float | list[float] = 0.0
    initial_rate: float | list[float] = 0.0
    latch: float | None = None
    torque: JointTorque | None = None

    @model_validator(mode="after")
    def _keys(self):
        given = self.model_fields_set - {"kind"}
        if self.kind == "clamp":
            if given:
                raise ValueError(f"{sorted(given)[0]}: not a key of a clamped joint (kind = 'clamp'); "
                                 "give kind = 'revolute'")
            return self
        if self.axis is None:
            raise ValueError("axis: required for a revolute joint ('flap', 'lag', 'pitch', [a, b, c] or a list)")
        axes = parse_axes(self.axis)
        n = len(axes)
        for key in PER_AXIS:
            value = getattr(self, key)
            values = value if isinstance(value, list) else [value] * n
            if len(values) != n:
                raise ValueError(f"{key}: one value per axis ({n} axes, got {len(values)} values)")
            for v in values:
                if not math.isfinite(v):
                    raise ValueError(f"{key}: must be finite (got {v})")
                if key in ("stiffness", "damping") and v < 0.0:
                    raise ValueError(f"{key}: must be >= 0 (got {v})")
        if n > 1 and (self.latch is not None or self.torque is not None):
            key = "latch" if self.latch is not None else "torque"
            raise ValueError(f"{key}: single-axis joints only (this joint has {n} axes)")
        if self.latch is not None:
            if not math.isfinite(self.latch):
                raise ValueError(f"latch: must be finite (got {self.latch})")
            if self.latch == self.per_axis("initial_angle")[0]:
                raise ValueError(f"latch: {self.latch} deg is the initial angle: the joint would start latched")
        return self

    @property
    def axes(self) -> tuple:
        """The axes (names or vectors), one per joint angle; () for a clamp."""
        return () if self.kind == "clamp" else parse_axes(self.axis)

    @property
    def axis_names(self) -> tuple[str, ...]:
        """One name per axis: the named axis, or "axis1", "axis2", ... for a vector."""
        return tuple(a if isinstance(a, str) else f"axis{i + 1}" for i, a in enumerate(self.axes))

    def per_axis(self, key: str) -> list[float]:
        """The values of a per-axis key, one per axis."""
        value = getattr(self, key)
        return [float(v) for v in value] if isinstance(value, list) else [float(value)] * len(self.axes)

    @model_serializer(mode="wrap")
    def _dump(self, handler):
        return {k: v for k, v in handler(self).items() if k == "kind" or k in self.model_fields_set}


@dataclass(frozen=True)
class ResolvedJoint:
    """A revolute joint in SI units: ``axes`` (names or unit-free vectors in the joint frame),
    ``names`` (one per axis), per axis ``stiffness`` (N m/rad), ``damping`` (N m s/rad),
    ``neutral``, ``initial_angle`` (rad), ``initial_rate`` (rad/s); ``latch`` (rad or None) and
    ``torque`` (the motor's table, or None)."""

    axes: tuple
    names: tuple
    stiffness: tuple
    damping: tuple
    neutral: tuple
    initial_angle: tuple
    initial_rate: tuple
    latch: float | None
    torque: Any


def resolved_joint(joint: Joint | None) -> ResolvedJoint | None:
    """The revolute joint of a ``[beams.joint]`` table in SI units (None for a clamp)."""
    if joint is None or joint.kind == "clamp":
        return None
    rad = lambda values: tuple(math.radians(v) for v in values)  # noqa: E731
    return ResolvedJoint(joint.axes, joint.axis_names, tuple(joint.per_axis("stiffness")),
                         tuple(joint.per_axis("damping")), rad(joint.per_axis("neutral")),
                         rad(joint.per_axis("initial_angle")), tuple(joint.per_axis("initial_rate")),
                         None if joint.latch is None else math.radians(joint.latch), joint.torque)
