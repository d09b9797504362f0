"""Hub time laws: drive profiles (analytic, slew, tables) and applied torque laws."""

import math

import numpy as np
import pytest

from hubbeam.system.laws import (
    CompiledDrive,
    CompiledTorque,
    DriveKind,
    DriveProfile,
    TorqueKind,
    TorqueLaw,
    applied_power,
    applied_work,
    drive_values,
    torque_values,
)

SPIN = DriveProfile("spin_up", 4.0, 15.0)
T_GRID = np.arange(0.0, 15.0 + 1e-9, 0.1)


def spin_omega_table():
    return DriveProfile.table(T_GRID, [SPIN(t)[1] for t in T_GRID])


def spin_theta_table():
    return DriveProfile.table(T_GRID, [SPIN(t)[0] for t in T_GRID], quantity="theta")


def profiles():
    """One profile of every kind (ids, profile)."""
    return {
        "rest": DriveProfile("rest"),
        "constant": DriveProfile("constant", 2.5),
        "exponential": DriveProfile("exponential", 3.0, 2.0, 1.5),
        "exponential_inf": DriveProfile("exponential", 3.0, 2.0),
        "spin_up": SPIN,
        "slew": DriveProfile.slew(0.7, 3.0),
        "slew_negative": DriveProfile.slew(-2.0, 1.5),
        "table_omega": spin_omega_table(),
        "table_theta": spin_theta_table(),
        "table_irregular": DriveProfile.table([0.0, 0.3, 0.5, 1.2, 2.0, 2.1], [0.0, 0.5, 0.4, 1.5, 1.0, 1.1]),
    }


PROFILES = profiles()


# -- the four original profiles are unchanged -----------------------------------------------------

def test_positional_construction_as_before():
    d = DriveProfile("exponential", 3.0, 2.0, 1.5)
    assert (d.kind, d.omega_s, d.T, d.t1) == ("exponential", 3.0, 2.0, 1.5)
    assert DriveProfile("constant", 2.0).kind == "constant"
    assert DriveProfile("rest").kind == "rest"
    assert DriveProfile("spin_up", 4.0, 15.0) == DriveProfile.spin_up(4.0, 15.0)
    assert DriveProfile("constant", 2.0) == DriveProfile.constant(2.0)
    assert DriveProfile(DriveKind.SLEW, T=2.0, angle=1.0).kind == "slew"
    assert DriveProfile(DriveKind.SLEW, T=2.0, angle=1.0).drive_kind is DriveKind.SLEW
    assert hash(DriveProfile.constant(2.0)) == hash(DriveProfile("constant", 2.0))
    assert spin_omega_table() == spin_omega_table()
    with pytest.raises(AttributeError):
        d.omega_s = 1.0
    assert "spin_up" in repr(SPIN) and "151 rows" in repr(spin_omega_table())


# -- derivatives against central differences --------------------------------------------------------

def _kinks(profile):
    if profile.kind == "exponential":
        return [profile.t1]
    if profile.kind in ("spin_up", "slew"):
        return [profile.T]
    return []


@pytest.mark.parametrize("name", list(PROFILES))
def test_omega_and_alpha_are_derivatives(name):
    profile = PROFILES[name]
    h = 1e-5
    times = np.concatenate([np.linspace(0.013, 19.9, 157), np.asarray(profile.times[1:-1]) + 0.0137])
    th_scale = max(1.0, max(abs(profile(t)[0]) for t in times))
    om_scale = max(1.0, max(abs(profile(t)[1]) for t in times))
    for t in times:
        if any(abs(t - k) < 2 * h for k in _kinks(profile)):
            continue
        th, om, al = profile(t)
        d_th = (profile(t + h)[0] - profile(t - h)[0]) / (2 * h)
        d_om = (profile(t + h)[1] - profile(t - h)[1]) / (2 * h)
        assert abs(d_th - om) < 1e-7 * th_scale, (t, d_th, om)
        assert abs(d_om - al) < 1e-6 * om_scale, (t, d_om, al)


