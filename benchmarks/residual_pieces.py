"""Where an FFR system's residual goes, piece by piece (issue 26): process time per call, best
of 5, numba's cache warm, at the initial state with every rate raised by 0.1 (as step_cost.py).

    python benchmarks/residual_pieces.py R|exp1_modal|exp1_nodal

Prints the frames' kinematics (``evaluate_chains``) to order 2 and 1; each part kind's residual
rows (``part_equations``, no Newton matrix) and powers; for the FFR beam its kernel
(``ffr_vspace_terms``), its v-space rates, the II contractions (``_moments``), the elastic force,
the mass matrix and the building of its argument tuples; the FFR beam's terms with and without
the scatter into the residual; and the whole ``system_equations``. Pieces timed alone run
warmer than inside a step: their sum is less than the whole.
"""
import os, sys
from numba import njit
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from probes import best, evaluation_point, part_loop, part_powers_loop
from hubbeam.io.scenario import load_example, load_scenario
from hubbeam.system.equations import system_equations
from hubbeam.system.frames import evaluate_chains, chain_state
from hubbeam.system import ffr_beams as fb
from hubbeam.elements.ffr import kernels as kn

@njit(_nrt=False)
def t_chains(n, ctx, x, F, order):
    for i in range(n):
        evaluate_chains(ctx.chains, x, F, order)
    return 0.0

@njit(_nrt=False)
def t_vspace(n, pack, ctx, x, v, a):
    k = 0
    nf = pack.places[k, 2]; x0 = pack.places[k, 1]
    force, H, Mv, Cv, K_el = fb._beam_scratch(pack, ctx, k, False)
    frame = chain_state(ctx.chains, pack.chains[k, 0])
    cols, r, R, Jr, Jw, Hr, Hw = frame
    p = x[x0:x0 + nf]
    vecs = pack.vectors_work
    n6 = 6 + nf
    vb, vdot, fv = vecs[0, :n6], vecs[1, :n6], vecs[2, :n6]
    fb._vspace_rates(R, Jr, Jw, Hr, Hw, cols, v, a, x0, nf, vecs[3:7, :3], vb, vdot)
    s = 0.0
    for i in range(n):
        inv, tip, drag = fb.ffr_arguments(pack, k, ctx.drag)
        s += kn.ffr_vspace_terms(inv, R, p, vb, vdot, ctx.gravity, tip, drag, 1.0, False, fv, Mv, Cv, K_el, fb._kernel_work(pack), True)
    return s

@njit(_nrt=False)
def t_rates(n, pack, ctx, x, v, a):
    k = 0
    nf = pack.places[k, 2]; x0 = pack.places[k, 1]
    frame = chain_state(ctx.chains, pack.chains[k, 0])
    cols, r, R, Jr, Jw, Hr, Hw = frame
    vecs = pack.vectors_work
    n6 = 6 + nf
    vb, vdot = vecs[0, :n6], vecs[1, :n6]
    for i in range(n):
        fb._vspace_rates(R, Jr, Jw, Hr, Hw, cols, v, a, x0, nf, vecs[3:7, :3], vb, vdot)
    return vb[0]

@njit(_nrt=False)
def t_moments(n, pack, x, v):
    k = 0
    nf = pack.places[k, 2]; x0 = pack.places[k, 1]
    p = x[x0:x0 + nf]; pd = v[x0:x0+nf]
    vectors, Q2s, squares, ints = fb._kernel_work(pack)
    St, R2 = vectors[2], vectors[6]
    for i in range(n):
        inv, tip, drag = fb.ffr_arguments(pack, k, (0.0, 0.0))
        kn._moments(inv[1], inv[2], inv[3], inv[4], inv[5], p, pd, True, nf, St, Q2s[0], Q2s[1], R2)
    return R2[0]

@njit(_nrt=False)
def t_elastic(n, pack, x):
    k = 0
    nf = pack.places[k, 2]; x0 = pack.places[k, 1]
    p = x[x0:x0 + nf]
    vectors, Q2s, squares, ints = fb._kernel_work(pack)
    for i in range(n):
        inv, tip, drag = fb.ffr_arguments(pack, k, (0.0, 0.0))
        kn._elastic(inv[7], inv[8], inv[9], inv[10], inv[11], p, nf, False, vectors[1], squares[0], vectors[4], ints[0, :nf])
    return vectors[1][0]

