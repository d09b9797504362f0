"""The base: the hub's support, fixed in space, a free rigid body, or moved by a table.

The base axes turn with R(t) and its origin O_b is at r_b(t) (global); a point p given in
base axes is at r_b + R p. The hub hangs on the base at ``hub.position`` (base axes) turned
by ``hub.orientation`` (R_h), so the hub's frame at theta is R R_h A_h(theta) (docs/base.md).

- ``fixed``: a constant pose (the initial position and rotation); no coordinates. With both
  zero it is today's hub on a fixed vertical axis.
- ``free``: a rigid body with six degrees of freedom in seven coordinates, the position of O_b
  and the Euler parameters e of R (:mod:`hubbeam.system.frames`, link ``FREE``), whose norm a
  constraint fixes; its mass and inertia (about its centre of mass, base axes) at the centre
  of mass c_b (base axes). Euler parameters have no singular attitude: a free body tumbles
  through any number of turns about any axis with one chart. Statics hold it at its initial
  pose by the six constraints of a table.
- ``table``: the same seven coordinates, driven by six constraints to the position and
  rotation of a table (:mod:`hubbeam.system.base_laws`).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np

from hubbeam.system.chains import Chain, constant, free
from hubbeam.system.rotations import euler_parameters, rotation_vector_matrix


class BaseMotion(enum.Enum):
    """How the base moves."""

    FIXED = "fixed"
    FREE = "free"
    TABLE = "table"


def check_inertia(inertia: np.ndarray, what: str = "inertia") -> np.ndarray:
    """A rigid body's inertia tensor (3 x 3, symmetric, positive definite, every principal
    moment at most the sum of the other two), or ValueError saying which condition fails."""
    J = np.asarray(inertia, dtype=float)
    if J.shape == (3,):
        J = np.diag(J)
    if J.shape != (3, 3) or not np.all(np.isfinite(J)):
        raise ValueError(f"{what}: three principal moments or a symmetric 3 x 3 matrix of finite numbers")
    if not np.allclose(J, J.T, rtol=1e-12, atol=1e-12 * max(np.max(np.abs(J)), 1e-300)):
        raise ValueError(f"{what}: the matrix is not symmetric")
    moments = np.linalg.eigvalsh(0.5 * (J + J.T))
    if not moments[0] > 0.0:
        raise ValueError(f"{what}: not positive definite (principal moments {', '.join(f'{m:.6g}' for m in moments)})")
    if moments[2] > (moments[0] + moments[1]) * (1.0 + 1e-9):
        raise ValueError(f"{what}: not a rigid body's (the principal moment {moments[2]:.6g} exceeds the sum of the "
                         f"other two, {moments[0]:.6g} + {moments[1]:.6g})")
    return 0.5 * (J + J.T)


@dataclass(frozen=True)
class Base:
    """The hub's support (SI units; rotations as rotation vectors in rad).

    ``position`` and ``rotation``: the pose at t = 0 (a fixed base keeps it); ``velocity``
    (m/s, global) and ``angular_velocity`` (rad/s, base axes): a free base's at t = 0;
    ``mass`` (kg), ``inertia`` (kg m^2, about the centre of mass, base axes) and
    ``centre_of_mass`` (m, base axes): a free base's body; ``table``: a table base's
    :class:`~hubbeam.system.base_laws.PoseTable`; ``torque``: a free base's attitude law
    (:class:`~hubbeam.system.base_laws.AttitudeLaw`) or None."""

    motion: BaseMotion = BaseMotion.FIXED
    position: tuple = (0.0, 0.0, 0.0)
    rotation: tuple = (0.0, 0.0, 0.0)
    velocity: tuple = (0.0, 0.0, 0.0)
    angular_velocity: tuple = (0.0, 0.0, 0.0)
    mass: float = 0.0
    inertia: tuple = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    centre_of_mass: tuple = (0.0, 0.0, 0.0)
    table: object = None
    torque: object = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "motion", BaseMotion(self.motion))
        for name in ("position", "rotation", "velocity", "angular_velocity", "centre_of_mass"):
            value = tuple(float(v) for v in np.ravel(np.asarray(getattr(self, name), dtype=float)))
            if len(value) != 3 or not all(math.isfinite(v) for v in value):
                raise ValueError(f"base {name}: three finite numbers")
            object.__setattr__(self, name, value)
        inertia = np.asarray(self.inertia, dtype=float)
        if inertia.shape == (3,):
            inertia = np.diag(inertia)
        if self.motion == BaseMotion.FREE:
            if not (math.isfinite(self.mass) and self.mass > 0.0):
                raise ValueError(f"base mass: must be > 0 (got {self.mass})")
            inertia = check_inertia(inertia, "base inertia")
        if self.motion == BaseMotion.TABLE and self.table is None:
            raise ValueError("base table: a table base needs its table")
        object.__setattr__(self, "inertia", tuple(map(tuple, inertia)))

    @property
    def moves(self) -> bool:
        """The base has coordinates (free, or following a table)."""
        return self.motion != BaseMotion.FIXED

    @property
    def initial_rotation(self) -> np.ndarray:
        """R(0) (3 x 3)."""
        return rotation_vector_matrix(self.rotation)

    def initial_coordinates(self) -> np.ndarray:
        """[r_b, e] at t = 0 (a moving base's 7 coordinates)."""
        if self.table is not None:
            position, R = self.table.pose(0.0)
            return np.concatenate([position, euler_parameters(R)])
        return np.concatenate([self.position, euler_parameters(self.initial_rotation)])

    def chain(self, first: int = 0) -> Chain:
        """The base frame (origin O_b, base axes) as a chain: constant, or FREE with its 7
        coordinates from x[first]."""
        if self.moves:
            return Chain((free(first),))
        return Chain((constant(self.position, self.initial_rotation),))

    def inertia_matrix(self) -> np.ndarray:
        return np.asarray(self.inertia, dtype=float)


@dataclass(frozen=True)
class HubPlacement:
    """Where the hub sits on the base: ``position`` (m, base axes: the hub origin O on its axis)
    and ``orientation`` (rotation vector, rad, turning the base axes into the hub's at theta = 0)."""

    position: tuple = (0.0, 0.0, 0.0)
    orientation: tuple = (0.0, 0.0, 0.0)

    def link(self):
        return constant(self.position, rotation_vector_matrix(self.orientation))

    @property
    def rotation(self) -> np.ndarray:
        return rotation_vector_matrix(self.orientation)
