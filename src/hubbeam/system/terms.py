"""The registry of part kinds: what a kind of part gives the compiled equations.

A *kind* of part (ANCF beams, FFR beams, tip bodies on ANCF tips, ...) is one module that
declares

- a *pack*: a ``typing.NamedTuple`` class holding every constant its compiled terms need
  for all parts of that kind in one system (SI units), and a ``packer(system, layout)``
  that builds it from a :class:`~hubbeam.system.hub_system.HubSystem` (None when the system
  has no part of that kind);
- its compiled terms, registered for its pack class with :func:`register`:

  ``equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor,
  exact_stiffness, want_matrix, res, ab, brow, bcol, bb) -> (hub_force, margin, power)``
      adds its residual rows (coef_k times its force rows on x, scale Phi on its
      multipliers: :class:`~hubbeam.system.layout.Layout` gives the places, the pack carries
      them) into ``res`` and, when ``want_matrix``, its Newton-matrix entries into the
      bordered storage (:func:`~hubbeam.system.assembly.add_entry`); returns its generalized
      force on the hub angle theta (unscaled, N m), the margin of its rotation charts (2.0
      when it has none; at or below :data:`CHART_SINGULAR` the caller stops) and the power it
      dissipates (W);
  ``energies(pack, ctx, F, x, v, beams) -> (T, U, V)``
      adds each beam's kinetic, strain and gravity energy (J) into ``beams[k]`` (k: the beam's
      place among all beams) and returns the energy that belongs to no beam;
  ``power(pack, ctx, F, x, v) -> float``
      the power it dissipates at (x, v) (W, >= 0);
  ``tips(pack, ctx, x, out)``
      each beam's tip displacement in its hub frame into ``out[k]`` (m).

  A kind leaves out what it does not have (no energy, no dissipation, no tip).

The compiled equations (:mod:`hubbeam.system.equations`) hold a tuple of the packs of the
kinds present in a system and call these four through :func:`part_equations`,
:func:`part_energies`, :func:`part_power` and :func:`part_tips`, which numba resolves by
the pack's class when it compiles them: a kind absent from a system is not compiled for it.
``ctx`` is the :class:`Context` of the system. A new kind of part is its module plus its
registration; nothing else in the system layer changes.
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
    """What every part's compiled terms see of the system: where unknowns sit and the
    environment."""

    border: int  # the bordered Newton matrix's dense border (theta and the drive multiplier)
    z_of_x: np.ndarray  # int64 (nx,): z index of each coordinate
    z_of_lambda: np.ndarray  # int64 (n_lambda,): z index of each multiplier
    ku: int  # upper bandwidth of the band storage (2 x the half-bandwidth, gbtrf layout)
    theta: int  # the hub angle's place in x
    gravity: tuple  # (g0, g1, g2) m/s^2: floats, not an array (a tuple of floats carries no
    #                 reference count, which every compiled call that passes the context pays)
    drag: tuple  # (c1, c2) of Eq. 37, floats


@dataclass(frozen=True)
class PartKind:
    """A registered kind: its pack class, the packer that builds its pack from a system and
    the half-bandwidth its entries need in the Newton matrix's band (a function of the system)."""

    pack: type
    packer: Callable
    bandwidth: Callable


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


def part_tips(pack, ctx, x, out):
    """A part kind's tip displacements (compiled; see the module)."""
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


def _no_tips(pack, ctx, x, out):
    return None


def _dispatch(stub, pack_class, impl) -> None:
    """Let numba resolve ``stub`` to ``impl`` for packs of ``pack_class`` (``impl``: a plain
    Python function with the stub's parameter names, which numba compiles where it is called).
    Inlined into the caller: a compiled call pays the reference counts of every array of its
    tuple arguments (the pack and the context), twice per step and beam kind in the time loop."""

    def resolve(pack, *args):
        if getattr(pack, "instance_class", None) is pack_class:
            return impl
        return None

    overload(stub, jit_options={"cache": True}, strict=False, inline="always")(resolve)


def register(pack: type, packer: Callable, equations, energies=None, power=None, tips=None,
             bandwidth: Callable = lambda system: 1) -> PartKind:
    """Register a kind of part: its pack class, its ``packer(system, layout) -> pack | None``,
    ``bandwidth(system)``, the half-bandwidth its band entries need (the distance from the
    diagonal of its farthest entry off the border), and its terms: plain Python functions in numba's subset with the parameter names of
    :func:`part_equations`, :func:`part_energies`, :func:`part_power` and :func:`part_tips`
    (the ones left out are zero), compiled where the system's equations call them. Returns
    the kind."""
    if any(kind.pack is pack for kind in KINDS):
        raise ValueError(f"{pack.__name__} is registered already")
    _dispatch(part_equations, pack, equations)
    _dispatch(part_energies, pack, energies if energies is not None else _no_energies)
    _dispatch(part_power, pack, power if power is not None else _no_power)
    _dispatch(part_tips, pack, tips if tips is not None else _no_tips)
    kind = PartKind(pack, packer, bandwidth)
    KINDS.append(kind)
    return kind


def native(packs: tuple) -> bool:
    """Whether every pack's kind is defined inside hubbeam (numba may then keep the system's
    compiled functions in its on-disk cache; see
    :func:`hubbeam.system.equations.uncached_twins`)."""
    return all(type(p).__module__.split(".")[0] == "hubbeam" for p in packs)


def packs(system, layout) -> tuple:
    """The packs of the kinds present in ``system`` (placed by ``layout``), in registration order."""
    found = (kind.packer(system, layout) for kind in KINDS)
    return tuple(p for p in found if p is not None)
