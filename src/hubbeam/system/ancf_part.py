"""An ANCF beam on the hub (paper Secs. 2 and 4): its mount, clamp, states, measures and
compiled terms.

:class:`AncfPart` supplies what the system needs around the equations: initial and
steadily rotating states, the rotation chart and the measured quantities. The kind "ANCF
beams" (:data:`KIND`, :mod:`hubbeam.system.terms`) packs every ANCF beam of a system
(:class:`AncfBeams`) and gives the compiled equations their terms: elastic forces with
structural damping, rotary inertia, drag (:mod:`hubbeam.elements.ancf.kernels`),
translational mass, gravity and tip loads (:func:`applied_load`), and the clamp of each
root to the hub (:mod:`hubbeam.system.clamp`); their energies, dissipated power and tip
displacements.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from hubbeam.elements.ancf import kernels
from hubbeam.elements.ancf.chart import frame_from_director, remap_chart
from hubbeam.elements.ancf.frame import section_frame
from hubbeam.elements.ancf.strain import strain_measures
from hubbeam.system import terms
from hubbeam.system.assembly import add_element_blocks_banded, add_entry
from hubbeam.system.beam import NODE_DOFS, AncfBeam
from hubbeam.system.clamp import add_clamp_jacobian, clamp_constraints, clamp_equations, clamp_residual, clamp_work
from hubbeam.system.loads import tip_moment_terms
from hubbeam.system.mount import Mount, tip_from_mount
from hubbeam.system.parts import ChartedBeamPart

if TYPE_CHECKING:
    from hubbeam.system.tip_body import TipBody

#: the hub's axis j0 (global)
AXIS = np.array([0.0, 1.0, 0.0])


@dataclass(eq=False)
class AncfPart(ChartedBeamPart):
    """An ANCF beam (:class:`~hubbeam.system.beam.AncfBeam`) on its mount, with an optional
    tip body (on its tip node: :meth:`tip_node`, the kind of :mod:`hubbeam.system.tip_body`)
    and constant tip loads (global directions: force N at the tip centroid, moment N m)."""

    beam: AncfBeam
    mount: Mount = field(default_factory=Mount)
    tip_body: TipBody | None = None
    tip_force: np.ndarray = field(default_factory=lambda: np.zeros(3))
    tip_moment: np.ndarray = field(default_factory=lambda: np.zeros(3))
    name: str = "beam1"

    formulation = "ancf"
    root_dofs = 7  # r0 (3), r0' (3), theta_1 of the root node

    @property
    def ndof(self) -> int:
        return self.beam.ndof

    @property
    def tip(self) -> slice:
        """The tip node's 8 coordinates in q."""
        return self.beam.node_slice(-1)

    def tip_node(self) -> slice:
        return self.tip

    # ------------------------------------------------------------ states
    def initial_state(self, theta: float) -> tuple[np.ndarray, np.ndarray]:
        return self.beam.straight_state(self.mount.root(theta), self.mount.frame(theta))

    def clamp(self, q, chart, theta):
        return clamp_constraints(np.concatenate([[theta], q[0:7]]), self.mount.params(), chart)

    def steady_rotation_rates(self, q, chart, omega):
        """r and r' move with w x (.), accelerate with w x (w x .) (w = -omega j0). theta_1 is
        measured from the chart's untwisted frame; in general theta_1' = w.tau + d.(tau x (w x
        tau))/(1 + d.tau); in the axis chart (d = w/|w|) that is exactly omega at every point,
        so d(theta_1')/dt = 0. Other charts are refused."""
        if not np.allclose(chart[:, 0], -AXIS, atol=1e-12):
            raise ValueError("steady rotation rates need the axis chart (director -j0); see axis_chart")
        w = -omega * AXIS
        nodes = q.reshape(self.beam.nodes, NODE_DOFS)
        vel = np.zeros_like(nodes)
        acc = np.zeros_like(nodes)
        for k in (0, 3):
            vel[:, k : k + 3] = np.cross(w, nodes[:, k : k + 3])
            acc[:, k : k + 3] = np.cross(w, vel[:, k : k + 3])
        vel[:, 6] = omega
        return vel.ravel(), acc.ravel()

    # ------------------------------------------------------------ charts
    def chart_margin(self, q, chart) -> float:
        return self.beam.chart_margin(q, chart)

    def better_chart(self, q) -> np.ndarray:
        return self.beam.better_chart(q)

    def remap(self, q, chart, new_chart) -> np.ndarray:
        """Only theta_1 and theta_1' change."""
        beam = self.beam
        nodes = remap_chart(q.reshape(beam.nodes, NODE_DOFS), beam.node_tangent_rates(q), chart, new_chart)
        return nodes.ravel()

    def axis_chart(self) -> np.ndarray:
        """Director d = -j0: the beam stays near the plane normal to the hub axis while the hub
        sweeps it through every direction of that plane; each of those tangents is 90 deg from
        the singular direction (+j0), and a rigid rotation about the axis advances theta_1 by
        exactly the hub angle (see :meth:`steady_rotation_rates`)."""
        return frame_from_director(-AXIS, hint=np.array([1.0, 0.0, 0.0]))

    # ------------------------------------------------------------ measured quantities
    def tip_position(self, q) -> np.ndarray:
        return q[self.tip][0:3].copy()

    def surface_strain(self, q, chart, station, y, z) -> float:
        return self.beam.surface_strain(q, chart, station, y, z)

    def frame_at(self, q, chart, station) -> np.ndarray:
        return self.beam.frame_at(q, chart, station)

    def section_motion(self, q, chart, u, stations):
        """The section frame R = F [tau m n](U, theta_1) (U = F^T r0') and its angular velocity
        R omega, where omega (section axes) is the curvature function of
        :func:`~hubbeam.elements.ancf.strain.strain_measures` evaluated at
        (U, F^T d r0'/dt, theta_1, d theta_1/dt) (as in the rotary inertia kernel); the centre
        line's velocity is the Hermite interpolation of u's positions and slopes."""
        beam = self.beam
        n = len(stations)
        frames, vel, omega = np.empty((n, 3, 3)), np.empty((n, 3)), np.empty((n, 3))
        F = np.asarray(chart, dtype=float)
        for i, x in enumerate(stations):
            _, r1, _, phi, _ = beam.interpolate(q, x)
            vel[i], v1, _, phi_dot, _ = beam.interpolate(u, x)
            U = F.T @ r1
            frames[i] = F @ np.column_stack(section_frame(U, phi))
            omega[i] = frames[i] @ np.array(strain_measures(U, F.T @ v1, phi, phi_dot)[1:4])
        return frames, vel, omega

    def frames_at(self, q, chart, stations) -> np.ndarray:
        return self.beam.frames_at(q, chart, stations)

    def surface_strains(self, q, chart, stations, y, z) -> np.ndarray:
        return self.beam.surface_strains(q, chart, stations, y, z)

    def centre_line_at(self, q, chart, stations) -> np.ndarray:
        return self.beam.interpolate_at(q, stations)[0]


