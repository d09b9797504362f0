"""A base, a hub and its beams as one system (paper Sec. 4, and its moving base): what the
solvers see.

A :class:`MultibodySystem` is a :class:`~hubbeam.system.base.Base` (fixed in space, free, or
following a table), a :class:`Hub` on it (its angle theta, inertia, drive or torque law,
placed by a :class:`~hubbeam.system.base.HubPlacement`) and any number of beam parts
(:mod:`hubbeam.system.parts`: ANCF and FFR, mixed), each on its root frame, plus the
environment (gravity, the air drag of Eq. 37). Every frame (the base's, the hub's, each
beam's reference and root section frames, the rigid bodies') is a chain of
:mod:`hubbeam.system.frames` (:class:`Frames`); the :class:`~hubbeam.system.layout.Layout`
places coordinates x, multipliers lambda and Newton unknowns z. The equations of every part
are one compiled call (:func:`hubbeam.system.equations.system_equations`) into a bordered
band matrix; each kind of part present (:mod:`hubbeam.system.terms`: ANCF beams, FFR beams,
tip bodies, rigid bodies, the hub's law) gives its pack of constants to the compiled model
(:meth:`MultibodySystem.model`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from hubbeam.errors import ChartSingularityError
from hubbeam.system import kinds, terms  # noqa: F401  (kinds: the registration of every kind of part)
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.assembly import BorderedBandMatrix
from hubbeam.system.base import Base, HubPlacement
from hubbeam.system.beam import NODE_DOFS
from hubbeam.system.clamp import frame_clamp_equations
from hubbeam.system.equations import CHART_SINGULAR, Compiled, SystemModel, compiled, context
from hubbeam.system.frames import Chain, ChainTable, chain_pose, revolute
from hubbeam.system.laws import DriveProfile, TorqueLaw
from hubbeam.system.layout import CLAMP_EQUATIONS, Layout
from hubbeam.system.parts import BEAM_MOTIONS, BeamPart, ChartedBeamPart
from hubbeam.system.rigid_body import RigidBody
from hubbeam.system.tip_body import TipBody

MOTIONS = ("free", "prescribed", "fixed")
#: the hub's axis in its own frame: theta turns the hub about -j (Eq. 74)
HUB_AXIS = np.array([0.0, 1.0, 0.0])


@dataclass(frozen=True)
class Hub:
    """The hub: ``motion`` "free" (theta a coordinate, driven by the ``torque`` law),
    "prescribed" (theta = theta_p(t) of the ``drive`` profile, Eq. 82) or "fixed"
    (theta = 0), relative to the base; ``inertia`` about its axis (kg m^2)."""

    motion: str = "fixed"
    inertia: float = 1.0
    torque: TorqueLaw = field(default_factory=TorqueLaw)
    drive: DriveProfile = field(default_factory=lambda: DriveProfile("rest"))

    def __post_init__(self) -> None:
        if self.motion not in MOTIONS:
            raise ValueError(f"hub motion {self.motion!r}: choose one of {MOTIONS}")

    @property
    def held(self) -> bool:
        return self.motion != "free"


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


class Frames:
    """The frames of a system as chains (:mod:`hubbeam.system.frames`): the base's, the shaft's
    (the hub frame at theta = 0, the axes ANCF charts are chosen in), the hub's, and for every
    beam its reference frame (its own hub frame A_h(theta + psi): the tip deflection's axes; on
    a parent beam, the parent's tip frame), its joint frame (its axis frame, where its joint
    turns) and its root section frame; rigid bodies add theirs with :meth:`add`. A beam on a
    parent hangs on the parent's tip frame (:meth:`BeamPart.tip_frame`), so the parent comes
    first."""

    def __init__(self, base: Base, placement: HubPlacement, beams, layout: Layout) -> None:
        self._chains: list[Chain] = []
        base_chain = base.chain(layout.base_x.start)
        self.base = self.add(base_chain)
        self.shaft = self.add(base_chain.then(placement.link()))
        hub = self.chain(self.shaft).then(revolute(layout.theta, HUB_AXIS, -1.0))
        self.hub = self.add(hub)
        self._reference, self._root, self._joint, tips = [], [], [], []
        for k, part in enumerate(beams):
            mount = part.mount
            if mount.parent is None:
                frame, reference = hub, hub.then(mount.reference_link())
            elif 0 <= mount.parent < k:
                frame = reference = tips[mount.parent]
            else:
                raise ValueError(f"beam {k} hangs on beam {mount.parent}: a parent must come before its child")
            axis = frame.then(mount.axis_link())
            root = axis.then(*mount.joint_links(layout.joint_x(k).start), mount.twist_link())
            self._reference.append(self.add(reference))
            self._joint.append(self.add(axis))
            self._root.append(self.add(root))
            tips.append(part.tip_frame(layout.beam_x(k).start, k, root))
        self._second: set[int] = set()  # chains whose Hessians the equations read, besides the roots
        self._table: ChainTable | None = None

    def add(self, chain: Chain) -> int:
        """Register a chain; returns its index."""
        self._chains.append(chain)
        self._table = None
        return len(self._chains) - 1

    def chain(self, index: int) -> Chain:
        return self._chains[index]

    def root(self, k: int) -> int:
        """Beam k's root section frame."""
        return self._root[k]

    def reference(self, k: int) -> int:
        """Beam k's reference frame (its own hub frame: radial, along the hub axis, tangential;
        on a parent, the parent's tip frame)."""
        return self._reference[k]

    def joint(self, k: int) -> int:
        """Beam k's joint frame (a, b, c): its axis frame before its joint and twist."""
        return self._joint[k]

    def needs_hessian(self, index: int) -> int:
        """Mark chain ``index`` as one whose derivatives Hr, Hw the system's equations read
        (:func:`hubbeam.system.frames.evaluate_chains` evaluates only those to order 2);
        returns the index."""
        self._second.add(index)
        self._table = None
        return index

    @property
    def table(self) -> ChainTable:
        """Every chain in arrays; the Hessians of the beams' root frames (their velocity
        products, the ANCF clamps' second derivatives) and of the chains marked by
        :meth:`needs_hessian` (the rigid bodies') are evaluated in the equations."""
        if self._table is None:
            self._table = ChainTable.of(self._chains, self._second | set(self._root))
        return self._table

    def pose(self, index: int, x, F=None) -> tuple[np.ndarray, np.ndarray]:
        """(origin, axes) of chain ``index`` at x."""
        r, R, *_ = chain_pose(self.table, index, x, F)
        return r, R

    def motion(self, index: int, x, v, F=None):
        """(origin, axes, origin velocity, angular velocity) of chain ``index`` at (x, v) (global)."""
        r, R, Jr, Jw, _, _ = chain_pose(self.table, index, x, F)
        cols = self.chain(index).coordinates
        cd = np.asarray(v)[cols] if cols else np.zeros(0)
        return r, R, Jr @ cd, Jw @ cd


