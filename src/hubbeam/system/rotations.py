"""Rotations: the rotation matrix of Euler parameters (normalised, for any e != 0) and its
rate matrix, compiled for the frames and the base; a rotation vector's matrix (Rodrigues),
Euler parameters from a matrix (Shepperd) and a matrix's rotation vector, in Python for
set-up and sensors."""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True, inline="always")
def cross3(a0, a1, a2, b0, b1, b2):
    """a x b of two vectors given by their components (a 3-tuple)."""
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@njit(cache=True)
def euler_rotation_into(e0, e1, e2, e3, R, c):
    """R[:, c:c + 3] = the rotation of the normalised Euler parameters (e0, e1, e2, e3) / |e|
    (columns: the body axes, global); ``c`` the first column (0 for a 3 x 3 matrix, 1 for a
    pose (3 x 4) whose column 0 is the origin)."""
    s = e0 * e0 + e1 * e1 + e2 * e2 + e3 * e3
    R[0, c] = (e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3) / s
    R[1, c + 1] = (e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3) / s
    R[2, c + 2] = (e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3) / s
    R[0, c + 1] = 2.0 * (e1 * e2 - e0 * e3) / s
    R[1, c] = 2.0 * (e1 * e2 + e0 * e3) / s
    R[0, c + 2] = 2.0 * (e1 * e3 + e0 * e2) / s
    R[2, c] = 2.0 * (e1 * e3 - e0 * e2) / s
    R[1, c + 2] = 2.0 * (e2 * e3 - e0 * e1) / s
    R[2, c + 1] = 2.0 * (e2 * e3 + e0 * e1) / s


@njit(cache=True)
def euler_rotation(e, R):
    """R = the rotation of the normalised Euler parameters e / |e| (columns: the body axes, global)."""
    euler_rotation_into(e[0], e[1], e[2], e[3], R, 0)


@njit(cache=True)
def euler_rate_matrix(e, E):
    """E (3 x 4) with the angular velocity (global axes) w = 2 E e' / (e . e) for any e != 0:
    E = [-v, e0 I + [v]x], v = (e1, e2, e3)."""
    e0, e1, e2, e3 = e[0], e[1], e[2], e[3]
    E[0, 0], E[0, 1], E[0, 2], E[0, 3] = -e1, e0, -e3, e2
    E[1, 0], E[1, 1], E[1, 2], E[1, 3] = -e2, e3, e0, -e1
    E[2, 0], E[2, 1], E[2, 2], E[2, 3] = -e3, -e2, e1, e0


def rotation_vector_matrix(phi) -> np.ndarray:
    """The rotation matrix of the rotation vector phi (rad): Rodrigues' formula."""
    phi = np.asarray(phi, dtype=float)
    angle = float(np.linalg.norm(phi))
    if angle == 0.0:
        return np.eye(3)
    k = phi / angle
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * K @ K


def euler_parameters(R) -> np.ndarray:
    """Unit Euler parameters (e0 >= 0) of the rotation matrix R (Shepperd's method)."""
    R = np.asarray(R, dtype=float)
    tr = np.trace(R)
    cands = [tr, R[0, 0], R[1, 1], R[2, 2]]
    i = int(np.argmax(cands))
    if i == 0:
        e0 = 0.5 * math.sqrt(1.0 + tr)
        e = np.array([e0, (R[2, 1] - R[1, 2]) / (4 * e0), (R[0, 2] - R[2, 0]) / (4 * e0), (R[1, 0] - R[0, 1]) / (4 * e0)])
    else:
        a = i - 1
        b, c = (a + 1) % 3, (a + 2) % 3
        ea = 0.5 * math.sqrt(max(1.0 + 2 * R[a, a] - tr, 0.0))
        e = np.empty(4)
        e[1 + a] = ea
        e[0] = (R[c, b] - R[b, c]) / (4 * ea)
        e[1 + b] = (R[b, a] + R[a, b]) / (4 * ea)
        e[1 + c] = (R[c, a] + R[a, c]) / (4 * ea)
    if e[0] < 0:
        e = -e
    return e / np.linalg.norm(e)


def rotation_vector(R) -> np.ndarray:
    """The rotation vector (rad, |phi| <= pi) of the rotation matrix R."""
    e = euler_parameters(R)
    s = float(np.linalg.norm(e[1:]))
    if s < 1e-300:
        return np.zeros(3)
    angle = 2.0 * math.atan2(s, e[0])
    return angle * e[1:] / s
