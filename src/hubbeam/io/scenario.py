"""Scenario files (TOML), validated with pydantic; docs/scenario.md is the reference.

Every problem with a scenario becomes a :class:`ScenarioError` whose message is one
line naming the key (dotted path, e.g. ``beam.thickness``, ``beams[1].tip_body.mass`` or
``sensors[1].x``) and the reason. Units are SI; angles in the file are in degrees (the
slew ``angle`` and table angles, which are hub angles in rad, excepted).

A hub carries one beam (a ``[beam]`` table) or several (``[[beams]]`` tables). Code that
builds a model reads :meth:`Scenario.resolved_beams`: every beam with its defaults filled in,
SI units and angles in radians. ``scenario.beam`` is kept for single-beam scenarios.

Span-wise sections (``[[beams.sections]]``: :class:`SectionStation`) and per-beam structural
damping (``[beams.damping]``) are fields of :class:`Beam`, resolved into a
:class:`~hubbeam.elements.section.SpanSections` and a float of :class:`ResolvedBeam`.
"""

from __future__ import annotations

import copy
import difflib
import math
import re
import tomllib
import unicodedata
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal, Union, get_args

from pydantic import (
    BaseModel,
    ConfigDict,
    Discriminator,
    Field,
    Tag,
    ValidationError,
    ValidationInfo,
    field_validator,
    model_serializer,
    model_validator,
)

from hubbeam.errors import ScenarioError  # noqa: F401  (part of this module's interface)
from hubbeam.io.examples import EXAMPLES, example_text  # noqa: F401  (part of this module's interface)


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


Positive = Annotated[float, Field(gt=0.0)]
NonNegative = Annotated[float, Field(ge=0.0)]
Vector3 = Annotated[list[float], Field(min_length=3, max_length=3)]
NonNegativeVector3 = Annotated[list[NonNegative], Field(min_length=3, max_length=3)]
Identifier = Annotated[str, Field(min_length=1, max_length=64, pattern=r"^[A-Za-z_][A-Za-z0-9_]*$")]

#: precone limit (deg): the FFR reference frame's Cardan angles become singular at 90 deg
MAX_PRECONE_DEG = 80.0
#: relative tolerance of "a whole multiple of analysis.dt"
STEP_TOLERANCE = 1e-9


def _given(model: BaseModel, own: tuple[str, ...], required: tuple[str, ...], what: str) -> None:
    """Only ``own`` keys (besides the selector) may be given and every ``required`` one must be."""
    given = model.model_fields_set
    for key in type(model).model_fields:
        if key in given and key not in own and key not in ("profile", "law"):
            raise ValueError(f"{key}: not a key of {what} (its keys: {', '.join(own)})")
    for key in required:
        if key not in given:
            raise ValueError(f"{key}: required for {what}")


def _absolute(value: str | None, info: ValidationInfo) -> str | None:
    """A table's path made absolute: relative to ``context['base_dir']`` (the scenario file's
    folder), else to the current directory."""
    if value is None:
        return None
    path = Path(value).expanduser()
    if not path.is_absolute():
        base = (info.context or {}).get("base_dir")
        path = Path(base if base is not None else Path.cwd()) / path
    return str(path.absolute())


def _check_file(path: str) -> None:
    p = Path(path)
    if not p.exists():
        raise ValueError(f"file: no such file {path}")
    if not p.is_file():
        raise ValueError(f"file: not a file {path}")


# ------------------------------------------------------------------------- beams
class TipBody(_Strict):
    """A rigid body at a beam's tip: mass (kg), principal inertia [J_tau, J_m, J_n] (kg m^2)
    about the tip section's axes through its centre of mass, and the offset [c_tau, c_m, c_n]
    (m) of that centre from the tip centroid, in the tip section frame."""

    mass: NonNegative
    inertia: NonNegativeVector3 = [0.0, 0.0, 0.0]
    offset: Vector3 = [0.0, 0.0, 0.0]

    @model_validator(mode="after")
    def _triangle(self):
        j = self.inertia
        for a in range(3):
            b, c = (a + 1) % 3, (a + 2) % 3
            if j[a] > (j[b] + j[c]) * (1 + 1e-9) + 1e-300:
                raise ValueError(
                    f"inertia: the principal moments {list(j)} kg m^2 are not those of a rigid body "
                    f"(each must be <= the sum of the other two; J[{a}] = {j[a]} > {j[b]} + {j[c]})")
        return self


#: the keys of a station in the constants form (rho_I = [I_tau, I_m, I_n])
STATION_CONSTANTS = ("EA", "GJ", "EI_y", "EI_z", "rho_A", "rho_I")


class SectionStation(_Strict):
    """One ``[[beams.sections]]`` station: ``x`` (m from the root), ``pretwist`` (deg, about the
    beam axis in the sense of the beam's twist, relative to the root), and either a rectangle
    (``width``, ``thickness``, m) or the constants EA (N), GJ, EI_y, EI_z (N m^2), rho_A (kg/m)
    and rho_I = [I_tau, I_m, I_n] (kg m), with optional width and thickness (default the beam's)."""

    x: NonNegative
    pretwist: float = 0.0
    width: Positive | None = None
    thickness: Positive | None = None
    EA: Positive | None = None
    GJ: Positive | None = None
    EI_y: Positive | None = None
    EI_z: Positive | None = None
    rho_A: Positive | None = None
    rho_I: Annotated[list[Positive], Field(min_length=3, max_length=3)] | None = None

    @property
    def form(self) -> str:
        """'constants' when any constant is given, else 'rectangle'."""
        return "constants" if any(getattr(self, k) is not None for k in STATION_CONSTANTS) else "rectangle"

    @model_validator(mode="after")
    def _one_form(self):
        if self.form == "constants":
            for key in STATION_CONSTANTS:
                if getattr(self, key) is None:
                    raise ValueError(f"{key}: required for a station given by its constants "
                                     f"({', '.join(STATION_CONSTANTS)})")
        else:
            for key in ("width", "thickness"):
                if getattr(self, key) is None:
                    raise ValueError(f"{key}: required for a rectangle station (width and thickness), or give "
                                     f"the constants {', '.join(STATION_CONSTANTS)}")
        return self


