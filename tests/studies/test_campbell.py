"""Campbell diagram: labels at every speed and MAC tracking through a crossing of a flap and a
lag branch, against Southwell's closed form of the rotating cantilever."""

import tomllib

import numpy as np
import pytest

from hubbeam import api
from hubbeam.studies.campbell import campbell

#: a near-square blade laid flat: at rest the first lag frequency is w/t = 1.1 times the first
#: flap frequency; flap stiffens as f^2 = f0^2 + K (Omega / 2 pi)^2, lag as f0^2 + (K - 1) (...)^2
CROSSING = """
name = "crossing"
[beam]
formulation = "ancf"
elements = 4
length = 1.0
width = 0.011
thickness = 0.010
density = 2700.0
youngs_modulus = 70.0e9
poisson_ratio = 0.33
[hub]
motion = "fixed"
radius = 0.0
twist = 90.0
[environment]
gravity = [0.0, 0.0, 0.0]
"""
#: Southwell coefficient of the first flap mode of a uniform cantilever on the axis (Wright et
#: al. 1982: 3.6816^2 - 3.5160^2 at lambda = 1)
SOUTHWELL = 3.6816**2 - 3.5160**2


@pytest.fixture(scope="module")
def crossing(tmp_path_factory):
    path = tmp_path_factory.mktemp("campbell") / "crossing.toml"
    path.write_text(CROSSING)
    speeds = np.linspace(0.0, 50.0, 6)
    return speeds, campbell(api.load_scenario(path), speeds, count=3, formulations=("ancf",))


def test_tracked_branches_keep_their_label_through_the_crossing(crossing):
    _, ds = crossing
    tracked = ds["tracked_frequency_hz"].sel(formulation="ancf").values
    labels = ds["tracked_label"].sel(formulation="ancf").values
    assert list(ds["branch_label"].sel(formulation="ancf").values) == ["flap", "lag", "flap"]
    assert all(set(labels[:, b]) == {name} for b, name in enumerate(("flap", "lag", "flap")))
    assert np.all(np.diff(tracked, axis=0) > 0)  # every branch rises with the speed
    assert np.all(ds["mac"].sel(formulation="ancf").values > 0.95)
    # the sorted modes swap: flap first at rest, lag first at the top speed
    sorted_labels = ds["label"].sel(formulation="ancf").values
    assert list(sorted_labels[0, :2]) == ["flap", "lag"] and list(sorted_labels[-1, :2]) == ["lag", "flap"]
    f_sorted = ds["frequency_hz"].sel(formulation="ancf").values
    assert np.allclose(f_sorted[-1, :2], tracked[-1, [1, 0]])


def test_tracked_branches_follow_southwell(crossing):
    speeds, ds = crossing
    f = ds["tracked_frequency_hz"].sel(formulation="ancf").values
    rev = speeds / (2 * np.pi)
    flap = np.sqrt(f[0, 0] ** 2 + SOUTHWELL * rev**2)
    lag = np.sqrt(f[0, 1] ** 2 + (SOUTHWELL - 1.0) * rev**2)
    assert np.allclose(f[:, 0], flap, rtol=1e-2)
    assert np.allclose(f[:, 1], lag, rtol=1e-2)
    assert f[0, 1] / f[0, 0] == pytest.approx(1.1, rel=2e-3)  # EI ratio (w/t)^2, frequency ratio w/t


def test_a_free_hub_with_a_torque_law_and_its_sensors_gets_a_diagram():
    """The bundled spacecraft (free hub, PD law, an applied-torque sensor) was refused: each
    speed's driven variant kept the free hub's sensors."""
    from hubbeam.io.scenario import load_example

    result = campbell(load_example("spacecraft"), np.array([0.0, 1.0]), count=2, formulations=("ancf",))
    first = result["frequency_hz"].values[0, :, 0]
    assert np.all(np.isfinite(first)) and first[1] > first[0]  # the spin stiffens the panels


