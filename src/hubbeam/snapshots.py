"""The geometry of a run at its output times, so that it can be drawn again (``hubbeam run --state``).

A :class:`StateRecorder` fixes, once per run, a set of span stations on every beam (its nodes
and :data:`POINTS_PER_ELEMENT` - 1 evenly spaced points inside each element) and the width and
thickness of the section there (through :meth:`hubbeam.system.parts.BeamPart.section_size`,
the one place that reads them). At each output time it records the hub angle theta and, for
every beam, at those stations: the deformed centre line, the section frame's unit vectors m
(along the width) and n (along the thickness), and the axial strain on the upper surface
(z = +h/2, h the station's thickness), and the frames of the hub (its origin and axes at
theta: R R_h A_h(theta)) and of the base. Everything is global and SI: m, rad, strain 1. The
beams whose root is on a revolute joint (:mod:`hubbeam.system.joints`) are listed
(``joints``): their first station is the hinge, which drawings mark.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: each element is cut into this many pieces: the nodes and 3 points inside every element
POINTS_PER_ELEMENT = 4


@dataclass(frozen=True)
class BeamSnapshot:
    """One beam at one output time, at its recorder's stations (n of them)."""

    centre_line: np.ndarray  # (n, 3) m, global
    m: np.ndarray  # (n, 3) unit vectors along the section's width, global
    n: np.ndarray  # (n, 3) unit vectors along the section's thickness, global
    strain: np.ndarray  # (n,) axial strain on the upper surface z = +h/2


@dataclass(frozen=True)
class Snapshot:
    """The hub angle (rad), the hub's and the base's frames (origin (3,) m and axes (3, 3),
    global) and every beam's :class:`BeamSnapshot` at one output time."""

    hub_angle: float
    beams: tuple[BeamSnapshot, ...]
    hub_origin: np.ndarray = None
    hub_axes: np.ndarray = None
    base_origin: np.ndarray = None
    base_axes: np.ndarray = None


class StateRecorder:
    """Records a :class:`Snapshot` of a system's state (call it with the system and an
    integrator state) at fixed span stations: ``stations[k]`` (m from the root) of beam k,
    with the sections' ``widths[k]`` and ``thicknesses[k]`` (m) there."""

    def __init__(self, system, points_per_element: int = POINTS_PER_ELEMENT) -> None:
        if int(points_per_element) < 1:
            raise ValueError(f"points_per_element must be >= 1 (got {points_per_element})")
        self.points_per_element = int(points_per_element)
        self.names = tuple(part.name for part in system.beams)
        #: the beams whose root is a hinge (on a revolute joint): drawn with a marker at their first station
        self.joints = tuple(part.name for part in system.beams if part.mount.joint is not None)
        self.formulations = tuple(part.formulation for part in system.beams)
        self.stations = tuple(part.stations(self.points_per_element) for part in system.beams)
        sizes = [np.array([part.section_size(s) for s in st], dtype=float).reshape(-1, 2)
                 for part, st in zip(system.beams, self.stations)]
        self.widths = tuple(s[:, 0] for s in sizes)
        self.thicknesses = tuple(s[:, 1] for s in sizes)
        #: the hub's radius for drawing (m): the largest root radius
        self.hub_radius = max(float(part.mount.radius) for part in system.beams)
        #: every beam's tip body ({"mass" (kg), "inertia" (kg m^2, about tau, m, n), "offset"
        #: (m, in the tip section frame)}) or None: drawn on the tip section's frame
        self.tip_bodies = tuple(None if part.tip_body is None else
                                {"mass": float(part.tip_body.mass), "inertia": [float(v) for v in part.tip_body.inertia],
                                 "offset": [float(v) for v in part.tip_body.offset]} for part in system.beams)
        #: every beam's undeformed centre line at the stations with the hub at theta = 0 (m, global):
        #: turned by the hub angle, the place the deflection is measured from
        x0, F0 = system.initial_state(0.0)
        self.references = tuple(system.centre_line_at(x0, F0, st, k) for k, st in enumerate(self.stations))
        #: the same in the hub's frame at theta = 0 (m): carried by the hub's frame at any time, the
        #: undeformed beams moving rigidly with the base and the hub
        O, H = system.frames.pose(system.frames.hub, x0)
        self.local_references = tuple((ref - O) @ H for ref in self.references)

    def __call__(self, system, state) -> Snapshot:
        beams = []
        for k, part, q, chart in system.parts(state.x, state.chart):
            xs = self.stations[k]
            frames = system.frames_at(state.x, state.chart, xs, k)
            strain = part.surface_strains(q, chart, xs, np.zeros(xs.size), 0.5 * self.thicknesses[k])
            beams.append(BeamSnapshot(system.centre_line_at(state.x, state.chart, xs, k), frames[:, :, 1],
                                      frames[:, :, 2], strain))
        hub = system.frames.pose(system.frames.hub, state.x)
        base = system.frames.pose(system.frames.base, state.x)
        return Snapshot(float(state.x[system.theta_index]), tuple(beams), hub[0], hub[1], base[0], base[1])