class BeamDamping(_Strict):
    """``[beams.damping]``: ``stiffness_proportional`` c (s), Kelvin-Voigt structural damping."""

    stiffness_proportional: NonNegative = 0.0


class Beam(_Strict):
    """One beam: a ``[beam]`` table or one of the ``[[beams]]`` tables."""

    name: Identifier | None = None  # default "beam1", "beam2", ... by position
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
    # --- modal reduction (FFR only): keep the `modes` lowest clamped-free modes
    modes: Annotated[int, Field(ge=1)] | None = None
    # where the beam sits on the hub
    azimuth: float = 0.0  # deg
    radius: NonNegative | None = None  # m, default hub.radius
    twist: float | None = None  # deg, default hub.twist
    precone: float = 0.0  # deg
    tip_body: TipBody | None = None
    sections: Annotated[list[SectionStation], Field(min_length=2, max_length=10000)] | None = None
    damping: BeamDamping | None = None

    @model_validator(mode="after")
    def _keys(self):
        if self.poisson_ratio is not None and self.shear_modulus is not None:
            raise ValueError("shear_modulus: give poisson_ratio or shear_modulus, not both")
        if self.formulation == "ancf" and self.geometric_stiffening:
            raise ValueError("geometric_stiffening: only applies to formulation = 'ffr'")
        if self.formulation == "ffr" and self.gauss_points is not None:
            raise ValueError("gauss_points: only applies to formulation = 'ancf'")
        # --- modal reduction (FFR only)
        if self.modes is not None and self.formulation != "ffr":
            raise ValueError("modes: only applies to formulation = 'ffr' (modal reduction of the FFR beam)")
        if self.modes is not None and self.modes > 6 * self.elements:
            raise ValueError(f"modes: at most the nodal model's 6 x elements = {6 * self.elements} coordinates "
                             f"(got {self.modes})")
        # --- end modal reduction
        if self.sections is not None:
            self._check_sections()
        if not abs(self.precone) < MAX_PRECONE_DEG:
            raise ValueError(
                f"precone: must be between -{MAX_PRECONE_DEG:g} and {MAX_PRECONE_DEG:g} deg (got {self.precone}): "
                "the FFR reference frame's Cardan angles become singular as the beam axis nears the hub axis (90 deg)")
        return self


    def _check_sections(self) -> None:
        st = self.sections
        for i, station in enumerate(st):
            if i == 0 and station.x != 0.0:
                raise ValueError(f"sections[0].x: the first station must be at the root, x = 0 (got {station.x})")
            if station.x > self.length * (1 + 1e-9):
                raise ValueError(f"sections[{i}].x: station {station.x} m is beyond the beam's length {self.length} m")
            if i > 0 and not station.x > st[i - 1].x:
                raise ValueError(f"sections[{i}].x: stations must be in ascending order of x ({station.x} m after "
                                 f"{st[i - 1].x} m)")
            if station.form != st[0].form:
                raise ValueError(f"sections[{i}]: a {station.form} station among {st[0].form} ones (one form per "
                                 f"beam: width and thickness, or the constants {', '.join(STATION_CONSTANTS)})")
        if not math.isclose(st[-1].x, self.length, rel_tol=1e-9):
            raise ValueError(f"sections[{len(st) - 1}].x: the last station must be at the beam's length "
                             f"{self.length} m (got {st[-1].x})")
        if st[0].pretwist != 0.0:
            raise ValueError(f"sections[0].pretwist: must be 0 at the root (pretwist is relative to the root; the "
                             f"root's angle is the beam's twist) (got {st[0].pretwist})")
        if st[0].form == "rectangle" and self.torsion_constant is not None:
            raise ValueError("torsion_constant: not used with rectangle [[sections]] stations (each takes "
                             "Saint-Venant's constant of its rectangle); give the constants (GJ) instead")

    def size_at(self, x: float) -> tuple[float, float]:
        """(width, thickness) (m) at station x: the sections' linear interpolation, else the beam's."""
        if self.sections is None:
            return self.width, self.thickness
        import numpy as np

        xs = [s.x for s in self.sections]
        return (float(np.interp(x, xs, [s.width or self.width for s in self.sections])),
                float(np.interp(x, xs, [s.thickness or self.thickness for s in self.sections])))


def span_sections(b: Beam, material):
    """The :class:`~hubbeam.elements.section.SpanSections` of a beam's stations (None without
    them); ``material``: the beam's :class:`~hubbeam.elements.section.Section` (SI units)."""
    import numpy as np

    from hubbeam.elements.section import SectionForm, SpanSections

    if b.sections is None:
        return None
    x = np.array([s.x for s in b.sections])
    x[-1] = b.length  # validated to 1e-9: the beam's length exactly
    twist = np.radians([s.pretwist for s in b.sections])
    if b.sections[0].form == "rectangle":
        values = [[s.width, s.thickness] for s in b.sections]
        return SpanSections(x, SectionForm.RECTANGLE, np.array(values), twist, material=material)
    values = [[s.EA, s.GJ, s.EI_y, s.EI_z, s.rho_A, *s.rho_I, s.width or b.width, s.thickness or b.thickness]
              for s in b.sections]
    return SpanSections(x, SectionForm.CONSTANTS, np.array(values), twist)


