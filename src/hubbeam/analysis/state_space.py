"""Continuous-time state space (A, B, C, D) of the hub-beam system about an equilibrium.

The equations of motion with constraints (paper Eq. 77), M(x) x'' + r(x, x') + Phi_x^T lambda
= B_x u, Phi(x) = 0, are linearised about a state that does not change in time:

- **rest**: the static equilibrium under the scenario's loads (``solve_static``), x' = 0;
- **steady rotation** (a hub driven at a constant speed omega): the state that turns rigidly
  with the hub (``solve_static(spin=omega)``), described in co-rotating coordinates
  x(t) = G(omega t) y(t) (G the rigid rotation of the whole system about the axis, a symmetry
  of the equations), in which the linearised equations do not depend on time.

Linearised: M dx'' + C dx' + K dx + A^T dlambda = B_x u with A dx = 0. The states are the
minimal coordinates of the constrained system: dx = N y with N an orthonormal basis of the
null space of A (the constraint Jacobian), state = [y, y'], so the state matrix has no
constraint drift:

    d/dt [y, y'] = [[0, I], [-Mr^-1 Kr, -Mr^-1 Cr]] [y, y'] + [0; Mr^-1 N^T B_x] u,
    Mr = N^T M N, Cr = N^T C N, Kr = N^T K N.

At rest K, M and A are the exact derivatives of :meth:`MultibodySystem.linearised` and C (the linear
part of the drag, and -dT/dtheta' of a torque law) is the system's Newton matrix with coef_c =
1, which is exact at zero velocity. About the steady rotation K and C (centrifugal softening and
pre-stress, gyroscopic and Coriolis terms, drag) are central differences of the system's own
residual in co-rotating coordinates (as the Campbell diagram's, :mod:`hubbeam.solvers.modal`),
M the Newton matrix with coef_m = 1.

Inputs: ``hub_torque`` (N m), a torque on a free hub added to its torque law: B_x is the unit
vector of theta (the hub row of the equations is J theta'' - T - u + ...); ``joint_torque:NAME``
(N m), a torque in the single-axis joint of beam NAME added to its motor law (on the beam about
the axis, its reaction on the parent): B_x the unit vector of its angle psi; ``tip_force:NAME``
(N): a force at the tip centroid of beam NAME, three inputs along the global x, y, z (about
steady rotation: the axes of the hub frame, which turn with the hub; at t = 0 they are the
global ones), its B_x column the difference of the residuals with and without a unit tip force
(the residual is affine in a dead load, so the difference is exact); ``load:NAME`` (N/m): a
uniform force per unit length along the three axes of the load NAME along the span (its own
axes: global or its root section frame; :func:`load_columns`), and ``load:tip`` (N) the tip
force of the tip loads' beam, named ``load_NAME_x|y|z``.

Outputs: the scenario's sensors, each linearised about the equilibrium by central differences
of the sensor (:mod:`hubbeam.sensors`) along the basis directions: y moves x = x0 + N y, y'
the velocity (about the steady rotation the velocity is omega Xi(x) + N y', Xi the rigid
rotation's rates). A sensor that reads the multipliers (``hub_torque``: the drive's reaction)
gets the linearised multipliers dlambda = (A A^T)^-1 A (B_x u - M N y'' - C N y' - K N y), which
depend on u directly: such an output has D != 0 when a force input is applied to a held hub;
every other output has D = 0. Left out (named in ``left_out``): the energy parts
"dissipated" and "drive" (work integrals over the run, not functions of the state) and
``constraint_violation`` (a norm, zero to first order).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.linalg import null_space

from hubbeam.errors import ScenarioError
from hubbeam.analysis import reduction
from hubbeam.analysis.output_jacobian import linear_outputs, output_jacobians
from hubbeam.analysis.reduction import RIGID_TOL_HZ
from hubbeam.solvers.modal import rotating_matrices
from hubbeam.solvers.static import StaticSolution
from hubbeam.system.multibody import MultibodySystem

#: tip force components (global directions)
AXES = ("x", "y", "z")


@dataclass
class Equilibrium:
    """The state the model is linearised about: coordinates ``x``, multipliers ``multipliers``
    (N, N m; the layout of the system's hub, held or free), ``chart`` (the beams' rotation
    charts), the hub speed ``omega`` (rad/s, 0 at rest) and the velocities ``v`` (rad/s, m/s)."""

    x: np.ndarray
    multipliers: np.ndarray
    chart: np.ndarray
    omega: float
    v: np.ndarray


@dataclass
class LinearModel:
    """x' = A x + B u, y = C x + D u: deviations from the equilibrium (SI units; the states
    [y, y'] are the coordinates of the constraint null-space basis ``basis``: the system's
    coordinates are equilibrium.x + basis @ y). ``output_offsets`` are the outputs' values at
    the equilibrium; ``rigid_modes`` how many rigid-body modes the modal summary leaves out.

    A reduced model (:meth:`reduced`, :meth:`balanced`) has its own states; ``projection``
    maps them to the full model's ([y, y'] ~ projection @ states, the residualised modes'
    steady part left out) and ``reduction`` says what was done (method, sizes, the Hankel
    singular values and the H-infinity error bound of a balanced reduction)."""

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    states: list[str]
    inputs: list[str]
    outputs: list[str]
    input_units: list[str]
    output_units: list[str]
    basis: np.ndarray
    equilibrium: Equilibrium
    output_offsets: np.ndarray
    about: str
    rigid_modes: int = 0
    left_out: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    projection: np.ndarray | None = None
    reduction: dict = field(default_factory=dict)

    def to_control(self):
        """A ``control.StateSpace`` with the state, input and output names (python-control,
        the extra ``hubbeam[control]``)."""
        try:
            import control
        except ImportError as exc:
            raise ImportError("python-control is not installed: pip install 'hubbeam[control]' "
                              "(or use the numpy arrays A, B, C, D)") from exc
        return control.ss(self.A, self.B, self.C, self.D, states=self.states, inputs=self.inputs,
                          outputs=self.outputs, name="hubbeam")

    def eigenvalues(self) -> np.ndarray:
        """The eigenvalues of A (1/s), computed once."""
        cached = getattr(self, "_eigenvalues", None)
        if cached is None or cached.size != self.A.shape[0]:
            cached = np.linalg.eigvals(self.A) if self.A.size else np.zeros(0, dtype=complex)
            self._eigenvalues = cached
        return cached

    def modal_summary(self) -> tuple[np.ndarray, np.ndarray]:
        """(frequencies Hz, damping ratios) of the eigenvalues lambda of A with Im > 0:
        |lambda| / 2 pi and -Re lambda / |lambda|, ascending in frequency. Rigid-body modes are
        left out as ``modes`` does: the ``rigid_modes`` eigenvalue pairs nearest zero (the free
        hub's rotation) and any mode below 1e-3 Hz."""
        s = self.eigenvalues()
        keep = np.ones(s.size, dtype=bool)
        keep[np.argsort(np.abs(s))[: 2 * self.rigid_modes]] = False
        keep &= np.abs(s) / (2.0 * np.pi) >= RIGID_TOL_HZ
        s = s[keep & (s.imag > 0.0)]
        s = s[np.argsort(np.abs(s))]
        return np.abs(s) / (2.0 * np.pi), -s.real / np.abs(s)

    def dc_gain(self) -> np.ndarray:
        """D - C A^-1 B (outputs x inputs): the steady response to a constant input; with rigid
        modes, that of every other mode (:func:`hubbeam.analysis.reduction.dc_gain`: a free
        hub without a torque law never settles under a constant torque)."""
        return reduction.dc_gain(self.A, self.B, self.C, self.D, self.rigid_modes)

    def frequency_response(self, freq_hz) -> np.ndarray:
        """G(i 2 pi f) (frequencies, outputs, inputs), complex, at the frequencies (Hz)
        (:func:`hubbeam.analysis.reduction.frequency_response`: one Schur form, then a
        triangular solve per frequency)."""
        return reduction.frequency_response(self.A, self.B, self.C, self.D, freq_hz)

    def select(self, outputs=None, inputs=None) -> "LinearModel":
        """The same model with only the named outputs and inputs (in the order given; None:
        all). ValueError naming an unknown one."""
        def pick(names, known, what):
            if names is None:
                return list(range(len(known)))
            if isinstance(names, str):
                names = [names]
            missing = [n for n in names if n not in known]
            if missing:
                raise ValueError(f"{what}: unknown {missing[0]!r} (this model has: {', '.join(known)})")
            return [known.index(n) for n in names]

        rows, cols = pick(outputs, self.outputs, "outputs"), pick(inputs, self.inputs, "inputs")
        return replace(self, B=self.B[:, cols], C=self.C[rows], D=self.D[np.ix_(rows, cols)],
                       inputs=[self.inputs[i] for i in cols], outputs=[self.outputs[i] for i in rows],
                       input_units=[self.input_units[i] for i in cols],
                       output_units=[self.output_units[i] for i in rows], output_offsets=self.output_offsets[rows],
                       notes=list(self.notes))

    def _with(self, reduced: "reduction.Reduced") -> "LinearModel":
        projection = reduced.V if self.projection is None else self.projection @ reduced.V
        info = dict(reduced.info)
        if self.reduction:
            info["full_states"] = self.reduction.get("full_states", info["full_states"])
        return replace(self, A=reduced.A, B=reduced.B, C=reduced.C, D=reduced.D, states=list(reduced.states),
                       projection=projection, reduction=info, notes=list(self.notes) + list(reduced.notes))

    def reduced(self, modes: int | None = None, fmax: float | None = None) -> "LinearModel":
        """Modal truncation (:func:`hubbeam.analysis.reduction.modal_reduction`): rigid and
        unstable modes kept as they are, of the other modes the ``modes`` lowest (a complex
        pair is one mode) and none above ``fmax`` Hz, the rest residualised (the DC gain kept);
        states ``modeJ_re``, ``modeJ_im`` (``modeJ`` for a real eigenvalue) and ``rigidK``."""
        if modes is not None and (isinstance(modes, bool) or not isinstance(modes, (int, np.integer)) or modes < 0):
            raise ValueError(f"modes: a whole number >= 0 (got {modes!r})")
        _check_fmax(fmax)
        return self._with(reduction.modal_reduction(self.A, self.B, self.C, self.D, modes, fmax, self.rigid_modes))

    def balanced(self, order: int, fmax: float | None = None, match: str = "dc") -> "LinearModel":
        """Balanced reduction of the stable part to ``order`` states
        (:func:`hubbeam.analysis.reduction.balanced_reduction`); ``reduction`` then holds the
        ``hankel_singular_values`` and the ``error_bound`` (twice the discarded ones' sum)."""
        if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 1:
            raise ValueError(f"order: a whole number >= 1 (got {order!r})")
        _check_fmax(fmax)
        return self._with(reduction.balanced_reduction(self.A, self.B, self.C, self.D, int(order), fmax,
                                                       self.rigid_modes, match))

    def to_dict(self) -> dict:
        f, zeta = self.modal_summary()
        out = {"states": len(self.states), "inputs": list(self.inputs), "outputs": list(self.outputs),
               "frequencies_hz": f.tolist(), "damping_ratios": zeta.tolist(), "about": self.about}
        if self.reduction:
            info = dict(self.reduction)
            sigma = info.pop("hankel_singular_values", None)
            out["reduction"] = info
            if sigma is not None:
                out["hankel_singular_values"] = sigma
        return out

    def to_dataset(self, scenario=None):
        """A, B, C, D with named dimensions (``state_rate`` x ``state``, ``state_rate`` x ``input``,
        ``output`` x ``state``, ``output`` x ``input``), the basis and the equilibrium, as an
        xarray.Dataset (A[i, j] = d(rate of state i) / d(state j)). A reduced model adds
        ``projection`` (``full_state`` x ``state``) and, balanced, ``hankel_singular_value``."""
        import xarray as xr

        n = self.basis.shape[1]
        data = {
            "A": (("state_rate", "state"), self.A, {"units": "1/s", "long_name": "state matrix"}),
            "B": (("state_rate", "input"), self.B, {"long_name": "input matrix"}),
            "C": (("output", "state"), self.C, {"long_name": "output matrix"}),
            "D": (("output", "input"), self.D, {"long_name": "feedthrough matrix"}),
            "basis": (("coordinate", "reduced"), self.basis,
                      {"long_name": "x = equilibrium_x + basis @ y (y: the first half of the full model's states)"}),
            "equilibrium_x": (("coordinate",), self.equilibrium.x, {"long_name": "coordinates at the equilibrium"}),
            "output_offset": (("output",), self.output_offsets, {"long_name": "outputs at the equilibrium"}),
        }
        full_states = [f"y{i + 1}" for i in range(n)] + [f"y{i + 1}_rate" for i in range(n)]
        coords = {"state": self.states, "state_rate": self.states, "input": self.inputs, "output": self.outputs,
                  "reduced": full_states[:n], "coordinate": np.arange(self.basis.shape[0]),
                  "input_units": ("input", self.input_units), "output_units": ("output", self.output_units)}
        if self.projection is not None:
            data["projection"] = (("full_state", "state"), self.projection,
                                  {"long_name": "the full model's states [y, y'] ~ projection @ states (the "
                                                "residualised modes' steady part left out)"})
            coords["full_state"] = full_states
        sigma = self.reduction.get("hankel_singular_values")
        if sigma is not None:
            data["hankel_singular_value"] = (("hankel",), np.asarray(sigma, dtype=float),
                                             {"long_name": "Hankel singular values of the stable part, descending"})
        ds = xr.Dataset(data, coords=coords)
        ds.attrs.update({"about": self.about, "omega": float(self.equilibrium.omega),
                         "left_out": json.dumps(self.left_out), "notes": json.dumps(self.notes)})
        if self.reduction:
            ds.attrs["reduction"] = json.dumps({k: v for k, v in self.reduction.items() if k != "hankel_singular_values"})
        if scenario is not None:
            ds.attrs["name"] = scenario.name
            ds.attrs["scenario"] = json.dumps(scenario.to_dict())
        return ds


def closed_loop(model: LinearModel, controller, columns, outputs, name: str = "controller") -> LinearModel:
    """``model`` with a linear controller s' = Ac s + Bc u_c, y_c = Cc s + Dc u_c closed around it
    (``controller``: a :class:`~hubbeam.system.controllers.LinearController`): its inputs u_c
    are the model's outputs ``columns`` (``NAME_rate``: that output's rate C_NAME x' = C_NAME (A x
    + B u), which needs D_NAME = 0), its outputs y_c add to the model's inputs ``outputs`` (the
    same torque the run applies). The closed loop's states are the model's, then the
    controller's (``NAME_s1``, ...); its inputs and outputs are the model's, a controller output
    among the inputs then being an input added to the controller's. ``projection`` maps the
    states to the full model's (the controller's left out). With u the model's inputs:

        x' = (A + B_y Dc Cu) x + B_y Cc s + B u,   s' = Bc Cu x + Ac s,
        y  = (C + D_y Dc Cu) x + D_y Cc s + D u

    (Cu the rows of the inputs u_c, B_y the columns of the controller's outputs). ValueError
    for a column or output the model does not have, or an input with a feedthrough."""
    rows = []
    for column in columns:
        base = column[:-len("_rate")] if column not in model.outputs and column.endswith("_rate") else column
        if base not in model.outputs:
            raise ValueError(f"{name}: input {column!r} is not an output of the linear model")
        i = model.outputs.index(base)
        if np.any(model.D[i]):
            raise ValueError(f"{name}: input {column!r} has a feedthrough from the model's inputs (an algebraic loop)")
        rows.append((model.C[i] @ model.A, model.C[i] @ model.B) if base != column else (model.C[i], model.D[i]))
    Cu = np.array([r[0] for r in rows]).reshape(len(rows), model.A.shape[0])
    if np.any([np.any(r[1]) for r in rows]):
        raise ValueError(f"{name}: an input's rate has a feedthrough from the model's inputs (an algebraic loop)")
    missing = [o for o in outputs if o not in model.inputs]
    if missing:
        raise ValueError(f"{name}: output {missing[0]!r} is not an input of the linear model")
    cols = [model.inputs.index(o) for o in outputs]
    By, Dy = model.B[:, cols], model.D[:, cols]
    Ac, Bc, Cc, Dc = controller.A, controller.B, controller.C, controller.D
    n, nc = model.A.shape[0], Ac.shape[0]
    A = np.block([[model.A + By @ Dc @ Cu, By @ Cc], [Bc @ Cu, Ac]])
    B = np.vstack([model.B, np.zeros((nc, model.B.shape[1]))])
    C = np.hstack([model.C + Dy @ Dc @ Cu, Dy @ Cc])
    full = model.projection if model.projection is not None else np.eye(n)
    projection = np.hstack([full, np.zeros((full.shape[0], nc))])
    states = list(model.states) + [f"{name}_s{j + 1}" for j in range(nc)]
    out = replace(model, A=A, B=B, C=C, D=model.D.copy(), states=states, projection=projection,
                  notes=list(model.notes))
    out.notes.append(f"{name} closed around the model: inputs {', '.join(columns)}; outputs {', '.join(outputs)} "
                     f"({nc} state{'s' if nc != 1 else ''})")
    return out


def _check_fmax(fmax) -> None:
    if fmax is not None and (isinstance(fmax, bool) or not isinstance(fmax, (int, float, np.floating))
                             or not np.isfinite(fmax) or fmax <= 0):
        raise ValueError(f"fmax: a frequency > 0 in Hz (got {fmax!r})")


#: the inputs of a free base: its attitude torque's components, base axes (N m)
BASE_TORQUE_INPUTS = ("base_torque_x", "base_torque_y", "base_torque_z")


def input_columns(system: MultibodySystem, names, x, v, acc, lam, F, tip_beam: int = 0
                  ) -> tuple[np.ndarray, list[str], list[str]]:
    """(B_x (nx x m), input names, units) of the inputs ``names``: "hub_torque" (a free hub),
    "tip_force:NAME" and "load:NAME" (three components each: :func:`load_columns`; the tip
    loads' "load:tip" on beam ``tip_beam``). ScenarioError ("inputs: ...") for an unknown one."""
    columns, labels, units = [], [], []
    held = system.hub.held
    for spec in names:
        kind, colon, beam = str(spec).strip().partition(":")
        if colon and not beam.strip():
            raise ScenarioError(f"inputs: {spec!r} names no beam (use tip_force:BEAM, or tip_force for the first beam)")
        if kind == "hub_torque" and not beam:
            if held:
                raise ScenarioError(f"inputs: hub_torque needs a free hub (hub.motion = {system.motion!r} holds it; "
                                    "a tip_force:BEAM input works on any hub)")
            e = np.zeros(system.nx)
            e[system.theta_index] = 1.0  # the hub row is J theta'' - T - u + ...: u enters as the torque law's T
            columns.append(e)
            labels.append("hub_torque")
            units.append("N m")
        elif kind == "joint_torque":
            names_ = [b.name for b in system.beams]
            k = names_.index(beam) if beam in names_ else None
            joint = None if k is None else system.beams[k].mount.joint
            if joint is None or joint.count != 1 or joint.locked_at is not None:
                raise ScenarioError(f"inputs: {spec!r}: needs a beam on a single-axis revolute joint (beams on one: "
                                    f"{', '.join(b.name for b in system.beams if b.mount.joint_count == 1) or 'none'})")
            e = np.zeros(system.nx)
            e[system.layout.joint_x(k).start] = 1.0  # the joint row is ... - T - u: u enters as the motor's torque
            columns.append(e)
            labels.append(f"joint_torque_{beam}")
            units.append("N m")
        elif kind in BASE_TORQUE_INPUTS and not beam:
            if system.base.motion.value != "free":
                raise ScenarioError(f"inputs: {kind} needs a free base (base.motion = {system.base.motion.value!r})")
            columns.append(system.base_torque_column(x, BASE_TORQUE_INPUTS.index(kind)))
            labels.append(kind)
            units.append("N m")
        elif kind == "tip_force":
            names_ = [b.name for b in system.beams]
            k = 0 if not beam else (names_.index(beam) if beam in names_ else None)
            if k is None:
                raise ScenarioError(f"inputs: tip_force:{beam}: no beam of that name (beams: {', '.join(names_)})")
            for axis, column in zip(AXES, _tip_force_columns(system, k, x, v, acc, lam, F)):
                columns.append(column)
                labels.append(f"tip_force_{axis}_{system.beams[k].name}")
                units.append("N")
        elif kind == "load":
            for column, label, unit in load_columns(system, beam.strip(), x, v, acc, lam, F, tip_beam):
                columns.append(column)
                labels.append(label)
                units.append(unit)
        else:
            raise ScenarioError(f"inputs: unknown input {spec!r} (use hub_torque, base_torque_x|y|z, joint_torque:BEAM, "
                                f"tip_force:BEAM or load:NAME)")
    if len(set(labels)) != len(labels):
        raise ScenarioError(f"inputs: an input is given twice ({', '.join(map(str, names))})")
    return np.array(columns).T.reshape(system.nx, len(columns)), labels, units


#: the name of the tip loads of ``[loads]`` among the load inputs (``load:tip``)
TIP_LOAD = "tip"


def load_columns(system: MultibodySystem, name: str, x, v, acc, lam, F, tip_beam: int = 0) -> list:
    """The three inputs ``load_NAME_x|y|z`` of the load ``name`` as (B_x column, label, unit):
    for a load along the span ([[loads.span]] ``name``), a force of 1 N/m along axis x, y or z
    (the load's axes: global, or its root section frame), uniform over the stations the load
    acts on (its table's x range; the whole span for a uniform load), whatever the load's own
    values; for ``tip`` (the tip loads of [loads], on beam ``tip_beam``) a force of 1 N at the
    tip centroid along the global axis. The column is the difference of the force rows with and
    without that unit load at (x, v): exact, the residual being affine in an applied load at a
    given state. ScenarioError ("inputs: ...") for a name that is no load."""
    from hubbeam.system.span_loads import SpanLoad

    if name == TIP_LOAD:
        return [(column, f"load_{TIP_LOAD}_{axis}", "N")
                for axis, column in zip(AXES, _tip_force_columns(system, tip_beam, x, v, acc, lam, F))]
    # the loads along the span by name (a tip table's load acts at the one station x = L: it is the tip's)
    spans = {a.name: a for a in system.attachments if isinstance(a, SpanLoad) and a.stations.size > 1}
    load = spans.get(name)
    if load is None:
        raise ScenarioError(f"inputs: load:{name}: no load of that name (loads: "
                            f"{', '.join([TIP_LOAD] + list(spans))})")
    base = _forces(system, x, v, acc, lam, F)
    out = []
    for i, axis in enumerate(AXES):
        values = np.zeros((1, load.stations.size, 6))
        values[0, :, i] = 1.0
        unit = SpanLoad(load.beam, load.stations, load.weights, [0.0], values, load.section_axes, f"{name}_unit")
        variant = system.with_attachments(list(system.attachments) + [unit])
        out.append((base - _forces(variant, x, v, acc, lam, F), f"load_{name}_{axis}", "N/m"))
    return out


def _tip_force_columns(system: MultibodySystem, k: int, x, v, acc, lam, F) -> list[np.ndarray]:
    """The generalized forces (B_x columns) of a unit force at beam k's tip centroid along the
    global x, y, z: the force rows without it minus with it (exact: the residual is affine in a
    dead load)."""
    base = _forces(system, x, v, acc, lam, F)
    part = system.beams[k]
    out = []
    for i in range(3):
        pushed = replace(part, tip_force=np.asarray(part.tip_force, dtype=float) + np.eye(3)[i])
        variant = system.with_beams([pushed if j == k else b for j, b in enumerate(system.beams)])
        out.append(base - _forces(variant, x, v, acc, lam, F))
    return out


def _forces(system: MultibodySystem, x, v, acc, lam, F) -> np.ndarray:
    """The force rows of the equations of motion on x (N, N m): M acc + r(x, v) + Phi_x^T lam - Q."""
    res = system.equations(x, v, acc, lam, F, 0.0, 0.0, 0.0, 1.0, 1.0, want_matrix=False)[0]
    return res[system.layout.z_of_x]


def _dense(system: MultibodySystem, x, v, acc, lam, F, coef_m, coef_c) -> np.ndarray:
    """coef_m M + coef_c C of the system's Newton matrix on x (dense)."""
    _, matrix = system.equations(x, v, acc, lam, F, 0.0, coef_m, coef_c, 0.0, 1.0)
    zx = system.layout.z_of_x
    return matrix.to_dense()[np.ix_(zx, zx)]


def rest_matrices(system: MultibodySystem, x, lam_held, F):
    """(M, C, K, A) about a static equilibrium (x, the held layout's multipliers lam_held as
    ``solve_static`` gives them, charts F): exact K, M, A of :meth:`MultibodySystem.linearised`, C the
    Newton matrix's velocity part at zero velocity (exact there: the drag's linear part and
    -dT/dtheta' of a torque law; the quadratic velocity terms have no slope at rest)."""
    held = system.hub.held
    K, M, A = system.linearised(x, lam_held, F, 1.0, held=held)
    zero = np.zeros(system.nx)
    C = _dense(system, x, zero, zero, system.lambda_from_held(lam_held, held), F, 0.0, 1.0)
    return M, C, K, A


def linearise(system: MultibodySystem, equilibrium: StaticSolution, omega: float = 0.0, inputs=("hub_torque",),
              sensors=(), about: str = "", progress=None, tip_beam: int = 0) -> LinearModel:
    """The state space of ``system`` about ``equilibrium`` (a ``solve_static`` solution; with
    ``spin=omega`` for a hub driven at the constant speed omega rad/s, then the system's hub is
    held). ``inputs``: names (see :func:`input_columns`; ``tip_beam`` the beam of the tip loads'
    ``load:tip``); ``sensors``: a scenario's sensors."""
    held = system.hub.held
    lam = system.lambda_from_held(equilibrium.multipliers, held)
    x0, F = equilibrium.x, equilibrium.chart
    if omega:
        if not held:
            raise ScenarioError("hub.motion: a steadily rotating state is linearised with the hub driven "
                                "(hub.motion = 'prescribed', profile 'constant')")
        v0, a0 = system.steady_rotation_rates(x0, F, omega)
        M, C, K, A = rotating_matrices(system, x0, lam, F, omega)
    else:
        v0 = a0 = np.zeros(system.nx)
        M, C, K, A = rest_matrices(system, x0, equilibrium.multipliers, F)
    Bx, in_names, in_units = input_columns(system, inputs, x0, v0, a0, lam, F, tip_beam)
    N = null_space(A)
    n, m = N.shape[1], Bx.shape[1]
    Mr, Cr, Kr, Br = N.T @ M @ N, N.T @ C @ N, N.T @ K @ N, N.T @ Bx
    Mr = 0.5 * (Mr + Mr.T)
    acc_y, acc_v, acc_u = (np.linalg.solve(Mr, X) for X in (-Kr, -Cr, Br))  # y'' = acc_y y + acc_v y' + acc_u u
    A_ss = np.block([[np.zeros((n, n)), np.eye(n)], [acc_y, acc_v]])
    B_ss = np.vstack([np.zeros((n, m)), acc_u])
    # multipliers: A^T dlam = B_x u - M N y'' - C N y' - K N y (least squares: A has full row rank)
    P = np.linalg.solve(A @ A.T, A)
    lam_y = -P @ (M @ N @ acc_y + K @ N)
    lam_v = -P @ (M @ N @ acc_v + C @ N)
    lam_u = P @ (Bx - M @ N @ acc_u)

    outputs, left_out = linear_outputs(sensors, system, x0, F)
    offsets, Hx, Hv, Hl = output_jacobians(outputs, system, x0, lam, F, omega, progress)
    C_ss = np.hstack([Hx @ N + Hl @ lam_y, Hv @ N + Hl @ lam_v])
    D_ss = Hl @ lam_u
    states = [f"y{i + 1}" for i in range(n)] + [f"y{i + 1}_rate" for i in range(n)]
    rigid = int(not held and system.hub.torque(0.0, x0[system.theta_index], 0.0)[1] == 0.0)
    return LinearModel(A_ss, B_ss, C_ss, D_ss, states, in_names, [name for o in outputs for name in o.names], in_units,
                       [u for o in outputs for u in o.units], N, Equilibrium(x0, lam, F, float(omega), v0), offsets, about,
                       rigid, left_out)
