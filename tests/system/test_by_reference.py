"""A value passed by reference between compiled functions (:mod:`hubbeam.system.by_reference`):
read back whole, and with reference counts that balance in functions that count them and in
functions that do not."""

import sys

import numpy as np
from numba import njit

from hubbeam.system.by_reference import address_of, held_at


@njit(_nrt=False)
def _sum_at_uncounted(pointer):
    first, second, scale = held_at(pointer)
    return scale * (first.sum() + second[1, 2])


@njit
def _sum_at_counted(pointer):
    first, second, scale = held_at(pointer)
    return scale * (first.sum() + second[1, 2])


@njit
def _calls(value, n, counted):
    pointer = address_of(value)
    total = 0.0
    for _ in range(n):
        total += _sum_at_counted(pointer) if counted else _sum_at_uncounted(pointer)
    return total


def test_a_value_read_by_reference_is_the_value_and_its_references_balance():
    """A tuple of two arrays and a float, read 1000 times by reference in a function that counts
    references and in one that does not: the sum of what was read is 1000 times the value's, and
    each array's reference count is what it was before (a read that released a reference it did
    not take drops it by one a call, and later frees the array under its owner)."""
    first, second = np.arange(5.0), np.arange(12.0).reshape(3, 4)
    value = (first, second, 2.0)
    expected = 2.0 * (first.sum() + second[1, 2])
    for counted in (True, False):
        before = sys.getrefcount(first), sys.getrefcount(second)
        assert _calls(value, 1000, counted) == 1000 * expected
        assert (sys.getrefcount(first), sys.getrefcount(second)) == before
