"""A straight ANCF beam mesh: DOF layout, reference states, assembled terms, stations.

The beam has ``n`` equal elements and n + 1 nodes; its coordinate vector q (8 (n + 1))
is node-major with the node layout of :data:`DOF_NAMES` (paper Eq. 14). The chart F
(see :mod:`hubbeam.elements.ancf.frame`) is part of the *state*: every method that
needs it takes it explicitly.

Section properties are evaluated at every Gauss point of every element, from the beam's
``section`` (a prismatic beam) or from a span-wise table (:class:`SpanSections`: taper,
pretwist). The stress-free state is the straight beam with the table's pretwist: its
theta_1 at node x_k is the root's minus pretwist(x_k) (pretwist turns the section about the
axis in the sense of the mount's twist, which turns it by -beta), theta_1' = -pretwist'(x_k),
and the strains are measured from those of this discrete state at each Gauss point.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hubbeam.elements.ancf import coordinates, elastic, inertia, loads
from hubbeam.elements.ancf.chart import choose_director, frame_from_director
from hubbeam.elements.ancf.frame import section_frame, section_frames
from hubbeam.elements.ancf.strain import strain_measures, strain_measures_at
from hubbeam.elements.hermite import gauss_legendre, hermite
from hubbeam.elements.section import COLUMN, Section, SpanSections, check_span, span_properties
from hubbeam.errors import ChartSingularityError

#: Names of the 8 coordinates of an ANCF node (Eq. 14).
DOF_NAMES = ("r_x", "r_y", "r_z", "r'_x", "r'_y", "r'_z", "theta_1", "theta_1'")
NODE_DOFS = coordinates.NODE_DOFS

#: Gauss points per element for the strain energy, chosen by the convergence study in
#: tests/elements/test_gauss_order.py (4 points give the energy of a strongly bent,
#: twisted state to 1e-6 relative; 5 leave round-off).
DEFAULT_GAUSS_POINTS = 5


#: the properties of :data:`hubbeam.elements.section.COLUMNS` that the kernels read per Gauss point
_STIFFNESS = [COLUMN[c] for c in ("EA", "GJ", "EI_y", "EI_z")]
_INERTIA = [COLUMN[c] for c in ("I_tau", "I_m", "I_n")]


@dataclass
class AncfBeam:
    """n equal ANCF elements over a beam of ``length`` (m) with one ``section`` (the material
    and the uniform section), or, when ``sections`` is given, the span-wise properties of that
    table (its length must be the beam's). ``structural_damping`` c (s): Kelvin-Voigt damping
    of the section resultants, c D e_dot (stiffness-proportional)."""

    length: float
    elements: int
    section: Section
    gauss_points: int = DEFAULT_GAUSS_POINTS
    sections: SpanSections | None = None
    structural_damping: float = 0.0
    _tables: tuple = field(init=False, repr=False)
    _rows: dict = field(init=False, repr=False, compare=False, default_factory=dict)  # stations' Hermite rows, once each

    def __post_init__(self) -> None:
        xi, w = gauss_legendre(self.gauss_points)
        S, dS, d2S = hermite(xi, self.element_length)
        self._tables = (np.ascontiguousarray(S), np.ascontiguousarray(dS), np.ascontiguousarray(d2S), w)
        self.structural_damping = check_span(self.length, self.sections, self.structural_damping)
        #: the section's properties (:data:`~hubbeam.elements.section.COLUMNS`) at every Gauss point
        points = (np.arange(self.elements)[:, None] + np.asarray(xi)[None, :]) * self.element_length
        props = span_properties(self.section, self.sections, points)
        self._stiffness = np.ascontiguousarray(props[..., _STIFFNESS])  # (n_el, ng, 4) N, N m^2
        self._inertia = np.ascontiguousarray(props[..., _INERTIA])  # (n_el, ng, 3) kg m
        self._rho_a = np.ascontiguousarray(props[..., COLUMN["rho_A"]])  # (n_el, ng) kg/m
        self._width = np.ascontiguousarray(props[..., COLUMN["width"]])  # (n_el, ng) m, the drag's frontal width
        self._trans_mass = inertia.translational_mass_blocks(self.element_length, S, w, self._rho_a)
        # the stress-free state: straight along e_1, twisted by the pretwist
        self._twist = self._node_pretwist()
        self._reference = np.zeros_like(self._stiffness)
        if np.any(self._twist):  # an untwisted straight beam's strains are exactly 0
            q_ref, F_ref = self.straight_state(np.zeros(3), np.eye(3))
            elastic.gauss_strains(q_ref, F_ref, self.element_length, S, dS, d2S, w, self._reference)
            self._reference_state = (q_ref, F_ref)
        else:
            self._reference_state = None

    def _node_pretwist(self) -> np.ndarray:
        """(pretwist, its rate) at the nodes (rad, rad/m; the mean of the two segments' slopes
        at a station where the slope changes), relative to the root."""
        x = np.arange(self.nodes) * self.element_length
        if self.sections is None:
            return np.zeros((self.nodes, 2))
        tab = self.sections
        angle = np.interp(x, tab.x, tab.pretwist) - tab.pretwist[0]
        slope = np.diff(tab.pretwist) / np.diff(tab.x)
        last = slope.size - 1
        right = slope[np.clip(np.searchsorted(tab.x, x, side="right") - 1, 0, last)]
        left = slope[np.clip(np.searchsorted(tab.x, x, side="left") - 1, 0, last)]
        return np.column_stack([angle, 0.5 * (left + right)])

    def reference_strains(self, x: float) -> np.ndarray:
        """(eps0, kappa1, kappa2, kappa3) of the stress-free state at station x (1, 1/m)."""
        if self._reference_state is None:
            return np.zeros(4)
        return self._measures_at(*self._reference_state, [x])[0]

    # ---------------------------------------------------------------- layout
    @property
    def element_length(self) -> float:
        return self.length / self.elements

    @property
    def nodes(self) -> int:
        return self.elements + 1

    @property
    def ndof(self) -> int:
        return NODE_DOFS * self.nodes

    def node_slice(self, node: int) -> slice:
        node = node % self.nodes
        return slice(NODE_DOFS * node, NODE_DOFS * (node + 1))

    # ---------------------------------------------------------------- states
    def straight_state(self, root: np.ndarray, frame: np.ndarray, reference: np.ndarray | None = None
                       ) -> tuple[np.ndarray, np.ndarray]:
        """Undeformed straight beam from ``root`` along frame[:, 0] with root section frame ``frame``
        (and the pretwist along the span: the stress-free state).

        Returns (q, F): the coordinates and a chart whose director is the beam axis, its other
        axes chosen in the ``reference`` axes (3 x 3 rotation; default the global axes) as
        :func:`~hubbeam.elements.ancf.chart.frame_from_director` chooses them in the global
        ones: a model turned as a whole gets the turned chart.
        """
        frame = np.asarray(frame, dtype=float)
        Q = np.eye(3) if reference is None else np.asarray(reference, dtype=float)
        F = Q @ frame_from_director(Q.T @ frame[:, 0])
        T, m, n = section_frame(F.T @ frame[:, 0], 0.0)
        m_g = F @ m
        theta = np.arctan2(np.dot(frame[:, 1], F @ n), np.dot(frame[:, 1], m_g))
        q = np.zeros(self.ndof)
        for k in range(self.nodes):
            s = self.node_slice(k)
            q[s][0:3] = np.asarray(root, dtype=float) + k * self.element_length * frame[:, 0]
            q[s][3:6] = frame[:, 0]
            q[s][6] = theta - self._twist[k, 0]
            q[s][7] = -self._twist[k, 1]
        return q, F

    # ---------------------------------------------------------------- energies
    def elastic(self, q: np.ndarray, F: np.ndarray, tangent: bool = True):
        """Strain energy U (J), internal force dU/dq (n_dof) and element tangents (n_el, 16, 16).

        Raises :class:`ChartSingularityError` where a tangent is at the chart's singular direction.
        """
        U, force, blocks, _ = self.internal(q, np.zeros(self.ndof), F, 0.0, 1.0 if tangent else None)
        return U, force, blocks

    def internal(self, q: np.ndarray, qdot: np.ndarray, F: np.ndarray, coef_c: float = 0.0,
                 coef_k: float | None = 1.0):
        """The section resultants with structural damping (:func:`~hubbeam.elements.ancf.elastic.elastic_kernel`):
        (U (J), internal force (n_dof, elastic plus damping), element blocks coef_k dforce/dq +
        coef_c dforce/dqdot (n_el, 16, 16; None when coef_k is None), dissipated power (W))."""
        S, dS, d2S, w = self._tables
        force = np.empty(self.ndof)
        blocks = np.zeros((self.elements if coef_k is not None else 0, 16, 16))
        U, margin, power = elastic.elastic_kernel(
            np.ascontiguousarray(q, dtype=float), np.ascontiguousarray(qdot, dtype=float), np.ascontiguousarray(F),
            self.element_length, S, dS, d2S, w, self._stiffness, self._reference, self.structural_damping,
            float(coef_c), float(coef_k or 0.0), force, blocks,
        )
        if not margin > 1e-6 or not np.isfinite(U):
            raise ChartSingularityError(
                f"a beam tangent is at the singular direction of the rotation chart (1 + d.tau = {margin:.2e})"
            )
        return U, force, (blocks if coef_k is not None else None), power

    def chart_margin(self, q: np.ndarray, F: np.ndarray) -> float:
        """min over Gauss points of 1 + d.tau (2 best, 0 singular)."""
        return float(np.min(1.0 + self.gauss_tangents(q) @ F[:, 0]))

    def mass_blocks(self, q: np.ndarray, F: np.ndarray) -> np.ndarray:
        """Element mass matrices (n_el, 16, 16) of Eq. 35 (kg, kg m, kg m^2 blocks)."""
        S, dS, _, w = self._tables
        out = np.zeros((self.elements, 16, 16))
        inertia.add_translational_mass(self._trans_mass, self.elements, 1.0, out)
        z = np.zeros(self.ndof)
        inertia.rotary_inertia_kernel(
            np.ascontiguousarray(q, dtype=float), z, z, np.ascontiguousarray(F), self.element_length, S, dS, w,
            self._inertia, 1.0, np.empty(self.ndof), out,
        )
        return out

    def apply_mass(self, blocks: np.ndarray, u: np.ndarray) -> np.ndarray:
        """M u for the assembled mass matrix whose element blocks (n_el, 16, 16) are ``blocks``."""
        n = NODE_DOFS
        idx = n * np.arange(self.elements)[:, None] + np.arange(2 * n)
        per_element = np.einsum("eij,ej->ei", blocks, u[idx])
        out = np.zeros(self.ndof)
        out[: -n] += per_element[:, :n].ravel()
        out[n:] += per_element[:, n:].ravel()
        return out

    def rotary_inertia(self, q: np.ndarray, qdot: np.ndarray, F: np.ndarray) -> tuple[float, np.ndarray]:
        """Rotational kinetic energy of the sections (J) and their quadratic-velocity force Q_v."""
        S, dS, _, w = self._tables
        out = np.empty(self.ndof)
        T = inertia.rotary_inertia_kernel(
            np.ascontiguousarray(q, dtype=float), np.ascontiguousarray(qdot, dtype=float), np.zeros(self.ndof),
            np.ascontiguousarray(F), self.element_length, S, dS, w, self._inertia, 0.0, out, np.empty((0, 16, 16)),
        )
        return T, out

    def drag(self, qdot: np.ndarray, linear: float, quadratic: float):
        """Damping of Eq. 37 on the centre line: (dissipated power W, Q_d, element damping matrices)."""
        S, _, _, w = self._tables
        force = np.empty(self.ndof)
        blocks = np.zeros((self.elements, 16, 16))
        power = loads.drag_kernel(
            np.ascontiguousarray(qdot, dtype=float), self.element_length, S, w, self._width,
            float(linear), float(quadratic), 1.0, force, blocks,
        )
        return power, force, blocks

    def distributed_load(self, per_length: np.ndarray) -> np.ndarray:
        """Generalized force of a constant load per unit length (N/m, global) (Eq. 32)."""
        return self._load(np.ones_like(self._rho_a), per_length)

    def gravity_load(self, gravity: np.ndarray) -> np.ndarray:
        """Generalized force of gravity (m/s^2, global) on the beam's own mass, int S^T rho A g dx (Eq. 32)."""
        return self._load(self._rho_a, gravity)

    def _load(self, density, load) -> np.ndarray:
        S, _, _, w = self._tables
        return loads.distributed_load(self.elements, self.element_length, S, w, density,
                                        np.asarray(load, dtype=float))

    # ---------------------------------------------------------------- stations
    def locate(self, x: float) -> tuple[int, float]:
        """Element index and local xi in [0, 1] of the station x (m from the root)."""
        e = min(int(x / self.element_length), self.elements - 1)
        return e, x / self.element_length - e

    def _station_rows(self, xs: np.ndarray):
        """(S, dS, d2S, indices into q of each station's r and r' (n x 4 x 3) and of its theta_1,
        theta_1' (n x 4)) of the stations xs (m from the root), computed once per set of stations
        (sensors and recorded states ask at every output time)."""
        key = tuple(np.asarray(xs, dtype=float).tolist())
        if key not in self._rows:
            located = [self.locate(x) for x in key]
            start = NODE_DOFS * np.array([e for e, _ in located], dtype=np.int64)[:, None]
            vectors = start[:, :, None] + np.array([0, 3, NODE_DOFS, NODE_DOFS + 3])[None, :, None] + np.arange(3)
            angles = start + np.array([6, 7, NODE_DOFS + 6, NODE_DOFS + 7])
            S, dS, d2S = hermite(np.array([xi for _, xi in located]), self.element_length)
            self._rows[key] = (S[:, None, :], dS[:, None, :], d2S[:, None, :], vectors, angles)
        return self._rows[key]

    def interpolate_at(self, q: np.ndarray, xs):
        """r0, r0', r0'' (n x 3, global components) and theta_1, theta_1' (n) at the stations xs (m)."""
        S, dS, d2S, vectors, angles = self._station_rows(np.atleast_1d(xs))
        vec, ang = q[vectors], q[angles]
        return ((S @ vec)[:, 0], (dS @ vec)[:, 0], (d2S @ vec)[:, 0], (S[:, 0] * ang).sum(axis=1),
                (dS[:, 0] * ang).sum(axis=1))

    def interpolate(self, q: np.ndarray, x: float):
        """r0, r0', r0'', theta_1, theta_1' at the station x (global components)."""
        r, u, v, phi, psi = self.interpolate_at(q, [x])
        return r[0], u[0], v[0], float(phi[0]), float(psi[0])

    def strains(self, q: np.ndarray, F: np.ndarray, x: float) -> tuple[float, float, float, float]:
        """(eps0, kappa1, kappa2, kappa3) at station x (1, 1/m)."""
        _, u, v, phi, psi = self.interpolate(q, x)
        return strain_measures(F.T @ u, F.T @ v, phi, psi)

    def frame_at(self, q: np.ndarray, F: np.ndarray, x: float) -> np.ndarray:
        """Section frame [tau m n] (3x3, global) at station x."""
        return self.frames_at(q, F, [x])[0]

    def frames_at(self, q: np.ndarray, F: np.ndarray, xs) -> np.ndarray:
        """Section frames [tau m n] (n x 3 x 3, global, columns) at the stations xs (m)."""
        _, u, _, phi, _ = self.interpolate_at(q, xs)
        return F @ section_frames(np.ascontiguousarray(u @ F), phi)  # u @ F: chart components F^T r0'

    def surface_strain(self, q: np.ndarray, F: np.ndarray, x: float, y: float, z: float) -> float:
        """Fibre axial strain eps0 - y kappa3 + z kappa2 at section point (y, z) of station x, the
        strains measured from the stress-free state's."""
        return float(self.surface_strains(q, F, [x], [y], [z])[0])

    def surface_strains(self, q: np.ndarray, F: np.ndarray, xs, y, z) -> np.ndarray:
        """Fibre axial strains at the section points (y_i, z_i) (m) of the stations xs (m), measured
        from the stress-free state's."""
        measures = self._measures_at(q, F, xs)
        if self._reference_state is not None:
            measures = measures - self._measures_at(*self._reference_state, xs)
        return measures[:, 0] - np.asarray(y, dtype=float) * measures[:, 3] + np.asarray(z, dtype=float) * measures[:, 2]

    def gauge_rows(self, x: float, y: float, z: float):
        """What compiled code needs of a strain gauge at the section point (y, z) (m) of station x
        (m) (:func:`hubbeam.system.equations.gauge_strains`): (element, S, dS, d2S (4 each: the
        Hermite functions at x and their derivatives), [y, z, the stress-free strains at x])."""
        e, xi = self.locate(x)
        S, dS, d2S = hermite(np.array([xi]), self.element_length)
        return e, S[0], dS[0], d2S[0], np.concatenate([[y, z], self.reference_strains(x)])

    def _measures_at(self, q: np.ndarray, F: np.ndarray, xs) -> np.ndarray:
        """(eps0, kappa1, kappa2, kappa3) (n x 4; 1, 1/m) at the stations xs (m)."""
        _, u, v, phi, psi = self.interpolate_at(q, xs)
        return strain_measures_at(np.ascontiguousarray(u @ F), np.ascontiguousarray(v @ F), phi, psi)

    def gauss_tangents(self, q: np.ndarray) -> np.ndarray:
        """Unit tangents at every Gauss point and node (rows)."""
        _, dS, _, _ = self._tables
        qn = q.reshape(self.nodes, NODE_DOFS)
        pts = []
        for e in range(self.elements):
            vec = np.array([qn[e, 0:3], qn[e, 3:6], qn[e + 1, 0:3], qn[e + 1, 3:6]])
            pts.append(dS @ vec)
        t = np.vstack(pts + [qn[:, 3:6]])
        return t / np.linalg.norm(t, axis=1, keepdims=True)

    def node_tangent_rates(self, q: np.ndarray) -> np.ndarray:
        """d(tau)/dx at each node, averaged over the elements that meet there (n_nodes, 3)."""
        qn = q.reshape(self.nodes, NODE_DOFS)
        _, dS, d2S = hermite(np.array([0.0, 1.0]), self.element_length)
        acc = np.zeros((self.nodes, 3))
        cnt = np.zeros(self.nodes)
        for e in range(self.elements):
            vec = np.array([qn[e, 0:3], qn[e, 3:6], qn[e + 1, 0:3], qn[e + 1, 3:6]])
            for k, node in enumerate((e, e + 1)):
                u, v = dS[k] @ vec, d2S[k] @ vec
                L = np.linalg.norm(u)
                t = u / L
                acc[node] += (v - t * np.dot(t, v)) / L
                cnt[node] += 1
        return acc / cnt[:, None]

    def better_chart(self, q: np.ndarray, reference: np.ndarray | None = None) -> np.ndarray:
        """A chart whose director keeps every current tangent as far as possible from -d, its
        candidates and axes chosen in the ``reference`` axes (default the global ones; see
        :meth:`straight_state`)."""
        Q = np.eye(3) if reference is None else np.asarray(reference, dtype=float)
        return Q @ frame_from_director(choose_director(self.gauss_tangents(q) @ Q))
