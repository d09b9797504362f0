"""The hub with an FFR beam (paper Secs. 3 and 4).

Coordinates x = [theta, r_C (3), Theta (3), p]: hub angle, body-frame origin (at the root
A), 2-3-1 Cardan angles of the body frame (:mod:`hubbeam.elements.ffr.cardan`) and the
deformation coordinates of nodes 1..n (the root node is clamped to the body frame).

**Clamp.** The paper couples the body frame to the hub by Eqs. 73 and 76. As printed,
Eq. 73 fixes five of the six freedoms (it leaves the rotation of i_b in the plane of
i_h, j_h free). hubbeam uses the equivalent full clamp A0 = A_h(theta) R_x(-beta), which
in 2-3-1 Cardan angles is *linear*:

    r_C - R i_h(theta) = 0,   Theta1 + theta = 0,   Theta2 = 0,   Theta3 + beta = 0,

(A_h(theta) = R_y(-theta), Eq. 74; the section's m = cos(beta) j_h - sin(beta) k_h as
for ANCF), plus theta - theta_p(t) = 0 for a held hub. It is better conditioned than
Eq. 73 (constant Jacobian rows for the angles) and keeps the Cardan angles away from
their singularity (Theta2 = 0).

**Equations** (Eqs. 65-72): with v = H q' (v = [r_C', omega^b, p'], omega^b = D Theta'),
M = H^T M_v H and Q = H^T (Q_g + Q_f + Q_d + Q_v + Q_tip) - H^T M_v h. The hub row is
J theta'' = T + reaction. The Newton matrices are dense (the body's reference coordinates
couple to every deformation coordinate). The dynamic iteration matrix is coef_m M +
coef_c H^T C_v H + coef_k (K_elastic + constraint Hessian); the inertia forces'
derivatives are left out (they are O((omega h)^2) against the mass term and only slow
Newton). The static matrix and the linearisation for modes are central differences of
the residual (dense and small: exact to about 1e-8 relative).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubbeam.elements.ffr.cardan import angular_velocity_matrix, angular_velocity_matrix_rate, rotation_matrix
from hubbeam.numerics import central_difference_jacobian, relative_steps
from hubbeam.system.assembly import DenseMatrix
from hubbeam.system.hub import hub_frame
from hubbeam.system.model import AXIS, HubSystem

R_C, ANGLES, BODY = slice(1, 4), slice(4, 7), 7


@dataclass
class FfrHubSystem(HubSystem):
    """An FFR beam (:class:`~hubbeam.elements.ffr.body.FfrBeam`) clamped to the hub."""

    def __post_init__(self) -> None:
        super().__post_init__()
        # the tip point (L, 0, 0) and its section's small rotation over p
        self._tip_rows = self.beam.displacement_row(self.beam.length)
        self._tip_rotation_rows = self.beam.rotation_row(self.beam.length)

    # ------------------------------------------------------------ layout and charts
    @property
    def nx(self) -> int:
        return BODY + self.beam.ndof

    def initial_state(self, theta: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Undeformed beam clamped at hub angle theta; the chart is unused by FFR (identity)."""
        x = np.zeros(self.nx)
        x[0] = theta
        x[R_C] = self.radius * hub_frame(theta)[:, 0]
        x[ANGLES] = [-theta, 0.0, -self.twist]
        return x, np.eye(3)

    def chart_margin(self, x, F) -> float:
        """The clamp holds Theta2 = 0: the 2-3-1 Cardan angles never come near their
        singularity (cos Theta2 = 0); reported as 1 + |cos Theta2|, never below 1."""
        return 1.0 + abs(np.cos(x[5]))

    def better_chart(self, x):
        return np.eye(3)

    def remap(self, x, F, F_new):
        return x.copy()

    def axis_chart(self, x, F):
        return x.copy(), F

    # ------------------------------------------------------------ kinematics
    def _body(self, x):
        angles = x[ANGLES]
        return rotation_matrix(angles), angular_velocity_matrix(angles)

    def _H(self, D):
        n = self.nx - 1
        H = np.eye(n)
        H[3:6, 3:6] = D
        return H

    def steady_rotation_rates(self, x, F, omega: float):
        """Rates of a rigid rotation with the hub at theta' = omega (w = -omega j0): theta' = omega,
        r_C' = w x r_C, Theta' = D^-1 A0^T w, p' = 0; accelerations r_C'' = w x (w x r_C),
        Theta'' = -D^-1 D' Theta' (omega^b = A0^T w is constant), p'' = 0."""
        A0, D = self._body(x)
        w = -omega * AXIS
        v = np.zeros(self.nx)
        a = np.zeros(self.nx)
        v[0] = omega
        v[R_C] = np.cross(w, x[R_C])
        v[ANGLES] = np.linalg.solve(D, A0.T @ w)
        a[R_C] = np.cross(w, v[R_C])
        a[ANGLES] = -np.linalg.solve(D, angular_velocity_matrix_rate(x[ANGLES], v[ANGLES]))
        return v, a

    # ------------------------------------------------------------ constraints
    def constraints(self, x, F, theta_p):
        """Phi, its Jacobian on the clamp coordinates c = x[0:7] = [theta, r_C, Theta] (m x 7)
        and the multiplier-weighted Hessian on them (7 x 7); p does not enter."""
        theta = x[0]
        m = 6 if theta_p is None else 7
        c, s = np.cos(theta), np.sin(theta)
        phi = np.zeros(m)
        jac = np.zeros((m, BODY))
        phi[0:3] = x[R_C] - self.radius * np.array([c, 0.0, s])
        phi[3] = x[4] + theta
        phi[4] = x[5]
        phi[5] = x[6] + self.twist
        jac[0:3, R_C] = np.eye(3)
        jac[0:3, 0] = -self.radius * np.array([-s, 0.0, c])
        jac[3, 4] = jac[3, 0] = 1.0
        jac[4, 5] = 1.0
        jac[5, 6] = 1.0
        if theta_p is not None:
            phi[6] = theta - theta_p
            jac[6, 0] = 1.0

        def hess(lam):
            H = np.zeros((BODY, BODY))
            H[0, 0] = self.radius * (lam[0] * c + lam[2] * s)
            return H

        return phi, jac, hess

    # ------------------------------------------------------------ generalized forces
    def _forces(self, x, v, acc, F, tangent: bool, factor: float = 1.0):
        """M q'' - Q on the body coordinates (everything but the constraints), and the pieces
        of the iteration matrix: M, H^T C_v H, the elastic tangent on p. ``factor`` scales
        the applied loads (gravity, tip force and moment)."""
        beam = self.beam
        nf = beam.ndof
        A0, D = self._body(x)
        H = self._H(D)
        p, pd = x[BODY:], v[BODY:]
        vb = H @ v[1:]
        omega = vb[3:6]
        h = np.zeros(6 + nf)
        h[3:6] = angular_velocity_matrix_rate(x[ANGLES], v[ANGLES])
        Mv = beam.mass_matrix(p, A0)
        _, f_el, K_el = beam.elastic(p)
        Q = beam.quadratic_velocity(p, pd, omega, A0) + factor * (beam.gravity(p, A0, self.gravity) + self._tip_load(A0))
        Q[6:] -= f_el
        Qd, Cv = self._drag(x, vb, A0, tangent)
        Q += Qd
        vdot = H @ acc[1:] + h
        force = H.T @ (Mv @ vdot - Q)
        if not tangent:
            return force, None
        M = H.T @ Mv @ H
        C = H.T @ Cv @ H
        K = np.zeros_like(M)
        K[6:, 6:] = K_el
        return force, (M, C, K)

    def _tip_load(self, A0):
        """Virtual work of the tip force and moment (global, constant) on v: the force acts at
        the tip point, the moment on the body rotation plus the small section rotations."""
        Q = np.zeros(6 + self.beam.ndof)
        if np.any(self.tip_force):
            fb = A0.T @ self.tip_force
            Q[0:3] += self.tip_force
            r_tip = np.array([self.beam.length, 0.0, 0.0])  # small-deformation lever arm
            Q[3:6] += np.cross(r_tip, fb)
            Q[6:] += self._tip_rows.T @ fb
        if np.any(self.tip_moment):
            mb = A0.T @ self.tip_moment
            Q[3:6] += mb
            Q[6:] += self._tip_rotation_rows.T @ mb
        return Q

    def _drag(self, x, vb, A0, tangent: bool):
        """Eq. 64 on the centre line (frontal width b): Q_d and its velocity Jacobian C_v
        (d(-Q_d)/dv)."""
        c1, c2 = self.damping
        n = vb.shape[0]
        if c1 == 0.0 and c2 == 0.0:
            return np.zeros(n), np.zeros((n, n))
        t = self.beam.centre_line_table
        b = self.beam.section.width
        p = x[BODY:]
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
        weight = b * t["w"]
        Q = -np.einsum("qif,qi->f", S, (weight * (c1 + c2 * speed))[:, None] * rdot)
        if not tangent:
            return Q, None
        safe = np.where(speed > 0, speed, 1.0)
        G = (c1 + c2 * speed)[:, None, None] * np.eye(3) + c2 * rdot[:, :, None] * (rdot / safe[:, None])[:, None, :]
        GS = (weight[:, None, None] * G) @ S
        C = S.reshape(-1, n).T @ GS.reshape(-1, n)
        return Q, C

    def dissipated_power(self, x, v, F) -> float:
        c1, c2 = self.damping
        if c1 == 0.0 and c2 == 0.0:
            return 0.0
        A0, D = self._body(x)
        vb = self._H(D) @ v[1:]
        Qd, _ = self._drag(x, vb, A0, tangent=False)
        return float(-Qd @ vb)

    # ------------------------------------------------------------ equations
    def _residual(self, x, acc, lam, force, jac, phi, coef_k, scale):
        m = jac.shape[0]
        res = np.empty(1 + m + self.nx - 1)
        res[0] = coef_k * (self.hub_inertia * acc[0] - self.hub_torque + jac[:, 0] @ lam)
        res[1 : 1 + m] = scale * phi
        res[1 + m :] = coef_k * force
        res[1 + m : m + BODY] += coef_k * jac[:, 1:].T @ lam
        return res

    def dynamic_residual(self, x, v, acc, lam, F, t, coef_k, scale):
        force, _ = self._forces(x, v, acc, F, tangent=False)
        phi, jac, _ = self.constraints(x, F, self.drive_angle(t))
        return self._residual(x, acc, lam, force, jac, phi, coef_k, scale)

    def dynamic_equations(self, x, v, acc, lam, F, t, coef_m, coef_c, coef_k, scale):
        """Residual (as for ANCF, unknowns z = [theta, mu, q]) and the dense iteration matrix."""
        force, (M, C, K) = self._forces(x, v, acc, F, tangent=True)
        phi, jac, hess = self.constraints(x, F, self.drive_angle(t))
        res = self._residual(x, acc, lam, force, jac, phi, coef_k, scale)
        m = jac.shape[0]
        A = np.zeros((res.shape[0], res.shape[0]))
        xi = np.concatenate([[0], np.arange(1 + m, m + BODY)])  # z indices of the clamp coordinates
        A[np.ix_(xi, xi)] = coef_k * hess(lam)
        A[0, 0] += coef_m * self.hub_inertia
        A[1 + m :, 1 + m :] += coef_m * M + coef_c * C + coef_k * K
        A[1 : 1 + m, xi] = scale * jac
        A[xi, 1 : 1 + m] = scale * jac.T
        return res, DenseMatrix(A)

    def static_equations(self, x, mu, F, factor, theta_p=0.0, spin=0.0):
        """Static residual (hub held at theta_p; with ``spin``, the steadily rotating state in
        the hub frame) and its Jacobian by central differences, on z = [theta, mu, q]."""
        s = self.constraint_scale
        m = mu.shape[0]

        def residual(z):
            xx = np.concatenate([[z[0]], z[1 + m :]])
            if spin:
                vel, acc = self.steady_rotation_rates(xx, F, spin)
                vel, acc = factor**0.5 * vel, factor * acc
            else:
                vel, acc = np.zeros_like(xx), np.zeros_like(xx)
            force, _ = self._forces(xx, vel, acc, F, tangent=False, factor=factor)
            phi, jac, _ = self.constraints(xx, F, theta_p)
            lam = s * z[1 : 1 + m]
            res = self._residual(xx, np.zeros_like(xx), lam, force, jac, phi, 1.0, s)
            res[0] += (1.0 - factor) * self.hub_torque  # the hub torque is a load too
            return res

        z = np.concatenate([[x[0]], mu, x[1:]])
        return residual(z), DenseMatrix(central_difference_jacobian(residual, z, relative_steps(z)))

    def linearised(self, x, lam, F, factor=1.0, held=False, theta_p=0.0):
        """K (central differences of the force rows, constraint Hessian included), M and A."""
        theta_p = theta_p if held else None
        lam = lam[: self.n_constraints(held)]

        def forces(xx):
            phi, jac, _ = self.constraints(xx, F, theta_p)
            f, _ = self._forces(xx, np.zeros_like(xx), np.zeros_like(xx), F, tangent=False, factor=factor)
            out = np.empty(self.nx)
            out[0] = -factor * self.hub_torque + jac[:, 0] @ lam
            out[1:] = f
            out[1:BODY] += jac[:, 1:].T @ lam
            return out

        K = central_difference_jacobian(forces, x, relative_steps(x))
        A0, D = self._body(x)
        H = self._H(D)
        M = np.zeros((self.nx, self.nx))
        M[0, 0] = self.hub_inertia
        M[1:, 1:] = H.T @ self.beam.mass_matrix(x[BODY:], A0) @ H
        _, jac, _ = self.constraints(x, F, theta_p)
        A = np.zeros((jac.shape[0], self.nx))
        A[:, 0:BODY] = jac
        return K, M, A

    # ------------------------------------------------------------ measured quantities
    def energies(self, x, v, F) -> dict[str, float]:
        A0, D = self._body(x)
        vb = self._H(D) @ v[1:]
        p = x[BODY:]
        kinetic = 0.5 * self.hub_inertia * v[0] ** 2 + 0.5 * vb @ self.beam.mass_matrix(p, A0) @ vb
        strain = self.beam.elastic(p)[0]
        inv = self.beam.invariants
        gravity = -self.gravity @ (inv["m"] * x[R_C] + A0 @ self.beam.first_moment(p))
        return {"kinetic": float(kinetic), "strain": float(strain), "gravity": float(gravity)}

    def angular_momentum(self, x, v, F) -> float:
        """About the axis, in the sense of theta': J theta' + (M_v v) . xi_v, xi_v = the v of a
        unit rigid rotation about -j0 (r_C' = -j0 x r_C, omega^b = -A0^T j0, p' = 0)."""
        A0, D = self._body(x)
        vb = self._H(D) @ v[1:]
        w = -AXIS
        xi = np.zeros_like(vb)
        xi[0:3] = np.cross(w, x[R_C])
        xi[3:6] = A0.T @ w
        return float(self.hub_inertia * v[0] + (self.beam.mass_matrix(x[BODY:], A0) @ vb) @ xi)

    def point_position(self, x, station: float, y: float = 0.0, z: float = 0.0) -> np.ndarray:
        """Global position of the material point (station, y, z) (Eq. 42)."""
        A0, _ = self._body(x)
        u = self.beam.displacement_row(station, y, z) @ x[BODY:]
        return x[R_C] + A0 @ (np.array([station, y, z]) + u)

    def tip_position(self, x) -> np.ndarray:
        return self.point_position(x, self.beam.length)

    def surface_strain(self, x, F, station: float, y: float, z: float) -> float:
        return self.beam.surface_strain(x[BODY:], station, y, z)

    def centre_line(self, x, F, points_per_element: int = 8) -> np.ndarray:
        beam = self.beam
        xs = np.linspace(0.0, beam.length, beam.elements * points_per_element + 1)
        return np.array([self.point_position(x, s) for s in xs])

    def static_force_scale(self, x, F, spin: float = 0.0) -> float:
        m = self.beam.invariants["m"]
        scale = max(m * np.linalg.norm(self.gravity), np.linalg.norm(self.tip_force),
                    np.linalg.norm(self.tip_moment) / self.beam.length, 1e-9)
        if spin:
            scale = max(scale, m * spin**2 * (self.radius + self.beam.length))
        return scale
