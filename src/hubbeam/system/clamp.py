"""Clamp of the ANCF beam root to the hub (paper Eqs. 73-75, completed) and the drive (Eq. 82).

Eq. 73 as printed fixes five of the six freedoms of a rigid connection (the root
position, k_h . i_b = 0 and j_h . j_b = cos beta), and its twist equation has a zero
derivative at beta = 0 and two roots (+-beta). hubbeam clamps instead with six
equations that are linear in the beam coordinates and have unit-size Jacobians. For a
beam placed by a mount (:mod:`hubbeam.system.mount`: root at R i_k, axis a_1, normals a_2,
a_3 of its tilted hub frame):

    Phi_0..2 = r0(0) - R i_k(theta)                 root position
    Phi_3    = a_2(theta) . r0'(0)                  root tangent along the axis a_1 ...
    Phi_4    = a_3(theta) . r0'(0)                  ... (two equations)
    Phi_5    = theta_1(0) - delta(theta)            twist: the root section is the mount
                                                    frame turned by -beta about a_1

while the root stretch |r0'(0)| and twist rate theta_1'(0) stay free. delta(theta) is
the chart angle of the clamped section at tau = a_1(theta); its derivatives follow from
the chart's twist rate for a section turning with the hub (w = -j0):
d delta / d theta = w.tau + d.(w - tau (tau.w)) / (1 + d.tau).
The drive of a prescribed or fixed hub, theta - theta_p(t) = 0 (Eq. 82), is the hub's
constraint (:mod:`hubbeam.system.hub`), not the clamp's.

Coordinates of the constraint block: c = [theta, r0(3), r0'(3), theta_1] at the root.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from hubbeam.elements.ancf.frame import section_frame
from hubbeam.system.assembly import add_entry
from hubbeam.system.mount import axis_frame, beam_hub_frame, mount_frame



@njit(cache=True)
def clamp_twist_angle(mount, theta: float, F: np.ndarray, near: float = math.nan) -> float:
    """delta(theta): theta_1 of the clamped root section in chart F (the branch nearest
    ``near``; the principal one for nan)."""
    C = mount_frame(mount, theta)
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
def clamp_equations(c, mount, F, lam, phi_val, jac, hess):
    """Phi (6), dPhi/dc (6 x 8) and sum_i lambda_i d2 Phi_i / dc2 (8 x 8) of the clamp of
    the root coordinates c = [theta, r0 (3), r0' (3), theta_1] to the hub, for a beam
    placed by ``mount`` (:mod:`hubbeam.system.mount`), written into the given arrays."""
    theta = c[0]
    radius = mount[0]
    A = beam_hub_frame(mount, theta)  # i_k, j0, k_k
    a = axis_frame(mount, theta)  # beam axis a_1 and the normals a_2, a_3
    u = c[4:7]
    delta = clamp_twist_angle(mount, theta, F, c[7])
    # d delta / d theta and d2 delta / d theta2 for the section turning with w = -j0:
    # delta' = w.tau + d.(w - tau (tau.w)) / (1 + d.tau), tau = a_1, tau.w = -tau_y constant
    tau_y = a[1, 0]
    d_y = F[1, 0]
    u0 = F[0, 0] * a[0, 0] + F[1, 0] * a[1, 0] + F[2, 0] * a[2, 0]  # d.tau
    u1 = -F[0, 0] * a[2, 0] + F[2, 0] * a[0, 0]  # d.(tau x j0) = d (tau)/d theta . d
    d1 = -tau_y + (-d_y + tau_y * u0) / (1.0 + u0)
    d2 = u1 * (tau_y + d_y) / (1.0 + u0) ** 2
    jac[:, :] = 0.0
    hess[:, :] = 0.0
    # position: Phi = r0 - R i_k; d i_k / d theta = k_k, d2 i_k / d theta2 = -i_k
    for i in range(3):
        phi_val[i] = c[1 + i] - radius * A[i, 0]
        jac[i, 0] = -radius * A[i, 2]
        jac[i, 1 + i] = 1.0
        hess[0, 0] += radius * lam[i] * A[i, 0]
    # tangent: Phi_3 = a_2 . r0', Phi_4 = a_3 . r0'; d a / d theta = a x j0 = (-a_z, 0, a_x)
    for r in range(2):
        col = r + 1
        ax, ay, az = a[0, col], a[1, col], a[2, col]
        val = ax * u[0] + ay * u[1] + az * u[2]
        dval = -az * u[0] + ax * u[2]  # (a x j0) . u
        ddval = -ax * u[0] - az * u[2]  # ((a x j0) x j0) . u
        phi_val[3 + r] = val
        jac[3 + r, 0] = dval
        jac[3 + r, 4] = ax
        jac[3 + r, 5] = ay
        jac[3 + r, 6] = az
        hess[0, 0] += lam[3 + r] * ddval
        hess[0, 4] += lam[3 + r] * -az
        hess[0, 6] += lam[3 + r] * ax
        hess[4, 0] += lam[3 + r] * -az
        hess[6, 0] += lam[3 + r] * ax
    # twist
    phi_val[5] = c[7] - delta
    jac[5, 0] = -d1
    jac[5, 7] = 1.0
    hess[0, 0] -= lam[5] * d2


def clamp_constraints(c: np.ndarray, mount: np.ndarray, F: np.ndarray):
    """Phi (6), its Jacobian dPhi/dc (6 x 8), and a function giving sum_i lambda_i d2 Phi_i / dc2."""
    c = np.ascontiguousarray(c, dtype=float)
    F = np.ascontiguousarray(F, dtype=float)
    mount = np.asarray(mount, dtype=float)
    phi_val, jac = np.empty(6), np.empty((6, 8))
    clamp_equations(c, mount, F, np.zeros(6), phi_val, jac, np.empty((8, 8)))

    def hessian(lam: np.ndarray) -> np.ndarray:
        Hc = np.empty((8, 8))
        clamp_equations(c, mount, F, np.asarray(lam, dtype=float), np.empty(6), np.empty((6, 8)), Hc)
        return Hc

    return phi_val, jac, hessian


@njit(cache=True)
def clamp_residual(lam_k, phi, jac, n_root, scale, zl, l0, force, res):
    """A clamp's part of the residual: Phi_q^T lambda added to the first ``n_root`` entries of
    the beam's ``force``, scale Phi into its multiplier rows of ``res``; returns Phi_theta . lambda
    (its part of the hub row). ``jac`` (6 x (1 + n_root)) is on [theta, q_root]."""
    for j in range(n_root):
        acc_j = 0.0
        for i in range(6):
            acc_j += jac[i, 1 + j] * lam_k[i]
        force[j] += acc_j
    hub = 0.0
    for i in range(6):
        hub += jac[i, 0] * lam_k[i]
        res[zl[l0 + i]] = scale * phi[i]
    return hub


@njit(cache=True)
def add_clamp_jacobian(ab, brow, bcol, bb, ku, jac, n_root, scale, zl, l0, q_start, z_theta):
    """scale times a clamp's Jacobian (6 x (1 + n_root), on [theta, q_root]; theta at z_theta,
    q_root from q_start) in its multiplier rows and, transposed, in their columns."""
    for i in range(6):
        ri = zl[l0 + i]
        add_entry(ab, brow, bcol, bb, ku, ri, z_theta, scale * jac[i, 0])
        add_entry(ab, brow, bcol, bb, ku, z_theta, ri, scale * jac[i, 0])
        for j in range(n_root):
            add_entry(ab, brow, bcol, bb, ku, ri, q_start + j, scale * jac[i, 1 + j])
            add_entry(ab, brow, bcol, bb, ku, q_start + j, ri, scale * jac[i, 1 + j])


@njit(cache=True)
def clamp_work():
    """Work arrays of one clamp: (Phi (6), Jacobian (6 x 8), Hessian (8 x 8), multipliers (6))."""
    return np.empty(6), np.empty((6, 8)), np.empty((8, 8)), np.empty(6)
