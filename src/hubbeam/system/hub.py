"""Hub kinematics (paper Eq. 74).

The hub turns about the vertical j0 by the angle theta; its frame is
A_h(theta) = [[c, 0, -s], [0, 1, 0], [s, 0, c]], so i_h = (cos th, 0, sin th) and a point
on i_h moves along k_h = (-sin th, 0, cos th) when theta grows. Its prescribed motions and
torque laws are in :mod:`hubbeam.system.laws`; where beams sit on it, in
:mod:`hubbeam.system.mount`.
"""

from __future__ import annotations

import math
import numpy as np
from numba import njit


@njit(cache=True)
def hub_frame(theta: float) -> np.ndarray:
    """A_h(theta) (Eq. 74); its columns are i_h, j_h, k_h in global components."""
    c, s = math.cos(theta), math.sin(theta)
    A = np.zeros((3, 3))
    A[0, 0] = c
    A[0, 2] = -s
    A[1, 1] = 1.0
    A[2, 0] = s
    A[2, 2] = c
    return A
