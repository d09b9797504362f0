"""Cardan angles of the FFR body frame, sequence 2-3-1 (paper Eqs. 68-70).

A0 = R_y(Theta1) R_z(Theta2) R_x(Theta3): first about the hub axis j0, so a body frame
clamped to a hub turning about j0 only changes Theta1 and never reaches the singularity
of this sequence (cos Theta2 = 0, the body axis along +-j0). The body angular velocity
is omega^b = D(Theta) Theta' (Eq. 68).
"""

from __future__ import annotations

import math

import numpy as np


def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rotation_matrix(angles: np.ndarray) -> np.ndarray:
    """A0(Theta) (body to global)."""
    return _ry(angles[0]) @ _rz(angles[1]) @ _rx(angles[2])


def angular_velocity_matrix(angles: np.ndarray) -> np.ndarray:
    """D(Theta) with omega^b = D Theta' (Eq. 68); singular where cos Theta2 = 0."""
    s2, c2 = math.sin(angles[1]), math.cos(angles[1])
    s3, c3 = math.sin(angles[2]), math.cos(angles[2])
    return np.array([[s2, 0.0, 1.0], [c2 * c3, s3, 0.0], [-c2 * s3, c3, 0.0]])


def angular_velocity_matrix_rate(angles: np.ndarray, rates: np.ndarray) -> np.ndarray:
    """D'(Theta, Theta') Theta', the h term of Eq. 70."""
    s2, c2 = math.sin(angles[1]), math.cos(angles[1])
    s3, c3 = math.sin(angles[2]), math.cos(angles[2])
    t1, t2, t3 = rates
    col1 = np.array([c2 * t2, -s2 * t2 * c3 - c2 * s3 * t3, s2 * t2 * s3 - c2 * c3 * t3])
    col2 = np.array([0.0, c3 * t3, -s3 * t3])
    return t1 * col1 + t2 * col2