@dataclass(frozen=True)
class ResolvedTipBody:
    """A tip body in SI units: mass (kg), principal inertia (J_tau, J_m, J_n) (kg m^2) about the
    tip section axes through its centre of mass, offset (c_tau, c_m, c_n) (m) from the tip centroid."""

    mass: float
    inertia: tuple[float, float, float]
    offset: tuple[float, float, float]


@dataclass(frozen=True)
class ResolvedBeam:
    """Beam ``index`` of a scenario with every default filled in: SI units, angles in radians.

    Placement: its own hub frame is A_h(theta + azimuth); the root is at radius * i_k; the axis
    is i_k turned by precone towards +j0; the section is turned about the axis by -twist
    (docs/scenario.md). tip_force (N) and tip_moment (N m) are the ``[loads]`` on this beam, in
    global directions (zeros when [loads] applies to another beam)."""

    name: str
    index: int
    formulation: str  # "ancf" | "ffr"
    elements: int
    length: float  # m
    width: float  # m, local y
    thickness: float  # m, local z
    density: float  # kg/m^3
    youngs_modulus: float  # Pa
    shear_modulus: float  # Pa
    torsion_constant: float  # m^4
    gauss_points: int | None  # ANCF only; None: the element's default
    geometric_stiffening: bool  # FFR only
    azimuth: float  # rad
    radius: float  # m
    twist: float  # rad
    precone: float  # rad
    tip_body: ResolvedTipBody | None
    tip_force: tuple[float, float, float]  # N, global
    tip_moment: tuple[float, float, float]  # N m, global
    modes: int | None = None  # FFR only: kept clamped-free modes; None: nodal
    sections: Any = None  # hubbeam.elements.section.SpanSections: span-wise properties; None: uniform
    structural_damping: float = 0.0  # s, c of the Kelvin-Voigt resultants c D e_dot


# ------------------------------------------------------------------------- hub
#: drive profile -> (its keys besides `profile`, the required ones)
DRIVE_KEYS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "constant": (("omega_s",), ("omega_s",)),
    "exponential": (("omega_s", "T", "t1"), ("omega_s", "T")),
    "spin_up": (("omega_s", "T"), ("omega_s", "T")),
    "slew": (("angle", "T"), ("angle", "T")),
    "table": (("file",), ("file",)),
}

#: torque law -> (its keys besides `law`, the required ones)
TORQUE_KEYS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "constant": (("value",), ("value",)),
    "table": (("file",), ("file",)),
    "pd": (("kp", "kd", "reference"), ("reference",)),
}


class _KeyedChoice(_Strict):
    """A table whose choice key (``profile``, ``law``) decides which of its other keys it takes
    (``_keys``: choice -> (its keys, the required ones)); the others keep their neutral defaults
    and are left out of :meth:`Scenario.to_dict`. ``file`` is stored as an absolute path and
    must exist."""

    _choice: ClassVar[str]
    _keys: ClassVar[dict[str, tuple[tuple[str, ...], tuple[str, ...]]]]

    @field_validator("file", check_fields=False)
    @classmethod
    def _absolute_file(cls, value, info: ValidationInfo):
        return _absolute(value, info)

    @model_validator(mode="after")
    def _own_keys(self):
        choice = getattr(self, self._choice)
        own, required = self._keys[choice]
        _given(self, own, required, f"{self._choice} {choice!r}")
        if self.file is not None:
            _check_file(self.file)
        return self

    @model_serializer(mode="wrap")
    def _dump(self, handler):
        return {k: v for k, v in handler(self).items() if k == self._choice or k in self.model_fields_set}


class Drive(_KeyedChoice):
    """A drive profile theta(t): ``[hub.drive]`` or ``[hub.torque.reference]`` (:data:`DRIVE_KEYS`)."""

    _choice: ClassVar[str] = "profile"
    _keys: ClassVar[dict] = DRIVE_KEYS

    profile: Literal["exponential", "constant", "spin_up", "slew", "table"] = "exponential"
    omega_s: float = 0.0  # rad/s
    T: Positive = 1.0  # s
    t1: Positive = math.inf  # s (exponential: omega_s from t1 on; default never)
    angle: float = 0.0  # rad (slew)
    file: Annotated[str, Field(min_length=1)] | None = None  # CSV: time, omega (rad/s) or theta (rad)


class HubTorque(_KeyedChoice):
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


class Hub(_Strict):
    """The hub. ``radius`` and ``twist`` are the defaults of every beam. ``inertia`` is required
    for a free hub (elsewhere it only enters a prescribed hub's drive torque; default 1 kg m^2);
    ``torque`` applies to a free hub only; ``drive`` to a prescribed one only."""

    motion: Literal["free", "prescribed", "fixed"] = "fixed"
    radius: NonNegative = 0.0  # m
    twist: float = 0.0  # deg
    inertia: Positive = 1.0  # kg m^2
    torque: TorqueSpec = 0.0  # N m, or a law
    drive: Drive | None = None

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
        for key in ("inertia", "torque"):
            if key not in self.model_fields_set:
                out.pop(key, None)
        return out


class Environment(_Strict):
    gravity: Vector3 = [0.0, -9.81, 0.0]


