"""The registry of part kinds: what a kind of part gives the compiled equations.

A *kind* of part (ANCF beams, FFR beams, tip bodies on ANCF tips, rigid bodies on frames,
the laws that drive or load coordinates, ...) is one module that declares

- a *pack*: a ``typing.NamedTuple`` class holding every constant its compiled terms need
  for all parts of that kind in one system (SI units), and a ``packer(system, layout)``
  that builds it from a :class:`~hubbeam.system.multibody.MultibodySystem` (None when the
  system has no part of that kind);
- its compiled terms, registered for its pack class with :func:`register`:

  ``equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor,
  exact_stiffness, want_matrix, res, ab, brow, bcol, bb) -> (margin, power)``
      adds its residual rows (coef_k times its generalized forces "M acc + f_int - Q" on the
      coordinates it involves, whoever owns them: its own, a frame's (the hub angle, the
      base's, a joint angle, a parent's tip), and scale Phi on its multipliers:
      :class:`~hubbeam.system.layout.Layout` gives the places, the pack carries them) into
      ``res`` and, when ``want_matrix``, its Newton-matrix entries into the bordered storage
      (:func:`~hubbeam.system.assembly.add_entry`); returns the margin of its rotation charts
      (2.0 when it has none; at or below :data:`CHART_SINGULAR` the caller stops) and the power
      it dissipates (W);
  ``energies(pack, ctx, F, x, v, beams) -> (T, U, V)``
      adds each beam's kinetic, strain and gravity energy (J) into ``beams[k]`` (k: the beam's
      place among all beams) and returns the energy that belongs to no beam;
  ``power(pack, ctx, F, x, v) -> float``
      the power it dissipates at (x, v) (W, >= 0);
  ``drive_power(pack, ctx, F, t, x, v, lam) -> float``
      the power of its applied torques, loads and prescribed motions on the system (W): what
      the energy balance counts as the drive's work;
  ``tips(pack, ctx, F, x, out)``
      each beam's tip displacement in its reference frame into ``out[k]`` (m);
  ``momenta(pack, ctx, F, x, v, out)``
      adds its mass (kg), first moment m r_cm (kg m), linear momentum (N s) and angular momentum
      about the global origin (N m s) into out[0], out[1:4], out[4:7], out[7:10];
  ``events(pack, ctx, x) -> bool``
      whether the state x has reached an event of the kind (a joint's latch angle): the time
      loop then stops after the step and Python changes the system (:mod:`hubbeam.simulation`).

  A kind leaves out what it does not have (no energy, no dissipation, no tip, no drive).

The compiled equations (:mod:`hubbeam.system.equations`) hold a tuple of the packs of the
kinds present in a system and call these through :func:`part_equations`,
:func:`part_energies`, ..., which numba resolves by the pack's class when it compiles them:
a kind absent from a system is not compiled for it. ``ctx`` is the :class:`Context` of the
system. A new kind of part is its module plus its registration; nothing else in the system
layer changes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, NamedTuple

import numpy as np
from numba import njit
from numba.extending import overload


#: a part's chart margin (min 1 + d.tau) at or below this value: a beam tangent is at the
#: singular direction of its rotation chart, and the residual is not valid
CHART_SINGULAR = 1e-6


class Context(NamedTuple):
    """What every part's compiled terms see of the system: where unknowns sit, the frames and
    the environment."""

    border: int  # the bordered Newton matrix's dense border (the frames' coordinates and constraints)
    z_of_x: np.ndarray  # int64 (nx,): z index of each coordinate
    z_of_lambda: np.ndarray  # int64 (n_lambda,): z index of each multiplier
    ku: int  # upper bandwidth of the band storage (2 x the half-bandwidth, gbtrf layout)
    theta: int  # the hub angle's place in x
    gravity: tuple  # (g0, g1, g2) m/s^2: floats, not an array (a tuple of floats carries no
    #                 reference count, which every compiled call that passes the context pays)
    drag: tuple  # (c1, c2) of Eq. 37, floats
    chains: tuple  # the system's frames (:class:`hubbeam.system.chains.ChainTable`)


@dataclass(frozen=True)
class PartKind:
    """A registered kind: its pack class, the packer that builds its pack from a system and
    the half-bandwidth its entries need in the Newton matrix's band (a function of the system
    and its layout)."""

    pack: type
    packer: Callable
    bandwidth: Callable
    has_events: bool = False  # it registered events (:func:`part_events`)
    #: whether a pack of this kind can reach an event at all (register's ``events_possible``; None: yes)
    events_possible: Callable | None = None
    has_powers: bool = False  # it registered a dissipated or a drive power (:func:`part_power`, :func:`part_drive_power`)
    #: whether a pack of this kind can have a power that is not zero (register's ``powers_possible``; None: yes)
    powers_possible: Callable | None = None


#: the registered kinds (every kind adds its terms: their order does not matter)
KINDS: list[PartKind] = []


def part_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                   want_matrix, res, ab, brow, bcol, bb):
    """A part kind's residual rows and Newton-matrix entries (compiled; see the module)."""
    raise TypeError(f"no compiled terms are registered for {type(pack).__name__}")


