"""The FFR beam as one flexible body: inertia invariants, stiffness, inertia forces (Eqs. 42-67).

The body frame O_b-i_b j_b k_b sits at the root A with i_b along the undeformed axis; the
root node is clamped to it, so the deformation coordinates p are those of nodes 1..n
(6 n values, node-major, :data:`~hubbeam.elements.ffr.shape.DOF_NAMES`).

A point of the beam is r = r_C + A0 (rho0 + N p) (Eq. 42), with rho0 = (x, y, z). Every
volume integral the equations need is a contraction of p (or dp/dt) with five *inertia
invariants*, computed once here by exact quadrature (Gauss in x, 2 x 2 Gauss over the
rectangle: the integrands are polynomials of degree <= 6 in x and <= 2 in y, z):

    m = int rho dV,          c0 = int rho rho0 dV,          Sbar = int rho N dV,
    I0 = int rho rho0 rho0^T dV,   J[k, l] = int rho rho0_k N_l dV,   II[k, l] = int rho N_k^T N_l dV.

With the generalized velocity v = [r_C', omega^b, p'] (Eq. 58), M_v (Eq. 66), Q_v (Eq. 67)
and Q_g follow in closed form (see the methods). Units: SI.

**Span-wise sections** (``sections=``, a :class:`~hubbeam.elements.section.SpanSections`):
every property is taken at the Gauss points of each element from the table (``section`` then
only stands for the material and the scales). The section's principal axes (m', n') turn
about the axis by the pretwist beta(x), in the sense of the mount's twist:
m' = cos(beta) j_b - sin(beta) k_b, n' = sin(beta) j_b + cos(beta) k_b. The centre line
stays straight (no reference strain). A section is given to the inertia by four points
(+-a m', +-c n') of mass rho_A / 4 each, a^2 = I_n / rho_A, c^2 = I_m / rho_A: they carry
its mass, its zero first moments and its second-moment tensor exactly, which is all the
invariants see (N and rho0 are linear in y, z); for the prismatic rectangle these are its
2 x 2 Gauss points. The torsional inertia is therefore I_m + I_n (a table's I_tau is not
used). The elastic energy's bending part is (v0'', w0'') E S (v0'', w0'')^T / 2 with
E S = EI_z m' m'^T + EI_y n' n'^T in the body's (y, z) plane: pretwist couples the two
bending planes. Sensor points (y, z) are in the local section axes (m', n').

**Structural damping** (``structural_damping`` = c, s): Kelvin-Voigt, proportional to the
material elastic stiffness K (Eq. 61 with the sections; not the geometric stiffening): the
generalized force c K p' on the elastic coordinates (:attr:`FfrBeam.damping_matrix`),
dissipating p'^T c K p' >= 0. About an unstressed state mode i decays with
zeta_i = c omega_i / 2.

A rigid tip body (:class:`~hubbeam.system.tip_body.TipBody`, ``tip_body=``) is part of the
invariants. It moves with the tip section under the FFR's linear kinematics: its point at
body position rho0 = (L, 0, 0) + d is displaced by u = N(L) p + phi(L) x d, phi the
section's small rotation (:meth:`FfrBeam.rotation_row`), so N_d = N(L) - [d]x Phi(L).
Every invariant is linear in the mass distribution and at most quadratic in d, so the body
is represented exactly by seven weighted points with its mass, centre of mass and second
moments (:meth:`~hubbeam.system.tip_body.TipBody.point_masses`).
M_v, Q_v, Q_g, the energies and the momentum of the FFR system then include it.

``modes=N`` makes the beam *modally reduced* (:mod:`hubbeam.elements.ffr.modal`): its
elastic coordinates are eta with p = B eta, B the N lowest clamped-free modes of the nodal
model above (tip body included; with geometric stiffening, those of bending and torsion plus
the nodal axial coordinates). Every term is a contraction of p with the invariants or with
rows over p, so the reduced beam is the nodal one with every invariant, row and stiffness
mapped by B once, when it is built (:func:`~hubbeam.elements.ffr.modal.project`; rows built
later pass through :meth:`FfrBeam._scatter`); every method is shared. ``ndof`` is the number
of columns of B; ``elements`` and ``element_length`` describe the underlying mesh.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hubbeam.elements.ffr.shape import NODE_DOFS, displacement_matrix, line_shapes
from hubbeam.elements.hermite import gauss_legendre
from hubbeam.elements.section import COLUMN, Section, SpanSections, check_span, span_properties


def skew(a: np.ndarray) -> np.ndarray:
    """The matrix of a x (.)."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