class Damping(_Strict):
    linear: NonNegative = 0.0
    quadratic: NonNegative = 0.0


class Loads(_Strict):
    tip_force: Vector3 = [0.0, 0.0, 0.0]
    tip_moment: Vector3 = [0.0, 0.0, 0.0]
    beam: Identifier | None = None  # default: the first beam


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
    #: where a dynamic run starts: "rest" (straight, undeformed, at rest: the paper's release) or
    #: "equilibrium" (at rest in the static equilibrium under gravity and loads, hub at theta = 0).
    #: A constant drive starts in the steadily rotating state either way.
    start: Literal["rest", "equilibrium"] = "rest"


# ------------------------------------------------------------------------- sensors
SensorKind = Literal[
    "surface_strain", "hub_angle", "hub_angular_velocity", "hub_torque", "tip_deflection", "energy",
    "angular_momentum", "constraint_violation", "applied_torque",
]

#: sensors that belong to one beam (``beam``: a beam name, default the first beam)
BEAM_SENSORS = frozenset({"surface_strain", "tip_deflection"})
#: sensors with an optional ``beam`` (without it, the whole system)
OPTIONAL_BEAM_SENSORS = frozenset({"energy"})
#: multi-part sensors -> their parts; the columns are NAME_PART
SENSOR_PARTS: dict[str, tuple[str, ...]] = {
    "tip_deflection": ("radial", "vertical", "tangential"),
    "energy": ("kinetic", "strain", "gravity", "total", "dissipated", "drive"),
}
#: the parts of an energy sensor that names a beam (the work terms belong to the whole system)
BEAM_ENERGY_PARTS = ("kinetic", "strain", "gravity", "total")


class Sensor(_Strict):
    name: Identifier
    kind: SensorKind
    beam: Identifier | None = None
    x: NonNegative | None = None
    surface: Literal["upper", "lower"] | None = None
    y: float | None = None
    z: float | None = None

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
        return SENSOR_PARTS.get(self.kind)

    @property
    def columns(self) -> tuple[str, ...]:
        """The result columns of this sensor: NAME, or NAME_PART for a multi-part sensor."""
        parts = self.parts
        return (self.name,) if parts is None else tuple(f"{self.name}_{p}" for p in parts)


# ------------------------------------------------------------------------- the scenario
class Scenario(_Strict):
    name: Annotated[str, Field(min_length=1, max_length=200)] = "scenario"
    single_beam: Beam | None = Field(default=None, alias="beam")  # a [beam] table
    beams: Annotated[list[Beam], Field(min_length=1, max_length=100)] | None = None  # [[beams]] tables
    hub: Hub = Hub()
    environment: Environment = Environment()
    damping: Damping = Damping()
    loads: Loads = Loads()
    analysis: Analysis = Analysis()
    sensors: list[Sensor] = []

    # ----------------------------------------------------------- beams
    @property
    def beam_tables(self) -> list[Beam]:
        """The beams as written ([beam] or [[beams]]), in order."""
        if self.single_beam is not None:
            return [self.single_beam]
        return list(self.beams or [])

    @property
    def beam_names(self) -> tuple[str, ...]:
        return tuple(b.name or f"beam{i + 1}" for i, b in enumerate(self.beam_tables))

    @property
    def beam(self) -> Beam:
        """The one beam of a single-beam scenario (its table as written; the placement keys
        may be None: :meth:`resolved_beams` has them resolved)."""
        tables = self.beam_tables
        if len(tables) != 1:
            raise ScenarioError(
                f"beams: this scenario has {len(tables)} beams ({', '.join(self.beam_names)}) where one is expected")
        return tables[0]

    def beam_index(self, name: str | None = None) -> int:
        """0-based index of the beam called ``name``; None means the first beam (0)."""
        if name is None:
            return 0
        names = self.beam_names
        if name not in names:
            raise ScenarioError(f"beam: no beam named {name!r} (beams: {', '.join(names)})")
        return names.index(name)

    def resolved_beams(self) -> list[ResolvedBeam]:
        """Every beam with its defaults filled in (SI units, radians)."""
        loaded = self.beam_index(self.loads.beam)
        out = []
        for i, (b, name) in enumerate(zip(self.beam_tables, self.beam_names)):
            if b.shear_modulus is not None:
                g = b.shear_modulus
            else:
                nu = 0.33 if b.poisson_ratio is None else b.poisson_ratio
                g = b.youngs_modulus / (2.0 * (1.0 + nu))
            from hubbeam.elements.section import Section, saint_venant_torsion_constant

            if b.torsion_constant is not None:
                jt = b.torsion_constant
            else:
                jt = saint_venant_torsion_constant(b.width, b.thickness)
            tb = b.tip_body
            tip = None if tb is None else ResolvedTipBody(
                float(tb.mass), tuple(float(v) for v in tb.inertia), tuple(float(v) for v in tb.offset))
            zero = (0.0, 0.0, 0.0)
            out.append(ResolvedBeam(
                name=name, index=i, formulation=b.formulation, elements=b.elements, length=b.length, width=b.width,
                thickness=b.thickness, density=b.density, youngs_modulus=b.youngs_modulus, shear_modulus=g,
                torsion_constant=jt, gauss_points=b.gauss_points, geometric_stiffening=bool(b.geometric_stiffening),
                azimuth=math.radians(b.azimuth),
                radius=float(self.hub.radius if b.radius is None else b.radius),
                twist=math.radians(self.hub.twist if b.twist is None else b.twist),
                precone=math.radians(b.precone), tip_body=tip,
                tip_force=tuple(float(v) for v in self.loads.tip_force) if i == loaded else zero,
                tip_moment=tuple(float(v) for v in self.loads.tip_moment) if i == loaded else zero,
                modes=b.modes,
                sections=span_sections(b, Section(b.width, b.thickness, b.density, b.youngs_modulus, g, jt)),
                structural_damping=float(b.damping.stiffness_proportional) if b.damping is not None else 0.0,
            ))
        return out

    # ----------------------------------------------------------- derived values (single beam)
    @property
    def shear_modulus(self) -> float:
        """Shear modulus (Pa) of the single beam."""
        self.beam  # noqa: B018 - one beam expected
        return self.resolved_beams()[0].shear_modulus

    @property
    def twist_rad(self) -> float:
        """Twist (rad) of the single beam."""
        self.beam  # noqa: B018 - one beam expected
        return self.resolved_beams()[0].twist

    @property
    def output_dt(self) -> float:
        return self.analysis.output_dt if self.analysis.output_dt is not None else self.analysis.dt

    @property
    def columns(self) -> list[str]:
        """The result columns of the sensors, in order (without ``time``)."""
        return [c for s in self.sensors for c in s.columns]

    def to_dict(self) -> dict:
        """The scenario as plain data ([beam] or [[beams]] as written; absolute table paths);
        ``validate(scenario.to_dict())`` gives the scenario back."""
        return self.model_dump(by_alias=True, exclude_none=True)


