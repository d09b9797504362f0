"""Plain-Python entry points: scenario in, data out (nothing is printed here)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.io.scenario import Scenario, ScenarioError
from hubbeam.solvers.static import StaticSolution, solve_static
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.beam import DEFAULT_GAUSS_POINTS, AncfBeam
from hubbeam.elements.section import Section
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.hub_system import Hub, HubSystem
from hubbeam.system.laws import DriveProfile, TorqueLaw
from hubbeam.system.mount import Mount
from hubbeam.system.tip_body import TipBody

if TYPE_CHECKING:  # the modal analysis is imported where it is used: scipy.linalg is slow to load
    from hubbeam.solvers.modal import Modes

#: analysis.newton of a scenario -> NewtonOptions.update (when the iteration matrix is rebuilt)
NEWTON_UPDATES = {"full": "iteration", "step": "step", "modified": "adaptive"}


def load_scenario(source, overrides: list[str] | None = None) -> Scenario:
    """Read, override (``--set``-style strings) and validate a scenario file; ScenarioError
    for anything else (a path that is not a text file, overrides that are not a list of strings)."""
    import os

    from hubbeam.io import scenario as io_scenario
    from hubbeam.io.targets import check_input_file

    if overrides is not None and (isinstance(overrides, (str, bytes)) or not isinstance(overrides, (list, tuple))
                                  or not all(isinstance(o, str) for o in overrides)):
        raise ScenarioError(f"overrides: expected a list of 'KEY=VALUE' strings (got {type(overrides).__name__} "
                            f"{overrides!r:.60})")
    if not isinstance(source, (str, os.PathLike)):
        raise ScenarioError(f"scenario: expected the path of a scenario file (got {type(source).__name__} {source!r:.60})")
    return io_scenario.load_scenario(check_input_file(source), list(overrides or []))


def as_scenario(scenario) -> Scenario:
    """A Scenario validated again (``model_copy(update=...)`` skips validation) or a scenario file's path."""
    import os
    import warnings

    from hubbeam.io.scenario import validate

    if isinstance(scenario, Scenario):
        unknown = [k for k in vars(scenario) if k not in type(scenario).model_fields]
        if unknown:  # model_copy(update=...) with a name that is not a field (e.g. "beam" for "single_beam")
            raise ScenarioError(f"{unknown[0]}: not a field of Scenario (fields: {', '.join(type(scenario).model_fields)})")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # pydantic warns when model_copy put a wrong type in
            try:
                data = scenario.to_dict()
            except Exception as exc:
                raise ScenarioError(f"scenario: not a valid Scenario ({exc.__class__.__name__})") from None
        scenario = validate(data)
    elif isinstance(scenario, (str, os.PathLike)):
        scenario = load_scenario(scenario)
    else:
        raise ScenarioError(f"scenario: expected a Scenario or the path of a scenario file (got "
                            f"{type(scenario).__name__} {scenario!r:.60})")
    from hubbeam.limits import check_magnitudes

    check_magnitudes(scenario)  # no overflow or underflow inside the model
    return scenario


def beam_part(spec):
    """The system part of one resolved beam of a scenario (:class:`hubbeam.io.scenario.ResolvedBeam`)."""
    section = Section(spec.width, spec.thickness, spec.density, spec.youngs_modulus, spec.shear_modulus,
                      spec.torsion_constant)
    mount = Mount(spec.radius, spec.twist, spec.azimuth, spec.precone)
    tip = None
    if spec.tip_body is not None:
        tb = spec.tip_body
        tip = TipBody(float(tb.mass), tuple(map(float, tb.inertia)), tuple(map(float, tb.offset)))
    loads = {"tip_force": np.array(spec.tip_force, dtype=float), "tip_moment": np.array(spec.tip_moment, dtype=float)}
    span = {"sections": spec.sections, "structural_damping": spec.structural_damping}
    if spec.formulation == "ancf":
        beam = AncfBeam(spec.length, spec.elements, section, spec.gauss_points or DEFAULT_GAUSS_POINTS, **span)
        return AncfPart(beam, mount, tip_body=tip, name=spec.name, **loads)
    beam = FfrBeam(spec.length, spec.elements, section, geometric_stiffening=spec.geometric_stiffening, tip_body=tip,
                   modes=spec.modes, **{k: v for k, v in span.items() if v})
    return FfrPart(beam, mount, name=spec.name, **loads)


def drive_profile(drive, key: str) -> DriveProfile:
    """The drive profile of a scenario's drive table (``key`` names it in errors)."""
    if drive.profile == "table":
        from hubbeam.io.tables import read_drive_table

        return read_drive_table(drive.file, f"{key}.file")
    if drive.profile == "slew":
        return DriveProfile.slew(drive.angle, drive.T)
    return DriveProfile(drive.profile, drive.omega_s, drive.T, drive.t1)


def torque_law(law) -> TorqueLaw:
    """The torque law of a scenario's [hub.torque] (None: no torque)."""
    if law is None:
        return TorqueLaw()
    if law.law == "constant":
        return TorqueLaw.constant(law.value)
    if law.law == "table":
        from hubbeam.io.tables import read_torque_table

        return read_torque_table(law.file, "hub.torque.file")
    return TorqueLaw.pd(law.kp, law.kd, drive_profile(law.reference, "hub.torque.reference"))


