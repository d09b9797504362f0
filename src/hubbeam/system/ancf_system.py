"""The hub with an ANCF beam (paper Secs. 2 and 4): coordinates, constraints, loads, tangents.

Coordinates x = [theta, q] (hub angle, ANCF nodal coordinates); the clamp (and a drive, for
a prescribed or fixed hub) adds constraints Phi(x, t) = 0 with multipliers lambda
(Eq. 77). The Newton systems order the unknowns z = [theta, mu, q], mu = lambda / s,
where s = EA / l (the axial stiffness of one element) scales the constraint rows to the
size of the stiffness entries; with this order the matrix is banded.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubbeam.elements.ancf.chart import frame_from_director, remap_chart
from hubbeam.system.ancf_equations import (CHART_SINGULAR, FIXED, FREE, PRESCRIBED, AncfModel, applied_load,
                                           assemble_newton_matrix, equations_of_motion)
from hubbeam.system.assembly import BandMatrix, add_element_blocks_dense
from hubbeam.system.beam import NODE_DOFS, ChartSingularityError
from hubbeam.system.clamp import clamp_constraints
from hubbeam.system.hub import clamp_frame, hub_frame
from hubbeam.system.model import AXIS, HubSystem


@dataclass
class AncfHubSystem(HubSystem):
    """An ANCF beam (:class:`~hubbeam.system.beam.AncfBeam`) clamped to the hub."""

    def __post_init__(self) -> None:
        super().__post_init__()
        self.gravity_load = self.beam.distributed_load(self.beam.section.mass_per_length * self.gravity)

    # ------------------------------------------------------------ layout
    @property
    def nx(self) -> int:
        return 1 + self.beam.ndof

    def bandwidth(self, m: int) -> int:
        return max(15, m + 8)

    def initial_state(self, theta: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Straight undeformed beam clamped to the hub at angle theta: (x, chart F)."""
        frame = clamp_frame(theta, self.twist)
        q, F = self.beam.straight_state(self.radius * hub_frame(theta)[:, 0], frame)
        return np.concatenate([[theta], q]), F

    # ------------------------------------------------------------ charts
    def chart_margin(self, x: np.ndarray, F: np.ndarray) -> float:
        """min(1 + d.tau) over the Gauss points: 0 at the chart's singular direction."""
        return self.beam.chart_margin(x[1:], F)

    def better_chart(self, x: np.ndarray) -> np.ndarray:
        return self.beam.better_chart(x[1:])

    def remap(self, x: np.ndarray, F: np.ndarray, F_new: np.ndarray) -> np.ndarray:
        """x re-expressed in the chart F_new (same configuration; only theta_1, theta_1' change)."""
        beam = self.beam
        q = x[1:]
        nodes = remap_chart(q.reshape(beam.nodes, NODE_DOFS), beam.node_tangent_rates(q), F, F_new)
        return np.concatenate([[x[0]], nodes.ravel()])

    def axis_chart(self, x: np.ndarray, F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """x re-expressed in the chart whose director is the hub's rotation vector, d = -j0.

        The beam stays near the plane normal to the hub axis while the hub sweeps it
        through every direction of that plane; with d = -j0 each of those tangents is 90
        deg from the singular direction (+j0), and a rigid rotation of the whole system
        about the axis advances theta_1 by exactly the hub angle (see
        :meth:`steady_rotation_rates`)."""
        F_new = frame_from_director(-AXIS, hint=np.array([1.0, 0.0, 0.0]))
        return self.remap(x, F, F_new), F_new

    def steady_rotation_rates(self, x: np.ndarray, F: np.ndarray, omega: float) -> tuple[np.ndarray, np.ndarray]:
        """Velocity and acceleration of x when the whole system turns rigidly with the hub at
        theta' = omega (rad/s) (angular velocity w = -omega j0, Eq. 74).

        r and r' move with w x (.), accelerate with w x (w x .). theta_1 is measured from the
        chart's untwisted frame; in general theta_1' = w.tau + d.(tau x (w x tau))/(1 + d.tau)
        (the section turns with w; the untwisted frame turns about tau by the parallel-transport
        rate). In the axis chart (d = w/|w|) that is exactly omega at every point, so
        d(theta_1')/dt = 0. Other charts are refused."""
        if not np.allclose(F[:, 0], -AXIS, atol=1e-12):
            raise ValueError("steady rotation rates need the axis chart (director -j0); see axis_chart")
        w = -omega * AXIS
        nodes = x[1:].reshape(self.beam.nodes, NODE_DOFS)
        vel = np.zeros_like(nodes)
        acc = np.zeros_like(nodes)
        for k in (0, 3):
            vel[:, k : k + 3] = np.cross(w, nodes[:, k : k + 3])
            acc[:, k : k + 3] = np.cross(w, vel[:, k : k + 3])
        vel[:, 6] = omega
        return np.concatenate([[omega], vel.ravel()]), np.concatenate([[0.0], acc.ravel()])

    def steady_rotation_load(self, q: np.ndarray, F: np.ndarray, omega: float):
        """Load of steady rotation at theta' = omega: Q_c = Q_v(q, q_r') - M(q) q_r'' + Q_d(q_r'),
        the inertia (centrifugal) load and the drag of Eq. 37 at the rigid-rotation rates of
        :meth:`steady_rotation_rates`. In the hub frame the steady beam is in static
        equilibrium under Q_c, gravity (parallel to the axis, so steady in that frame) and the
        elastic forces; the drive then supplies the drag torque. Also returns element blocks
        of an approximate tangent -dQ_c/dq = M D (D applies (w x)^2 to r and r'), which
        leaves out the small dependence of the rotary-inertia and drag terms on q."""
        x = np.concatenate([[0.0], q])
        vel, acc = self.steady_rotation_rates(x, F, omega)
        Mb = self.beam.mass_blocks(q, F)
        _, Qv = self.beam.rotary_inertia(q, vel[1:], F)
        _, Qd, _ = self.beam.drag(vel[1:], *self.damping)
        Q = Qv + Qd - self.beam.apply_mass(Mb, acc[1:])
        W = omega**2 * (np.outer(AXIS, AXIS) - np.eye(3))  # (w x)^2
        D = np.zeros((16, 16))
        for k in (0, 3, 8, 11):
            D[k : k + 3, k : k + 3] = W
        return Q, Mb @ D

    # ------------------------------------------------------------ loads
    def external_load(self, q: np.ndarray, F: np.ndarray, factor: float = 1.0):
        """Applied generalized force on q (gravity, tip force and moment) scaled by ``factor``,
        and the tip-moment load Jacobian (4 x 3: the tip's (r0', theta_1) rows, r0' columns);
        :func:`~hubbeam.system.ancf_equations.applied_load`, as in the dynamics."""
        Q, J = np.empty(self.beam.ndof), np.empty((4, 3))
        applied_load(self.equations_model(), np.ascontiguousarray(q, dtype=float), np.ascontiguousarray(F),
                     float(factor), Q, J)
        return Q, J

    # ------------------------------------------------------------ constraints
    def constraints(self, x: np.ndarray, F: np.ndarray, theta_p: float | None):
        """Phi, its Jacobian on the clamp coordinates c = [theta, q_root[0:7]], and the
        multiplier-weighted Hessian function (see :mod:`hubbeam.system.clamp`)."""
        c = x[0:8]
        return clamp_constraints(c, self.radius, self.twist, F, theta_p)

    # ------------------------------------------------------------ statics
    def static_equations(self, x, mu, F, factor, theta_p=0.0, spin=0.0):
        """Residual and band-stored Newton matrix of the static problem with the hub held at theta_p.

        ``spin`` (rad/s): the hub's steady rate; its steady-rotation load (:meth:`steady_rotation_load`: centrifugal and drag)
        is applied, scaled by ``factor`` like the other loads, which gives the steadily rotating
        state in the hub frame.

        Unknown order z = [theta, mu, q]; lambda = s mu. Returns (residual, BandMatrix).
        """
        beam = self.beam
        s = self.constraint_scale
        q = x[1:]
        m = mu.shape[0]
        lam = s * mu
        U, f_int, blocks = beam.elastic(q, F, tangent=True)
        Q, Jload = self.external_load(q, F, factor)
        phi, jac, hess = self.constraints(x, F, theta_p)
        n = 1 + m + beam.ndof
        kq = 1 + m  # offset of q in z
        res = np.empty(n)
        res[0] = s * jac[:, 0] @ mu - factor * self.hub_torque
        res[1 : 1 + m] = s * phi
        res[kq:] = f_int - Q
        res[kq : kq + 7] += s * jac[:, 1:8].T @ mu
        if spin:
            Qc, Kc = self.steady_rotation_load(q, F, spin)
            res[kq:] -= factor * Qc
            blocks = blocks + factor * Kc
        bw = self.bandwidth(m)
        ab = np.zeros((3 * bw + 1, n), order="F")
        assemble_newton_matrix(ab, blocks, kq, 2 * bw, Jload, jac, s, hess(lam), 1.0, 0.0)
        return res, BandMatrix(ab, bw)

    # ------------------------------------------------------------ dynamics
    def compiled_model(self) -> AncfModel:
        """Constants for compiled time integration: :meth:`equations_model`."""
        return self.equations_model()

    def equations_model(self) -> AncfModel:
        """The constants of the compiled equations of motion (:mod:`hubbeam.system.ancf_equations`),
        from the system's current fields."""
        beam = self.beam
        S, dS, d2S, w = beam._tables
        sec = beam.section
        motion = {"free": FREE, "prescribed": PRESCRIBED, "fixed": FIXED}[self.motion]
        d = self.drive
        return AncfModel(
            S, dS, d2S, w, float(beam.element_length), beam._stiffness, beam._trans_mass,
            beam._inertia, float(sec.width), float(self.damping[0]), float(self.damping[1]),
            np.ascontiguousarray(self.gravity_load, dtype=float), np.asarray(self.tip_force, dtype=float),
            np.asarray(self.tip_moment, dtype=float), float(self.radius), float(self.twist),
            float(self.hub_inertia), float(self.hub_torque), motion,
            (d.code, float(d.omega_s), float(d.T), float(d.t1)), self.bandwidth(self.n_constraints(motion != FREE)),
        )

    def _equations(self, x, v, acc, lam, F, t, coefs, want_matrix):
        model = self.equations_model()
        n = 1 + lam.shape[0] + self.beam.ndof
        res = np.empty(n)
        bw = model.bandwidth
        # always a full Fortran-ordered array (a 0 x 0 one would be typed C-ordered and load
        # a second compiled version of the equations)
        ab = np.zeros((3 * bw + 1, n), order="F")
        margin, _ = equations_of_motion(model, np.ascontiguousarray(F), *(np.asarray(a, dtype=float) for a in (x, v, acc, lam)),
                                        float(t), *map(float, coefs), want_matrix, res, ab)
        if not margin > CHART_SINGULAR:
            raise ChartSingularityError(
                f"a beam tangent is at the singular direction of the rotation chart (1 + d.tau = {margin:.2e})"
            )
        return res, BandMatrix(ab, bw)

    def dynamic_residual(self, x, v, acc, lam, F, t, coef_k, scale):
        """Scaled residual of the equations of motion (Eq. 77) on z = [theta, mu, q]
        (:func:`~hubbeam.system.ancf_equations.equations_of_motion`)."""
        return self._equations(x, v, acc, lam, F, t, (0.0, 0.0, coef_k, scale), False)[0]

    def dynamic_equations(self, x, v, acc, lam, F, t, coef_m, coef_c, coef_k, scale):
        """Scaled residual and Newton matrix coef_m M + coef_c C + coef_k (K - dQ/dq +
        lambda.d2Phi) of the equations of motion on z = [theta, mu, q], lambda = scale mu / coef_k
        (:func:`~hubbeam.system.ancf_equations.equations_of_motion`). Returns (residual, BandMatrix)."""
        return self._equations(x, v, acc, lam, F, t, (coef_m, coef_c, coef_k, scale), True)

    # ------------------------------------------------------------ linearisation
    def linearised(self, x, lam, F, factor=1.0, held=False, theta_p=0.0):
        """Dense stiffness and mass of x about an equilibrium, and the constraint Jacobian.

        Returns (K, M, A): K = d2(U - W)/dx2 + lambda . d2 Phi/dx2 (the load stiffness of
        the tip moment included), M = diag(J, M_beam(q)), A = dPhi/dx (m x nx).
        ``held`` keeps the driving constraint theta = theta_p (fixed hub).
        """
        beam = self.beam
        q = x[1:]
        nx = self.nx
        _, _, blocks = beam.elastic(q, F, tangent=True)
        K = np.zeros((nx, nx))
        add_element_blocks_dense(K, blocks, 1, 1.0)
        _, Jload = self.external_load(q, F, factor)
        t = 1 + beam.node_slice(-1).start  # the tip node in x
        K[t + 3 : t + 7, t + 3 : t + 6] -= Jload
        phi, jac, hess = self.constraints(x, F, theta_p if held else None)
        lam = lam[: jac.shape[0]]
        K[0:8, 0:8] += hess(lam)
        M = np.zeros((nx, nx))
        M[0, 0] = self.hub_inertia
        add_element_blocks_dense(M, beam.mass_blocks(q, F), 1, 1.0)
        A = np.zeros((jac.shape[0], nx))
        A[:, 0:8] = jac
        return K, M, A

    # ------------------------------------------------------------ measured quantities
    def energies(self, x, v, F) -> dict[str, float]:
        """Kinetic (hub and beam, with the sections' rotary inertia), strain and gravity energy (J)."""
        beam = self.beam
        q, qd = x[1:], v[1:]
        Mb = beam.mass_blocks(q, F)
        kinetic = 0.5 * self.hub_inertia * v[0] ** 2 + 0.5 * qd @ beam.apply_mass(Mb, qd)
        strain = beam.elastic(q, F, tangent=False)[0]
        gravity = -self.gravity_load @ q
        return {"kinetic": kinetic, "strain": strain, "gravity": gravity}

    def angular_momentum(self, x, v, F) -> float:
        """Angular momentum about the hub axis (N m s), positive in the sense of theta' (about -j0).

        By Noether's theorem it is the generalized momentum p = M(q) v projected on the rigid
        rotation of the whole system about the axis (xi = rates of theta' = 1): J theta' +
        v_q^T M(q) xi_q. In the axis chart xi is exact; otherwise the state is first moved to it."""
        beam = self.beam
        if not np.allclose(F[:, 0], -AXIS, atol=1e-12):
            x_axis, F_axis = self.axis_chart(x, F)
            eps = 1e-6  # velocities move with the remap's Jacobian (central difference)
            v = (self.remap(x + eps * v, F, F_axis) - self.remap(x - eps * v, F, F_axis)) / (2 * eps)
            x, F = x_axis, F_axis
        xi, _ = self.steady_rotation_rates(x, F, 1.0)
        Mb = beam.mass_blocks(x[1:], F)
        return float(self.hub_inertia * v[0] + v[1:] @ beam.apply_mass(Mb, xi[1:]))

    def dissipated_power(self, x, v, F) -> float:
        """Power of the drag of Eq. 37 (W, >= 0)."""
        return self.beam.drag(v[1:], *self.damping)[0]

    def tip_position(self, x) -> np.ndarray:
        return x[1:][self.beam.node_slice(-1)][0:3].copy()

    def surface_strain(self, x, F, station: float, y: float, z: float) -> float:
        return self.beam.surface_strain(x[1:], F, station, y, z)

    def centre_line(self, x, F, points_per_element: int = 8) -> np.ndarray:
        """Points of the deformed centre line (global, m), root to tip."""
        beam = self.beam
        xs = np.linspace(0.0, beam.length, beam.elements * points_per_element + 1)
        return np.array([beam.interpolate(x[1:], s)[0] for s in xs])

    def static_force_scale(self, x, F, spin: float = 0.0) -> float:
        """The size of the applied generalized forces (N), for the static force tolerance."""
        Q, _ = self.external_load(x[1:], F, 1.0)
        if spin:
            Q = Q + self.steady_rotation_load(x[1:], F, spin)[0]
        return max(np.max(np.abs(Q)), np.linalg.norm(self.tip_moment) / self.beam.length, 1e-9)