def _nearest_multiples(value: float, step: float) -> str:
    n = value / step
    lo, hi = max(math.floor(n), 1), max(math.ceil(n), 1)
    vals = sorted({float(f"{k * step:.12g}") for k in (lo, hi)})
    return " or ".join(f"{v:.12g}" for v in vals)


def _is_multiple(value: float, step: float) -> bool:
    n = round(value / step)
    return n >= 1 and abs(n * step - value) <= STEP_TOLERANCE * value


def _cross_checks(s: Scenario) -> None:
    """Checks that involve several keys; each raises ScenarioError naming one key."""
    if any(unicodedata.category(c) == "Cc" for c in s.name):
        raise ScenarioError("name: must not contain control characters (NUL, tab, line breaks, ...)")
    if s.single_beam is not None and s.beams is not None:
        raise ScenarioError("beams: give one [beam] table or [[beams]] tables, not both")
    if s.single_beam is None and s.beams is None:
        raise ScenarioError("beam: required key is missing (a [beam] table, or [[beams]] tables for several beams)")
    tables, names = s.beam_tables, s.beam_names
    where = "beam" if s.single_beam is not None else "beams"
    seen: dict[str, int] = {}
    for i, name in enumerate(names):
        if name in seen:
            how = "" if tables[i].name is not None else " by default"
            raise ScenarioError(f"beams[{i}].name: duplicate beam name {name!r}{how} (also beams[{seen[name]}])")
        seen[name] = i
    listed = ", ".join(names)

    hub = s.hub
    if hub.motion == "prescribed" and hub.drive is None:
        raise ScenarioError("hub.drive: required when hub.motion = 'prescribed'")
    if hub.motion == "free" and "inertia" not in hub.model_fields_set:
        raise ScenarioError("hub.inertia: required for motion = 'free' (kg m^2 about j0)")

    if s.loads.beam is not None and s.loads.beam not in names:
        raise ScenarioError(f"loads.beam: no beam named {s.loads.beam!r} (beams: {listed})")

    a = s.analysis
    if a.kind == "dynamic":
        if a.dt > a.t_end:
            raise ScenarioError(f"analysis.dt: larger than analysis.t_end ({a.dt} > {a.t_end})")
        if a.output_dt is not None and a.output_dt < a.dt:
            raise ScenarioError(f"analysis.output_dt: smaller than analysis.dt ({a.output_dt} < {a.dt})")
        for key in ("output_dt", "t_end"):
            value = getattr(a, key)
            if value is not None and not math.isfinite(value / a.dt):  # too many steps to count in a float
                raise ScenarioError(f"analysis.{key}: {value:.12g} s is more steps of analysis.dt = {a.dt:.12g} s "
                                    "than a number can count")
        if a.output_dt is not None and not _is_multiple(a.output_dt, a.dt):
            raise ScenarioError(f"analysis.output_dt: {a.output_dt:.12g} s is not a whole multiple of analysis.dt = "
                                f"{a.dt:.12g} s (nearest valid: {_nearest_multiples(a.output_dt, a.dt)})")
        if not _is_multiple(a.t_end, a.dt):
            raise ScenarioError(f"analysis.t_end: {a.t_end:.12g} s is not a whole number of steps of analysis.dt = "
                                f"{a.dt:.12g} s (nearest valid: {_nearest_multiples(a.t_end, a.dt)})")

    columns: dict[str, int] = {}
    for i, sen in enumerate(s.sensors):
        if sen.kind == "applied_torque" and hub.motion != "free":
            raise ScenarioError(f"sensors[{i}].kind: applied_torque needs hub.motion = 'free' "
                                f"(motion is {hub.motion!r}; a prescribed hub's torque is hub_torque)")
        for col in sen.columns:
            if col == "time":
                raise ScenarioError(f"sensors[{i}].name: {sen.name!r} makes the column 'time', the time coordinate")
            if col in columns:
                j = columns[col]
                if s.sensors[j].name == sen.name:
                    raise ScenarioError(f"sensors[{i}].name: duplicate sensor name {sen.name!r} (also sensors[{j}])")
                raise ScenarioError(f"sensors[{i}].name: {sen.name!r} makes the column {col!r}, which sensors[{j}] "
                                    f"({s.sensors[j].name!r}, {s.sensors[j].kind}) makes too")
            columns[col] = i
        if sen.beam is not None and sen.beam not in names:
            raise ScenarioError(f"sensors[{i}].beam: no beam named {sen.beam!r} (beams: {listed})")
        k = s.beam_index(sen.beam)
        b = tables[k]
        of = f"{where}[{k}]" if where == "beams" else "beam"
        label = f"beam {names[k]!r}" if len(tables) > 1 else "the beam"
        if sen.x is not None and sen.x > b.length:
            raise ScenarioError(f"sensors[{i}].x: station {sen.x} m is beyond the length of {label} "
                                f"({of}.length = {b.length} m)")
        width, thickness = b.size_at(sen.x) if sen.x is not None else (b.width, b.thickness)
        if sen.y is not None and abs(sen.y) > width / 2 * (1 + 1e-12):
            raise ScenarioError(f"sensors[{i}].y: {sen.y} m is outside the section of {label} "
                                f"(|y| <= width/2 = {width / 2})")
        if sen.z is not None and abs(sen.z) > thickness / 2 * (1 + 1e-12):
            raise ScenarioError(
                f"sensors[{i}].z: {sen.z} m is outside the section of {label} (|z| <= thickness/2 = {thickness / 2})")


