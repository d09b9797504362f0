"""What a beam must provide to sit on the hub: the formulation protocol of the system layer.

A beam part owns its coordinates q_k (the layout places them in x), its mount (where its
root sits, :mod:`hubbeam.system.mount`), an optional tip body and its tip loads. The
system (:mod:`hubbeam.system.hub_system`) adds the hub, places every part with the layout
and sums the parts' terms; the solvers see only the system.

The *chart* of a part is part of its state (one 3 x 3 array per beam, the identity for a
formulation that does not use one). Formulations whose rotation parametrisation has a
singular direction (ANCF) are :class:`ChartedBeamPart`: only they are asked for chart
margins and replacements.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np

from hubbeam.elements.section import COLUMN
from hubbeam.system.mount import Mount


class BeamPart(ABC):
    """One beam clamped to the hub (paper Secs. 2-4), in its formulation's coordinates q."""

    #: the formulation's name in scenarios ("ancf", "ffr")
    formulation: str = ""
    #: coordinates of the root that the clamp involves (the leading entries of q)
    root_dofs: int = 0

    name: str
    mount: Mount
    tip_force: np.ndarray
    tip_moment: np.ndarray
    beam: object  # the formulation's mesh: length, section, elements

    def __post_init__(self) -> None:
        self.tip_force = np.asarray(self.tip_force, dtype=float)
        self.tip_moment = np.asarray(self.tip_moment, dtype=float)

    @property
    @abstractmethod
    def ndof(self) -> int:
        """Number of coordinates q of this beam."""

    @property
    def length(self) -> float:
        """Undeformed length L (m)."""
        return float(self.beam.length)

    @property
    def section(self):
        """The cross-section (:class:`hubbeam.elements.section.Section`)."""
        return self.beam.section

    def thickness_at(self, station: float) -> float:
        """The section's thickness h (m) at the station x (m from the root): the span-wise
        table's (``beam.sections``) where the beam has one."""
        sections = getattr(self.beam, "sections", None)  # a formulation without span-wise tables has none
        if sections is None:
            return float(self.section.thickness)
        return float(sections.at(station)[COLUMN["thickness"]])

    @abstractmethod
    def initial_state(self, theta: float) -> tuple[np.ndarray, np.ndarray]:
        """Undeformed, straight beam clamped to the hub at angle theta: (q, chart)."""

    @abstractmethod
    def clamp(self, q: np.ndarray, chart: np.ndarray, theta: float):
        """The six clamp equations: (Phi (6), dPhi/d[theta, q_root] (6 x (1 + root_dofs)),
        lambda -> lambda . d2 Phi / d[theta, q_root]^2)."""

    @abstractmethod
    def steady_rotation_rates(self, q: np.ndarray, chart: np.ndarray, omega: float):
        """(q', q'') when the beam turns rigidly with the hub at theta' = omega (rad/s)."""

    @abstractmethod
    def mass_matrix(self, q: np.ndarray, chart: np.ndarray) -> np.ndarray:
        """Dense mass matrix on q (tip body included)."""

    @abstractmethod
    def energies(self, q: np.ndarray, v: np.ndarray, chart: np.ndarray, gravity: np.ndarray) -> dict[str, float]:
        """Kinetic, strain and gravity energy (J) of the beam and its tip body."""

    @abstractmethod
    def tip_position(self, q: np.ndarray) -> np.ndarray:
        """Global position of the tip centroid (m)."""

    @abstractmethod
    def surface_strain(self, q: np.ndarray, chart: np.ndarray, station: float, y: float, z: float) -> float:
        """Fibre axial strain at section point (y, z) of the station x (m from the root)."""

    @abstractmethod
    def centre_line(self, q: np.ndarray, chart: np.ndarray, points_per_element: int = 8) -> np.ndarray:
        """Points of the deformed centre line (global, m), root to tip."""

    def tip_displacement(self, q: np.ndarray, theta: float) -> dict[str, float]:
        """Tip centroid displacement from its undeformed place, along the beam's own hub frame
        i_k (radial), j0 (vertical), k_k (tangential) (m)."""
        A = self.mount.hub_frame(theta)
        undeformed = self.mount.root(theta) + self.length * self.mount.frame(theta)[:, 0]
        disp = self.tip_position(q) - undeformed
        return {"radial": float(disp @ A[:, 0]), "vertical": float(disp @ A[:, 1]),
                "tangential": float(disp @ A[:, 2])}


class ChartedBeamPart(BeamPart):
    """A beam whose rotation chart must be replaced before a tangent reaches its singular direction."""

    @abstractmethod
    def chart_margin(self, q: np.ndarray, chart: np.ndarray) -> float:
        """min(1 + d.tau): 2 best, 0 singular."""

    @abstractmethod
    def better_chart(self, q: np.ndarray) -> np.ndarray:
        """A chart that keeps every current tangent far from its singular direction."""

    @abstractmethod
    def remap(self, q: np.ndarray, chart: np.ndarray, new_chart: np.ndarray) -> np.ndarray:
        """q re-expressed in ``new_chart`` (the same configuration)."""

    @abstractmethod
    def axis_chart(self) -> np.ndarray:
        """The chart in which a rigid rotation about the hub axis is exact (director -j0)."""
