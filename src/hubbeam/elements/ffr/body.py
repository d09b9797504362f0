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
from hubbeam.elements.section import Section


def skew(a: np.ndarray) -> np.ndarray:
    """The matrix of a x (.)."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


@dataclass
class FfrBeam:
    """n equal FFR elements over a beam of ``length`` (m) with one ``section``; with ``modes``,
    reduced to that many clamped-free modes (``frequencies_hz``, ``max_frequency_hz``, ``basis``)."""

    length: float
    elements: int
    section: Section
    gauss_points: int = 4
    geometric_stiffening: bool = False
    #: a rigid body on the tip section (:class:`~hubbeam.system.tip_body.TipBody`), or None
    tip_body: object = None
    #: None: the nodal coordinates p; N: the N lowest clamped-free modes (:mod:`~hubbeam.elements.ffr.modal`)
    modes: int | None = None
    invariants: dict = field(init=False, repr=False)
    _rows: dict = field(init=False, repr=False, compare=False, default_factory=dict)  # station rows, once each

    def __post_init__(self) -> None:
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

    # ---------------------------------------------------------------- invariants
    def _inertia_invariants(self) -> dict:
        sec = self.section
        xg, wx = gauss_legendre(self.gauss_points)
        sg, ws = gauss_legendre(2)
        ys, zs = (sg - 0.5) * sec.width, (sg - 0.5) * sec.thickness
        l = self.element_length
        shapes = line_shapes(xg, l)
        N_list, r0_list, w_list = [], [], []
        for e in range(self.elements):
            for k, (xi, wk) in enumerate(zip(xg, wx)):
                for y, wy in zip(ys, ws):
                    for z, wz in zip(zs, ws):
                        N_list.append(self._scatter(e, displacement_matrix(shapes, k, y, z)))
                        r0_list.append([(e + xi) * l, y, z])
                        w_list.append(sec.density * wk * l * wy * sec.width * wz * sec.thickness)
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
        """K of Eq. 61: EA u0'^2 + EI_z v0''^2 + EI_y w0''^2 + GJ theta'^2, exact with 4 Gauss points."""
        EA, GJ, EIy, EIz = self.section.stiffness
        xg, wx = gauss_legendre(4)
        l = self.element_length
        sh = line_shapes(xg, l)
        Ka = l * EA * np.einsum("q,qi,qj->ij", wx, sh["N1x"], sh["N1x"])
        Ke = Ka + l * (EIz * np.einsum("q,qi,qj->ij", wx, sh["N2xx"], sh["N2xx"])
                       + EIy * np.einsum("q,qi,qj->ij", wx, sh["N3xx"], sh["N3xx"])
                       + GJ * np.einsum("q,qi,qj->ij", wx, sh["N4x"], sh["N4x"]))
        K = np.zeros((self.nodal_ndof, self.nodal_ndof))
        self._axial_stiffness = np.zeros((self.nodal_ndof, self.nodal_ndof))
        for e in range(self.elements):
            dofs = self.element_dofs(e)
            keep = dofs >= 0
            K[np.ix_(dofs[keep], dofs[keep])] += Ke[np.ix_(keep, keep)]
            self._axial_stiffness[np.ix_(dofs[keep], dofs[keep])] += Ka[np.ix_(keep, keep)]
        return K

    def _centre_line_table(self) -> dict:
        """Gauss points along the centre line (4 per element): weights (m), x, and N(x, 0, 0)
        over p; and per element the rows of the element-mean axial strain: a_e (the mean of
        u0') and G_e = (1/l) int (N2x^T N2x + N3x^T N3x) dx (exact: 4 points)."""
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
        return {"N": np.array(N), "x": np.array(xs), "w": np.array(ws), "mean_stretch": a, "mean_slope2": G}

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
        The axial energy therefore uses the element-mean strain, EA l eps_e^2 / 2 per
        element, which the linear u0 can match exactly. Bending and torsion keep Eq. 61.
        """
        K = self.stiffness_matrix
        if not self.geometric_stiffening:
            f = K @ p
            return 0.5 * p @ f, f, K
        EAl = self.section.stiffness[0] * self.element_length
        K_rest = K - self._axial_stiffness
        eps, deps = self._mean_axial_strain(p)
        f = K_rest @ p + EAl * deps.T @ eps
        Kt = K_rest + EAl * (deps.T @ deps + np.einsum("e,efg->fg", eps, self.centre_line_table["mean_slope2"]))
        U = 0.5 * p @ (K_rest @ p) + 0.5 * EAl * eps @ eps
        return U, f, Kt

    def _station_rows(self, x: float, y: float = 0.0, z: float = 0.0):
        """(element, row of u0', row of -y v0'' - z w0'') over the coordinates at the station x and
        section point (y, z), computed once per station (sensors ask at every output time)."""
        key = ("strain", float(x), float(y), float(z))
        if key not in self._rows:
            e, xi = self.locate(x)
            sh = line_shapes(np.array([xi]), self.element_length)
            self._rows[key] = (e, self._scatter(e, sh["N1x"][0]),
                               self._scatter(e, -y * sh["N2xx"][0] - z * sh["N3xx"][0]))
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
        """Fibre strain eps = eps0 - y v0'' - z w0'' at (x, y, z) (eps0 as in :meth:`axial_strain`)."""
        _, _, bending = self._station_rows(x, y, z)
        return self.axial_strain(p, x) + float(bending @ p)

    def strain_row(self, x: float, y: float, z: float) -> np.ndarray:
        """The row of eps = u0' - y v0'' - z w0'' (the linear FFR fibre strain) over p."""
        e, xi = self.locate(x)
        sh = line_shapes(np.array([xi]), self.element_length)
        return self._scatter(e, sh["N1x"][0] - y * sh["N2xx"][0] - z * sh["N3xx"][0])
