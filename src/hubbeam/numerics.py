"""Small numerical helpers shared by the system and solver layers."""

from __future__ import annotations

import numpy as np


def central_difference_jacobian(fun, z: np.ndarray, steps: np.ndarray) -> np.ndarray:
    """d fun / dz by central differences, column i with step ``steps[i]``."""
    z = np.asarray(z, dtype=float)
    columns = []
    for i in range(z.size):
        e = np.zeros_like(z)
        e[i] = steps[i]
        columns.append((np.asarray(fun(z + e)) - np.asarray(fun(z - e))) / (2.0 * steps[i]))
    return np.array(columns).T


def relative_steps(z: np.ndarray, rel: float = 1e-7) -> np.ndarray:
    """Difference steps rel * max(1, |z_i|)."""
    return rel * np.maximum(1.0, np.abs(z))
