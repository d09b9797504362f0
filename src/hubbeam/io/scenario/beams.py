"""The beam tables: ``[beam]`` / ``[[beams]]``, their sections, damping and tip body, and the
resolved beam (SI units, radians) that model code reads."""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

from pydantic import (
    Field,
    model_validator,
)
from dataclasses import dataclass

from hubbeam.io.scenario.common import (MAX_PRECONE_DEG, Identifier, NonNegative, NonNegativeVector3, Positive,
                                        Vector3, StrictTable)
from hubbeam.io.scenario.joints import Joint, ResolvedJoint


class TipBody(StrictTable):
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


class SectionStation(StrictTable):
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


#: the largest Kelvin-Voigt constant c (s): every mode down to 1 mHz is then overdamped (zeta = c omega / 2 > 3);
#: a larger c describes no structure, and drowns the beam's mass in round-off against c K / dt in the Newton matrix
MAX_STRUCTURAL_DAMPING = 1.0e3


class BeamDamping(StrictTable):
    """``[beams.damping]``: ``stiffness_proportional`` c (s), Kelvin-Voigt structural damping,
    at most :data:`MAX_STRUCTURAL_DAMPING`."""

    stiffness_proportional: Annotated[float, Field(ge=0.0, le=MAX_STRUCTURAL_DAMPING)] = 0.0


#: the most beams a hub carries (copies counted)
MAX_BEAMS = 100
#: the name of a table's copies when it has none: "blade1", "blade2", ...
COPY_NAME = "blade"


def beam_names_of(tables) -> list[tuple[int, int | None, str]]:
    """(table index, copy index or None, name) of every beam the tables describe, in order:
    a table with ``copies = N`` gives N beams named NAME1 .. NAMEN (NAME its ``name``, default
    :data:`COPY_NAME`), another one beam named by its ``name``, default "beam<k>" with k its
    position among all the beams (1-based). ``tables`` are :class:`Beam` models or their dicts
    (parsed TOML, before validation: what is not a count of copies counts as one beam)."""
    out = []
    for i, table in enumerate(tables):
        get = table.get if isinstance(table, dict) else (lambda key, t=table: getattr(t, key, None))
        name, copies = get("name"), get("copies")
        name = name if isinstance(name, str) else None
        if isinstance(copies, int) and not isinstance(copies, bool) and copies >= 2:
            out += [(i, k, f"{name or COPY_NAME}{k + 1}") for k in range(min(copies, MAX_BEAMS + 1))]
        else:
            out.append((i, None, name or f"beam{len(out) + 1}"))
    return out


def copy_azimuth(azimuth: float, copy: int | None, copies: int | None) -> float:
    """The azimuth (deg) of copy ``copy`` of a table at ``azimuth`` with ``copies`` copies:
    azimuth + copy 360 / copies (the table's own azimuth for a table without copies)."""
    return azimuth if copy is None else azimuth + copy * 360.0 / copies


class Beam(StrictTable):
    """One beam: a ``[beam]`` table or one of the ``[[beams]]`` tables; with ``copies = N``, N
    identical beams at azimuth + k 360/N deg (k = 0 .. N-1) named NAME1 .. NAMEN."""

    name: Identifier | None = None  # default "beam1", "beam2", ... by position; with copies the copies' stem
    copies: Annotated[int, Field(ge=2, le=MAX_BEAMS)] | None = None
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
    # a chain: the beam whose tip carries this root (default: the hub), and the root's joint
    parent: Identifier | None = None
    joint: Joint | None = None

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
        if self.parent is not None:
            for key, unset in (("azimuth", 0.0), ("radius", None)):
                if getattr(self, key) != unset:
                    raise ValueError(f"{key}: does not apply to a beam on a parent (its root sits at the parent's "
                                     f"tip, {self.parent!r}); remove it")
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
    parent: int | None = None  # the index of the beam whose tip carries this root (None: the hub)
    joint: ResolvedJoint | None = None  # the root's revolute joint (None: clamped)