@njit(_nrt=False)
def t_mass(n, pack, ctx, x):
    k = 0
    nf = pack.places[k, 2]
    force, H, Mv, Cv, K_el = fb._beam_scratch(pack, ctx, k, False)
    cols, r, R, Jr, Jw, Hr, Hw = chain_state(ctx.chains, pack.chains[k, 0])
    vectors, Q2s, squares, ints = fb._kernel_work(pack)
    for i in range(n):
        inv, tip, drag = fb.ffr_arguments(pack, k, (0.0, 0.0))
        kn._mass_matrix(inv[0], inv[2], inv[4], inv[6], nf, R, vectors[2], Q2s[0], vectors[6], Mv)
    return Mv[0, 0]

@njit(_nrt=False)
def t_args(n, pack, ctx):
    s = 0.0
    for i in range(n):
        inv, tip, drag = fb.ffr_arguments(pack, 0, ctx.drag)
        s += inv[0] + tip[4]
    return s

case = sys.argv[1]
if case == "exp1_modal":
    sc = load_example("exp1", ['beam.formulation="ffr"', 'beam.modes=4'])
elif case == "exp1_nodal":
    sc = load_example("exp1", ['beam.formulation="ffr"'])
else:
    sc = load_scenario(os.path.join(os.path.dirname(os.path.abspath(__file__)), "case_a.toml"),
                       ['beam.formulation="ffr"', 'beam.modes=4', 'beam.elements=8', 'analysis.dt=0.001'])
point = evaluation_point(sc)
model, lay, ctx, res, mat = point.model, point.layout, point.ctx, point.res, point.mat
x, v, a, lam, F = point.x, point.v, point.a, point.lam, point.F
N = 50000
print(case, "nz", lay.nz, "nx", len(x), [type(q).__name__ for q in model.parts], "chains", ctx.chains.orders)
print(f"chains order2 {best(lambda n: t_chains(n, ctx, x, F, 2), N):.3f}  order1 {best(lambda n: t_chains(n, ctx, x, F, 1), N):.3f}")
evaluate_chains(ctx.chains, x, F, 2)
for pk in model.parts:
    print(f"  part {type(pk).__name__}: eq {best(lambda n: part_loop(n, pk, ctx, F, x, v, a, lam, res, mat.ab, mat.brow, mat.bcol, mat.bb), N):.3f}  powers {best(lambda n: part_powers_loop(n, pk, ctx, F, x, v, lam), N):.3f}")
    if isinstance(pk, fb.FfrBeams):
        print(f"    vspace_terms {best(lambda n: t_vspace(n, pk, ctx, x, v, a), N):.3f} rates {best(lambda n: t_rates(n, pk, ctx, x, v, a), N):.3f} moments {best(lambda n: t_moments(n, pk, x, v), N):.3f} elastic {best(lambda n: t_elastic(n, pk, x), N):.3f} mass {best(lambda n: t_mass(n, pk, ctx, x), N):.3f} args {best(lambda n: t_args(n, pk, ctx), N):.3f}")

@njit(_nrt=False)
def t_beamterms(n, pack, ctx, x, v, a):
    k = 0
    force, H, Mv, Cv, K_el = fb._beam_scratch(pack, ctx, k, False)
    frame = chain_state(ctx.chains, pack.chains[k, 0])
    s = 0.0
    for i in range(n):
        s += fb.ffr_beam_terms(pack, ctx, frame, k, x, v, a, 1.0, False, force, H, Mv, Cv, K_el)
    return s

@njit(_nrt=False)
def t_beamres(n, pack, ctx, x, v, a, res):
    s = 0.0
    for i in range(n):
        s += fb._beam_residual(pack, ctx, 0, x, v, a, 1.0, False, 0.3e-6, res)
    return s

@njit(_nrt=False)
def t_sys(n, model, F, x, v, a, lam, res, ab, brow, bcol, bb):
    s = 0.0
    for i in range(n):
        m, p = system_equations(model, F, x, v, a, lam, 0.1, 1.0, 0.5, 0.3e-6, 1.0, 1.0, False, False, res, ab, brow, bcol, bb)
        s += p
    return s

for pk in model.parts:
    if isinstance(pk, fb.FfrBeams):
        print(f"    beam_terms {best(lambda n: t_beamterms(n, pk, ctx, x, v, a), N):.3f} beam_residual {best(lambda n: t_beamres(n, pk, ctx, x, v, a, res), N):.3f}")
print(f"system_equations {best(lambda n: t_sys(n, model, F, x, v, a, lam, res, mat.ab, mat.brow, mat.bcol, mat.bb), N):.3f}")
