"""FFR element shape functions (paper Eqs. 50-54, 57).

Element deformation coordinates (Eq. 50), in the body frame:

    p_e = [u01 v1 v1' w1 w1' theta1  u02 v2 v2' w2 w2' theta2]

u0 and theta_tau are interpolated linearly (g1, g4), v0 and w0 by cubic Hermite functions
(g2, g3, g5, g6). The displacement of a point (x, y, z) of the section is Eq. 43:

    u = u0 - y v0' - z w0',   v = v0 - z theta,   w = w0 + y theta,

so u^b = N(x, y, z) p_e with N of Eq. 57.
"""

from __future__ import annotations

import numpy as np

from hubbeam.elements.hermite import hermite

#: Names of the six deformation coordinates of an FFR node (Eq. 50).
DOF_NAMES = ("u0", "v", "v'", "w", "w'", "theta")
NODE_DOFS = 6

_U, _V, _W, _T = [0, 6], [1, 2, 7, 8], [3, 4, 9, 10], [5, 11]


def line_shapes(xi: np.ndarray, length: float):
    """N1..N4 and their x-derivatives at ``xi`` (shape (n, 12) each, Eqs. 51-54).

    Returns a dict: 'N1', 'N1x' (u0, u0'), 'N2', 'N2x', 'N2xx' (v0), 'N3', 'N3x', 'N3xx' (w0),
    'N4', 'N4x' (theta_tau); derivatives in 1/m.
    """
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    n = xi.shape[0]
    s, ds, d2s = hermite(xi, length)
    out = {k: np.zeros((n, 12)) for k in ("N1", "N1x", "N2", "N2x", "N2xx", "N3", "N3x", "N3xx", "N4", "N4x")}
    linear = np.stack([1.0 - xi, xi], axis=-1)
    dlinear = np.tile(np.array([-1.0, 1.0]) / length, (n, 1))
    out["N1"][:, _U], out["N1x"][:, _U] = linear, dlinear
    out["N4"][:, _T], out["N4x"][:, _T] = linear, dlinear
    for key, idx in (("N2", _V), ("N3", _W)):
        out[key][:, idx], out[key + "x"][:, idx], out[key + "xx"][:, idx] = s, ds, d2s
    return out


def displacement_matrix(shapes: dict, k: int, y: float, z: float) -> np.ndarray:
    """N(x_k, y, z) of Eq. 57 (3 x 12) at the k-th point of ``shapes``."""
    return np.array([
        shapes["N1"][k] - y * shapes["N2x"][k] - z * shapes["N3x"][k],
        shapes["N2"][k] - z * shapes["N4"][k],
        shapes["N3"][k] + y * shapes["N4"][k],
    ])