# -- slew ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("angle, T", [(0.7, 3.0), (-2.0, 1.5), (math.pi, 10.0)])
def test_slew_is_rest_to_rest(angle, T):
    d = DriveProfile.slew(angle, T)
    assert d(0.0) == (0.0, 0.0, 0.0)
    assert d(T) == (angle, 0.0, 0.0)
    assert d(2 * T) == (angle, 0.0, 0.0)
    th, om, al = d(T * (1 - 1e-12))  # left limit
    assert th == pytest.approx(angle, abs=1e-9)
    assert abs(om) < 1e-9 and abs(al) < 1e-9 * abs(angle) / T**2 * 1e3
    th, om, al = d(T / 2)
    assert th == pytest.approx(angle / 2)
    assert om == pytest.approx(2 * angle / T)  # peak speed
    theta = np.array([d(t)[0] for t in np.linspace(0, T, 401)])
    assert np.all(np.diff(theta) * np.sign(angle) > 0)


# -- tables --------------------------------------------------------------------------------------

def _limits(profile, t, eps=1e-9):
    return np.array(profile(t - eps)), np.array(profile(t + eps))


@pytest.mark.parametrize("name", ["table_omega", "table_theta", "table_irregular"])
def test_table_is_C2_at_knots_and_at_the_last_row(name):
    profile = PROFILES[name]
    scale = np.array([max(abs(profile(t)[i]) for t in profile.times) + 1.0 for i in range(3)])
    for t in profile.times[1:]:
        left, right = _limits(profile, t)
        assert np.all(np.abs(left - right) < 1e-6 * scale), (t, left, right)
        assert np.all(np.abs(left - np.array(profile(t))) < 1e-6 * scale)
    t_end = profile.times[-1]
    th, om, al = profile(t_end)
    assert profile(t_end + 3.0) == pytest.approx((th + 3.0 * om, om, 0.0), abs=1e-12 * (1 + abs(th)))
    assert abs(al) < 1e-12 * scale[2]


def test_omega_table_starts_at_theta_zero_and_interpolates_rows():
    d = PROFILES["table_irregular"]
    assert d(0.0)[0] == 0.0
    for t, w in zip(d.times, d.values):
        assert d(t)[1] == pytest.approx(w, abs=1e-12)
    # alpha of the clamped end: 0 at the last row
    assert abs(d(d.times[-1])[2]) < 1e-12


@pytest.mark.parametrize("make", [spin_omega_table, spin_theta_table])
def test_table_sampled_from_spin_up_reproduces_it(make):
    table = make()
    t = np.linspace(0.0, 20.0, 2001)
    got = np.array([table(x) for x in t])
    ref = np.array([SPIN(x) for x in t])
    peaks = np.abs(ref).max(axis=0)
    err = np.abs(got - ref).max(axis=0) / peaks
    assert np.all(err < 2e-3), err


def test_angle_table_of_a_slew():
    slew = DriveProfile.slew(1.2, 4.0)
    times = np.linspace(0.0, 4.0, 41)
    d = DriveProfile.table(times, [slew(t)[0] for t in times], "theta")
    assert d.quantity == "theta"
    assert d(0.0)[0] == 0.0
    for x in np.linspace(0.0, 6.0, 301):
        got, ref = np.array(d(x)), np.array(slew(x))
        assert np.all(np.abs(got - ref) < np.array([1e-4, 5e-4, 5e-3])), (x, got, ref)
    assert d(10.0)[0] == pytest.approx(1.2, abs=1e-4)


# -- compiled form -------------------------------------------------------------------------------

@pytest.mark.parametrize("name", list(PROFILES))
def test_compiled_drive_equals_python(name):
    profile = PROFILES[name]
    c = profile.compiled()
    assert isinstance(c, CompiledDrive)
    assert type(c.kind) is int and c.kind == int(profile.drive_kind)
    assert c.params.dtype == np.float64 and c.params.shape == (4,)
    assert c.knots.dtype == np.float64 and c.knots.ndim == 1
    assert c.coefs.dtype == np.float64 and c.coefs.ndim == 2 and c.coefs.flags.c_contiguous
    if profile.drive_kind == DriveKind.TABLE:
        assert c.coefs.shape[0] == c.knots.size - 1
    else:
        assert c.knots.shape == (0,) and c.coefs.shape == (0, 0)
    for t in np.linspace(0.0, 20.0, 41):
        assert drive_values(*c, t) == profile(t)
    c.params[0] = 99.0  # a copy: the profile is unchanged
    assert drive_values(*profile.compiled(), 1.0) == profile(1.0)


# -- torque laws ---------------------------------------------------------------------------------

def test_constant_torque():
    assert TorqueLaw()(1.0, 2.0, 3.0) == (0.0, 0.0, 0.0)
    assert TorqueLaw() == TorqueLaw.constant(0.0)
    law = TorqueLaw.constant(2.5)
    assert law.kind == "constant" and law.torque_kind is TorqueKind.CONSTANT and law.compilable
    assert law(7.0, 1.0, -1.0) == (2.5, 0.0, 0.0)


