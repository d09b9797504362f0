"""What a beam must provide to sit on its frame: the formulation protocol of the system layer.

A beam part owns its coordinates q_k (the layout places them in x), its mount (where its
root sits, :mod:`hubbeam.system.mount`), an optional tip body and its tip loads. The
system (:mod:`hubbeam.system.multibody`) adds the base, the hub and the frames, places every
part with the layout and sums the parts' terms; the solvers see only the system. Where a
part's geometry depends on its frame (an FFR beam floats on it), the system passes the root
frame's pose ``frame`` = (origin, axes) and, for a motion, its ``rate`` = (origin velocity,
angular velocity); an ANCF beam's absolute coordinates need neither.

The *chart* of a part is part of its state (one 3 x 3 array per beam, the identity for a
formulation that does not use one). Formulations whose rotation parametrisation has a
singular direction (ANCF) are :class:`ChartedBeamPart`: only they are asked for chart
margins and replacements.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import replace

import numpy as np

from hubbeam.elements.hermite import gauss_legendre
from hubbeam.elements.section import COLUMN, span_properties
from hubbeam.system.chains import Chain
from hubbeam.system.mount import Mount

#: the parts of a beam's kinetic energy (:meth:`BeamPart.kinetic_energy_split`), in the order
#: a label joins them
BEAM_MOTIONS = ("flap", "lag", "axial", "torsion")


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
    tip_body: object  # a TipBody or None

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

    @abstractmethod
    def initial_state(self, root: np.ndarray, frame: np.ndarray, reference: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Undeformed, straight beam on its root frame (origin ``root``, section axes ``frame``):
        (q, chart), a chart chosen in the ``reference`` axes (the hub's at theta = 0)."""

    @abstractmethod
    def rigid_rates(self, q: np.ndarray, chart: np.ndarray, velocity, w, origin, acceleration=None):
        """(q', q'') when the beam moves rigidly with its frame: its points at velocity + w x
        (r - origin); ``acceleration`` not None: a steady rotation about the axis through origin."""

    @abstractmethod
    def tip_position(self, q: np.ndarray, frame=None) -> np.ndarray:
        """Global position of the tip centroid (m)."""

    @abstractmethod
    def tip_frame(self, x0: int, index: int, root) -> "Chain":
        """The frame a child beam's joint hangs on at this beam's tip (a chain of
        :mod:`hubbeam.system.frames`): the tip section frame turned back about its axis by the
        twist and the tip pretwist, so that, undeformed, it is this beam's axis frame carried to
        the tip. ``x0``: where this beam's coordinates start in x; ``index``: its place among the
        beams (its chart); ``root``: the chain of its root section frame."""

    def tip_node(self) -> slice | None:
        """The coordinates of the tip's ANCF node [r0, r0', theta_1, theta_1'] in q, to which a
        tip body attaches as a part of its own (:mod:`hubbeam.system.tip_body`); None when the
        formulation carries its tip body itself (FFR: in its inertia invariants)."""
        return None

    @abstractmethod
    def surface_strain(self, q: np.ndarray, chart: np.ndarray, station: float, y: float, z: float) -> float:
        """Fibre axial strain at section point (y, z) of the station x (m from the root)."""

    def without_structural_damping(self) -> "BeamPart":
        """The same part with its beam's structural damping c = 0 (itself when it has none);
        parts are dataclasses holding their beam as ``beam``."""
        if not self.beam.structural_damping:
            return self
        return replace(self, beam=replace(self.beam, structural_damping=0.0))

    @abstractmethod
    def centre_line_at(self, q: np.ndarray, chart: np.ndarray, stations, frame=None) -> np.ndarray:
        """Centre-line points (n x 3, global, m) of the stations (m from the root along the undeformed beam)."""

    @abstractmethod
    def frames_at(self, q: np.ndarray, chart: np.ndarray, stations, frame=None) -> np.ndarray:
        """Section frames [tau m n] (n x 3 x 3, unit columns, global) of the stations (m from the root)."""

    def surface_strains(self, q: np.ndarray, chart: np.ndarray, stations, y, z) -> np.ndarray:
        """Fibre axial strains (1) at the section points (y_i, z_i) (m) of the stations (m)."""
        return np.array([self.surface_strain(q, chart, s, yi, zi) for s, yi, zi in zip(stations, y, z)])

    def surface_strains_of_states(self, Q: np.ndarray, chart: np.ndarray, station: float, y: float, z: float
                                  ) -> np.ndarray:
        """:meth:`surface_strain` at one section point for each row of Q (states x the part's
        coordinates, one chart): a strain gauge over a run's records."""
        return np.array([self.surface_strain(q, chart, station, y, z) for q in Q])

    def stations(self, points_per_element: int) -> np.ndarray:
        """Span stations (m from the root): the nodes and points_per_element - 1 points evenly
        inside each element."""
        return np.linspace(0.0, self.length, self.beam.elements * points_per_element + 1)

    def section_size(self, station: float) -> tuple[float, float]:
        """Width b (m, along m) and thickness h (m, along n) of the section at the station
        (m from the root), from the beam's span-wise table when it has one. What draws or samples
        a section (a strain gauge's 'upper' face z = +h/2) asks here, not the section itself."""
        row = self.properties(float(station))
        return float(row[COLUMN["width"]]), float(row[COLUMN["thickness"]])

    def properties(self, stations) -> np.ndarray:
        """The section's :data:`~hubbeam.elements.section.COLUMNS` at the stations (m from the
        root; scalar or array), from the beam's span-wise table when it has one."""
        return span_properties(self.section, self.beam.sections, stations)

    def centre_line(self, q: np.ndarray, chart: np.ndarray, points_per_element: int = 8, frame=None) -> np.ndarray:
        """Points of the deformed centre line (global, m), root to tip, at :meth:`stations`."""
        return self.centre_line_at(q, chart, self.stations(points_per_element), frame)

    @abstractmethod
    def section_motion(self, q: np.ndarray, chart: np.ndarray, u: np.ndarray, stations: np.ndarray, frame=None,
                       rate=None):
        """The sections at the stations x (m from the root) of the configuration q moved at the
        coordinate rate u (and the root frame ``frame`` at ``rate``): (frames (n, 3, 3): the section frames [tau m n] at q, global;
        velocity (n, 3): the centre line's velocity (m/s per unit of u); omega (n, 3): the
        section's angular velocity (rad/s), global). Both are linear in u; with u a mode shape
        they are the centre line's displacement and the section's small rotation."""

    def span_quadrature(self, gauss_points: int) -> tuple[np.ndarray, np.ndarray]:
        """Gauss stations along the span (m from the root) and their weights (m): ``gauss_points``
        per element of the mesh."""
        xi, w = gauss_legendre(gauss_points)
        le = self.length / self.beam.elements
        e = np.arange(self.beam.elements)[:, None]
        return ((e + xi[None, :]) * le).ravel(), np.tile(w * le, self.beam.elements)

    def kinetic_energy_split(self, q: np.ndarray, chart: np.ndarray, u: np.ndarray, axes: np.ndarray, frame=None,
                             rate=None) -> dict[str, float]:
        """The kinetic energy (J) of the beam and its tip body moving at the coordinate rate u
        about the configuration q (u complex: the sum of its real and imaginary parts' energies),
        split by direction in the beam's undeformed axis frame ``axes`` (a_1 the axis, a_2, a_3 =
        k_k; with no precone a_1 = i_k and a_2 = j_h; on a joint, turned by the joint):

        - ``flap``: centre-line motion along a_2 and section rotation about a_3 (the slope of
          the flap deflection);
        - ``lag``: centre-line motion along a_3 and section rotation about a_2;
        - ``axial``: centre-line motion along a_1;
        - ``torsion``: section rotation about a_1.

        Per length the energy is rho A |v|^2 / 2 + omega . J omega / 2 (rho A and J, the rotary
        inertia, of the local section; its frame at q); the rotary part is split as sum_i (omega . a_i)(J omega . a_i) / 2,
        so the four parts add up to the whole kinetic energy. A tip body adds m |v_cm|^2 / 2
        (v_cm = v + omega x (R c), c its offset) and omega . J_b omega / 2 the same way."""
        u = np.asarray(u)
        if np.iscomplexobj(u):
            rates = (None, None) if rate is None else (tuple(np.real(r) for r in rate), tuple(np.imag(r) for r in rate))
            re, im = (self.kinetic_energy_split(q, chart, part, axes, frame, rt) for part, rt in zip((u.real, u.imag), rates))
            return {k: re[k] + im[k] for k in BEAM_MOTIONS}
        a = np.asarray(axes, dtype=float)
        x, w = self.span_quadrature(self.beam.gauss_points)  # the beam's own rule: its mass matrix's quadrature
        frames, vel, omega = self.section_motion(q, chart, u, x, frame, rate)
        props = self.properties(x)  # the local section: rho A (kg/m), rotary inertias about (tau, m, n) (kg m)
        J = props[:, [COLUMN["I_tau"], COLUMN["I_m"], COLUMN["I_n"]]]
        J_omega = np.einsum("nij,nj,nkj,nk->ni", frames, J, frames, omega)  # R J R^T omega
        trans = 0.5 * np.einsum("n,ni->i", w * props[:, COLUMN["rho_A"]], (vel @ a) ** 2)
        rot = 0.5 * np.einsum("n,ni->i", w, (omega @ a) * (J_omega @ a))
        body = self.tip_body
        if body is not None:
            R, v, om = (arr[0] for arr in self.section_motion(q, chart, u, np.array([self.length]), frame, rate))
            v_cm = v + np.cross(om, R @ np.array(body.offset))
            trans = trans + 0.5 * body.mass * (v_cm @ a) ** 2
            Jb_omega = R @ (np.array(body.inertia) * (R.T @ om))
            rot = rot + 0.5 * (om @ a) * (Jb_omega @ a)
        return {"flap": float(trans[1] + rot[2]), "lag": float(trans[2] + rot[1]), "axial": float(trans[0]),
                "torsion": float(rot[0])}

    def span_shape(self, q: np.ndarray, chart: np.ndarray, u: np.ndarray, axes: np.ndarray, stations: np.ndarray,
                   frame=None, rate=None):
        """The centre-line displacement (n, 3) along (a_1, a_2, a_3) = (axial, flap, lag) (m per
        unit of u) and the section rotation about the beam axis a_1 (twist, rad per unit of u) at
        the stations (m from the root) for the coordinate change u about q (complex u: complex)."""
        u = np.asarray(u)
        if np.iscomplexobj(u):
            rates = (None, None) if rate is None else (tuple(np.real(r) for r in rate), tuple(np.imag(r) for r in rate))
            re, im = (self.span_shape(q, chart, part, axes, stations, frame, rt) for part, rt in zip((u.real, u.imag), rates))
            return re[0] + 1j * im[0], re[1] + 1j * im[1]
        a = np.asarray(axes, dtype=float)
        _, disp, rot = self.section_motion(q, chart, u, np.asarray(stations, dtype=float), frame, rate)
        return disp @ a, rot @ a[:, 0]

class ChartedBeamPart(BeamPart):
    """A beam whose rotation chart must be replaced before a tangent reaches its singular direction."""

    @abstractmethod
    def chart_margin(self, q: np.ndarray, chart: np.ndarray) -> float:
        """min(1 + d.tau): 2 best, 0 singular."""

    @abstractmethod
    def better_chart(self, q: np.ndarray, reference: np.ndarray | None = None) -> np.ndarray:
        """A chart that keeps every current tangent far from its singular direction (chosen in the
        ``reference`` axes)."""

    @abstractmethod
    def remap(self, q: np.ndarray, chart: np.ndarray, new_chart: np.ndarray) -> np.ndarray:
        """q re-expressed in ``new_chart`` (the same configuration)."""

    @abstractmethod
    def axis_chart(self, axis, hint) -> np.ndarray:
        """The chart in which a rigid rotation about the hub axis ``axis`` is exact (director -axis)."""