# ================================================================ compiled terms: the kind "ANCF beams"
#: half-bandwidth of an ANCF beam block (16 x 16 element blocks; the clamp rows reach 12 ahead)
BANDWIDTH = 15


class AncfBeams(NamedTuple):
    """Every ANCF beam of a system, one row each, zero-padded to the largest (padding Gauss
    points repeat a real one with weight 0; padding elements are never read)."""

    index: np.ndarray  # int64 (nb,): the beam's place among all beams (its chart in F, its energy row)
    x0: np.ndarray  # int64 (nb,): where its coordinates start in x (the layout's)
    lambda0: np.ndarray  # int64 (nb,): where its clamp multipliers start in lambda (the layout's)
    elements: np.ndarray  # int64 (nb,)
    S: np.ndarray  # (nb, ng, 4) Hermite functions at the Gauss points, and derivatives (1/m, 1/m^2)
    dS: np.ndarray
    d2S: np.ndarray
    w: np.ndarray  # (nb, ng) Gauss weights on [0, 1] (0 on padding points)
    element_length: np.ndarray  # (nb,) m
    stiffness: np.ndarray  # (nb, n_el, ng, 4) EA, GJ_t, EI_y, EI_z at each Gauss point (N, N m^2)
    reference: np.ndarray  # (nb, n_el, ng, 4) strains of the stress-free (pretwisted) state (1, 1/m)
    structural_damping: np.ndarray  # (nb,) c of the Kelvin-Voigt resultants c D e_dot (s)
    trans_mass: np.ndarray  # (nb, n_el, 16, 16) translational element masses (kg)
    inertia: np.ndarray  # (nb, n_el, ng, 3) rho (I_y + I_z), rho I_y, rho I_z (kg m)
    width: np.ndarray  # (nb, n_el, ng) frontal width of the drag (m)
    mount: np.ndarray  # (nb, 4) radius, twist, azimuth, precone (m, rad)
    tip_force: np.ndarray  # (nb, 3) N
    tip_moment: np.ndarray  # (nb, 3) N m
    gravity_load: np.ndarray  # (nb, nq) generalized gravity force of the beam's own mass (N)


