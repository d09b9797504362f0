"""Rectangular cross-section properties (docs/scenario.md: width b along y, thickness h along z)."""

from __future__ import annotations

from dataclasses import dataclass


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
