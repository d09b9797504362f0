"""The environment, drag, loads and analysis tables."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import (
    Field,
    ValidationInfo,
    field_validator,
    model_validator,
)

from hubbeam.io.scenario.common import (Identifier, NonNegative, Positive, Vector3, StrictTable, _absolute,
                                        _check_file)


class Environment(StrictTable):
    gravity: Vector3 = [0.0, -9.81, 0.0]


class Damping(StrictTable):
    linear: NonNegative = 0.0
    quadratic: NonNegative = 0.0


class SpanLoadTable(StrictTable):
    """One ``[[loads.span]]``: a force (N/m) and moment (N m/m) per unit length on a beam, uniform
    (``force``, ``moment``) or from a CSV ``file`` (docs/loads.md), in ``axes`` "global" or
    "section" (the root section frame)."""

    name: Identifier | None = None  # default: span1, span2, ... by its place
    beam: Identifier | None = None  # default: the first beam
    axes: Literal["global", "section"] = "global"
    force: Vector3 | None = None
    moment: Vector3 | None = None
    file: Annotated[str, Field(min_length=1)] | None = None

    @field_validator("file")
    @classmethod
    def _absolute_file(cls, value, info: ValidationInfo):
        return _absolute(value, info)

    @model_validator(mode="after")
    def _one_source(self):
        if self.file is not None and (self.force is not None or self.moment is not None):
            given = "force" if self.force is not None else "moment"
            raise ValueError(f"{given}: give either a file or force and moment, not both")
        if self.file is None and self.force is None and self.moment is None:
            raise ValueError("force: give force (N/m) and/or moment (N m/m), or a file")
        if self.file is not None:
            _check_file(self.file)
        return self


class Loads(StrictTable):
    tip_force: Vector3 = [0.0, 0.0, 0.0]
    tip_moment: Vector3 = [0.0, 0.0, 0.0]
    #: CSV tables of the tip force (time, fx, fy, fz; N) and moment (time, mx, my, mz; N m), global
    tip_force_file: Annotated[str, Field(min_length=1)] | None = None
    tip_moment_file: Annotated[str, Field(min_length=1)] | None = None
    beam: Identifier | None = None  # default: the first beam
    span: list[SpanLoadTable] = []

    @field_validator("tip_force_file", "tip_moment_file")
    @classmethod
    def _absolute_files(cls, value, info: ValidationInfo):
        return _absolute(value, info)

    @model_validator(mode="after")
    def _one_tip_source(self):
        for what in ("tip_force", "tip_moment"):
            path = getattr(self, f"{what}_file")
            if path is None:
                continue
            if any(getattr(self, what)):
                raise ValueError(f"{what}_file: give either {what} or {what}_file, not both")
            try:
                _check_file(path)
            except ValueError as exc:
                raise ValueError(f"{what}_{exc}") from None
        names = self.span_names
        for i, name in enumerate(names):
            if name in names[:i]:
                raise ValueError(f"span[{i}].name: {name!r} names two span loads")
            if name == "tip":
                raise ValueError(f"span[{i}].name: 'tip' names the tip loads (linearize's load:tip); choose another")
        return self

    @property
    def span_names(self) -> list[str]:
        """Each span load's name (its own, or span1, span2, ... by its place)."""
        return [s.name if s.name is not None else f"span{i + 1}" for i, s in enumerate(self.span)]


class Analysis(StrictTable):
    kind: Literal["dynamic", "static", "modes"] = "dynamic"
    t_end: Positive = 1.0
    dt: Positive = 1.0e-3
    spectral_radius: Annotated[float, Field(ge=0.0, le=1.0)] = 0.8
    output_dt: Positive | None = None
    load_steps: Annotated[int, Field(gt=0, le=100000)] = 20
    count: Annotated[int, Field(gt=0, le=500)] = 6
    newton: Literal["full", "step", "modified"] = "modified"
    #: Newton's tolerance on the increments relative to the beam length: from 1e-12 (4500 times the double
    #: precision; below it the increments are round-off and Newton cannot stop) to below 1e-3
    tolerance: Annotated[float, Field(ge=1e-12, lt=1e-3)] = 1e-9
    #: where a dynamic run starts: "rest" (straight, undeformed, at rest: the paper's release) or
    #: "equilibrium" (at rest in the static equilibrium under gravity and loads, hub at theta = 0).
    #: A constant drive starts in the steadily rotating state either way.
    start: Literal["rest", "equilibrium"] = "rest"