def part_energies(pack, ctx, F, x, v, beams):
    """A part kind's energies (compiled; see the module)."""
    raise TypeError(f"no compiled terms are registered for {type(pack).__name__}")


def part_power(pack, ctx, F, x, v):
    """A part kind's dissipated power (compiled; see the module)."""
    raise TypeError(f"no compiled terms are registered for {type(pack).__name__}")


def part_tips(pack, ctx, F, x, out):
    """A part kind's tip displacements (compiled; see the module)."""
    raise TypeError(f"no compiled terms are registered for {type(pack).__name__}")


def part_drive_power(pack, ctx, F, t, x, v, lam):
    """A part kind's drive power (compiled; see the module)."""
    raise TypeError(f"no compiled terms are registered for {type(pack).__name__}")


def part_momenta(pack, ctx, F, x, v, out):
    """A part kind's mass, first moment and momenta (compiled; see the module)."""
    raise TypeError(f"no compiled terms are registered for {type(pack).__name__}")


def part_events(pack, ctx, x):
    """Whether a part kind's event is reached at x (compiled; see the module)."""
    raise TypeError(f"no compiled terms are registered for {type(pack).__name__}")


@njit(cache=True)
def add_beam_energy(beams, k, kinetic, strain, gravity):
    """Add (kinetic, strain, gravity) (J) to the energy row of beam k (its place among all beams)."""
    beams[k, 0] += kinetic
    beams[k, 1] += strain
    beams[k, 2] += gravity


def _no_energies(pack, ctx, F, x, v, beams):
    return 0.0, 0.0, 0.0


def _no_power(pack, ctx, F, x, v):
    return 0.0


def _no_tips(pack, ctx, F, x, out):
    return None


def _no_drive_power(pack, ctx, F, t, x, v, lam):
    return 0.0


def _no_momenta(pack, ctx, F, x, v, out):
    return None


def _no_events(pack, ctx, x):
    return False


def _dispatch(stub, pack_class, impl, inline: str = "always", called: bool = False) -> None:
    """Let numba resolve ``stub`` to ``impl`` for packs of ``pack_class`` (``impl``: a plain
    Python function with the stub's parameter names, which numba compiles where it is called).
    ``inline`` "always" for the terms of the time step (the equations, the powers, the events):
    a compiled call pays the reference counts of every array of its tuple arguments (the pack
    and the context), twice per step and beam kind in the time loop. "never" for the rest (the
    energies, tips and momenta of the records): numba compiles an inlined overload twice, once
    on its own to type it and once more in its caller, so that a called one costs half the
    compile. ``called``: ``impl`` is a function of its own, compiled with numba's reference
    counting, that the caller calls (the overload is not inlined): for the time step's terms of
    a kind that allocates or takes arrays from its calls, since the system's functions of the
    time step count no references (:func:`register`'s ``counts_references``). (An inlined
    wrapper that only called it cost its own compile, with the callee's code linked in, on exp1
    about 3 s of CPU: ``python benchmarks/compile_time.py exp1``.) Only hubbeam's own kinds go
    to numba's on-disk cache: a cache index records the classes of
    every signature compiled, and a class of a script or a test module in it (a default term
    such as ``_no_power`` is compiled for every kind) would make the index unreadable in every
    other process (see :func:`native`)."""
    jit_options = {"cache": native_class(pack_class)}
    if called:
        jit_options["_nrt"] = True  # explicit: callees inherit _nrt
        inline = "never"

    def resolve(pack, *args):
        if getattr(pack, "instance_class", None) is pack_class:
            return impl
        return None

    overload(stub, jit_options=jit_options, strict=False, inline=inline)(resolve)


