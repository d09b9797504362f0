"""Where every unknown of a system lives: the one owner of offsets.

Parts declare how many coordinates they have and how many constraints they bring;
:class:`Layout` places them:

- coordinates  x = [base (0 or 7), theta, (psi_1, q_1), (psi_2, q_2), ..., w]: the base's
  position and Euler parameters (a free base, or one that follows a table), the hub angle,
  then for every beam its joint angles psi_k (0 to 3) and its own coordinates q_k, last the
  controllers' coordinates w (the time integrals of their states: the states are w',
  :mod:`hubbeam.system.controllers`);
- multipliers  lambda = [norm (1), base (6), drive (1), (lock_1, clamp_1 (6)), (lock_2,
  clamp_2 (6)), ...]: the Euler parameters' norm (a base with coordinates), the base's six
  driving constraints (a base that follows a table, or a free base held for statics), the
  hub's drive (a held hub), and for every beam the locks of its latched joint angles (0 or
  more; :mod:`hubbeam.system.joints`) and its clamp when its formulation is clamped to its
  root frame by constraints (ANCF; an FFR beam uses its root frame as its floating frame and
  has none);
- Newton unknowns z = [base, theta, mu_norm, mu_base, mu_drive, w, (psi_1, mu_lock_1, mu_clamp_1,
  q_1), ...].

The leading entries (the base, theta, the multipliers of their constraints and the
controllers' coordinates, which read sensors anywhere) couple to every beam; the rest of the Newton matrix is block-diagonal over the beams (a beam that
hangs on another's tip couples to its parent's block), each block banded for an ANCF beam.
With several beams, or a base with coordinates, the leading entries are the *border*,
eliminated by a Schur complement (:class:`hubbeam.system.assembly.BorderedBandMatrix`); a
single beam on a fixed base without controllers keeps them in the band (theta reaches the
root coordinates 14 entries on) and the border is empty. Nothing else in the package computes an offset into x,
lambda or z: it asks the layout (``z_of_x``, ``z_of_lambda`` map every entry of x and
lambda to its place in z).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

#: equations of the clamp of a beam root to its frame (position 3, tangent 2, twist 1)
CLAMP_EQUATIONS = 6
#: coordinates of a base that moves: its position (3) and Euler parameters (4)
BASE_COORDINATES = 7
#: driving constraints of a base held or following a table: position (3) and rotation (3)
BASE_DRIVES = 6


@dataclass(frozen=True)
class Layout:
    """The unknowns of a system: ``beam_dofs[k]`` coordinates of beam k, ``joint_dofs[k]`` joint
    angles at its root, ``locks[k]`` multipliers of its latched joint angles and ``clamped[k]``
    (its six clamp multipliers); ``held``: the hub angle is prescribed (or fixed) by a driving
    constraint; ``base_moves``: the base has coordinates (free or following a table);
    ``base_held``: those coordinates are driven by six constraints (a table, or a free base
    held for statics); ``controller_states``: the controllers' states (one coordinate each,
    last in x)."""

    beam_dofs: tuple[int, ...]
    held: bool
    joint_dofs: tuple[int, ...] | None = None
    clamped: tuple[bool, ...] | None = None
    base_moves: bool = False
    base_held: bool = False
    locks: tuple[int, ...] | None = None
    controller_states: int = 0

    def __post_init__(self) -> None:
        n = len(self.beam_dofs)
        if self.joint_dofs is None:
            object.__setattr__(self, "joint_dofs", (0,) * n)
        if self.clamped is None:
            object.__setattr__(self, "clamped", (True,) * n)
        if self.locks is None:
            object.__setattr__(self, "locks", (0,) * n)
        if len(self.joint_dofs) != n or len(self.clamped) != n or len(self.locks) != n:
            raise ValueError("one joint count, one lock count and one clamp flag per beam")
        if any(lock > joints for lock, joints in zip(self.locks, self.joint_dofs)):
            raise ValueError("a beam has more locks than joint angles")
        if self.base_held and not self.base_moves:
            raise ValueError("a base without coordinates cannot be held by constraints")

    # ------------------------------------------------------------ sizes
    @property
    def beams(self) -> int:
        return len(self.beam_dofs)

    @property
    def base_dofs(self) -> int:
        """Coordinates of the base: 7 when it moves, else 0."""
        return BASE_COORDINATES if self.base_moves else 0

    @property
    def frame_dofs(self) -> int:
        """Coordinates of the frames every beam hangs on: the base's and the hub angle."""
        return self.base_dofs + 1

    @property
    def border_constraints(self) -> int:
        """Constraints on the frames' coordinates: the norm, the base's drives, the hub's drive."""
        return int(self.base_moves) + BASE_DRIVES * int(self.base_held) + int(self.held)

    def block_size(self, k: int) -> int:
        """Beam k's entries in z: its joint angles, lock and clamp multipliers and coordinates."""
        return self.joint_dofs[k] + self.beam_constraints(k) + self.beam_dofs[k]

    def beam_constraints(self, k: int) -> int:
        """Beam k's multipliers: its joints' locks and its clamp's."""
        return self.locks[k] + CLAMP_EQUATIONS * int(self.clamped[k])

    @property
    def nx(self) -> int:
        """Coordinates: the frames' and every beam's (joint angles included)."""
        return self.frame_dofs + sum(self.joint_dofs) + sum(self.beam_dofs) + self.controller_states

    @property
    def n_lambda(self) -> int:
        """Constraints: the frames' and every beam's (locks and clamps)."""
        return self.border_constraints + sum(self.beam_constraints(k) for k in range(self.beams))

    @property
    def nz(self) -> int:
        return self.nx + self.n_lambda

    @property
    def leading(self) -> int:
        """Entries of z before the beams' blocks: the frames' coordinates and constraints and
        the controllers' coordinates."""
        return self.frame_dofs + self.border_constraints + self.controller_states

    @property
    def border(self) -> int:
        """Leading entries of z kept out of the band: all of them when several beams share
        them, the base moves or controllers read sensors (or there is no beam); none for one
        beam on a fixed base without controllers (the band holds them)."""
        return 0 if (self.beams == 1 and not self.base_moves and not self.controller_states) else self.leading

    # ------------------------------------------------------------ where things are
    @property
    def theta(self) -> int:
        """The hub angle in x."""
        return self.base_dofs

    @property
    def base_x(self) -> slice:
        """The base's coordinates in x (empty when it does not move): position, then Euler parameters."""
        return slice(0, self.base_dofs)

    @property
    def beams_x(self) -> slice:
        """Every beam's coordinates and joint angles in x."""
        return slice(self.frame_dofs, self.nx - self.controller_states)

    @property
    def controllers_x(self) -> slice:
        """The controllers' coordinates in x (last)."""
        return slice(self.nx - self.controller_states, self.nx)

    def joint_x(self, k: int) -> slice:
        """Beam k's joint angles in x."""
        start = self.frame_dofs + sum(self.joint_dofs[j] + self.beam_dofs[j] for j in range(k))
        return slice(start, start + self.joint_dofs[k])

    def beam_x(self, k: int) -> slice:
        """Beam k's coordinates in x."""
        start = self.joint_x(k).stop
        return slice(start, start + self.beam_dofs[k])

    @property
    def norm_lambda(self) -> int | None:
        """The Euler parameters' norm constraint in lambda (None for a fixed base)."""
        return 0 if self.base_moves else None

    @property
    def base_lambda(self) -> slice | None:
        """The base's six driving constraints in lambda (None when not held)."""
        return slice(1, 1 + BASE_DRIVES) if self.base_held else None

    @property
    def drive_lambda(self) -> int | None:
        """Index of the hub's drive multiplier in lambda (None for a free hub)."""
        return self.border_constraints - 1 if self.held else None

    def lock_lambda(self, k: int) -> slice:
        """Beam k's lock multipliers in lambda (its latched joint angles'; empty without)."""
        start = self.border_constraints + sum(self.beam_constraints(j) for j in range(k))
        return slice(start, start + self.locks[k])

    def clamp_lambda(self, k: int) -> slice:
        """Beam k's clamp multipliers in lambda (empty for an unclamped beam)."""
        start = self.lock_lambda(k).stop
        return slice(start, start + CLAMP_EQUATIONS * int(self.clamped[k]))

    def beam_z(self, k: int) -> slice:
        """Beam k's block in z: its joint angles, lock and clamp multipliers, then its coordinates."""
        start = self.leading + sum(self.block_size(j) for j in range(k))
        return slice(start, start + self.block_size(k))

    @property
    def z_of_x(self) -> np.ndarray:
        """z index of every entry of x."""
        out = np.empty(self.nx, dtype=np.int64)
        out[: self.frame_dofs] = np.arange(self.frame_dofs)
        for k in range(self.beams):
            z = self.beam_z(k).start
            nj = self.joint_dofs[k]
            out[self.joint_x(k)] = np.arange(z, z + nj)
            q0 = z + nj + self.beam_constraints(k)
            out[self.beam_x(k)] = np.arange(q0, q0 + self.beam_dofs[k])
        w0 = self.frame_dofs + self.border_constraints
        out[self.controllers_x] = np.arange(w0, w0 + self.controller_states)
        return out

    @property
    def z_of_lambda(self) -> np.ndarray:
        """z index of every entry of lambda."""
        out = np.empty(self.n_lambda, dtype=np.int64)
        nb = self.border_constraints
        out[:nb] = np.arange(self.frame_dofs, self.frame_dofs + nb)
        for k in range(self.beams):
            z = self.beam_z(k).start + self.joint_dofs[k]
            n = self.beam_constraints(k)
            start = self.lock_lambda(k).start
            out[start:start + n] = np.arange(z, z + n)
        return out

    # ------------------------------------------------------------ moving between x, lambda and z
    def to_z(self, x_part: np.ndarray, lam_part: np.ndarray) -> np.ndarray:
        """z from an x-shaped and a lambda-shaped vector."""
        z = np.empty(self.nz)
        z[self.z_of_x] = x_part
        z[self.z_of_lambda] = lam_part
        return z

    def split_z(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(x part, lambda part) of a z-shaped vector."""
        return z[self.z_of_x], z[self.z_of_lambda]

    def with_held(self, held: bool, base_held: bool | None = None) -> "Layout":
        """The same unknowns with the hub (and the base) held or not."""
        return replace(self, held=held, base_held=self.base_held if base_held is None else base_held)

    def lambda_in(self, other: "Layout", lam: np.ndarray) -> np.ndarray:
        """Multipliers ``lam`` of this layout moved to ``other`` (the same beams): the clamps',
        the locks' (of joints locked in both) and the norm's carried over, constraints ``other``
        lacks dropped, ones it adds zero."""
        lam = np.asarray(lam, dtype=float)
        out = np.zeros(other.n_lambda)
        for k in range(self.beams):
            out[other.clamp_lambda(k)] = lam[self.clamp_lambda(k)]
            n = min(self.locks[k], other.locks[k])
            out[other.lock_lambda(k).start:other.lock_lambda(k).start + n] = lam[self.lock_lambda(k)][:n]
        if self.norm_lambda is not None and other.norm_lambda is not None:
            out[other.norm_lambda] = lam[self.norm_lambda]
        if self.base_lambda is not None and other.base_lambda is not None:
            out[other.base_lambda] = lam[self.base_lambda]
        if self.drive_lambda is not None and other.drive_lambda is not None:
            out[other.drive_lambda] = lam[self.drive_lambda]
        return out
