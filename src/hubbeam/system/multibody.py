"""A base, a hub and its beams as one system (paper Sec. 4, and its moving base): what the
solvers see.

A :class:`MultibodySystem` is a :class:`~hubbeam.system.base.Base` (fixed in space, free, or
following a table), a :class:`Hub` on it (its angle theta, inertia, drive or torque law,
placed by a :class:`~hubbeam.system.base.HubPlacement`) and any number of beam parts
(:mod:`hubbeam.system.parts`: ANCF and FFR, mixed), each on its root frame, plus the
environment (gravity, the air drag of Eq. 37). Every frame (the base's, the hub's, each
beam's reference and root section frames, the rigid bodies') is a chain of
:mod:`hubbeam.system.frames` (:class:`~hubbeam.system.system_frames.Frames`); the :class:`~hubbeam.system.layout.Layout`
places coordinates x, multipliers lambda and Newton unknowns z. The equations of every part
are one compiled call (:func:`hubbeam.system.equations.system_equations`) into a bordered
band matrix; each kind of part present (:mod:`hubbeam.system.terms`: ANCF beams, FFR beams,
tip bodies, rigid bodies, the hub's law) gives its pack of constants to the compiled model
(:meth:`MultibodySystem.model`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from enum import Enum

import numpy as np

from hubbeam.errors import ChartSingularityError
from hubbeam.system import kinds, terms  # noqa: F401  (kinds: the registration of every kind of part)
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.assembly import BorderedBandMatrix
from hubbeam.system.base import Base, HubPlacement
from hubbeam.system.controller_inputs import hessian_chains
from hubbeam.system.equations import CHART_SINGULAR, Compiled, SystemModel, compiled, context
from hubbeam.system.laws import DriveProfile, TorqueLaw
from hubbeam.system.layout import Layout
from hubbeam.system.measures import SystemMeasures, energy_sums  # noqa: F401  (energy_sums: re-exported)
from hubbeam.system.parts import BeamPart, ChartedBeamPart
from hubbeam.system.rigid_body import RigidBody
from hubbeam.system.statics import SystemStatics
from hubbeam.system.system_frames import Frames
from hubbeam.system.tip_body import TipBody

MOTIONS = ("free", "prescribed", "fixed")


class PerLayout(Enum):
    """What a :class:`MultibodySystem` builds once per layout (:meth:`MultibodySystem._per_layout`)."""

    MODEL = "the compiled equations' constants"
    FUNCTION_LOADS = "the loads from Python functions"
    CONTROLLER_LAWS = "the Python controller laws' packs"


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


class MultibodySystem(SystemStatics, SystemMeasures):
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
        for controller in self.controllers:  # and a tip deflection's rate its root's and reference frame's
            for chain in hessian_chains(self, controller.inputs):
                self.frames.needs_hessian(chain)
        self.rigid_bodies = self._rigid_bodies()
        #: what is built once per layout (:meth:`_per_layout`): the compiled equations' constants,
        #: the loads from Python functions and the Python controller laws' packs
        self._built: dict[tuple[PerLayout, bool, bool], object] = {}

    def _rigid_bodies(self) -> list[RigidBody]:
        """The hub's rotor (its inertia about its axis) and a free base's body."""
        bodies = []
        if self.hub.inertia > 0.0:
            J = float(self.hub.inertia)
            bodies.append(RigidBody("hub", self.frames.needs_products(self.frames.hub), 0.0,
                                    ((0.0, 0.0, 0.0), (0.0, J, 0.0), (0.0, 0.0, 0.0))))
        if self.base.moves and self.base.mass > 0.0:
            from hubbeam.system.chains import constant

            chain = self.frames.chain(self.frames.base).then(constant(self.base.centre_of_mass))
            bodies.append(RigidBody("base", self.frames.needs_products(self.frames.add(chain)), self.base.mass,
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

    def _per_layout(self, what: PerLayout, held: bool, static: bool, build):
        """``build(held, static)``, built once for each layout (:meth:`layout_for`): ``static`` counts
        only where the base moves (a fixed base's statics use the layout of its runs)."""
        key = (what, bool(held), bool(static) and self.base.moves)
        if key not in self._built:
            self._built[key] = build(*key[1:])
        return self._built[key]

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
            from hubbeam.system.rotations import euler_rate_matrix

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
            from hubbeam.system.rotations import euler_rate_matrix

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

        return self._per_layout(PerLayout.FUNCTION_LOADS, held, static, lambda h, s: FunctionLoads(
            self, self.layout_for(h, s), self.model(h, s).context, self.load_functions))

    @property
    def controller_laws(self) -> list:
        """The controllers that are Python laws (:class:`~hubbeam.system.controllers.ControllerLaw`)."""
        from hubbeam.system.controllers import ControllerLaw

        return [c for c in self.controllers if isinstance(c, ControllerLaw)]

    def _law_packs(self, held: bool, static: bool) -> list:
        """(law, its pack) of each Python controller law for the layout (held, static), built once."""
        from hubbeam.system.controllers import law_pack

        return self._per_layout(PerLayout.CONTROLLER_LAWS, held, static, lambda h, s: [
            (law, law_pack(self, self.layout_for(h, s), law)) for law in self.controller_laws])

    def model(self, held: bool | None = None, static: bool = False) -> SystemModel:
        """The constants of the compiled equations for the hub held or not (default: its motion)
        and, with ``static``, a free base held (:meth:`layout_for`)."""
        held = self.hub.held if held is None else held
        return self._per_layout(PerLayout.MODEL, held, static, self._build_model)

    def _build_model(self, held: bool, static: bool) -> SystemModel:
        layout = self.layout_for(held, static)
        bandwidth = self.bandwidth_for(layout)
        packs = terms.packs(self, layout)
        ctx = context(layout, bandwidth, self.gravity, self.damping, self.frames.table)
        return SystemModel(packs, ctx, bandwidth, terms.with_events(packs), terms.with_powers(packs, ctx))

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
