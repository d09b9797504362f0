"""Plain-Python entry points: scenario in, data out (nothing is printed here). The analyses
(:func:`run`, :func:`static`, :func:`modes`, :func:`linearize`) are defined here; the
functions that read a scenario and build its system are :mod:`hubbeam.from_scenario`'s, and are
importable from here too."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from hubbeam.from_scenario import (FREE_FALL_NOTE, as_scenario, base_of, beam_part, build_system,
                                   drive_profile, equilibrium_system, joint_of, load_attachments,
                                   load_function_argument, load_scenario, reduction_warnings, torque_argument,
                                   torque_law)
from hubbeam.io.scenario import Scenario, ScenarioError
from hubbeam.solvers.static import StaticSolution, solve_static
from hubbeam.system.base import BaseMotion
from hubbeam.system.laws import TorqueLaw
from hubbeam.system.multibody import MultibodySystem

#: the public names: the analyses defined here and the scenario and system builders of :mod:`hubbeam.from_scenario`
__all__ = ["FREE_FALL_NOTE", "ModalResult", "StaticResult", "as_scenario", "base_of", "beam_part", "build_system",
           "drive_profile", "equilibrium_system", "joint_of", "linearize", "load_attachments", "load_function_argument",
           "load_scenario", "modes", "reduction_warnings", "run", "static", "tip_displacement", "torque_argument",
           "torque_law", "with_sensors"]

if TYPE_CHECKING:  # the modal analysis is imported where it is used: scipy.linalg is slow to load
    from hubbeam.solvers.modal import Modes

#: analysis.newton of a scenario -> NewtonOptions.update (when the iteration matrix is rebuilt)
NEWTON_UPDATES = {"full": "iteration", "step": "step", "modified": "adaptive"}


def tip_displacement(system: MultibodySystem, x: np.ndarray, beam: int = 0, F=None) -> dict[str, float]:
    """Tip centroid displacement of a beam from its undeformed place, in its hub frame (m)."""
    return system.tip_displacement(x, beam, F)


@dataclass
class StaticResult:
    """Static equilibrium of a scenario and its summary."""

    system: MultibodySystem
    solution: StaticSolution
    notes: list = field(default_factory=list)

    def to_dict(self) -> dict:
        sol = self.solution
        lam = sol.multipliers
        system = self.system
        layout = system.layout_for(True, static=True)
        out = {
            "tip_displacement": tip_displacement(system, sol.x),
            "tip_position": [float(v) for v in system.tip_position(sol.x)],
            "root_reaction_force": [float(v) for v in -lam[layout.clamp_lambda(0)][0:3]],
            "hub_holding_torque": float(-lam[layout.drive_lambda]),
            "newton_iterations": sol.newton_iterations,
            "load_steps": sol.load_steps,
            "chart_switches": sol.chart_switches,
        }
        if len(system.beams) > 1:
            out["beams"] = {b.name: {"tip_displacement": tip_displacement(system, sol.x, k),
                                     "tip_position": [float(v) for v in system.tip_position(sol.x, k)],
                                     "root_reaction_force": [float(v) for v in -lam[layout.clamp_lambda(k)][0:3]]}
                            for k, b in enumerate(system.beams)}
        return out


@dataclass
class ModalResult:
    """Natural frequencies about the static equilibrium of a scenario."""

    static: StaticResult
    modes: Modes
    about: str = "static equilibrium under the scenario's gravity and loads"

    def energy_fractions(self) -> list[dict[str, float]]:
        """Per mode, the shares of its kinetic energy (:mod:`hubbeam.solvers.mode_shapes`)."""
        from hubbeam.solvers.mode_shapes import energy_fractions

        sol = self.static.solution
        return [energy_fractions(self.static.system, sol.x, sol.chart, u) for u in self.modes.shapes.T]

    def shapes_dataset(self):
        """The mode shapes as an xarray.Dataset (docs/modes.md): the generalized vectors
        ``shape`` (mode, coordinate), mass-normalised, and every beam's centre-line
        ``displacement`` (mode, beam, station, component: axial, flap, lag) and ``twist``
        (mode, beam, station) at ``x`` (beam, station) (m from the root); complex shapes add
        the imaginary parts as ``*_imag``; ``frequency_hz``, ``label`` and ``energy_fraction``
        per mode."""
        import json

        import xarray as xr

        from hubbeam.solvers.mode_shapes import mode_label, motions_of, span_shapes

        system, sol, modes = self.static.system, self.static.solution, self.modes
        fractions = self.energy_fractions()
        motions = motions_of(system)
        spans = span_shapes(system, sol.x, sol.chart, modes.shapes)
        n = max(xs.size for xs, _, _ in spans)
        nm, nb = modes.shapes.shape[1], len(spans)
        x = np.full((nb, n), np.nan)
        disp = np.full((nm, nb, n, 3), np.nan, dtype=modes.shapes.dtype)
        twist = np.full((nm, nb, n), np.nan, dtype=modes.shapes.dtype)
        for k, (xs, d, t) in enumerate(spans):
            x[k, : xs.size], disp[:, k, : xs.size], twist[:, k, : xs.size] = xs, d, t
        unit = "per unit modal coordinate (kinetic energy eta'^2/2)"
        data = {"frequency_hz": ("mode", modes.frequencies_hz, {"units": "Hz"}),
                "label": ("mode", np.array([mode_label(f) for f in fractions], dtype=object)),
                "energy_fraction": (("mode", "motion"), np.array([[f.get(k, 0.0) for k in motions] for f in fractions]),
                                    {"units": "1"}),
                "x": (("beam", "station"), x, {"units": "m", "long_name": "station from the root"})}
        arrays = {"shape": (("mode", "coordinate"), modes.shapes.T, {"units": "coordinates' units kg^-1/2"}),
                  "displacement": (("mode", "beam", "station", "component"), disp, {"units": "kg^-1/2", "note": unit}),
                  "twist": (("mode", "beam", "station"), twist, {"units": "rad kg^-1/2 m^-1", "note": unit})}
        for name, (dims, values, attrs) in arrays.items():
            data[name] = (dims, np.real(values), attrs)
            if np.iscomplexobj(values):
                data[name + "_imag"] = (dims, np.imag(values), attrs)
        ds = xr.Dataset(data, coords={"mode": np.arange(1, nm + 1), "motion": list(motions),
                                      "beam": [b.name for b in system.beams],
                                      "component": ["axial", "flap", "lag"]})
        ds.attrs.update({"about": self.about, "normalisation": "u^H M u = 1 (mass-normalised); complex shapes "
                         "turned so that their largest generalized entry is real and positive",
                         "equilibrium": json.dumps([float(v) for v in sol.x])})
        return ds

    def to_dict(self) -> dict:
        from hubbeam.solvers.mode_shapes import mode_label

        fractions = self.energy_fractions()
        return {
            "frequencies_hz": [float(f) for f in self.modes.frequencies_hz],
            "labels": [mode_label(f) for f in fractions],
            "energy_fractions": fractions,
            "rigid_modes": self.modes.rigid_modes,
            "rigid_frequencies_hz": [float(f) for f in self.modes.rigid_frequencies_hz],
            "about": self.about,
            "equilibrium_tip_displacement": tip_displacement(self.static.system, self.static.solution.x),
        }


def static(scenario: Scenario, loads=None) -> StaticResult:
    """Static equilibrium under gravity and loads, hub held at theta = 0 and a free base at its
    initial pose (load stepping; a free base's gravity left out: :func:`equilibrium_system`).
    ``loads``: loads from Python functions as :func:`build_system` takes them (at t = 0, at rest)."""
    scenario = as_scenario(scenario)
    notes: list[str] = []
    system = equilibrium_system(scenario, notes, loads)
    return StaticResult(system, solve_static(system, load_steps=scenario.analysis.load_steps), notes)


def modes(scenario: Scenario) -> ModalResult:
    """Natural frequencies (Hz) linearised about the static equilibrium (fixed or free hub),
    or, for a hub driven at a constant omega_s, about the steadily rotating state
    (centrifugal pre-stress and gyroscopic terms; drag left out). Other prescribed profiles
    give the modes at rest with the hub held."""
    from hubbeam.solvers.modal import modal_analysis, rotating_modal_analysis

    scenario = as_scenario(scenario)
    notes: list[str] = []
    system = equilibrium_system(scenario, notes)
    count = scenario.analysis.count
    load_steps = scenario.analysis.load_steps
    if scenario.hub.motion == "prescribed" and system.drive.kind == "constant":
        omega = system.drive(0.0)[1]
        steady = solve_static(system, load_steps=load_steps, spin=omega)
        return ModalResult(StaticResult(system, steady, notes), rotating_modal_analysis(system, steady, omega, count=count),
                           about=f"steadily rotating state at omega = {omega:g} rad/s (centrifugal and gyroscopic "
                                 "terms; drag left out)")
    st = StaticResult(system, solve_static(system, load_steps=load_steps), notes)
    about = "static equilibrium under the scenario's gravity and loads"
    if scenario.hub.motion == "prescribed":
        about += f" with the hub held at rest (profile {system.drive.kind!r} does not turn steadily)"
    return ModalResult(st, modal_analysis(st.system, st.solution, count=count, free_hub=scenario.hub.motion == "free"),
                       about=about)


def linearize(scenario: Scenario, inputs=None, open_loop: bool = False, outputs=None, reduce: int | None = None,
              balanced: int | None = None, fmax: float | None = None, progress=None):
    """The continuous-time state space (A, B, C, D) of a scenario
    (:class:`hubbeam.analysis.state_space.LinearModel`): about the static equilibrium under its
    loads or, for a hub driven at a constant omega_s, about the steadily rotating state (other
    prescribed profiles: at rest with the hub held). ``inputs``: a list of "hub_torque" (free
    hub, N m, added to the torque law), "joint_torque:BEAM" (N m, in the joint of BEAM, added to
    its motor law), "tip_force:BEAM" (N, three components) and "load:NAME" (three components
    ``load_NAME_x|y|z``: a force of 1 N/m along the axes of the span load NAME, uniform over
    its stations, or, for ``load:tip``, of 1 N at the tip of the tip loads' beam; docs/loads.md);
    default: the hub torque of a free hub (the first beam's tip force on a held one) and every
    joint motor's torque. Outputs: the
    scenario's sensors (``outputs``: only those columns, in that order). ``open_loop``: leave
    the scenario's torque laws out, the hub's and the joints' motors, and its controllers (the
    plant a controller is designed for); otherwise the controllers ([[controllers]]) are closed
    around the linear model (:func:`hubbeam.analysis.state_space.closed_loop`), their states last.

    Reduced models (docs/state_space.md): ``reduce=N`` keeps the N lowest modes (modal
    truncation, the rest residualised: :meth:`LinearModel.reduced`), ``balanced=N`` N balanced
    states of the stable part (:meth:`LinearModel.balanced`), ``fmax=F`` (Hz) drops the modes
    above F (alone: a modal truncation at F; with ``balanced``: before balancing).
    ``progress(done, total)``: called as the output derivatives are computed."""
    from hubbeam.analysis.state_space import linearise

    if isinstance(outputs, str):  # one output, not a sequence of one-letter outputs
        outputs = [outputs]
    if reduce is not None and balanced is not None:
        raise ScenarioError("reduce: give reduce (modal) or balanced, not both")
    for key, value, low in (("reduce", reduce, 1), ("balanced", balanced, 1)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low):
            raise ScenarioError(f"{key}: a whole number >= {low} (got {value!r})")
    if fmax is not None and (isinstance(fmax, bool) or not isinstance(fmax, (int, float, np.floating))
                             or not np.isfinite(fmax) or fmax <= 0):
        raise ScenarioError(f"fmax: a frequency > 0 in Hz (got {fmax!r})")
    scenario = as_scenario(scenario)
    if isinstance(inputs, str):  # one input, not a sequence of one-letter inputs
        inputs = [inputs]
    elif inputs is not None:
        try:
            inputs = list(inputs)
        except TypeError:
            raise TypeError(f"inputs: expected a list of input names such as 'hub_torque' or 'tip_force:BEAM' (got "
                            f"{type(inputs).__name__} {inputs!r:.60})") from None
        bad = [i for i in inputs if not isinstance(i, str)]
        if bad:
            raise TypeError(f"inputs: every input is a name such as 'hub_torque' or 'tip_force:BEAM' (got "
                            f"{type(bad[0]).__name__} {bad[0]!r:.60})")
    notes: list[str] = []
    system = equilibrium_system(scenario, notes)
    motors = [f"joint_torque:{b.name}" for b in system.beams if b.mount.joint is not None
              and b.mount.joint.torque is not None]
    if open_loop:
        system = system.with_hub(torque=TorqueLaw()).without_motors()
    load_steps = scenario.analysis.load_steps
    if inputs is None:
        from hubbeam.analysis.state_space import BASE_TORQUE_INPUTS

        inputs = ["hub_torque"] if not system.hub.held else []
        if system.base.motion == BaseMotion.FREE:
            inputs += list(BASE_TORQUE_INPUTS)
        if not inputs:
            inputs = [f"tip_force:{system.beams[0].name}"]
        inputs += motors
    omega = 0.0
    if scenario.hub.motion == "prescribed" and system.drive.kind == "constant":
        omega = float(system.drive(0.0)[1])
        about = f"steadily rotating state at omega = {omega:g} rad/s (co-rotating coordinates)"
        equilibrium = solve_static(system, load_steps=load_steps, spin=omega)
    else:
        about = "static equilibrium under the scenario's gravity and loads"
        if scenario.hub.motion == "prescribed":
            about += f" with the hub held at rest (profile {system.drive.kind!r} does not turn steadily)"
        equilibrium = solve_static(system, load_steps=load_steps)
    closing = [] if open_loop else list(scenario.controllers)
    # the controllers' outputs as linearise names its inputs (joint_torque_NAME is "joint_torque:NAME")
    as_input = lambda o: "joint_torque:" + o[len("joint_torque_"):] if o.startswith("joint_torque_") else o  # noqa: E731
    extra = list(dict.fromkeys(as_input(o) for c in closing for o in c.outputs if as_input(o) not in inputs))
    model = linearise(system, equilibrium, omega, list(inputs) + extra, scenario.sensors, about, progress,
                      tip_beam=scenario.beam_index(scenario.loads.beam))
    wanted = model.inputs[:len(model.inputs) - len(extra)]  # every extra input is one column
    if closing:
        from hubbeam.analysis.state_space import closed_loop
        from hubbeam.io.scenario.controllers import controller_of

        for i, table in enumerate(closing):
            controller = controller_of(scenario, i)
            try:
                model = closed_loop(model, controller, table.inputs, table.outputs, controller.name)
            except ValueError as exc:
                raise ScenarioError(f"controllers[{i}]: {exc}") from None
        model = model.select(inputs=wanted)
    if outputs is not None:
        try:
            model = model.select(outputs=list(outputs))
        except ValueError as exc:
            raise ScenarioError(str(exc)) from None
    model.notes.extend(notes)
    if not system.hub.held:
        needed = -float(equilibrium.multipliers[system.layout_for(True, static=True).drive_lambda])  # the torque that holds it
        missing = needed - system.applied_torque(0.0, equilibrium.x, np.zeros(system.nx), equilibrium.chart)
        scale = system.static_force_scale(equilibrium.x, equilibrium.chart) * system.length_scale  # N m
        if abs(missing) > 1e-4 * max(scale, abs(needed)):  # above the discretisation's own small torque
            model.notes.append(f"the free hub is not in equilibrium there: it needs {missing:+.6g} N m more torque "
                               "(the model holds for the motion about that state)")
    if balanced is not None:
        try:
            model = model.balanced(balanced, fmax)
        except ValueError as exc:
            raise ScenarioError(f"balanced: {exc}") from None
    elif reduce is not None or fmax is not None:
        model = model.reduced(reduce, fmax)
    return model


def run(scenario: Scenario, progress=None, torque: TorqueLaw | None = None, sensors=None, state: bool = False,
        loads=None, laws=None):
    """Time integration of a scenario's dynamic analysis with all its settings (step,
    spectral radius, output step, Newton options). ``torque`` replaces the scenario's torque
    law on a free hub (a TorqueLaw, a number of N m or a function torque(t, theta, omega),
    :func:`torque_argument`; a function takes the slower Python step path); ``loads`` adds loads
    per unit length from Python functions f(t, x, position, velocity, frame) -> (force, moment)
    (:func:`load_function_argument`, docs/loads.md; the Python step path too); ``sensors`` its
    sensors (Sensor objects, tables or names of the scenario's sensors, :func:`with_sensors`);
    ``laws``: Python controller laws in the loop beside the scenario's ``[[controllers]]``, each
    a table {"function": f(t, u) -> y, "inputs": [sensor columns], "outputs": [names as
    ``[[controllers]]``' outputs], "name": optional}: f receives t (s) and the inputs' current
    values (an array) and returns the outputs' torques (N m), no states (the Python step path;
    dy/du by central differences); ``state=True`` also records the hub angle and every beam's
    geometry at the output times (:class:`hubbeam.snapshots.StateRecorder`; ``hubbeam run
    --state``). Returns (trajectory, failure): on a ComputationError, failure is that error and
    the trajectory holds the results up to it. A run too large to do (steps, records' memory)
    is a ScenarioError before anything is built; an interruption (KeyboardInterrupt,
    hubbeam.interrupt.Interrupted) carries the trajectory so far in its ``partial``."""
    from hubbeam.errors import ComputationError
    from hubbeam.limits import check_run
    from hubbeam.simulation import initial_state, simulate
    from hubbeam.solvers.newton_control import NewtonOptions

    scenario = as_scenario(scenario)
    torque = torque_argument(torque, scenario)
    if sensors is not None:
        scenario = with_sensors(scenario, sensors)
    check_run(scenario, state=state)
    for i, sensor in enumerate(scenario.sensors if state else ()):
        if sensor.name.startswith("state_"):
            raise ScenarioError(f"sensors[{i}].name: {sensor.name!r}: with a recorded state (--state) the names "
                                "state_... belong to the state's variables; rename the sensor")
    a = scenario.analysis
    newton = NewtonOptions(tolerance=a.tolerance, update=NEWTON_UPDATES[a.newton])
    try:
        system = build_system(scenario, torque, loads, list(laws or ()))
        if not system.compiled:  # the one model that cannot integrate in compiled code says so
            import warnings

            what = ("the controller laws are Python functions" if system.controller_laws
                    else "a load is a Python function" if system.load_functions
                    else f"{system.hub.torque!r} is a Python function")
            warnings.warn(f"{what}: the run takes the Python step path, several times slower than the compiled "
                          "laws and loads of a scenario file", stacklevel=2)
        recorder = None
        if state:
            from hubbeam.snapshots import StateRecorder

            recorder = StateRecorder(system)
        start = initial_state(system, a.load_steps, a.start)
        traj = simulate(system, scenario.sensors, a.t_end, a.dt, a.spectral_radius, min(scenario.output_dt, a.t_end),
                        progress, newton, start, recorder)
        traj.scenario = scenario
        return traj, None
    except ComputationError as exc:
        if exc.partial is not None:
            exc.partial.scenario = scenario
        return exc.partial, exc


def with_sensors(scenario: Scenario, sensors) -> Scenario:
    """``scenario`` with the sensors of :func:`run`'s ``sensors`` argument, validated like a
    scenario file's: Sensor objects or tables (dicts), or names of the scenario's own sensors
    (a single one or a list). TypeError naming ``sensors`` for anything else; ScenarioError
    for a name the scenario has not or a sensor the scenario refuses (a duplicate name, a
    beam it does not have)."""
    from hubbeam.io.scenario import Sensor, validate

    own = {s.name: s for s in scenario.sensors}
    if isinstance(sensors, (str, Sensor, dict)):
        sensors = [sensors]
    try:
        items = list(sensors)
    except TypeError:
        raise TypeError(f"sensors: expected a list of Sensor objects or of the scenario's sensor names (got "
                        f"{type(sensors).__name__} {sensors!r:.60})") from None
    tables = []
    for i, item in enumerate(items):
        if isinstance(item, str):
            if item not in own:
                raise ScenarioError(f"sensors[{i}]: the scenario has no sensor named {item!r} (its sensors: "
                                    f"{', '.join(own) or 'none'})")
            item = own[item]
        if isinstance(item, Sensor):
            item = item.model_dump(exclude_none=True)
        if not isinstance(item, dict):
            raise TypeError(f"sensors[{i}]: expected a Sensor, a sensor table (dict) or a sensor name (got "
                            f"{type(item).__name__} {item!r:.60})")
        tables.append(item)
    data = scenario.to_dict()
    data["sensors"] = tables
    return validate(data)
