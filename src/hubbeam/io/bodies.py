"""The rigid bodies of a recorded run, as what draws them needs: a pose over time (position and
rotation matrix) and a glyph (a box, or a disc for the hub), for :mod:`hubbeam.animate` and
:mod:`hubbeam.io.vtk`.

- the **hub**: at its origin, its axes the hub frame at the hub angle (R R_h A_h(theta), Eq. 74
  on a fixed upright base: i_h, j0, k_h), drawn as a disc of the hub radius (the largest root
  radius) about its axis, 1/10 of that radius thick;
- a **moving base**: its origin and axes, drawn as a box of the hub radius with its axes;
- each **tip body**: its centre of mass at the tip centroid plus the offset in the tip
  section frame [tau m n] (tau = m x n, from the recorded section frame at the tip), its axes
  that frame, drawn as the uniform box of the same mass and principal inertias (sides
  a_i = sqrt(6 (J_j + J_k - J_i) / m) along tau, m, n; a body whose inertias give no box, a
  point mass, as a cube of the tip section's width).

With a magnification ``scale`` (``hubbeam animate --scale``) a tip body follows its beam's
magnified tip (the tip's deflection from the undeformed beam carried by the hub's frame, times
scale); its rotation is the computed one.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import numpy as np

from hubbeam.io.state import RunState

#: sides of the polygon drawn as the hub's disc
DISC_SIDES = 36
#: the hub disc's half thickness, a fraction of its radius
DISC_HALF_THICKNESS = 0.05


class Glyph(Enum):
    """How a rigid body is drawn in its own axes: a box of half sides ``half_size`` along
    them, or a disc of radius half_size[0] about its second axis, half_size[1] half thick."""

    BOX = "box"
    DISC = "disc"


@dataclass(frozen=True)
class RigidBody:
    """A rigid body over a run: ``name``, ``position`` (nt, 3) m and ``rotation`` (nt, 3, 3)
    (its axes as global columns) at the output times, and its ``glyph`` of ``half_size``
    (3,) m."""

    name: str
    position: np.ndarray
    rotation: np.ndarray
    glyph: Glyph
    half_size: np.ndarray

    def surface(self, i: int) -> tuple[np.ndarray, list[np.ndarray]]:
        """(vertices (k, 3) m, global; faces: index arrays, each a flat polygon) of the glyph
        at output time i."""
        local, faces = glyph_surface(self.glyph, self.half_size)
        return self.position[i] + local @ self.rotation[i].T, faces

    def axes(self, i: int, length: float | None = None) -> np.ndarray:
        """(4, 3): the body's origin and the tips of its three axes at output time i (global,
        m), each ``length`` long (default: the glyph's largest half side, times 1.5)."""
        length = 1.5 * float(np.max(self.half_size)) if length is None else float(length)
        return np.vstack([self.position[i], self.position[i] + length * self.rotation[i].T])


def glyph_surface(glyph: Glyph, half_size) -> tuple[np.ndarray, list[np.ndarray]]:
    """(vertices in the body's axes (k, 3), faces) of a glyph."""
    h = np.asarray(half_size, dtype=float)
    if glyph is Glyph.BOX:
        corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float) * h
        faces = [np.array(f) for f in ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4),
                                       (1, 5, 7, 3))]
        return corners, faces
    phi = 2 * np.pi * np.arange(DISC_SIDES) / DISC_SIDES
    ring = np.column_stack([h[0] * np.cos(phi), np.zeros(DISC_SIDES), h[0] * np.sin(phi)])
    vertices = np.vstack([ring - [0.0, h[1], 0.0], ring + [0.0, h[1], 0.0]])
    n = DISC_SIDES
    sides = [np.array([j, (j + 1) % n, n + (j + 1) % n, n + j]) for j in range(n)]
    return vertices, [np.arange(n), np.arange(n, 2 * n)] + sides


def box_of_inertia(mass: float, inertia, fallback: float) -> np.ndarray:
    """Half sides (3,) m of the uniform box with this mass (kg) and principal inertias (kg m^2)
    about its axes; a cube of side ``fallback`` when they give none (a point mass)."""
    J = np.asarray(inertia, dtype=float)
    squares = 6.0 * (J.sum() - 2.0 * J) / mass if mass > 0 else np.zeros(3)
    if mass <= 0 or np.any(squares <= 0):
        return np.full(3, 0.5 * fallback)
    return 0.5 * np.sqrt(squares)


def rigid_bodies(state: RunState, scale: float = 1.0) -> list[RigidBody]:
    """The hub, a moving base and every tip body of a recorded run (see the module doc);
    ``scale`` magnifies the tips' deflections."""
    extent = max((float(np.max(np.ptp(b.centre_line.reshape(-1, 3), axis=0))) for b in state.beams), default=1.0) or 1.0
    radius = state.hub_radius if state.hub_radius > 0 else 0.05 * extent
    nt = state.times.size
    bodies = [RigidBody("hub", np.asarray(state.hub_origin), np.asarray(state.hub_axes), Glyph.DISC,
                        np.array([radius, DISC_HALF_THICKNESS * radius, radius]))]
    if np.ptp(state.base_origin, axis=0).any() or np.ptp(state.base_axes.reshape(nt, 9), axis=0).any():
        bodies.append(RigidBody("base", np.asarray(state.base_origin), np.asarray(state.base_axes), Glyph.BOX,
                                np.full(3, radius)))
    for k, beam in enumerate(state.beams):
        if beam.tip_body is None:
            continue
        tip = beam.centre_line[:, -1]
        if scale != 1.0:
            tip = tip + (scale - 1.0) * state.displacement(k)[:, -1]
        m, n = beam.m[:, -1], beam.n[:, -1]
        rotation = np.stack([np.cross(m, n), m, n], axis=2)  # columns tau, m, n
        offset = np.asarray(beam.tip_body["offset"], dtype=float)
        half = box_of_inertia(beam.tip_body["mass"], beam.tip_body["inertia"], float(beam.width[-1]))
        bodies.append(RigidBody(f"tip_body_{beam.name}", tip + rotation @ offset, rotation, Glyph.BOX, half))
    return bodies
