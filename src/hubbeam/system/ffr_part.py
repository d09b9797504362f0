"""An FFR beam on its frame (paper Secs. 3 and 4), in minimal coordinates: the part.

The floating frame of reference of an FFR beam is the frame it hangs on: its root section
frame (:mod:`hubbeam.system.frames`: the hub, its mount, joint angles, the base, a parent's
tip), so the beam's own coordinates are its elastic coordinates p alone (nodal, or N modes:
modal reduction, :mod:`hubbeam.elements.ffr.modal`). No reference coordinates of its own, no
clamp multipliers: the body's inertia couples to the frame's coordinates c exactly.

:class:`FfrPart` is the beam as a part of the system: its coordinates, initial state, sensors
(positions, strains, section frames along the span) and :meth:`FfrPart.vspace_forces`, the
Python reference of its equations in v-space written with numpy, which the tests hold the
compiled kernels against. The compiled equations and the kind "FFR beams" that packs every FFR
beam of a system are :mod:`hubbeam.system.ffr_beams`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.system.chains import Chain, constant, ffr_tip
from hubbeam.system.mount import Mount, about_axis
from hubbeam.system.parts import BeamPart


@dataclass(eq=False)
class FfrPart(BeamPart):
    """An FFR beam (:class:`~hubbeam.elements.ffr.body.FfrBeam`) on its mount; its coordinates
    are its elastic coordinates p, its floating frame its root section frame."""

    beam: FfrBeam
    mount: Mount = field(default_factory=Mount)
    tip_force: np.ndarray = field(default_factory=lambda: np.zeros(3))
    tip_moment: np.ndarray = field(default_factory=lambda: np.zeros(3))
    name: str = "beam1"

    formulation = "ffr"
    root_dofs = 0  # no clamp: the root frame is the body frame
    clamped = False

    def __post_init__(self) -> None:
        super().__post_init__()
        # the tip point (L, 0, 0) and its section's small rotation over p
        self._tip_rows = self.beam.displacement_row(self.beam.length)
        self._tip_rotation_rows = self.beam.rotation_row(self.beam.length)

    @property
    def ndof(self) -> int:
        return self.beam.ndof

    @property
    def tip_body(self):
        return self.beam.tip_body

    def tip_frame(self, x0: int, index: int, root: Chain) -> Chain:
        """The root chain (the body frame) continued by the tip's place (L, 0, 0) + N_L p and
        small rotation Phi_L p (an FFR_TIP link), turned back by the twist (the pretwist of the
        section axes is not in the link's rotation)."""
        return root.then(ffr_tip(x0, self.length, self._tip_rows, self._tip_rotation_rows),
                         constant(rotation=about_axis(self.mount.twist)))

    # ------------------------------------------------------------ states
    def initial_state(self, root, frame, reference) -> tuple[np.ndarray, np.ndarray]:
        """Undeformed: p = 0; the chart is unused by FFR (identity)."""
        return np.zeros(self.ndof), np.eye(3)

    def rigid_rates(self, q, chart, velocity, w, origin, acceleration=None):
        """A rigid motion of the frame leaves p at rest: (0, 0)."""
        return np.zeros(self.ndof), np.zeros(self.ndof)

    # ------------------------------------------------------------ generalized forces
    def vspace_forces(self, A0, p, vb, vdot, gravity, damping, tangent: bool, factor: float = 1.0):
        """M_v vdot - Q on v = [r_C', omega^b, p'] (everything but the frame's projection), and
        the pieces of the iteration matrix: M_v, C_v + c K on p (drag and structural damping),
        the elastic tangent on p. ``factor`` scales the applied loads (gravity, tip force and
        moment). The Python reference of the compiled kernel."""
        beam = self.beam
        nf = beam.ndof
        pd = vb[6:]
        omega = vb[3:6]
        Mv = beam.mass_matrix(p, A0)
        _, f_el, K_el = beam.elastic(p)
        Q = beam.quadratic_velocity(p, pd, omega, A0) + factor * (beam.gravity(p, A0, gravity) + self._tip_load(A0, p))
        Q[6:] -= f_el + beam.damping_matrix @ pd
        Qd, Cv = self._drag(p, vb, A0, damping, tangent)
        Q += Qd
        force = Mv @ vdot - Q
        if not tangent:
            return force, None
        C = np.array(Cv)
        C[6:, 6:] += beam.damping_matrix
        K = np.zeros_like(Mv)
        K[6:, 6:] = K_el
        assert K.shape == (6 + nf, 6 + nf)
        return force, (Mv, C, K)

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

    def _drag(self, p, vb, A0, damping, tangent: bool):
        """Eq. 64 on the centre line (frontal width b): Q_d and its velocity Jacobian C_v
        (d(-Q_d)/dv)."""
        c1, c2 = damping
        n = vb.shape[0]
        if c1 == 0.0 and c2 == 0.0:
            return np.zeros(n), np.zeros((n, n))
        t = self.beam.centre_line_table
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

    def dissipated_power(self, A0, p, vb, damping) -> float:
        """Power of the drag and the structural damping (W, >= 0): the Python reference of the
        compiled one."""
        pd = vb[6:]
        power = float(pd @ self.beam.damping_matrix @ pd)
        c1, c2 = damping
        if c1 == 0.0 and c2 == 0.0:
            return power
        Qd, _ = self._drag(p, vb, A0, damping, tangent=False)
        return power + float(-Qd @ vb)

    def energies(self, r_C, A0, p, vb, gravity) -> dict[str, float]:
        """Kinetic, strain and gravity energy (J) in v-space (the Python reference)."""
        kinetic = 0.5 * vb @ self.beam.mass_matrix(p, A0) @ vb
        strain = self.beam.elastic(p)[0]
        inv = self.beam.invariants
        grav = -np.asarray(gravity) @ (inv["m"] * np.asarray(r_C) + A0 @ self.beam.first_moment(p))
        return {"kinetic": float(kinetic), "strain": float(strain), "gravity": float(grav)}

    # ------------------------------------------------------------ measured quantities
    def point_position(self, q, frame, station: float, y: float = 0.0, z: float = 0.0) -> np.ndarray:
        """Global position of the material point (station, y, z) (Eq. 42) for the body frame
        ``frame`` = (r_C, A0); (y, z) (m) on the local section axes of the station (turned by the
        pretwist, :meth:`FfrBeam.body_point`)."""
        r_C, A0 = frame
        yb, zb = self.beam.body_point(station, y, z)
        u = self.beam.displacement_row(station, yb, zb) @ q
        return np.asarray(r_C) + np.asarray(A0) @ (np.array([station, yb, zb]) + u)

    def tip_position(self, q, frame) -> np.ndarray:
        return self.point_position(q, frame, self.beam.length)

    def surface_strain(self, q, chart, station, y, z) -> float:
        """Fibre strain at the section point (y, z) on the local section axes of the station
        (:meth:`FfrBeam.surface_strain`)."""
        return self.beam.surface_strain(q, station, y, z)

    def surface_strains_of_states(self, Q, chart, station, y, z) -> np.ndarray:
        """:meth:`surface_strain` for each row of Q in one product (:meth:`FfrBeam.surface_strains_of_states`)."""
        return self.beam.surface_strains_of_states(Q, station, y, z)

    def section_motion(self, q, chart, u, stations, frame, frame_rate):
        """FFR's kinematics (Eq. 42) at the station's centre point, r = r_C + A0 (rho0 + N p), for
        the body frame ``frame`` = (r_C, A0) moving at ``frame_rate`` = (r_C', w) (global; w the
        frame's angular velocity) and p at the rate u: velocity r_C' + w x A0 (rho0 + N p) + A0 N u;
        the section turns by the body rotation and its small rotation phi = Phi p
        (:meth:`FfrBeam.rotation_row`): frame A0 exp([phi]x) P(x) (the body frame's axes are the
        undeformed root section's, P the pretwist's turn of the section axes), angular velocity
        w + A0 Phi u (to first order in phi, as FFR's kinematics)."""
        beam = self.beam
        r_C, A0 = (np.asarray(a, dtype=float) for a in frame)
        v_C, w = (np.asarray(a) for a in frame_rate)
        n = len(stations)
        frames = np.empty((n, 3, 3))
        vel = np.empty((n, 3), dtype=np.result_type(u, v_C, w))
        omega = np.empty((n, 3), dtype=vel.dtype)
        for i, x in enumerate(stations):
            N, Phi = beam.displacement_row(x), beam.rotation_row(x)
            r = A0 @ (np.array([x, 0.0, 0.0]) + N @ q)
            vel[i] = v_C + np.cross(w, r) + A0 @ (N @ u)
            omega[i] = w + A0 @ (Phi @ u)
            frames[i] = A0 @ rotations_about(Phi @ q)[0] @ self._pretwisted_axes([x])[0]
        return frames, vel, omega

    def centre_line_at(self, q, chart, stations, frame) -> np.ndarray:
        """Eq. 42 at (x, 0, 0) of every station, for the body frame ``frame`` = (r_C, A0)."""
        r_C, A0 = frame
        xs = np.asarray(stations, dtype=float)
        rows = np.array([self.beam.displacement_row(s) for s in xs]).reshape(xs.size, 3, -1)
        local = rows @ q
        local[:, 0] += xs
        return np.asarray(r_C) + local @ np.asarray(A0).T

    def frames_at(self, q, chart, stations, frame) -> np.ndarray:
        """Section frames at the stations: the body frame turned by each section's rotation
        phi (:meth:`~hubbeam.elements.ffr.body.FfrBeam.rotation_row`). FFR's kinematics are
        linear in phi (u = phi x (0, y, z)); the frame turns by the rotation vector phi
        (Rodrigues), which agrees with them to first order and stays orthonormal."""
        _, A0 = frame
        rows = np.array([self.beam.rotation_row(s) for s in stations]).reshape(len(stations), 3, -1)
        return np.asarray(A0) @ rotations_about(rows @ q) @ self._pretwisted_axes(stations)

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