class MultibodySystem:
    """A base carrying a hub carrying beams. ``gravity`` (m/s^2, global), ``damping`` = (c1,
    c2) of Eq. 37; ``attachments``: parts of other registered kinds
    (:mod:`hubbeam.system.terms`) that have no coordinates of their own and act on the beams'
    (each kind's packer picks its own from this list); ``base`` and ``placement``: the hub's
    support (default: fixed at the origin, the hub's axis along j0); ``controllers``: linear
    controllers in the loop (:class:`~hubbeam.system.controllers.LinearController`), their
    states coordinates of the system (last in x, :class:`~hubbeam.system.layout.Layout`)."""

    def __init__(self, beams: list[BeamPart], hub: Hub = Hub(), gravity=(0.0, 0.0, 0.0),
                 damping: tuple[float, float] = (0.0, 0.0), attachments=(), base: Base = Base(),
                 placement: HubPlacement = HubPlacement(), controllers=()) -> None:
        self.beams = list(beams)
        self.controllers = tuple(controllers)
        if not self.beams and not base.moves:
            raise ValueError("a system needs at least one beam, or a base that moves")
        self.attachments = tuple(attachments)
        self.hub = hub
        self.base = base
        self.placement = placement
        self.gravity = np.asarray(gravity, dtype=float)
        self.damping = (float(damping[0]), float(damping[1]))
        self.layout = Layout(tuple(b.ndof for b in self.beams), hub.held, clamped=tuple(
            bool(getattr(b, "clamped", True)) for b in self.beams), base_moves=base.moves,
            base_held=base.table is not None, joint_dofs=tuple(b.mount.joint_count for b in self.beams),
            locks=tuple(0 if b.mount.joint is None else b.mount.joint.locks for b in self.beams),
            controller_states=sum(c.states for c in self.controllers))
        self.frames = Frames(base, placement, self.beams, self.layout)
        if base.moves and self.controllers:  # their base torques and rates read the base frame's Hessians
            self.frames.needs_hessian(self.frames.base)
        self.rigid_bodies = self._rigid_bodies()
        self._models: dict[tuple[bool, bool], SystemModel] = {}
        self._function_loads: dict[tuple[bool, bool], object] = {}
        self._laws: dict[tuple[bool, bool], list] = {}

    def _rigid_bodies(self) -> list[RigidBody]:
        """The hub's rotor (its inertia about its axis) and a free base's body."""
        bodies = []
        if self.hub.inertia > 0.0:
            J = float(self.hub.inertia)
            bodies.append(RigidBody("hub", self.frames.needs_hessian(self.frames.hub), 0.0,
                                    ((0.0, 0.0, 0.0), (0.0, J, 0.0), (0.0, 0.0, 0.0))))
        if self.base.moves and self.base.mass > 0.0:
            from hubbeam.system.frames import constant

            chain = self.frames.chain(self.frames.base).then(constant(self.base.centre_of_mass))
            bodies.append(RigidBody("base", self.frames.needs_hessian(self.frames.add(chain)), self.base.mass,
                                    tuple(map(tuple, self.base.inertia_matrix()))))
        return bodies

    # ------------------------------------------------------------ what the system is
    @property
    def motion(self) -> str:
        return self.hub.motion

    @property
    def drive(self) -> DriveProfile:
        return self.hub.drive

    @property
    def beam(self):
        """The first beam's element mesh (single-beam convenience)."""
        return self.beams[0].beam

    @property
    def nx(self) -> int:
        return self.layout.nx

    @property
    def theta_index(self) -> int:
        """The hub angle's place in x."""
        return self.layout.theta

    def layout_for(self, held: bool, static: bool = False) -> Layout:
        """The layout with the hub held or not; ``static``: statics, which also hold a free base
        at its initial pose (six constraints, as a table's)."""
        return self.layout.with_held(held, self.base.table is not None or (static and self.base.moves))

    def n_constraints(self, held: bool, static: bool = False) -> int:
        return self.layout_for(held, static).n_lambda

    def beam_index(self, name: str | None) -> int:
        """Index of the beam called ``name`` (None: the first)."""
        if name is None:
            return 0
        for k, b in enumerate(self.beams):
            if b.name == name:
                return k
        raise KeyError(name)

    @property
    def length_scale(self) -> float:
        """Length for relative tolerances on coordinates (m): the longest beam (1 m without beams)."""
        return max((b.length for b in self.beams), default=1.0)

    @property
    def mass_scale(self) -> float:
        """rho A l of the first beam's element (kg): scales the constraint rows of the dynamics
        (the base's mass without beams)."""
        if not self.beams:
            return float(self.base.mass)
        b = self.beams[0]
        return b.section.mass_per_length * b.beam.element_length

    @property
    def constraint_scale(self) -> float:
        """EA / l of the first beam (N/m): scales the constraint rows of the statics."""
        if not self.beams:
            return 1.0
        b = self.beams[0]
        return b.section.stiffness[0] / b.beam.element_length

    def _with(self, **changes) -> "MultibodySystem":
        args = dict(beams=self.beams, hub=self.hub, gravity=self.gravity, damping=self.damping,
                    attachments=self.attachments, base=self.base, placement=self.placement,
                    controllers=self.controllers)
        args.update(changes)
        return MultibodySystem(**args)

    def with_beams(self, beams) -> "MultibodySystem":
        """The same system with other beam parts (the same number, each in its place)."""
        return self._with(beams=list(beams))

    def with_attachments(self, attachments) -> "MultibodySystem":
        """The same system with these parts of other kinds (``attachments``) instead of its own."""
        return self._with(attachments=tuple(attachments))

    def without_controllers(self) -> "MultibodySystem":
        """The same system without its controllers (the plant they close the loop around)."""
        return self._with(controllers=())

    def without_damping(self) -> "MultibodySystem":
        """The same system without air drag, without the beams' structural damping and without the
        joints' dampers."""
        beams = []
        for b in self.beams:
            b = b.without_structural_damping()
            joint = b.mount.joint
            if joint is not None and any(joint.damping):
                b = replace(b, mount=replace(b.mount, joint=replace(joint, damping=(0.0,) * joint.count)))
            beams.append(b)
        return self._with(beams=beams, damping=(0.0, 0.0))

    def without_motors(self) -> "MultibodySystem":
        """The same system without its joints' motor laws (springs and dampers kept)."""
        beams = [replace(b, mount=replace(b.mount, joint=replace(b.mount.joint, torque=None)))
                 if b.mount.joint is not None and b.mount.joint.torque is not None else b for b in self.beams]
        return self._with(beams=beams)

    def with_hub(self, **changes) -> "MultibodySystem":
        """The same beams on a hub with some fields changed (motion, drive, torque, inertia)."""
        return self._with(hub=replace(self.hub, **changes))

    def with_gravity(self, gravity) -> "MultibodySystem":
        """The same system under another uniform gravity (m/s^2)."""
        return self._with(gravity=gravity)

    # ------------------------------------------------------------ frames
    @property
    def hub_axis_rotation(self) -> np.ndarray:
        """R(0) R_h: the axes of the hub frame at theta = 0 at the start (the hub axis is its j)."""
        return self.base.initial_rotation @ self.placement.rotation

    def shaft_axes(self, x) -> np.ndarray:
        """R R_h at x: the hub frame's axes at theta = 0 (the axes ANCF charts are chosen in)."""
        return self.frames.pose(self.frames.shaft, x)[1]

    def root_pose(self, k: int, x, F=None) -> tuple[np.ndarray, np.ndarray]:
        """Beam k's root section frame (origin, axes) at x."""
        return self.frames.pose(self.frames.root(k), x, F)

    def root_motion(self, k: int, x, v, F=None):
        """Beam k's root frame (origin, axes, origin velocity, angular velocity) at (x, v)."""
        return self.frames.motion(self.frames.root(k), x, v, F)

    def hub_axis(self, x) -> tuple[np.ndarray, np.ndarray]:
        """(O, j_h): the hub's origin and axis (global) at x."""
        r, R = self.frames.pose(self.frames.hub, x)
        return r, R[:, 1]

    # ------------------------------------------------------------ states
    def initial_state(self, theta: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Straight undeformed beams on their root frames with the hub at angle theta and the
        base at its initial pose: (x, charts (nb, 3, 3)); the charts are chosen in the hub's
        axes at theta = 0 (a model turned as a whole has turned charts)."""
        x = np.zeros(self.nx)
        if self.base.moves:
            x[self.layout.base_x] = self.base.initial_coordinates()
        x[self.layout.theta] = theta
        charts = np.tile(np.eye(3), (len(self.beams), 1, 1))
        reference = self.shaft_axes(x)
        for k, part in enumerate(self.beams):  # parents first: a child's root frame is its parent's tip
            if part.mount.joint is not None:
                x[self.layout.joint_x(k)] = part.mount.joint.initial_angle
            r, R = self.root_pose(k, x, charts)
            x[self.layout.beam_x(k)], charts[k] = part.initial_state(r, R, reference)
        return x, charts

    def parts(self, x, F):
        """(k, part, q_k, chart_k) for every beam."""
        for k, part in enumerate(self.beams):
            yield k, part, x[self.layout.beam_x(k)], F[k]

    def rigid_rates(self, x, F, omega: float = 0.0, velocity=(0.0, 0.0, 0.0), angular_velocity=(0.0, 0.0, 0.0),
                    steady: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """Velocity (and, with ``steady``, acceleration) of x when the whole system moves rigidly:
        the base at ``velocity`` (of O_b, m/s, global) and ``angular_velocity`` (rad/s, global),
        the hub turning on it at theta' = omega (rad/s) about -j_h. ``steady``: a steady
        rotation about the hub axis of a base at rest (accelerations w x (w x r))."""
        v, a = np.zeros(self.nx), np.zeros(self.nx)
        v[self.layout.theta] = omega
        v_b, w_b = np.asarray(velocity, dtype=float), np.asarray(angular_velocity, dtype=float)
        if self.base.moves:
            from hubbeam.system.frames import euler_rate_matrix

            e = x[self.layout.base_x][3:7]
            E = np.empty((3, 4))
            euler_rate_matrix(e, E)
            v[self.layout.base_x] = np.concatenate([v_b, 0.5 * E.T @ w_b])  # w = 2 E e' / (e . e)
        r_b = self.frames.pose(self.frames.base, x)[0]
        O, j_h = self.hub_axis(x)
        w = w_b - omega * j_h
        for k, part, q, chart in self.parts(x, F):
            s = self.layout.beam_x(k)
            # points move at v_b + w_b x (r - r_b) - omega j_h x (r - O) = (v_b + w_b x (O - r_b)) + w x (r - O)
            v_O = v_b + np.cross(w_b, O - r_b)
            v[s], a[s] = part.rigid_rates(q, chart, v_O, w, O, np.zeros(3) if steady else None)
        return v, a

    def initial_rates(self, x, F) -> np.ndarray:
        """The rates at t = 0 of a system at rest relative to its base: the base's own (a free
        base's initial velocity and angular velocity, or a table's rates at t = 0) carried
        rigidly by everything on it (zero for a fixed base), and the joints' initial rates, each
        beam carried rigidly by its root frame."""
        v = self._base_rates(x, F)
        if not any(np.any(part.mount.joint.initial_rate) for part in self.beams if part.mount.joint is not None):
            return v
        for k, part in enumerate(self.beams):  # parents first
            if part.mount.joint is not None:
                v[self.layout.joint_x(k)] = part.mount.joint.initial_rate
            r, _, v_r, w = self.root_motion(k, x, v, F)
            s = self.layout.beam_x(k)
            v[s] = part.rigid_rates(x[s], F[k], v_r, w, r)[0]
        return v

    def _base_rates(self, x, F) -> np.ndarray:
        """The rates at t = 0 of everything at rest relative to the base (zero for a fixed base)."""
        if not self.base.moves:
            return np.zeros(self.nx)
        if self.base.table is not None:
            from hubbeam.system.base_laws import rotation_vector_quaternion, table_values
            from hubbeam.system.frames import euler_rate_matrix

            values = table_values(self.base.table.knots, self.base.table.coefs, 0.0)
            q, dq, ddq = np.empty(4), np.empty(4), np.empty(4)
            rotation_vector_quaternion(values[3], values[4], values[5], q, dq, ddq)
            E = np.empty((3, 4))
            euler_rate_matrix(q, E)
            return self.rigid_rates(x, F, velocity=values[1], angular_velocity=2.0 * E @ dq)[0]
        R0 = self.frames.pose(self.frames.base, x)[1]
        return self.rigid_rates(x, F, velocity=self.base.velocity, angular_velocity=R0 @ np.asarray(
            self.base.angular_velocity))[0]

    def steady_rotation_rates(self, x, F, omega: float) -> tuple[np.ndarray, np.ndarray]:
        """Velocity and acceleration of x when the whole system turns rigidly with the hub at
        theta' = omega (rad/s) on a base at rest (angular velocity w = -omega j_h, Eq. 74)."""
        return self.rigid_rates(x, F, omega, steady=True)

    # ------------------------------------------------------------ charts
    def chart_margin(self, x, F) -> float:
        """min(1 + d.tau) over every charted beam's Gauss points: 0 at a chart's singular direction."""
        margins = [part.chart_margin(q, chart) for _, part, q, chart in self.parts(x, F)
                   if isinstance(part, ChartedBeamPart)]
        return min(margins, default=2.0)

    def better_chart(self, x, F=None, limit: float | None = None) -> np.ndarray:
        """Charts for every beam: a better one for each charted beam whose margin is below
        ``limit`` (every charted beam when ``limit`` is None or F is None), chosen in the hub's
        axes at theta = 0."""
        new = np.array(F, dtype=float) if F is not None else self.initial_state(0.0)[1]
        reference = self.shaft_axes(x)
        for k, part in enumerate(self.beams):
            if not isinstance(part, ChartedBeamPart):
                continue
            q = x[self.layout.beam_x(k)]
            if F is None or limit is None or part.chart_margin(q, F[k]) < limit:
                new[k] = part.better_chart(q, reference)
        return new

    def remap(self, x, F, F_new) -> np.ndarray:
        """x re-expressed in the charts F_new (same configuration)."""
        out = np.array(x, dtype=float)
        for k, part, q, chart in self.parts(x, F):
            if isinstance(part, ChartedBeamPart) and not np.array_equal(chart, F_new[k]):
                out[self.layout.beam_x(k)] = part.remap(q, chart, F_new[k])
        return out

    def axis_chart(self, x, F) -> tuple[np.ndarray, np.ndarray]:
        """x re-expressed in the charts in which a rigid rotation about the hub axis is exact
        (director -j_h, its second axis i_h at theta = 0)."""
        F_new = np.array(F, dtype=float)
        S = self.shaft_axes(x)
        for k, part in enumerate(self.beams):
            if isinstance(part, ChartedBeamPart):
                F_new[k] = part.axis_chart(S[:, 1], S[:, 0])
        return self.remap(x, F, F_new), F_new

    # ------------------------------------------------------------ compiled model
    def bandwidth_for(self, layout: Layout) -> int:
        """Half-bandwidth of the Newton matrix's band for ``layout``: the widest any kind of part
        present needs (and the whole leading block when the border is empty)."""
        width = max(kind.bandwidth(self, layout) for kind in terms.KINDS)
        if layout.border == 0:
            width = max(width, layout.leading)
        return width

    @property
    def bandwidth(self) -> int:
        return self.bandwidth_for(self.layout)

    @property
    def compiled(self) -> bool:
        """Whether the time integration runs in compiled code: every part does; a torque law
        that is a Python function takes the Python step (on a free hub: a held hub ignores its
        torque law), as does a load from a Python function (:attr:`load_functions`) or a Python
        controller law (:attr:`controller_laws`)."""
        return (self.hub.held or self.hub.torque.compilable) and not self.load_functions and not self.controller_laws

    @property
    def load_functions(self) -> list:
        """The attachments that are loads from Python functions
        (:class:`hubbeam.system.load_functions.LoadFunction`), evaluated in Python."""
        from hubbeam.system.load_functions import LoadFunction

        return [a for a in self.attachments if isinstance(a, LoadFunction)]

    def _functions_for(self, held: bool, static: bool):
        """The :class:`~hubbeam.system.load_functions.FunctionLoads` of the layout (held, static)."""
        from hubbeam.system.load_functions import FunctionLoads

        key = (bool(held), bool(static) and self.base.moves)
        if key not in self._function_loads:
            self._function_loads[key] = FunctionLoads(self, self.layout_for(*key), self.model(*key).context,
                                                      self.load_functions)
        return self._function_loads[key]

    @property
    def controller_laws(self) -> list:
        """The controllers that are Python laws (:class:`~hubbeam.system.controllers.ControllerLaw`)."""
        from hubbeam.system.controllers import ControllerLaw

        return [c for c in self.controllers if isinstance(c, ControllerLaw)]

    def _law_packs(self, held: bool, static: bool) -> list:
        """(law, its pack) of each Python controller law for the layout (held, static), built once."""
        from hubbeam.system.controllers import law_pack

        key = (bool(held), bool(static))
        if key not in self._laws:
            layout = self.layout_for(held, static)
            self._laws[key] = [(law, law_pack(self, layout, law)) for law in self.controller_laws]
        return self._laws[key]

    def model(self, held: bool | None = None, static: bool = False) -> SystemModel:
        """The constants of the compiled equations for the hub held or not (default: its motion)
        and, with ``static``, a free base held (:meth:`layout_for`)."""
        held = self.hub.held if held is None else held
        key = (bool(held), bool(static) and self.base.moves)
        if key not in self._models:
            layout = self.layout_for(*key)
            bandwidth = self.bandwidth_for(layout)
            packs = terms.packs(self, layout)
            self._models[key] = SystemModel(packs,
                                            context(layout, bandwidth, self.gravity, self.damping, self.frames.table),
                                            bandwidth, terms.with_events(packs))
        return self._models[key]

    @property
    def functions(self) -> Compiled:
        """The compiled functions of the model (:func:`hubbeam.system.equations.compiled`):
        numba-cached unless a kind of part of this system is defined outside hubbeam."""
        return compiled(terms.native(self.model().parts))

    # ------------------------------------------------------------ equations
    def equations(self, x, v, acc, lam, F, t, coef_m, coef_c, coef_k, scale, load_factor=1.0,
                  want_matrix=True, held=None, stiffness="dynamic", static=False):
        """Scaled residual on z and Newton matrix coef_m M + coef_c C + coef_k (K - dQ/dx +
        lambda.d2 Phi) of the equations of motion (Eq. 77), lambda = scale mu / coef_k (see
        :func:`~hubbeam.system.equations.system_equations`). ``held`` overrides the hub's
        drive constraint (statics hold the hub); ``static`` holds a free base too.
        ``stiffness``: "dynamic" (the iteration matrix) or "exact" (every load's and frame's
        stiffness, for statics and modes). Returns (residual, BorderedBandMatrix)."""
        held = self.hub.held if held is None else held
        model = self.model(held, static)
        layout = self.layout_for(held, static)
        res = np.empty(layout.nz)
        matrix = BorderedBandMatrix.empty(layout.nz, layout.border, model.bandwidth)
        F = np.ascontiguousarray(F, dtype=float)
        x, v, acc, lam = (np.ascontiguousarray(a, dtype=float) for a in (x, v, acc, lam))
        margin, _ = self.functions.system_equations(model, F, x, v, acc, lam, float(t), float(coef_m), float(coef_c),
                                                    float(coef_k), float(scale), float(load_factor),
                                                    stiffness == "exact", bool(want_matrix), res, matrix.ab,
                                                    matrix.brow, matrix.bcol, matrix.bb)
        if not margin > CHART_SINGULAR:
            raise ChartSingularityError(
                f"a beam tangent is at the singular direction of the rotation chart (1 + d.tau = {margin:.2e})")
        if not self.hub.torque.compilable and not held:  # a Python torque law (its derivatives by differences)
            th = layout.theta
            torque, d_theta, d_omega = self.hub.torque(t, x[th], v[th])
            res[layout.z_of_x[th]] -= coef_k * load_factor * torque
            if want_matrix:
                matrix.add(layout.z_of_x[th], layout.z_of_x[th], -load_factor * (coef_k * d_theta + coef_c * d_omega))
        if self.load_functions:  # loads from Python functions (their matrix by differences)
            self._functions_for(held, static).add(t, x, v, F, coef_c, coef_k, load_factor, want_matrix, res, matrix,
                                                  layout.z_of_x)
        if self.controller_laws and not static:  # Python controller laws (dy/du by differences)
            from hubbeam.system.controllers import law_terms

            for law, pack in self._law_packs(held, static):
                law_terms(law, pack, model.context, F, x, v, t, coef_c, coef_k, load_factor, want_matrix,
                          res, matrix)
        return res, matrix

    def dynamic_residual(self, x, v, acc, lam, F, t, coef_k, scale):
        """Scaled residual of the equations of motion on z (no matrix)."""
        return self.equations(x, v, acc, lam, F, t, 0.0, 0.0, coef_k, scale, want_matrix=False)[0]

    def dynamic_equations(self, x, v, acc, lam, F, t, coef_m, coef_c, coef_k, scale):
        """Scaled residual and Newton matrix of the equations of motion on z."""
        return self.equations(x, v, acc, lam, F, t, coef_m, coef_c, coef_k, scale)

    # ------------------------------------------------------------ statics and linearisation
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

    # ------------------------------------------------------------ measured quantities
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
        from hubbeam.system.frames import chain_motions

        X = np.ascontiguousarray(X, dtype=float).reshape(-1, self.nx)
        V = np.ascontiguousarray(V, dtype=float).reshape(-1, self.nx)
        n = X.shape[0]
        r, R, vel, w = np.empty((n, 3)), np.empty((n, 3, 3)), np.empty((n, 3)), np.empty((n, 3))
        chain_motions(self.frames.table, self.frames.base, X, V, np.zeros((1, 3, 3)), r, R, vel, w)
        return r, R, vel, w

    def base_rotation_vector(self, x) -> np.ndarray:
        """The rotation vector (rad, |phi| <= pi) of the base axes at x."""
        from hubbeam.system.frames import rotation_vector

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
            from hubbeam.system.controllers import law_terms

            scratch = np.zeros(self.layout.nz)
            for law, pack in self._law_packs(self.hub.held, False):
                drive += law_terms(law, pack, self.model().context, np.ascontiguousarray(F, dtype=float),
                                   x, v, t, 0.0, 1.0, 1.0, False, scratch, None)
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