def test_torque_table_interpolates_and_holds():
    law = TorqueLaw.table([0.0, 1.0, 3.0], [0.0, 2.0, -2.0])
    assert law(0.5, 0.0, 0.0) == (1.0, 0.0, 0.0)
    assert law(2.0, 5.0, 5.0) == (0.0, 0.0, 0.0)
    assert law(1.0, 0.0, 0.0)[0] == 2.0
    assert law(3.0, 0.0, 0.0)[0] == -2.0
    assert law(100.0, 0.0, 0.0)[0] == -2.0
    assert law(-1.0, 0.0, 0.0)[0] == 0.0
    late = TorqueLaw.table([2.0, 4.0], [1.0, 3.0])
    assert late(0.0, 0, 0)[0] == 1.0 and late(3.0, 0, 0)[0] == 2.0


def test_pd_torque_values_and_derivatives():
    law = TorqueLaw.pd(200.0, 80.0, DriveProfile("spin_up", 0.5, 10.0))
    ref = DriveProfile("spin_up", 0.5, 10.0)
    h = 1e-6
    for t, th, om in [(0.0, 0.0, 0.0), (2.0, 0.1, 0.05), (5.0, -0.3, 0.4), (30.0, 12.0, 0.6)]:
        tq, d_th, d_om = law(t, th, om)
        th_r, om_r, _ = ref(t)
        assert tq == pytest.approx(200.0 * (th_r - th) + 80.0 * (om_r - om), rel=1e-14, abs=1e-12)
        assert d_th == pytest.approx((law(t, th + h, om)[0] - law(t, th - h, om)[0]) / (2 * h), rel=1e-6)
        assert d_om == pytest.approx((law(t, th, om + h)[0] - law(t, th, om - h)[0]) / (2 * h), rel=1e-6)


def test_callable_torque():
    def f(t, theta, omega):
        return math.sin(t) - 3.0 * theta**2 + 0.5 * omega**3

    law = TorqueLaw.callable(f)
    assert not law.compilable and law.torque_kind is TorqueKind.CALLABLE
    tq, d_th, d_om = law(1.0, 0.4, -2.0)
    assert tq == f(1.0, 0.4, -2.0)
    assert d_th == pytest.approx(-6.0 * 0.4, rel=1e-6)
    assert d_om == pytest.approx(1.5 * 4.0, rel=1e-6)
    assert torque_values(*law.compiled(), 1.0, 0.4, -2.0) == (0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="not a number|returned"):
        TorqueLaw.callable(lambda t, th, om: float("nan"))(0.0, 0.0, 0.0)


@pytest.mark.parametrize("law", [TorqueLaw(), TorqueLaw.constant(-3.0), TorqueLaw.table([0.0, 1.0, 2.5], [1.0, -1.0, 4.0]),
                                 TorqueLaw.pd(10.0, 2.0, SPIN), TorqueLaw.pd(1.0, 0.0, spin_omega_table()),
                                 TorqueLaw.pd(3.0, 1.0, DriveProfile.slew(1.0, 2.0))],
                         ids=["zero", "constant", "table", "pd_spin", "pd_table", "pd_slew"])
def test_compiled_torque_equals_python(law):
    c = law.compiled()
    assert isinstance(c, CompiledTorque)
    assert type(c.kind) is int and type(c.ref_kind) is int
    assert c.params.shape == (4,) and c.knots.ndim == 1 and c.values.ndim == 1 and c.ref_coefs.ndim == 2
    for t in np.linspace(0.0, 20.0, 21):
        for th, om in [(0.0, 0.0), (0.3, -1.0)]:
            assert torque_values(*c, t, th, om) == law(t, th, om)


def test_applied_work():
    t = np.linspace(0.0, 2.0, 5)
    assert np.allclose(applied_work(t, np.full(5, 3.0), np.full(5, 2.0)), 6.0 * t)
    assert np.allclose(applied_work(t, t, np.ones(5)), t**2 / 2)
    assert np.allclose(applied_power([1.0, 2.0], [3.0, 4.0]), [3.0, 8.0])
    with pytest.raises(ValueError):
        applied_work(t, np.ones(4), np.ones(4))


# -- validation ------------------------------------------------------------------------------------

