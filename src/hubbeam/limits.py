"""Up-front size of a time integration: steps, output records and their memory.

A scenario may ask for more than any run can give (``t_end = 1e6`` at ``dt = 1e-6`` is
10^12 steps; ``output_dt = dt`` over a long run fills the memory with records). These
are found before anything is built, from the scenario alone, and refused as bad input
naming the key (exit status 2):

- ``analysis.dt`` below :data:`MIN_DT` (the integrator's h^2 terms lose all precision or
  underflow);
- more than :data:`MAX_STEPS` steps (t_end / dt);
- output records estimated to need more than :data:`MAX_RECORD_BYTES` of memory (each
  record holds every sensor column as Python objects until the run ends, then as arrays
  while it is written).

Above :data:`WARN_RECORD_BYTES` :func:`check_run` returns a one-line note to print.

:func:`check_magnitudes` does the same for the model: each valid input alone may still make a
derived quantity (a second moment of area, a stiffness, a mass) overflow or vanish in double
precision (``beam.width = 1e102`` gives h b^3 / 12 = inf), and any number given beyond
1e150 in magnitude (a tip body's mass, a drive's speed, a gain) makes the model's products
overflow; such a scenario is refused naming its keys rather than failing somewhere inside the
model (or, worse, giving a wrong answer).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from hubbeam.io.scenario import ScenarioError

MIN_DT = 1.0e-9  # s
MAX_STEPS = 10**8
MAX_RECORD_BYTES = 4 * 2**30
WARN_RECORD_BYTES = 2**30
#: memory per sensor column and output record while a run is kept and written (B):
#: a Python float in a list or dict (about 65 B measured) and the arrays written from them
BYTES_PER_VALUE = 100
#: memory per number of a recorded state (B): in the snapshots' arrays and in the arrays written from them
BYTES_PER_STATE_VALUE = 16
#: sensor kinds with several parts (columns NAME_PART)
PART_NAMES = {"tip_deflection": ("radial", "vertical", "tangential"),
              "energy": ("kinetic", "strain", "gravity", "total", "dissipated", "drive")}
PARTS = {kind: len(parts) for kind, parts in PART_NAMES.items()}


@dataclass(frozen=True)
class RunSize:
    steps: int
    records: int
    columns: int
    record_bytes: int
    note: str | None = None


def columns(sensors) -> int:
    """Columns of a run's result (time and one per sensor part)."""
    return 1 + sum(PARTS.get(s.kind, 1) for s in sensors)


def _gib(n: float) -> str:
    return f"{n / 2**30:.3g} GiB" if n >= 2**30 else f"{n / 2**20:.3g} MiB"


def run_size(t_end: float, dt: float, output_dt: float | None, n_columns: int, state_values: int = 0) -> RunSize:
    """Steps, records and record memory of a run; ScenarioError when it cannot be done.
    ``state_values``: numbers per record of a recorded state (``--state``), kept as arrays."""
    if not (math.isfinite(dt) and dt > 0 and math.isfinite(t_end) and t_end > 0):
        raise ScenarioError(f"analysis.dt: needs finite positive analysis.dt and analysis.t_end (got {dt!r}, {t_end!r})")
    if dt < MIN_DT:
        raise ScenarioError(f"analysis.dt: {dt:g} s is below the smallest supported time step, {MIN_DT:g} s")
    steps = t_end / dt
    if steps > MAX_STEPS:
        raise ScenarioError(
            f"analysis.dt: analysis.t_end / analysis.dt = {t_end:g} s / {dt:g} s = {steps:.3g} steps, more than the "
            f"{MAX_STEPS:.0e} a run may take; use a larger analysis.dt or a shorter analysis.t_end")
    out = dt if output_dt is None else min(output_dt, t_end)  # longer than the run: the start and the end
    every = max(1, round(out / dt))
    n_steps = max(1, round(steps))
    records = n_steps // every + 2
    need = records * (n_columns * BYTES_PER_VALUE + state_values * BYTES_PER_STATE_VALUE)
    if need > MAX_RECORD_BYTES:
        raise ScenarioError(
            f"analysis.output_dt: {records:.3g} output records of {n_columns} columns would need about {_gib(need)} of "
            f"memory (at most {_gib(MAX_RECORD_BYTES)}); use a larger analysis.output_dt or a shorter analysis.t_end")
    note = None
    if need > WARN_RECORD_BYTES:
        note = (f"{records} output records of {n_columns} columns will need about {_gib(need)} of memory "
                "(a larger analysis.output_dt needs less)")
    return RunSize(n_steps, records, n_columns, need, note)


def state_values(scenario) -> int:
    """Numbers per output record of a recorded state (:mod:`hubbeam.snapshots`): the hub angle
    and, at every station of every beam, its centre line, m, n and strain (10)."""
    from hubbeam.snapshots import POINTS_PER_ELEMENT

    return 1 + sum(10 * (b.elements * POINTS_PER_ELEMENT + 1) for b in scenario.resolved_beams())


def check_run(scenario, state: bool = False) -> RunSize:
    """:func:`run_size` of a scenario's dynamic analysis (``state``: with a recorded state)."""
    a = scenario.analysis
    return run_size(a.t_end, a.dt, a.output_dt, columns(scenario.sensors), state_values(scenario) if state else 0)


