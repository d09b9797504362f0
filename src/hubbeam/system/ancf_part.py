"""An ANCF beam on the hub (paper Secs. 2 and 4): its mount, clamp, states and measures.

The equations of motion of every ANCF beam are summed in compiled code
(:func:`hubbeam.system.equations.system_equations`); this part supplies what the system
needs around them: initial and steadily rotating states, the rotation chart, energies,
the mass matrix for the angular momentum, and the measured quantities.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hubbeam.elements.ancf.chart import frame_from_director, remap_chart
from hubbeam.elements.ancf.frame import section_frame
from hubbeam.elements.ancf.strain import strain_measures
from hubbeam.system.beam import NODE_DOFS, AncfBeam
from hubbeam.system.clamp import clamp_constraints
from hubbeam.system.mount import Mount
from hubbeam.system.parts import ChartedBeamPart
from hubbeam.system.tip_body import TipBody

#: the hub's axis j0 (global)
AXIS = np.array([0.0, 1.0, 0.0])


@dataclass(eq=False)
class AncfPart(ChartedBeamPart):
    """An ANCF beam (:class:`~hubbeam.system.beam.AncfBeam`) on its mount, with an optional
    tip body and constant tip loads (global directions: force N at the tip centroid, moment N m)."""

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

    # ------------------------------------------------------------ inertia and energies
    def _tip_body_terms(self, q, v, chart, gravity, acc=None):
        t = self.tip
        a8 = np.zeros(8) if acc is None else acc[t]
        return self.tip_body.ancf_terms(chart, q[t], v[t], a8, np.asarray(gravity, dtype=float))

    def mass_matrix(self, q, chart) -> np.ndarray:
        beam = self.beam
        M = np.zeros((beam.ndof, beam.ndof))
        for e, block in enumerate(beam.mass_blocks(q, chart)):
            s = NODE_DOFS * e
            M[s : s + 16, s : s + 16] += block
        if self.tip_body is not None:
            t = self.tip
            M[t, t] += self._tip_body_terms(q, np.zeros_like(q), chart, np.zeros(3))[1]
        return M

    def apply_mass(self, q, chart, u) -> np.ndarray:
        """M(q) u (tip body included)."""
        beam = self.beam
        out = beam.apply_mass(beam.mass_blocks(q, chart), u)
        if self.tip_body is not None:
            t = self.tip
            out[t] += self._tip_body_terms(q, np.zeros_like(q), chart, np.zeros(3))[1] @ u[t]
        return out

    def energies(self, q, v, chart, gravity) -> dict[str, float]:
        beam = self.beam
        kinetic = 0.5 * v @ beam.apply_mass(beam.mass_blocks(q, chart), v)
        strain = beam.elastic(q, chart, tangent=False)[0]
        grav = -beam.gravity_load(np.asarray(gravity, dtype=float)) @ q
        if self.tip_body is not None:  # one evaluation of the tip body gives its mass and potential
            t = self.tip
            _, M, _, _, V = self._tip_body_terms(q, v, chart, gravity)
            kinetic += 0.5 * v[t] @ M @ v[t]
            grav += V
        return {"kinetic": float(kinetic), "strain": float(strain), "gravity": float(grav)}

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
