"""What can be measured on a :class:`~hubbeam.system.multibody.MultibodySystem` at a state: the
hub's and the controllers' torques, energies and momenta, the records' compiled measures, the
mode-shape energy splits, the base's motion, tip positions, strains and centre lines: the
methods of :class:`SystemMeasures`, which the system class takes on, and :func:`energy_sums`."""

from __future__ import annotations

import numpy as np

from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.frames import chain_pose
from hubbeam.system.parts import BEAM_MOTIONS


def energy_sums(hub: np.ndarray, beams: np.ndarray, beam: int | None = None) -> dict:
    """{kinetic, strain, gravity} (J) from the row of the parts that belong to no beam (the hub's
    rotor, the base) and the beams' rows (kinetic, strain, gravity): of the whole system, or of
    beam number ``beam`` alone. hub (3,) and beams (beams, 3) give floats; a leading axis of
    records, hub (n, 3) and beams (n, beams, 3), gives arrays (n,), the same sums record by record."""
    hub, beams = np.asarray(hub, dtype=float), np.asarray(beams, dtype=float)
    if beam is not None:
        parts = beams[..., beam, :]
    else:
        parts = hub
        for k in range(beams.shape[-2]):  # in the beams' order, as a sum over the parts
            parts = parts + beams[..., k, :]
    return {name: float(e) if e.ndim == 0 else e for name, e in zip(("kinetic", "strain", "gravity"), parts.T)}