def rotor(blades: int, elements: int = 1, extra: str = "", gravity: str = "[0.0, -9.81, 0.0]", twist: float = 80.0,
          length: float = 1.0, thickness: float = 0.004):
    """N identical aluminium blades (copies) with tip masses on a hub driven at constant speed."""
    from hubbeam.io.scenario import validate

    return validate(tomllib.loads(f"""
name = "rotor{blades}"
[[beams]]
copies = {blades}
elements = {elements}
length = {length}
width = 0.05
thickness = {thickness}
density = 2700.0
youngs_modulus = 70.0e9
[beams.tip_body]
mass = 0.05
[hub]
motion = "prescribed"
radius = 0.2
twist = {twist}
[hub.drive]
profile = "constant"
omega_s = 1.0
[environment]
gravity = {gravity}
""" + extra))


def _curves(ds, reverse=False, every=1):
    """The fixed-frame branches as (label, frequencies) pairs, sorted (speeds reversed or
    thinned first): the same set however the speeds were run."""
    f = ds["fixed_frequency_hz"].values[0][::-1 if reverse else 1][::every]
    labels = ds["fixed_label"].values[0]
    return sorted(((str(labels[0, b]), f[:, b]) for b in range(f.shape[1])), key=lambda c: (c[0], c[1][0], c[1][-1]))


def _same_curves(a, b, rtol=1e-6):
    """Two sets of (label, frequencies) equal: the labels alike, the frequencies to ``rtol`` (the
    steady states of neighbouring speeds, reached from either side, agree to Newton's tolerance)."""
    return len(a) == len(b) and all(la == lb and np.allclose(fa, fb, rtol=rtol) for (la, fa), (lb, fb) in zip(a, b))


@pytest.mark.slow
@pytest.mark.parametrize("blades", [3, 4])
def test_identical_blades_give_continuous_branches_the_same_both_ways(blades):
    """Identical blades repeat every frequency N times (issue 27: single-vector MAC jumped a
    branch from 2.6 to 26.9 Hz at 41 speeds). Tracked as eigenspaces: every match is certain
    (MAC above 0.99); the changes between neighbouring speeds scale with the speed step (the
    11-speed steps at most 4 x 1.5 times the 41-speed ones: a jump does not shrink with the
    step) and stay below 5 % at 41 speeds; the 11-speed branches are the 41-speed ones at the
    common speeds, and the branches run from 0 up to 10 rad/s are the ones run from 10 down to
    0, each with its multi-blade label, in both frames. (Four blades: 41 speeds one way.)"""
    sc = rotor(blades)
    count = 2 * blades
    ways = [(11, 1), (11, -1), (41, 1)] + ([(41, -1)] if blades == 3 else [])
    runs = {(n, way): campbell(sc, np.linspace(0, 10, n)[::way], count=count) for n, way in ways}
    for ds in runs.values():
        assert ds.attrs["symmetric"] == 1 and ds.attrs["uncertain"] == ""
        assert np.all(np.isfinite(ds["tracked_frequency_hz"].values)) and np.all(ds["mac"].values[0, 1:] > 0.99)
    for frame in ("tracked", "fixed"):
        coarse, fine = (np.abs(np.diff(runs[n, 1][f"{frame}_frequency_hz"].values[0], axis=0)) for n in (11, 41))
        assert np.all(coarse.max(axis=0) <= 6.0 * fine.max(axis=0) + 1e-12)
        f = runs[41, 1][f"{frame}_frequency_hz"].values[0]
        assert np.max(fine / f[:-1]) < 0.05
    for n, way in ways:
        if way == -1:
            assert _same_curves(_curves(runs[n, 1]), _curves(runs[n, -1], reverse=True))
    assert _same_curves(_curves(runs[11, 1]), _curves(runs[41, 1], every=4))
    labels = set(runs[11, 1]["fixed_label"].values[0, -1])
    expected = {"collective", "progressive", "regressive"} | ({"differential"} if blades == 4 else set())
    assert {label.split()[0] for label in labels} == expected


