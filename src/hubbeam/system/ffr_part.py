"""An FFR beam on the hub (paper Secs. 3 and 4).

Coordinates q = [r_C (3), Theta (3), p]: body-frame origin (at the root A), 2-3-1 Cardan
angles of the body frame (:mod:`hubbeam.elements.ffr.cardan`) and the deformation
coordinates of nodes 1..n (the root node is clamped to the body frame).

**Clamp.** The paper couples the body frame to the hub by Eqs. 73 and 76. As printed,
Eq. 73 fixes five of the six freedoms. hubbeam uses the full clamp
A0 = A_h(theta + psi) R_z(p) R_x(-beta) (the mount frame of :mod:`hubbeam.system.mount`),
which in 2-3-1 Cardan angles (A_h(theta) = R_y(-theta), Eq. 74) is *linear*:

    r_C - R i_k(theta) = 0,   Theta1 + theta + psi = 0,   Theta2 - p = 0,   Theta3 + beta = 0.

It is better conditioned than Eq. 73 and keeps the Cardan angles away from their
singularity (Theta2 = precone, limited well below 90 deg).

**Equations** (Eqs. 65-72): with v = H q' (v = [r_C', omega^b, p'], omega^b = D Theta'),
M = H^T M_v H and Q = H^T (Q_g + Q_f + Q_d + Q_v + Q_tip) - H^T M_v h. The beam's block of
the Newton matrix is dense (the body's reference coordinates couple to every deformation
coordinate). The dynamic iteration matrix is coef_m M + coef_c H^T C_v H + coef_k K_elastic;
the inertia forces' derivatives are left out (O((omega h)^2) against the mass term; they
only slow Newton); statics and modes add the exact load stiffness. A tip body is part of the
body's inertia invariants (:class:`hubbeam.elements.ffr.body.FfrBeam`), modal reduction a
basis of its elastic coordinates.

The equations are evaluated in compiled code: the kind "FFR beams" (:data:`KIND`,
:mod:`hubbeam.system.terms`) packs every FFR beam of a system (:class:`FfrBeams`) and gives
the compiled equations the body terms of :mod:`hubbeam.elements.ffr.kernels` (a dense block
inside the band) and the linear clamp above (:func:`ffr_clamp`). :meth:`FfrPart.forces` and
:meth:`FfrPart.stiffness` below are their Python reference: the same formulas written with
numpy, and the stiffness by central differences, which the tests hold the kernels against.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.elements.ffr.cardan import angular_velocity_matrix, angular_velocity_matrix_rate, rotation_matrix
from hubbeam.elements.ffr.kernels import (cardan, ffr_body_terms, ffr_dissipated_power, ffr_energies,
                                          ffr_load_stiffness, tip_lever)
from hubbeam.elements.ffr.kernels import pack as ffr_constants
from hubbeam.numerics import central_difference_jacobian, relative_steps
from hubbeam.system import terms
from hubbeam.system.assembly import add_entry
from hubbeam.system.clamp import add_clamp_jacobian, clamp_residual
from hubbeam.system.mount import Mount, tip_from_mount
from hubbeam.system.parts import BeamPart

R_C, ANGLES, BODY = slice(0, 3), slice(3, 6), 6
#: the hub's axis j0 (global)
AXIS = np.array([0.0, 1.0, 0.0])


@dataclass(eq=False)
class FfrPart(BeamPart):
    """An FFR beam (:class:`~hubbeam.elements.ffr.body.FfrBeam`) on its mount."""

    beam: FfrBeam
    mount: Mount = field(default_factory=Mount)
    tip_force: np.ndarray = field(default_factory=lambda: np.zeros(3))
    tip_moment: np.ndarray = field(default_factory=lambda: np.zeros(3))
    name: str = "beam1"

    formulation = "ffr"
    root_dofs = 6  # r_C, Theta

    def __post_init__(self) -> None:
        super().__post_init__()
        # the tip point (L, 0, 0) and its section's small rotation over p
        self._tip_rows = self.beam.displacement_row(self.beam.length)
        self._tip_rotation_rows = self.beam.rotation_row(self.beam.length)

    @property
    def ndof(self) -> int:
        return BODY + self.beam.ndof

    @property
    def tip_body(self):
        return self.beam.tip_body

    # ------------------------------------------------------------ states
    def initial_state(self, theta: float) -> tuple[np.ndarray, np.ndarray]:
        """Undeformed beam clamped at hub angle theta; the chart is unused by FFR (identity)."""
        m = self.mount
        q = np.zeros(self.ndof)
        q[R_C] = m.root(theta)
        q[ANGLES] = [-(theta + m.azimuth), m.precone, -m.twist]
        return q, np.eye(3)

    def _body(self, q):
        angles = q[ANGLES]
        return rotation_matrix(angles), angular_velocity_matrix(angles)

    def _H(self, D):
        H = np.eye(self.ndof)
        H[3:6, 3:6] = D
        return H

    def steady_rotation_rates(self, q, chart, omega: float):
        """Rates of a rigid rotation with the hub at theta' = omega (w = -omega j0):
        r_C' = w x r_C, Theta' = D^-1 A0^T w, p' = 0; accelerations r_C'' = w x (w x r_C),
        Theta'' = -D^-1 D' Theta' (omega^b = A0^T w is constant), p'' = 0."""
        A0, D = self._body(q)
        w = -omega * AXIS
        v = np.zeros(self.ndof)
        a = np.zeros(self.ndof)
        v[R_C] = np.cross(w, q[R_C])
        v[ANGLES] = np.linalg.solve(D, A0.T @ w)
        a[R_C] = np.cross(w, v[R_C])
        a[ANGLES] = -np.linalg.solve(D, angular_velocity_matrix_rate(q[ANGLES], v[ANGLES]))
        return v, a

    # ------------------------------------------------------------ constraints
    def clamp(self, q, chart, theta):
        """Phi (6), its Jacobian on [theta, r_C, Theta] (6 x 7) and the multiplier-weighted
        Hessian on them (7 x 7); p does not enter."""
        m = self.mount
        a = theta + m.azimuth
        c, s = np.cos(a), np.sin(a)
        phi = np.zeros(6)
        jac = np.zeros((6, 7))
        phi[0:3] = q[R_C] - m.radius * np.array([c, 0.0, s])
        phi[3] = q[3] + a
        phi[4] = q[4] - m.precone
        phi[5] = q[5] + m.twist
        jac[0:3, 1:4] = np.eye(3)
        jac[0:3, 0] = -m.radius * np.array([-s, 0.0, c])
        jac[3, 4] = jac[3, 0] = 1.0
        jac[4, 5] = 1.0
        jac[5, 6] = 1.0

        def hess(lam):
            H = np.zeros((7, 7))
            H[0, 0] = m.radius * (lam[0] * c + lam[2] * s)
            return H

        return phi, jac, hess

    # ------------------------------------------------------------ generalized forces
    def forces(self, q, v, acc, gravity, damping, tangent: bool, factor: float = 1.0):
        """M q'' - Q on q (everything but the constraints), and the pieces of the iteration
        matrix: M, H^T C_v H + c K on p (drag and structural damping), the elastic tangent on p.
        ``factor`` scales the applied loads (gravity, tip force and moment). The Python reference
        of the compiled kernel."""
        beam = self.beam
        nf = beam.ndof
        A0, D = self._body(q)
        H = self._H(D)
        p, pd = q[BODY:], v[BODY:]
        vb = H @ v
        omega = vb[3:6]
        h = np.zeros(6 + nf)
        h[3:6] = angular_velocity_matrix_rate(q[ANGLES], v[ANGLES])
        Mv = beam.mass_matrix(p, A0)
        _, f_el, K_el = beam.elastic(p)
        Q = beam.quadratic_velocity(p, pd, omega, A0) + factor * (beam.gravity(p, A0, gravity) + self._tip_load(A0, p))
        Q[6:] -= f_el + beam.damping_matrix @ pd
        Qd, Cv = self._drag(q, vb, A0, damping, tangent)
        Q += Qd
        vdot = H @ acc + h
        force = H.T @ (Mv @ vdot - Q)
        if not tangent:
            return force, None
        M = H.T @ Mv @ H
        C = H.T @ Cv @ H
        C[6:, 6:] += beam.damping_matrix
        K = np.zeros_like(M)
        K[6:, 6:] = K_el
        return force, (M, C, K)

    def stiffness(self, q, gravity, damping, factor: float = 1.0, spin: float = 0.0) -> np.ndarray:
        """d(forces)/dq at rest (or in steady rotation at ``spin`` rad/s, its rates following q)
        by central differences: the static and modal stiffness with every load's dependence
        (the reference for the compiled load and spin stiffness)."""
        def forces(qq):
            if spin:
                vel, acc = self.steady_rotation_rates(qq, None, spin)
                vel, acc = factor**0.5 * vel, factor * acc
            else:
                vel = acc = np.zeros_like(qq)
            return self.forces(qq, vel, acc, gravity, damping, tangent=False, factor=factor)[0]

        return central_difference_jacobian(forces, q, relative_steps(q))

    def _tip_load(self, A0, p):
        """Virtual work of the tip force and moment (global, constant) on v: the force acts at
        the deformed tip point (body frame (L, 0, 0) + T p, so its moment on the body rotation
        has that lever arm), the moment on the body rotation plus the small section rotations."""
        Q = np.zeros(6 + self.beam.ndof)
        if np.any(self.tip_force):
            fb = A0.T @ self.tip_force
            Q[0:3] += self.tip_force
            r_tip = np.array([self.beam.length, 0.0, 0.0]) + self._tip_rows @ p
            Q[3:6] += np.cross(r_tip, fb)
            Q[6:] += self._tip_rows.T @ fb
        if np.any(self.tip_moment):
            mb = A0.T @ self.tip_moment
            Q[3:6] += mb
            Q[6:] += self._tip_rotation_rows.T @ mb
        return Q

    def _drag(self, q, vb, A0, damping, tangent: bool):
        """Eq. 64 on the centre line (frontal width b): Q_d and its velocity Jacobian C_v
        (d(-Q_d)/dv)."""
        c1, c2 = damping
        n = vb.shape[0]
        if c1 == 0.0 and c2 == 0.0:
            return np.zeros(n), np.zeros((n, n))
        t = self.beam.centre_line_table
        p = q[BODY:]
        r = np.column_stack([t["x"], np.zeros((t["x"].shape[0], 2))]) + t["N"] @ p  # body frame
        S = np.empty((r.shape[0], 3, n))
        S[:, :, 0:3] = np.eye(3)
        rt = np.zeros((r.shape[0], 3, 3))  # skew(r) for every point
        rt[:, 0, 1], rt[:, 0, 2], rt[:, 1, 2] = -r[:, 2], r[:, 1], -r[:, 0]
        rt -= rt.transpose(0, 2, 1)
        S[:, :, 3:6] = -A0 @ rt
        S[:, :, 6:] = A0 @ t["N"]
        rdot = S @ vb
        speed = np.linalg.norm(rdot, axis=1)
        weight = t["b"] * t["w"]
        Q = -np.einsum("qif,qi->f", S, (weight * (c1 + c2 * speed))[:, None] * rdot)
        if not tangent:
            return Q, None
        safe = np.where(speed > 0, speed, 1.0)
        G = (c1 + c2 * speed)[:, None, None] * np.eye(3) + c2 * rdot[:, :, None] * (rdot / safe[:, None])[:, None, :]
        GS = (weight[:, None, None] * G) @ S
        C = S.reshape(-1, n).T @ GS.reshape(-1, n)
        return Q, C

    def dissipated_power(self, q, v, damping) -> float:
        """Power of the drag and the structural damping (W, >= 0): the Python reference of the
        compiled one."""
        pd = v[BODY:]
        power = float(pd @ self.beam.damping_matrix @ pd)
        c1, c2 = damping
        if c1 == 0.0 and c2 == 0.0:
            return power
        A0, D = self._body(q)
        vb = self._H(D) @ v
        Qd, _ = self._drag(q, vb, A0, damping, tangent=False)
        return power + float(-Qd @ vb)

    # ------------------------------------------------------------ inertia and energies
    def mass_matrix(self, q, chart=None) -> np.ndarray:
        A0, D = self._body(q)
        H = self._H(D)
        return H.T @ self.beam.mass_matrix(q[BODY:], A0) @ H

    def apply_mass(self, q, chart, u) -> np.ndarray:
        return self.mass_matrix(q) @ u

    def energies(self, q, v, chart, gravity) -> dict[str, float]:
        A0, D = self._body(q)
        vb = self._H(D) @ v
        p = q[BODY:]
        kinetic = 0.5 * vb @ self.beam.mass_matrix(p, A0) @ vb
        strain = self.beam.elastic(p)[0]
        inv = self.beam.invariants
        grav = -np.asarray(gravity) @ (inv["m"] * q[R_C] + A0 @ self.beam.first_moment(p))
        return {"kinetic": float(kinetic), "strain": float(strain), "gravity": float(grav)}

    # ------------------------------------------------------------ measured quantities
    def point_position(self, q, station: float, y: float = 0.0, z: float = 0.0) -> np.ndarray:
        """Global position of the material point (station, y, z) (Eq. 42); (y, z) (m) on the local
        section axes of the station (turned by the pretwist, :meth:`FfrBeam.body_point`)."""
        A0, _ = self._body(q)
        yb, zb = self.beam.body_point(station, y, z)
        u = self.beam.displacement_row(station, yb, zb) @ q[BODY:]
        return q[R_C] + A0 @ (np.array([station, yb, zb]) + u)

    def tip_position(self, q) -> np.ndarray:
        return self.point_position(q, self.beam.length)

    def surface_strain(self, q, chart, station, y, z) -> float:
        """Fibre strain at the section point (y, z) on the local section axes of the station
        (:meth:`FfrBeam.surface_strain`)."""
        return self.beam.surface_strain(q[BODY:], station, y, z)

    def surface_strains_of_states(self, Q, chart, station, y, z) -> np.ndarray:
        """:meth:`surface_strain` for each row of Q in one product (:meth:`FfrBeam.surface_strains_of_states`)."""
        return self.beam.surface_strains_of_states(Q[:, BODY:], station, y, z)

    def section_motion(self, q, chart, u, stations):
        """FFR's kinematics (Eq. 42) at the station's centre point, r = r_C + A0 (rho0 + N p):
        velocity r_C' + A0 (omega^b x (rho0 + N p) + N p'), omega^b = D Theta'; the section turns
        by the body rotation and its small rotation phi = Phi p (:meth:`FfrBeam.rotation_row`):
        frame A0 exp([phi]x) P(x) (the body frame's axes are the undeformed root section's, P the
        pretwist's turn of the section axes), angular
        velocity A0 (omega^b + Phi p') (to first order in phi, as FFR's kinematics)."""
        beam = self.beam
        A0, D = self._body(q)
        p, w_b, pd = q[BODY:], D @ u[ANGLES], u[BODY:]
        n = len(stations)
        frames, vel, omega = np.empty((n, 3, 3)), np.empty((n, 3)), np.empty((n, 3))
        for i, x in enumerate(stations):
            N, Phi = beam.displacement_row(x), beam.rotation_row(x)
            r = np.array([x, 0.0, 0.0]) + N @ p
            vel[i] = u[R_C] + A0 @ (np.cross(w_b, r) + N @ pd)
            omega[i] = A0 @ (w_b + Phi @ pd)
            frames[i] = A0 @ rotations_about(Phi @ p)[0] @ self._pretwisted_axes([x])[0]
        return frames, vel, omega

    def centre_line_at(self, q, chart, stations) -> np.ndarray:
        """Eq. 42 at (x, 0, 0) of every station."""
        A0, _ = self._body(q)
        xs = np.asarray(stations, dtype=float)
        rows = np.array([self.beam.displacement_row(s) for s in xs]).reshape(xs.size, 3, -1)
        local = rows @ q[BODY:]
        local[:, 0] += xs
        return q[R_C] + local @ A0.T

    def frame_at(self, q, chart, station) -> np.ndarray:
        """Section frame [tau m n] (3x3, global) at the station (m from the root)."""
        return self.frames_at(q, chart, [station])[0]

    def frames_at(self, q, chart, stations) -> np.ndarray:
        """Section frames at the stations: the body frame turned by each section's rotation
        phi (:meth:`~hubbeam.elements.ffr.body.FfrBeam.rotation_row`). FFR's kinematics are
        linear in phi (u = phi x (0, y, z)); the frame turns by the rotation vector phi
        (Rodrigues), which agrees with them to first order and stays orthonormal."""
        A0, _ = self._body(q)
        rows = np.array([self.beam.rotation_row(s) for s in stations]).reshape(len(stations), 3, -1)
        return A0 @ rotations_about(rows @ q[BODY:]) @ self._pretwisted_axes(stations)

    def _pretwisted_axes(self, stations) -> np.ndarray:
        """The undeformed section axes [tau m n] at the stations over the body frame (n x 3 x 3):
        the root section's turned by the pretwist (:meth:`FfrBeam.section_axes`)."""
        axes = np.tile(np.eye(3), (len(stations), 1, 1))
        if self.beam.sections is not None:
            for i, x in enumerate(stations):
                axes[i, 1:, 1:] = self.beam.section_axes(x)
        return axes


def rotations_about(phi: np.ndarray) -> np.ndarray:
    """Rotation matrices (n x 3 x 3) of the rotation vectors phi (n x 3, rad): Rodrigues' formula."""
    phi = np.asarray(phi, dtype=float).reshape(-1, 3)
    angle = np.linalg.norm(phi, axis=1)
    axis = phi / np.where(angle > 0.0, angle, 1.0)[:, None]
    K = np.zeros((phi.shape[0], 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 2] = -axis[:, 2], axis[:, 1], -axis[:, 0]
    K -= K.transpose(0, 2, 1)
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3) + s * K + (1.0 - c) * K @ K


# ================================================================ compiled terms: the kind "FFR beams"
#: the constants of :class:`hubbeam.elements.ffr.kernels.FfrArrays` that :class:`FfrBeams` holds
#: in one array per group of equal shapes, each field in its slot (its place in the group) along
#: the axis after the beam's: every array of the pack costs its reference count each time compiled
#: code passes the model or the pack (measured: 11 more arrays, +0.5 us per step_powers on exp1)
FFR_GROUPS = {"scalars": ("m", "stiffening", "damped", "length"),
              "vectors": ("c0", "tip_force", "tip_moment"),
              "rows": ("Sbar", "tip_rows", "tip_rotation_rows"),
              "squares": ("Mff", "K", "C_struct"),
              "points": ("x_pts", "w_pts", "width")}
#: the constants of FfrArrays that FfrBeams holds one array each
FFR_SINGLE = ("I0", "J", "II", "EAl", "mean_stretch", "mean_slope2", "N_pts")
#: the columns of :attr:`FfrBeams.places`
INDEX, X0, LAMBDA0, NF = 0, 1, 2, 3


class FfrBeams(NamedTuple):
    """The FFR beams' constants (:func:`hubbeam.elements.ffr.kernels.pack`), one row per FFR
    beam, zero-padded to the largest beam (the kernels read the leading nf entries); fields of
    equal shape grouped (:data:`FFR_GROUPS`, slots as listed there; :func:`ffr_arguments`)."""

    places: np.ndarray  # int64 (nb, 4): the beam's place among all beams (INDEX), where q_k starts in x (X0),
    #                     where its clamp multipliers start in lambda (LAMBDA0), its elastic coordinates (NF)
    mount: np.ndarray  # (nb, 4) radius, twist, azimuth, precone
    scalars: np.ndarray  # (nb, 4): m (kg), stiffening, damped, length (m)
    vectors: np.ndarray  # (nb, 3, 3): c0, tip_force, tip_moment
    rows: np.ndarray  # (nb, 3, 3, nf): Sbar, tip_rows, tip_rotation_rows
    squares: np.ndarray  # (nb, 3, nf, nf): Mff, K, C_struct (structural damping c K, N s)
    points: np.ndarray  # (nb, 3, npts): x_pts, w_pts, width of the centre-line points
    I0: np.ndarray
    J: np.ndarray
    II: np.ndarray
    EAl: np.ndarray
    mean_stretch: np.ndarray
    mean_slope2: np.ndarray
    N_pts: np.ndarray


def _stacked(values) -> np.ndarray:
    """The arrays ``values`` (of equal ndim) along a new leading axis, zero-padded to the largest."""
    values = [np.asarray(v, dtype=float) for v in values]
    shape = tuple(np.max([v.shape for v in values], axis=0)) if values[0].ndim else ()
    stacked = np.zeros((len(values),) + shape)
    for i, v in enumerate(values):
        stacked[(i,) + tuple(slice(0, n) for n in v.shape)] = v
    return stacked


def pack_ffr_beams(system, layout) -> FfrBeams | None:
    """The :class:`FfrBeams` of ``system`` placed by ``layout``, stacked and zero-padded (None
    without FFR beams)."""
    ffr = [(k, b) for k, b in enumerate(system.beams) if isinstance(b, FfrPart)]
    if not ffr:
        return None
    packs = [ffr_constants(b) for _, b in ffr]
    fields = {group: _stacked([_stacked([getattr(p, name) for name in names]) for p in packs])
              for group, names in FFR_GROUPS.items()}
    fields.update({name: _stacked([getattr(p, name) for p in packs]) for name in FFR_SINGLE})
    ints = lambda values: np.array(values, dtype=np.int64)  # noqa: E731
    places = np.array([(k, layout.beam_x(k).start, layout.clamp_lambda(k).start, b.beam.ndof) for k, b in ffr],
                      dtype=np.int64).reshape(len(ffr), 4)
    return FfrBeams(places, np.array([b.mount.params() for _, b in ffr], dtype=float).reshape(len(ffr), 4), **fields)


def ffr_bandwidth(system) -> int:
    """Half-bandwidth an FFR beam's whole block needs (its six clamp rows and 6 + nf
    coordinates); 1 without FFR beams."""
    return max([11 + b.beam.ndof for b in system.beams if isinstance(b, FfrPart)], default=1)


@njit(cache=True, inline="always")
def ffr_drag_arguments(pack, k, drag_c):
    """The drag group of FFR beam k for :mod:`hubbeam.elements.ffr.kernels` (``drag_c``: c1, c2 of Eq. 37)."""
    pts = pack.points
    return (pack.N_pts[k], pts[k, 0], pts[k, 1], pts[k, 2], drag_c[0], drag_c[1])


@njit(cache=True, inline="always")
def ffr_arguments(pack, k, drag_c):
    """(inv, tip, drag) of FFR beam k for :mod:`hubbeam.elements.ffr.kernels` (``drag_c``: c1, c2 of Eq. 37).
    Each array is a view of the pack's (each costs its construction and reference count, about
    10 to 20 ns): callers that need only some groups build only those (:func:`ffr_drag_arguments`)."""
    sc, vec, rows, sq = pack.scalars, pack.vectors, pack.rows, pack.squares  # slots: FFR_GROUPS
    inv = (sc[k, 0], vec[k, 0], rows[k, 0], pack.I0[k], pack.J[k], pack.II[k], sq[k, 0], sq[k, 1], pack.EAl[k],
           pack.mean_stretch[k], pack.mean_slope2[k], sc[k, 1], sq[k, 2], sc[k, 2])
    tip = (vec[k, 1], vec[k, 2], rows[k, 1], rows[k, 2], sc[k, 3])
    return inv, tip, ffr_drag_arguments(pack, k, drag_c)


@njit(cache=True)
def ffr_clamp(mount, theta, q, lam, phi, jac):
    """The six clamp equations of an FFR body frame (see :mod:`hubbeam.system.ffr_part`):
    r_C - R i_k(theta) = 0, Theta1 + theta + psi = 0, Theta2 - p = 0, Theta3 + beta = 0, with
    their Jacobian on [theta, r_C, Theta] (6 x 7, written into the leading columns of ``jac``).
    Returns the multiplier-weighted Hessian's only entry, d2/dtheta2 of the position rows."""
    radius, twist, azimuth, precone = mount[0], mount[1], mount[2], mount[3]
    a = theta + azimuth
    c, s = np.cos(a), np.sin(a)
    for i in range(6):
        for j in range(7):
            jac[i, j] = 0.0
    phi[0] = q[0] - radius * c
    phi[1] = q[1]
    phi[2] = q[2] - radius * s
    phi[3] = q[3] + a
    phi[4] = q[4] - precone
    phi[5] = q[5] + twist
    for i in range(3):
        jac[i, 1 + i] = 1.0
    jac[0, 0] = radius * s
    jac[2, 0] = -radius * c
    jac[3, 0] = 1.0
    jac[3, 4] = 1.0
    jac[4, 5] = 1.0
    jac[5, 6] = 1.0
    return radius * (lam[0] * c + lam[2] * s)


def ffr_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                  want_matrix, res, ab, brow, bcol, bb):
    """Every FFR beam's rows (:mod:`hubbeam.system.terms`): the body terms of
    :func:`~hubbeam.elements.ffr.kernels.ffr_body_terms` and the clamp :func:`ffr_clamp`;
    ``exact_stiffness`` adds the load stiffness (statics and modes)."""
    zx, zl, ku = ctx.z_of_x, ctx.z_of_lambda, ctx.ku
    z_theta = zx[ctx.theta]
    theta = x[ctx.theta]
    power = 0.0
    hub_force = 0.0
    phi = np.empty(6)  # the clamp's Phi, Jacobian (on [theta, r_C, Theta]) and multipliers
    jac = np.empty((6, 7))
    lam_k = np.empty(6)
    places = pack.places
    for k in range(places.shape[0]):
        n = 6 + places[k, NF]
        x0 = places[k, X0]
        l0 = places[k, LAMBDA0]
        q = x[x0 : x0 + n]
        force = np.empty(n)
        nbk = n if want_matrix else 0
        block = np.empty((nbk, nbk))  # ffr_body_terms overwrites it
        inv, tip, drag = ffr_arguments(pack, k, ctx.drag)
        power += ffr_body_terms(inv, q, v[x0 : x0 + n], acc[x0 : x0 + n], ctx.gravity, tip, drag, coef_m, coef_c,
                                coef_k, load_factor, want_matrix, force, block)
        for i in range(6):
            lam_k[i] = lam[l0 + i]
        hess = ffr_clamp(pack.mount[k], theta, q, lam_k, phi, jac)
        hub_force += clamp_residual(lam_k, phi, jac, 6, scale, zl, l0, force, res)
        for j in range(n):
            res[zx[x0 + j]] += coef_k * force[j]
        if not want_matrix:
            continue
        if exact_stiffness:
            load = np.empty((n, n))
            ffr_load_stiffness(inv, q, ctx.gravity, tip, load_factor, load)
            for i in range(n):
                for j in range(n):
                    block[i, j] += coef_k * load[i, j]
        q_start = zx[x0]
        for i in range(n):
            for j in range(n):
                add_entry(ab, brow, bcol, bb, ku, q_start + i, q_start + j, block[i, j])
        add_clamp_jacobian(ab, brow, bcol, bb, ku, jac, 6, scale, zl, l0, q_start, z_theta)
        add_entry(ab, brow, bcol, bb, ku, z_theta, z_theta, coef_k * hess)
    return hub_force, 2.0, power


