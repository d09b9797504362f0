"""Compiled equations of motion of a system (paper Eq. 77), residual and Newton matrix in one
call, for any number of ANCF and FFR beams, tip bodies, rigid bodies and coordinate laws.

The unknowns are placed by :class:`hubbeam.system.layout.Layout`: z = [the frames'
coordinates and constraints, (joint angles, clamp multipliers, q_k) for each beam]; lambda =
scale mu / coef_k. The Newton matrix is stored bordered
(:class:`hubbeam.system.assembly.BorderedBandMatrix`): the border (the frames' coordinates
and constraints) as dense rows, columns and corner, the rest -- block-diagonal over the
beams, each block banded -- in LAPACK band storage.

This module only adds up: every kind of part (ANCF beams, FFR beams, tip bodies, the hub's
rotor and the base as rigid bodies, the hub's law, ...) registers its pack and compiled
terms in :mod:`hubbeam.system.terms`, and :class:`SystemModel` holds the packs of the kinds
present in a system, which every function here iterates over (``numba.literal_unroll``): a
kind absent from a system is not compiled for it.
"""

from __future__ import annotations

import types
from functools import cache
from typing import NamedTuple

import numpy as np
from numba import literal_unroll, njit

from hubbeam.elements.ancf import coordinates
from hubbeam.elements.ancf.strain import strain_measures
from hubbeam.system.by_reference import address_of, held_at
from hubbeam.system.frames import evaluate_chains, evaluate_motion
from hubbeam.system.terms import (CHART_SINGULAR, Context, part_drive_power, part_energies, part_equations,
                                  part_events, part_momenta, part_power, part_tips)


class SystemModel(NamedTuple):
    """Everything constant that the compiled equations need (SI units): ``parts``, the packs of
    the kinds present (:func:`hubbeam.system.terms.packs`), and the ``context`` they all see
    (the layout's places of the unknowns, the frames, the environment)."""

    parts: tuple  # the packs of the kinds of part present
    context: Context  # what the parts' terms see (:func:`context`)
    bandwidth: int
    events: bool = False  # a part's kind has events (:func:`system_events`): the time loop looks for them
    powers: bool = True  # a part can have a dissipated or drive power (:func:`hubbeam.system.terms.with_powers`):
    #                      else :func:`step_powers` is (0, 0) at every state and the time loop does not call it


def context(layout, bandwidth: int, gravity, drag, chains) -> Context:
    """The :class:`~hubbeam.system.terms.Context` of a system placed by ``layout`` with the frames ``chains``."""
    g0, g1, g2 = (float(g) for g in gravity)
    c1, c2 = (float(c) for c in drag)
    return Context(layout.border, layout.z_of_x, layout.z_of_lambda, 2 * bandwidth, layout.theta, (g0, g1, g2),
                   (c1, c2), chains)


@njit(cache=True, _nrt=False)
def system_equations(model, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                     want_matrix, res, ab, brow, bcol, bb):
    """:func:`equations_at` for the model itself (the calls from Python)."""
    return equations_at(address_of(model), F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor,
                        exact_stiffness, want_matrix, res, ab, brow, bcol, bb)


@njit(cache=True, _nrt=False)
def equations_at(model_at, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                 want_matrix, res, ab, brow, bcol, bb):
    """Scaled residual and (when ``want_matrix``) Newton matrix of the system.

    Force rows: coef_k (M(x) acc + f_int - Q_ext - Q_v - Q_d + Phi_x^T lambda) on every
    coordinate; constraint rows: scale Phi(x, t). ``load_factor`` scales the applied loads
    (gravity, tip loads, applied torques) for load stepping; ``exact_stiffness`` asks the
    parts for the stiffness of every load (statics and modes). The matrix coef_m M + coef_c C
    + coef_k (K - dQ/dx + lambda . d2 Phi), with the constraint Jacobian scaled by ``scale``
    in its rows and columns, is written into the bordered storage (``bb`` border x border,
    ``brow`` border rows, ``bcol`` border columns, ``ab`` the band of the rest in gbtrf layout
    with kl = ku = model.bandwidth). ``F`` holds every beam's chart. The parts' terms:
    :mod:`hubbeam.system.terms`.

    Every frame's kinematics are evaluated first, once (:func:`~hubbeam.system.frames.evaluate_motion`),
    and the parts read them. Returns (chart margin min(1 + d.tau) over all Gauss points,
    dissipated power W). A margin at or below :data:`CHART_SINGULAR` means the residual is not
    valid.

    Compiled without numba's reference counting, as :func:`step_powers` and
    :func:`system_events` (the functions the time loop calls every step): they allocate
    nothing, and the kinds whose terms do are called as functions of their own
    (:func:`hubbeam.system.terms.register`'s ``counts_references``). Counting the references
    of the model's arrays (43 on exp1 with 4 modes) and of the packs each term is given cost
    0.7 us of the 1.6 us of a call of the step's powers there. The model comes by reference,
    ``model_at`` = :func:`~hubbeam.system.by_reference.address_of` (model), as the time loop
    passes it: by value it cost 550 words copied per call on exp1
    (:mod:`hubbeam.system.by_reference`).
    """
    model = held_at(model_at)
    ctx = model.context
    evaluate_motion(ctx.chains, x, v, F, exact_stiffness)
    for i in range(res.shape[0]):
        res[i] = 0.0
    if want_matrix:
        ab[:, :] = 0.0
        brow[:, :] = 0.0
        bcol[:, :] = 0.0
        bb[:, :] = 0.0
    margin = 2.0
    power = 0.0
    for pack in literal_unroll(model.parts):
        part_margin, part_power_ = part_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale,
                                                  load_factor, exact_stiffness, want_matrix, res, ab, brow, bcol, bb)
        margin = min(margin, part_margin)
        if not margin > CHART_SINGULAR:
            return margin, 0.0
        power += part_power_
    return margin, power


