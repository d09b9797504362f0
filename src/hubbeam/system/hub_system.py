"""The hub and its beams as one system (paper Sec. 4): what the solvers see.

A :class:`HubSystem` is a :class:`Hub` (its angle theta, inertia, drive or torque law) and
any number of beam parts (:mod:`hubbeam.system.parts`: ANCF and FFR, mixed), each clamped
to the hub by six equations, plus the environment (gravity, the air drag of Eq. 37). The
:class:`~hubbeam.system.layout.Layout` places coordinates x, multipliers lambda and Newton
unknowns z. The equations of the hub and every part are one compiled call
(:func:`hubbeam.system.equations.system_equations`) into a bordered band matrix; each
kind of part present (:mod:`hubbeam.system.terms`: ANCF beams, FFR beams, tip bodies)
gives its pack of constants to the compiled model (:meth:`HubSystem.model`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from hubbeam.errors import ChartSingularityError
from hubbeam.elements.ffr.kernels import ffr_spin_stiffness, pack
from hubbeam.system import ffr_part, terms, tip_body  # noqa: F401  (importing a kind's module registers it)
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.assembly import BorderedBandMatrix
from hubbeam.system.beam import NODE_DOFS
from hubbeam.system.equations import CHART_SINGULAR, Compiled, SystemModel, compiled, context
from hubbeam.system.laws import DriveProfile, TorqueLaw
from hubbeam.system.layout import CLAMP_EQUATIONS, Layout
from hubbeam.system.parts import BEAM_MOTIONS, BeamPart, ChartedBeamPart
from hubbeam.system.tip_body import TipBody

#: the hub's axis j0 (global); the hub turns about -j0 for increasing theta (Eq. 74)
AXIS = np.array([0.0, 1.0, 0.0])
MOTIONS = ("free", "prescribed", "fixed")


@dataclass(frozen=True)
class Hub:
    """The hub: ``motion`` "free" (theta a coordinate, driven by the ``torque`` law),
    "prescribed" (theta = theta_p(t) of the ``drive`` profile, Eq. 82) or "fixed"
    (theta = 0); ``inertia`` about j0 (kg m^2)."""

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
    """{kinetic, strain, gravity} (J) from the hub's row (its kinetic energy and the
    energies of parts that belong to no beam) and the beams' rows (kinetic, strain,
    gravity): of the whole system, or of beam number ``beam`` alone. hub (3,) and beams
    (beams, 3) give floats; a leading axis of records, hub (n, 3) and beams (n, beams, 3),
    gives arrays (n,), the same sums record by record."""
    hub, beams = np.asarray(hub, dtype=float), np.asarray(beams, dtype=float)
    if beam is not None:
        parts = beams[..., beam, :]
    else:
        parts = hub
        for k in range(beams.shape[-2]):  # in the beams' order, as a sum over the parts
            parts = parts + beams[..., k, :]
    return {name: float(e) if e.ndim == 0 else e for name, e in zip(("kinetic", "strain", "gravity"), parts.T)}


class HubSystem:
    """A hub carrying beams. ``gravity`` (m/s^2, global), ``damping`` = (c1, c2) of Eq. 37;
    ``attachments``: parts of other registered kinds (:mod:`hubbeam.system.terms`) that have
    no coordinates of their own and act on the hub's and the beams' (each kind's packer picks
    its own from this list)."""

    def __init__(self, beams: list[BeamPart], hub: Hub = Hub(), gravity=(0.0, 0.0, 0.0),
                 damping: tuple[float, float] = (0.0, 0.0), attachments=()) -> None:
        if not beams:
            raise ValueError("a hub system needs at least one beam")
        self.beams = list(beams)
        self.attachments = tuple(attachments)
        self.hub = hub
        self.gravity = np.asarray(gravity, dtype=float)
        self.damping = (float(damping[0]), float(damping[1]))
        self.layout = Layout(tuple(b.ndof for b in self.beams), hub.held)
        self._models: dict[bool, SystemModel] = {}

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

    def layout_for(self, held: bool) -> Layout:
        return self.layout.with_held(held)

    def n_constraints(self, held: bool) -> int:
        return self.layout_for(held).n_lambda

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
        """Length for relative tolerances on coordinates (m): the longest beam."""
        return max(b.length for b in self.beams)

    @property
    def mass_scale(self) -> float:
        """rho A l of the first beam's element (kg): scales the constraint rows of the dynamics."""
        b = self.beams[0]
        return b.section.mass_per_length * b.beam.element_length

    @property
    def constraint_scale(self) -> float:
        """EA / l of the first beam (N/m): scales the constraint rows of the statics."""
        b = self.beams[0]
        return b.section.stiffness[0] / b.beam.element_length

    def without_damping(self) -> "HubSystem":
        """The same system without air drag and without the beams' structural damping."""
        return HubSystem([b.without_structural_damping() for b in self.beams], self.hub, self.gravity, (0.0, 0.0),
                         self.attachments)

    def with_hub(self, **changes) -> "HubSystem":
        """The same beams on a hub with some fields changed (motion, drive, torque, inertia)."""
        return HubSystem(self.beams, replace(self.hub, **changes), self.gravity, self.damping, self.attachments)

    # ------------------------------------------------------------ states
    def initial_state(self, theta: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Straight undeformed beams clamped to the hub at angle theta: (x, charts (nb, 3, 3))."""
        x = np.empty(self.nx)
        x[0] = theta
        charts = np.empty((len(self.beams), 3, 3))
        for k, part in enumerate(self.beams):
            x[self.layout.beam_x(k)], charts[k] = part.initial_state(theta)
        return x, charts

    def parts(self, x, F):
        """(k, part, q_k, chart_k) for every beam."""
        for k, part in enumerate(self.beams):
            yield k, part, x[self.layout.beam_x(k)], F[k]

    def steady_rotation_rates(self, x, F, omega: float) -> tuple[np.ndarray, np.ndarray]:
        """Velocity and acceleration of x when the whole system turns rigidly with the hub at
        theta' = omega (rad/s) (angular velocity w = -omega j0, Eq. 74)."""
        v, a = np.zeros(self.nx), np.zeros(self.nx)
        v[0] = omega
        for k, part, q, chart in self.parts(x, F):
            s = self.layout.beam_x(k)
            v[s], a[s] = part.steady_rotation_rates(q, chart, omega)
        return v, a

    # ------------------------------------------------------------ charts
    def chart_margin(self, x, F) -> float:
        """min(1 + d.tau) over every charted beam's Gauss points: 0 at a chart's singular direction."""
        margins = [part.chart_margin(q, chart) for _, part, q, chart in self.parts(x, F)
                   if isinstance(part, ChartedBeamPart)]
        return min(margins, default=2.0)

    def better_chart(self, x, F=None, limit: float | None = None) -> np.ndarray:
        """Charts for every beam: a better one for each charted beam whose margin is below
        ``limit`` (every charted beam when ``limit`` is None or F is None)."""
        new = np.array(F, dtype=float) if F is not None else self.initial_state(0.0)[1]
        for k, part in enumerate(self.beams):
            if not isinstance(part, ChartedBeamPart):
                continue
            q = x[self.layout.beam_x(k)]
            if F is None or limit is None or part.chart_margin(q, F[k]) < limit:
                new[k] = part.better_chart(q)
        return new

    def remap(self, x, F, F_new) -> np.ndarray:
        """x re-expressed in the charts F_new (same configuration)."""
        out = np.array(x, dtype=float)
        for k, part, q, chart in self.parts(x, F):
            if isinstance(part, ChartedBeamPart) and not np.array_equal(chart, F_new[k]):
                out[self.layout.beam_x(k)] = part.remap(q, chart, F_new[k])
        return out

    def axis_chart(self, x, F) -> tuple[np.ndarray, np.ndarray]:
        """x re-expressed in the charts in which a rigid rotation about the hub axis is exact."""
        F_new = np.array(F, dtype=float)
        for k, part in enumerate(self.beams):
            if isinstance(part, ChartedBeamPart):
                F_new[k] = part.axis_chart()
        return self.remap(x, F, F_new), F_new

    # ------------------------------------------------------------ compiled model
    @property
    def bandwidth(self) -> int:
        """Half-bandwidth of the beams' blocks of the Newton matrix: the widest any kind of
        part present needs."""
        return max(kind.bandwidth(self) for kind in terms.KINDS)

    @property
    def compiled(self) -> bool:
        """Whether the time integration runs in compiled code: every beam does; a torque law
        that is a Python function takes the Python step (on a free hub: a held hub ignores
        its torque law)."""
        return self.hub.held or self.hub.torque.compilable

    def model(self, held: bool | None = None) -> SystemModel:
        """The constants of the compiled equations for the hub held or not (default: its motion)."""
        held = self.hub.held if held is None else held
        if held not in self._models:
            self._models[held] = self._build_model(held)
        return self._models[held]

    def _build_model(self, held: bool) -> SystemModel:
        layout = self.layout_for(held)
        # a fixed hub is held at theta = 0: the profile 'rest'
        drive = self.hub.drive if self.motion == "prescribed" else DriveProfile("rest")
        torque = self.hub.torque if (not held and self.hub.torque.compilable) else TorqueLaw()
        return SystemModel(
            held,
            -1 if layout.drive_lambda is None else layout.drive_lambda, float(self.hub.inertia),
            tuple(drive.compiled()), tuple(torque.compiled()), terms.packs(self, layout),
            context(layout, self.bandwidth, self.gravity, self.damping), self.bandwidth,
        )

    @property
    def functions(self) -> Compiled:
        """The compiled functions of the model (:func:`hubbeam.system.equations.compiled`):
        numba-cached unless a kind of part of this system is defined outside hubbeam."""
        return compiled(terms.native(self.model().parts))

    # ------------------------------------------------------------ equations
    def equations(self, x, v, acc, lam, F, t, coef_m, coef_c, coef_k, scale, load_factor=1.0,
                  want_matrix=True, held=None, stiffness="dynamic"):
        """Scaled residual on z and Newton matrix coef_m M + coef_c C + coef_k (K - dQ/dx +
        lambda.d2 Phi) of the equations of motion (Eq. 77), lambda = scale mu / coef_k (see
        :func:`~hubbeam.system.equations.system_equations`). ``held`` overrides the hub's
        drive constraint (statics hold the hub). ``stiffness``: "dynamic" (the iteration
        matrix) or "exact" (FFR beams' stiffness with every load's dependence, for statics and
        modes). Returns (residual, BorderedBandMatrix)."""
        held = self.hub.held if held is None else held
        model = self.model(held)
        layout = self.layout_for(held)
        res = np.empty(layout.nz)
        matrix = BorderedBandMatrix.empty(layout.nz, layout.border, model.bandwidth)
        F = np.ascontiguousarray(F, dtype=float)
        x, v, acc, lam = (np.ascontiguousarray(a, dtype=float) for a in (x, v, acc, lam))
        margin, _ = self.functions.system_equations(model, F, x, v, acc, lam, float(t), float(coef_m), float(coef_c),
                                     float(coef_k), float(scale), float(load_factor), stiffness == "exact",
                                     bool(want_matrix), res, matrix.ab, matrix.brow, matrix.bcol, matrix.bb)
        if not margin > CHART_SINGULAR:
            raise ChartSingularityError(
                f"a beam tangent is at the singular direction of the rotation chart (1 + d.tau = {margin:.2e})")
        if not self.hub.torque.compilable and not held:  # a Python torque law (its derivatives by differences)
            torque, d_theta, d_omega = self.hub.torque(t, x[0], v[0])
            res[0] -= coef_k * load_factor * torque
            if want_matrix:
                matrix.add(0, 0, -load_factor * (coef_k * d_theta + coef_c * d_omega))
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
        exact stiffness by differences. A BorderedBandMatrix when every beam is ANCF."""
        s = self.constraint_scale
        layout = self.layout_for(True)
        lam = s * np.asarray(mu, dtype=float)
        if spin:
            vel, acc = self.steady_rotation_rates(x, F, spin)
            vel, acc = np.sqrt(factor) * vel, factor * acc
        else:
            vel = acc = np.zeros(self.nx)
        res, matrix = self.equations(x, vel, acc, lam, F, 0.0, 0.0, 0.0, 1.0, s, load_factor=factor, held=True,
                                     stiffness="exact")
        if not spin:
            return res, matrix
        W = spin**2 * (np.outer(AXIS, AXIS) - np.eye(3))  # (w x)^2
        zx = layout.z_of_x
        M = None
        for k, part, q, chart in self.parts(x, F):
            sx = layout.beam_x(k)
            if isinstance(part, AncfPart):  # -factor M D: D = d(acc)/dq of the rigid rotation, on r and r'
                M = self.mass_matrix(x, F, held=True) if M is None else M
                D = np.zeros((part.ndof, part.ndof))
                for node in range(part.beam.nodes):
                    for off in (0, 3):
                        s0 = NODE_DOFS * node + off
                        D[s0 : s0 + 3, s0 : s0 + 3] = W
                K = factor * M[sx, sx] @ D
                for i, j in zip(*np.nonzero(K)):
                    matrix.add(zx[sx.start + i], zx[sx.start + j], K[i, j])
            else:  # the exact stiffness of the steady-rotation inertia rows (drag's left out)
                spin_stiffness = np.empty((part.ndof, part.ndof))
                ffr_spin_stiffness(pack(part).inv, np.ascontiguousarray(q), -np.sqrt(factor) * spin * AXIS,
                                   spin_stiffness)
                for i, zi in enumerate(zx[sx]):
                    for j, zj in enumerate(zx[sx]):
                        matrix.add(zi, zj, spin_stiffness[i, j])
        return res, matrix

    def mass_matrix(self, x, F, held: bool | None = None) -> np.ndarray:
        """The dense mass matrix M(x) on x (kg, kg m, kg m^2; every part's, tip bodies'
        included): the compiled Newton matrix with coef_m = 1 and nothing else."""
        held = self.hub.held if held is None else held
        layout = self.layout_for(held)
        zero = np.zeros(self.nx)
        _, matrix = self.equations(x, zero, zero, np.zeros(layout.n_lambda), F, 0.0, 1.0, 0.0, 0.0, 0.0, held=held)
        zx = layout.z_of_x
        return matrix.to_dense()[np.ix_(zx, zx)]

    def linearised(self, x, lam, F, factor=1.0, held=False):
        """Dense stiffness and mass of x about an equilibrium, and the constraint Jacobian.

        Returns (K, M, A): K = d2(U - W)/dx2 + lambda.d2 Phi/dx2 (load stiffness of the tip
        moment and, for FFR, of gravity included), M the mass matrix, A = dPhi/dx. ``held``
        keeps the driving constraint (theta = theta_p(0)); ``lam`` are the multipliers of the
        held layout (a static solution's)."""
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
        """dPhi/dx (n_lambda x nx) of the clamps and, for a held hub, the drive."""
        held = self.hub.held if held is None else held
        layout = self.layout_for(held)
        zero = np.zeros(self.nx)
        _, matrix = self.equations(x, zero, zero, np.zeros(layout.n_lambda), F, 0.0, 0.0, 0.0, 0.0, 1.0, held=held)
        A = matrix.to_dense()
        return A[np.ix_(layout.z_of_lambda, layout.z_of_x)]

    def lambda_from_held(self, lam, held: bool) -> np.ndarray:
        """Multipliers of the held layout (a static solution's) for the layout with the hub
        held or free (the drive multiplier dropped)."""
        lam = np.asarray(lam, dtype=float)
        if held:
            return lam
        src, dst = self.layout_for(True), self.layout_for(False)
        out = np.empty(dst.n_lambda)
        for k in range(len(self.beams)):
            out[dst.clamp_lambda(k)] = lam[src.clamp_lambda(k)]
        return out

    def constraint_acceleration_terms(self, x, v, F, t, held=None) -> np.ndarray:
        """v^T Phi_xx v + Phi_tt for every constraint: what Phi_x xdd must cancel. The clamps
        have no explicit time dependence; the drive theta - theta_p(t) has Phi_tt = -theta_p''."""
        held = self.hub.held if held is None else held
        layout = self.layout_for(held)
        out = np.zeros(layout.n_lambda)
        if held and self.motion == "prescribed":
            out[layout.drive_lambda] = -self.hub.drive(t)[2]
        for k, part, q, chart in self.parts(x, F):
            _, jac, hess = part.clamp(q, chart, x[0])
            c = np.concatenate([[v[0]], v[layout.beam_x(k)][: part.root_dofs]])
            sl = layout.clamp_lambda(k)
            out[sl] = [c @ hess(e) @ c for e in np.eye(CLAMP_EQUATIONS)]
        return out

    def constraint_violation(self, x, F, t) -> float:
        """Largest violation of the clamps' position equations (m)."""
        return max(float(np.max(np.abs(part.clamp(q, chart, x[0])[0][0:3]))) for _, part, q, chart in self.parts(x, F))

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

    def applied_torque(self, t: float, x: np.ndarray, v: np.ndarray) -> float:
        """The free hub's torque law at the state (N m); zero for a held hub."""
        if self.hub.held:
            return 0.0
        return float(self.hub.torque(t, x[0], v[0])[0])

    def energies(self, x, v, F, beam: int | None = None) -> dict[str, float]:
        """Kinetic (hub and beams, rotary inertia and tip bodies included), strain and gravity
        energy (J); of one beam when ``beam`` is its index (compiled:
        :func:`~hubbeam.system.equations.beam_energies`)."""
        hub, beams = np.zeros(3), np.zeros((len(self.beams), 3))
        self.functions.beam_energies(self.model(), np.ascontiguousarray(F, dtype=float), np.ascontiguousarray(x, dtype=float),
                      np.ascontiguousarray(v, dtype=float), beams, hub)
        return energy_sums(hub, beams, beam)

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
        ``hub`` (count, 3) the hub's kinetic energy with the (kinetic, strain, gravity)
        energy of parts that belong to no beam and ``beams`` (count, beams, 3) each beam's
        (kinetic, strain, gravity) energy (J), for :func:`energy_sums`; ``strains`` (count,
        gauges) at the gauges of ``gauges`` (a :meth:`gauge_table`; default none)."""
        nb = len(self.beams)
        gauges = self.gauge_table([])[0] if gauges is None else gauges
        out = {"hub": np.zeros((count if energies else 0, 3)), "beams": np.zeros((count if energies else 0, nb, 3)),
               "tips": np.empty((count, nb, 3)), "strains": np.empty((count, gauges[0].shape[0]))}
        self.functions.record_measures(self.model(), np.ascontiguousarray(F, dtype=float), np.ascontiguousarray(xs, dtype=float),
                        np.ascontiguousarray(vs, dtype=float), count, energies, gauges, out["hub"], out["beams"],
                        out["tips"], out["strains"])
        return out

    def kinetic_energy_split(self, x, F, u) -> dict[str, float]:
        """The kinetic energy (J) of the system moving at the rate u about the configuration x
        (u complex: real and imaginary parts' energies summed), split into the hub's
        (J theta'^2 / 2, ``hub``) and, summed over the beams, each beam's ``flap``, ``lag``,
        ``axial`` and ``torsion`` parts in its own directions
        (:meth:`~hubbeam.system.parts.BeamPart.kinetic_energy_split`)."""
        u = np.asarray(u)
        total = dict.fromkeys(BEAM_MOTIONS, 0.0)
        total["hub"] = 0.5 * self.hub.inertia * float(np.abs(u[0]) ** 2)
        for k, part, q, chart in self.parts(x, F):
            u_k = u[self.layout.beam_x(k)]
            if not np.any(u_k):  # a beam the rate does not move (a mode of another beam) has none
                continue
            for key, value in part.kinetic_energy_split(q, chart, u_k, x[0]).items():
                total[key] += value
        return total

    def angular_momentum(self, x, v, F) -> float:
        """Angular momentum about the hub axis (N m s), positive in the sense of theta' (about -j0).

        By Noether's theorem it is the generalized momentum M(x) v projected on the rigid
        rotation of the whole system about the axis (xi = the rates of theta' = 1): v^T M xi
        (:meth:`mass_matrix`: J theta' + sum_k v_k^T M_k(q_k) xi_k, tip bodies included). In the axis charts xi is exact; otherwise the state is first
        moved to them (velocities by the remap's Jacobian, a central difference)."""
        x_axis, F_axis = self.axis_chart(x, F)
        if not np.array_equal(F_axis, F):
            eps = 1e-6
            v = (self.remap(x + eps * v, F, F_axis) - self.remap(x - eps * v, F, F_axis)) / (2 * eps)
            x, F = x_axis, F_axis
        xi, _ = self.steady_rotation_rates(x, F, 1.0)
        return float(v @ self.mass_matrix(x, F) @ xi)

    def step_powers(self, t, x, v, lam, F) -> tuple[float, float]:
        """(dissipated, drive) power at a state (W): the drag of Eq. 37 and the beams'
        structural damping (>= 0), and the drive reaction and the applied torque on the hub
        (:func:`hubbeam.system.equations.step_powers`; a Python torque law is evaluated here)."""
        x, v, lam = (np.ascontiguousarray(u, dtype=float) for u in (x, v, lam))
        dissipated, drive = self.functions.step_powers(self.model(), np.ascontiguousarray(F, dtype=float), float(t),
                                                       x, v, lam)
        if not self.hub.torque.compilable:
            drive = (self.applied_torque(t, x, v) + self.drive_torque(lam)) * float(v[0])
        return float(dissipated), float(drive)

    def tip_position(self, x, beam: int = 0) -> np.ndarray:
        return self.beams[beam].tip_position(x[self.layout.beam_x(beam)])

    def tip_displacement(self, x, beam: int = 0) -> dict[str, float]:
        """Tip centroid displacement of a beam from its undeformed place, in its own hub frame (m)."""
        return self.beams[beam].tip_displacement(x[self.layout.beam_x(beam)], x[0])

    def surface_strain(self, x, F, station: float, y: float, z: float, beam: int = 0) -> float:
        return self.beams[beam].surface_strain(x[self.layout.beam_x(beam)], F[beam], station, y, z)

    def surface_strains_of_states(self, xs, F, station: float, y: float, z: float, beam: int = 0) -> np.ndarray:
        """:meth:`surface_strain` for each row of xs (states in the charts F)."""
        return self.beams[beam].surface_strains_of_states(xs[:, self.layout.beam_x(beam)], F[beam], station, y, z)

    def centre_line(self, x, F, beam: int = 0, points_per_element: int = 8) -> np.ndarray:
        return self.beams[beam].centre_line(x[self.layout.beam_x(beam)], F[beam], points_per_element)



def single_beam_system(beam, radius: float = 0.0, twist: float = 0.0, motion: str = "fixed",
                       hub_inertia: float = 1.0, hub_torque: float | TorqueLaw = 0.0,
                       drive: DriveProfile | None = None, gravity=(0.0, 0.0, 0.0), tip_force=(0.0, 0.0, 0.0),
                       tip_moment=(0.0, 0.0, 0.0), damping=(0.0, 0.0), tip_body: TipBody | None = None,
                       azimuth: float = 0.0, precone: float = 0.0) -> HubSystem:
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
    return HubSystem([part], hub, gravity, damping)