_TYPE_PARTS = {"function-after", "function-before", "function-wrap", "list[float]", "float", "int", "str", "bool",
               "constrained-float", "constrained-int", "constrained-str", "list[constrained-float]"}


def _format_loc(loc: tuple) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        elif part in _TYPE_PARTS or str(part).startswith(("<", "function-")):
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
        n = ctx.get("min_length") if kind == "too_short" else ctx.get("max_length")
        bound = "at least" if kind == "too_short" else "at most"
        if ctx.get("min_length") == 3 or ctx.get("max_length") == 3:
            bound = "exactly"  # a 3-vector
        return f"must have {bound} {n} entr{'y' if n == 1 else 'ies'} (got {ctx.get('actual_length')})"
    if kind == "string_too_short":
        return "must not be empty"
    if kind == "string_too_long":
        return f"must be at most {ctx.get('max_length')} characters long"
    if kind == "string_pattern_mismatch":
        return f"must be an identifier: letters, digits and _, not starting with a digit (got {value!r})"
    if kind in ("float_type", "int_type", "string_type", "bool_type", "list_type", "model_type", "dict_type",
                "model_attributes_type"):
        want = {"float_type": "a number", "int_type": "an integer", "string_type": "a string",
                "bool_type": "true or false", "list_type": "a list", "model_type": "a table", "dict_type": "a table",
                "model_attributes_type": "a table"}[kind]
        return f"must be {want} (got {type(value).__name__} {value!r})"
    msg = err["msg"]
    return msg.removeprefix("Value error, ")


def _first_error(errors: list) -> dict:
    """The error to report: an unknown key before the others (a misspelt required key is both
    unknown and missing, and the unknown one is what the user wrote), else the first."""
    return next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])


def _models_in(annotation) -> list:
    """The pydantic models an annotation can hold (through Optional, Union, list, Annotated)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    return [m for arg in get_args(annotation) for m in _models_in(arg)]


def _keys_of_table(loc: tuple) -> list[str]:
    """The keys the scenario's table at ``loc`` (a pydantic error location) can have."""
    def keys(model) -> dict:  # as written in a file: by alias where a field has one
        return {f.alias or name: f for name, f in model.model_fields.items()}

    models = [Scenario]
    for part in loc:
        if isinstance(part, int):
            continue
        fields = [keys(m)[part] for m in models if part in keys(m)]
        if fields:
            models = [m for f in fields for m in _models_in(f.annotation)]
    return sorted({key for m in models for key in keys(m)})


def _did_you_mean(unknown: dict, errors: list) -> str:
    """' (did you mean NAME?)' for an unknown key close to a key of its table: one missing from
    it first (a misspelt required key), else any of its keys."""
    table, name = unknown["loc"][:-1], str(unknown["loc"][-1])
    missing = [str(e["loc"][-1]) for e in errors if e["type"] == "missing" and e["loc"][:-1] == table]
    close = (difflib.get_close_matches(name, missing, n=1, cutoff=0.6)
             or difflib.get_close_matches(name, _keys_of_table(table), n=1, cutoff=0.75))
    return f" (did you mean {close[0]}?)" if close else ""


def validate(data: dict, base_dir: str | Path | None = None) -> Scenario:
    """A validated Scenario from a plain dict (parsed TOML), or ScenarioError. Relative table
    paths (``file`` keys) are taken relative to ``base_dir`` (default: the current directory)."""
    if not isinstance(data, dict):
        raise ScenarioError("scenario: must be a TOML table")
    try:
        scenario = Scenario.model_validate(data, context={"base_dir": base_dir})
    except ValidationError as exc:
        err = _first_error(exc.errors())
        key = _format_loc(err["loc"]) or "scenario"
        reason = _explain(err)
        if err["type"] == "extra_forbidden":
            reason += _did_you_mean(err, exc.errors())
        # validators report "key: reason" for a key of their own model
        if err["type"] == "value_error" and ": " in reason and not reason.startswith(" "):
            sub, reason = reason.split(": ", 1)
            key = f"{key}.{sub}" if key != "scenario" else sub
        raise ScenarioError(f"{key}: {reason}") from None
    _cross_checks(scenario)
    _check_tables(scenario)
    return scenario


