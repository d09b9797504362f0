"""What the benchmarks that time one call at a time share (step_cost.py, residual_pieces.py,
bus_cost.py): the point they evaluate at, the best-of timer, and compiled loops over one kind's
terms.

The evaluation point is a system's initial state with every rate raised by 0.1 (and the
accelerations by ``acceleration``), so that velocity-dependent terms (drag, damping, the
gyroscopic terms) do their work.
"""
from __future__ import annotations

import time
from types import SimpleNamespace

import numpy as np
from numba import njit

from hubbeam import api
from hubbeam.simulation import initial_state
from hubbeam.system.assembly import BorderedBandMatrix
from hubbeam.system.terms import part_drive_power, part_equations, part_power


def evaluation_point(scenario, acceleration: float = 0.0) -> SimpleNamespace:
    """The built system of ``scenario``, its compiled model, its residual and Newton-matrix
    storage, and the state (x, v, a, lam) and charts F to evaluate its terms at."""
    system = api.build_system(scenario)
    state = initial_state(system)
    model = system.model()
    layout = system.layout
    return SimpleNamespace(
        system=system, model=model, layout=layout, ctx=model.context, res=np.empty(layout.nz),
        mat=BorderedBandMatrix.empty(layout.nz, layout.border, model.bandwidth), x=state.x, v=state.v + 0.1,
        a=state.xdd + acceleration, lam=state.lam, F=np.ascontiguousarray(state.chart))


def best(f, n: int, repeats: int = 5) -> float:
    """The least process time per call (us) of ``f(n)`` (n calls) over ``repeats`` runs, after
    one warm-up call f(1)."""
    f(1)
    least = 1e9
    for _ in range(repeats):
        t = time.process_time()
        f(n)
        least = min(least, (time.process_time() - t) / n * 1e6)
    return least


@njit(_nrt=False)  # as the system's functions: the kinds' terms count no references
def part_loop(n, pack, ctx, F, x, v, a, lam, res, ab, brow, bcol, bb):
    """n evaluations of one kind's residual rows (no Newton matrix), t = 0.1 s + 1e-9 i."""
    s = 0.0
    for i in range(n):
        m, p = part_equations(pack, ctx, F, x, v, a, lam, 0.1 + 1e-9 * i, 1.0, 0.5, 0.3e-6, 1.0, 1.0, False, False,
                              res, ab, brow, bcol, bb)
        s += m
    return s


@njit(_nrt=False)
def part_powers_loop(n, pack, ctx, F, x, v, lam):
    """n evaluations of one kind's dissipated and drive power, t = 0.1 s + 1e-9 i."""
    s = 0.0
    for i in range(n):
        s += part_power(pack, ctx, F, x, v) + part_drive_power(pack, ctx, F, 0.1 + 1e-9 * i, x, v, lam)
    return s