def pack_ancf_beams(system, layout) -> AncfBeams | None:
    """The :class:`AncfBeams` of ``system`` placed by ``layout`` (None without ANCF beams)."""
    ancf = [(k, b) for k, b in enumerate(system.beams) if isinstance(b, AncfPart)]
    if not ancf:
        return None
    nb = len(ancf)
    ng = max(b.beam.gauss_points for _, b in ancf)
    ne = max(b.beam.elements for _, b in ancf)
    S, dS, d2S = np.zeros((nb, ng, 4)), np.zeros((nb, ng, 4)), np.zeros((nb, ng, 4))
    w = np.zeros((nb, ng))
    stiffness, reference = np.zeros((nb, ne, ng, 4)), np.zeros((nb, ne, ng, 4))
    inertia, width = np.zeros((nb, ne, ng, 3)), np.zeros((nb, ne, ng))
    trans_mass = np.zeros((nb, ne, 16, 16))
    gravity_load = np.zeros((nb, NODE_DOFS * (ne + 1)))
    for i, (_, b) in enumerate(ancf):
        beam = b.beam
        tS, tdS, td2S, tw = beam._tables
        n, m = tw.shape[0], beam.elements
        for arr, table in ((S, tS), (dS, tdS), (d2S, td2S)):
            arr[i, :n] = table
            arr[i, n:] = table[0]
        w[i, :n] = tw
        stiffness[i, :m, :n] = beam._stiffness
        reference[i, :m, :n] = beam._reference
        inertia[i, :m, :n] = beam._inertia
        width[i, :m, :n] = beam._width
        trans_mass[i, :m] = beam._trans_mass
        gravity_load[i, : beam.ndof] = beam.gravity_load(system.gravity)
    ints = lambda values: np.array(values, dtype=np.int64)  # noqa: E731
    rows = lambda values, width: np.array(values, dtype=float).reshape(nb, width)  # noqa: E731
    return AncfBeams(ints([k for k, _ in ancf]), ints([layout.beam_x(k).start for k, _ in ancf]),
                     ints([layout.clamp_lambda(k).start for k, _ in ancf]), ints([b.beam.elements for _, b in ancf]),
                     S, dS, d2S, w, np.array([b.beam.element_length for _, b in ancf], dtype=float),
                     stiffness, reference, np.array([b.beam.structural_damping for _, b in ancf], dtype=float),
                     trans_mass, inertia, width, rows([b.mount.params() for _, b in ancf], 4),
                     rows([b.tip_force for _, b in ancf], 3), rows([b.tip_moment for _, b in ancf], 3), gravity_load)


@njit(cache=True)
def ancf_beam(pack, k, F, x, v):
    """ANCF beam k's place and state: (x0 (where its coordinates start in x), nq (their
    number), its chart, q, q')."""
    nq = NODE_DOFS * (pack.elements[k] + 1)
    x0 = pack.x0[k]
    return x0, nq, F[pack.index[k]], x[x0 : x0 + nq], v[x0 : x0 + nq]