@dataclass
class FfrBeam:
    """n equal FFR elements over a beam of ``length`` (m) with one ``section`` (or, with
    ``sections``, the span-wise table); with ``modes``, reduced to that many clamped-free modes
    (``frequencies_hz``, ``max_frequency_hz``, ``basis``); ``structural_damping`` c (s)."""

    length: float
    elements: int
    section: Section
    gauss_points: int = 4
    geometric_stiffening: bool = False
    #: a rigid body on the tip section (:class:`~hubbeam.system.tip_body.TipBody`), or None
    tip_body: object = None
    #: None: the nodal coordinates p; N: the N lowest clamped-free modes (:mod:`~hubbeam.elements.ffr.modal`)
    modes: int | None = None
    #: span-wise properties and pretwist (:class:`~hubbeam.elements.section.SpanSections`); None: ``section`` throughout
    sections: SpanSections | None = None
    #: Kelvin-Voigt coefficient c (s): the generalized force c K p' on the elastic coordinates
    structural_damping: float = 0.0
    invariants: dict = field(init=False, repr=False)
    _rows: dict = field(init=False, repr=False, compare=False, default_factory=dict)  # station rows, once each

    def __post_init__(self) -> None:
        self.structural_damping = check_span(self.length, self.sections, self.structural_damping)
        #: p = basis @ eta for a modally reduced beam (nodal ndof x ndof); None: nodal
        self.basis = None
        #: a reduced beam's kept clamped-free modes: shapes over p (columns) and frequencies (Hz)
        self.mode_shapes = self.frequencies_hz = None
        self.invariants = self._inertia_invariants()
        self.stiffness_matrix = self._stiffness()
        self.centre_line_table = self._centre_line_table()
        if self.modes is not None:
            from hubbeam.elements.ffr.modal import reduce

            reduce(self, self.modes)
        self._rows.clear()  # rows asked for while the invariants were built are over the nodal coordinates

    # ---------------------------------------------------------------- layout
    @property
    def element_length(self) -> float:
        return self.length / self.elements

    @property
    def ndof(self) -> int:
        """Elastic coordinates: the nodal ones (the root node is clamped to the body frame),
        or the kept modes of a reduced beam."""
        return self.nodal_ndof if self.basis is None else self.basis.shape[1]

    @property
    def max_frequency_hz(self) -> float | None:
        """The highest kept mode's clamped frequency (Hz) of a reduced beam; None for a nodal one."""
        return None if self.frequencies_hz is None else float(self.frequencies_hz[-1])

    @property
    def nodal_ndof(self) -> int:
        """Deformation coordinates of the nodal model, 6 per element."""
        return NODE_DOFS * self.elements

    def element_dofs(self, e: int) -> np.ndarray:
        """Indices into p of element e's 12 coordinates; -1 for the clamped root node's."""
        idx = np.arange(NODE_DOFS * (e - 1), NODE_DOFS * (e + 1))
        return np.where(idx >= 0, idx, -1)

    def locate(self, x: float) -> tuple[int, float]:
        e = min(int(x / self.element_length), self.elements - 1)
        return e, x / self.element_length - e

    def _scatter(self, e: int, row: np.ndarray) -> np.ndarray:
        """An element row (..., 12) as a row over the elastic coordinates (..., ndof): over p,
        or mapped by the modal basis."""
        out = np.zeros(row.shape[:-1] + (self.nodal_ndof,))
        dofs = self.element_dofs(e)
        keep = dofs >= 0
        out[..., dofs[keep]] = row[..., keep]
        return out if self.basis is None else out @ self.basis

    # ---------------------------------------------------------------- sections
    def properties(self, x) -> np.ndarray:
        """The section columns (:data:`~hubbeam.elements.section.COLUMNS`: EA, GJ, EI_y, EI_z (N, N m^2),
        rho_A (kg/m), I_tau, I_m, I_n (kg m), width, thickness (m), pretwist (rad)) at stations ``x``
        (m; scalar or array): from ``sections``, or ``section`` throughout. Shape (..., 11)."""
        return span_properties(self.section, self.sections, x)

    def section_axes(self, x: float) -> np.ndarray:
        """The local section axes m', n' at station x as columns of a 2 x 2 matrix over the body's
        (y, z): turned by the pretwist beta(x) in the sense of the mount's twist."""
        beta = float(self.properties(float(x))[COLUMN["pretwist"]])
        c, s = np.cos(beta), np.sin(beta)
        return np.array([[c, s], [-s, c]])

    def body_point(self, x: float, y: float, z: float) -> tuple[float, float]:
        """Body-frame (y, z) (m) of the section point (y, z) given on the local axes m', n' at x."""
        if y == 0.0 and z == 0.0 or self.sections is None:
            return float(y), float(z)
        yb, zb = self.section_axes(x) @ np.array([y, z], dtype=float)
        return float(yb), float(zb)

    @property
    def damping_matrix(self) -> np.ndarray:
        """c K (N s over the elastic coordinates): the structural damping's generalized force is
        damping_matrix @ p'."""
        return self.structural_damping * self.stiffness_matrix

    # ---------------------------------------------------------------- invariants
    def _section_points(self, props: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Four body-frame points (y, z) (4, 2) and their weight per length (kg/m) of the section with
        columns ``props``: (+-a m', +-c n'), a^2 = I_n / rho_A, c^2 = I_m / rho_A, rho_A / 4 each (the
        section's mass, first and second moments)."""
        rho_a = props[COLUMN["rho_A"]]
        a = np.sqrt(props[COLUMN["I_n"]] / rho_a)
        c = np.sqrt(props[COLUMN["I_m"]] / rho_a)
        beta = props[COLUMN["pretwist"]]
        axes = np.array([[np.cos(beta), np.sin(beta)], [-np.sin(beta), np.cos(beta)]])
        local = np.array([[-a, -c], [-a, c], [a, -c], [a, c]])
        return local @ axes.T, 0.25 * rho_a

    def _inertia_invariants(self) -> dict:
        xg, wx = gauss_legendre(self.gauss_points)
        l = self.element_length
        shapes = line_shapes(xg, l)
        N_list, r0_list, w_list = [], [], []
        for e in range(self.elements):
            props = self.properties((e + xg) * l)
            for k, (xi, wk) in enumerate(zip(xg, wx)):
                points, weight = self._section_points(props[k])
                for y, z in points:
                    N_list.append(self._scatter(e, displacement_matrix(shapes, k, y, z)))
                    r0_list.append([(e + xi) * l, y, z])
                    w_list.append(weight * wk * l)
        if self.tip_body is not None:
            # seven weighted points carrying the tip body's mass, first and second moments,
            # moving with the tip section: u = N(L) p + phi(L) x d
            N_tip, Phi_tip = self.displacement_row(self.length), self.rotation_row(self.length)
            weights, offsets = self.tip_body.point_masses()
            for wk, d in zip(weights, offsets):
                N_list.append(N_tip - skew(d) @ Phi_tip)
                r0_list.append([self.length + d[0], d[1], d[2]])
                w_list.append(wk)
        N, r0, w = np.array(N_list), np.array(r0_list), np.array(w_list)
        return {
            "m": w.sum(),
            "c0": w @ r0,
            "Sbar": np.einsum("q,qkf->kf", w, N),
            "I0": np.einsum("q,qk,ql->kl", w, r0, r0),
            "J": np.einsum("q,qk,qlf->klf", w, r0, N),
            "II": np.einsum("q,qkf,qlg->klfg", w, N, N),
            "Mff": np.einsum("q,qkf,qkg->fg", w, N, N),
        }

    # ---------------------------------------------------------------- stiffness
    def _stiffness(self) -> np.ndarray:
        """K of Eq. 61 with the properties at the Gauss points (max(4, gauss_points) per element;
        exact for a prismatic beam): EA u0'^2 + GJ theta'^2 + (v0'', w0'') E S (v0'', w0'')^T,
        E S = EI_z m' m'^T + EI_y n' n'^T in the body's (y, z) plane (m', n' the local section axes,
        turned by the pretwist; without pretwist EI_z v0''^2 + EI_y w0''^2). Also sets the axial
        part and the element integrals int EA dx (N m) of the element-mean strain."""
        xg, wx = gauss_legendre(max(4, self.gauss_points))
        l = self.element_length
        sh = line_shapes(xg, l)
        K = np.zeros((self.nodal_ndof, self.nodal_ndof))
        self._axial_stiffness = np.zeros((self.nodal_ndof, self.nodal_ndof))
        self._axial_integrals = np.zeros(self.elements)
        c_ = COLUMN
        for e in range(self.elements):
            props = self.properties((e + xg) * l)
            EA, GJ, EIy, EIz, beta = (props[:, c_[k]] for k in ("EA", "GJ", "EI_y", "EI_z", "pretwist"))
            c, s = np.cos(beta), np.sin(beta)
            kvv, kww, kvw = EIz * c * c + EIy * s * s, EIz * s * s + EIy * c * c, (EIy - EIz) * c * s
            Ka = l * np.einsum("q,qi,qj->ij", wx * EA, sh["N1x"], sh["N1x"])
            cross = np.einsum("q,qi,qj->ij", wx * kvw, sh["N2xx"], sh["N3xx"])
            Ke = Ka + l * (np.einsum("q,qi,qj->ij", wx * kvv, sh["N2xx"], sh["N2xx"])
                           + np.einsum("q,qi,qj->ij", wx * kww, sh["N3xx"], sh["N3xx"])
                           + cross + cross.T
                           + np.einsum("q,qi,qj->ij", wx * GJ, sh["N4x"], sh["N4x"]))
            dofs = self.element_dofs(e)
            keep = dofs >= 0
            K[np.ix_(dofs[keep], dofs[keep])] += Ke[np.ix_(keep, keep)]
            self._axial_stiffness[np.ix_(dofs[keep], dofs[keep])] += Ka[np.ix_(keep, keep)]
            self._axial_integrals[e] = l * (wx @ EA)
        return K

    def _centre_line_table(self) -> dict:
        """Gauss points along the centre line (4 per element): weights (m), x, the frontal width
        b (m, of the drag) and N(x, 0, 0) over p; and per element the rows of the element-mean
        axial strain: a_e (the mean of u0') and G_e = (1/l) int (N2x^T N2x + N3x^T N3x) dx (exact: 4 points)."""
        xg, wx = gauss_legendre(4)
        l = self.element_length
        sh = line_shapes(xg, l)
        N, xs, ws = [], [], []
        a = np.zeros((self.elements, self.nodal_ndof))
        G = np.zeros((self.elements, self.nodal_ndof, self.nodal_ndof))
        for e in range(self.elements):
            for k in range(xg.shape[0]):
                N.append(self._scatter(e, displacement_matrix(sh, k, 0.0, 0.0)))
                xs.append((e + xg[k]) * l)
                ws.append(wx[k] * l)
                n2, n3 = self._scatter(e, sh["N2x"][k]), self._scatter(e, sh["N3x"][k])
                G[e] += wx[k] * (np.outer(n2, n2) + np.outer(n3, n3))
            a[e] = self._scatter(e, sh["N1x"][0])  # u0' is constant on the element
        xs = np.array(xs)
        return {"N": np.array(N), "x": xs, "w": np.array(ws), "b": self.properties(xs)[:, COLUMN["width"]],
                "mean_stretch": a, "mean_slope2": G}

    def _mean_axial_strain(self, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Element-mean axial strain with its second-order part and its gradient rows:
        eps_e = a_e p + p^T G_e p / 2, d eps_e / dp = a_e + G_e p."""
        t = self.centre_line_table
        Gp = t["mean_slope2"] @ p
        return t["mean_stretch"] @ p + 0.5 * Gp @ p, t["mean_stretch"] + Gp

    def elastic(self, p: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
        """Strain energy (J), internal force (N) and tangent stiffness over p.

        The paper's FFR (Eq. 46 with Eq. 48, eps0 = u0'): U = p^T K p / 2 with K of Eq. 61.
        With ``geometric_stiffening`` the axial strain keeps its second-order part,
        eps0 = u0' + (v0'^2 + w0'^2) / 2 (the Green strain of the centre line to second
        order in the slopes), so the axial force N = EA eps0 adds N (v0'^2 + w0'^2) / 2 to
        the energy of a deflection: the centrifugal stiffening of a rotating beam.
        u0 is linear on an element but v0'^2 is quartic, so a pointwise eps0 cannot vanish in
        an inextensible bending mode and the element locks (measured on Kane's spin-up at
        10 rad/s: tip lag 0.57 / 0.71 / 0.80 m with 8 / 16 / 32 elements against 0.84 m).
        The axial energy therefore uses the element-mean strain, (int_e EA dx) eps_e^2 / 2 per
        element, which the linear u0 can match exactly. Bending and torsion keep Eq. 61.
        """
        K = self.stiffness_matrix
        if not self.geometric_stiffening:
            f = K @ p
            return 0.5 * p @ f, f, K
        EAl = self.axial_integrals
        K_rest = K - self._axial_stiffness
        eps, deps = self._mean_axial_strain(p)
        f = K_rest @ p + deps.T @ (EAl * eps)
        Kt = K_rest + deps.T @ (EAl[:, None] * deps) \
            + np.einsum("e,efg->fg", EAl * eps, self.centre_line_table["mean_slope2"])
        U = 0.5 * p @ (K_rest @ p) + 0.5 * (EAl * eps) @ eps
        return U, f, Kt

    @property
    def axial_integrals(self) -> np.ndarray:
        """int_e EA dx (N m) per element: the axial stiffness of the element-mean strain."""
        return self._axial_integrals

    def _station_rows(self, x: float, y: float = 0.0, z: float = 0.0):
        """(element, row of u0', row of -y_b v0'' - z_b w0'') over the coordinates at the station x and
        section point (y, z) on the local axes ((y_b, z_b) its body coordinates, :meth:`body_point`),
        computed once per station (sensors ask at every output time)."""
        key = ("strain", float(x), float(y), float(z))
        if key not in self._rows:
            e, xi = self.locate(x)
            sh = line_shapes(np.array([xi]), self.element_length)
            yb, zb = self.body_point(x, y, z)
            self._rows[key] = (e, self._scatter(e, sh["N1x"][0]),
                               self._scatter(e, -yb * sh["N2xx"][0] - zb * sh["N3xx"][0]))
        return self._rows[key]

    def axial_strain(self, p: np.ndarray, x: float) -> float:
        """eps0 at station x: u0', or with geometric stiffening the element-mean strain
        including (v0'^2 + w0'^2) / 2 (the strain the energy uses)."""
        e, axial, _ = self._station_rows(x)
        if self.geometric_stiffening:
            return float(self._mean_axial_strain(p)[0][e])
        return float(axial @ p)

    # ---------------------------------------------------------------- inertia
    def first_moment(self, p: np.ndarray) -> np.ndarray:
        """S_t = int rho (rho0 + u) dV (kg m), body frame."""
        inv = self.invariants
        return inv["c0"] + inv["Sbar"] @ p

    def _moments(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """G[j, k] = int rho (rho0 + N a)_j (N b)_k dV."""
        inv = self.invariants
        return inv["J"] @ b + np.einsum("f,jkfg,g->jk", a, inv["II"], b)

    def second_moment(self, p: np.ndarray) -> np.ndarray:
        """R2 = int rho r r^T dV with r = rho0 + N p (kg m^2), body frame."""
        inv = self.invariants
        Jp = inv["J"] @ p
        return inv["I0"] + Jp + Jp.T + np.einsum("f,klfg,g->kl", p, inv["II"], p)

    def mass_matrix(self, p: np.ndarray, A0: np.ndarray) -> np.ndarray:
        """M_v of Eq. 66 on v = [r_C', omega^b, p'], a (6 + ndof) square matrix."""
        inv = self.invariants
        nf = self.ndof
        M = np.zeros((6 + nf, 6 + nf))
        St = self.first_moment(p)
        R2 = self.second_moment(p)
        M[0:3, 0:3] = inv["m"] * np.eye(3)
        M[0:3, 3:6] = -A0 @ skew(St)
        M[0:3, 6:] = A0 @ inv["Sbar"]
        M[3:6, 3:6] = np.trace(R2) * np.eye(3) - R2
        # int rho (-A0 r~)^T A0 N dV = int rho r~ N dV: row i = eps_ijk int rho r_j N_k
        P = inv["J"] + np.einsum("f,jkfg->jkg", p, inv["II"])
        M[3:6, 6:] = np.array([P[1, 2] - P[2, 1], P[2, 0] - P[0, 2], P[0, 1] - P[1, 0]])
        M[6:, 6:] = inv["Mff"]
        M[3:6, 0:3] = M[0:3, 3:6].T
        M[6:, 0:3] = M[0:3, 6:].T
        M[6:, 3:6] = M[3:6, 6:].T
        return M

    def quadratic_velocity(self, p: np.ndarray, pdot: np.ndarray, omega: np.ndarray, A0: np.ndarray) -> np.ndarray:
        """Q_v = -int rho S^T s dV (Eq. 67), s = A0 (w~ w~ r + 2 w~ N p') (Eq. 56)."""
        inv = self.invariants
        W = skew(omega)
        St = self.first_moment(p)
        R2 = self.second_moment(p)
        udot_mean = inv["Sbar"] @ pdot
        Q = np.empty(6 + self.ndof)
        Q[0:3] = -A0 @ (W @ W @ St + 2.0 * W @ udot_mean)
        inertia = np.trace(R2) * np.eye(3) - R2
        G = self._moments(p, pdot)  # int rho r_j udot_k
        Q[3:6] = -np.cross(omega, inertia @ omega) - 2.0 * (omega * np.trace(G) - G.T @ omega)
        # -int rho N^T (W W r + 2 W N p'): sum_kl A_kl int rho N_k^T r_l
        WW = W @ W
        Nr = np.einsum("kl,lkf->f", WW, inv["J"]) + np.einsum("kl,klfg,g->f", WW, inv["II"], p)
        Q[6:] = -Nr - 2.0 * np.einsum("kl,klfg,g->f", W, inv["II"], pdot)
        return Q

    def gravity(self, p: np.ndarray, A0: np.ndarray, g: np.ndarray) -> np.ndarray:
        """Q_g = int rho S^T g dV (Eq. 67)."""
        gb = A0.T @ g
        Q = np.empty(6 + self.ndof)
        Q[0:3] = self.invariants["m"] * g
        Q[3:6] = np.cross(self.first_moment(p), gb)
        Q[6:] = self.invariants["Sbar"].T @ gb
        return Q

    # ---------------------------------------------------------------- stations
    def displacement_row(self, x: float, y: float = 0.0, z: float = 0.0) -> np.ndarray:
        """N(x, y, z) over p (3 x ndof): u^b = N p at the point (Eq. 43); computed once per point."""
        key = ("displacement", float(x), float(y), float(z))
        if key not in self._rows:
            e, xi = self.locate(x)
            self._rows[key] = self._scatter(e, displacement_matrix(line_shapes(np.array([xi]), self.element_length),
                                                                   0, y, z))
        return self._rows[key]

    def rotation_row(self, x: float) -> np.ndarray:
        """Rows (3 x ndof) of the section's small rotation (theta_tau, -w0', v0') in the body
        frame at x: the rotation phi with u = phi x (0, y, z) in Eq. 43; computed once per station."""
        key = ("rotation", float(x))
        if key not in self._rows:
            e, xi = self.locate(x)
            sh = line_shapes(np.array([xi]), self.element_length)
            self._rows[key] = np.array([self._scatter(e, sh["N4"][0]), -self._scatter(e, sh["N3x"][0]),
                                        self._scatter(e, sh["N2x"][0])])
        return self._rows[key]

    def surface_strain(self, p: np.ndarray, x: float, y: float, z: float) -> float:
        """Fibre strain eps = eps0 - y_b v0'' - z_b w0'' at the section point (y, z) (m, on the local
        section axes m', n' of station x; (y_b, z_b) its body coordinates) (eps0 as in :meth:`axial_strain`):
        the curvatures resolved on the local principal axes."""
        return float(self.surface_strains_of_states(p[None, :], x, y, z)[0])

    def surface_strains_of_states(self, P: np.ndarray, x: float, y: float, z: float) -> np.ndarray:
        """:meth:`surface_strain` at one section point for each row of P (states x ndof): the
        strain gauge's reading over a run's records in one product."""
        # one look-up of the station's rows: the axial row does not depend on (y, z), so this is
        # axial_strain(p, x) + bending @ p, with the element-mean eps0 of element e alone
        e, axial, bending = self._station_rows(x, y, z)
        if self.geometric_stiffening:
            t = self.centre_line_table
            eps0 = P @ t["mean_stretch"][e] + 0.5 * np.einsum("ki,ij,kj->k", P, t["mean_slope2"][e], P)
        else:
            eps0 = P @ axial
        return eps0 + P @ bending

    def strain_polynomial(self, x: float, y: float, z: float) -> tuple[np.ndarray, np.ndarray]:
        """(c, Q) with :meth:`surface_strain` eps(p) = c . p + p^T Q p / 2 at the station x and
        section point (y, z) (Q = 0 without geometric stiffening; with it, the element-mean
        strain's second-order part): what a controller that reads the strain needs."""
        e, axial, bending = self._station_rows(x, y, z)
        if not self.geometric_stiffening:
            return axial + bending, np.zeros((axial.size, axial.size))
        t = self.centre_line_table
        return t["mean_stretch"][e] + bending, np.array(t["mean_slope2"][e], dtype=float)

    def strain_row(self, x: float, y: float, z: float) -> np.ndarray:
        """The row of eps = u0' - y_b v0'' - z_b w0'' (the linear FFR fibre strain) over p, (y, z) on the
        local section axes as in :meth:`surface_strain`."""
        _, axial, bending = self._station_rows(x, y, z)
        return axial + bending
