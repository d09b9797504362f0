"""Cross-section properties: the homogeneous rectangle (docs/scenario.md: width b along y, thickness
h along z) and the span-wise table of stations (:class:`SpanSections`) that tapered and pretwisted
beams are described by."""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np


def saint_venant_torsion_constant(width: float, thickness: float) -> float:
    """J_t = (a c^3 / 3)(1 - 0.63 c / a), a = max(b, h), c = min(b, h) (m^4)."""
    a, c = max(width, thickness), min(width, thickness)
    return a * c**3 / 3.0 * (1.0 - 0.63 * c / a)


@dataclass(frozen=True)
class Section:
    """Homogeneous rectangular section of a beam.

    width b (m, local y), thickness h (m, local z), density rho (kg/m^3), Young's modulus
    E and shear modulus G (Pa), torsion constant J_t (m^4).
    """

    width: float
    thickness: float
    density: float
    youngs_modulus: float
    shear_modulus: float
    torsion_constant: float

    @property
    def area(self) -> float:
        return self.width * self.thickness

    @property
    def i_y(self) -> float:
        """int z^2 dA = b h^3 / 12: the weak axis, bending deflection along n (m^4)."""
        return self.width * self.thickness**3 / 12.0

    @property
    def i_z(self) -> float:
        """int y^2 dA = h b^3 / 12: the strong axis, bending deflection along m (m^4)."""
        return self.thickness * self.width**3 / 12.0

    @property
    def stiffness(self) -> tuple[float, float, float, float]:
        """(EA, GJ_t, EI_y, EI_z) in the order of the strain measures (eps0, kappa1, kappa2, kappa3)."""
        E = self.youngs_modulus
        return (E * self.area, self.shear_modulus * self.torsion_constant, E * self.i_y, E * self.i_z)

    @property
    def mass_per_length(self) -> float:
        return self.density * self.area


class SectionForm(enum.Enum):
    """How the stations of a :class:`SpanSections` table are given."""

    RECTANGLE = "rectangle"  # width and thickness; the constants follow from the material
    CONSTANTS = "constants"  # EA, GJ, EI_y, EI_z, rho_A, rho_I directly


#: the columns of :meth:`SpanSections.at`, in order (SI units: N, N m^2, N m^2, N m^2, kg/m,
#: kg m, kg m, kg m, m, m, rad)
COLUMNS = ("EA", "GJ", "EI_y", "EI_z", "rho_A", "I_tau", "I_m", "I_n", "width", "thickness", "pretwist")
COLUMN = {name: k for k, name in enumerate(COLUMNS)}


def rectangle_constants(section: Section) -> np.ndarray:
    """The :data:`COLUMNS` of a homogeneous rectangle, pretwist 0: EA, GJ_t, EI_y, EI_z (Section.stiffness),
    rho A, rotary inertias per length rho (I_y + I_z), rho I_y, rho I_z (kg m), width, thickness."""
    rho = section.density
    return np.array([*section.stiffness, section.mass_per_length, rho * (section.i_y + section.i_z),
                     rho * section.i_y, rho * section.i_z, section.width, section.thickness, 0.0])


