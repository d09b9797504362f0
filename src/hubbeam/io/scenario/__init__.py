"""Scenario files (TOML), validated with pydantic; docs/scenario.md is the reference.

Every problem with a scenario becomes a :class:`ScenarioError` whose message is one
line naming the key (dotted path, e.g. ``beam.thickness``, ``beams[1].tip_body.mass`` or
``sensors[1].x``) and the reason. Units are SI; angles in the file are in degrees (the
slew ``angle`` and table angles, which are hub angles in rad, excepted).

A hub carries one beam (a ``[beam]`` table) or several (``[[beams]]`` tables). Code that
builds a model reads :meth:`Scenario.resolved_beams`: every beam with its defaults filled in,
SI units and angles in radians. ``scenario.beam`` is kept for single-beam scenarios.

Span-wise sections (``[[beams.sections]]``: :class:`SectionStation`) and per-beam structural
damping (``[beams.damping]``) are fields of :class:`Beam`, resolved into a
:class:`~hubbeam.elements.section.SpanSections` and a float of :class:`ResolvedBeam`.

The schema is split by table: :mod:`.common` (shared types), :mod:`.beams`, :mod:`.hub`,
:mod:`.analysis` (environment, drag, loads, analysis), :mod:`.sensors`, :mod:`.model` (the
scenario, checks across tables, messages, :func:`validate`) and :mod:`.overrides` (``--set``,
reading files and examples).
"""

from hubbeam.errors import ScenarioError
from hubbeam.io.examples import EXAMPLES, example_text
from hubbeam.io.scenario.analysis import Analysis, Damping, Environment, Loads
from hubbeam.io.scenario.beams import (STATION_CONSTANTS, Beam, BeamDamping, ResolvedBeam, ResolvedTipBody,
                                       SectionStation, TipBody, span_sections)
from hubbeam.io.scenario.common import MAX_PRECONE_DEG, STEP_TOLERANCE, KeyedChoice, StrictTable
from hubbeam.io.scenario.hub import DRIVE_KEYS, TORQUE_KEYS, Drive, Hub, HubTorque
from hubbeam.io.scenario.model import Scenario, table_files, validate
from hubbeam.io.scenario.overrides import apply_overrides, load_example, load_scenario, parse_override, value_at
from hubbeam.io.scenario.joints import Joint, JointTorque, ResolvedJoint
from hubbeam.io.scenario.sensors import (BEAM_ENERGY_PARTS, BEAM_SENSORS, JOINT_SENSORS, OPTIONAL_BEAM_SENSORS,
                                         SENSOR_PARTS, Sensor, SensorKind)

__all__ = [
    "Analysis", "BEAM_ENERGY_PARTS", "BEAM_SENSORS", "Beam", "BeamDamping", "DRIVE_KEYS", "Damping", "Drive",
    "EXAMPLES", "Environment", "Hub", "HubTorque", "JOINT_SENSORS", "Joint", "JointTorque", "KeyedChoice", "Loads",
    "MAX_PRECONE_DEG", "OPTIONAL_BEAM_SENSORS", "ResolvedBeam", "ResolvedJoint", "ResolvedTipBody", "SENSOR_PARTS",
    "STATION_CONSTANTS", "STEP_TOLERANCE", "Scenario", "ScenarioError", "SectionStation", "Sensor", "SensorKind",
    "StrictTable", "TORQUE_KEYS", "TipBody", "apply_overrides", "example_text", "load_example", "load_scenario",
    "parse_override", "span_sections", "table_files", "validate", "value_at",
]