def test_fixed_frame_is_the_rotating_one_shifted_by_the_harmonic():
    """An isotropic rotor: the collective (and, four blades, the differential) keep their
    rotating-frame frequency; a cyclic pair at omega_r is omega_r + Omega (progressive, forward)
    and |omega_r - Omega| (regressive) to solver precision; the nP lines are n Omega / 2 pi."""
    ds = campbell(rotor(4), [0.0, 6.0], count=4)
    f, fixed, p = (ds[name].values[0] for name in ("tracked_frequency_hz", "fixed_frequency_hz", "harmonic"))
    assert sorted(p[1]) == [-1, 0, 1, 2]
    shift = 6.0 / (2 * np.pi)
    expected = np.where((p == 0) | (p == 2), f, np.abs(f + p * shift * np.array([[0.0], [1.0]])))
    assert np.allclose(fixed, expected, rtol=1e-12)
    assert np.allclose(f[1], f[1, 0], rtol=1e-6)  # one repeated frequency in the rotating frame
    assert np.allclose(ds["np_line_hz"].values[:, 1], np.arange(1, 9) * shift)


def _whirl_spectrum(blades, omega, component, **kw):
    """Simulate the rotor at constant speed from its steady state, one blade kicked in its first
    mode, and return (the campbell dataset at that speed, frequencies, spectrum of the cyclic
    pair q_1c + i q_1s of the tip deflection ``component`` of the blades, its multi-blade
    transform taken with the blades' azimuths at each record)."""
    from hubbeam import api
    from hubbeam.io.scenario import Sensor
    from hubbeam.simulation import initial_state, simulate
    from hubbeam.solvers import generalized_alpha as ga
    from hubbeam.solvers.modal import rotating_modal_analysis
    from hubbeam.solvers.multiblade import to_multiblade

    sc = rotor(blades, **kw)
    sc = sc.model_copy(update={"hub": sc.hub.model_copy(update={"drive": sc.hub.drive.model_copy(
        update={"omega_s": omega})})})
    ds = campbell(sc, [omega], count=blades)
    system = api.build_system(sc)
    start = initial_state(system)
    from hubbeam.solvers.static import solve_static

    steady = solve_static(system, load_steps=4, spin=omega)
    mode = rotating_modal_analysis(system, steady, omega, count=1)
    kick = np.real(mode.shapes[:, 0])
    kick *= 1e-3 * 2 * np.pi * mode.frequencies_hz[0] / np.max(np.abs(kick))
    state = ga.init(system, start.x, start.chart, v0=start.v + kick)
    sensors = [Sensor(name=f"tip{k}", kind="tip_deflection", beam=f"blade{k + 1}") for k in range(blades)]
    traj = simulate(system, sensors, 16.0, 0.0025, output_dt=0.01, state=state)
    t = np.array(traj.times)
    q = np.array([[r[component] for r in traj.records[f"tip{k}"]] for k in range(blades)]).T
    q -= q.mean(axis=0)
    psi = omega * t[:, None] + np.array([b.azimuth for b in sc.resolved_beams()])[None, :]
    z = to_multiblade(q, psi)
    z = (z[:, 1] + 1j * z[:, 2]) * np.hanning(t.size)
    n = 1 << 16
    return ds, np.fft.fftshift(np.fft.fftfreq(n, t[1] - t[0])), np.abs(np.fft.fftshift(np.fft.fft(z, n)))


def _peak_near(freqs, spectrum, f0, width=0.05):
    """The spectrum's largest value within width of f0 (relative) and where it is."""
    near = np.abs(freqs - f0) < width * abs(f0)
    i = np.argmax(np.where(near, spectrum, 0.0))
    return spectrum[i], freqs[i]


