"""The system's compiled equations, energies and powers agree with each other at a state: the
power balance dE/dt = drive power - dissipated power, an identity of the continuous equations
of motion that no time step enters (:mod:`hubbeam.system.equations`)."""

import numpy as np
import pytest

from hubbeam import api
from hubbeam.io.scenario import load_example
from hubbeam.simulation import CompiledSteps, initial_state
from hubbeam.system.chains import HESSIANS, POSE, PRODUCTS
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers import newton_control as nc

SPIN_UP = ['hub.motion="prescribed"', 'hub.drive.profile="spin_up"', "hub.drive.omega_s=2.0", "hub.drive.T=1.0"]
CASES = {
    # drag of Eq. 37, gravity, the drive's reaction doing the work
    "exp1 ANCF spun up": ("exp1", ["beam.elements=4"] + SPIN_UP),
    "exp1 nodal FFR spun up": ("exp1", ["beam.elements=4", 'beam.formulation="ffr"'] + SPIN_UP),
    "exp1 FFR on 4 modes spun up": ("exp1", ["beam.elements=4", 'beam.formulation="ffr"', "beam.modes=4"] + SPIN_UP),
    # a free hub under a PD law (a 2 s slew): two panels with tip bodies
    "spacecraft": ("spacecraft", ["hub.torque.reference.T=2.0"]),
    # tapered, pretwisted, structural damping, tip mass, gravity, driven
    "blade": ("blade", ["beam.elements=4"]),
}


def energy(system, x, v, F) -> float:
    e = system.energies(x, v, F)
    return e["kinetic"] + e["strain"] + e["gravity"]


@pytest.mark.parametrize("case", list(CASES))
def test_the_energy_changes_at_the_rate_of_the_drive_minus_the_dissipated_power(case):
    """At a moving state of a run (t = 0.4 s; random rates added where no constraint holds,
    then projected onto the velocity constraints), the accelerations and multipliers that make
    the residual zero (the equations as the time steps solve them: inertia, elastic, gravity,
    damping and drag forces, constraint reactions, Phi_x xdd = -Phi_tt - (d/dt Phi_x) v) give
    dE/dt, the central difference of the energies (kinetic, strain, gravity) along (v, xdd);
    it equals the drive power (applied torque minus the drive's reaction, times theta') minus
    the power of the drag and the structural damping. The energies, the equations and the
    powers are three pieces of code; an error in any one breaks the identity (Coriolis forces
    among the elastic coordinates alone do no work: the kernel tests hold those)."""
    name, overrides = CASES[case]
    system = api.build_system(load_example(name, overrides))
    start = initial_state(system)
    dt = 1e-3
    steps = CompiledSteps(system, ga.AlphaParameters.from_spectral_radius(0.8), nc.NewtonOptions(), dt, start)
    state = steps.advance(start, 400, 0, 400, 400)[0]
    t, x, v, F = state.t, state.x, state.v.copy(), state.chart
    # rates in every direction (the run's own are mostly bending and rotation about the hub
    # axis) on the coordinates that no constraint holds; then the rates projected onto the
    # constraints' velocity equations Phi_x v + Phi_t = 0 (a run meets them to O(h^2))
    G = system.constraint_jacobian(x, F)
    free = np.all(G == 0.0, axis=0)
    v[free] += 0.05 * np.random.default_rng(7).normal(size=int(free.sum()))
    violation = G @ v
    if system.motion == "prescribed":
        violation[system.layout.drive_lambda] -= system.drive(t)[1]  # Phi_t of theta - theta_p(t)
    v -= np.linalg.lstsq(G, violation, rcond=None)[0]
    at = ga.init(system, x, F, t, v0=v)  # accelerations and multipliers of the DAE at (x, v) ...
    xdd, lam = at.xdd.copy(), at.lam.copy()
    s, layout = system.mass_scale, system.layout
    mass = system.dynamic_equations(x, v, 0 * x, 0 * lam, F, t, 1.0, 0.0, 0.0, s)[1].to_dense()
    for _ in range(3):  # ... made roots of the residual itself (init takes the inertia from the matrix)
        dx, dmu = layout.split_z(np.linalg.solve(mass, -system.dynamic_residual(x, v, xdd, lam, F, t, 1.0, s)))
        xdd += dx
        lam += s * dmu
    along = lambda e: energy(system, x + e * v, v + e * xdd, F)  # noqa: E731  (E along the motion)
    eps = 1e-5  # fourth-order central difference: the stiff axial directions make E''' large
    rate = (8 * (along(eps) - along(-eps)) - (along(2 * eps) - along(-2 * eps))) / (12 * eps)
    dissipated, drive = system.step_powers(t, x, v, lam, F)
    scale = abs(drive) + dissipated + np.sqrt(np.mean(v ** 2))
    assert abs(drive) + dissipated > 1e-3  # something does work here
    assert abs(rate - (drive - dissipated)) < 2e-7 * scale  # measured: 3.6e-8 (spacecraft: round-off), others 6e-11


