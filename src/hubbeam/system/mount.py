"""Where a beam sits on the hub: azimuth, radius, twist and precone (the root placement).

Beam k with azimuth psi, radius R, twist beta and precone p has its own hub frame
A_h(theta + psi) (Eq. 74): i_k = i_h(theta + psi), j0, k_k = k_h(theta + psi). Its root is at
R i_k. Its undeformed axis is i_k tilted out of the hub plane by p towards +j0 (a rotation
by p about k_k), and its section is turned about that axis by -beta exactly as a single
beam's is (docs/scenario.md, Eq. 79): with beta = 0 the width (m) lies in the plane of the
axis and j0. So the clamped root section frame [tau m n] is

    a = A_h(theta + psi) R_k(p),   tau = a_1,   m = cos(beta) a_2 - sin(beta) a_3,
    n = sin(beta) a_2 + cos(beta) a_3,

with R_k(p) the rotation by p about the third axis. A beam at azimuth 180 deg with twist
-beta is the mirror image (in the plane through j0 and k_h(theta)) of one at 0 deg with +beta.
Every vector fixed to the hub turns with d v / d theta = v x j0 (the hub turns about -j0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from hubbeam.system.hub import hub_frame


@dataclass(frozen=True)
class Mount:
    """Root placement of one beam (SI units, angles in rad)."""

    radius: float = 0.0
    twist: float = 0.0
    azimuth: float = 0.0
    precone: float = 0.0

    def params(self) -> np.ndarray:
        """[radius, twist, azimuth, precone] for compiled code."""
        return np.array([self.radius, self.twist, self.azimuth, self.precone], dtype=float)

    def frame(self, theta: float) -> np.ndarray:
        """Clamped root section frame [tau m n] (columns, global) at hub angle theta."""
        return mount_frame(self.params(), float(theta))

    def hub_frame(self, theta: float) -> np.ndarray:
        """The beam's own hub frame [i_k j0 k_k] (columns) at hub angle theta."""
        return beam_hub_frame(self.params(), float(theta))

    def root(self, theta: float) -> np.ndarray:
        """Root position R i_k (m)."""
        return self.radius * self.hub_frame(theta)[:, 0]


@njit(cache=True)
def beam_hub_frame(mount, theta):
    """A_h(theta + psi): columns i_k, j0, k_k (global)."""
    return hub_frame(theta + mount[2])


@njit(cache=True)
def _turned(A, i, j, angle):
    """A frame with its columns i and j turned by ``angle`` about the third one (right-handed:
    column i moves towards column j)."""
    c, s = math.cos(angle), math.sin(angle)
    out = A.copy()
    for r in range(3):
        out[r, i] = c * A[r, i] + s * A[r, j]
        out[r, j] = -s * A[r, i] + c * A[r, j]
    return out


@njit(cache=True)
def axis_frame(mount, theta):
    """a = A_h(theta + psi) R_k(p): columns a_1 (the beam axis), a_2, a_3 = k_k."""
    return _turned(beam_hub_frame(mount, theta), 0, 1, mount[3])


@njit(cache=True)
def mount_frame(mount, theta):
    """Clamped root section frame [tau m n] (columns, global) at hub angle theta: the axis
    frame turned by -beta about the axis."""
    return _turned(axis_frame(mount, theta), 1, 2, -mount[1])


@njit(cache=True)
def tip_from_mount(mount, theta, length, tip_at, out):
    """out = A_k^T (tip_at - R i_k - L a_1): the tip's displacement on the beam's hub frame."""
    A = beam_hub_frame(mount, theta)
    a = axis_frame(mount, theta)
    d = np.empty(3)
    for i in range(3):
        d[i] = tip_at[i] - mount[0] * A[i, 0] - length * a[i, 0]
    for j in range(3):
        out[j] = A[0, j] * d[0] + A[1, j] * d[1] + A[2, j] * d[2]
