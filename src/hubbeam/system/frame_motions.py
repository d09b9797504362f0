"""What the part kinds read from the frames once :func:`~hubbeam.system.frames.evaluate_chains`
has evaluated them: a chain's coordinate columns, a frame's velocity and acceleration from its
Jacobians and their derivatives (:func:`frame_motion`), a chain's motion over a run's records
(:func:`chain_motions`), and a tip's displacement in a reference frame
(:func:`displacement_in_reference`)."""

from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.system.frames import W_WIDTH, chain_kinematics_into


@njit(cache=True)
def chain_columns(table, k):
    """The x indices of chain k's coordinate columns."""
    return table.columns[table.column_start[k]:table.column_start[k + 1]]


@njit(cache=True)
def frame_motion(Jr, Jw, products, cols, v, acc_x, vel, w, acc, alpha):
    """The frame's origin velocity vel = Jr c' and angular velocity w = Jw c' (global), and its
    accelerations acc = Jr c'' + h_r and alpha = Jw c'' + h_w, h_r = products[0] and h_w =
    products[1] the velocity products of its chain (sum_il Hr[:, i, l] c'_i c'_l, exact:
    :func:`~hubbeam.system.frames.evaluate_motion`); c' = v[cols], c'' = acc_x[cols]."""
    nc = Jr.shape[1]
    for a in range(3):
        sv = sw = sa = sal = 0.0
        for i in range(nc):
            cd = v[cols[i]]
            cdd = acc_x[cols[i]]
            sv += Jr[a, i] * cd
            sw += Jw[a, i] * cd
            sa += Jr[a, i] * cdd
            sal += Jw[a, i] * cdd
        vel[a] = sv
        w[a] = sw
        acc[a] = sa + products[0, a]
        alpha[a] = sal + products[1, a]


@njit(cache=True)
def chain_motions(table, k, X, V, F, r, R, vel, w):
    """Chain k's origin r[i] (m), axes R[i], origin velocity vel[i] = Jr c' (m/s) and angular
    velocity w[i] = Jw c' (rad/s, global) at each state (X[i], V[i]) (charts F): the records of
    a run at once (a sensor over a chunk of records; one call instead of one per record)."""
    nc = table.column_start[k + 1] - table.column_start[k]
    cols = table.columns[table.column_start[k]:table.column_start[k + 1]]
    pose, jac, hess = np.empty((1, 3, 4)), np.empty((1, 2, 3, nc)), np.empty((1, 2, 3, nc, nc))
    P, J = pose[0], jac[0]
    work, orders = np.empty((nc, W_WIDTH)), np.full(1, 1, np.int64)
    products = np.empty((1, 2, 3))
    for s in range(X.shape[0]):
        chain_kinematics_into(table, np.int64(k), k + 1, X[s], F, np.int64(1), orders, pose, jac, hess, work,
                              table.free_links, table.ancf_tips, table.ffr_tips, X[s], products,
                              nc < 0)  # no literal: one signature
        for i in range(3):
            r[s, i] = P[i, 0]
            for j in range(3):
                R[s, i, j] = P[i, 1 + j]
            sv = 0.0
            sw = 0.0
            for c in range(nc):
                sv += J[0, i, c] * V[s, cols[c]]
                sw += J[1, i, c] * V[s, cols[c]]
            vel[s, i] = sv
            w[s, i] = sw


@njit(cache=True)
def displacement_in_reference(ctx, F, x, root_chain, reference_chain, length, tip, out):
    """out = R_ref^T (tip - r_root - length tau_root): a tip's displacement (m) from its
    undeformed place (the root frame's axis carried out to ``length``), along the axes of
    the reference frame (the beam's hub frame: radial, along the hub axis, tangential); the
    frames as :func:`evaluate_chains` left them at x."""
    P = ctx.chains.pose[root_chain]
    d0 = tip[0] - P[0, 0] - length * P[0, 1]
    d1 = tip[1] - P[1, 0] - length * P[1, 1]
    d2 = tip[2] - P[2, 0] - length * P[2, 1]
    Q = ctx.chains.pose[reference_chain]
    for j in range(3):
        out[j] = Q[0, 1 + j] * d0 + Q[1, 1 + j] * d1 + Q[2, 1 + j] * d2
