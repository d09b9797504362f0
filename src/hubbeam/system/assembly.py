"""Assembly of element blocks into LAPACK band storage or dense matrices, and their LU.

Band storage (as scipy.linalg.solve_banded takes it): ab[ku + i - j, j] = A[i, j].
Element e of a beam couples the 16 coordinates starting at offset + 8 e.
The band LU (:func:`band_factor`, :func:`band_solve`) is LAPACK's dgbtrf from scipy's
bundled LAPACK, callable from compiled code, and the loops of its dgbtrs compiled here; both
are used by :class:`BorderedBandMatrix` too. Its storage is gbtrf's: a Fortran-ordered array
of shape (2 kl + ku + 1, n) with A[i, j] at ab[kl + ku + i - j, j] and kl spare rows on top
for the fill-in of pivoting. Measured on this machine for n = 80, kl = ku = 15:
factorisation about 21 us (a numba port of dgbtf2 took as long).
"""

from __future__ import annotations

import llvmlite.binding as llvm
import numpy as np
from numba import njit, types
from numba.extending import get_cython_function_address

# The LAPACK routine is registered under a name of its own and called as an external
# function, so compiled callers refer to it by name and stay cacheable (a ctypes
# function pointer would bake this process's address into the cached code).
llvm.add_symbol("hubbeam_dgbtrf", get_cython_function_address("scipy.linalg.cython_lapack", "dgbtrf"))
_p = types.intp  # every argument is a pointer (Fortran calling convention)
_dgbtrf = types.ExternalFunction("hubbeam_dgbtrf", types.void(_p, _p, _p, _p, _p, _p, _p, _p))


@njit(cache=True)
def band_factor(ab, kl, ku, ipiv):
    """LU of the band matrix in ``ab`` (overwritten), pivots in ``ipiv`` (int32, n).
    Returns LAPACK's info: 0, or j > 0 when U[j-1, j-1] is exactly zero."""
    n = ab.shape[1]
    a = np.array([n, n, kl, ku, ab.shape[0], 0], dtype=np.int32)
    p = a.ctypes.data
    _dgbtrf(p, p + 4, p + 8, p + 12, ab.ctypes.data, p + 16, ipiv.ctypes.data, p + 20)
    return a[5]  # the array stays alive through the call


@njit(cache=True)
def band_solve(lu, kl, ku, ipiv, b):
    """Solve A x = b in place (b overwritten with x) with the factors of :func:`band_factor`:
    LAPACK's dgbtrs (no transpose, one right-hand side) in compiled loops, the same operations
    in the same order (row interchanges and L's columns, then U from the last row up). Calling
    dgbtrs itself cost more than its arithmetic on these sizes (about 0.7 us of call overhead
    at n = 17, measured). Returns 0 (dgbtrs's info)."""
    n = lu.shape[1]
    kv = kl + ku  # the diagonal's row
    if kl > 0:
        for j in range(n - 1):
            lm = min(kl, n - 1 - j)
            jp = ipiv[j] - 1
            bj = b[jp]
            if jp != j:
                b[jp] = b[j]
                b[j] = bj
            if bj != 0.0:
                for i in range(lm):
                    b[j + 1 + i] -= lu[kv + 1 + i, j] * bj
    for j in range(n - 1, -1, -1):
        if b[j] != 0.0:
            bj = b[j] / lu[kv, j]
            b[j] = bj
            i0 = max(0, j - kv)
            for i in range(i0, j):  # independent updates: any order gives the same numbers
                b[i] -= bj * lu[kv + i - j, j]
    return 0


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


def banded_to_dense(ab: np.ndarray, kl: int, ku: int) -> np.ndarray:
    """Dense copy of a band-stored matrix (for tests and small problems)."""
    n = ab.shape[1]
    A = np.zeros((n, n))
    for j in range(n):
        for i in range(max(0, j - ku), min(n, j + kl + 1)):
            A[i, j] = ab[ku + i - j, j]
    return A


class Factorisation:
    """An LU factorisation: ``solve(rhs)``."""

    def __init__(self, solve) -> None:
        self.solve = solve


@njit(cache=True)
def add_entry(ab, brow, bcol, bb, ku, i, j, value):
    """A[i, j] += value in bordered storage (border size bb.shape[0]; ``ku``: the row of the
    diagonal in ``ab``), i and j indices of the whole matrix."""
    nb = bb.shape[0]
    if i < nb:
        if j < nb:
            bb[i, j] += value
        else:
            brow[i, j - nb] += value
    elif j < nb:
        bcol[i - nb, j] += value
    else:
        ab[ku + i - j, j - nb] += value


@njit(cache=True)
def bordered_factor(ab, bw, ipiv, brow, bcol, bb, Y, schur):
    """Factorise the bordered matrix [[bb, brow], [bcol, B]] (B banded in ``ab``, overwritten
    by its LU): B^-1 bcol into the rows of ``Y`` (border x n), and the inverse of the Schur
    complement bb - brow B^-1 bcol (border x border) into ``schur``. Returns 0, or
    j > 0 when B's pivot j is zero, or -1 when the Schur complement is singular."""
    info = band_factor(ab, bw, bw, ipiv)
    nb = bb.shape[0]
    if info != 0 or nb == 0:
        return info
    n = ab.shape[1]
    for j in range(nb):
        for i in range(n):
            Y[j, i] = bcol[i, j]
        band_solve(ab, bw, bw, ipiv, Y[j])
    S = np.empty((nb, nb))
    for a in range(nb):
        for b in range(nb):
            acc = bb[a, b]
            for i in range(n):
                acc -= brow[a, i] * Y[b, i]
            S[a, b] = acc
    if nb == 1:
        if S[0, 0] == 0.0 or not np.isfinite(S[0, 0]):
            return -1
        schur[0, 0] = 1.0 / S[0, 0]
        return 0
    if nb == 2:
        det = S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0]
        if det == 0.0 or not np.isfinite(det):
            return -1
        schur[0, 0] = S[1, 1] / det
        schur[0, 1] = -S[0, 1] / det
        schur[1, 0] = -S[1, 0] / det
        schur[1, 1] = S[0, 0] / det
        return 0
    return dense_inverse(S, schur)


