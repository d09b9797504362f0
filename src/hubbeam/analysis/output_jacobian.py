"""The linearised outputs' derivatives by parts: each sensor differentiated only along the
coordinates it depends on.

A sensor of one beam (a strain gauge, a tip deflection, one beam's energy) depends on the
frames' coordinates (the hub angle, a moving base's) and that beam's coordinates (its joint
angles and its own); the hub's sensors (angle, speed, applied torque) on theta and theta';
the drive torque on the multipliers; the system's energy and angular
momentum are sums of a hub part and one part per beam, each part reading only its beam's
coordinates (and the hub's). Every output is therefore written as a matrix of *parts*
(columns x (1 + beams): the hub's part, then each beam's), whose row sums are its values.
The beams never share a coordinate, so one central difference that moves coordinate i of
*every* beam at once gives, in beam k's part, the derivative along beam k's coordinate i
(a column grouping of the Jacobian, as Curtis, Powell and Reid's): 2 (1 + the largest
beam's coordinates) evaluations for the positions and as many for the velocities, instead
of 2 per coordinate of the system, each of which measured every sensor. The frames'
coordinates (theta, a moving base's) and their rates are moved alone (every sensor reads them).

A sensor of a kind this module does not know (or a system with ``attachments``, parts that
belong to no beam but may read the beams' coordinates) is differentiated coordinate by
coordinate as a whole (:attr:`Scope.WHOLE`).

The angular momentum (every kind's momenta, compiled: cheap) and the sensors of a base and of
the system in space read every coordinate: they are differenced coordinate by coordinate.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Callable

import numpy as np

from hubbeam.sensors import PARTS, UNITS, prepare
from hubbeam.system.multibody import MultibodySystem

#: parts of a multi-part sensor that are work integrals over a run, not functions of the state
WORK_PARTS = ("dissipated", "drive")
#: sensor kinds that give no linear output (a norm, zero to first order)
NOT_LINEARISED = ("constraint_violation",)
#: the energy parts a state gives (total = their sum)
ENERGY_PARTS = ("kinetic", "strain", "gravity", "total")
#: central-difference step on coordinates and velocities (m, rad, m/s, rad/s)
STEP = 1e-6


class Scope(Enum):
    """What a linearised output reads of the state."""

    HUB = "hub"  # theta, theta', the multipliers and t only
    BEAM = "beam"  # theta and one beam's coordinates (and velocities)
    SUM = "sum"  # a hub part and one part per beam, each reading theta and its beam only
    WHOLE = "whole"  # anything: differentiated coordinate by coordinate


@dataclass
class Probe:
    """The state a sensor reads (what :func:`hubbeam.sensors.measure` needs of an integrator state)."""

    t: float
    x: np.ndarray
    v: np.ndarray
    lam: np.ndarray
    chart: np.ndarray


@dataclass
class LinearOutput:
    """The linearised columns of one sensor: ``names`` and ``units`` of its columns,
    ``parts(probe)`` (columns x (1 + beams): the hub's part, then each beam's; their row
    sums are the values), what it reads (``scope``) and whether it reads the multipliers."""

    names: list[str]
    units: list[str]
    parts: Callable[[Probe], np.ndarray]
    scope: Scope
    reads_multipliers: bool = False


#: the linearised work of a run: none (the work parts are left out)
NO_WORK = {"dissipated": 0.0, "drive": 0.0}


def _single(measure, column: int, beams: int):
    def parts(probe):
        out = np.zeros((1, 1 + beams))
        out[0, column] = measure(probe, NO_WORK)
        return out
    return parts


def _several(measure, keys, column: int, beams: int):
    def parts(probe):
        values = measure(probe, NO_WORK)
        out = np.zeros((len(keys), 1 + beams))
        out[:, column] = [values[key] for key in keys]
        return out
    return parts


def _energy_parts(system: MultibodySystem, beam: int | None):
    """(4, 1 + beams): kinetic, strain, gravity and total of the hub and each beam (``beam``:
    only that beam's column is filled)."""
    nb = len(system.beams)

    def parts(probe):
        hub, beams = system.energy_table(probe.x, probe.v, probe.chart)
        table = np.vstack([hub, beams]).T  # (3, 1 + beams)
        if beam is not None:
            keep = np.zeros(1 + nb, dtype=bool)
            keep[1 + beam] = True
            table = np.where(keep, table, 0.0)
        return np.vstack([table, table.sum(axis=0)])
    return parts


def linear_outputs(sensors, system: MultibodySystem, x0, F0) -> tuple[list[LinearOutput], list[str]]:
    """The linearised outputs of ``sensors`` on ``system`` about the equilibrium (x0, F0), and
    the names of the columns left out (work integrals; norms zero to first order)."""
    nb = len(system.beams)
    outputs, left_out = [], []
    for s in sensors:
        if s.kind in NOT_LINEARISED:
            left_out.append(s.name)
            continue
        beam = getattr(s, "beam", None)
        keys = PARTS.get(s.kind)
        if s.kind == "energy" and beam is not None:
            keys = ENERGY_PARTS  # one beam's energy has no work parts
        kept = None if keys is None else [k for k in keys if k not in WORK_PARTS]
        left_out += [f"{s.name}_{k}" for k in keys or () if k in WORK_PARTS]
        names = [s.name] if kept is None else [f"{s.name}_{k}" for k in kept]
        units = [UNITS[s.kind]] * len(names)
        k = None if beam is None else system.beam_index(beam)
        if s.kind == "energy":
            table = _energy_parts(system, k)
            rows = [ENERGY_PARTS.index(key) for key in kept]
            output = LinearOutput(names, units, lambda probe, table=table, rows=rows: table(probe)[rows],
                                  Scope.BEAM if k is not None else Scope.SUM)
        else:
            measure = prepare(s, system)
            scope = {"hub_angle": Scope.HUB, "hub_angular_velocity": Scope.HUB, "applied_torque": Scope.HUB,
                     "hub_torque": Scope.HUB, "surface_strain": Scope.BEAM, "tip_deflection": Scope.BEAM
                     }.get(s.kind, Scope.WHOLE)
            column = 1 + system.beam_index(beam) if scope is Scope.BEAM else 0
            parts = _single(measure, column, nb) if kept is None else _several(measure, kept, column, nb)
            output = LinearOutput(names, units, parts, scope, reads_multipliers=s.kind in ("hub_torque",)
                                  or scope is Scope.WHOLE)
        if system.attachments and output.scope is Scope.SUM:
            output.scope = Scope.WHOLE  # an attachment's energy sits in the hub's part and may read a beam
        outputs.append(output)
    return outputs, left_out


def output_jacobians(outputs: list[LinearOutput], system: MultibodySystem, x0, lam0, F, omega: float = 0.0,
                     progress: Callable[[int, int], None] | None = None
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(values, Hx, Hv, Hl): the outputs' values at the equilibrium and their derivatives along
    the coordinates x, the velocities v and the multipliers, by central differences grouped
    by beam (see the module doc). About the steady rotation at ``omega`` (rad/s) the velocity
    is the rigid rotation's, omega xi(x), and Hx differentiates through it.
    ``progress(done, total)``: called after each group of evaluations."""
    nx, nl = x0.size, lam0.size
    layout = system.layout
    # a beam's slice: its joint angles and its own coordinates (adjacent in x)
    slices = [slice(layout.joint_x(k).start, layout.beam_x(k).stop) for k in range(len(system.beams))]
    widest = max((s.stop - s.start for s in slices), default=0)
    frames = range(layout.frame_dofs)  # the base's coordinates and theta: every output reads them

    def velocity(x):
        return system.steady_rotation_rates(x, F, omega)[0] if omega else np.zeros(nx)

    v0 = velocity(x0)
    sizes = [len(o.names) for o in outputs]
    rows = np.cumsum([0] + sizes)
    n_out = int(rows[-1])
    Hx, Hv, Hl = np.zeros((n_out, nx)), np.zeros((n_out, nx)), np.zeros((n_out, nl))

    def evaluate(chosen, x, v, lam):
        probe = Probe(0.0, x, v, lam, F)
        return [outputs[i].parts(probe) for i in chosen]

    everything = list(range(len(outputs)))
    values = np.concatenate([p.sum(axis=1) for p in evaluate(everything, x0, v0, lam0)]) if outputs else np.zeros(0)
    grouped = [i for i, o in enumerate(outputs) if o.scope in (Scope.BEAM, Scope.SUM)]
    whole = [i for i, o in enumerate(outputs) if o.scope is Scope.WHOLE]
    total = 2 * (len(frames) + widest) + (2 * (nx - len(frames)) if whole else 0) + nl
    done = 0

    def report(count=1):
        nonlocal done
        done += count
        if progress is not None:
            progress(done, total)

    for H, moving_v in ((Hx, False), (Hv, True)):
        def shifted(delta, chosen):
            if moving_v:
                return evaluate(chosen, x0, v0 + delta, lam0)
            return evaluate(chosen, x0 + delta, velocity(x0 + delta), lam0)

        # the frames' coordinates (rates): every output reads them
        for c in frames:
            delta = np.zeros(nx)
            delta[c] = STEP
            for i, (p, m) in enumerate(zip(shifted(delta, everything), shifted(-delta, everything))):
                H[rows[i]:rows[i + 1], c] = (p.sum(axis=1) - m.sum(axis=1)) / (2 * STEP)
            report()
        # coordinate j of every beam at once: beam k's part moves with beam k's coordinate only
        for j in range(widest):
            delta = np.zeros(nx)
            places = [(k, s.start + j) for k, s in enumerate(slices) if s.start + j < s.stop]
            for _, c in places:
                delta[c] = STEP
            for i, p, m in zip(grouped, shifted(delta, grouped), shifted(-delta, grouped)):
                d = (p - m) / (2 * STEP)
                for k, c in places:
                    H[rows[i]:rows[i + 1], c] = d[:, 1 + k]
            report()
        for c in range(len(frames), nx) if whole else ():  # the outputs that are not split: coordinate by coordinate
            delta = np.zeros(nx)
            delta[c] = STEP
            for i, p, m in zip(whole, shifted(delta, whole), shifted(-delta, whole)):
                H[rows[i]:rows[i + 1], c] = (p.sum(axis=1) - m.sum(axis=1)) / (2 * STEP)
            report()
    readers = [i for i, o in enumerate(outputs) if o.reads_multipliers]
    steps = 1e-6 * np.maximum(1.0, np.abs(lam0))
    for c in range(nl) if readers else ():
        delta = np.zeros(nl)
        delta[c] = steps[c]
        plus, minus = evaluate(readers, x0, v0, lam0 + delta), evaluate(readers, x0, v0, lam0 - delta)
        for i, p, m in zip(readers, plus, minus):
            Hl[rows[i]:rows[i + 1], c] = (p.sum(axis=1) - m.sum(axis=1)) / (2 * steps[c])
    report(nl)
    return values, Hx, Hv, Hl