@njit(cache=True, _nrt=False)
def step_powers(model, F, t, x, v, lam):
    """:func:`powers_at` for the model itself (the calls from Python)."""
    return powers_at(address_of(model), F, t, x, v, lam)


@njit(cache=True, _nrt=False)
def powers_at(model_at, F, t, x, v, lam):
    """(dissipated, drive) power at the state (t, x, v, lambda) in the charts F (W): the power
    of the drag of Eq. 37 and of the structural damping of every part (>= 0), and the power of
    the applied torques and the prescribed motions (the hub's drive reaction and torque law,
    ...). One function for both, called after every step. Not inlined into the compiled
    loop (the model comes by reference, which costs little): inlined, its unrolled loop over
    the parts took stack that the loop's frame never gave back, ~1.3 kB a step, and a chunk of
    ~6000 steps died of SIGSEGV (tests/solvers/test_compiled_alpha.py). Without reference
    counting (:func:`equations_at`). (0, 0) without evaluating anything where no part can
    have a power (``model.powers`` False). The model by reference, as :func:`equations_at`."""
    model = held_at(model_at)
    if not model.powers:
        return 0.0, 0.0
    ctx = model.context
    evaluate_chains(ctx.chains, x, F, 1)
    dissipated = 0.0
    drive = 0.0
    for pack in literal_unroll(model.parts):
        dissipated += part_power(pack, ctx, F, x, v)
        drive += part_drive_power(pack, ctx, F, t, x, v, lam)
    return dissipated, drive


@njit(cache=True, _nrt=False)
def system_events(model, x):
    """:func:`events_at` for the model itself (the calls from Python)."""
    return events_at(address_of(model), x)


@njit(cache=True, _nrt=False)
def events_at(model_at, x):
    """Whether any part's event (a joint reaching its latch angle) is reached at x
    (:func:`hubbeam.system.terms.part_events`), after every step of the time loop. Not inlined
    into the loop, as :func:`powers_at`: its unrolled loop over the parts would take stack
    that the loop's frame never gives back. The model by reference, as :func:`equations_at`."""
    model = held_at(model_at)
    ctx = model.context
    event = False
    for pack in literal_unroll(model.parts):
        if part_events(pack, ctx, x):
            event = True
    return event


@njit(cache=True)
def beam_energies(model, F, x, v, beams, hub):
    """Kinetic, strain and gravity energy (J) at (x, v) in the charts F: beams[k] = (T, U, V)
    of beam k (its place among all beams; tip bodies in their beam's row), hub = (T, U, V)
    of every part's energy that belongs to no beam (the hub's rotor, the base)."""
    ctx = model.context
    evaluate_chains(ctx.chains, x, F, 1)
    beams[:, :] = 0.0
    hub[0] = 0.0
    hub[1] = 0.0
    hub[2] = 0.0
    for pack in literal_unroll(model.parts):
        T, U, V = part_energies(pack, ctx, F, x, v, beams)
        hub[0] += T
        hub[1] += U
        hub[2] += V


@njit(cache=True)
def tip_displacements(model, F, x, out):
    """Each beam's tip centroid displacement from its undeformed place along its reference
    frame's axes at x (m; radial, along the hub axis, tangential): out[k] for beam k (its
    place among all beams)."""
    ctx = model.context
    evaluate_chains(ctx.chains, x, F, 1)
    for pack in literal_unroll(model.parts):
        part_tips(pack, ctx, F, x, out)