def single_beam_system(beam, radius: float = 0.0, twist: float = 0.0, motion: str = "fixed",
                       hub_inertia: float = 1.0, hub_torque: float | TorqueLaw = 0.0,
                       drive: DriveProfile | None = None, gravity=(0.0, 0.0, 0.0), tip_force=(0.0, 0.0, 0.0),
                       tip_moment=(0.0, 0.0, 0.0), damping=(0.0, 0.0), tip_body: TipBody | None = None,
                       azimuth: float = 0.0, precone: float = 0.0) -> MultibodySystem:
    """A hub with one beam (an :class:`~hubbeam.system.beam.AncfBeam` or an
    :class:`~hubbeam.elements.ffr.body.FfrBeam`), the paper's system."""
    from hubbeam.elements.ffr.body import FfrBeam
    from hubbeam.system.ffr_part import FfrPart
    from hubbeam.system.mount import Mount

    mount = Mount(radius, twist, azimuth, precone)
    if isinstance(beam, FfrBeam):
        if tip_body is not None:
            beam = replace(beam, tip_body=tip_body)
        part = FfrPart(beam, mount, tip_force=tip_force, tip_moment=tip_moment)
    else:
        part = AncfPart(beam, mount, tip_body=tip_body, tip_force=tip_force, tip_moment=tip_moment)
    torque = hub_torque if isinstance(hub_torque, TorqueLaw) else TorqueLaw.constant(float(hub_torque))
    hub = Hub(motion, hub_inertia, torque, drive if drive is not None else DriveProfile("rest"))
    return MultibodySystem([part], hub, gravity, damping)
