"""Rigid bodies on frames: the base, the hub's rotor (Newton-Euler, projected on the frames'
coordinates).

A rigid body hangs on a frame of the system (:mod:`hubbeam.system.frames`) whose origin is
its centre of mass and whose axes are the body's: it has mass m (kg) and the inertia tensor
I (kg m^2, 3 x 3, about its centre of mass, in its own axes). With the frame's Jacobians
(velocity v = Jr c', angular velocity w = Jw c', c the frame's coordinates) and the
velocity products of the chain (a = Jr c'' + h_r, alpha = Jw c'' + h_w), the body adds the
generalized force of Newton-Euler's equations about its centre of mass (Kane's form):

    Jr^T m (a - g) + Jw^T (I_g alpha + w x I_g w),     I_g = R I R^T (global axes),

and the Newton matrix coef_m (m Jr^T Jr + Jw^T I_g Jw) + coef_c Jw^T ([w]x I_g - [I_g w]x) Jw
(the gyroscopic term's velocity derivative); statics and modes add the exact load stiffness
of gravity, -m g . dJr/dc (Hr of the chain). Kinetic energy m |v|^2 / 2 + w . I_g w / 2,
gravity energy -m g . r.

The hub is a rotor symmetric about its axis: its mass and its inertia across the axis belong
to the base (a fixed base carries them away), so its rigid body is the inertia J about the
hub axis alone, I = J j j^T, on the hub frame. The base is a free body with its mass and
full inertia at its centre of mass. Both are parts of the kind "rigid bodies" (:data:`KIND`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.system import terms
from hubbeam.system.assembly import add_entry
from hubbeam.system.chains import PRODUCTS
from hubbeam.system.frame_motions import frame_motion
from hubbeam.system.frames import chain_products, chain_state


@dataclass(frozen=True)
class RigidBody:
    """A rigid body on the frame ``chain`` (its index among the system's frames): ``mass`` (kg)
    and ``inertia`` (kg m^2, 3 x 3 symmetric, about the centre of mass in the frame's axes)."""

    name: str
    chain: int
    mass: float
    inertia: tuple

    def inertia_matrix(self) -> np.ndarray:
        return np.asarray(self.inertia, dtype=float).reshape(3, 3)


class RigidBodies(NamedTuple):
    """Every rigid body of a system, one row each."""

    chain: np.ndarray  # int64 (n,): the frame each body's centre of mass and axes are
    mass: np.ndarray  # (n,) kg
    inertia: np.ndarray  # (n, 3, 3) kg m^2, body axes about the centre of mass
    work: np.ndarray  # (5, 3, 3) scratch of the equations (:func:`rigid_body_equations`: they allocate nothing)


def pack_rigid_bodies(system, layout) -> RigidBodies | None:
    bodies = list(system.rigid_bodies)
    if not bodies:
        return None
    orders = system.frames.table.orders
    for b in bodies:  # their accelerations read the frame's velocity products (and statics its Hessians)
        if orders[b.chain] < PRODUCTS:
            raise ValueError(f"rigid body {b.name!r}: its frame {b.chain} was not marked by Frames.needs_products")
    return RigidBodies(np.array([b.chain for b in bodies], dtype=np.int64),
                       np.array([b.mass for b in bodies], dtype=float),
                       np.array([b.inertia_matrix() for b in bodies], dtype=float).reshape(len(bodies), 3, 3),
                       np.zeros((5, 3, 3)))


@njit(cache=True)
def _global_inertia(R, I, out):
    """out = R I R^T."""
    for i in range(3):
        for j in range(3):
            s = 0.0
            for a in range(3):
                for b in range(3):
                    s += R[i, a] * I[a, b] * R[j, b]
            out[i, j] = s


@njit(cache=True, inline="always")
def _body_state(pack, ctx, b, x, F, Ig):
    """(columns, r, R, Jr, Jw, Hr, Hw) of body b's frame (:func:`~hubbeam.system.frames.chain_state`),
    and its inertia in global axes into Ig."""
    cols, r, R, Jr, Jw, Hr, Hw = chain_state(ctx.chains, pack.chain[b])
    _global_inertia(R, pack.inertia[b], Ig)
    return cols, r, R, Jr, Jw, Hr, Hw


def rigid_body_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor,
                         exact_stiffness, want_matrix, res, ab, brow, bcol, bb):
    """Every rigid body's generalized force and Newton-matrix entries (module docstring). Its
    vectors and matrices are views of the pack's scratch: compiled into the system's equations,
    which count no references (:func:`hubbeam.system.terms.register`), it allocates nothing."""
    zx, ku = ctx.z_of_x, ctx.ku
    g = ctx.gravity
    work = pack.work
    vel, w, a, alpha = work[0, 0], work[0, 1], work[0, 2], work[1, 0]
    f, tq, Iw = work[1, 1], work[1, 2], work[2, 0]
    Ig, G = work[3], work[4]
    for b in range(pack.chain.shape[0]):
        cols, r, R, Jr, Jw, Hr, Hw = _body_state(pack, ctx, b, x, F, Ig)
        nc = cols.shape[0]
        m = pack.mass[b]
        frame_motion(Jr, Jw, chain_products(ctx.chains, pack.chain[b]), cols, v, acc, vel, w, a, alpha)
        for i in range(3):
            f[i] = m * (a[i] - load_factor * g[i])
            Iw[i] = Ig[i, 0] * w[0] + Ig[i, 1] * w[1] + Ig[i, 2] * w[2]
        for i in range(3):
            tq[i] = Ig[i, 0] * alpha[0] + Ig[i, 1] * alpha[1] + Ig[i, 2] * alpha[2]
        tq[0] += w[1] * Iw[2] - w[2] * Iw[1]
        tq[1] += w[2] * Iw[0] - w[0] * Iw[2]
        tq[2] += w[0] * Iw[1] - w[1] * Iw[0]
        for j in range(nc):
            res[zx[cols[j]]] += coef_k * (Jr[0, j] * f[0] + Jr[1, j] * f[1] + Jr[2, j] * f[2]
                                          + Jw[0, j] * tq[0] + Jw[1, j] * tq[1] + Jw[2, j] * tq[2])
        if not want_matrix:
            continue
        # d(w x I w)/dw = [w]x I - [I w]x
        for i in range(3):
            for j in range(3):
                G[i, j] = 0.0
        for j in range(3):
            col = Ig[:, j]
            G[0, j] = w[1] * col[2] - w[2] * col[1]
            G[1, j] = w[2] * col[0] - w[0] * col[2]
            G[2, j] = w[0] * col[1] - w[1] * col[0]
        G[0, 1] += Iw[2]
        G[0, 2] -= Iw[1]
        G[1, 0] -= Iw[2]
        G[1, 2] += Iw[0]
        G[2, 0] += Iw[1]
        G[2, 1] -= Iw[0]
        for i in range(nc):
            for j in range(nc):
                mm = m * (Jr[0, i] * Jr[0, j] + Jr[1, i] * Jr[1, j] + Jr[2, i] * Jr[2, j])
                gyro = 0.0
                for p in range(3):
                    for q in range(3):
                        mm += Jw[p, i] * Ig[p, q] * Jw[q, j]
                        gyro += Jw[p, i] * G[p, q] * Jw[q, j]
                value = coef_m * mm + coef_c * gyro
                if exact_stiffness:  # the load stiffness of gravity: -m g . dJr_i/dc_j
                    value -= coef_k * load_factor * m * (g[0] * Hr[0, i, j] + g[1] * Hr[1, i, j] + g[2] * Hr[2, i, j])
                if value != 0.0:
                    add_entry(ab, brow, bcol, bb, ku, zx[cols[i]], zx[cols[j]], value)
    return 2.0, 0.0


def rigid_body_energies(pack, ctx, F, x, v, beams):
    """Kinetic and gravity energy of the rigid bodies (J), none belonging to a beam."""
    T = V = 0.0
    g = ctx.gravity
    Ig = np.empty((3, 3))
    vel, w, a, alpha = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    for b in range(pack.chain.shape[0]):
        cols, r, R, Jr, Jw, Hr, Hw = _body_state(pack, ctx, b, x, F, Ig)
        frame_motion(Jr, Jw, chain_products(ctx.chains, pack.chain[b]), cols, v, v, vel, w, a, alpha)
        T += 0.5 * pack.mass[b] * (vel[0] ** 2 + vel[1] ** 2 + vel[2] ** 2) + 0.5 * (w @ (Ig @ w))
        V -= pack.mass[b] * (g[0] * r[0] + g[1] * r[1] + g[2] * r[2])
    return T, 0.0, V


def rigid_body_momenta(pack, ctx, F, x, v, out):
    """Mass, first moment, linear momentum and angular momentum about the origin of the bodies."""
    Ig = np.empty((3, 3))
    vel, w, a, alpha = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    for b in range(pack.chain.shape[0]):
        cols, r, R, Jr, Jw, Hr, Hw = _body_state(pack, ctx, b, x, F, Ig)
        frame_motion(Jr, Jw, chain_products(ctx.chains, pack.chain[b]), cols, v, v, vel, w, a, alpha)
        m = pack.mass[b]
        Iw = Ig @ w
        out[0] += m
        for i in range(3):
            out[1 + i] += m * r[i]
            out[4 + i] += m * vel[i]
        out[7] += m * (r[1] * vel[2] - r[2] * vel[1]) + Iw[0]
        out[8] += m * (r[2] * vel[0] - r[0] * vel[2]) + Iw[1]
        out[9] += m * (r[0] * vel[1] - r[1] * vel[0]) + Iw[2]


def rigid_body_bandwidth(system, layout) -> int:
    """The bodies hang on frames whose coordinates are the border's (the base, the hub): no band
    entries off the border, unless the border is empty (one beam on a fixed base), where the
    hub angle is the band's first entry."""
    return 1


KIND = terms.register(RigidBodies, pack_rigid_bodies, rigid_body_equations, rigid_body_energies,
                      bandwidth=rigid_body_bandwidth, momenta=rigid_body_momenta, counts_references=False)