@pytest.mark.parametrize("case", ["flap", "lag"])
def test_progressive_and_regressive_whirl_are_what_a_simulated_rotor_does(case):
    """Independent of the eigen-solver and of the shift by +-Omega: the nonlinear time
    integration of three blades at constant speed, one blade kicked in its first mode (so every
    harmonic moves), read through the Coleman transformation with the blades' azimuths at each
    record. The cyclic pair's spectrum (positive frequency: forward whirl) peaks at the
    progressive frequency on the forward side and at the regressive one on the side of its
    whirl sense, each within 0.3 % (the integrator's period error at dt = 2.5 ms), and is at
    least 20 times smaller at the mirrored frequencies. Flap: the regressive mode whirls
    backward (omega_r > Omega); a soft lag mode below 1P: the regressive mode whirls forward."""
    if case == "flap":
        ds, freqs, spectrum = _whirl_spectrum(3, 6.0, "vertical", gravity="[0.0, 0.0, 0.0]")
    else:  # width vertical, long and thin: the lag frequency (1.1 Hz) below the speed (1.6 Hz)
        ds, freqs, spectrum = _whirl_spectrum(3, 10.0, "tangential", gravity="[0.0, 0.0, 0.0]", twist=0.0,
                                              length=1.5, thickness=0.002)
    labels = list(ds["fixed_label"].values[0, 0])
    f = dict(zip(labels, ds["fixed_frequency_hz"].values[0, 0]))
    sense = dict(zip(labels, ds["whirl"].values[0, 0]))
    assert sense[f"progressive {case}"] == "forward"
    assert sense[f"regressive {case}"] == ("backward" if case == "flap" else "forward")
    for name in (f"progressive {case}", f"regressive {case}"):
        signed = f[name] if sense[name] == "forward" else -f[name]
        peak, where = _peak_near(freqs, spectrum, signed)
        assert where == pytest.approx(signed, rel=3e-3)
        assert peak > 20 * _peak_near(freqs, spectrum, -signed)[0]


def test_one_stiffer_blade_splits_the_repeated_frequency_and_is_said():
    """Blade 2 0.1 % stiffer: without gravity, at rest its frequencies are the others' times
    sqrt(1.001) (frequency ~ sqrt(E) with the mass unchanged); the other two stay repeated;
    every branch is followed continuously (no uncertain match), and the rotor is reported not
    symmetric (so no multi-blade labels)."""
    from hubbeam.studies.variants import variant

    sc = variant(rotor(3, gravity="[0.0, 0.0, 0.0]"), ["beams.blade2.youngs_modulus=70.07e9"])
    ds = campbell(sc, np.linspace(0, 10, 11), count=6)
    assert ds.attrs["symmetric"] == 0 and "blade2 differs from blade1 in youngs_modulus" in ds.attrs["symmetry"]
    assert "fixed_frequency_hz" not in ds and ds.attrs["uncertain"] == ""
    f = ds["tracked_frequency_hz"].values[0]
    assert f[0, 2] / f[0, 0] == pytest.approx(np.sqrt(1.001), rel=1e-7)
    assert f[0, 1] == pytest.approx(f[0, 0], rel=1e-7) and f[0, 5] / f[0, 3] == pytest.approx(np.sqrt(1.001), rel=1e-7)
    assert np.max(np.abs(np.diff(f, axis=0))) < 2 * 1.0 / (2 * np.pi)
    assert np.all(f[:, 2] > f[:, 1] * (1 + 1e-4))  # the split holds at every speed
    assert list(ds["branch_label"].values[0]) == ["flap"] * 6


def test_what_makes_a_rotor_symmetric():
    from hubbeam.studies.campbell import rotor_symmetry
    from hubbeam.studies.variants import variant

    psi, why = rotor_symmetry(rotor(3))
    assert why == "" and np.allclose(np.degrees(psi), [0, 120, 240])
    for overrides, reason in ((["hub.orientation=[10.0, 0.0, 0.0]"], "is not along the hub axis"),
                              (["beams[*].copies=2"], "at least 3 identical beams (this rotor has 2)"),
                              (["beams.blade3.azimuth=250.0"], "are not evenly spaced"),
                              (["loads.tip_force=[0.0, 1.0, 0.0]"], "a tip load acts on blade1"),
                              (["beams.blade1.tip_body.mass=0.06"], "blade2 differs from blade1 in tip_body")):
        assert rotor_symmetry(variant(rotor(3), overrides))[0] is None
        assert reason in rotor_symmetry(variant(rotor(3), overrides))[1]
    # a tilted hub with gravity along its tilted axis, or without gravity, is symmetric
    assert rotor_symmetry(variant(rotor(3, gravity="[0.0, 0.0, 0.0]"), ["hub.orientation=[10.0, 0.0, 0.0]"]))[1] == ""