@njit(cache=True)
def dense_inverse(S, out):
    """out = S^-1 by Gauss-Jordan elimination with partial pivoting (S is overwritten); -1 when
    S is singular (a zero or non-finite pivot), else 0. For the border's Schur complement
    (a moving base's coordinates and constraints with the hub's: up to about 17 unknowns) and
    the capacitance matrix of a column update (:mod:`hubbeam.solvers.column_update`)."""
    n = S.shape[0]
    for i in range(n):
        for j in range(n):
            out[i, j] = 1.0 if i == j else 0.0
    for c in range(n):
        p = c
        for i in range(c + 1, n):
            if abs(S[i, c]) > abs(S[p, c]):
                p = i
        pivot = S[p, c]
        if pivot == 0.0 or not np.isfinite(pivot):
            return -1
        if p != c:
            for j in range(n):
                S[c, j], S[p, j] = S[p, j], S[c, j]
                out[c, j], out[p, j] = out[p, j], out[c, j]
        inv = 1.0 / pivot
        for j in range(n):
            S[c, j] *= inv
            out[c, j] *= inv
        for i in range(n):
            if i != c:
                f = S[i, c]
                if f != 0.0:
                    for j in range(n):
                        S[i, j] -= f * S[c, j]
                        out[i, j] -= f * out[c, j]
    return 0


@njit(cache=True)
def bordered_solve(ab, bw, ipiv, brow, Y, schur, r, scratch):
    """Solve the factorised bordered system in place (``r`` overwritten with the solution);
    ``scratch`` (at least border long) holds the border's reduced right-hand side, so that a
    solve allocates nothing (the time loop solves two to three times a step)."""
    nb = schur.shape[0]
    interior = r[nb:]
    band_solve(ab, bw, bw, ipiv, interior)
    if nb == 0:
        return
    for a in range(nb):
        acc = r[a]
        for i in range(interior.shape[0]):
            acc -= brow[a, i] * interior[i]
        scratch[a] = acc
    for a in range(nb):
        acc = 0.0
        for b in range(nb):
            acc += schur[a, b] * scratch[b]
        r[a] = acc
    for i in range(interior.shape[0]):
        acc = 0.0
        for a in range(nb):
            acc += Y[a, i] * r[a]
        interior[i] -= acc


class BorderedBandMatrix:
    """A square matrix [[bb, brow], [bcol, B]] whose leading ``border`` rows and columns are
    dense (the frames' coordinates and constraints, which couple to every beam) and whose rest
    B is banded with kl = ku = ``bandwidth`` (LAPACK gbtrf storage in ``ab``: A[i, j] at
    ab[2 bw + i - j, j]). Solved by band LU of B and the Schur complement on the border."""

    def __init__(self, ab: np.ndarray, bandwidth: int, brow: np.ndarray, bcol: np.ndarray, bb: np.ndarray) -> None:
        self.ab, self.bandwidth, self.brow, self.bcol, self.bb = ab, bandwidth, brow, bcol, bb

    @classmethod
    def empty(cls, n: int, border: int, bandwidth: int) -> "BorderedBandMatrix":
        """Zero storage for an n x n matrix with the given border and bandwidth."""
        m = n - border
        return cls(np.zeros((3 * bandwidth + 1, m), order="F"), bandwidth, np.zeros((border, m)),
                   np.zeros((m, border)), np.zeros((border, border)))

    @property
    def border(self) -> int:
        return self.bb.shape[0]

    def add(self, i: int, j: int, value: float) -> None:
        """A[i, j] += value."""
        add_entry(self.ab, self.brow, self.bcol, self.bb, 2 * self.bandwidth, int(i), int(j), float(value))

    def factorise(self) -> "Factorisation":
        bw = self.bandwidth
        lu = np.array(self.ab, dtype=float, order="F")
        piv = np.zeros(lu.shape[1], dtype=np.int32)
        Y = np.empty((self.border, lu.shape[1]))
        schur = np.empty((self.border, self.border))
        scratch = np.empty(self.border)
        info = bordered_factor(lu, bw, piv, self.brow, self.bcol, self.bb, Y, schur)
        if info != 0:
            where = "the border of the frames' coordinates (Schur complement)" if info < 0 else f"column {info} of the band"
            raise np.linalg.LinAlgError(f"singular matrix (zero pivot in {where})")

        def solve(rhs):
            x = np.array(rhs, dtype=float)
            bordered_solve(lu, bw, piv, self.brow, Y, schur, x, scratch)
            return x

        return Factorisation(solve)

    def to_dense(self) -> np.ndarray:
        nb = self.border
        m = self.ab.shape[1]
        A = np.zeros((nb + m, nb + m))
        A[:nb, :nb] = self.bb
        A[:nb, nb:] = self.brow
        A[nb:, :nb] = self.bcol
        A[nb:, nb:] = banded_to_dense(self.ab[self.bandwidth :], self.bandwidth, self.bandwidth)
        return A