@njit(cache=True)
def applied_load(pack, k, q, F, factor, Q, tip_jacobian):
    """Q = ``factor`` times the applied generalized force on beam k's coordinates q: gravity
    on its own mass (Eq. 32), the tip force and the tip moment
    (:func:`hubbeam.system.loads.tip_moment_terms`), and tip_jacobian (4 x 3) = ``factor``
    d Q / d r0'(L) of the moment on the tip's (r0', theta_1) rows (zero without a moment)."""
    nq = q.shape[0]
    tip = nq - NODE_DOFS
    g = pack.gravity_load[k]
    for j in range(nq):
        Q[j] = factor * g[j]
    for i in range(3):
        Q[tip + i] += factor * pack.tip_force[k, i]
    tip_jacobian[:, :] = 0.0
    moment = pack.tip_moment[k]
    if moment[0] == 0.0 and moment[1] == 0.0 and moment[2] == 0.0:
        return
    tQ = np.empty(4)
    tip_moment_terms(q[tip + 3 : tip + 6], moment, F, tQ, tip_jacobian)
    for i in range(4):
        Q[tip + 3 + i] += factor * tQ[i]
        for j in range(3):
            tip_jacobian[i, j] *= factor


def ancf_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                   want_matrix, res, ab, brow, bcol, bb):
    """Every ANCF beam's rows (:mod:`hubbeam.system.terms`): coef_k (M(q) acc + f_int - Q_ext
    - Q_v - Q_d + Phi_q^T lambda) on its coordinates, scale Phi of its clamp; the matrix
    coef_m M + coef_c C + coef_k (K - dQ/dq + lambda . d2 Phi) (the small velocity derivative
    of the rotary-inertia force and the q-derivative of M(q) acc left out: they slow Newton
    slightly and never change the answer; the matrix is exact at rest). f_int holds the
    structural damping (Kelvin-Voigt resultants c D e_dot), whose matrix enters with coef_c."""
    zx, zl, ku = ctx.z_of_x, ctx.z_of_lambda, ctx.ku
    z_theta = zx[ctx.theta]
    theta = x[ctx.theta]
    margin = 2.0
    power = 0.0
    hub_force = 0.0
    phi, jac, hess, lam_k = clamp_work()
    c = np.empty(8)
    tip_jacobian = np.empty((4, 3))
    no_blocks = np.empty((0, 16, 16))
    for k in range(pack.index.shape[0]):
        n_el = pack.elements[k]
        x0, nq, Fk, q, qd = ancf_beam(pack, k, F, x, v)
        l0 = pack.lambda0[k]
        qa = acc[x0 : x0 + nq]
        S, dS, d2S, w, le = pack.S[k], pack.dS[k], pack.d2S[k], pack.w[k], pack.element_length[k]
        blocks = np.zeros((n_el if want_matrix else 0, 16, 16))
        fq = np.empty(nq)
        # the elastic matrix path adds the rotary mass coef_m M_rot too (one chart-to-global rotation)
        _, mk, pk = kernels.elastic_rotary_kernel(q, qd, Fk, le, S, dS, d2S, w, pack.stiffness[k], pack.reference[k],
                                                  pack.structural_damping[k], pack.inertia[k][:n_el], coef_m, coef_c,
                                                  coef_k, fq, blocks)
        margin = min(margin, mk)
        power += pk
        if not mk > terms.CHART_SINGULAR:
            return 0.0, margin, 0.0
        term = np.empty(nq)
        kernels.rotary_inertia_kernel(q, qd, qa, Fk, le, S, dS, w, pack.inertia[k], coef_m, term, no_blocks)
        for j in range(nq):
            fq[j] -= term[j]  # -(Q_v - M_rot acc)
        if ctx.drag[0] != 0.0 or ctx.drag[1] != 0.0:
            power += kernels.drag_kernel(qd, le, S, w, pack.width[k], ctx.drag[0], ctx.drag[1], coef_c, term, blocks)
            for j in range(nq):
                fq[j] -= term[j]
        kernels.translational_mass_product(pack.trans_mass[k], qa, fq)
        applied_load(pack, k, q, Fk, load_factor, term, tip_jacobian)
        for j in range(nq):
            fq[j] -= term[j]
        # clamp of the root to the hub
        c[0] = theta
        for j in range(7):
            c[1 + j] = q[j]
        for i in range(6):
            lam_k[i] = lam[l0 + i]
        clamp_equations(c, pack.mount[k], Fk, lam_k, phi, jac, hess)
        hub_force += clamp_residual(lam_k, phi, jac, 7, scale, zl, l0, fq, res)
        for j in range(nq):
            res[zx[x0 + j]] += coef_k * fq[j]
        if not want_matrix:
            continue
        # the tip moment's load stiffness on the tip's (r0', theta_1) rows and r0' columns
        for i in range(4):
            for j in range(3):
                blocks[n_el - 1, 11 + i, 11 + j] -= coef_k * tip_jacobian[i, j]
        kernels.add_translational_mass(pack.trans_mass[k], n_el, coef_m, blocks)
        q_start = zx[x0]  # z index of the beam's first coordinate
        add_element_blocks_banded(ab, blocks, q_start - ctx.border, ku, 1.0)
        # clamp: Jacobian in the multiplier rows and columns, Hessian on [theta, root coordinates]
        add_clamp_jacobian(ab, brow, bcol, bb, ku, jac, 7, scale, zl, l0, q_start, z_theta)
        add_entry(ab, brow, bcol, bb, ku, z_theta, z_theta, coef_k * hess[0, 0])
        for a in range(7):
            add_entry(ab, brow, bcol, bb, ku, z_theta, q_start + a, coef_k * hess[0, 1 + a])
            add_entry(ab, brow, bcol, bb, ku, q_start + a, z_theta, coef_k * hess[1 + a, 0])
            for b in range(7):
                add_entry(ab, brow, bcol, bb, ku, q_start + a, q_start + b, coef_k * hess[1 + a, 1 + b])
    return hub_force, margin, power


