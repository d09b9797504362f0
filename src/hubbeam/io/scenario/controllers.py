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
from hubbeam.system.controllers import ACCELERATION_RATES, INPUTS, OUTPUTS, LinearController

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


def _input_code(scenario, column: str, key: str):
    """The controller input a sensor column (or its ``_rate``) gives."""
    sensors = {c: s for s in scenario.sensors for c in s.columns}
    rate = column not in sensors and column.endswith(RATE) and column[: -len(RATE)] in sensors
    name = column[: -len(RATE)] if rate else column
    if name not in sensors:
        raise ScenarioError(f"{key}: {column!r} is not a sensor column of the scenario (its columns: "
                            f"{', '.join(sensors) or 'none'}; NAME{RATE} for a column's rate)")
    kind = sensors[name].kind
    if rate and kind in ACCELERATION_RATES:
        raise ScenarioError(f"{key}: {column!r}: the rate of a {kind} sensor depends on the accelerations; a "
                            "controller input may depend on positions and velocities only")
    code = INPUTS.get((kind, rate))
    if code is None:
        supported = ", ".join(sorted({k + (RATE if r else "") for k, r in INPUTS}))
        raise ScenarioError(f"{key}: {column!r}: a {kind} sensor{' rate' if rate else ''} is not supported as a "
                            f"controller input (supported: {supported})")
    return code


def controller_of(scenario, i: int) -> LinearController:
    """The :class:`LinearController` of ``scenario.controllers[i]`` (ScenarioError naming the key)."""
    table = scenario.controllers[i]
    where = f"controllers[{i}]"
    inputs = [_input_code(scenario, c, f"{where}.inputs[{j}]") for j, c in enumerate(table.inputs)]
    outputs = []
    for j, name in enumerate(table.outputs):
        if name not in OUTPUTS:
            raise ScenarioError(f"{where}.outputs[{j}]: {name!r} is not a supported output (supported: "
                                f"{', '.join(OUTPUTS)})")
        if name == "hub_torque" and scenario.hub.motion != "free":
            raise ScenarioError(f"{where}.outputs[{j}]: hub_torque needs a free hub (hub.motion = "
                                f"{scenario.hub.motion!r})")
        outputs.append(OUTPUTS[name])
    m = read_matrices(table.file, f"{where}.file")
    try:
        return LinearController(m["A"], m["B"], m["C"], m["D"], tuple(inputs), tuple(outputs),
                                table.name or f"controller{i + 1}")
    except ValueError as exc:
        raise ScenarioError(f"{where}.file: {Path(table.file).name}: {exc}") from None


def check_controllers(scenario) -> None:
    """Every controller table read and checked (ScenarioError naming the key)."""
    names = set()
    for i, table in enumerate(scenario.controllers):
        name = table.name or f"controller{i + 1}"
        if name in names:
            raise ScenarioError(f"controllers[{i}].name: {name!r} is used twice")
        names.add(name)
        controller_of(scenario, i)
