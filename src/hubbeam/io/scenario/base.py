"""The ``[base]`` table: the hub's support, fixed in space, a free rigid body or moved by a table
(docs/base.md)."""

from __future__ import annotations

import math
from typing import Annotated, Literal

import numpy as np
from pydantic import Field, ValidationInfo, field_validator, model_serializer, model_validator

from hubbeam.io.scenario.common import NonNegative, Positive, StrictTable, Vector3, _absolute, _check_file

#: a rotation vector's size limit (rad): beyond it, another vector gives the same rotation
ROTATION_LIMIT = 1e6


class GivenKeys(StrictTable):
    """A table written back (:meth:`Scenario.to_dict`) with the keys it was given only, so that
    a default never reads as a key the motion refuses."""

    @model_serializer(mode="wrap")
    def _dump(self, handler):
        return {k: v for k, v in handler(self).items() if k in self.model_fields_set or k == "motion"}


class BaseInitial(GivenKeys):
    """``[base.initial]``: the base's state at t = 0 (global frame unless said)."""

    position: Vector3 = [0.0, 0.0, 0.0]  # m, O_b
    rotation: Vector3 = [0.0, 0.0, 0.0]  # rad, rotation vector of the base axes
    velocity: Vector3 = [0.0, 0.0, 0.0]  # m/s, of O_b (free)
    angular_velocity: Vector3 = [0.0, 0.0, 0.0]  # rad/s, base axes (free)


class BaseSlew(StrictTable):
    """``[base.torque.slew]``: the reference turns by ``angle`` (rad) in ``T`` (s) about ``axis``
    (base axes at t = 0), along the slew profile of ``[hub.drive]``."""

    axis: Vector3
    angle: float
    T: Positive

    @model_validator(mode="after")
    def _axis(self):
        if not math.hypot(*self.axis) > 0.0:
            raise ValueError("axis: a zero vector has no direction (give the slew's axis)")
        return self


class BaseTorque(StrictTable):
    """``[base.torque]``: a free base's attitude law (base axes), torque = -kp phi - kd (w - w_ref)
    component-wise; the reference a fixed ``target`` (rotation vector, rad) or a ``slew``."""

    law: Literal["pd"]
    kp: Annotated[list[NonNegative], Field(min_length=3, max_length=3)]
    kd: Annotated[list[NonNegative], Field(min_length=3, max_length=3)]
    target: Vector3 | None = None
    slew: BaseSlew | None = None

    @model_validator(mode="after")
    def _reference(self):
        if self.target is not None and self.slew is not None:
            raise ValueError("slew: give a fixed target or a slew, not both")
        if not any(self.kp) and not any(self.kd):
            raise ValueError("kp: kp and kd are all 0, so the law applies no torque")
        return self


def _inertia_matrix(value) -> np.ndarray:
    J = np.asarray(value, dtype=float)
    return np.diag(J) if J.shape == (3,) else J


class Base(GivenKeys):
    """``[base]``: ``motion`` fixed (default), free (a rigid body: ``mass``, ``inertia``,
    ``centre_of_mass``) or table (``file``: CSV with time, x, y, z, rx, ry, rz)."""

    motion: Literal["fixed", "free", "table"] = "fixed"
    mass: Positive | None = None  # kg
    inertia: list[float] | list[list[float]] | None = None  # kg m^2: 3 principal values, or a 3 x 3 matrix
    centre_of_mass: Vector3 = [0.0, 0.0, 0.0]  # m, base axes
    file: Annotated[str, Field(min_length=1)] | None = None
    initial: BaseInitial = BaseInitial()
    torque: BaseTorque | None = None

    @field_validator("file")
    @classmethod
    def _absolute_file(cls, value, info: ValidationInfo):
        return _absolute(value, info)

    @field_validator("inertia")
    @classmethod
    def _inertia_shape(cls, value):
        if value is None:
            return value
        J = np.asarray(value, dtype=float) if all(isinstance(v, (int, float)) for v in np.ravel(
            np.asarray(value, dtype=object))) else None
        if J is None or J.shape not in ((3,), (3, 3)):
            raise ValueError("three principal moments [Jx, Jy, Jz] or a symmetric 3 x 3 matrix (kg m^2)")
        if not np.all(np.isfinite(J)):
            raise ValueError("must be finite numbers")
        from hubbeam.system.base import check_inertia

        try:
            check_inertia(J, "inertia")
        except ValueError as exc:
            raise ValueError(str(exc).removeprefix("inertia: ")) from None
        return value

    @model_validator(mode="after")
    def _for_its_motion(self):
        given = self.model_fields_set
        if self.motion == "free":
            for key in ("mass", "inertia"):
                if getattr(self, key) is None:
                    raise ValueError(f"{key}: required for base.motion = 'free'")
            if "file" in given:
                raise ValueError("file: only for base.motion = 'table'")
        else:
            for key in ("mass", "inertia", "centre_of_mass", "torque"):
                if key in given:
                    raise ValueError(f"{key}: only for base.motion = 'free' (motion is {self.motion!r})")
        if self.motion == "table":
            if self.file is None:
                raise ValueError("file: required for base.motion = 'table' (CSV: time, x, y, z, rx, ry, rz)")
            _check_file(self.file)
            moved = self.initial.model_fields_set
            if moved:
                raise ValueError(f"initial.{sorted(moved)[0]}: a table base starts where its table does")
        elif "file" in given:
            raise ValueError(f"file: only for base.motion = 'table' (motion is {self.motion!r})")
        if self.motion == "fixed":
            for key in ("velocity", "angular_velocity"):
                if key in self.initial.model_fields_set:
                    raise ValueError(f"initial.{key}: a fixed base does not move (give base.motion = 'free')")
        for key in ("rotation",):
            if math.hypot(*getattr(self.initial, key)) > ROTATION_LIMIT:
                raise ValueError(f"initial.{key}: larger than {ROTATION_LIMIT:g} rad")
        return self

    @property
    def inertia_matrix(self) -> np.ndarray | None:
        return None if self.inertia is None else _inertia_matrix(self.inertia)