@njit(cache=True)
def system_momenta(model, F, x, v, out):
    """out (10,) = the system's mass (kg), first moment m r_cm (kg m), linear momentum (N s) and
    angular momentum about the global origin (N m s) at (x, v)."""
    ctx = model.context
    evaluate_chains(ctx.chains, x, F, 1)
    for i in range(out.shape[0]):
        out[i] = 0.0
    for pack in literal_unroll(model.parts):
        part_momenta(pack, ctx, F, x, v, out)


@njit(cache=True)
def gauge_strains(F, x, gauges, out):
    """Fibre strains eps0 - y kappa3 + z kappa2 (measured from the stress-free state's) at the
    strain gauges of ANCF beams at x, into out[i] for gauge i. ``gauges`` = (where (n, 2) int:
    the beam's chart in F and where its gauge's element's coordinates start in x; S, dS, d2S
    (n, 4): the Hermite functions at the gauge's station and their derivatives (1/m, 1/m^2);
    section (n, 6): y, z (m) and the stress-free strains (eps0, kappa1, kappa2, kappa3) there)
    (:meth:`MultibodySystem.gauge_table`)."""
    where, S, dS, d2S, section = gauges
    w1 = np.empty(16)
    w2 = np.empty(16)
    Y = np.empty(8)
    X = np.empty(8)
    for i in range(where.shape[0]):
        coordinates.dof_weights(S, dS, d2S, i, w1, w2)
        coordinates.gauss_variables(x, where[i, 1], F[where[i, 0]], w1, w2, Y, X)
        eps0, _, kappa2, kappa3 = strain_measures(X[0:3], X[3:6], X[6], X[7])
        sec = section[i]
        out[i] = (eps0 - sec[2]) - sec[0] * (kappa3 - sec[5]) + sec[1] * (kappa2 - sec[4])


@njit(cache=True)
def record_measures(model, F, xs, vs, count, energies, gauges, hub, beams, tips, strains):
    """For the first ``count`` rows of xs, vs (one state each): when ``energies``, the hub's
    energies into hub[r] and the beams' (:func:`beam_energies`) into beams[r] (J); the
    beams' tip displacements (:func:`tip_displacements`) into tips[r] (m); the ANCF strain
    gauges' strains (:func:`gauge_strains`) into strains[r]."""
    for r in range(count):
        if energies:
            beam_energies(model, F, xs[r], vs[r], beams[r], hub[r])
        tip_displacements(model, F, xs[r], tips[r])
        gauge_strains(F, xs[r], gauges, strains[r])


#: the functions here that take the model, which holds the parts' packs
MODEL_FUNCTIONS = ("system_equations", "equations_at", "step_powers", "powers_at", "beam_energies",
                   "tip_displacements", "system_momenta", "record_measures", "system_events", "events_at")


class Compiled(NamedTuple):
    """The compiled functions of this module that take the model."""

    system_equations: object
    equations_at: object
    step_powers: object
    powers_at: object
    beam_energies: object
    tip_displacements: object
    system_momenta: object
    record_measures: object
    system_events: object
    events_at: object


def uncached_twins(functions: dict, others: dict | None = None) -> dict:
    """Copies of the ``cache=True`` numba functions ``functions`` (name: dispatcher) compiled
    without numba's on-disk cache, calling each other (and ``others``, name: dispatcher) instead
    of the originals.

    For kinds of part defined outside hubbeam: numba's cache index of a function records
    every signature it was compiled for, and unpickling a signature imports the classes in
    it; a pack class of a script or a test module would make the index unreadable in every
    other process (a later ``hubbeam run`` would fail). Systems with such kinds compile these
    copies in memory instead."""
    twins: dict = {}
    for name, function in functions.items():
        py = function.py_func
        namespace = dict(py.__globals__)
        twin = types.FunctionType(py.__code__, namespace, py.__name__, py.__defaults__, py.__closure__)
        twin.__qualname__, twin.__doc__ = py.__qualname__, py.__doc__
        twins[name] = (njit(cache=False)(twin), namespace)
    replacements = {name: twin for name, (twin, _) in twins.items()}
    replacements.update(others or {})
    for _, namespace in twins.values():
        namespace.update({name: f for name, f in replacements.items() if name in namespace})
    return {name: twin for name, (twin, _) in twins.items()}


@cache
def compiled(native: bool = True) -> Compiled:
    """This module's functions that take the model: cached in numba's on-disk cache when every
    kind of part of the system is hubbeam's own (``native``), else uncached copies
    (:func:`uncached_twins`)."""
    originals = {name: globals()[name] for name in MODEL_FUNCTIONS}
    return Compiled(**(originals if native else uncached_twins(originals)))
