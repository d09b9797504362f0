"""Plain-Python entry points: scenario in, data out (nothing is printed here)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubbeam.elements.section import Section, saint_venant_torsion_constant
from hubbeam.io.scenario import Scenario, ScenarioError
from hubbeam.solvers.modal import Modes, modal_analysis, rotating_modal_analysis
from hubbeam.solvers.static import StaticSolution, solve_static
from hubbeam.system.beam import DEFAULT_GAUSS_POINTS, AncfBeam
from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.system.ancf_system import AncfHubSystem

#: analysis.newton of a scenario -> NewtonOptions.update (when the iteration matrix is rebuilt)
NEWTON_UPDATES = {"full": "iteration", "step": "step", "modified": "adaptive"}
from hubbeam.system.ffr_system import FfrHubSystem
from hubbeam.system.hub import DriveProfile
from hubbeam.system.model import HubSystem


# --- issue 15: public functions take a Scenario or the path of a scenario file, and nothing else
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
# --- end issue 15


def section_of(scenario: Scenario) -> Section:
    b = scenario.beam
    jt = b.torsion_constant if b.torsion_constant is not None else saint_venant_torsion_constant(b.width, b.thickness)
    return Section(b.width, b.thickness, b.density, b.youngs_modulus, scenario.shear_modulus, jt)


def build_system(scenario: Scenario) -> HubSystem:
    """The hub-beam system a scenario describes (a Scenario or a path)."""
    scenario = as_scenario(scenario)  # issue 15
    b = scenario.beam
    if b.formulation == "ancf":
        beam, system_class = AncfBeam(b.length, b.elements, section_of(scenario), b.gauss_points or DEFAULT_GAUSS_POINTS), AncfHubSystem
    else:
        beam = FfrBeam(b.length, b.elements, section_of(scenario), geometric_stiffening=bool(b.geometric_stiffening))
        system_class = FfrHubSystem
    hub = scenario.hub
    drive = DriveProfile("rest")
    if hub.drive is not None:
        drive = DriveProfile(hub.drive.profile, hub.drive.omega_s, hub.drive.T, hub.drive.t1)
    return system_class(
        beam,
        radius=hub.radius,
        twist=scenario.twist_rad,
        motion=hub.motion,
        hub_inertia=hub.inertia,
        hub_torque=hub.torque,
        drive=drive,
        gravity=np.array(scenario.environment.gravity),
        tip_force=np.array(scenario.loads.tip_force),
        tip_moment=np.array(scenario.loads.tip_moment),
        damping=(scenario.damping.linear, scenario.damping.quadratic),
    )


def tip_displacement(system: HubSystem, x: np.ndarray) -> dict[str, float]:
    """Tip centroid displacement from its undeformed place, in the hub frame (m)."""
    return system.tip_displacement(x)


@dataclass
class StaticResult:
    """Static equilibrium of a scenario and its summary."""

    system: HubSystem
    solution: StaticSolution

    def to_dict(self) -> dict:
        sol = self.solution
        lam = sol.multipliers
        return {
            "tip_displacement": tip_displacement(self.system, sol.x),
            "tip_position": [float(v) for v in self.system.tip_position(sol.x)],
            "root_reaction_force": [float(v) for v in -lam[0:3]],
            "hub_holding_torque": self.system.drive_torque(lam),
            "newton_iterations": sol.newton_iterations,
            "load_steps": sol.load_steps,
            "chart_switches": sol.chart_switches,
        }


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
    scenario = as_scenario(scenario)  # issue 15
    system = build_system(scenario)
    return StaticResult(system, solve_static(system, load_steps=scenario.analysis.load_steps))


def modes(scenario: Scenario) -> ModalResult:
    """Natural frequencies (Hz) linearised about the static equilibrium (fixed or free hub),
    or, for a hub driven at a constant omega_s, about the steadily rotating state
    (centrifugal pre-stress and gyroscopic terms; drag left out). Other prescribed profiles
    give the modes at rest with the hub held."""
    scenario = as_scenario(scenario)  # issue 15
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


def run(scenario: Scenario, progress=None):
    """Time integration of a scenario's dynamic analysis with all its settings (step,
    spectral radius, output step, Newton options). Returns (trajectory, failure): on a
    ComputationError, failure is that error and the trajectory holds the results up to it.
    A run too large to do (steps, records' memory) is a ScenarioError before anything is built;
    an interruption (KeyboardInterrupt, hubbeam.interrupt.Interrupted) carries the trajectory
    so far in its ``partial``."""
    from hubbeam.limits import check_run
    from hubbeam.simulation import simulate
    from hubbeam.solvers.errors import ComputationError
    from hubbeam.solvers.generalized_alpha import NewtonOptions

    scenario = as_scenario(scenario)  # issue 15
    check_run(scenario)  # issue 15
    a = scenario.analysis
    newton = NewtonOptions(tolerance=a.tolerance, update=NEWTON_UPDATES[a.newton])
    try:
        return simulate(build_system(scenario), scenario.sensors, a.t_end, a.dt, a.spectral_radius,
                        min(scenario.output_dt, a.t_end), progress, newton), None  # issue 15: no overflow at 1e300
    except ComputationError as exc:
        return exc.partial, exc