@pytest.mark.slow  # each case is the only test of its model: compiling it is most of a minute
@pytest.mark.parametrize("example, overrides", [
    # a free base (rigid body), an ANCF panel (clamp) and an FFR panel on modes, with tip bodies
    ("spacecraft3d", ['beams[1].formulation="ffr"', "beams[1].modes=3", "base.initial.angular_velocity=[0.1, 0.3, 0.2]"]),
    # beams on lag hinges, children on their parents' tips; the second an FFR beam
    ("articulated", ['beams[1].formulation="ffr"']),
])
def test_the_equations_read_no_hessian_that_evaluate_chains_leaves_out(example, overrides):
    """:func:`hubbeam.system.frames.evaluate_motion` takes a chain's Hessians only where the
    system marks it (the ANCF roots, the controllers' inputs) and its velocity products only
    where it marks those (the FFR roots, the rigid bodies'); every other chain's hess and
    products keep what an earlier evaluation left there. At a moving state, with every chain's
    hess and products first filled with garbage, the residual and the Newton matrix are those of
    the same equations with every chain's Hessians evaluated (its velocity products contracted
    from them: round-off apart): a part that read an unmarked chain's Hessians or products would
    read the garbage."""
    from hubbeam.system.assembly import BorderedBandMatrix
    from hubbeam.system.equations import system_equations

    system = api.build_system(load_example(example, overrides))
    state = initial_state(system)
    rng = np.random.default_rng(3)
    x, F = state.x + 1e-3 * rng.standard_normal(state.x.size), np.ascontiguousarray(state.chart)
    v, acc = rng.standard_normal(x.size), rng.standard_normal(x.size)
    lam = rng.standard_normal(state.lam.size)
    model = system.model()
    table = model.context.chains
    assert POSE in table.orders and PRODUCTS in table.orders  # chains left out and chains of products alone
    every = model._replace(context=model.context._replace(chains=table._replace(
        orders=np.full_like(table.orders, HESSIANS), hess=table.hess.copy(), products=table.products.copy())))
    layout = system.layout
    out = []
    for m in (model, every):
        m.context.chains.hess[...] = 1e300  # garbage where no evaluation writes
        m.context.chains.products[...] = 1e300
        res = np.empty(layout.nz)
        mat = BorderedBandMatrix.empty(layout.nz, layout.border, m.bandwidth)
        system_equations(m, F, x, v, acc, lam, 0.1, 1.0, 0.5, 0.3e-6, 1.0, 1.0, False, True, res, mat.ab, mat.brow,
                         mat.bcol, mat.bb)
        out.append((res, mat.to_dense()))
    assert np.all(np.isfinite(out[0][0])) and np.all(np.isfinite(out[0][1]))
    np.testing.assert_allclose(out[0][0], out[1][0], rtol=0, atol=1e-12 * np.max(np.abs(out[1][0])))
    np.testing.assert_allclose(out[0][1], out[1][1], rtol=0, atol=1e-12 * np.max(np.abs(out[1][1])))


LEAK_CHECK = """
import gc, json, sys
from numba.core.runtime import rtsys
from hubbeam import api
from hubbeam.io.scenario import load_example
example, overrides = sys.argv[1], json.loads(sys.argv[2])
def run(t_end):
    traj, failure = api.run(load_example(example, overrides + [f"analysis.t_end={t_end}"]))
    assert failure is None, failure
run(0.002)  # loads the compiled code
def unreleased(t_end):
    gc.collect()
    before = rtsys.get_allocation_stats()
    run(t_end)
    gc.collect()
    after = rtsys.get_allocation_stats()
    return (after.alloc - before.alloc) - (after.free - before.free), after.alloc - before.alloc
print(json.dumps([unreleased(0.02), unreleased(0.08)]))
"""


@pytest.mark.parametrize("example, overrides", [
    ("exp1", ['beam.formulation="ffr"', "beam.modes=4", "beam.elements=4"]),  # terms compiled into the step
    ("blade", ["beam.elements=4"]),  # ANCF, tip body, damping: terms called as functions of their own
    # the base's laws compiled into the step: a free base's norm and attitude law (a slew) ...
    ("spacecraft3d", ['beams[*].formulation="ffr"', "beams[*].modes=4", "beams[*].elements=4", "analysis.dt=0.001"]),
    # ... and a table base's drive
    ("platform", ['beams[*].formulation="ffr"', "beams[*].modes=2", "beams[*].elements=4"]),
])
def test_a_run_releases_every_array_it_allocates(example, overrides):
    """The time step's system functions count no references (system_equations, step_powers:
    numba's _nrt=False): an array that a term takes from a call or allocates there would never
    be released. With numba's allocation statistics (NUMBA_NRT_STATS, in a fresh process), a
    run of 20 and one of 80 steps release every array they allocate, and the longer run
    allocates more (the statistics count)."""
    import json
    import os
    import subprocess
    import sys

    env = dict(os.environ, NUMBA_NRT_STATS="1")
    out = subprocess.run([sys.executable, "-c", LEAK_CHECK, example, json.dumps(overrides)], capture_output=True,
                         text=True, env=env, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    (short_left, short_made), (long_left, long_made) = json.loads(out.stdout.strip().splitlines()[-1])
    assert long_made > short_made > 0
    assert short_left == 0 and long_left == 0
