"""Cubic Hermite shape functions and Gauss-Legendre rules on an element.

The paper interpolates both the centre line r0 and the twist angle theta_1 with the
same cubic Hermite functions (Eqs. 15-16):

    s1 = 1 - 3 xi^2 + 2 xi^3,   s2 = l (xi - 2 xi^2 + xi^3),
    s3 = 3 xi^2 - 2 xi^3,       s4 = l (-xi^2 + xi^3),        xi = x / l.

All derivatives returned here are with respect to the physical coordinate x (m).
"""

from __future__ import annotations

import numpy as np


def hermite(xi: np.ndarray, length: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Values, first and second x-derivatives of (s1, s2, s3, s4) at ``xi`` in [0, 1].

    Returns three arrays of shape (len(xi), 4): s, ds/dx (1/m), d2s/dx2 (1/m^2).
    """
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    l = float(length)
    s = np.stack(
        [1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3, l * (-(xi**2) + xi**3)],
        axis=-1,
    )
    ds = np.stack([(-6 * xi + 6 * xi**2) / l, 1 - 4 * xi + 3 * xi**2, (6 * xi - 6 * xi**2) / l, -2 * xi + 3 * xi**2], axis=-1)
    d2s = np.stack([(-6 + 12 * xi) / l**2, (-4 + 6 * xi) / l, (6 - 12 * xi) / l**2, (-2 + 6 * xi) / l], axis=-1)
    return s, ds, d2s


def gauss_legendre(order: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre points on [0, 1] and weights summing to 1."""
    if order < 1:
        raise ValueError("Gauss order must be >= 1")
    x, w = np.polynomial.legendre.leggauss(order)
    return 0.5 * (x + 1.0), 0.5 * w