@dataclass(frozen=True)
class SpanSections:
    """Section properties along the undeformed span of a beam: stations x_0 = 0 < ... < x_n = length (m),
    linear interpolation between them.

    ``form`` RECTANGLE: ``values`` hold (width, thickness) per station; width and thickness interpolate
    linearly and the constants follow from them with the ``material`` (a :class:`Section` whose density,
    Young's and shear moduli are used; the torsion constant is Saint-Venant's formula of the
    interpolated rectangle).
    ``form`` CONSTANTS: ``values`` hold the first 10 :data:`COLUMNS` (EA ... I_n, width, thickness)
    per station; every one interpolates linearly. ``pretwist`` (rad, per station, about the beam axis,
    in the sense of the mount's twist) interpolates linearly in both forms.
    """

    x: np.ndarray
    form: SectionForm
    values: np.ndarray
    pretwist: np.ndarray
    material: Section | None = None

    def __post_init__(self) -> None:
        x = np.asarray(self.x, dtype=float)
        if x.ndim != 1 or x.size < 2 or x[0] != 0.0 or np.any(np.diff(x) <= 0.0):
            raise ValueError("sections: stations x must start at 0 and strictly increase (at least 2)")
        width = 2 if self.form is SectionForm.RECTANGLE else 10
        values = np.asarray(self.values, dtype=float).reshape(x.size, width)
        if self.form is SectionForm.RECTANGLE and self.material is None:
            raise ValueError("sections: rectangle stations need the beam's material")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "pretwist", np.asarray(self.pretwist, dtype=float).reshape(x.size))

    def __eq__(self, other) -> bool:
        """The same stations, form, values, pretwist and material (arrays compared by value)."""
        if not isinstance(other, SpanSections):
            return NotImplemented
        return (self.form is other.form and self.material == other.material and self.x.shape == other.x.shape
                and all(np.array_equal(getattr(self, k), getattr(other, k)) for k in ("x", "values", "pretwist")))

    __hash__ = None  # mutable arrays inside

    @classmethod
    def uniform(cls, section: Section, length: float) -> "SpanSections":
        """The prismatic beam of ``section`` over ``length`` (m), as two equal constant stations."""
        row = rectangle_constants(section)[:10]
        return cls(np.array([0.0, float(length)]), SectionForm.CONSTANTS, np.vstack([row, row]), np.zeros(2))

    @property
    def length(self) -> float:
        return float(self.x[-1])

    @property
    def is_uniform(self) -> bool:
        """Whether every station has the same properties and no pretwist."""
        return bool(np.all(self.values == self.values[0]) and not np.any(self.pretwist))

    def at(self, x) -> np.ndarray:
        """The :data:`COLUMNS` at stations ``x`` (m from the root; scalar or array): shape (..., 11)."""
        xs = np.clip(np.asarray(x, dtype=float), 0.0, self.length)
        interpolated = np.stack([np.interp(xs, self.x, column) for column in self.values.T], axis=-1)
        twist = np.interp(xs, self.x, self.pretwist)[..., None]
        if self.form is SectionForm.CONSTANTS:
            return np.concatenate([interpolated, twist], axis=-1)
        width, thickness = interpolated[..., 0], interpolated[..., 1]
        rows = [rectangle_constants(self._rectangle(float(b), float(h)))[:10]
                for b, h in zip(np.ravel(width), np.ravel(thickness))]
        return np.concatenate([np.reshape(rows, width.shape + (10,)), twist], axis=-1)

    def _rectangle(self, width: float, thickness: float) -> Section:
        m = self.material
        return Section(width, thickness, m.density, m.youngs_modulus, m.shear_modulus,
                       saint_venant_torsion_constant(width, thickness))

    def pretwist_rate(self, x) -> np.ndarray:
        """d(pretwist)/dx (rad/m) at ``x``: the slope of the segment holding x (the right one at a station)."""
        xs = np.clip(np.asarray(x, dtype=float), 0.0, self.length)
        k = np.clip(np.searchsorted(self.x, xs, side="right") - 1, 0, self.x.size - 2)
        return (self.pretwist[k + 1] - self.pretwist[k]) / (self.x[k + 1] - self.x[k])


def span_properties(section: Section, sections: SpanSections | None, x) -> np.ndarray:
    """The :data:`COLUMNS` of a beam at stations ``x`` (m from the root; scalar or array), shape
    (..., 11): from its span-wise table ``sections`` when it has one, else the uniform ``section``
    throughout (pretwist 0)."""
    if sections is None:
        return np.broadcast_to(rectangle_constants(section), np.shape(x) + (len(COLUMNS),)).copy()
    return sections.at(x)


def check_span(length: float, sections: SpanSections | None, structural_damping: float) -> float:
    """ValueError unless the table's last station is at the beam's ``length`` (m) and the
    structural damping c (s) is finite and >= 0; returns c as a float."""
    if sections is not None and not np.isclose(sections.length, length, rtol=1e-12, atol=0.0):
        raise ValueError(f"sections: the last station ({sections.length} m) must be at the beam's length ({length} m)")
    c = float(structural_damping)
    if not (np.isfinite(c) and c >= 0.0):
        raise ValueError(f"structural_damping: must be >= 0 s (got {structural_damping!r})")
    return c
