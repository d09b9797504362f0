"""Shared fixtures: the reference plate of conventions.md and small helpers."""

import numpy as np
import pytest

from hubbeam.elements.section import Section, saint_venant_torsion_constant

B, H, E, NU, RHO, L = 0.05, 0.0025, 70e9, 0.33, 2700.0, 1.45


def plate(width=B, thickness=H) -> Section:
    return Section(width, thickness, RHO, E, E / (2 * (1 + NU)), saint_venant_torsion_constant(width, thickness))


@pytest.fixture
def section() -> Section:
    return plate()


def rotation(axis, angle) -> np.ndarray:
    """Rodrigues rotation matrix (independent of the code's frame construction)."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def central_difference(fun, x, h):
    """Column-wise central difference of a vector function."""
    x = np.asarray(x, float)
    cols = []
    for i in range(x.size):
        e = np.zeros_like(x)
        e[i] = h
        cols.append((np.asarray(fun(x + e)) - np.asarray(fun(x - e))) / (2 * h))
    return np.array(cols).T
