"""Assembly of element blocks into LAPACK band storage or dense matrices.

Band storage (as scipy.linalg.solve_banded takes it): ab[ku + i - j, j] = A[i, j].
Element e of a beam couples the 16 coordinates starting at offset + 8 e.
"""

from __future__ import annotations

import numpy as np
from numba import njit
from scipy.linalg.lapack import dgbtrf, dgbtrs, dgetrf, dgetrs


@njit(cache=True)
def add_element_blocks_banded(ab, blocks, offset, ku, scale):
    """ab += scale * (element blocks placed at offset + 8 e)."""
    for e in range(blocks.shape[0]):
        o = offset + 8 * e
        for i in range(16):
            for j in range(16):
                ab[ku + (o + i) - (o + j), o + j] += scale * blocks[e, i, j]


@njit(cache=True)
def add_element_blocks_dense(A, blocks, offset, scale):
    """A += scale * (element blocks placed at offset + 8 e)."""
    for e in range(blocks.shape[0]):
        o = offset + 8 * e
        for i in range(16):
            for j in range(16):
                A[o + i, o + j] += scale * blocks[e, i, j]


@njit(cache=True)
def add_block_banded(ab: np.ndarray, rows: np.ndarray, cols: np.ndarray, block: np.ndarray, ku: int) -> None:
    """ab += block placed at the given global rows and columns (entries must lie in the band)."""
    for a, i in enumerate(rows):
        for b, j in enumerate(cols):
            if block[a, b] != 0.0:
                ab[ku + i - j, j] += block[a, b]


def banded_to_dense(ab: np.ndarray, kl: int, ku: int) -> np.ndarray:
    """Dense copy of a band-stored matrix (for tests and small problems)."""
    n = ab.shape[1]
    A = np.zeros((n, n))
    for j in range(n):
        for i in range(max(0, j - ku), min(n, j + kl + 1)):
            A[i, j] = ab[ku + i - j, j]
    return A


class BandMatrix:
    """A square matrix in LAPACK general-band storage with kl = ku = ``bandwidth`` (the
    gbtrf layout: ``bandwidth`` spare rows on top, A[i, j] at ab[2 bw + i - j, j])."""

    def __init__(self, ab: np.ndarray, bandwidth: int) -> None:
        self.ab, self.bandwidth = ab, bandwidth

    def factorise(self) -> "Factorisation":
        lu, piv, info = dgbtrf(self.ab, self.bandwidth, self.bandwidth)
        if info != 0:
            raise np.linalg.LinAlgError(f"singular matrix (zero pivot in column {info})")
        bw = self.bandwidth
        return Factorisation(lambda rhs: dgbtrs(lu, bw, bw, rhs, piv)[0])

    def to_dense(self) -> np.ndarray:
        return banded_to_dense(self.ab[self.bandwidth :], self.bandwidth, self.bandwidth)


class DenseMatrix:
    """A small dense square matrix (LAPACK getrf/getrs)."""

    def __init__(self, a: np.ndarray) -> None:
        self.a = a

    def factorise(self) -> "Factorisation":
        lu, piv, info = dgetrf(self.a)
        if info != 0:
            raise np.linalg.LinAlgError(f"singular matrix (zero pivot in column {info})")
        return Factorisation(lambda rhs: dgetrs(lu, piv, rhs)[0])

    def to_dense(self) -> np.ndarray:
        return self.a


class Factorisation:
    """An LU factorisation: ``solve(rhs)``."""

    def __init__(self, solve) -> None:
        self.solve = solve
