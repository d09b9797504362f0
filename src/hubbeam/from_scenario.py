"""The system a scenario describes: a scenario file read and validated, and its base, hub, beams,
joints, loads and controllers built as a :class:`~hubbeam.system.multibody.MultibodySystem`
(nothing is printed here). :mod:`hubbeam.api` runs the analyses on it."""

from __future__ import annotations

import numpy as np

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.elements.section import Section
from hubbeam.io.scenario import Scenario, ScenarioError
from hubbeam.system.ancf_part import AncfPart
from hubbeam.system.base import Base, BaseMotion, HubPlacement
from hubbeam.system.base_laws import AttitudeLaw
from hubbeam.system.beam import DEFAULT_GAUSS_POINTS, AncfBeam
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.joints import NAMED_AXES, Joint
from hubbeam.system.laws import DriveProfile, TorqueLaw
from hubbeam.system.mount import Mount
from hubbeam.system.multibody import Hub, MultibodySystem
from hubbeam.system.tip_body import TipBody

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


def joint_of(spec, key: str) -> Joint | None:
    """The :class:`~hubbeam.system.joints.Joint` of a resolved beam's joint (None: clamped);
    ``key`` names its table in errors (``beams[k].joint``)."""
    j = spec.joint
    if j is None:
        return None
    axes = tuple(NAMED_AXES[a] if isinstance(a, str) else a for a in j.axes)
    return Joint(axes, j.names, j.stiffness, j.damping, j.neutral, j.initial_angle, j.initial_rate, j.latch,
                 None if j.torque is None else torque_law(j.torque, f"{key}.torque"))


def beam_part(spec, key: str = "beams[0]"):
    """The system part of one resolved beam of a scenario (:class:`hubbeam.io.scenario.ResolvedBeam`);
    ``key`` names its table in errors."""
    section = Section(spec.width, spec.thickness, spec.density, spec.youngs_modulus, spec.shear_modulus,
                      spec.torsion_constant)
    mount = Mount(spec.radius, spec.twist, spec.azimuth, spec.precone, getattr(spec, "parent", None),
                  joint_of(spec, f"{key}.joint") if getattr(spec, "joint", None) is not None else None)
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
                   modes=spec.modes, **span)
    return FfrPart(beam, mount, name=spec.name, **loads)


def drive_profile(drive, key: str) -> DriveProfile:
    """The drive profile of a scenario's drive table (``key`` names it in errors)."""
    if drive.profile == "table":
        from hubbeam.io.tables import read_drive_table

        return read_drive_table(drive.file, f"{key}.file", interpolation=drive.interpolation,
                                smoothing=drive.smoothing)
    if drive.profile == "slew":
        return DriveProfile.slew(drive.angle, drive.T)
    return DriveProfile(drive.profile, drive.omega_s, drive.T, drive.t1)


def torque_law(law, key: str = "hub.torque") -> TorqueLaw:
    """The torque law of a scenario's [hub.torque] (None: no torque), or of another torque table
    named ``key`` in errors (a joint's motor)."""
    if law is None:
        return TorqueLaw()
    if law.law == "constant":
        return TorqueLaw.constant(law.value)
    if law.law == "table":
        from hubbeam.io.tables import read_torque_table

        return read_torque_table(law.file, f"{key}.file")
    return TorqueLaw.pd(law.kp, law.kd, drive_profile(law.reference, f"{key}.reference"))


def torque_argument(torque, scenario: Scenario) -> TorqueLaw | None:
    """The ``torque`` argument of :func:`run` and :func:`build_system` as a TorqueLaw: None
    (the scenario's law), a TorqueLaw, a number (N m, a constant law) or a Python function
    torque(t, theta, omega) (wrapped in ``TorqueLaw.callable``). TypeError naming ``torque``
    for anything else; ScenarioError when the scenario's hub is not free (a fixed or
    prescribed hub takes no torque law, as a scenario file's hub.torque is refused there)."""
    import numbers

    if torque is None:
        return None
    if isinstance(torque, TorqueLaw):
        law = torque
    elif isinstance(torque, numbers.Real) and not isinstance(torque, bool):
        if not np.isfinite(float(torque)):
            raise ValueError(f"torque: must be a finite number of N m (got {float(torque)!r})")
        law = TorqueLaw.constant(float(torque))
    elif callable(torque):
        law = TorqueLaw.callable(torque)
    else:
        raise TypeError(f"torque: expected a TorqueLaw, a number (N m) or a function torque(t, theta, omega) "
                        f"(got {type(torque).__name__} {torque!r:.60})")
    if law.function is not None:  # a Python function: called once here, so that a wrong one is named now
        try:
            value = float(law.function(0.0, 0.0, 0.0))
        except Exception as exc:
            raise TypeError(f"torque: the function must take (t, theta, omega) and return a number of N m (at t = 0: "
                            f"{exc.__class__.__name__}: {exc})") from None
        if not np.isfinite(value):
            raise ValueError(f"torque: the function returns {value!r} N m at t = 0, theta = 0, omega = 0")
    if scenario.hub.motion != "free":
        raise ScenarioError(f"torque: a torque law acts on a free hub only (hub.motion is {scenario.hub.motion!r}, "
                            "as a scenario file's hub.torque is refused there)")
    return law