#: derived model quantities must lie in this range (positive ones), so that the products the
#: model forms with them (stiffness times curvature squared, mass times length squared) stay finite
MAGNITUDE_RANGE = (1e-150, 1e150)


def check_magnitudes(scenario) -> None:
    """ScenarioError naming the keys when a derived quantity of the model is not a finite
    number within :data:`MAGNITUDE_RANGE` (see the module doc). Every beam is checked; its keys
    are named as written (``beam.width`` for a ``[beam]`` table, ``beams[1].width`` otherwise)."""
    import numpy as np

    h = scenario.hub
    low, high = MAGNITUDE_RANGE
    single = scenario.single_beam is not None
    quantities, values = [], {}
    for i, b in enumerate(scenario.beam_tables):
        k = "beam" if single else f"beams[{i}]"
        radius_key = f"{k}.radius" if b.radius is not None else "hub.radius"
        with np.errstate(all="ignore"):
            w, t, L = np.float64(b.width), np.float64(b.thickness), np.float64(b.length)
            E, rho = np.float64(b.youngs_modulus), np.float64(b.density)
            nu = 0.33 if b.poisson_ratio is None else b.poisson_ratio
            G = np.float64(b.shear_modulus) if b.shear_modulus is not None else E / (2.0 * (1.0 + nu))
            R = np.float64(h.radius if b.radius is None else b.radius)
            a, c = max(w, t), min(w, t)
            J = np.float64(b.torsion_constant) if b.torsion_constant is not None else a * c**3 / 3.0 * (1.0 - 0.63 * c / a)
            area, i_y, i_z = w * t, w * t**3 / 12.0, t * w**3 / 12.0
            quantities += [
                ("the section area", area, "m^2", [f"{k}.width", f"{k}.thickness"]),
                ("the weak-axis second moment of area", i_y, "m^4", [f"{k}.thickness", f"{k}.width"]),
                ("the strong-axis second moment of area", i_z, "m^4", [f"{k}.width", f"{k}.thickness"]),
                ("the torsion constant", J, "m^4", [f"{k}.torsion_constant" if b.torsion_constant is not None
                                                     else f"{k}.thickness", f"{k}.width"]),
                ("the axial stiffness EA", E * area, "N", [f"{k}.youngs_modulus", f"{k}.width", f"{k}.thickness"]),
                ("the bending stiffness EI", E * i_y, "N m^2", [f"{k}.youngs_modulus", f"{k}.thickness"]),
                ("the bending stiffness EI", E * i_z, "N m^2", [f"{k}.youngs_modulus", f"{k}.width"]),
                ("the torsional stiffness GJ", G * J, "N m^2", [f"{k}.youngs_modulus", f"{k}.thickness"]),
                ("the beam's mass", rho * area * L, "kg", [f"{k}.density", f"{k}.length", f"{k}.width"]),
                ("the section's rotary inertia", rho * (i_y + i_z), "kg m", [f"{k}.density", f"{k}.width"]),
                ("the axial stiffness of an element EA / (L / n)", E * area * b.elements / L, "N/m",
                 [f"{k}.length", f"{k}.youngs_modulus"]),
                ("the bending stiffness of an element EI / (L / n)^3", E * i_z * (b.elements / L) ** 3, "N/m",
                 [f"{k}.length", f"{k}.youngs_modulus"]),
                ("the beam's moment of inertia about the hub", rho * area * L * (L + R) ** 2, "kg m^2",
                 [f"{k}.length", radius_key, f"{k}.density"]),
            ]
        values.update({f"{k}.{name}": getattr(b, name) for name in ("width", "thickness", "length", "youngs_modulus",
                                                                     "density", "torsion_constant", "radius")})
    values["hub.radius"], values["hub.inertia"] = h.radius, h.inertia
    if h.motion == "free":
        quantities.append(("the hub's inertia", np.float64(h.inertia), "kg m^2", ["hub.inertia"]))
    for what, value, unit, keys in quantities:
        if not (np.isfinite(value) and low < value < high):
            given = ", ".join(f"{key} = {values[key]:g}" for key in keys if _number(values.get(key)))
            raise ScenarioError(f"{keys[0]}: with {given}, {what} is {float(value):.3g} {unit}, outside the range "
                                f"hubbeam computes with ({low:g} to {high:g}); check the values and their units (SI)")
    # then every number of the model as given (a tip body's mass, a drive's speed, a gain, a damping
    # constant ...): beyond the range, the products the model forms with it overflow somewhere
    # inside (the analysis' times have their own limits: :func:`run_size`)
    for key, value in _numbers(scenario.model_dump(exclude_none=True, by_alias=True, exclude={"analysis"})):
        if not abs(value) < high:
            raise ScenarioError(f"{key}: {value:g} is outside the range hubbeam computes with (magnitudes up to "
                                f"{high:g}); check the value and its unit (SI)")


def _numbers(tree, key: str = ""):
    """(key as written in a scenario file, number) for every number in a scenario's dump."""
    if isinstance(tree, dict):
        for name, sub in tree.items():
            yield from _numbers(sub, f"{key}.{name}" if key else name)
    elif isinstance(tree, (list, tuple)):
        if tree and all(_number(v) for v in tree):  # a vector: one key
            for v in tree:
                yield key, float(v)
        else:
            for i, sub in enumerate(tree):
                yield from _numbers(sub, f"{key}[{i}]")
    elif _number(tree):
        yield key, float(tree)


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)
