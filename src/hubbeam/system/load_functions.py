"""Loads per unit length from a Python function along a beam's span (the slow path, for users
bringing their own aerodynamics).

A :class:`LoadFunction` calls ``function(t, x, position, velocity, frame)`` once per evaluation
of the equations with every station of its beam at once:

- ``t`` (s), ``x`` (ns,) the stations (m from the root),
- ``position`` (ns, 3) and ``velocity`` (ns, 3) of the centre line there (global, m and m/s),
- ``frame`` (ns, 3, 3) the section frames there, columns [tau m n] (global, unit vectors,
  following the deflection and the pretwist),

and takes back ``(force, moment)``: each (ns, 3) or (3,) (the same at every station), global
components, N/m and N m/m. The stations are Gauss points on every element (by default the
beam's own quadrature: ``gauss_points`` of an ANCF beam, 4 on an FFR beam, those of its drag),
and the generalized force is that of the loads along the span
(:func:`hubbeam.system.span_loads.load_force`) with the function's values as a global load
there: the virtual work f . delta r0(x) + m . delta omega(x).

The velocity is the directional central difference of the centre line along the rates,
(r(x + h v) - r(x - h v)) / 2h with h |v|_max = 1e-6: exact for ANCF (its centre line is linear
in its coordinates), to about 1e-12 of the speed for FFR. The Newton matrix gets the load's
derivatives by central differences over the coordinates and, when the matrix has a velocity
part, the rates (as the Python torque law's): slow, but the same Newton as the built-in loads,
and ``linearize``'s damping and stiffness of the load. The power Q . x' enters the energy
balance as the drive's work (:meth:`MultibodySystem.step_powers`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from hubbeam.system.span_loads import SpanLoad, load_force, pack_loads, span_stations

#: the largest rate step of the velocity's difference, h |v|_max (m or rad)
VELOCITY_STEP = 1e-6


@dataclass(eq=False)
class LoadFunction:
    """A load per unit length along beam ``beam`` (its place among the system's beams) from
    ``function(t, x, position, velocity, frame) -> (force, moment)`` (module docstring), at
    ``gauss`` Gauss points per element (None: the beam's own quadrature). ``name`` names it in
    messages."""

    function: Callable
    beam: int | str = 0  # a place among the beams, or (through the API) a beam's name
    gauss: int | None = None
    name: str = "function1"

    def __post_init__(self) -> None:
        if not callable(self.function):
            raise TypeError(f"{self.name}: function must be callable as f(t, x, position, velocity, frame) "
                            f"(got {type(self.function).__name__})")
        if self.gauss is not None and (isinstance(self.gauss, bool) or not isinstance(self.gauss, int)
                                       or not 1 <= self.gauss <= 20):
            raise ValueError(f"{self.name}: gauss must be a whole number from 1 to 20 (got {self.gauss!r})")

    def stations(self, part) -> tuple[np.ndarray, np.ndarray]:
        """The stations and weights (m) on ``part`` (the beam's part)."""
        gauss = self.gauss
        if gauss is None:
            gauss = getattr(part.beam, "gauss_points", 4)
        return span_stations(part, 0.0, part.length, (), gauss)

    def values(self, t: float, stations, position, velocity, frame) -> np.ndarray:
        """(ns, 6): the function's force and moment per unit length at the stations. ValueError
        naming the function for anything but two finite arrays of shape (ns, 3) or (3,)."""
        out = self.function(float(t), stations, position, velocity, frame)
        ns = stations.size
        try:
            force, moment = out
            values = np.concatenate([np.broadcast_to(np.asarray(force, dtype=float), (ns, 3)),
                                     np.broadcast_to(np.asarray(moment, dtype=float), (ns, 3))], axis=1)
        except (TypeError, ValueError):
            raise ValueError(f"{self.name}: the load function must return (force, moment), each of shape ({ns}, 3) or "
                             f"(3,) (got {_shape(out)}, t = {t})") from None
        if not np.all(np.isfinite(values)):
            raise ValueError(f"{self.name}: the load function returned a value that is not finite (t = {t})")
        return values


def _shape(out) -> str:
    try:
        return ", ".join(str(np.shape(o)) for o in out)
    except TypeError:
        return type(out).__name__


class FunctionLoads:
    """The :class:`LoadFunction` s of a system for one layout (the hub held or not): their
    template packs, evaluated by :meth:`force` and added into the equations by :meth:`add`."""

    def __init__(self, system, layout, context, loads) -> None:
        self.system, self.context, self.loads = system, context, list(loads)
        self.places = []
        for load in self.loads:
            part = system.beams[load.beam]
            stations, weights = load.stations(part)
            template = SpanLoad(load.beam, stations, weights, [0.0], np.zeros((1, stations.size, 6)), False, load.name)
            self.places.append((stations, weights, pack_loads(system, layout, [template])))

    def force(self, i: int, t: float, x, v, F, factor: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
        """(columns (x indices), generalized force (N, N m)) of load i at (t, x, v): ``factor``
        times its Q (module docstring)."""
        load, (stations, weights, pack) = self.loads[i], self.places[i]
        system, k = self.system, load.beam
        position = system.centre_line_at(x, F, stations, k)
        speed = float(np.max(np.abs(v))) if v.size else 0.0
        if speed > 0.0:
            h = VELOCITY_STEP / speed
            velocity = (system.centre_line_at(x + h * v, F, stations, k)
                        - system.centre_line_at(x - h * v, F, stations, k)) / (2.0 * h)
        else:
            velocity = np.zeros_like(position)
        frame = system.frames_at(x, F, stations, k)
        pack.values[0, 0, :stations.size] = load.values(t, stations, position, velocity, frame) * weights[:, None]
        cols = np.empty(pack.widest, dtype=np.int64)
        Q = np.empty(pack.widest)
        m = load_force(pack, self.context, F, 0, x, 0.0, float(factor), cols, Q)
        return cols[:m].copy(), Q[:m].copy()

    def add(self, t, x, v, F, coef_c, coef_k, factor, want_matrix, res, matrix, z_of_x) -> None:
        """-coef_k Q of every load into the residual ``res`` (z rows) and, ``want_matrix``, the
        matrix -coef_k dQ/dx - coef_c dQ/dx' by central differences into ``matrix``."""
        for i in range(len(self.loads)):
            cols, Q = self.force(i, t, x, v, F, factor)
            rows = z_of_x[cols]
            res[rows] -= coef_k * Q
            if not want_matrix:
                continue
            for which, coef in ((x, coef_k), (v, coef_c)):
                if coef == 0.0:
                    continue
                for j, c in enumerate(cols):
                    h = 1e-6 * max(1.0, abs(which[c]))
                    plus, minus = which.copy(), which.copy()
                    plus[c] += h
                    minus[c] -= h
                    pair = [(plus, v), (minus, v)] if which is x else [(x, plus), (x, minus)]
                    Qp = self.force(i, t, *pair[0], F, factor)[1]
                    Qm = self.force(i, t, *pair[1], F, factor)[1]
                    column = -coef * (Qp - Qm) / (2.0 * h)
                    zc = z_of_x[c]
                    for r, value in zip(rows, column):
                        # within the band (or the border): a function that couples stations far
                        # apart loses those entries (a modified Newton, as the loads in time)
                        if value != 0.0 and (min(r, zc) < matrix.border or abs(r - zc) <= matrix.bandwidth):
                            matrix.add(r, zc, value)

    def power(self, t, x, v, F) -> float:
        """The loads' power sum Q . x' (W): the drive's work of the energy balance."""
        total = 0.0
        for i in range(len(self.loads)):
            cols, Q = self.force(i, t, x, v, F)
            total += float(Q @ v[cols])
        return total if math.isfinite(total) else float("nan")