def base_of(scenario: Scenario) -> Base:
    """The :class:`~hubbeam.system.base.Base` of a scenario's ``[base]`` (SI units, radians)."""
    b = scenario.base
    init = b.initial
    law = None
    if b.torque is not None:
        t = b.torque
        law = AttitudeLaw(t.kp, t.kd, t.target or (0.0, 0.0, 0.0),
                          None if t.slew is None else t.slew.axis, 0.0 if t.slew is None else t.slew.angle,
                          1.0 if t.slew is None else t.slew.T)
    table = None
    if b.motion == "table":
        from hubbeam.io.tables import read_pose_table

        table = read_pose_table(b.file, "base.file")
    inertia = b.inertia_matrix if b.inertia_matrix is not None else np.zeros((3, 3))
    return Base(b.motion, init.position, init.rotation, init.velocity, init.angular_velocity, b.mass or 0.0,
                inertia, b.centre_of_mass, table, law)


def load_function_argument(loads, scenario: Scenario) -> list:
    """The ``loads`` argument of :func:`run`, :func:`static` and :func:`build_system` as a list
    of :class:`~hubbeam.system.load_functions.LoadFunction` with the beam's place: None (none),
    a LoadFunction (its ``beam`` a place or a beam's name) or a Python function
    f(t, x, position, velocity, frame) -> (force, moment) on the first beam, or a list of these.
    TypeError naming ``loads`` for anything else; ScenarioError for a beam the scenario has not."""
    from dataclasses import replace as replaced

    from hubbeam.system.load_functions import LoadFunction

    if loads is None:
        return []
    items = list(loads) if isinstance(loads, (list, tuple)) else [loads]
    out = []
    for i, item in enumerate(items):
        if not isinstance(item, LoadFunction):
            if not callable(item):
                raise TypeError(f"loads[{i}]: expected a LoadFunction or a function f(t, x, position, velocity, frame) "
                                f"(got {type(item).__name__} {item!r:.60})")
            item = LoadFunction(item, 0, name=f"function{i + 1}")
        beam = item.beam
        if isinstance(beam, str):
            beam = scenario.beam_index(beam)
        elif isinstance(beam, bool) or not isinstance(beam, (int, np.integer)) or not 0 <= beam < len(scenario.beam_names):
            raise ScenarioError(f"loads[{i}].beam: a beam's name or place 0 .. {len(scenario.beam_names) - 1} "
                                f"(got {beam!r})")
        out.append(replaced(item, beam=int(beam)))
    return out


def build_system(scenario: Scenario, torque: TorqueLaw | None = None, loads=None, laws=()) -> MultibodySystem:
    """The system a scenario describes: its base, its hub and its beams. ``torque``: a torque law
    that replaces the scenario's (e.g. ``TorqueLaw.callable(f)`` for a Python function
    torque(t, theta, omega), which integrates step by step in Python; a number or a bare function
    is taken as :func:`torque_argument` says; a free hub only). ``loads``: loads per unit length
    from Python functions f(t, x, position, velocity, frame) (:func:`load_function_argument`,
    docs/loads.md), added to the scenario's; they too integrate step by step in Python.
    ``laws``: Python controller laws beside the scenario's ``[[controllers]]`` (:func:`run`).
    ``scenario``: a Scenario or a scenario file's path."""
    scenario = as_scenario(scenario)
    torque = torque_argument(torque, scenario)
    functions = load_function_argument(loads, scenario)
    hub = scenario.hub
    drive = drive_profile(hub.drive, "hub.drive") if hub.drive is not None else DriveProfile("rest")
    law = torque if torque is not None else torque_law(hub.torque_law)
    base = base_of(scenario)
    # a hub fixed to a base that moves is part of it: no rotor of its own (a free base's body holds
    # its inertia; on a table base hub.inertia of a fixed hub is unused, as on a fixed base)
    inertia = 0.0 if (base.moves and hub.motion == "fixed") else hub.inertia
    from hubbeam.io.scenario.controllers import controller_of, law_of

    parts = [beam_part(spec, scenario.beam_key(spec.index)) for spec in scenario.resolved_beams()]
    return MultibodySystem(parts, Hub(hub.motion, inertia, law, drive),
                           attachments=load_attachments(scenario, parts) + functions,
                           gravity=np.array(scenario.environment.gravity),
                           damping=(scenario.damping.linear, scenario.damping.quadratic), base=base,
                           placement=HubPlacement(hub.position, np.radians(hub.orientation)),
                           controllers=[controller_of(scenario, i) for i in range(len(scenario.controllers))]
                           + [law_of(scenario, law, i) for i, law in enumerate(laws)])


