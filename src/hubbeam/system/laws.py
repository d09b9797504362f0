"""Time laws of the hub: prescribed drive profiles theta(t) and applied torque laws.

Both kinds of law are usable from Python (``law(t)`` / ``law(t, theta, omega)``) and from
numba-compiled code: ``law.compiled()`` gives plain arrays (:class:`CompiledDrive`,
:class:`CompiledTorque`) that the compiled evaluators of :mod:`hubbeam.system.law_kernels` read,
one compiled signature for every kind::

    kind, params, knots, coefs = drive.compiled()
    theta, omega, alpha = drive_values(kind, params, knots, coefs, t)

    c = torque.compiled()
    tq, dtq_dtheta, dtq_domega = torque_values(c.kind, c.params, c.knots, c.values, c.ref_kind,
                                               c.ref_params, c.ref_knots, c.ref_coefs, t, theta, omega)

``params`` is a float64 array of 4 entries, ``knots`` a float64 1-D array, ``coefs`` a float64
2-D C-contiguous array; analytic laws carry empty ``knots`` (shape (0,)) and ``coefs`` (shape
(0, 0)). This module builds and checks the laws and their tables; the kinds and the evaluators
are re-exported from :mod:`~hubbeam.system.law_kernels`.

Units: time s, angle rad, speed rad/s, acceleration rad/s^2, torque N m.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hubbeam.system.law_kernels import (
    CompiledDrive,
    CompiledTorque,
    DriveKind,
    TorqueKind,
    drive_values,
    torque_values,
)

__all__ = [
    "DriveKind",
    "DriveProfile",
    "CompiledDrive",
    "drive_values",
    "TorqueKind",
    "TorqueLaw",
    "CompiledTorque",
    "torque_values",
    "applied_power",
    "applied_work",
    "MIN_DRIVE_ROWS",
    "MIN_TORQUE_ROWS",
    "MIN_SMOOTHED_ROWS",
    "TableInterpolation",
    "smooth_table",
]


#: minimum number of rows of a drive table (the not-a-knot start condition needs two intervals)
MIN_DRIVE_ROWS = 3
#: minimum number of rows of a torque table (linear interpolation)
MIN_TORQUE_ROWS = 2
#: minimum number of rows of a drive table to be smoothed (a cubic smoothing spline needs five)
MIN_SMOOTHED_ROWS = 5


class TableInterpolation(enum.Enum):
    """How a drive table is interpolated between its rows (:meth:`DriveProfile.table`)."""

    SPLINE = "spline"  # cubic spline: omega C2 (theta C3), or theta C2
    LINEAR = "linear"  # omega piecewise linear, theta piecewise quadratic (omega tables only)


_EMPTY1 = np.zeros(0)
_EMPTY2 = np.zeros((0, 0))


def _finite_float(name: str, value: Any) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: must be a number (got {value!r})") from None
    if not math.isfinite(x):
        raise ValueError(f"{name}: must be finite (got {x})")
    return x


def _series(name_t: str, times: Any, name_v: str, values: Any, min_rows: int, start_at_zero: bool):
    """Validated (times, values) as float64 arrays; ValueError naming the problem otherwise."""
    try:
        t = np.array(times, dtype=float)
        v = np.array(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name_t}, {name_v}: must be sequences of numbers") from None
    if t.ndim != 1 or v.ndim != 1:
        raise ValueError(f"{name_t}, {name_v}: must be 1-D sequences (got shapes {t.shape} and {v.shape})")
    if t.size != v.size:
        raise ValueError(f"{name_v}: {v.size} values for {t.size} times")
    if t.size < min_rows:
        raise ValueError(f"{name_t}: a table needs at least {min_rows} rows (got {t.size})")
    for name, a in ((name_t, t), (name_v, v)):
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise ValueError(f"{name}: row {bad[0]} is not finite ({a[bad[0]]})")
    steps = np.diff(t)
    bad = np.flatnonzero(steps <= 0.0)
    if bad.size:
        i = bad[0] + 1
        raise ValueError(f"{name_t}: times must be strictly increasing (row {i}: {t[i]} after {t[i - 1]})")
    if start_at_zero and t[0] != 0.0:
        raise ValueError(f"{name_t}: the table must start at t = 0 (first time is {t[0]})")
    return t, v


def _table_pieces(times: np.ndarray, values: np.ndarray, quantity: str,
                  interpolation: TableInterpolation = TableInterpolation.SPLINE) -> np.ndarray:
    """Piecewise polynomial coefficients of theta, shape (n-1, k), highest power first."""
    if interpolation is TableInterpolation.LINEAR:  # omega linear on each interval, theta its integral
        h = np.diff(times)
        theta = np.concatenate([[0.0], np.cumsum(0.5 * (values[1:] + values[:-1]) * h)])
        return np.ascontiguousarray(np.column_stack([np.diff(values) / (2.0 * h), values[:-1], theta[:-1]]))
    from scipy.interpolate import CubicSpline

    if quantity == "omega":
        # C2 speed; alpha = 0 at the last row so that it is continuous with the held speed
        spline = CubicSpline(times, values, bc_type=("not-a-knot", (1, 0.0)))
        pieces = spline.antiderivative()  # theta(times[0]) = 0, quartic pieces, theta in C3
    else:
        # C2 angle; theta'' = 0 at the last row so that alpha is continuous with the held speed
        pieces = CubicSpline(times, values, bc_type=("not-a-knot", (2, 0.0)))
    return np.ascontiguousarray(np.asarray(pieces.c, dtype=float).T)


def smooth_table(times, values, cutoff_hz: float) -> np.ndarray:
    """The values of a measured series smoothed without phase shift above ``cutoff_hz`` (Hz),
    the first row's value kept: a cubic smoothing spline (scipy's ``make_smoothing_spline``)
    that minimises sum_i w_i (y_i - f(t_i))^2 + lambda int f''(t)^2 dt with the weights w_i the
    time each row stands for (half its two intervals) and lambda = (2 pi F)^-4. On evenly
    sampled data away from its ends this is the linear filter H(f) = 1 / (1 + (f/F)^4) (the
    Euler-Lagrange equation of the continuous problem is f + lambda f^(4) = y): real, so without
    phase shift, 1/2 at F and falling as (F/f)^4 above it, the magnitude of a second-order
    Butterworth filter run forward and backward (scipy.signal.filtfilt) at F; unlike that
    filter it takes unevenly spaced rows as they are. The first row carries a weight 1e8 times
    its neighbour's and is then set back to its value exactly (the start of a run: at rest, or
    theta = 0). At least :data:`MIN_SMOOTHED_ROWS` rows. Returns the smoothed values at the rows."""
    from scipy.interpolate import make_smoothing_spline

    t, v = np.asarray(times, dtype=float), np.asarray(values, dtype=float)
    if t.size < MIN_SMOOTHED_ROWS:
        raise ValueError(f"smoothing: a table needs at least {MIN_SMOOTHED_ROWS} rows to be smoothed (got {t.size})")
    cutoff = _finite_float("smoothing", cutoff_hz)
    if not cutoff > 0.0:
        raise ValueError(f"smoothing: the cut-off frequency must be > 0 Hz (got {cutoff})")
    h = np.diff(t)
    weights = 0.5 * (np.concatenate([[0.0], h]) + np.concatenate([h, [0.0]]))
    weights[0] = 1e8 * weights[1]
    scale = float(np.mean(weights[1:]))  # the objective divided by it: the same minimiser, numbers near 1
    spline = make_smoothing_spline(t, v, w=weights / scale, lam=(2.0 * np.pi * cutoff) ** -4 / scale)
    smooth = spline(t)
    smooth[0] = v[0]
    return smooth


_DRIVE_NAMES = {k.name.lower(): k for k in DriveKind}
_TORQUE_NAMES = {k.name.lower(): k for k in TorqueKind}


def _kind_name(kind: Any, names: dict, what: str) -> str:
    """The lower-case name of ``kind`` (an enum member or one of ``names``), or ValueError."""
    if isinstance(kind, enum.IntEnum) and kind.name.lower() in names:
        return kind.name.lower()
    if isinstance(kind, str) and kind in names:
        return kind
    raise ValueError(f"unknown {what} {kind!r}; choose one of {sorted(names)}")


@dataclass(frozen=True, repr=False)
class DriveProfile:
    """Prescribed hub angle theta(t) with its first two derivatives (rad, rad/s, rad/s^2).

    Kinds (``kind`` is the lower-case name of a :class:`DriveKind`):

    - ``DriveProfile("rest")``: theta = 0.
    - ``DriveProfile("constant", omega_s)``: theta = omega_s t.
    - ``DriveProfile("exponential", omega_s, T, t1=inf)``: paper Eqs. 81, 83,
      omega = omega_s (1 - exp(-5 t / T)) up to t1, then omega_s.
    - ``DriveProfile("spin_up", omega_s, T)``: Kane, Ryan & Banerjee (1987),
      omega = omega_s/T (t - T/(2 pi) sin(2 pi t/T)) up to T, then omega_s.
    - ``DriveProfile.slew(angle, T)``: rest to rest,
      theta = angle (t/T - sin(2 pi t/T)/(2 pi)) for t < T, then angle.
    - ``DriveProfile.table(times, values, quantity="omega" | "theta")``: a measured speed (rad/s)
      or angle (rad) series; see :meth:`table`.
    """

    kind: str
    omega_s: float = 0.0
    T: float = 1.0
    t1: float = math.inf
    angle: float = 0.0
    times: tuple[float, ...] = ()
    values: tuple[float, ...] = ()
    quantity: str = "omega"
    interpolation: str = "spline"
    smoothing: float | None = None
    _compiled: CompiledDrive = field(init=False, repr=False, compare=False, hash=False)

    # -- construction -------------------------------------------------------------------------

    def __post_init__(self) -> None:
        name = _kind_name(self.kind, _DRIVE_NAMES, "drive profile")
        object.__setattr__(self, "kind", name)
        dk = _DRIVE_NAMES[name]
        omega_s = _finite_float("omega_s", self.omega_s)
        T = float(self.T)
        t1 = float(self.t1)
        angle = _finite_float("angle", self.angle)
        if dk in (DriveKind.EXPONENTIAL, DriveKind.SPIN_UP, DriveKind.SLEW):
            if not (math.isfinite(T) and T > 0.0):
                raise ValueError(f"T: must be a finite time > 0 s for profile {name!r} (got {self.T})")
        if dk == DriveKind.EXPONENTIAL and not t1 > 0.0:
            raise ValueError(f"t1: must be > 0 s (or inf) for profile 'exponential' (got {self.t1})")
        if dk != DriveKind.SLEW and angle != 0.0:
            raise ValueError(f"angle: only for profile 'slew' (profile is {name!r})")
        if dk != DriveKind.TABLE and (len(self.times) or len(self.values) or self.quantity != "omega"
                                      or self.interpolation != "spline" or self.smoothing is not None):
            raise ValueError(f"times, values, quantity, interpolation, smoothing: only for profile 'table' "
                             f"(profile is {name!r})")
        for attr, val in (("omega_s", omega_s), ("T", T), ("t1", t1), ("angle", angle)):
            object.__setattr__(self, attr, val)

        knots, coefs = _EMPTY1, _EMPTY2
        if dk == DriveKind.TABLE:
            if self.quantity not in ("omega", "theta"):
                raise ValueError(f"quantity: must be 'omega' or 'theta' (got {self.quantity!r})")
            knots, vals = _series("times", self.times, "values", self.values, MIN_DRIVE_ROWS, True)
            if self.quantity == "theta" and vals[0] != 0.0:
                raise ValueError(
                    f"values: an angle table must start at theta = 0 (the initial configuration); got {vals[0]}"
                )
            object.__setattr__(self, "times", tuple(knots.tolist()))
            object.__setattr__(self, "values", tuple(vals.tolist()))
            try:
                interpolation = TableInterpolation(self.interpolation)
            except ValueError:
                raise ValueError(f"interpolation: must be one of {[i.value for i in TableInterpolation]} "
                                 f"(got {self.interpolation!r})") from None
            if interpolation is TableInterpolation.LINEAR and self.quantity == "theta":
                raise ValueError("interpolation: 'linear' is for an omega table (omega piecewise linear, theta "
                                 "piecewise quadratic); a theta table piecewise linear would have infinite "
                                 "accelerations at its rows: use 'spline', with smoothing for a noisy one")
            if self.smoothing is not None:
                object.__setattr__(self, "smoothing", _finite_float("smoothing", self.smoothing))
                vals = smooth_table(knots, vals, self.smoothing)
            coefs = _table_pieces(knots, vals, self.quantity, interpolation)
        params = np.array([omega_s, T, t1, angle], dtype=float)
        object.__setattr__(self, "_compiled", CompiledDrive(int(dk), params, knots, coefs))

    @classmethod
    def rest(cls) -> DriveProfile:
        """theta = 0."""
        return cls("rest")

    @classmethod
    def constant(cls, omega_s: float) -> DriveProfile:
        """theta = omega_s t."""
        return cls("constant", omega_s)

    @classmethod
    def exponential(cls, omega_s: float, T: float, t1: float = math.inf) -> DriveProfile:
        """Paper Eqs. 81, 83."""
        return cls("exponential", omega_s, T, t1)

    @classmethod
    def spin_up(cls, omega_s: float, T: float) -> DriveProfile:
        """Kane, Ryan & Banerjee (1987)."""
        return cls("spin_up", omega_s, T)

    @classmethod
    def slew(cls, angle: float, T: float) -> DriveProfile:
        """Rest-to-rest turn by ``angle`` (rad) in ``T`` (s).

        theta = angle (t/T - sin(2 pi t/T)/(2 pi)) for t < T, then angle; omega and alpha are its
        exact derivatives, both zero at t = 0 and t = T (alpha continuous, jerk not).
        """
        return cls("slew", T=T, angle=angle)

    @classmethod
    def table(cls, times: Any, values: Any, quantity: str = "omega", interpolation: str = "spline",
              smoothing: float | None = None) -> DriveProfile:
        """A measured speed (``quantity="omega"``, rad/s) or angle (``"theta"``, rad) series.

        Requirements: at least 3 rows (:data:`MIN_DRIVE_ROWS`), finite values, times strictly
        increasing and starting at t = 0 (nothing is defined before the first row); an angle
        table starts at theta = 0.

        ``smoothing`` (Hz): the values are first smoothed without phase shift above that
        frequency, the first row's value kept (:func:`smooth_table`; at least 5 rows); the
        interpolation then runs through the smoothed values.

        Interpolation (``interpolation``, stored as piecewise polynomials of theta):

        - "spline" (scipy ``CubicSpline``), omega table: a cubic spline of omega (C2),
          not-a-knot at t = 0 and clamped omega' = 0 at the last row; theta is its exact
          antiderivative with theta(0) = 0 (C3). After the last row omega is held (theta grows
          linearly, alpha = 0), so theta, omega and alpha are continuous there. The clamped end
          condition bends the last interval if the series has not settled; end the table where
          it has.
        - "spline", theta table: a cubic spline of theta (C2), not-a-knot at t = 0 and
          theta'' = 0 at the last row; after it omega = theta'(t_end) is held (alpha = 0,
          continuous).
        - "linear" (omega tables only): omega piecewise linear through the rows, theta its exact
          integral (piecewise quadratic, theta at each row the trapezoidal sum of the rows
          before), alpha constant on each interval and stepping at the rows (and to 0 after the
          last row). The spline overshoots between sparse or noisy rows; the linear law never
          leaves the rows' range but steps the acceleration, and so the drive torque, at each row.
        """
        return cls("table", times=times, values=values, quantity=quantity, interpolation=interpolation,
                   smoothing=smoothing)

    # -- use ----------------------------------------------------------------------------------

    @property
    def drive_kind(self) -> DriveKind:
        return _DRIVE_NAMES[self.kind]

    @property
    def code(self) -> int:
        """int(DriveKind) of this profile (what compiled code receives as ``kind``)."""
        return int(self.drive_kind)

    def compiled(self) -> CompiledDrive:
        """(kind, params, knots, coefs) for :func:`drive_values`; fresh arrays on every call."""
        c = self._compiled
        return CompiledDrive(c.kind, c.params.copy(), c.knots.copy(), c.coefs.copy())

    def __call__(self, t: float) -> tuple[float, float, float]:
        c = self._compiled
        return drive_values(c.kind, c.params, c.knots, c.coefs, float(t))

    def __repr__(self) -> str:
        k = self.drive_kind
        if k == DriveKind.REST:
            return "DriveProfile('rest')"
        if k == DriveKind.CONSTANT:
            return f"DriveProfile('constant', omega_s={self.omega_s!r})"
        if k == DriveKind.EXPONENTIAL:
            return f"DriveProfile('exponential', omega_s={self.omega_s!r}, T={self.T!r}, t1={self.t1!r})"
        if k == DriveKind.SPIN_UP:
            return f"DriveProfile('spin_up', omega_s={self.omega_s!r}, T={self.T!r})"
        if k == DriveKind.SLEW:
            return f"DriveProfile.slew(angle={self.angle!r}, T={self.T!r})"
        options = "".join(f", {key}={getattr(self, key)!r}" for key, default in
                          (("interpolation", "spline"), ("smoothing", None)) if getattr(self, key) != default)
        return (f"DriveProfile.table(<{len(self.times)} rows, t = 0 .. {self.times[-1]!r} s>, "
                f"quantity={self.quantity!r}{options})")


@dataclass(frozen=True, repr=False)
class TorqueLaw:
    """Torque applied to a free hub about j0 (N m), a function of t, theta and omega.

    - ``TorqueLaw.constant(value)`` (also ``TorqueLaw()`` = 0 N m).
    - ``TorqueLaw.table(times, torques)``: linear interpolation; the first torque is held before
      the first row and the last after the last row (at least 2 rows, times strictly increasing).
    - ``TorqueLaw.pd(kp, kd, reference)``: torque = kp (theta_ref - theta) + kd (omega_ref - omega)
      with kp in N m/rad, kd in N m s/rad (both >= 0) and the reference a :class:`DriveProfile`.
    - ``TorqueLaw.callable(function)``: ``function(t, theta, omega) -> float`` in Python. Calling
      the law gives the derivatives by central differences (5 calls of the function) -- the slow
      path; it cannot run inside compiled code (:attr:`compilable` is False and
      :func:`torque_values` returns (0, 0, 0) for it).

    ``law(t, theta, omega)`` returns (torque, d torque/d theta, d torque/d omega).
    """

    kind: str = "constant"
    value: float = 0.0
    times: tuple[float, ...] = ()
    torques: tuple[float, ...] = ()
    kp: float = 0.0
    kd: float = 0.0
    reference: DriveProfile | None = None
    function: Callable[[float, float, float], float] | None = None
    _compiled: CompiledTorque = field(init=False, repr=False, compare=False, hash=False)

    def __post_init__(self) -> None:
        name = _kind_name(self.kind, _TORQUE_NAMES, "torque law")
        object.__setattr__(self, "kind", name)
        tk = _TORQUE_NAMES[name]
        value = _finite_float("value", self.value)
        kp = _finite_float("kp", self.kp)
        kd = _finite_float("kd", self.kd)
        if tk != TorqueKind.CONSTANT and value != 0.0:
            raise ValueError(f"value: only for law 'constant' (law is {name!r})")
        if tk != TorqueKind.TABLE and (len(self.times) or len(self.torques)):
            raise ValueError(f"times, torques: only for law 'table' (law is {name!r})")
        if tk != TorqueKind.PD and (kp != 0.0 or kd != 0.0 or self.reference is not None):
            raise ValueError(f"kp, kd, reference: only for law 'pd' (law is {name!r})")
        if tk != TorqueKind.CALLABLE and self.function is not None:
            raise ValueError(f"function: only for law 'callable' (law is {name!r})")
        object.__setattr__(self, "value", value)
        object.__setattr__(self, "kp", kp)
        object.__setattr__(self, "kd", kd)

        knots, vals = _EMPTY1, _EMPTY1
        ref = DriveProfile("rest")
        if tk == TorqueKind.TABLE:
            knots, vals = _series("times", self.times, "torques", self.torques, MIN_TORQUE_ROWS, False)
            object.__setattr__(self, "times", tuple(knots.tolist()))
            object.__setattr__(self, "torques", tuple(vals.tolist()))
        elif tk == TorqueKind.PD:
            if kp < 0.0 or kd < 0.0:
                raise ValueError(f"kp, kd: gains must be >= 0 (got kp = {kp}, kd = {kd})")
            if not isinstance(self.reference, DriveProfile):
                raise ValueError(f"reference: a pd law needs a DriveProfile (got {self.reference!r})")
            ref = self.reference
        elif tk == TorqueKind.CALLABLE:
            if not callable(self.function):
                raise ValueError(f"function: must be callable as function(t, theta, omega) (got {self.function!r})")
        r = ref._compiled
        params = np.array([value, kp, kd, 0.0])
        object.__setattr__(self, "_compiled",
                           CompiledTorque(int(tk), params, knots, vals, r.kind, r.params, r.knots, r.coefs))

    @classmethod
    def constant(cls, value: float = 0.0) -> TorqueLaw:
        """A constant torque (N m)."""
        return cls("constant", value)

    @classmethod
    def table(cls, times: Any, torques: Any) -> TorqueLaw:
        """Torque series (s, N m): linear interpolation, end values held."""
        return cls("table", times=times, torques=torques)

    @classmethod
    def pd(cls, kp: float, kd: float, reference: DriveProfile) -> TorqueLaw:
        """torque = kp (theta_ref - theta) + kd (omega_ref - omega)."""
        return cls("pd", kp=kp, kd=kd, reference=reference)

    @classmethod
    def callable(cls, function: Callable[[float, float, float], float]) -> TorqueLaw:  # noqa: A003
        """A Python function torque(t, theta, omega) -> float (N m); not compilable."""
        return cls("callable", function=function)

    @property
    def torque_kind(self) -> TorqueKind:
        return _TORQUE_NAMES[self.kind]

    @property
    def compilable(self) -> bool:
        """False for a Python-callable law: compiled code must evaluate it in Python."""
        return self.torque_kind != TorqueKind.CALLABLE

    def compiled(self) -> CompiledTorque:
        """Arguments of :func:`torque_values` before (t, theta, omega); fresh arrays on every call."""
        c = self._compiled
        return CompiledTorque(c.kind, c.params.copy(), c.knots.copy(), c.values.copy(), c.ref_kind,
                              c.ref_params.copy(), c.ref_knots.copy(), c.ref_coefs.copy())

    def __call__(self, t: float, theta: float, omega: float) -> tuple[float, float, float]:
        t, theta, omega = float(t), float(theta), float(omega)
        if self.torque_kind == TorqueKind.CALLABLE:
            f = self._call_function
            h_th = 1e-6 * max(1.0, abs(theta))
            h_om = 1e-6 * max(1.0, abs(omega))
            tq = f(t, theta, omega)
            d_th = (f(t, theta + h_th, omega) - f(t, theta - h_th, omega)) / (2.0 * h_th)
            d_om = (f(t, theta, omega + h_om) - f(t, theta, omega - h_om)) / (2.0 * h_om)
            return tq, d_th, d_om
        c = self._compiled
        return torque_values(c.kind, c.params, c.knots, c.values, c.ref_kind, c.ref_params, c.ref_knots,
                             c.ref_coefs, t, theta, omega)

    def _call_function(self, t: float, theta: float, omega: float) -> float:
        value = self.function(t, theta, omega)
        try:
            x = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"torque function returned {value!r}, not a number (t = {t})") from None
        if not math.isfinite(x):
            raise ValueError(f"torque function returned {x} (t = {t}, theta = {theta}, omega = {omega})")
        return x

    def __repr__(self) -> str:
        k = self.torque_kind
        if k == TorqueKind.CONSTANT:
            return f"TorqueLaw.constant({self.value!r})"
        if k == TorqueKind.TABLE:
            return f"TorqueLaw.table(<{len(self.times)} rows, t = {self.times[0]!r} .. {self.times[-1]!r} s>)"
        if k == TorqueKind.PD:
            return f"TorqueLaw.pd(kp={self.kp!r}, kd={self.kd!r}, reference={self.reference!r})"
        return f"TorqueLaw.callable({self.function!r})"


def applied_power(torque: Any, omega: Any) -> np.ndarray:
    """Power of the applied hub torque, torque * omega (W), element-wise."""
    return np.asarray(torque, dtype=float) * np.asarray(omega, dtype=float)


def applied_work(t: Any, torque: Any, omega: Any) -> np.ndarray:
    """Work done by the applied hub torque from t[0] to each t[i] (J): cumulative trapezoid of torque * omega."""
    t = np.asarray(t, dtype=float)
    p = applied_power(torque, omega)
    if t.shape != p.shape or t.ndim != 1:
        raise ValueError(f"t, torque, omega: need three 1-D series of one length (got {t.shape} and {p.shape})")
    out = np.zeros_like(t)
    if t.size > 1:
        out[1:] = np.cumsum(0.5 * (p[1:] + p[:-1]) * np.diff(t))
    return out
