"""Where a compiled step's time goes: one evaluation of the system's equations without and with
the Newton matrix, and the step's powers (process time per call, best of 3; numba's cache warm).

    python benchmarks/step_cost.py exp1_nodal|exp1_modal|exp1_ancf|casem_modal|spacecraft3d_modal|R

exp1_nodal: experiment 1 with the nodal FFR beam; exp1_modal: experiment 1 on 4 modes;
exp1_ancf: experiment 1 with ANCF; casem_modal: case M's free bus with two FFR panels on 4
modes (benchmarks/case_s.toml); spacecraft3d_modal: the bundled spacecraft3d (the free bus
under its PD attitude law's slew) with the panels on 4 modes, 8 elements, at 1 ms; R: case R (case A's plate on 4 modes on the fixed hub,
benchmarks/case_a.toml, as ``loop_cost.py``). A step
costs one residual
for the predictor, one per Newton iteration, the step's powers and the band solves.
"""
import os
import sys

from numba import njit

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from probes import best, evaluation_point  # noqa: E402

from hubbeam.io.scenario import load_example, load_scenario
from hubbeam.system.equations import system_equations, step_powers

@njit
def loop_eq(n, want, model, F, x, v, a, lam, res, ab, brow, bcol, bb):
    s = 0.0
    for i in range(n):
        m, p = system_equations(model, F, x, v, a, lam, 0.1, 1.0, 0.5, 0.3e-6, 1.0, 1.0, False, want, res, ab, brow, bcol, bb)
        s += p
    return s

@njit
def loop_pow(n, model, F, x, v, lam):
    s = 0.0
    for i in range(n):
        p, q = step_powers(model, F, 0.1, x, v, lam)
        s += p
    return s

case = sys.argv[1]
if case == "exp1_nodal":
    sc = load_example("exp1", ['beam.formulation="ffr"'])
elif case == "exp1_modal":
    sc = load_example("exp1", ['beam.formulation="ffr"', 'beam.modes=4'])
elif case == "exp1_ancf":
    sc = load_example("exp1", [])
elif case == "spacecraft3d_modal":
    sc = load_example("spacecraft3d", ['beams[*].formulation="ffr"', 'beams[*].modes=4', 'beams[*].elements=8',
                                       'analysis.dt=0.001'])
elif case == "R":
    sc = load_scenario(os.path.join(os.path.dirname(os.path.abspath(__file__)), "case_a.toml"),
                       ['beam.formulation="ffr"', 'beam.modes=4', 'beam.elements=8', 'analysis.dt=0.001'])
else:
    sc = load_scenario(os.path.join(os.path.dirname(os.path.abspath(__file__)), "case_s.toml"), ['beams[*].formulation="ffr"', 'beams[*].modes=4', 'analysis.dt=0.001'])
point = evaluation_point(sc)
model, lay, res, mat = point.model, point.layout, point.res, point.mat
x, v, a, lam, F = point.x, point.v, point.a, point.lam, point.F
r = best(lambda n: loop_eq(n, False, model, F, x, v, a, lam, res, mat.ab, mat.brow, mat.bcol, mat.bb), 50000, 3)
m = best(lambda n: loop_eq(n, True, model, F, x, v, a, lam, res, mat.ab, mat.brow, mat.bcol, mat.bb), 10000, 3)
p = best(lambda n: loop_pow(n, model, F, x, v, lam), 50000, 3)
print(f"{case}: nz {lay.nz}, parts {[type(q).__name__ for q in model.parts]}: residual {r:.2f} us, with matrix {m:.2f} us, step powers {p:.2f} us")
