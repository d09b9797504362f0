"""Where every unknown of a hub-beam system lives: the one owner of offsets.

Parts declare how many coordinates they have (the hub: its angle theta; beam k: the
n_k coordinates of its formulation) and how many constraints they bring (each beam's
clamp: six; a held hub: the drive theta = theta_p(t)). :class:`Layout` places them:

- coordinates  x = [theta, q_1, q_2, ...]
- multipliers  lambda = [lambda_drive (held hub only), lambda_clamp_1 (6), lambda_clamp_2 (6), ...]
- Newton unknowns z = [theta, mu_drive, (mu_clamp_1, q_1), (mu_clamp_2, q_2), ...]

Theta and, for a held hub, the drive multiplier couple to every beam; the rest of the
Newton matrix is block-diagonal over the beams, each block banded for an ANCF beam. With
several beams these leading entries are the *border*, eliminated by a Schur complement
(:class:`hubbeam.system.assembly.BorderedBandMatrix`); with one beam they fit in the band
(theta reaches the root coordinates 14 entries on) and the border is empty. Nothing else in the package computes
an offset into x, lambda or z: it asks the layout (``z_of_x``, ``z_of_lambda`` map every
entry of x and lambda to its place in z).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: equations of the clamp of a beam root to the hub (position 3, tangent 2, twist 1)
CLAMP_EQUATIONS = 6


@dataclass(frozen=True)
class Layout:
    """The unknowns of a hub carrying beams with ``beam_dofs[k]`` coordinates each; ``held``:
    the hub angle is prescribed (or fixed) by a driving constraint."""

    beam_dofs: tuple[int, ...]
    held: bool

    # ------------------------------------------------------------ sizes
    @property
    def beams(self) -> int:
        return len(self.beam_dofs)

    @property
    def nx(self) -> int:
        """Coordinates: the hub angle and every beam's."""
        return 1 + sum(self.beam_dofs)

    @property
    def n_lambda(self) -> int:
        """Constraints: every beam's clamp and, for a held hub, the drive."""
        return int(self.held) + CLAMP_EQUATIONS * self.beams

    @property
    def nz(self) -> int:
        return self.nx + self.n_lambda

    @property
    def leading(self) -> int:
        """Entries of z before the beams' blocks: theta and, for a held hub, the drive multiplier."""
        return 1 + int(self.held)

    @property
    def border(self) -> int:
        """Leading entries of z kept out of the band: theta and the drive multiplier when
        several beams share them; none for one beam (the band holds them)."""
        return 0 if self.beams == 1 else self.leading

    # ------------------------------------------------------------ where things are
    #: the hub angle in x
    theta = 0
    #: every beam coordinate in x
    beams_x = slice(1, None)

    def beam_x(self, k: int) -> slice:
        """Beam k's coordinates in x."""
        start = 1 + sum(self.beam_dofs[:k])
        return slice(start, start + self.beam_dofs[k])

    def clamp_lambda(self, k: int) -> slice:
        """Beam k's clamp multipliers in lambda."""
        start = int(self.held) + CLAMP_EQUATIONS * k
        return slice(start, start + CLAMP_EQUATIONS)

    @property
    def drive_lambda(self) -> int | None:
        """Index of the drive multiplier in lambda (None for a free hub)."""
        return 0 if self.held else None

    def beam_z(self, k: int) -> slice:
        """Beam k's block in z: its clamp multipliers, then its coordinates."""
        start = self.leading + sum(CLAMP_EQUATIONS + n for n in self.beam_dofs[:k])
        return slice(start, start + CLAMP_EQUATIONS + self.beam_dofs[k])

    @property
    def z_of_x(self) -> np.ndarray:
        """z index of every entry of x."""
        out = np.empty(self.nx, dtype=np.int64)
        out[0] = 0
        for k in range(self.beams):
            z = self.beam_z(k)
            out[self.beam_x(k)] = np.arange(z.start + CLAMP_EQUATIONS, z.stop)
        return out

    @property
    def z_of_lambda(self) -> np.ndarray:
        """z index of every entry of lambda."""
        out = np.empty(self.n_lambda, dtype=np.int64)
        if self.held:
            out[0] = 1
        for k in range(self.beams):
            z = self.beam_z(k)
            out[self.clamp_lambda(k)] = np.arange(z.start, z.start + CLAMP_EQUATIONS)
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

    def with_held(self, held: bool) -> "Layout":
        return Layout(self.beam_dofs, held)
