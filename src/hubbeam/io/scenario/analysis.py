"""The environment, drag, loads and analysis tables."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import (
    Field,
)

from hubbeam.io.scenario.common import Identifier, NonNegative, Positive, Vector3, StrictTable


class Environment(StrictTable):
    gravity: Vector3 = [0.0, -9.81, 0.0]


class Damping(StrictTable):
    linear: NonNegative = 0.0
    quadratic: NonNegative = 0.0


class Loads(StrictTable):
    tip_force: Vector3 = [0.0, 0.0, 0.0]
    tip_moment: Vector3 = [0.0, 0.0, 0.0]
    beam: Identifier | None = None  # default: the first beam


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


