"""Where case M's free bus costs more than its free hub: per call, process time, best of 5
(numba's cache warm), the same panels (two FFR panels on 4 modes, 8 elements) slewed alike
(benchmarks/engines.py's case_m_text), the bus's and the hub's model in turn:

    python benchmarks/bus_cost.py

residual / matrix: one evaluation of the system's equations without / with the Newton matrix;
powers: the step's powers; motion / chains1 / hessians: every frame's kinematics as the
equations evaluate them (evaluate_motion: velocity products where read, Hessians only where
read) / to order 1 (the powers') / with every marked frame's Hessians (evaluate_chains order
2, the controllers'); eq / pow KIND: one kind's terms alone (its residual rows; its
dissipated and drive power). Prints the frames' count, orders and widths of each model.
"""
import os, sys, tempfile
from numba import njit
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from engines import case_m_text
from probes import best, evaluation_point, part_loop, part_powers_loop
from hubbeam.io.scenario import load_scenario
from hubbeam.system.equations import system_equations, step_powers
from hubbeam.system.frames import evaluate_chains, evaluate_motion

@njit(_nrt=False)  # as the system's functions: the kinds' terms count no references
def loop_eq(n, want, model, F, x, v, a, lam, res, ab, brow, bcol, bb):
    s = 0.0
    for i in range(n):
        m, p = system_equations(model, F, x, v, a, lam, 0.1 + 1e-9 * i, 1.0, 0.5, 0.3e-6, 1.0, 1.0, False, want, res, ab, brow, bcol, bb)
        s += p
    return s

@njit(_nrt=False)
def loop_pow(n, model, F, x, v, lam):
    s = 0.0
    for i in range(n):
        p, q = step_powers(model, F, 0.1 + 1e-9 * i, x, v, lam)
        s += p + q
    return s

@njit(_nrt=False)
def loop_chains(n, table, x, F, order):
    for i in range(n):
        evaluate_chains(table, x, F, order)

@njit(_nrt=False)
def loop_motion(n, table, x, v, F):
    for i in range(n):
        evaluate_motion(table, x, v, F, n < 0)

def scenario_of(free_base):
    text = case_m_text(free_base, slew=True)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "m.toml")
        open(path, "w").write(text)
        return load_scenario(path, ['beams[*].formulation="ffr"', 'beams[*].modes=4', 'analysis.dt=0.001'])

for free_base in (True, False):
    point = evaluation_point(scenario_of(free_base), acceleration=0.05)
    model, lay, ctx, res, mat = point.model, point.layout, point.ctx, point.res, point.mat
    x, v, a, lam, F = point.x, point.v, point.a, point.lam, point.F
    tab = ctx.chains
    out = {}
    out["residual"] = best(lambda n: loop_eq(n, False, model, F, x, v, a, lam, res, mat.ab, mat.brow, mat.bcol, mat.bb), 50000)
    out["matrix"] = best(lambda n: loop_eq(n, True, model, F, x, v, a, lam, res, mat.ab, mat.brow, mat.bcol, mat.bb), 10000)
    out["powers"] = best(lambda n: loop_pow(n, model, F, x, v, lam), 50000)
    out["motion"] = best(lambda n: loop_motion(n, tab, x, v, F), 50000)
    out["chains1"] = best(lambda n: loop_chains(n, tab, x, F, 1), 50000)
    out["hessians"] = best(lambda n: loop_chains(n, tab, x, F, 2), 50000)
    for pack in model.parts:
        nm = type(pack).__name__
        out["eq " + nm] = best(lambda n: part_loop(n, pack, ctx, F, x, v, a, lam, res, mat.ab, mat.brow, mat.bcol, mat.bb), 50000)
        out["pow " + nm] = best(lambda n: part_powers_loop(n, pack, ctx, F, x, v, lam), 50000)
    print(("BUS" if free_base else "HUB"), f"nz {lay.nz} border {lay.border} bw {model.bandwidth} chains {tab.orders.shape[0]} orders {list(tab.orders)} widths {[tab.width(k) for k in range(tab.orders.shape[0])]}")
    print("   " + ", ".join(f"{k} {v:.2f}" for k, v in out.items()))
