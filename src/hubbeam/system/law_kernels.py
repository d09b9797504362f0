"""The hub's time laws as compiled code: their kinds and one njit evaluator per family.

:mod:`hubbeam.system.laws` builds the laws (:class:`~hubbeam.system.laws.DriveProfile`,
:class:`~hubbeam.system.laws.TorqueLaw`) and checks their tables; ``law.compiled()`` gives the
plain arrays this module's functions read, with one compiled signature for every kind::

    kind, params, knots, coefs = drive.compiled()
    theta, omega, alpha = drive_values(kind, params, knots, coefs, t)

``kind`` is a plain ``int`` (the value of :class:`DriveKind` / :class:`TorqueKind`). Units: time
s, angle rad, speed rad/s, acceleration rad/s^2, torque N m. Scalar loops only.
"""

from __future__ import annotations

import enum
import math
from typing import NamedTuple

import numpy as np
from numba import njit

__all__ = [
    "DriveKind",
    "TorqueKind",
    "CompiledDrive",
    "CompiledTorque",
    "table_interval",
    "poly2",
    "drive_values",
    "linear_hold",
    "torque_values",
]


class DriveKind(enum.IntEnum):
    """The prescribed hub motions; ``int(kind)`` is what compiled code receives."""

    REST = 0
    CONSTANT = 1
    EXPONENTIAL = 2
    SPIN_UP = 3
    TABLE = 4
    SLEW = 5


class TorqueKind(enum.IntEnum):
    """The applied hub torque laws; ``int(kind)`` is what compiled code receives."""

    CONSTANT = 0
    TABLE = 1
    PD = 2
    CALLABLE = 3


@njit(cache=True)
def table_interval(knots, t):
    """i with knots[i] <= t < knots[i+1], clipped to 0 .. len(knots) - 2 (binary search)."""
    lo = 0
    hi = knots.shape[0] - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if t < knots[mid]:
            hi = mid
        else:
            lo = mid
    return lo


@njit(cache=True)
def poly2(coefs, i, h):
    """Value, first and second derivative of the polynomial in row i (highest power first) at h."""
    k = coefs.shape[1]
    p = coefs[i, 0]
    d1 = 0.0
    d2 = 0.0
    for m in range(1, k):
        d2 = d2 * h + d1
        d1 = d1 * h + p
        p = p * h + coefs[i, m]
    return p, d1, 2.0 * d2


@njit(cache=True)
def drive_values(kind, params, knots, coefs, t):
    """(theta, theta', theta'') of a drive profile at time t (see :meth:`DriveProfile.compiled`).

    ``params`` = (omega_s, T, t1, angle); ``knots``/``coefs`` the piecewise polynomial of theta
    for a table (row i: theta on [knots[i], knots[i+1]] in powers of (t - knots[i]), highest
    first), empty otherwise.
    """
    if kind == DriveKind.REST:
        return 0.0, 0.0, 0.0
    w = params[0]
    T = params[1]
    if kind == DriveKind.CONSTANT:
        return w * t, w, 0.0
    if kind == DriveKind.EXPONENTIAL:  # paper Eqs. 81 and 83
        t1 = params[2]
        if t < t1:
            e = math.exp(-5.0 * t / T)
            return w * (t + T / 5.0 * e - T / 5.0), w * (1.0 - e), w * 5.0 / T * e
        e1 = math.exp(-5.0 * t1 / T)
        return w * (t1 + T / 5.0 * e1 - T / 5.0) + w * (t - t1), w, 0.0
    if kind == DriveKind.SPIN_UP:  # Kane, Ryan & Banerjee (1987)
        if t < T:
            a = 2.0 * math.pi / T
            theta = (w / T) * (t * t / 2.0 + (T / (2 * math.pi)) ** 2 * (math.cos(a * t) - 1.0))
            omega = (w / T) * (t - math.sin(a * t) / a)
            alpha = (w / T) * (1.0 - math.cos(a * t))
            return theta, omega, alpha
        return w * (t - T / 2.0), w, 0.0
    if kind == DriveKind.SLEW:  # rest to rest
        angle = params[3]
        if t < T:
            a = 2.0 * math.pi / T
            theta = angle * (t / T - math.sin(a * t) / (2.0 * math.pi))
            omega = (angle / T) * (1.0 - math.cos(a * t))
            alpha = (angle / T) * a * math.sin(a * t)
            return theta, omega, alpha
        return angle, 0.0, 0.0
    if kind == DriveKind.TABLE:
        n = knots.shape[0]
        t_end = knots[n - 1]
        if t >= t_end:  # speed held: theta linear, alpha = 0
            th, om, _ = poly2(coefs, n - 2, t_end - knots[n - 2])
            return th + om * (t - t_end), om, 0.0
        i = table_interval(knots, t)
        return poly2(coefs, i, t - knots[i])
    return math.nan, math.nan, math.nan


@njit(cache=True)
def linear_hold(knots, values, t):
    """Linear interpolation of values(knots) at t; the end values are held outside."""
    n = knots.shape[0]
    if t <= knots[0]:
        return values[0]
    if t >= knots[n - 1]:
        return values[n - 1]
    i = table_interval(knots, t)
    s = (t - knots[i]) / (knots[i + 1] - knots[i])
    return values[i] + s * (values[i + 1] - values[i])


@njit(cache=True)
def torque_values(kind, params, knots, values, ref_kind, ref_params, ref_knots, ref_coefs, t, theta, omega):
    """(torque, d torque / d theta, d torque / d omega) of a torque law (see :meth:`TorqueLaw.compiled`).

    ``params`` = (value, kp, kd, 0); ``knots``/``values`` the torque table; ``ref_*`` the
    reference drive of a PD law (as for :func:`drive_values`). A Python-callable law
    (``TorqueKind.CALLABLE``) cannot be evaluated here and gives (0, 0, 0).
    """
    if kind == TorqueKind.CONSTANT:
        return params[0], 0.0, 0.0
    if kind == TorqueKind.TABLE:
        return linear_hold(knots, values, t), 0.0, 0.0
    if kind == TorqueKind.PD:
        kp = params[1]
        kd = params[2]
        th_ref, om_ref, _ = drive_values(ref_kind, ref_params, ref_knots, ref_coefs, t)
        return kp * (th_ref - theta) + kd * (om_ref - omega), -kp, -kd
    return 0.0, 0.0, 0.0


class CompiledDrive(NamedTuple):
    """Arguments of :func:`drive_values` (before ``t``)."""

    kind: int  # int(DriveKind)
    params: np.ndarray  # float64 (4,): omega_s, T, t1, angle
    knots: np.ndarray  # float64 (n,): table times, empty otherwise
    coefs: np.ndarray  # float64 (n-1, k) C-contiguous: theta pieces, highest power first; (0, 0) otherwise


class CompiledTorque(NamedTuple):
    """Arguments of :func:`torque_values` (before ``t, theta, omega``)."""

    kind: int  # int(TorqueKind)
    params: np.ndarray  # float64 (4,): value, kp, kd, 0
    knots: np.ndarray  # float64 (n,): table times, empty otherwise
    values: np.ndarray  # float64 (n,): table torques, empty otherwise
    ref_kind: int  # the PD reference drive (rest for other laws), as CompiledDrive
    ref_params: np.ndarray
    ref_knots: np.ndarray
    ref_coefs: np.ndarray
