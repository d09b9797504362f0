"""The ``[[controllers]]`` tables: linear controllers in the loop, read from a matrix file.

A table names its ``file`` (``.npz`` or NetCDF ``.nc`` holding arrays ``A`` n x n, ``B`` n x m,
``C`` p x n and ``D`` p x m, as ``hubbeam linearize -o`` writes or ``numpy.savez`` of a
python-control model), its ``inputs`` (m sensor columns of the scenario; ``NAME_rate`` for that
column's time derivative) and its ``outputs`` (p torque names as ``linearize`` uses them).
:func:`check_controllers` reads every file and checks it against the scenario, each problem a
one-line :class:`ScenarioError` naming its key (``controllers[0].inputs[1]: ...``);
:func:`controller_of` gives the system's :class:`~hubbeam.system.controllers.LinearController`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import numpy as np
from pydantic import Field, ValidationInfo, field_validator

from hubbeam.errors import ScenarioError
from hubbeam.io.scenario.common import Identifier, StrictTable, _absolute
from hubbeam.system.controller_inputs import (
    ACCELERATION_RATES,
    BASE_INPUTS,
    BASE_TORQUES,
    SENSOR_INPUTS,
    ControllerInput,
    ControllerOutput,
)
from hubbeam.system.controllers import ControllerLaw, LinearController

#: the suffix of an input that is a column's time derivative
RATE = "_rate"
#: the matrices a controller file holds
MATRICES = ("A", "B", "C", "D")


class Controller(StrictTable):
    name: Identifier | None = None
    file: Annotated[str, Field(min_length=1)]
    inputs: Annotated[list[Annotated[str, Field(min_length=1)]], Field(min_length=1)]
    outputs: Annotated[list[Annotated[str, Field(min_length=1)]], Field(min_length=1)]

    @field_validator("file")
    @classmethod
    def _absolute_file(cls, value, info: ValidationInfo):
        return _absolute(value, info)


def read_matrices(path: str, key: str) -> dict[str, np.ndarray]:
    """A, B, C, D from a ``.npz`` or NetCDF file; ScenarioError naming ``key`` otherwise."""
    p = Path(path)
    if not p.is_file():
        raise ScenarioError(f"{key}: no such file {path}")
    suffix = p.suffix.lower()
    try:
        if suffix == ".npz":
            with np.load(p, allow_pickle=False) as data:
                found = {name: np.asarray(data[name], dtype=float) for name in MATRICES if name in data.files}
        elif suffix in (".nc", ".nc4", ".netcdf"):
            import xarray as xr

            with xr.open_dataset(p) as data:
                found = {name: np.asarray(data[name].values, dtype=float) for name in MATRICES if name in data}
        else:
            raise ScenarioError(f"{key}: {p.name}: a .npz or NetCDF (.nc) file with arrays A, B, C, D")
    except ScenarioError:
        raise
    except (OSError, ValueError, TypeError, KeyError) as exc:
        raise ScenarioError(f"{key}: {p.name} is not a readable {suffix} file with arrays A, B, C, D "
                            f"({type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''})") from None
    missing = [name for name in MATRICES if name not in found]
    if missing:
        raise ScenarioError(f"{key}: {p.name} has no array {', '.join(missing)} (it needs A, B, C, D)")
    for name in MATRICES:
        bad = np.argwhere(~np.isfinite(found[name]))
        if bad.size:
            where = ", ".join(str(int(i)) for i in bad[0])
            raise ScenarioError(f"{key}: {p.name}: {name}[{where}] is {found[name][tuple(bad[0])]} (every entry of "
                                "A, B, C, D must be a finite number)")
    return found


def _input_of(scenario, column: str, key: str) -> ControllerInput:
    """The controller input a sensor column (or its ``_rate``) gives (ScenarioError naming ``key``)."""
    sensors = {c: s for s in scenario.sensors for c in s.columns}
    rate = column not in sensors and column.endswith(RATE) and column[: -len(RATE)] in sensors
    name = column[: -len(RATE)] if rate else column
    if name not in sensors:
        raise ScenarioError(f"{key}: {column!r} is not a sensor column of the scenario (its columns: "
                            f"{', '.join(sensors) or 'none'}; NAME{RATE} for a column's rate)")
    sensor = sensors[name]
    kind = sensor.kind
    if rate and kind in ACCELERATION_RATES:
        raise ScenarioError(f"{key}: {column!r}: the rate of a {kind} sensor depends on the accelerations; a "
                            "controller input may depend on positions and velocities only")
    if (kind, rate) not in SENSOR_INPUTS:
        supported = ", ".join(sorted({k + (RATE if r else "") for k, r in SENSOR_INPUTS}))
        raise ScenarioError(f"{key}: {column!r}: a {kind} sensor{' rate' if rate else ''} is not supported as a "
                            f"controller input (supported: {supported})")
    names = scenario.beam_names
    beam = names.index(sensor.beam) if sensor.beam is not None else 0
    part = 0
    if sensor.parts and name != sensor.name:
        part = sensor.parts.index(name[len(sensor.name) + 1:])
    if kind in BASE_INPUTS and scenario.base.motion == "fixed":
        raise ScenarioError(f"{key}: {column!r}: {kind} needs a base that moves (base.motion = 'fixed')")
    return ControllerInput(kind, rate, beam, part, float(sensor.x or 0.0), sensor.surface, float(sensor.y or 0.0),
                           float(sensor.z or 0.0))


def _output_of(scenario, name: str, key: str) -> ControllerOutput:
    """The controller output ``name`` (ScenarioError naming ``key`` when the scenario cannot take it)."""
    try:
        output = ControllerOutput.named(name, scenario.beam_names)
    except ValueError:
        raise ScenarioError(f"{key}: {name!r} is not a supported output (supported: hub_torque, "
                            f"{', '.join(BASE_TORQUES)}, joint_torque_BEAM for a beam on a single-axis joint)") from None
    if name == "hub_torque" and scenario.hub.motion != "free":
        raise ScenarioError(f"{key}: hub_torque needs a free hub (hub.motion = {scenario.hub.motion!r})")
    if name in BASE_TORQUES and scenario.base.motion != "free":
        raise ScenarioError(f"{key}: {name} needs a free base (base.motion = {scenario.base.motion!r})")
    if name.startswith("joint_torque_"):
        joint = scenario.resolved_beams()[output.beam].joint
        if joint is None or len(joint.axes) != 1:
            raise ScenarioError(f"{key}: {name}: beam {scenario.beam_names[output.beam]!r} is not on a single-axis "
                                "joint")
    return output


def controller_of(scenario, i: int) -> LinearController:
    """The :class:`LinearController` of ``scenario.controllers[i]`` (ScenarioError naming the key)."""
    table = scenario.controllers[i]
    where = f"controllers[{i}]"
    inputs = [_input_of(scenario, c, f"{where}.inputs[{j}]") for j, c in enumerate(table.inputs)]
    outputs = [_output_of(scenario, name, f"{where}.outputs[{j}]") for j, name in enumerate(table.outputs)]
    m = read_matrices(table.file, f"{where}.file")
    try:
        return LinearController(m["A"], m["B"], m["C"], m["D"], tuple(inputs), tuple(outputs),
                                table.name or f"controller{i + 1}")
    except ValueError as exc:
        raise ScenarioError(f"{where}.file: {Path(table.file).name}: {exc}") from None


def law_of(scenario, law, i: int) -> ControllerLaw:
    """The :class:`ControllerLaw` of ``law``, a table {"function": f(t, u) -> y, "inputs": sensor
    columns, "outputs": output names, "name": optional} (``laws[i]`` in messages: TypeError for a
    malformed table, ScenarioError naming the key for a column or output the scenario refuses)."""
    where = f"laws[{i}]"
    if not isinstance(law, dict) or not callable(law.get("function")) or set(law) - {"function", "inputs", "outputs",
                                                                                        "name"}:
        raise TypeError(f"{where}: a table {{'function': f(t, u), 'inputs': [...], 'outputs': [...]}} (got "
                        f"{law!r:.80})")
    inputs, outputs = law.get("inputs"), law.get("outputs")
    for key, names in (("inputs", inputs), ("outputs", outputs)):
        if not isinstance(names, (list, tuple)) or not names or not all(isinstance(n, str) for n in names):
            raise TypeError(f"{where}.{key}: a non-empty list of names (got {names!r:.80})")
    specs = [_input_of(scenario, c, f"{where}.inputs[{j}]") for j, c in enumerate(inputs)]
    places = [_output_of(scenario, n, f"{where}.outputs[{j}]") for j, n in enumerate(outputs)]
    return ControllerLaw(law["function"], tuple(specs), tuple(places), str(law.get("name", f"law{i + 1}")))


def check_controllers(scenario) -> None:
    """Every controller table read and checked (ScenarioError naming the key)."""
    names = set()
    for i, table in enumerate(scenario.controllers):
        name = table.name or f"controller{i + 1}"
        if name in names:
            raise ScenarioError(f"controllers[{i}].name: {name!r} is used twice")
        names.add(name)
        controller_of(scenario, i)
