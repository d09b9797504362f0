"""Band storage and its LAPACK LU (called from compiled code and by BandMatrix), against dense solves."""

import numpy as np

from hubbeam.system.assembly import BandMatrix, band_factor, band_solve, banded_to_dense


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
    x = BandMatrix(ab, bw).factorise().solve(b)
    assert np.allclose(A @ x, b, rtol=0, atol=1e-10)
    assert np.array_equal(ab, before)
