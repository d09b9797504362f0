"""Clamp of the ANCF beam root to the hub (paper Eqs. 73-75, completed) and the drive (Eq. 82).

Eq. 73 as printed fixes five of the six freedoms of a rigid connection (the root
position, k_h . i_b = 0 and j_h . j_b = cos beta), and its twist equation has a zero
derivative at beta = 0 and two roots (+-beta). hubbeam clamps instead with six
equations that are linear in the beam coordinates and have unit-size Jacobians:

    Phi_0..2 = r0(0) - R i_h(theta)                 root position
    Phi_3    = j_h . r0'(0)                         root tangent along i_h ...
    Phi_4    = k_h(theta) . r0'(0)                  ... (two equations)
    Phi_5    = theta_1(0) - delta(theta)            twist: the root section is the hub
                                                    frame turned by -beta about i_h

while the root stretch |r0'(0)| and twist rate theta_1'(0) stay free. delta(theta) is
the chart angle of the clamped section at tau = i_h(theta); its derivatives follow from
the chart's twist rate, d delta / d theta = -d_y / (1 + d . i_h).
A prescribed or fixed hub adds Phi_6 = theta - theta_p(t) (Eq. 82), whose multiplier is
the drive torque.

Coordinates of the constraint block: c = [theta, r0(3), r0'(3), theta_1] at the root.
"""

from __future__ import annotations

import math

import numpy as np

from hubbeam.elements.ancf.frame import section_frame
from hubbeam.system.hub import clamp_frame, hub_frame



def clamp_twist_angle(theta: float, twist: float, F: np.ndarray, near: float | None = None) -> float:
    """delta(theta): theta_1 of the clamped section in chart F (the branch nearest ``near``)."""
    C = clamp_frame(theta, twist)
    _, m0, n0 = section_frame(F.T @ C[:, 0], 0.0)
    delta = math.atan2(np.dot(C[:, 1], F @ n0), np.dot(C[:, 1], F @ m0))
    if near is not None:
        delta += 2.0 * math.pi * round((near - delta) / (2.0 * math.pi))
    return delta


def _twist_angle_rates(theta: float, F: np.ndarray) -> tuple[float, float]:
    """d delta / d theta and d2 delta / d theta2 (the twist beta drops out)."""
    A = hub_frame(theta)
    d = F[:, 0]
    den = 1.0 + np.dot(d, A[:, 0])
    return -d[1] / den, d[1] * np.dot(d, A[:, 2]) / den**2


def clamp_constraints(c: np.ndarray, radius: float, twist: float, F: np.ndarray, drive: float | None):
    """Phi, its Jacobian dPhi/dc, and a function giving sum_i lambda_i d2 Phi_i / dc2.

    ``drive`` is theta_p(t) for a prescribed or fixed hub, None for a free hub.
    """
    theta = c[0]
    r, u, phi = c[1:4], c[4:7], c[7]
    A = hub_frame(theta)
    i_h, j_h, k_h = A[:, 0], A[:, 1], A[:, 2]
    delta = clamp_twist_angle(theta, twist, F, near=phi)
    d1, d2 = _twist_angle_rates(theta, F)
    m = 6 if drive is None else 7
    phi_val = np.empty(m)
    jac = np.zeros((m, 8))
    phi_val[0:3] = r - radius * i_h
    phi_val[3] = np.dot(j_h, u)
    phi_val[4] = np.dot(k_h, u)
    phi_val[5] = phi - delta
    jac[0:3, 0] = -radius * k_h
    jac[0:3, 1:4] = np.eye(3)
    jac[3, 4:7] = j_h
    jac[4, 0] = -np.dot(i_h, u)
    jac[4, 4:7] = k_h
    jac[5, 0] = -d1
    jac[5, 7] = 1.0
    if drive is not None:
        phi_val[6] = theta - drive
        jac[6, 0] = 1.0

    def hessian(lam: np.ndarray) -> np.ndarray:
        Hc = np.zeros((8, 8))
        Hc[0, 0] = radius * np.dot(lam[0:3], i_h) - lam[4] * np.dot(k_h, u) - lam[5] * d2
        Hc[0, 4:7] = -lam[4] * i_h
        Hc[4:7, 0] = -lam[4] * i_h
        return Hc

    return phi_val, jac, hessian