def register(pack: type, packer: Callable, equations, energies=None, power=None, tips=None,
             bandwidth: Callable = lambda system, layout: 1, drive_power=None, momenta=None,
             events=None, events_possible: Callable | None = None,
             powers_possible: Callable | None = None, counts_references: bool = True) -> PartKind:
    """Register a kind of part: its pack class, its ``packer(system, layout) -> pack | None``,
    ``bandwidth(system, layout)``, the half-bandwidth its band entries need (the distance from
    the diagonal of its farthest entry off the border), and its terms: plain Python functions
    in numba's subset with the parameter names of :func:`part_equations`,
    :func:`part_energies`, :func:`part_power`, :func:`part_tips`, :func:`part_drive_power`,
    :func:`part_momenta` and :func:`part_events` (the ones left out are zero, or no event),
    compiled where the system's equations call them; ``events_possible(pack) -> bool``: whether
    that pack can reach an event (default: yes), so that the time loop does not look for events
    that cannot happen; ``powers_possible(pack, ctx) -> bool``: whether that pack in a system of
    context ``ctx`` (:class:`Context`) can have a dissipated or drive power that is not zero
    (default: yes, when it registered ``power`` or ``drive_power``), so that the time loop does
    not evaluate powers that are zero at every state (:func:`with_powers`): it must say yes
    wherever one of them can be nonzero, else the energy balance loses that work without a word.
    Returns the kind."""
    if any(kind.pack is pack for kind in KINDS):
        raise ValueError(f"{pack.__name__} is registered already")
    called = counts_references
    _dispatch(part_equations, pack, equations, called=called)
    _dispatch(part_energies, pack, energies if energies is not None else _no_energies, "never")
    _dispatch(part_power, pack, power if power is not None else _no_power, called=called and power is not None)
    _dispatch(part_tips, pack, tips if tips is not None else _no_tips, "never")
    _dispatch(part_drive_power, pack, drive_power if drive_power is not None else _no_drive_power,
              called=called and drive_power is not None)
    _dispatch(part_momenta, pack, momenta if momenta is not None else _no_momenta, "never")
    _dispatch(part_events, pack, events if events is not None else _no_events, called=called and events is not None)
    kind = PartKind(pack, packer, bandwidth, events is not None, events_possible,
                    power is not None or drive_power is not None, powers_possible)
    KINDS.append(kind)
    return kind


def native_class(pack_class: type) -> bool:
    """Whether a pack class is defined inside hubbeam."""
    return pack_class.__module__.split(".")[0] == "hubbeam"


def native(packs: tuple) -> bool:
    """Whether every pack's kind is defined inside hubbeam (numba may then keep the system's
    compiled functions in its on-disk cache; see
    :func:`hubbeam.system.equations.uncached_twins`)."""
    return all(native_class(type(p)) for p in packs)


def with_events(packs: tuple) -> bool:
    """Whether a pack's kind registered events and the pack can reach one: the time loop looks for
    events only then (the look costs about 0.3-1 us per step)."""
    return any(kind.has_events and (kind.events_possible is None or kind.events_possible(p))
               for kind in KINDS for p in packs if type(p) is kind.pack)


def with_powers(packs: tuple, ctx: Context) -> bool:
    """Whether a pack's kind registered a dissipated or drive power and the pack can have one that
    is not zero in a system of context ``ctx``: the time loop evaluates the step's powers
    (:func:`hubbeam.system.equations.step_powers`, about 0.4-0.9 us per step) only then, and
    takes them as zero otherwise."""
    return any(kind.has_powers and (kind.powers_possible is None or kind.powers_possible(p, ctx))
               for kind in KINDS for p in packs if type(p) is kind.pack)


def packs(system, layout) -> tuple:
    """The packs of the kinds present in ``system`` (placed by ``layout``), in registration order."""
    found = (kind.packer(system, layout) for kind in KINDS)
    return tuple(p for p in found if p is not None)