class SystemMeasures:
    """Measured quantities of the system at a state (mixed into
    :class:`~hubbeam.system.multibody.MultibodySystem`)."""

    def drive_torque(self, lam: np.ndarray) -> float:
        """Torque the drive applies to the hub (N m): minus the driving constraint's multiplier;
        zero for a free hub (no driving constraint)."""
        i = self.layout.drive_lambda
        return float(-lam[i]) if i is not None and lam.shape[0] == self.layout.n_lambda else 0.0

    def applied_torque(self, t: float, x: np.ndarray, v: np.ndarray, F=None) -> float:
        """The free hub's torque law and its controllers' torque at the state (N m; charts F,
        default the initial ones); zero for a held hub."""
        if self.hub.held:
            return 0.0
        th = self.layout.theta
        torque = float(self.hub.torque(t, x[th], v[th])[0])
        return torque + self.controller_torques(t, x, v, F)[0]

    def controller_torques(self, t, x, v, F=None) -> tuple[float, dict[int, float], np.ndarray]:
        """The controllers' torques at (t, x, v) (charts F, default the initial ones): (on the
        hub, {beam k: in its joint}, on the base about its axes (3,)) (N m)."""
        hub, joints, base = 0.0, {}, np.zeros(3)
        if not self.controllers:
            return hub, joints, base
        from hubbeam.system.controller_inputs import OutputKind
        from hubbeam.system.controllers import controller_values, law_inputs, linear_controllers

        F = np.ascontiguousarray(self.initial_state()[1] if F is None else F, dtype=float)
        pairs = []
        if linear_controllers(self):
            _, y, outputs = controller_values(self, x, v, F)
            pairs += list(zip(y, outputs))
        for law, pack in self._law_packs(self.hub.held, False):
            u = law_inputs(pack, self.model().context, F, np.ascontiguousarray(x, dtype=float),
                            np.ascontiguousarray(v, dtype=float))[0]
            pairs += list(zip(law(t, u), law.outputs))
        for value, out in pairs:
            if out.kind == OutputKind.HUB_TORQUE:
                hub += float(value)
            elif out.kind == OutputKind.JOINT_TORQUE:
                joints[out.beam] = joints.get(out.beam, 0.0) + float(value)
            else:
                base[out.axis] += float(value)
        return hub, joints, base

    def energies(self, x, v, F, beam: int | None = None) -> dict[str, float]:
        """Kinetic (rigid bodies and beams, rotary inertia and tip bodies included), strain and
        gravity energy (J); of one beam when ``beam`` is its index (compiled:
        :func:`~hubbeam.system.equations.beam_energies`)."""
        return energy_sums(*self.energy_table(x, v, F), beam)

    def energy_table(self, x, v, F) -> tuple[np.ndarray, np.ndarray]:
        """(others (3,), beams (beams, 3)): the (kinetic, strain, gravity) energy (J) of the parts
        that belong to no beam (the hub's rotor, the base) and of each beam (tip bodies in their
        beam's row), as :func:`energy_sums` adds them (compiled:
        :func:`~hubbeam.system.equations.beam_energies`)."""
        hub, beams = np.zeros(3), np.zeros((len(self.beams), 3))
        self.functions.beam_energies(self.model(), np.ascontiguousarray(F, dtype=float),
                                     np.ascontiguousarray(x, dtype=float), np.ascontiguousarray(v, dtype=float), beams,
                                     hub)
        return hub, beams

    def momenta(self, x, v, F) -> dict[str, np.ndarray | float]:
        """The whole system's mass (kg), centre of mass (m), linear momentum (N s) and angular
        momentum about the global origin (N m s), every part's (compiled:
        :func:`~hubbeam.system.equations.system_momenta`)."""
        out = np.zeros(10)
        self.functions.system_momenta(self.model(), np.ascontiguousarray(F, dtype=float),
                                      np.ascontiguousarray(x, dtype=float), np.ascontiguousarray(v, dtype=float), out)
        mass = float(out[0])
        return {"mass": mass, "centre_of_mass": out[1:4] / mass if mass > 0 else np.zeros(3),
                "linear": out[4:7].copy(), "angular": out[7:10].copy()}

    def gauge_table(self, gauges) -> tuple[tuple, list]:
        """The strain gauges (beam, station, y, z) (index, m, m, m) on ANCF beams packed for
        :meth:`record_measures`, and the list of those gauges in their order there (other
        beams' gauges are left out: their sensors measure them)."""
        kept = [g for g in gauges if isinstance(self.beams[g[0]], AncfPart)]
        rows = [(k, self.beams[k].beam.gauge_rows(x, y, z)) for k, x, y, z in kept]
        n = len(rows)
        where = np.array([[k, self.layout.beam_x(k).start + self.beams[k].beam.node_slice(r[0]).start]
                          for k, r in rows], dtype=np.int64).reshape(n, 2)
        S, dS, d2S, section = (np.array([r[i] for _, r in rows], dtype=float).reshape(n, width)
                               for i, width in ((1, 4), (2, 4), (3, 4), (4, 6)))
        return (where, S, dS, d2S, section), kept

    def record_measures(self, xs, vs, F, count: int, energies: bool = True, gauges: tuple | None = None
                        ) -> dict[str, np.ndarray]:
        """Measures of the first ``count`` states (rows of xs, vs; charts F) in compiled code
        (:func:`~hubbeam.system.equations.record_measures`): ``tips`` (count, beams, 3) each
        beam's tip displacement (radial, vertical, tangential, m); with ``energies`` also
        ``hub`` (count, 3) the (kinetic, strain, gravity) energy of parts that belong to no
        beam and ``beams`` (count, beams, 3) each beam's (kinetic, strain, gravity) energy (J),
        for :func:`energy_sums`; ``strains`` (count, gauges) at the gauges of ``gauges`` (a
        :meth:`gauge_table`; default none)."""
        nb = len(self.beams)
        gauges = self.gauge_table([])[0] if gauges is None else gauges
        out = {"hub": np.zeros((count if energies else 0, 3)), "beams": np.zeros((count if energies else 0, nb, 3)),
               "tips": np.empty((count, nb, 3)), "strains": np.empty((count, gauges[0].shape[0]))}
        self.functions.record_measures(self.model(), np.ascontiguousarray(F, dtype=float),
                                       np.ascontiguousarray(xs, dtype=float), np.ascontiguousarray(vs, dtype=float),
                                       count, energies, gauges, out["hub"], out["beams"], out["tips"], out["strains"])
        return out

    def kinetic_energy_split(self, x, F, u) -> dict[str, float]:
        """The kinetic energy (J) of the system moving at the rate u about the configuration x
        (u complex: real and imaginary parts' energies summed), split into the rigid bodies'
        (``hub``: the hub's rotor; ``base``) and, summed over the beams, each beam's ``flap``,
        ``lag``, ``axial`` and ``torsion`` parts in its own directions
        (:meth:`~hubbeam.system.parts.BeamPart.kinetic_energy_split`)."""
        u = np.asarray(u)
        total = dict.fromkeys(BEAM_MOTIONS, 0.0)
        for body in self.rigid_bodies:
            r, R, v_c, w = self.frames.motion(body.chain, x, u.real, F)
            e = 0.5 * body.mass * float(v_c @ v_c) + 0.5 * float(w @ R @ body.inertia_matrix() @ R.T @ w)
            if np.iscomplexobj(u):
                r, R, v_c, w = self.frames.motion(body.chain, x, u.imag, F)
                e += 0.5 * body.mass * float(v_c @ v_c) + 0.5 * float(w @ R @ body.inertia_matrix() @ R.T @ w)
            total[body.name] = total.get(body.name, 0.0) + e
        total.setdefault("hub", 0.0)
        if self.base.moves:
            total.setdefault("base", 0.0)
        for k, part, q, chart in self.parts(x, F):
            frame, rate = self._frame_and_rate(k, x, u, F)
            u_k = u[self.layout.beam_x(k)]
            if not (np.any(u_k) or np.any(rate[0]) or np.any(rate[1])):  # a beam the rate does not move has none
                continue
            axes = self.root_axes(k, x, F)
            for key, value in part.kinetic_energy_split(q, chart, u_k, axes, frame, rate).items():
                total[key] += value
        return total

    def hinge_generators(self, x, F) -> list[tuple[str, int, np.ndarray]]:
        """For every joint axis: (its mode label, e.g. "flap hinge"; its angle's x index; the rate
        g of x when that angle turns at unit rate with its beam and every beam hanging on it
        carried rigidly: g[psi] = 1 and each ANCF beam of that subtree turning rigidly about the
        axis through the joint, at e x (r - r_J); FFR beams and joint angles of the subtree float
        on their frames and stay at rest)."""
        out = []
        children = {k: [j for j, b in enumerate(self.beams) if b.mount.parent == k] for k in range(len(self.beams))}
        for k, part in enumerate(self.beams):
            joint = part.mount.joint
            if joint is None:
                continue
            chain = self.frames.root(k)
            r, _, _, Jw, _, _ = chain_pose(self.frames.table, chain, x, F)
            columns = self.frames.chain(chain).coordinates
            subtree, todo = [], [k]
            while todo:
                j = todo.pop()
                subtree.append(j)
                todo += children[j]
            for i in range(joint.count):
                c = self.layout.joint_x(k).start + i
                axis = Jw[:, columns.index(c)]
                g = np.zeros(self.nx)
                g[c] = 1.0
                for j in subtree:
                    s = self.layout.beam_x(j)
                    g[s] = self.beams[j].rigid_rates(x[s], F[j], np.zeros(3), axis, r)[0]
                out.append((joint.label(i), c, g))
        return out

    def mode_energy_split(self, x, F, u) -> dict[str, float]:
        """:meth:`kinetic_energy_split` of the rate u with every joint's rigid rotation taken out
        as a part of its own: for each joint axis, the kinetic energy of u[psi] g
        (:meth:`hinge_generators`) under its label ("flap hinge", "lag hinge", "pitch hinge",
        "hinge": axes of one label summed), and the split of what is left of u (the parts add
        up to the kinetic energy less the cross terms between the hinges' rotations and the rest)."""
        u = np.asarray(u)
        generators = self.hinge_generators(x, F)
        if not generators:
            return self.kinetic_energy_split(x, F, u)
        rest = np.array(u, copy=True)
        hinges: dict[str, float] = {}
        for label, c, g in generators:
            rotation = u[c] * g
            rest = rest - rotation
            hinges[label] = hinges.get(label, 0.0) + sum(self.kinetic_energy_split(x, F, rotation).values())
        split = self.kinetic_energy_split(x, F, rest)
        split.update(hinges)
        return split

    def hinge_labels(self) -> tuple[str, ...]:
        """The mode labels of the system's joint axes, each once, in the beams' order."""
        labels = [b.mount.joint.label(i) for b in self.beams if b.mount.joint is not None
                  for i in range(b.mount.joint.count)]
        return tuple(dict.fromkeys(labels))

    def root_axes(self, k: int, x, F=None) -> np.ndarray:
        """Beam k's undeformed axis frame (a_1 the axis, a_2, a_3) at x: the root section's axes
        turned back by the twist."""
        _, R = self.root_pose(k, x, F)
        c, s = np.cos(self.beams[k].mount.twist), np.sin(self.beams[k].mount.twist)
        return R @ np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])

    def _frame_and_rate(self, k: int, x, u, F=None):
        """Beam k's root frame (origin, axes) at x and its (origin velocity, angular velocity)
        at the rate u (complex u: complex rates)."""
        chain = self.frames.root(k)
        r, R, Jr, Jw, _, _ = chain_pose(self.frames.table, chain, x, F)
        cols = self.frames.chain(chain).coordinates
        cu = np.asarray(u)[cols]
        return (r, R), (Jr @ cu, Jw @ cu)

    def span_shape(self, k: int, x, F, u, stations):
        """Beam k's centre-line displacement along its axis frame (axial, flap, lag) and section
        twist at the stations for the change u about x (:meth:`BeamPart.span_shape`)."""
        part = self.beams[k]
        frame, rate = self._frame_and_rate(k, x, u, F)
        return part.span_shape(x[self.layout.beam_x(k)], F[k], np.asarray(u)[self.layout.beam_x(k)],
                               self.root_axes(k, x, F), np.asarray(stations, dtype=float), frame, rate)

    def base_motion(self, x, v):
        """The base frame (origin, axes, origin velocity, angular velocity; global) at (x, v)."""
        return self.frames.motion(self.frames.base, x, v)

    def base_motions(self, X, V):
        """:meth:`base_motion` at each row of X, V (states x nx) in one compiled call: (origins
        (n, 3), axes (n, 3, 3), origin velocities (n, 3), angular velocities (n, 3); global)."""
        from hubbeam.system.frame_motions import chain_motions

        X = np.ascontiguousarray(X, dtype=float).reshape(-1, self.nx)
        V = np.ascontiguousarray(V, dtype=float).reshape(-1, self.nx)
        n = X.shape[0]
        r, R, vel, w = np.empty((n, 3)), np.empty((n, 3, 3)), np.empty((n, 3)), np.empty((n, 3))
        chain_motions(self.frames.table, self.frames.base, X, V, np.zeros((1, 3, 3)), r, R, vel, w)
        return r, R, vel, w

    def base_rotation_vector(self, x) -> np.ndarray:
        """The rotation vector (rad, |phi| <= pi) of the base axes at x."""
        from hubbeam.system.rotations import rotation_vector

        return rotation_vector(self.frames.pose(self.frames.base, x)[1])

    def base_torque(self, t, x, v, F=None) -> np.ndarray:
        """A free base's attitude torque (N m, base axes) at the state, its controllers' included
        (charts F, default the initial ones); zero without a law or a controller."""
        from hubbeam.system.base_laws import BaseLaws, attitude_torque

        laws = [p for p in self.model().parts if isinstance(p, BaseLaws)]
        torque = self.controller_torques(t, x, v, F)[2]
        if not laws:
            return torque
        _, R, _, w = self.base_motion(x, v)
        e = np.ascontiguousarray(x[self.layout.base_x][3:], dtype=float)
        return torque + np.array(attitude_torque(laws[0], float(t), e, R.T @ w))

    def base_torque_column(self, x, axis: int) -> np.ndarray:
        """The generalized force (on x) of a unit torque on a moving base about its base axis
        ``axis`` (0, 1, 2): Jw^T R e_axis on the base's coordinates (N m per N m)."""
        from hubbeam.system.frames import chain_pose

        _, R, _, Jw, _, _ = chain_pose(self.frames.table, self.frames.base, x)
        out = np.zeros(self.nx)
        out[self.layout.base_x] = Jw.T @ R[:, axis]
        return out

    def angular_momentum(self, x, v, F) -> float:
        """The whole system's absolute angular momentum about the hub axis (the line through O
        along j_h; N m s), positive in the sense of theta' (about -j_h)."""
        mom = self.momenta(x, v, F)
        O, j_h = self.hub_axis(x)
        about_O = mom["angular"] - np.cross(O, mom["linear"])
        return float(-j_h @ about_O)

    def event_reached(self, x) -> bool:
        """Whether the state x reached an event of a part (a joint at its latch angle:
        :func:`hubbeam.system.joints.joint_events`)."""
        return bool(self.functions.system_events(self.model(), np.ascontiguousarray(x, dtype=float)))

    def step_powers(self, t, x, v, lam, F) -> tuple[float, float]:
        """(dissipated, drive) power at a state (W): the drag of Eq. 37 and the beams'
        structural damping (>= 0), and the applied torques' and prescribed motions' power
        (:func:`hubbeam.system.equations.step_powers`; a Python torque law is evaluated here)."""
        x, v, lam = (np.ascontiguousarray(u, dtype=float) for u in (x, v, lam))
        dissipated, drive = self.functions.step_powers(self.model(), np.ascontiguousarray(F, dtype=float), float(t),
                                                       x, v, lam)
        if not self.hub.torque.compilable and not self.hub.held:  # the controllers' power is compiled
            th = self.layout.theta
            drive += float(self.hub.torque(t, x[th], v[th])[0]) * float(v[th])
        if self.controller_laws:
            from hubbeam.system.controllers import law_power

            for law, pack in self._law_packs(self.hub.held, False):
                drive += law_power(law, pack, self.model().context, np.ascontiguousarray(F, dtype=float), x, v, t)
        if self.load_functions:
            drive += self._functions_for(self.hub.held, False).power(t, x, v, F)
        return float(dissipated), float(drive)

    def tip_position(self, x, beam: int = 0, F=None) -> np.ndarray:
        F = self.initial_state()[1] if F is None else F
        return self.beams[beam].tip_position(x[self.layout.beam_x(beam)], self.root_pose(beam, x, F))

    def tip_displacement(self, x, beam: int = 0, F=None) -> dict[str, float]:
        """Tip centroid displacement of a beam from its undeformed place, along its reference
        frame's axes (its own hub frame: radial, along the hub axis, tangential) (m)."""
        F = self.initial_state()[1] if F is None else F
        out = np.empty((len(self.beams), 3))
        self.functions.tip_displacements(self.model(), np.ascontiguousarray(F, dtype=float),
                                         np.ascontiguousarray(x, dtype=float), out)
        d = out[beam]
        return {"radial": float(d[0]), "vertical": float(d[1]), "tangential": float(d[2])}

    def surface_strain(self, x, F, station: float, y: float, z: float, beam: int = 0) -> float:
        return self.beams[beam].surface_strain(x[self.layout.beam_x(beam)], F[beam], station, y, z)

    def surface_strains_of_states(self, xs, F, station: float, y: float, z: float, beam: int = 0) -> np.ndarray:
        """:meth:`surface_strain` for each row of xs (states in the charts F)."""
        return self.beams[beam].surface_strains_of_states(xs[:, self.layout.beam_x(beam)], F[beam], station, y, z)

    def centre_line_at(self, x, F, stations, beam: int = 0) -> np.ndarray:
        """Beam ``beam``'s centre line (n x 3, global, m) at the stations (m from the root)."""
        return self.beams[beam].centre_line_at(x[self.layout.beam_x(beam)], F[beam], stations,
                                               self.root_pose(beam, x, F))

    def frames_at(self, x, F, stations, beam: int = 0) -> np.ndarray:
        """Beam ``beam``'s section frames (n x 3 x 3, global) at the stations."""
        return self.beams[beam].frames_at(x[self.layout.beam_x(beam)], F[beam], stations, self.root_pose(beam, x, F))

    def centre_line(self, x, F, beam: int = 0, points_per_element: int = 8) -> np.ndarray:
        return self.centre_line_at(x, F, self.beams[beam].stations(points_per_element), beam)
