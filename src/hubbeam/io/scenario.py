"""Scenario files (TOML) per ../shared/interface.md, validated with pydantic.

Every problem with a scenario becomes a :class:`ScenarioError` whose message is one
line naming the key (dotted path, e.g. ``beam.thickness`` or ``sensors[1].x``) and the
reason. Units are SI; angles in the file are in degrees.
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources
from pathlib import Path
from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator


class ScenarioError(ValueError):
    """Bad scenario input: the message names the key and says what is wrong."""


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


Positive = Annotated[float, Field(gt=0.0)]
NonNegative = Annotated[float, Field(ge=0.0)]
Vector3 = Annotated[list[float], Field(min_length=3, max_length=3)]


class Beam(_Strict):
    formulation: Literal["ancf", "ffr"] = "ancf"
    elements: Annotated[int, Field(gt=0, le=2000)]
    length: Positive
    width: Positive
    thickness: Positive
    density: Positive
    youngs_modulus: Positive
    poisson_ratio: Annotated[float, Field(gt=-1.0, lt=0.5)] | None = None
    shear_modulus: Positive | None = None
    torsion_constant: Positive | None = None
    geometric_stiffening: bool = False
    gauss_points: Annotated[int, Field(ge=2, le=10)] | None = None


class Drive(_Strict):
    profile: Literal["exponential", "constant", "spin_up"] = "exponential"
    omega_s: float
    T: Positive = 1.0
    t1: Positive = 1.0e300


class Hub(_Strict):
    motion: Literal["free", "prescribed", "fixed"] = "fixed"
    radius: NonNegative = 0.0
    twist: float = 0.0
    inertia: Positive = 1.0
    torque: float = 0.0
    drive: Drive | None = None


class Environment(_Strict):
    gravity: Vector3 = [0.0, -9.81, 0.0]


class Damping(_Strict):
    linear: NonNegative = 0.0
    quadratic: NonNegative = 0.0


class Loads(_Strict):
    tip_force: Vector3 = [0.0, 0.0, 0.0]
    tip_moment: Vector3 = [0.0, 0.0, 0.0]


class Analysis(_Strict):
    kind: Literal["dynamic", "static", "modes"] = "dynamic"
    t_end: Positive = 1.0
    dt: Positive = 1.0e-3
    spectral_radius: Annotated[float, Field(ge=0.0, le=1.0)] = 0.8
    output_dt: Positive | None = None
    load_steps: Annotated[int, Field(gt=0, le=100000)] = 20
    count: Annotated[int, Field(gt=0, le=500)] = 6
    newton: Literal["full", "step", "modified"] = "modified"
    tolerance: Annotated[float, Field(gt=0.0, lt=1e-3)] = 1e-9


SensorKind = Literal[
    "surface_strain", "hub_angle", "hub_angular_velocity", "hub_torque", "tip_deflection", "energy",
    "angular_momentum", "constraint_violation",
]


class Sensor(_Strict):
    name: Annotated[str, Field(min_length=1, pattern=r"^[A-Za-z_][A-Za-z0-9_]*$")]
    kind: SensorKind
    x: NonNegative | None = None
    surface: Literal["upper", "lower"] | None = None
    y: float | None = None
    z: float | None = None

    @model_validator(mode="after")
    def _station(self):
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


class Scenario(_Strict):
    name: Annotated[str, Field(min_length=1)] = "scenario"
    beam: Beam
    hub: Hub = Hub()
    environment: Environment = Environment()
    damping: Damping = Damping()
    loads: Loads = Loads()
    analysis: Analysis = Analysis()
    sensors: list[Sensor] = []

    # ----------------------------------------------------------- derived values
    @property
    def shear_modulus(self) -> float:
        b = self.beam
        if b.shear_modulus is not None:
            return b.shear_modulus
        nu = 0.33 if b.poisson_ratio is None else b.poisson_ratio
        return b.youngs_modulus / (2.0 * (1.0 + nu))

    @property
    def twist_rad(self) -> float:
        return math.radians(self.hub.twist)

    @property
    def output_dt(self) -> float:
        return self.analysis.output_dt if self.analysis.output_dt is not None else self.analysis.dt

    def to_dict(self) -> dict:
        return self.model_dump(exclude_none=True)


def _cross_checks(s: Scenario) -> None:
    """Checks that involve several keys; each raises ScenarioError naming one key."""
    b = s.beam
    if b.poisson_ratio is not None and b.shear_modulus is not None:
        raise ScenarioError("beam.shear_modulus: give poisson_ratio or shear_modulus, not both")
    if b.formulation == "ancf" and b.geometric_stiffening:
        raise ScenarioError("beam.geometric_stiffening: only applies to formulation = 'ffr'")
    if b.formulation == "ffr" and b.gauss_points is not None:
        raise ScenarioError("beam.gauss_points: only applies to formulation = 'ancf'")
    if s.hub.motion == "prescribed" and s.hub.drive is None:
        raise ScenarioError("hub.drive: required when hub.motion = 'prescribed'")
    if s.hub.motion != "prescribed" and s.hub.drive is not None:
        raise ScenarioError(f"hub.drive: only with hub.motion = 'prescribed' (motion is {s.hub.motion!r})")
    a = s.analysis
    if a.kind == "dynamic":
        if a.dt > a.t_end:
            raise ScenarioError(f"analysis.dt: larger than analysis.t_end ({a.dt} > {a.t_end})")
        if a.output_dt is not None and a.output_dt < a.dt:
            raise ScenarioError(f"analysis.output_dt: smaller than analysis.dt ({a.output_dt} < {a.dt})")
    names = set()
    for i, sen in enumerate(s.sensors):
        if sen.name in names:
            raise ScenarioError(f"sensors[{i}].name: duplicate sensor name {sen.name!r}")
        names.add(sen.name)
        if sen.x is not None and sen.x > b.length:
            raise ScenarioError(f"sensors[{i}].x: station {sen.x} m is beyond the beam length {b.length} m")
        if sen.y is not None and abs(sen.y) > b.width / 2 * (1 + 1e-12):
            raise ScenarioError(f"sensors[{i}].y: {sen.y} m is outside the section (|y| <= width/2 = {b.width / 2})")
        if sen.z is not None and abs(sen.z) > b.thickness / 2 * (1 + 1e-12):
            raise ScenarioError(
                f"sensors[{i}].z: {sen.z} m is outside the section (|z| <= thickness/2 = {b.thickness / 2})"
            )


def _format_loc(loc: tuple) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        elif part in ("function-after", "list[float]", "float", "int", "constrained-float", "constrained-int"):
            continue
        else:
            out += ("." if out else "") + str(part)
    return out


def _explain(err: dict) -> str:
    kind = err["type"]
    ctx = err.get("ctx", {})
    value = err.get("input")
    if kind == "extra_forbidden":
        return "unknown key"
    if kind == "missing":
        return "required key is missing"
    if kind in ("finite_number",):
        return f"must be a finite number (got {value})"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        op = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<", "less_than_equal": "<="}[kind]
        bound = next(iter(ctx.values()))
        return f"must be {op} {bound} (got {value})"
    if kind == "literal_error":
        return f"must be one of {ctx.get('expected')} (got {value!r})"
    if kind in ("too_short", "too_long"):
        return f"must have {ctx.get('min_length', ctx.get('max_length'))} entries"
    if kind in ("float_type", "int_type", "string_type", "bool_type", "list_type", "model_type", "dict_type"):
        want = {"float_type": "a number", "int_type": "an integer", "string_type": "a string", "bool_type": "true or false",
                "list_type": "a list", "model_type": "a table", "dict_type": "a table"}[kind]
        return f"must be {want} (got {type(value).__name__} {value!r})"
    msg = err["msg"]
    return msg.removeprefix("Value error, ")


def validate(data: dict) -> Scenario:
    """A validated Scenario from a plain dict (parsed TOML), or ScenarioError."""
    if not isinstance(data, dict):
        raise ScenarioError("scenario: must be a TOML table")
    try:
        scenario = Scenario.model_validate(data)
    except ValidationError as exc:
        err = exc.errors()[0]
        key = _format_loc(err["loc"]) or "scenario"
        reason = _explain(err)
        # validators report "key: reason" for a key of their own model
        if err["type"] == "value_error" and ": " in reason and not reason.startswith(" "):
            sub, reason = reason.split(": ", 1)
            key = f"{key}.{sub}" if key != "scenario" else sub
        raise ScenarioError(f"{key}: {reason}") from None
    _cross_checks(scenario)
    return scenario


def parse_override(text: str) -> tuple[list[str], object]:
    """'beam.elements=8' -> (['beam', 'elements'], 8); the value uses TOML syntax, a bare word is a string."""
    if "=" not in text:
        raise ScenarioError(f"--set {text}: expected KEY=VALUE")
    key, raw = text.split("=", 1)
    key = key.strip()
    if not key or any(not part for part in key.split(".")):
        raise ScenarioError(f"--set {text}: malformed key {key!r}")
    try:
        value = tomllib.loads(f"v = {raw.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw.strip()
    return key.split("."), value


def apply_overrides(data: dict, overrides: list[str]) -> dict:
    """Apply --set overrides to parsed TOML data (a new dict is returned)."""
    import copy

    data = copy.deepcopy(data)
    for text in overrides or []:
        path, value = parse_override(text)
        node = data
        for part in path[:-1]:
            nxt = node.setdefault(part, {})
            if not isinstance(nxt, dict):
                raise ScenarioError(f"--set {text}: {part} is not a table")
            node = nxt
        node[path[-1]] = value
    return data


#: the bundled scenarios (package data in hubbeam/examples)
EXAMPLES = ("cantilever", "exp1", "exp1_h4", "exp1_h1", "exp2")


def example_text(name: str) -> str:
    """The TOML text of a bundled scenario."""
    if name not in EXAMPLES:
        raise ScenarioError(f"example: unknown example {name!r} (available: {', '.join(EXAMPLES)})")
    return resources.files("hubbeam").joinpath("examples", f"{name}.toml").read_text(encoding="utf-8")


def load_example(name: str, overrides: list[str] | None = None) -> Scenario:
    """A bundled scenario, overridden and validated."""
    return validate(apply_overrides(tomllib.loads(example_text(name)), overrides or []))


def load_scenario(source: str | Path, overrides: list[str] | None = None) -> Scenario:
    """Read, override and validate a scenario file."""
    path = Path(source)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ScenarioError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise ScenarioError(f"{path}: is a directory, not a scenario file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ScenarioError(f"{path}: cannot read ({exc.__class__.__name__})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(f"{path}: malformed TOML ({exc})") from None
    return validate(apply_overrides(data, overrides or []))
