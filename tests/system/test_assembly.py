"""Band and bordered band storage and their LU (LAPACK from compiled code; a Schur complement on the border), against dense solves."""

import numpy as np
import pytest

from hubbeam.system.assembly import BorderedBandMatrix, band_factor, band_solve, banded_to_dense


def random_band(n, bw, seed):
    rng = np.random.default_rng(seed)
    ab = np.zeros((3 * bw + 1, n), order="F")
    for j in range(n):
        for i in range(max(0, j - bw), min(n, j + bw + 1)):
            ab[2 * bw + i - j, j] = rng.normal()
    return ab


def test_band_lu_solves_like_a_dense_solve():
    n, bw = 40, 6
    ab = random_band(n, bw, 0)
    A = banded_to_dense(ab[bw:], bw, bw)
    b = np.random.default_rng(1).normal(size=n)
    ipiv = np.zeros(n, dtype=np.int32)
    assert band_factor(ab, bw, bw, ipiv) == 0
    x = b.copy()
    assert band_solve(ab, bw, bw, ipiv, x) == 0
    assert np.allclose(x, np.linalg.solve(A, b), rtol=1e-10, atol=1e-12)


def test_band_lu_reports_a_singular_matrix():
    n, bw = 10, 2
    ab = random_band(n, bw, 2)
    ab[:, 4] = 0.0  # a zero column
    assert band_factor(ab, bw, bw, np.zeros(n, dtype=np.int32)) == 5


def test_band_matrix_factorisation_solves_and_keeps_its_matrix():
    n, bw = 30, 4
    ab = random_band(n, bw, 3)
    before = ab.copy()
    A = banded_to_dense(ab[bw:], bw, bw)
    b = np.random.default_rng(4).normal(size=n)
    m = BorderedBandMatrix(ab, bw, np.zeros((0, n)), np.zeros((n, 0)), np.zeros((0, 0)))
    x = m.factorise().solve(b)
    assert np.allclose(A @ x, b, rtol=0, atol=1e-10)
    assert np.array_equal(ab, before)


@pytest.mark.parametrize("border", [1, 2, 3, 7])
def test_bordered_matrix_solves_like_the_dense_matrix(border):
    """Dense border rows, columns and corner around a band (the hub angle and drive multiplier,
    or a moving base's coordinates and constraints besides, coupling to several beams): the Schur-complement solve equals a dense solve."""
    n, bw = 30, 4
    rng = np.random.default_rng(7)
    ab = random_band(n, bw, 5)
    m = BorderedBandMatrix(ab, bw, rng.normal(size=(border, n)), rng.normal(size=(n, border)),
                           rng.normal(size=(border, border)) + 5 * np.eye(border))
    A = m.to_dense()
    assert A.shape == (n + border, n + border)
    assert np.allclose(A[border:, border:], banded_to_dense(ab[bw:], bw, bw))
    b = rng.normal(size=n + border)
    assert np.allclose(A @ m.factorise().solve(b), b, rtol=0, atol=1e-9)
    m.add(0, border + 3, 2.5)
    m.add(border + 3, border + 2, -1.0)
    A2 = A.copy()
    A2[0, border + 3] += 2.5
    A2[border + 3, border + 2] += -1.0
    assert np.allclose(m.to_dense(), A2)