def ancf_energies(pack, ctx, F, x, v, beams):
    """Kinetic (translational and rotary), strain and gravity energy of every ANCF beam (J)."""
    for k in range(pack.index.shape[0]):
        _, nq, Fk, q, qd = ancf_beam(pack, k, F, x, v)
        S, dS, d2S, w, le = pack.S[k], pack.dS[k], pack.d2S[k], pack.w[k], pack.element_length[k]
        term = np.zeros(nq)
        kernels.translational_mass_product(pack.trans_mass[k], qd, term)
        kinetic = 0.0
        potential = 0.0
        g = pack.gravity_load[k]
        for j in range(nq):
            kinetic += 0.5 * qd[j] * term[j]
            potential -= g[j] * q[j]
        kinetic += kernels.rotary_inertia_kernel(q, qd, np.zeros(nq), Fk, le, S, dS, w, pack.inertia[k], 0.0, term,
                                                 np.empty((0, 16, 16)))
        strain = kernels.elastic_kernel(q, qd, Fk, le, S, dS, d2S, w, pack.stiffness[k], pack.reference[k], 0.0, 0.0,
                                        0.0, term, np.empty((0, 16, 16)))[0]
        terms.add_beam_energy(beams, pack.index[k], kinetic, strain, potential)
    return 0.0, 0.0, 0.0


def ancf_power(pack, ctx, F, x, v):
    """Power of the drag of Eq. 37 and of the structural damping on every ANCF beam (W)."""
    power = 0.0
    for k in range(pack.index.shape[0]):
        _, nq, Fk, q, qd = ancf_beam(pack, k, F, x, v)
        force = np.empty(nq)
        power += kernels.drag_kernel(qd, pack.element_length[k], pack.S[k], pack.w[k], pack.width[k],
                                     ctx.drag[0], ctx.drag[1], 0.0, force, np.empty((0, 16, 16)))
        if pack.structural_damping[k] > 0.0:
            power += kernels.elastic_kernel(q, qd, Fk, pack.element_length[k], pack.S[k], pack.dS[k], pack.d2S[k],
                                            pack.w[k], pack.stiffness[k], pack.reference[k],
                                            pack.structural_damping[k], 0.0, 0.0, force, np.empty((0, 16, 16)))[2]
    return power


def ancf_tips(pack, ctx, x, out):
    """Each ANCF beam's tip centroid displacement in its hub frame (m)."""
    theta = x[ctx.theta]
    tip_at = np.empty(3)
    for k in range(pack.index.shape[0]):
        tip = pack.x0[k] + NODE_DOFS * pack.elements[k]
        for i in range(3):
            tip_at[i] = x[tip + i]
        tip_from_mount(pack.mount[k], theta, pack.element_length[k] * pack.elements[k], tip_at, out[pack.index[k]])


KIND = terms.register(AncfBeams, pack_ancf_beams, ancf_equations, ancf_energies, ancf_power, ancf_tips,
                      bandwidth=lambda system: BANDWIDTH if any(isinstance(b, AncfPart) for b in system.beams) else 1)
