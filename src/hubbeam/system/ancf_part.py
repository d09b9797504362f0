"""An ANCF beam on its frame (paper Secs. 2 and 4): its mount, clamp, states, measures and
compiled terms.

:class:`AncfPart` supplies what the system needs around the equations: initial and
steadily rotating states, the rotation chart and the measured quantities. The kind "ANCF
beams" (:data:`KIND`, :mod:`hubbeam.system.terms`) packs every ANCF beam of a system
(:class:`AncfBeams`) and gives the compiled equations their terms: elastic forces with
structural damping (:mod:`hubbeam.elements.ancf.elastic`), rotary inertia
(:mod:`hubbeam.elements.ancf.inertia`), drag (:mod:`hubbeam.elements.ancf.loads`),
translational mass, gravity and tip loads (:func:`applied_load`), and the clamp of each
root to its root frame (:mod:`hubbeam.system.clamp`); their energies, dissipated power, tip
displacements and momenta.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from hubbeam.elements.ancf import elastic, inertia, loads
from hubbeam.elements.ancf.chart import frame_from_director, remap_chart
from hubbeam.elements.ancf.frame import section_frame
from hubbeam.elements.ancf.strain import strain_measures
from hubbeam.elements.section import COLUMN
from hubbeam.system import terms
from hubbeam.system.assembly import add_element_blocks_banded
from hubbeam.system.beam import NODE_DOFS, AncfBeam
from hubbeam.system.clamp import ROOT_COORDINATES, add_clamp_matrix, clamp_residual, frame_clamp
from hubbeam.system.chains import Chain, LinkKind, ancf_tip, constant
from hubbeam.system.frame_motions import displacement_in_reference
from hubbeam.system.frames import chain_state
from hubbeam.system.loads import tip_moment_terms
from hubbeam.system.mount import Mount, about_axis
from hubbeam.system.parts import ChartedBeamPart

if TYPE_CHECKING:
    from hubbeam.system.tip_body import TipBody

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

    def tip_frame(self, x0: int, index: int, root: Chain) -> Chain:
        """The tip node's section frame (in this beam's chart ``index``: an ANCF_TIP link, a chain
        of its own) turned back by the twist and the tip pretwist."""
        untwist = self.mount.twist + float(self.properties(self.length)[COLUMN["pretwist"]])
        return Chain((ancf_tip(x0 + self.tip.start, index), constant(rotation=about_axis(untwist))))

    # ------------------------------------------------------------ states
    def initial_state(self, root: np.ndarray, frame: np.ndarray, reference: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The undeformed, straight beam from ``root`` (m) with root section frame ``frame``
        (3 x 3, columns global): (q, chart), the chart chosen in the ``reference`` axes (the
        hub's at theta = 0), so that a turned model has the turned chart."""
        return self.beam.straight_state(root, frame, reference)

    def rigid_rates(self, q, chart, velocity, w, origin, acceleration=None):
        """(q', q'') of the beam moving rigidly: its points at velocity + w x (r - origin) (m/s;
        w rad/s, global), turning at w; accelerations w x (w x (r - origin)) + ``acceleration``
        for a steady rotation about an axis through ``origin`` (None: zero). r and r' move with
        w, theta_1 at the chart's rate w.tau + d.(w - tau (tau.w))/(1 + d.tau) (which is exactly
        d.w at every point normal to the axis in the axis chart, director along w, so that
        d(theta_1')/dt = 0 there; other charts are refused for accelerations)."""
        w = np.asarray(w, dtype=float)
        nodes = q.reshape(self.beam.nodes, NODE_DOFS)
        vel = np.zeros_like(nodes)
        acc = np.zeros_like(nodes)
        rel = nodes[:, 0:3] - np.asarray(origin, dtype=float)
        vel[:, 0:3] = np.asarray(velocity, dtype=float) + np.cross(w, rel)
        vel[:, 3:6] = np.cross(w, nodes[:, 3:6])
        d = chart[:, 0]
        tau = nodes[:, 3:6] / np.linalg.norm(nodes[:, 3:6], axis=1)[:, None]
        dt = tau @ d
        tw = tau @ w
        vel[:, 6] = tw + (d @ w - dt * tw) / (1.0 + dt)
        if acceleration is not None:
            acc[:, 0:3] = np.cross(w, np.cross(w, rel)) + np.asarray(acceleration)
            acc[:, 3:6] = np.cross(w, np.cross(w, nodes[:, 3:6]))
            if np.any(w) and not np.allclose(np.cross(d, w), 0.0, atol=1e-12 * np.linalg.norm(w)):
                raise ValueError("steady rotation rates need the axis chart (director along the axis); see axis_chart")
        return vel.ravel(), acc.ravel()

    # ------------------------------------------------------------ charts
    def chart_margin(self, q, chart) -> float:
        return self.beam.chart_margin(q, chart)

    def better_chart(self, q, reference=None) -> np.ndarray:
        return self.beam.better_chart(q, reference)

    def remap(self, q, chart, new_chart) -> np.ndarray:
        """Only theta_1 and theta_1' change."""
        beam = self.beam
        nodes = remap_chart(q.reshape(beam.nodes, NODE_DOFS), beam.node_tangent_rates(q), chart, new_chart)
        return nodes.ravel()

    def axis_chart(self, axis=(0.0, 1.0, 0.0), hint=(1.0, 0.0, 0.0)) -> np.ndarray:
        """Director d = -axis (the hub's axis j_h, hint its i_h): the beam stays near the plane
        normal to the hub axis while the hub sweeps it through every direction of that plane;
        each of those tangents is 90 deg from the singular direction (+j_h), and a rigid rotation
        about the axis advances theta_1 by exactly the hub angle (see :meth:`rigid_rates`)."""
        return frame_from_director(-np.asarray(axis, dtype=float), hint=np.asarray(hint, dtype=float))

    # ------------------------------------------------------------ measured quantities
    def tip_position(self, q, frame=None) -> np.ndarray:
        return q[self.tip][0:3].copy()

    def surface_strain(self, q, chart, station, y, z) -> float:
        return self.beam.surface_strain(q, chart, station, y, z)

    def frame_at(self, q, chart, station, frame=None) -> np.ndarray:
        return self.beam.frame_at(q, chart, station)

    def section_motion(self, q, chart, u, stations, frame=None, rate=None):
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

    def frames_at(self, q, chart, stations, frame=None) -> np.ndarray:
        return self.beam.frames_at(q, chart, stations)

    def surface_strains(self, q, chart, stations, y, z) -> np.ndarray:
        return self.beam.surface_strains(q, chart, stations, y, z)

    def centre_line_at(self, q, chart, stations, frame=None) -> np.ndarray:
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
    chains: np.ndarray  # int64 (nb, 2): its root section frame's chain and its reference frame's
    #                     (the tip deflection's axes), :mod:`hubbeam.system.frames`
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
    twist: np.ndarray  # (nb,) rad: the root section's twist from its axis frame (the clamp's tangent normals)
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
    chains = np.array([(system.frames.root(k), system.frames.reference(k)) for k, _ in ancf],
                      dtype=np.int64).reshape(nb, 2)
    return AncfBeams(ints([k for k, _ in ancf]), ints([layout.beam_x(k).start for k, _ in ancf]),
                     ints([layout.clamp_lambda(k).start for k, _ in ancf]), chains,
                     ints([b.beam.elements for _, b in ancf]),
                     S, dS, d2S, w, np.array([b.beam.element_length for _, b in ancf], dtype=float),
                     stiffness, reference, np.array([b.beam.structural_damping for _, b in ancf], dtype=float),
                     trans_mass, inertia, width, np.array([b.mount.twist for _, b in ancf], dtype=float),
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
    - Q_v - Q_d + Phi_q^T lambda) on its coordinates, scale Phi of its clamp to its root frame
    (:mod:`hubbeam.system.clamp`) and coef_k Phi_c^T lambda on the frame's coordinates; the
    matrix coef_m M + coef_c C + coef_k (K - dQ/dq + lambda . d2 Phi) (the small velocity
    derivative of the rotary-inertia force and the q-derivative of M(q) acc left out: they slow
    Newton slightly and never change the answer; the matrix is exact at rest). f_int holds the
    structural damping (Kelvin-Voigt resultants c D e_dot), whose matrix enters with coef_c."""
    zx, zl, ku = ctx.z_of_x, ctx.z_of_lambda, ctx.ku
    margin = 2.0
    power = 0.0
    phi = np.empty(6)
    lam_k = np.empty(6)
    tip_jacobian = np.empty((4, 3))
    no_blocks = np.empty((0, 16, 16))
    order = 2 if want_matrix else 1
    for k in range(pack.index.shape[0]):
        n_el = pack.elements[k]
        x0, nq, Fk, q, qd = ancf_beam(pack, k, F, x, v)
        l0 = pack.lambda0[k]
        qa = acc[x0 : x0 + nq]
        S, dS, d2S, w, le = pack.S[k], pack.dS[k], pack.d2S[k], pack.w[k], pack.element_length[k]
        blocks = np.zeros((n_el if want_matrix else 0, 16, 16))
        fq = np.empty(nq)
        # the elastic matrix path adds the rotary mass coef_m M_rot too (one chart-to-global rotation)
        _, mk, pk = elastic.elastic_rotary_kernel(q, qd, Fk, le, S, dS, d2S, w, pack.stiffness[k], pack.reference[k],
                                                  pack.structural_damping[k], pack.inertia[k][:n_el], coef_m, coef_c,
                                                  coef_k, fq, blocks)
        margin = min(margin, mk)
        power += pk
        if not mk > terms.CHART_SINGULAR:
            return margin, 0.0
        term = np.empty(nq)
        inertia.rotary_inertia_kernel(q, qd, qa, Fk, le, S, dS, w, pack.inertia[k], coef_m, term, no_blocks)
        for j in range(nq):
            fq[j] -= term[j]  # -(Q_v - M_rot acc)
        if ctx.drag[0] != 0.0 or ctx.drag[1] != 0.0:
            power += loads.drag_kernel(qd, le, S, w, pack.width[k], ctx.drag[0], ctx.drag[1], coef_c, term, blocks)
            for j in range(nq):
                fq[j] -= term[j]
        inertia.translational_mass_product(pack.trans_mass[k], qa, fq)
        applied_load(pack, k, q, Fk, load_factor, term, tip_jacobian)
        for j in range(nq):
            res[zx[x0 + j]] += coef_k * (fq[j] - term[j])
        # clamp of the root to its frame
        cols, r, R, Jr, Jw, Hr, Hw = chain_state(ctx.chains, pack.chains[k, 0])
        nc = cols.shape[0]
        jac = np.empty((6, nc + ROOT_COORDINATES))
        hess = np.empty((nc + ROOT_COORDINATES, nc + ROOT_COORDINATES))
        for i in range(6):
            lam_k[i] = lam[l0 + i]
        frame_clamp(r, R, Jr, Jw, Hr, Hw, q[0:ROOT_COORDINATES], Fk, pack.twist[k], lam_k, order, phi, jac, hess)
        rows = np.empty(nc + ROOT_COORDINATES, dtype=np.int64)
        for j in range(nc):
            rows[j] = zx[cols[j]]
        for j in range(ROOT_COORDINATES):
            rows[nc + j] = zx[x0 + j]
        clamp_residual(lam_k, phi, jac, nc, scale, zl, l0, rows, res, coef_k)
        if not want_matrix:
            continue
        # the tip moment's load stiffness on the tip's (r0', theta_1) rows and r0' columns
        for i in range(4):
            for j in range(3):
                blocks[n_el - 1, 11 + i, 11 + j] -= coef_k * tip_jacobian[i, j]
        inertia.add_translational_mass(pack.trans_mass[k], n_el, coef_m, blocks)
        add_element_blocks_banded(ab, blocks, zx[x0] - ctx.border, ku, 1.0)
        add_clamp_matrix(ab, brow, bcol, bb, ku, jac, hess, rows, nc, scale, coef_k, zl, l0)
    return margin, power


def ancf_energies(pack, ctx, F, x, v, beams):
    """Kinetic (translational and rotary), strain and gravity energy of every ANCF beam (J)."""
    for k in range(pack.index.shape[0]):
        _, nq, Fk, q, qd = ancf_beam(pack, k, F, x, v)
        S, dS, d2S, w, le = pack.S[k], pack.dS[k], pack.d2S[k], pack.w[k], pack.element_length[k]
        term = np.zeros(nq)
        inertia.translational_mass_product(pack.trans_mass[k], qd, term)
        kinetic = 0.0
        potential = 0.0
        g = pack.gravity_load[k]
        for j in range(nq):
            kinetic += 0.5 * qd[j] * term[j]
            potential -= g[j] * q[j]
        kinetic += inertia.rotary_inertia_kernel(q, qd, np.zeros(nq), Fk, le, S, dS, w, pack.inertia[k], 0.0, term,
                                                 np.empty((0, 16, 16)))
        strain = elastic.elastic_kernel(q, qd, Fk, le, S, dS, d2S, w, pack.stiffness[k], pack.reference[k], 0.0, 0.0,
                                        0.0, term, np.empty((0, 16, 16)))[0]
        terms.add_beam_energy(beams, pack.index[k], kinetic, strain, potential)
    return 0.0, 0.0, 0.0


def ancf_momenta(pack, ctx, F, x, v, out):
    """Every ANCF beam's mass, first moment, linear momentum and angular momentum about the origin
    (:mod:`hubbeam.system.terms`): by Noether's theorem the translational momenta are the
    generalized momenta M q' on the positions and slopes (a rigid translation moves the
    positions alone, a rotation e x r0 and e x r0'), so p = sum_i p_r,i and H_trans = sum_i
    (r0_i x p_r,i + r0'_i x p_r',i); the sections' rotary inertia adds int R J omega dx."""
    for k in range(pack.index.shape[0]):
        _, nq, Fk, q, qd = ancf_beam(pack, k, F, x, v)
        p = np.zeros(nq)
        inertia.translational_mass_product(pack.trans_mass[k], qd, p)
        H = np.zeros(3)
        for node in range(nq // NODE_DOFS):
            o = NODE_DOFS * node
            for a in (0, 3):
                r0, r1, r2 = q[o + a], q[o + a + 1], q[o + a + 2]
                p0, p1, p2 = p[o + a], p[o + a + 1], p[o + a + 2]
                H[0] += r1 * p2 - r2 * p1
                H[1] += r2 * p0 - r0 * p2
                H[2] += r0 * p1 - r1 * p0
            for i in range(3):
                out[4 + i] += p[o + i]
        inertia.rotary_momentum(q, qd, Fk, pack.element_length[k], pack.S[k], pack.dS[k], pack.w[k], pack.inertia[k],
                                H)
        for i in range(3):
            out[7 + i] += H[i]
        # mass and first moment: the generalized gravity load of a unit field along e_i is the
        # beam's mass m on the positions; m r_cm . e_i = (M u_i) . q with u_i the unit translation
        for i in range(3):
            u = np.zeros(nq)
            for node in range(nq // NODE_DOFS):
                u[NODE_DOFS * node + i] = 1.0
            mu = np.zeros(nq)
            inertia.translational_mass_product(pack.trans_mass[k], u, mu)
            first = 0.0
            mass = 0.0
            for j in range(nq):
                first += mu[j] * q[j]
                mass += mu[j] * u[j]
            out[1 + i] += first
            if i == 0:
                out[0] += mass


def ancf_power(pack, ctx, F, x, v):
    """Power of the drag of Eq. 37 and of the structural damping on every ANCF beam (W)."""
    power = 0.0
    for k in range(pack.index.shape[0]):
        _, nq, Fk, q, qd = ancf_beam(pack, k, F, x, v)
        force = np.empty(nq)
        power += loads.drag_kernel(qd, pack.element_length[k], pack.S[k], pack.w[k], pack.width[k],
                                     ctx.drag[0], ctx.drag[1], 0.0, force, np.empty((0, 16, 16)))
        if pack.structural_damping[k] > 0.0:
            power += elastic.elastic_kernel(q, qd, Fk, pack.element_length[k], pack.S[k], pack.dS[k], pack.d2S[k],
                                            pack.w[k], pack.stiffness[k], pack.reference[k],
                                            pack.structural_damping[k], 0.0, 0.0, force, np.empty((0, 16, 16)))[2]
    return power


def ancf_drive_power(pack, ctx, F, t, x, v, lam):
    """The power of the constant tip force and tip moment on every ANCF beam (W), Q_tip . q' with
    Q_tip their generalized force of :func:`applied_load` (the tip moment's through
    :func:`hubbeam.system.loads.tip_moment_terms`): the drive's work of the energy balance, as
    the loads along the span count theirs (:func:`hubbeam.system.span_loads.span_load_power`)."""
    power = 0.0
    tQ, tJ = np.empty(4), np.empty((4, 3))
    for k in range(pack.index.shape[0]):
        force, moment = pack.tip_force[k], pack.tip_moment[k]
        pushed = force[0] != 0.0 or force[1] != 0.0 or force[2] != 0.0
        turned = moment[0] != 0.0 or moment[1] != 0.0 or moment[2] != 0.0
        if not (pushed or turned):
            continue
        _, nq, Fk, q, qd = ancf_beam(pack, k, F, x, v)
        tip = nq - NODE_DOFS
        for i in range(3):
            power += force[i] * qd[tip + i]
        if turned:
            tip_moment_terms(q[tip + 3 : tip + 6], moment, Fk, tQ, tJ)
            for i in range(4):
                power += tQ[i] * qd[tip + 3 + i]
    return power


def ancf_tips(pack, ctx, F, x, out):
    """Each ANCF beam's tip centroid displacement from its undeformed place (the root frame's
    axis carried out to the length), along its reference frame's axes (m)."""
    for k in range(pack.index.shape[0]):
        tip = pack.x0[k] + NODE_DOFS * pack.elements[k]
        length = pack.element_length[k] * pack.elements[k]
        displacement_in_reference(ctx, F, x, pack.chains[k, 0], pack.chains[k, 1], length, x[tip:tip + 3],
                                  out[pack.index[k]])


def turns_frame(link, j: int) -> bool:
    """Whether coordinate j of a chain's ``link`` can turn the frame (frames.py: the position
    coordinates of a FREE or ANCF_TIP link, its first three, only move it; an FFR tip's may do
    both)."""
    if link.kind in (LinkKind.FREE, LinkKind.ANCF_TIP):
        return j >= 3
    return link.kind != LinkKind.CONSTANT


def ancf_bandwidth(system, layout) -> int:
    """Half-bandwidth of the ANCF beams' blocks: 15 (16 x 16 element blocks; the clamp rows reach
    12 ahead), or what the clamp's entries need to reach its frame's coordinates outside the
    border (a joint angle, a parent beam's tip); 1 without ANCF beams.

    The clamp (:mod:`hubbeam.system.clamp`) puts entries at its multipliers' rows and columns
    against the frame's coordinates and the root's seven (its Jacobian), among the frame's
    coordinates, and between the frame's coordinates that turn it and the root slope r0'(0)
    (its Hessian: a_2 . r0'(0) and a_3 . r0'(0) are bilinear in the frame's axes and the slope;
    the root position and twist enter linearly): the band must reach those pairs only, not
    from a parent's tip position to the child's root twist (a chain's junction: 17 instead of
    21)."""
    width = 1
    zx = layout.z_of_x
    for k, b in enumerate(system.beams):
        if not isinstance(b, AncfPart):
            continue
        width = max(width, BANDWIDTH)
        start = layout.beam_x(k).start
        root = [zx[start + j] for j in range(ROOT_COORDINATES)]
        slope = root[3:6]
        multipliers = list(layout.z_of_lambda[layout.clamp_lambda(k)])
        frame, turning = [], []
        for link in system.frames.chain(system.frames.root(k)).links:
            for j in range(link.coordinates):
                z = zx[link.coordinate + j]
                if z >= layout.border:
                    frame.append(z)
                    if turns_frame(link, j):
                        turning.append(z)
        pairs = [(a, c) for a in multipliers for c in frame + root] + [(a, c) for a in turning for c in slope]
        if frame:
            pairs.append((min(frame), max(frame)))
        width = max([width] + [abs(int(a) - int(c)) for a, c in pairs])
    return width


KIND = terms.register(AncfBeams, pack_ancf_beams, ancf_equations, ancf_energies, ancf_power, ancf_tips,
                      bandwidth=ancf_bandwidth, drive_power=ancf_drive_power, momenta=ancf_momenta)