@pytest.mark.parametrize("make, match", [
    (lambda: DriveProfile("wobble"), "unknown drive profile"),
    (lambda: DriveProfile("spin_up", 1.0, -2.0), "T: must be"),
    (lambda: DriveProfile("exponential", 1.0, 0.0), "T: must be"),
    (lambda: DriveProfile("spin_up", float("nan"), 2.0), "omega_s: must be finite"),
    (lambda: DriveProfile("exponential", 1.0, 2.0, -1.0), "t1: must be"),
    (lambda: DriveProfile.slew(1.0, -1.0), "T: must be"),
    (lambda: DriveProfile.slew(float("inf"), 1.0), "angle: must be finite"),
    (lambda: DriveProfile("constant", 1.0, angle=2.0), "angle: only for profile 'slew'"),
    (lambda: DriveProfile("constant", 1.0, times=(0.0, 1.0)), "only for profile 'table'"),
    (lambda: DriveProfile.table([0.0, 1.0], [0.0, 1.0]), "at least 3 rows"),
    (lambda: DriveProfile.table([0.0, 1.0, 1.0, 2.0], [0.0, 1.0, 1.0, 2.0]), "strictly increasing"),
    (lambda: DriveProfile.table([0.0, 2.0, 1.0, 3.0], [0.0, 1.0, 1.0, 2.0]), "strictly increasing"),
    (lambda: DriveProfile.table([0.5, 1.0, 2.0], [0.0, 1.0, 2.0]), "must start at t = 0"),
    (lambda: DriveProfile.table([0.0, 1.0, 2.0], [0.0, float("nan"), 2.0]), "values: row 1 is not finite"),
    (lambda: DriveProfile.table([0.0, 1.0, float("inf")], [0.0, 1.0, 2.0]), "times: row 2 is not finite"),
    (lambda: DriveProfile.table([0.0, 1.0, 2.0], [0.0, 1.0]), "2 values for 3 times"),
    (lambda: DriveProfile.table([0.0, 1.0, 2.0], [0.0, 1.0, 2.0], "speed"), "quantity: must be"),
    (lambda: DriveProfile.table([0.0, 1.0, 2.0], [0.1, 1.0, 2.0], "theta"), "start at theta = 0"),
    (lambda: DriveProfile.table([0.0, 1.0, 2.0], ["a", "b", "c"]), "sequences of numbers"),
    (lambda: TorqueLaw("spring"), "unknown torque law"),
    (lambda: TorqueLaw.constant(float("nan")), "value: must be finite"),
    (lambda: TorqueLaw.table([0.0], [1.0]), "at least 2 rows"),
    (lambda: TorqueLaw.table([0.0, 0.0], [1.0, 2.0]), "strictly increasing"),
    (lambda: TorqueLaw.pd(-1.0, 1.0, SPIN), "gains must be >= 0"),
    (lambda: TorqueLaw.pd(1.0, 1.0, None), "needs a DriveProfile"),
    (lambda: TorqueLaw("pd", value=3.0, kp=1.0, reference=SPIN), "value: only for law 'constant'"),
    (lambda: TorqueLaw("constant", 1.0, kp=2.0), "only for law 'pd'"),
    (lambda: TorqueLaw.callable(3.0), "must be callable"),
])
def test_validation(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_a_callable_torque_law_takes_the_python_step_only_on_a_free_hub():
    """A held hub ignores its torque law, so a Python function there keeps the compiled loop
    (the API refuses a torque law on a held hub, as a scenario file does: issue 29)."""
    from hubbeam import api
    from hubbeam.io.scenario import ScenarioError, load_example

    law = TorqueLaw.callable(lambda t, theta, omega: 0.0)
    assert api.build_system(load_example("exp2")).with_hub(torque=law).compiled  # prescribed spin-up: held
    assert not api.build_system(load_example("exp1"), law).compiled  # free hub
    with pytest.raises(ScenarioError, match="^torque: a torque law acts on a free hub only"):
        api.build_system(load_example("exp2"), law)


# -- measured speed logs: linear interpolation and smoothing ---------------------------------------
def test_a_linear_omega_table_passes_its_rows_and_integrates_them_by_trapezoids():
    """omega piecewise linear through the rows, theta its integral: at the rows theta is the
    trapezoidal sum of the rows before (scipy's cumulative_trapezoid), alpha the slope of each
    interval (a step at every row), and after the last row the speed is held."""
    from scipy.integrate import cumulative_trapezoid

    rng = np.random.default_rng(4)
    t = np.concatenate([[0.0], np.cumsum(rng.uniform(0.05, 0.3, 30))])
    w = rng.normal(2.0, 1.0, t.size)
    d = DriveProfile.table(t, w, interpolation="linear")
    theta = cumulative_trapezoid(w, t, initial=0.0)
    at_rows = np.array([d(x) for x in t])
    assert np.allclose(at_rows[:, 0], theta, rtol=1e-13, atol=1e-13)
    assert np.allclose(at_rows[:, 1], w, rtol=1e-13, atol=1e-13)
    mid = 0.5 * (t[1:] + t[:-1])
    assert np.allclose([d(x)[2] for x in mid], np.diff(w) / np.diff(t), rtol=1e-12)
    assert np.allclose([d(x)[1] for x in mid], 0.5 * (w[1:] + w[:-1]), rtol=1e-12)
    assert d(t[-1] + 2.0) == pytest.approx((theta[-1] + 2.0 * w[-1], w[-1], 0.0), rel=1e-13)
    assert np.allclose(drive_values(*d.compiled(), 1.234), d(1.234), rtol=0, atol=0)


@pytest.mark.parametrize("uneven", [False, True])
def test_smoothing_is_the_filter_one_over_one_plus_f_over_F_to_the_fourth_without_phase(uneven):
    """Sines through the smoothing at F = 1 Hz, away from the series' ends: the gain is
    1 / (1 + (f/F)^4) (the Euler-Lagrange equation of the smoothing functional, f + lambda
    f^(4) = y with lambda = (2 pi F)^-4) to 1e-5 and the phase is zero, on evenly and on
    unevenly spaced rows; the first row's value is kept exactly."""
    from hubbeam.system.laws import smooth_table

    rng = np.random.default_rng(5)
    t = np.sort(np.concatenate([[0.0], rng.uniform(0.0, 40.0, 4000)])) if uneven else np.linspace(0.0, 40.0, 4001)
    middle = (t > 10.0) & (t < 30.0)
    for f in (0.25, 0.5, 1.0, 2.0):
        y = np.sin(2 * np.pi * f * t + 0.3)
        s = smooth_table(t, y, 1.0)
        assert s[0] == y[0]
        basis = np.column_stack([np.sin(2 * np.pi * f * t[middle] + 0.3), np.cos(2 * np.pi * f * t[middle] + 0.3)])
        in_phase, quadrature = np.linalg.lstsq(basis, s[middle], rcond=None)[0]
        gain = 1.0 / (1.0 + f**4)
        assert in_phase == pytest.approx(gain, abs=1e-5 if not uneven else 2e-3)
        assert abs(quadrature) < (1e-6 if not uneven else 2e-3)


def test_a_smoothed_table_keeps_its_rows_and_its_start():
    t = np.arange(0.0, 3.0 + 1e-9, 0.01)
    w = 2.0 * t + np.random.default_rng(6).normal(0.0, 0.05, t.size)
    w[0] = 0.0
    d = DriveProfile.table(t, w, smoothing=3.0)
    assert d.values == tuple(w) and d.smoothing == 3.0 and "smoothing=3.0" in repr(d)
    assert d(0.0)[:2] == (0.0, 0.0)
    # a straight line passes the filter unchanged: the smoothed table is 2 t within the noise left
    assert np.max(np.abs(np.array([d(x)[1] for x in t[50:-50]]) - 2.0 * t[50:-50])) < 0.05


@pytest.mark.parametrize("make, match", [
    (lambda: DriveProfile.table([0.0, 1.0, 2.0], [0.0, 1.0, 2.0], "theta", interpolation="linear"),
     "'linear' is for an omega table"),
    (lambda: DriveProfile.table([0.0, 1.0, 2.0], [0.0, 1.0, 2.0], interpolation="cubic"), "interpolation: must be"),
    (lambda: DriveProfile.table([0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 2.0, 2.0], smoothing=1.0), "at least 5 rows"),
    (lambda: DriveProfile.table(np.arange(6.0), np.arange(6.0), smoothing=0.0), "must be > 0"),
    (lambda: DriveProfile.table(np.arange(6.0), np.arange(6.0), smoothing=float("inf")), "smoothing: must be finite"),
    (lambda: DriveProfile("constant", 1.0, smoothing=2.0), "only for profile 'table'"),
])
def test_table_options_are_checked(make, match):
    with pytest.raises(ValueError, match=match):
        make()