def table_files(s: Scenario) -> list[tuple[str, str, str]]:
    """(kind "drive" or "torque", key, absolute path) of every CSV table the scenario reads:
    its inputs, which no output of a command may overwrite."""
    hub = s.hub
    tables = []
    if hub.drive is not None and hub.drive.profile == "table":
        tables.append(("drive", "hub.drive.file", hub.drive.file))
    torque = hub.torque if isinstance(hub.torque, HubTorque) else None
    if torque is not None and torque.law == "table":
        tables.append(("torque", "hub.torque.file", torque.file))
    if torque is not None and torque.reference is not None and torque.reference.profile == "table":
        tables.append(("drive", "hub.torque.reference.file", torque.reference.file))
    return tables


def _check_tables(s: Scenario) -> None:
    """The numbers of the CSV tables a scenario names (columns, rows, times)."""
    tables = table_files(s)
    if not tables:
        return
    from hubbeam.io.tables import read_drive_table, read_torque_table

    for what, key, path in tables:
        (read_drive_table if what == "drive" else read_torque_table)(path, key)


# ------------------------------------------------------------------------- --set
_SEGMENT = re.compile(r"([^.\[\]]+)((?:\[(?:\d+|\*)\])*)")
_INDEX = re.compile(r"\[(\d+|\*)\]")
#: keys whose value selects which other keys of the same table apply
_SWITCHES = {"formulation", "motion", "profile", "law"}


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


def _tokens(key: str, text: str) -> list:
    """'beams[1].tip_body.mass' -> ['beams', 1, 'tip_body', 'mass'] ('*' for [*])."""
    out: list = []
    for seg in key.split("."):
        m = _SEGMENT.fullmatch(seg)
        if not m:
            raise ScenarioError(f"--set {text}: malformed key {key!r}")
        out.append(m.group(1))
        out += [int(i) if i != "*" else "*" for i in _INDEX.findall(m.group(2))]
    return out


def _beam_name(table: Any, i: int) -> str:
    if isinstance(table, dict) and isinstance(table.get("name"), str):
        return table["name"]
    return f"beam{i + 1}"


def _addresses(data: dict, tokens: list, text: str) -> list[tuple]:
    """The places a --set key addresses, with a beam named by index or name turned into its
    table: ('beam', ...) for a single [beam], ('beams', i, ...) for [[beams]]."""
    head, rest = tokens[0], tokens[1:]
    single = data.get("beam")
    many = data.get("beams")
    if head == "beam":
        if isinstance(many, list) and single is None:
            if len(many) != 1:
                raise ScenarioError(f"--set {text}: the scenario has {len(many)} beams; address one as "
                                    f"beams[i].KEY (0-based) or beams.NAME.KEY")
            return [("beams", 0, *rest)]
        return [("beam", *rest)]
    if head == "beams" and rest:
        sel, rest = rest[0], rest[1:]
        if isinstance(single, dict) and many is None:
            tables, to = [single], (lambda i: ("beam",))
        elif isinstance(many, list):
            tables, to = many, (lambda i: ("beams", i))
        else:
            raise ScenarioError(f"--set {text}: the scenario has no beams to address")
        names = [_beam_name(t, i) for i, t in enumerate(tables)]
        if sel == "*":
            picked = list(range(len(tables)))
        elif isinstance(sel, int):
            if sel >= len(tables):
                raise ScenarioError(f"--set {text}: beam index {sel} is out of range (the scenario has "
                                    f"{len(tables)} beam{'s' if len(tables) > 1 else ''}: 0..{len(tables) - 1})")
            picked = [sel]
        else:
            if sel not in names:
                raise ScenarioError(f"--set {text}: no beam named {sel!r} (beams: {', '.join(names)})")
            picked = [names.index(sel)]
        return [address for i in picked for address in _expand(data, (*to(i), *rest), text)]
    return _expand(data, tuple(tokens), text)


def _expand(data: dict, address: tuple, text: str) -> list[tuple]:
    """``address`` with every ``[*]`` replaced by each index of that list."""
    if "*" not in address:
        return [address]
    k = address.index("*")
    node = _get(data, address[:k])
    if not isinstance(node, list):
        raise ScenarioError(f"--set {text}: {_show(address[:k])} is not a list")
    return [a for i in range(len(node)) for a in _expand(data, (*address[:k], i, *address[k + 1:]), text)]


def _canonical(address: tuple) -> tuple:
    return ("beams", 0, *address[1:]) if address[:1] == ("beam",) else address


def _set(data: dict, address: tuple, value, text: str) -> None:
    node: Any = data
    for k, part in enumerate(address[:-1]):
        shown = _show(address[:k + 1])
        if isinstance(part, int) or part == "*":
            if not isinstance(node, list):
                raise ScenarioError(f"--set {text}: {_show(address[:k])} is not a list")
            if part == "*" or part >= len(node):
                raise ScenarioError(f"--set {text}: index {part} of {_show(address[:k])} is out of range "
                                    f"({len(node)} entries)")
            node = node[part]
        else:
            if not isinstance(node, dict):
                raise ScenarioError(f"--set {text}: {_show(address[:k])} is not a table")
            node = node.setdefault(part, {})
            if not isinstance(node, (dict, list)):
                raise ScenarioError(f"--set {text}: {shown} is not a table (it is {node!r}; set the whole "
                                    f"{shown} instead, e.g. {shown}={{...}})")
        if not isinstance(node, (dict, list)):
            raise ScenarioError(f"--set {text}: {shown} is not a table")
    last = address[-1]
    if isinstance(last, int):
        if not isinstance(node, list) or last >= len(node):
            raise ScenarioError(f"--set {text}: index {last} of {_show(address[:-1])} is out of range")
        node[last] = value
    else:
        if not isinstance(node, dict):
            raise ScenarioError(f"--set {text}: {_show(address[:-1])} is not a table")
        node[last] = value