def load_attachments(scenario: Scenario, parts) -> list:
    """The scenario's loads along the span and tip loads from tables (:class:`hubbeam.system.span_loads.SpanLoad`)
    on its beams' ``parts``: ``[[loads.span]]`` and ``loads.tip_force_file``, ``loads.tip_moment_file``."""
    from hubbeam.io.tables import FORCE_COLUMNS, MOMENT_COLUMNS, read_span_table, read_tip_table
    from hubbeam.system.span_loads import SpanLoad

    loads = scenario.loads
    out = []
    for i, (span, name) in enumerate(zip(loads.span, loads.span_names)):
        k = scenario.beam_index(span.beam)
        section = span.axes == "section"
        if span.file is None:
            zero = (0.0, 0.0, 0.0)
            out.append(SpanLoad.uniform(k, parts[k], span.force or zero, span.moment or zero, section, name))
        else:
            x, times, values = read_span_table(span.file, f"loads.span[{i}].file", parts[k].length)
            out.append(SpanLoad.table(k, parts[k], x, times, values, section, name))
    k = scenario.beam_index(loads.beam)
    tables = {what: read_tip_table(getattr(loads, f"{what}_file"), f"loads.{what}_file", columns)
              for what, columns in (("tip_force", FORCE_COLUMNS), ("tip_moment", MOMENT_COLUMNS))
              if getattr(loads, f"{what}_file") is not None}
    for what, (times, values) in tables.items():
        zero = np.zeros_like(values)
        force, moment = (values, zero) if what == "tip_force" else (zero, values)
        out.append(SpanLoad.tip(k, parts[k], times, force, moment, what))
    return out


#: what statics, modes and linearize say when they leave a free base's gravity out
FREE_FALL_NOTE = ("the base is free: its uniform gravity field is left out of the equilibrium and the linear model "
                  "(a free body in free fall is not deformed by it)")


def equilibrium_system(scenario: Scenario, notes: list | None = None, loads=None) -> MultibodySystem:
    """The system of a scenario for statics, modes and linearize: a free base's uniform gravity
    is removed (the equivalence principle: a body in free fall is not deformed by it), with a
    note in ``notes``. Without the scenario's controllers: statics and modes leave them out (with
    a note), ``linearize`` closes them around the linear model (:func:`linearize`)."""
    system = build_system(scenario, loads=loads).without_controllers()
    if scenario.controllers and notes is not None:
        notes.append("the controllers ([[controllers]]) are left out of the equilibrium (and of modes); linearize "
                     "closes them around the linear model unless --open-loop")
    if system.base.motion == BaseMotion.FREE and np.any(system.gravity):
        system = system.with_gravity((0.0, 0.0, 0.0))
        if notes is not None:
            notes.append(FREE_FALL_NOTE)
    return system


def reduction_warnings(scenario: Scenario, system: MultibodySystem | None = None) -> list[str]:
    """One line for each thing the kept modes of a modally reduced FFR beam (``modes = N``)
    may miss in the scenario: a share of the static deflection under gravity above 1 %, or a
    drive or PD reference (spin_up, slew, exponential over T s: up to about 2 / T Hz) that
    excites frequencies near the highest kept mode."""
    if not any(getattr(b, "modes", None) for b in scenario.resolved_beams()):
        return []
    from hubbeam.elements.ffr.modal import coverage_warnings  # here: it imports scipy.linalg (0.3 s)

    system = build_system(scenario) if system is None else system
    hub = scenario.hub
    law = hub.torque_law
    drive = hub.drive if hub.drive is not None else (law.reference if law is not None and law.law == "pd" else None)
    excitation = 2.0 / drive.T if drive is not None and drive.profile in ("spin_up", "slew", "exponential") else None
    out = []
    x0, F0 = system.initial_state()
    for k, part in enumerate(system.beams):
        if isinstance(part, FfrPart):
            out += coverage_warnings(part.beam, system.root_pose(k, x0, F0)[1].T @ system.gravity, excitation,
                                     name=part.name)
    return out