def ffr_beam_energies(pack, ctx, F, x, v, beams):
    """Kinetic, strain and gravity energy of every FFR beam, tip body included (J)."""
    places = pack.places
    for k in range(places.shape[0]):
        n = 6 + places[k, NF]
        x0 = places[k, X0]
        inv, _, _ = ffr_arguments(pack, k, ctx.drag)
        kinetic, strain, potential = ffr_energies(inv, x[x0 : x0 + n], v[x0 : x0 + n], ctx.gravity)
        terms.add_beam_energy(beams, places[k, INDEX], kinetic, strain, potential)
    return 0.0, 0.0, 0.0


def ffr_power(pack, ctx, F, x, v):
    """Power of the drag of Eq. 37 and of the structural damping on every FFR beam (W)."""
    power = 0.0
    places = pack.places
    still = ctx.drag[0] == 0.0 and ctx.drag[1] == 0.0
    for k in range(places.shape[0]):
        if still and pack.scalars[k, 2] == 0.0:  # neither drag nor structural damping: no views to build
            continue
        n = 6 + places[k, NF]
        x0 = places[k, X0]
        power += ffr_dissipated_power(x[x0 : x0 + n], v[x0 : x0 + n], pack.squares[k, 2], pack.scalars[k, 2],
                                      ffr_drag_arguments(pack, k, ctx.drag))
    return power


def ffr_tips(pack, ctx, x, out):
    """Each FFR beam's tip centroid displacement in its hub frame (m)."""
    theta = x[ctx.theta]
    A = np.empty((3, 3))
    D = np.empty((3, 3))
    tip_at = np.empty(3)
    places = pack.places
    for k in range(places.shape[0]):
        x0 = places[k, X0]
        cardan(x[x0 + 3], x[x0 + 4], x[x0 + 5], A, D)
        length = pack.scalars[k, 3]
        local = tip_lever(pack.rows[k, 1], length, x[x0 + 6 : x0 + 6 + places[k, NF]])
        for i in range(3):
            tip_at[i] = x[x0 + i] + A[i, 0] * local[0] + A[i, 1] * local[1] + A[i, 2] * local[2]
        tip_from_mount(pack.mount[k], theta, length, tip_at, out[places[k, INDEX]])


KIND = terms.register(FfrBeams, pack_ffr_beams, ffr_equations, ffr_beam_energies, ffr_power, ffr_tips,
                      bandwidth=ffr_bandwidth)
