"""Small numerical helpers shared by the element, system and solver layers."""

from __future__ import annotations

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components


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


def coupled_groups(pattern: np.ndarray) -> list[np.ndarray]:
    """The groups of coordinates that the (n x n) boolean ``pattern`` couples (the connected
    components of its graph, an entry in either triangle linking two coordinates), each
    ascending, in the order of their first coordinate."""
    _, labels = connected_components(csr_matrix(np.asarray(pattern, dtype=bool)), directed=False)
    groups = [np.flatnonzero(labels == c) for c in np.unique(labels)]
    return sorted(groups, key=lambda g: g[0])
