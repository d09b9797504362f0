"""LAPACK band LU (dgbtrf/dgbtrs from scipy's bundled LAPACK) callable from compiled code.

Storage as LAPACK's gbtrf: a Fortran-ordered array ab of shape (2 kl + ku + 1, n) with
A[i, j] at ab[kl + ku + i - j, j] and kl spare rows on top for the fill-in of pivoting.
Measured on this machine for n = 80, kl = ku = 15: factorisation about 30 us, solve
about 4 us (a numba port of dgbtf2 took 57 us).
"""

from __future__ import annotations

import llvmlite.binding as llvm
import numpy as np
from numba import njit, types
from numba.extending import get_cython_function_address

# The LAPACK routines are registered under names of their own and called as external
# functions, so compiled callers refer to them by name and stay cacheable (a ctypes
# function pointer would bake this process's address into the cached code).
llvm.add_symbol("hubbeam_dgbtrf", get_cython_function_address("scipy.linalg.cython_lapack", "dgbtrf"))
llvm.add_symbol("hubbeam_dgbtrs", get_cython_function_address("scipy.linalg.cython_lapack", "dgbtrs"))
_p = types.intp  # every argument is a pointer (Fortran calling convention)
_dgbtrf = types.ExternalFunction("hubbeam_dgbtrf", types.void(_p, _p, _p, _p, _p, _p, _p, _p))
_dgbtrs = types.ExternalFunction("hubbeam_dgbtrs", types.void(_p, _p, _p, _p, _p, _p, _p, _p, _p, _p, _p))


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
    """Solve A x = b in place (b overwritten with x) with the factors of :func:`band_factor`."""
    n = lu.shape[1]
    # the last entry holds the character 'N' (no transpose) in its first byte (little-endian)
    a = np.array([n, kl, ku, 1, lu.shape[0], n, 0, ord("N")], dtype=np.int32)
    p = a.ctypes.data
    _dgbtrs(p + 28, p, p + 4, p + 8, p + 12, lu.ctypes.data, p + 16, ipiv.ctypes.data, b.ctypes.data, p + 20, p + 24)
    return a[6]