def _show(address: tuple) -> str:
    out = ""
    for part in address:
        out += f"[{part}]" if isinstance(part, int) else ("." if out else "") + str(part)
    return out


def _get(data: Any, address: tuple):
    node = data
    for part in address:
        if isinstance(part, int):
            if not isinstance(node, list) or part >= len(node):
                return None
            node = node[part]
        else:
            if not isinstance(node, dict) or part not in node:
                return None
            node = node[part]
    return node


def _prune(data: dict, switch: tuple, set_paths: set) -> list[str]:
    """After --set switched ``switch`` (a formulation, motion, profile or law), drop the keys of
    the old choice that the new one does not take (unless they are set by --set as well).
    Returns the dropped keys' names."""
    table = _get(data, switch[:-1])
    value = table.get(switch[-1]) if isinstance(table, dict) else None
    if not isinstance(table, dict) or not isinstance(value, str):
        return []
    key = switch[-1]
    dropped = []

    def drop(*names):
        for name in names:
            if _canonical(switch[:-1] + (name,)) not in set_paths and name in table:
                table.pop(name)
                dropped.append(name)

    if key == "formulation":
        drop(*{"ancf": ("geometric_stiffening", "modes"), "ffr": ("gauss_points",)}.get(value, ()))
    elif key == "motion" and switch[:-1] == ("hub",):
        if value != "free":
            drop("torque")
        if value != "prescribed":
            drop("drive")
    elif key == "profile" and value in DRIVE_KEYS:
        drop(*(k for k in ("omega_s", "T", "t1", "angle", "file") if k not in DRIVE_KEYS[value][0]))
    elif key == "law" and value in TORQUE_KEYS:
        drop(*(k for k in ("value", "file", "kp", "kd", "reference") if k not in TORQUE_KEYS[value][0]))
    return dropped


def apply_overrides(data: dict, overrides: list[str], dropped: list[str] | None = None) -> dict:
    """Apply --set overrides to parsed TOML data (a new dict is returned).

    Keys are dotted paths; a list entry is addressed by a 0-based index (``sensors[1].x``);
    a beam by index or name (``beams[1].twist``, ``beams.blade2.twist``, and ``beams[*].KEY``
    for every beam); ``beam.KEY`` addresses the one beam of a single-beam scenario. A key may
    be set once. A relative ``file`` value is taken relative to the current directory.
    Switching a formulation, hub.motion, a drive profile or a torque law drops the keys of
    the old choice that the new one does not take; each drop is added to ``dropped`` (when
    given) as a line naming the --set and the keys.
    """
    data = copy.deepcopy(data)
    set_paths: dict[tuple, str] = {}
    switches = []
    for text in overrides or []:
        _, value = parse_override(text)  # checks the KEY=VALUE form
        key = text.split("=", 1)[0].strip()
        for address in _addresses(data, _tokens(key, text), text):
            canon = _canonical(address)
            for other, other_text in set_paths.items():
                other_key = other_text.split("=", 1)[0].strip()
                also = "" if other_key == key else f" (also as {other_key})"
                if other == canon:
                    raise ScenarioError(f"--set {key}: given more than once{also}")
                n = min(len(other), len(canon))
                if other[:n] == canon[:n]:
                    raise ScenarioError(f"--set {key}: overlaps --set {other_key} (set a key or its table once)")
            if address[-1] == "file" and isinstance(value, str) and value:
                value = str(Path(value).expanduser().absolute())  # a path typed here: from the current directory
            _set(data, address, value, text)
            set_paths[canon] = text
            if isinstance(address[-1], str) and address[-1] in _SWITCHES:
                switches.append(address)
    for address in switches:
        names = _prune(data, address, set(set_paths))
        if names and dropped is not None:
            text = set_paths[_canonical(address)].strip()
            table = _format_loc(address[:-1])  # the table switched (beams[*] names each beam)
            choice = f"{address[-1]} {_get(data, address)!r}"
            dropped.append(f"--set {text}: {', '.join(f'{table}.{n}' for n in names)} dropped ({choice} does not "
                           f"take {'it' if len(names) == 1 else 'them'})")
    return data


def value_at(data: dict, key: str):
    """The value a --set key addresses in parsed scenario data (None if not set there)."""
    addresses = _addresses(data, _tokens(key, key), key)
    if len(addresses) != 1:
        raise ScenarioError(f"{key}: addresses {len(addresses)} values; name one")
    return _get(data, addresses[0])


def load_example(name: str, overrides: list[str] | None = None, dropped: list[str] | None = None) -> Scenario:
    """A bundled scenario, overridden and validated (``dropped``: see :func:`apply_overrides`)."""
    return validate(apply_overrides(tomllib.loads(example_text(name)), overrides or [], dropped))


def load_scenario(source: str | Path, overrides: list[str] | None = None,
                  dropped: list[str] | None = None) -> Scenario:
    """Read, override and validate a scenario file (relative table paths: relative to the file;
    ``dropped``: see :func:`apply_overrides`)."""
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
    return validate(apply_overrides(data, overrides or [], dropped), base_dir=path.absolute().parent)