def build_system(scenario: Scenario, torque: TorqueLaw | None = None) -> HubSystem:
    """The hub system a scenario describes. ``torque``: a torque law that replaces the
    scenario's (e.g. ``TorqueLaw.callable(f)`` for a Python function torque(t, theta, omega),
    which integrates step by step in Python). ``scenario``: a Scenario or a scenario file's path."""
    scenario = as_scenario(scenario)
    hub = scenario.hub
    drive = drive_profile(hub.drive, "hub.drive") if hub.drive is not None else DriveProfile("rest")
    law = torque if torque is not None else torque_law(hub.torque_law)
    return HubSystem([beam_part(spec) for spec in scenario.resolved_beams()],
                     Hub(hub.motion, hub.inertia, law, drive),
                     gravity=np.array(scenario.environment.gravity), damping=(scenario.damping.linear,
                                                                              scenario.damping.quadratic))


def reduction_warnings(scenario: Scenario, system: HubSystem | None = None) -> list[str]:
    """One line for each thing the kept modes of a modally reduced FFR beam (``modes = N``)
    may miss in the scenario: a share of the static deflection under gravity above 1 %, or a
    drive or PD reference (spin_up, slew, exponential over T s: up to about 2 / T Hz) that
    excites frequencies near the highest kept mode."""
    from hubbeam.elements.ffr.modal import coverage_warnings

    if not any(getattr(b, "modes", None) for b in scenario.resolved_beams()):
        return []
    system = build_system(scenario) if system is None else system
    hub = scenario.hub
    law = hub.torque_law
    drive = hub.drive if hub.drive is not None else (law.reference if law is not None and law.law == "pd" else None)
    excitation = 2.0 / drive.T if drive is not None and drive.profile in ("spin_up", "slew", "exponential") else None
    out = []
    for part in system.beams:
        if isinstance(part, FfrPart):
            out += coverage_warnings(part.beam, part.mount.frame(0.0).T @ system.gravity, excitation, name=part.name)
    return out


def tip_displacement(system: HubSystem, x: np.ndarray, beam: int = 0) -> dict[str, float]:
    """Tip centroid displacement of a beam from its undeformed place, in its hub frame (m)."""
    return system.tip_displacement(x, beam)


@dataclass
class StaticResult:
    """Static equilibrium of a scenario and its summary."""

    system: HubSystem
    solution: StaticSolution

    def to_dict(self) -> dict:
        sol = self.solution
        lam = sol.multipliers
        system = self.system
        layout = system.layout_for(True)
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

    def to_dict(self) -> dict:
        return {
            "frequencies_hz": [float(f) for f in self.modes.frequencies_hz],
            "rigid_modes": self.modes.rigid_modes,
            "rigid_frequencies_hz": [float(f) for f in self.modes.rigid_frequencies_hz],
            "about": self.about,
            "equilibrium_tip_displacement": tip_displacement(self.static.system, self.static.solution.x),
        }


def static(scenario: Scenario) -> StaticResult:
    """Static equilibrium under gravity and loads, hub held at theta = 0 (load stepping)."""
    scenario = as_scenario(scenario)
    system = build_system(scenario)
    return StaticResult(system, solve_static(system, load_steps=scenario.analysis.load_steps))


def modes(scenario: Scenario) -> ModalResult:
    """Natural frequencies (Hz) linearised about the static equilibrium (fixed or free hub),
    or, for a hub driven at a constant omega_s, about the steadily rotating state
    (centrifugal pre-stress and gyroscopic terms; drag left out). Other prescribed profiles
    give the modes at rest with the hub held."""
    from hubbeam.solvers.modal import modal_analysis, rotating_modal_analysis

    scenario = as_scenario(scenario)
    system = build_system(scenario)
    count = scenario.analysis.count
    load_steps = scenario.analysis.load_steps
    if scenario.hub.motion == "prescribed" and system.drive.kind == "constant":
        omega = system.drive(0.0)[1]
        steady = solve_static(system, load_steps=load_steps, spin=omega)
        return ModalResult(StaticResult(system, steady), rotating_modal_analysis(system, steady, omega, count=count),
                           about=f"steadily rotating state at omega = {omega:g} rad/s (centrifugal and gyroscopic "
                                 "terms; drag left out)")
    st = StaticResult(system, solve_static(system, load_steps=load_steps))
    about = "static equilibrium under the scenario's gravity and loads"
    if scenario.hub.motion == "prescribed":
        about += f" with the hub held at rest (profile {system.drive.kind!r} does not turn steadily)"
    return ModalResult(st, modal_analysis(st.system, st.solution, count=count, free_hub=scenario.hub.motion == "free"),
                       about=about)


def run(scenario: Scenario, progress=None, torque: TorqueLaw | None = None, sensors=None):
    """Time integration of a scenario's dynamic analysis with all its settings (step,
    spectral radius, output step, Newton options). ``torque`` replaces the scenario's torque
    law (e.g. ``TorqueLaw.callable(f)``: the slower Python step path); ``sensors`` its
    sensors. Returns (trajectory, failure): on a ComputationError, failure is that error and
    the trajectory holds the results up to it. A run too large to do (steps, records' memory)
    is a ScenarioError before anything is built; an interruption (KeyboardInterrupt,
    hubbeam.interrupt.Interrupted) carries the trajectory so far in its ``partial``."""
    from hubbeam.errors import ComputationError
    from hubbeam.limits import check_run
    from hubbeam.simulation import initial_state, simulate
    from hubbeam.solvers.generalized_alpha import NewtonOptions

    scenario = as_scenario(scenario)
    check_run(scenario)
    a = scenario.analysis
    newton = NewtonOptions(tolerance=a.tolerance, update=NEWTON_UPDATES[a.newton])
    try:
        system = build_system(scenario, torque)
        state = initial_state(system, a.load_steps, a.start)
        return simulate(system, scenario.sensors if sensors is None else sensors, a.t_end, a.dt, a.spectral_radius,
                        min(scenario.output_dt, a.t_end), progress, newton, state), None
    except ComputationError as exc:
        return exc.partial, exc
