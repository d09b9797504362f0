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
from numba import njit

from hubbeam.elements.ancf.frame import section_frame
from hubbeam.system.hub import clamp_frame, hub_frame



@njit(cache=True)
def clamp_twist_angle(theta: float, twist: float, F: np.ndarray, near: float = math.nan) -> float:
    """delta(theta): theta_1 of the clamped section in chart F (the branch nearest ``near``;
    the principal one for nan)."""
    C = clamp_frame(theta, twist)
    tau = np.empty(3)
    for i in range(3):
        tau[i] = F[0, i] * C[0, 0] + F[1, i] * C[1, 0] + F[2, i] * C[2, 0]
    _, m0, n0 = section_frame(tau, 0.0)
    # m_clamp . (F m0) and m_clamp . (F n0), with m_clamp = C[:, 1]
    cm = cn = 0.0
    for i in range(3):
        for k in range(3):
            cm += C[i, 1] * F[i, k] * m0[k]
            cn += C[i, 1] * F[i, k] * n0[k]
    delta = math.atan2(cn, cm)
    if not math.isnan(near):
        delta += 2.0 * math.pi * math.floor((near - delta) / (2.0 * math.pi) + 0.5)
    return delta


@njit(cache=True)
def clamp_equations(c, radius, twist, F, held, drive, lam, phi_val, jac, hess):
    """Phi (m), dPhi/dc (m x 8) and sum_i lambda_i d2 Phi_i / dc2 (8 x 8), written into the
    given arrays; m = 7 when ``held`` (the drive theta = ``drive``), else 6."""
    theta = c[0]
    A = hub_frame(theta)
    u0, u1, u2 = c[4], c[5], c[6]
    delta = clamp_twist_angle(theta, twist, F, c[7])
    # d delta / d theta and d2 delta / d theta2 (the twist beta drops out)
    den = 1.0 + F[0, 0] * A[0, 0] + F[1, 0] * A[1, 0] + F[2, 0] * A[2, 0]
    d1 = -F[1, 0] / den
    d2 = F[1, 0] * (F[0, 0] * A[0, 2] + F[1, 0] * A[1, 2] + F[2, 0] * A[2, 2]) / den**2
    iu = A[0, 0] * u0 + A[1, 0] * u1 + A[2, 0] * u2
    ku = A[0, 2] * u0 + A[1, 2] * u1 + A[2, 2] * u2
    jac[:, :] = 0.0
    for i in range(3):
        phi_val[i] = c[1 + i] - radius * A[i, 0]
        jac[i, 0] = -radius * A[i, 2]
        jac[i, 1 + i] = 1.0
        jac[3, 4 + i] = A[i, 1]
        jac[4, 4 + i] = A[i, 2]
    phi_val[3] = A[0, 1] * u0 + A[1, 1] * u1 + A[2, 1] * u2
    phi_val[4] = ku
    phi_val[5] = c[7] - delta
    jac[4, 0] = -iu
    jac[5, 0] = -d1
    jac[5, 7] = 1.0
    if held:
        phi_val[6] = theta - drive
        jac[6, 0] = 1.0
    hess[:, :] = 0.0
    hess[0, 0] = radius * (lam[0] * A[0, 0] + lam[1] * A[1, 0] + lam[2] * A[2, 0]) - lam[4] * ku - lam[5] * d2
    for i in range(3):
        hess[0, 4 + i] = -lam[4] * A[i, 0]
        hess[4 + i, 0] = -lam[4] * A[i, 0]


def clamp_constraints(c: np.ndarray, radius: float, twist: float, F: np.ndarray, drive: float | None):
    """Phi, its Jacobian dPhi/dc, and a function giving sum_i lambda_i d2 Phi_i / dc2.

    ``drive`` is theta_p(t) for a prescribed or fixed hub, None for a free hub.
    """
    held = drive is not None
    m = 7 if held else 6
    c = np.ascontiguousarray(c, dtype=float)
    F = np.ascontiguousarray(F, dtype=float)
    phi_val, jac = np.empty(m), np.empty((m, 8))
    args = (c, float(radius), float(twist), F, held, float(drive) if held else 0.0)
    clamp_equations(*args, np.zeros(m), phi_val, jac, np.empty((8, 8)))

    def hessian(lam: np.ndarray) -> np.ndarray:
        Hc = np.empty((8, 8))
        clamp_equations(*args, np.asarray(lam, dtype=float), np.empty(m), np.empty((m, 8)), Hc)
        return Hc

    return phi_val, jac, hessian
