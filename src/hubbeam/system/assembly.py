"""Assembly of element blocks into LAPACK band storage or dense matrices.

Band storage (as scipy.linalg.solve_banded takes it): ab[ku + i - j, j] = A[i, j].
Element e of a beam couples the 16 coordinates starting at offset + 8 e.
"""

from __future__ import annotations

import numpy as np
from numba import njit


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
