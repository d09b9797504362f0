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


def run_size(t_end: float, dt: float, output_dt: float | None, n_columns: int) -> RunSize:
    """Steps, records and record memory of a run; ScenarioError when it cannot be done."""
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
    need = records * n_columns * BYTES_PER_VALUE
    if need > MAX_RECORD_BYTES:
        raise ScenarioError(
            f"analysis.output_dt: {records:.3g} output records of {n_columns} columns would need about {_gib(need)} of "
            f"memory (at most {_gib(MAX_RECORD_BYTES)}); use a larger analysis.output_dt or a shorter analysis.t_end")
    note = None
    if need > WARN_RECORD_BYTES:
        note = (f"{records} output records of {n_columns} columns will need about {_gib(need)} of memory "
                "(a larger analysis.output_dt needs less)")
    return RunSize(n_steps, records, n_columns, need, note)


def check_run(scenario) -> RunSize:
    """:func:`run_size` of a scenario's dynamic analysis."""
    a = scenario.analysis
    return run_size(a.t_end, a.dt, a.output_dt, columns(scenario.sensors))
