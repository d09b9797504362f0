"""The static and linearised equations of a :class:`~hubbeam.system.multibody.MultibodySystem`
(its statics, the mass matrix, the constraints' Jacobian and acceleration terms): the methods
of :class:`SystemStatics`, which the system class takes on. Every call reads the system's
compiled model and layout; nothing here keeps state of its own."""

from __future__ import annotations

import numpy as np

from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.beam import NODE_DOFS
from hubbeam.system.clamp import frame_clamp_equations
from hubbeam.system.frames import chain_pose
from hubbeam.system.layout import CLAMP_EQUATIONS


class SystemStatics:
    """Statics and linearisation of the system (mixed into
    :class:`~hubbeam.system.multibody.MultibodySystem`)."""

    def static_equations(self, x, mu, F, factor, spin=0.0):
        """Residual and Newton matrix of the static problem with the hub held at theta = 0, on z
        of the held layout (lambda = s mu, s = :attr:`constraint_scale`). ``spin`` (rad/s): the
        hub's steady rate; the rigid-rotation velocities and accelerations (centrifugal,
        gyroscopic and drag loads, scaled with the loads: rates by sqrt(factor)) are applied,
        which gives the steadily rotating state in the hub frame. The matrix of an ANCF beam
        adds the centrifugal stiffness -factor M D (D: (w x)^2 on positions and slopes; the
        small dependence of the gyroscopic and drag loads on q is left out); FFR beams have the
        exact stiffness by differences (their rates do not depend on their coordinates)."""
        s = self.constraint_scale
        layout = self.layout_for(True, static=True)
        lam = s * np.asarray(mu, dtype=float)
        if spin:
            vel, acc = self.steady_rotation_rates(x, F, spin)
            vel, acc = np.sqrt(factor) * vel, factor * acc
        else:
            vel = acc = np.zeros(self.nx)
        res, matrix = self.equations(x, vel, acc, lam, F, 0.0, 0.0, 0.0, 1.0, s, load_factor=factor, held=True,
                                     stiffness="exact", static=True)
        if not spin:
            return res, matrix
        _, j_h = self.hub_axis(x)
        W = spin**2 * (np.outer(j_h, j_h) - np.eye(3))  # (w x)^2
        zx = layout.z_of_x
        M = None
        for k, part, q, chart in self.parts(x, F):
            if not isinstance(part, AncfPart):
                continue
            sx = layout.beam_x(k)
            M = self.mass_matrix(x, F, held=True, static=True) if M is None else M
            D = np.zeros((part.ndof, part.ndof))  # -factor M D: D = d(acc)/dq of the rigid rotation, on r and r'
            for node in range(part.beam.nodes):
                for off in (0, 3):
                    s0 = NODE_DOFS * node + off
                    D[s0 : s0 + 3, s0 : s0 + 3] = W
            K = factor * M[sx, sx] @ D
            for i, j in zip(*np.nonzero(K)):
                matrix.add(zx[sx.start + i], zx[sx.start + j], K[i, j])
        return res, matrix

    def mass_matrix(self, x, F, held: bool | None = None, static: bool = False) -> np.ndarray:
        """The dense mass matrix M(x) on x (kg, kg m, kg m^2; every part's, tip bodies' and
        rigid bodies' included): the compiled Newton matrix with coef_m = 1 and nothing else."""
        held = self.hub.held if held is None else held
        layout = self.layout_for(held, static)
        zero = np.zeros(self.nx)
        _, matrix = self.equations(x, zero, zero, np.zeros(layout.n_lambda), F, 0.0, 1.0, 0.0, 0.0, 0.0, held=held,
                                   static=static)
        zx = layout.z_of_x
        return matrix.to_dense()[np.ix_(zx, zx)]

    def linearised(self, x, lam, F, factor=1.0, held=False):
        """Dense stiffness and mass of x about an equilibrium, and the constraint Jacobian.

        Returns (K, M, A): K = d2(U - W)/dx2 + lambda.d2 Phi/dx2 (every load's and frame's
        stiffness included), M the mass matrix, A = dPhi/dx. ``held`` keeps the driving
        constraint (theta = theta_p(0)); ``lam`` are the multipliers of the held layout (a
        static solution's)."""
        layout = self.layout_for(held)
        lam = self.lambda_from_held(lam, held)
        zero = np.zeros(self.nx)
        _, Kz = self.equations(x, zero, zero, lam, F, 0.0, 0.0, 0.0, 1.0, 1.0, load_factor=factor, held=held,
                               stiffness="exact")
        _, Mz = self.equations(x, zero, zero, lam, F, 0.0, 1.0, 0.0, 0.0, 1.0, load_factor=factor, held=held)
        Kd, Md = Kz.to_dense(), Mz.to_dense()
        zx, zl = layout.z_of_x, layout.z_of_lambda
        return Kd[np.ix_(zx, zx)], Md[np.ix_(zx, zx)], Kd[np.ix_(zl, zx)]

    def constraint_jacobian(self, x, F, held: bool | None = None) -> np.ndarray:
        """dPhi/dx (n_lambda x nx) of the clamps and the frames' constraints."""
        held = self.hub.held if held is None else held
        layout = self.layout_for(held)
        zero = np.zeros(self.nx)
        _, matrix = self.equations(x, zero, zero, np.zeros(layout.n_lambda), F, 0.0, 0.0, 0.0, 0.0, 1.0, held=held)
        A = matrix.to_dense()
        return A[np.ix_(layout.z_of_lambda, layout.z_of_x)]

    def lambda_from_held(self, lam, held: bool) -> np.ndarray:
        """Multipliers of the static layout (a static solution's: the hub and a free base held)
        for the dynamic layout with the hub held or free (the drives statics add dropped)."""
        lam = np.asarray(lam, dtype=float)
        return self.layout_for(True, static=True).lambda_in(self.layout_for(held), lam)

    def _clamp(self, k: int, x, F, lam=None):
        """(Phi, Jacobian, lambda-weighted Hessian, columns (x indices)) of beam k's clamp."""
        part = self.beams[k]
        chain = self.frames.root(k)
        r, R, Jr, Jw, Hr, Hw = chain_pose(self.frames.table, chain, x, F, order=2)
        s = self.layout.beam_x(k)
        phi, jac, hess = frame_clamp_equations(r, R, Jr, Jw, Hr, Hw, x[s][0:7], F[k], part.mount.twist, lam)
        cols = self.frames.chain(chain).coordinates + list(range(s.start, s.start + 7))
        return phi, jac, hess, cols

    def constraint_acceleration_terms(self, x, v, F, t, held=None) -> np.ndarray:
        """v^T Phi_xx v + Phi_tt for every constraint: what Phi_x xdd must cancel. The drive
        theta - theta_p(t) has Phi_tt = -theta_p''."""
        held = self.hub.held if held is None else held
        layout = self.layout_for(held)
        out = np.zeros(layout.n_lambda)
        if held and self.motion == "prescribed":
            out[layout.drive_lambda] = -self.hub.drive(t)[2]
        if layout.norm_lambda is not None:  # (e . e - 1)/2: e' . e'
            out[layout.norm_lambda] = float(v[layout.base_x][3:] @ v[layout.base_x][3:])
        if layout.base_lambda is not None:
            out[layout.base_lambda] = self._base_drive_acceleration_terms(x, v, t)
        for k, part in enumerate(self.beams):
            sl = layout.clamp_lambda(k)
            if sl.stop == sl.start:
                continue
            *_, cols = self._clamp(k, x, F)
            c = np.asarray(v)[cols]
            out[sl] = [c @ self._clamp(k, x, F, e)[2] @ c for e in np.eye(CLAMP_EQUATIONS)]
        return out

    def _base_drive_acceleration_terms(self, x, v, t) -> np.ndarray:
        """Phi_tt + 2 Phi_xt v of the base's six drive constraints: -r_tab'' and
        G(e_tab'') e + 2 G(e_tab') e' (:mod:`hubbeam.system.base_laws`)."""
        from hubbeam.system.base_laws import BaseLaws, conjugate_product_matrix, driven_pose

        laws = next(p for p in self.model().parts if isinstance(p, BaseLaws))
        r, dr, ddr, q, dq, ddq = driven_pose(laws, float(t))
        e, de = x[self.layout.base_x][3:], v[self.layout.base_x][3:]
        G1, G2 = np.empty((3, 4)), np.empty((3, 4))
        conjugate_product_matrix(dq, G1)
        conjugate_product_matrix(ddq, G2)
        return np.concatenate([-ddr, G2 @ e + 2.0 * G1 @ de])

    def constraint_violation(self, x, F, t) -> float:
        """Largest violation of the clamps' position equations (m)."""
        return max((float(np.max(np.abs(self._clamp(k, x, F)[0][0:3]))) for k in range(len(self.beams))
                    if self.layout.clamped[k]), default=0.0)

    def static_force_scale(self, x, F, spin: float = 0.0) -> float:
        """The size of the applied generalized forces (N), for the static force tolerance."""
        scale = 1e-9
        for _, part, q, chart in self.parts(x, F):
            sec = part.section
            mass = sec.mass_per_length * part.length + (part.tip_body.mass if part.tip_body is not None else 0.0)
            scale = max(scale, mass * float(np.linalg.norm(self.gravity)) / max(getattr(part.beam, "elements", 1), 1),
                        float(np.linalg.norm(part.tip_force)), float(np.linalg.norm(part.tip_moment)) / part.length)
            if spin:
                scale = max(scale, mass * spin**2 * (part.mount.radius + part.length) / part.beam.elements)
        return scale
