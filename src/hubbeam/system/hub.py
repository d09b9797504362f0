"""Hub kinematics (paper Eq. 74) and prescribed hub motions (Eqs. 81-83, Kane's spin-up).

The hub turns about the vertical j0 by the angle theta; its frame is
A_h(theta) = [[c, 0, -s], [0, 1, 0], [s, 0, c]], so i_h = (cos th, 0, sin th) and a point
on i_h moves along k_h = (-sin th, 0, cos th) when theta grows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

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


@njit(cache=True)
def clamp_frame(theta: float, twist: float) -> np.ndarray:
    """Section frame [tau m n] of the clamped root: the hub frame turned by -beta about i_h.

    With beta = 0 the width (m) is vertical; the twist rotates the section by theta_1 = -beta
    about the beam axis (conventions.md, Eq. 79), so n = sin(beta) j_h + cos(beta) k_h.
    """
    A = hub_frame(theta)
    cb, sb = math.cos(twist), math.sin(twist)
    C = np.empty((3, 3))
    for i in range(3):
        C[i, 0] = A[i, 0]
        C[i, 1] = cb * A[i, 1] - sb * A[i, 2]
        C[i, 2] = sb * A[i, 1] + cb * A[i, 2]
    return C


#: codes of the drive profiles inside compiled code
DRIVE_CODES = {"rest": 0, "constant": 1, "exponential": 2, "spin_up": 3}


@njit(cache=True)
def drive_values(code: int, w: float, T: float, t1: float, t: float):
    """(theta, theta', theta'') of profile ``code`` (:data:`DRIVE_CODES`) at time t."""
    if code == 0:
        return 0.0, 0.0, 0.0
    if code == 1:
        return w * t, w, 0.0
    if code == 2:  # Eqs. 81 and 83
        if t < t1:
            e = math.exp(-5.0 * t / T)
            return w * (t + T / 5.0 * e - T / 5.0), w * (1.0 - e), w * 5.0 / T * e
        e1 = math.exp(-5.0 * t1 / T)
        return w * (t1 + T / 5.0 * e1 - T / 5.0) + w * (t - t1), w, 0.0
    # Kane, Ryan & Banerjee (1987)
    if t < T:
        a = 2.0 * math.pi / T
        theta = (w / T) * (t * t / 2.0 + (T / (2 * math.pi)) ** 2 * (math.cos(a * t) - 1.0))
        omega = (w / T) * (t - math.sin(a * t) / a)
        alpha = (w / T) * (1.0 - math.cos(a * t))
        return theta, omega, alpha
    return w * (t - T / 2.0), w, 0.0


@dataclass(frozen=True)
class DriveProfile:
    """Prescribed hub angle theta(t) with its first two derivatives (rad, rad/s, rad/s^2)."""

    kind: str  # "exponential" | "constant" | "spin_up" | "rest"
    omega_s: float = 0.0
    T: float = 1.0
    t1: float = math.inf

    def __post_init__(self) -> None:
        if self.kind not in DRIVE_CODES:
            raise ValueError(f"unknown drive profile {self.kind!r}; choose one of {sorted(DRIVE_CODES)}")

    @property
    def code(self) -> int:
        return DRIVE_CODES[self.kind]

    def __call__(self, t: float) -> tuple[float, float, float]:
        return drive_values(self.code, float(self.omega_s), float(self.T), float(self.t1), float(t))
