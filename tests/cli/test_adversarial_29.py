"""The adversarial pass of issue 29, first part: each test is a class of defect found there
(wrong numbers with exit 0, results lost, internal errors, late failures) and fails without
its fix. The classes: a sweep's time axis (1), sensors of one name (2), identification (3:
more in tests/studies/test_identify.py), concurrent vtk exports (4), accepted inputs with
wrong or lost results (5), internal errors after the computation (6), stored states (8),
tables and keys beyond the scenario's limits (9), the Python API's argument types (10), and
numpy reprs, late signals and a switched hub that keeps its torque sensor. The Newton test
(11) is in tests/solvers/test_newton_test.py."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from hubbeam import api
from hubbeam.io.scenario import ScenarioError, load_scenario
from tests.cli.helpers import assert_contract, cli, finish, no_temporary_files, popen, without_notes

pytestmark = pytest.mark.filterwarnings("ignore")

TINY = """name = "tiny"
[beam]
formulation = "ancf"
elements = 2
length = 1.0
width = 0.05
thickness = 0.005
density = 2700.0
youngs_modulus = 70.0e9
[hub]
{hub}
[analysis]
kind = "dynamic"
t_end = 0.2
dt = 0.002
{analysis}
{sensors}"""
FREE = 'motion = "free"\nradius = 0.1\ninertia = 1.0\ntorque = 0.1'
FIXED = 'motion = "fixed"\nradius = 0.1'
SPIN = 'motion = "prescribed"\nradius = 0.1\n[hub.drive]\nprofile = "spin_up"\nomega_s = 2.0\nT = 1.0'
PD = ('motion = "free"\nradius = 0.1\ninertia = 1.0\n[hub.torque]\nlaw = "pd"\nkp = {kp}\nkd = {kd}\n'
      '[hub.torque.reference]\nprofile = "slew"\nangle = 0.5\nT = 1.0')
OMEGA = '[[sensors]]\nname = "w"\nkind = "hub_angular_velocity"\n'


def write(tmp_path, hub=FREE, analysis="", sensors=OMEGA, name="s.toml"):
    path = tmp_path / name
    path.write_text(TINY.format(hub=hub, analysis=analysis, sensors=sensors))
    return path


def sensors(*pairs):
    return "".join(f'[[sensors]]\nname = "{n}"\nkind = "{k}"\n' for n, k in pairs)


# ------------------------------------------------------------- 1. a sweep's time axis
def _sweep_against_direct_runs(tmp_path, key, values, analysis=""):
    import xarray as xr

    path = write(tmp_path, analysis=analysis)
    code, out, err = cli("sweep", path, "--vary", f"{key}={values}", "-o", tmp_path / "sw.nc", "--workers", "1")
    assert code == 0, err
    with xr.open_dataset(tmp_path / "sw.nc") as ds:
        ds = ds.load()
    for value in ds[key].values:
        direct, failure = api.run(load_scenario(path, [f"{key}={float(value)!r}"]))
        assert failure is None
        t = np.array(direct.times)
        got = ds["w"].sel({key: value}).sel(time=t).values  # every direct output time is on the sweep's axis
        np.testing.assert_array_equal(got, np.array(direct.records["w"]))
        others = np.setdiff1d(ds["time"].values, t)
        assert np.all(np.isnan(ds["w"].sel({key: value}).sel(time=others).values))  # not copied from another point
    return ds


def test_a_time_step_convergence_study_keeps_each_point_on_its_own_times(tmp_path):
    """--vary analysis.dt=0.002:0.004:2: the dt = 4 ms point's hub speed at "t = 0.1 s" was its
    value at 0.2 s (each point's values were copied positionally onto the longest axis; exit 0)."""
    ds = _sweep_against_direct_runs(tmp_path, "analysis.dt", "0.002:0.004:2")
    assert ds.sizes["time"] == 101  # the union: the 2 ms axis holds every 4 ms time


def test_a_sweep_over_output_dt_keeps_each_point_on_its_own_times(tmp_path):
    _sweep_against_direct_runs(tmp_path, "analysis.output_dt", "0.004:0.01:2", "output_dt = 0.004")


def test_a_sweep_too_large_for_memory_on_its_union_of_times_is_refused(tmp_path):
    code, out, err = cli("sweep", write(tmp_path), "--vary", "analysis.dt=0.00001:0.00002:1000",
                         "--vary", "analysis.t_end=10:20:50", "-o", tmp_path / "sw.nc")
    assert_contract(code, out, err)
    assert code == 2 and without_notes(err).startswith("hubbeam: error: --vary:") and "GiB" in err, err
    assert not (tmp_path / "sw.nc").exists()


def test_merge_places_values_at_their_times_and_keeps_every_mode():
    """Without Dask: two points on 2 ms and 4 ms axes; a modes point with 60 frequencies (the
    merge had 50 hard-coded and failed after computing every point)."""
    from hubbeam.studies.sweep import _merge

    varied = {"analysis.dt": (np.array([0.002, 0.004]), False)}
    t2, t4 = np.round(np.arange(0, 0.0201, 0.002), 10), np.round(np.arange(0, 0.0201, 0.004), 10)
    results = {(0,): {"values": {"w": (t2, t2 * 10)}, "failure": None},
               (1,): {"values": {"w": (t4, t4 * 10)}, "failure": None}}
    ds = _merge(varied, [((0,), []), ((1,), [])], results)
    assert ds["w"].sel({"analysis.dt": 0.004, "time": 0.008}).item() == pytest.approx(0.08)
    assert np.isnan(ds["w"].sel({"analysis.dt": 0.004, "time": 0.006}).item())
    varied = {"beam.thickness": (np.array([0.004, 0.005]), False)}
    results = {(0,): {"values": {"frequency_hz": np.arange(1.0, 61.0)}, "failure": None},
               (1,): {"values": {"frequency_hz": np.arange(1.0, 41.0)}, "failure": None}}
    ds = _merge(varied, [((0,), []), ((1,), [])], results)
    assert ds.sizes["mode"] == 60 and np.isnan(ds["frequency_hz"].values[1, 45])


# ------------------------------------------------------------- 2. sensors of one name
@pytest.mark.parametrize("first,second", [("hub_angle", "energy"), ("hub_angle", "tip_deflection"),
                                          ("energy", "energy"), ("tip_deflection", "hub_angular_velocity"),
                                          ("hub_angle", "hub_angle"), ("angular_momentum", "energy")])
def test_two_sensors_of_one_name_are_refused_naming_the_key(tmp_path, first, second):
    """{name="a", kind="hub_angle"} and {name="a", kind="energy"} ran (exit 0) and the hub angle
    was missing from every result file."""
    path = write(tmp_path, sensors=sensors(("w", "hub_angular_velocity"), ("a", first), ("a", second)))
    code, out, err = cli("run", path, "--csv", tmp_path / "r.csv")
    assert_contract(code, out, err)
    assert code == 2 and "sensors[2].name: duplicate sensor name 'a' (also sensors[1])" in err, err
    assert not (tmp_path / "r.csv").exists()


# ------------------------------------------------------------- 3. identification (inputs)
def test_a_record_with_two_columns_of_one_name_is_refused(tmp_path):
    """pandas renamed the second strain_P1 to strain_P1.1 and one of them was fitted without a word."""
    from tests.cli.helpers import EXAMPLES

    path = tmp_path / "m.csv"
    path.write_text("time,strain_P1,strain_P1\n" + "".join(f"{0.1 * k:g},{np.sin(k)},{np.cos(k)}\n" for k in range(8)))
    code, out, err = cli("identify", EXAMPLES / "exp1.toml", path, "--fit", "damping.linear")
    assert_contract(code, out, err)
    assert code == 2 and f"{path}: column 'strain_P1' appears 2 times" in err, err


@pytest.mark.parametrize("key", ["analysis.dt", "analysis.t_end", "analysis.spectral_radius"])
def test_an_analysis_setting_is_not_a_parameter_to_fit(tmp_path, key):
    from tests.cli.helpers import EXAMPLES

    path = tmp_path / "m.csv"
    path.write_text("time,strain_P1\n" + "".join(f"{0.1 * k:g},{np.sin(k)}\n" for k in range(8)))
    code, out, err = cli("identify", EXAMPLES / "exp1.toml", path, "--fit", key)
    assert code == 2 and f"--fit {key}: an analysis setting" in err, err


# ------------------------------------------------------------- 4. concurrent vtk exports
@pytest.fixture(scope="module")
def two_states(tmp_path_factory):
    d = tmp_path_factory.mktemp("states")
    path = write(d, analysis="output_dt = 0.002")
    for name, torque in (("a.nc", "0.1"), ("b.nc", "0.5")):
        code, _, err = cli("run", path, "-o", d / name, "--state", "--set", f"hub.torque={torque}")
        assert code == 0, err
    return d / "a.nc", d / "b.nc"


def test_two_concurrent_vtk_exports_into_one_directory_do_not_mix(two_states, tmp_path):
    """Both exited 0 and the .pvd listed files of the other run (a check-then-write race)."""
    out = tmp_path / "series"
    for attempt in range(3):  # the loser must lose at the lock, whichever starts first
        procs = [popen("vtk", state, "-o", out) for state in two_states]
        results = [(p, *finish(p)) for p in procs]
        codes = sorted(p.returncode for p, _, _ in results)
        for p, stdout, stderr in results:
            assert_contract(p.returncode, stdout, stderr)
        assert codes == [0, 2], [r[2] for r in results]
        loser = next(stderr for p, _, stderr in results if p.returncode == 2)
        assert ("another hubbeam vtk" in loser and "is writing the series 'tiny'" in loser) or \
            "holds a series named 'tiny' already" in loser, loser
        winner = two_states[[p.returncode for p, _, _ in results].index(0)]
        from hubbeam.io import vtk
        from hubbeam.io.state import read_state

        expected = vtk.pvd_text(read_state(winner))
        assert (out / "tiny.pvd").read_text() == expected  # its own times only
        import meshio

        last = meshio.read(out / "tiny_00100.vtu")
        state = read_state(winner)
        np.testing.assert_allclose(last.points[0::2], state.beams[0].centre_line[100] - 0.5 * 0.05 *
                                   state.beams[0].m[100], atol=1e-12)  # the winner's geometry, not the loser's
        assert not [p for p in out.iterdir() if p.name.endswith("hubbeam-lock")]
        for p in out.iterdir():
            p.unlink()


def test_a_lock_left_by_a_killed_export_is_taken_over(two_states, tmp_path):
    out = tmp_path / "series"
    out.mkdir()
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    (out / ".tiny.hubbeam-lock").write_text(dead.stdout.strip())  # a process that is gone
    code, stdout, err = cli("vtk", two_states[0], "-o", out)
    assert code == 0, err
    (out / ".tiny.hubbeam-lock").write_text(str(os.getpid()))  # a live one: this test's own process
    code, stdout, err = cli("vtk", two_states[1], "-o", out, "--force")
    assert_contract(code, stdout, err)
    assert code == 2 and "another hubbeam vtk" in err, err


# ------------------------------------------------------------- 5. accepted inputs, wrong or lost results
@pytest.mark.parametrize("hub", [FIXED, SPIN])
@pytest.mark.parametrize("torque", ["law", "number", "function"])
def test_api_run_refuses_a_torque_law_on_a_held_hub(tmp_path, hub, torque):
    """api.run(sc, torque=...) on a fixed or prescribed hub ignored the law (identical results)."""
    from hubbeam.system.laws import TorqueLaw

    law = {"law": TorqueLaw.constant(5.0), "number": 5.0, "function": lambda t, th, om: 5.0}[torque]
    with pytest.raises(ScenarioError, match=r"^torque: a torque law acts on a free hub only"):
        api.run(write(tmp_path, hub=hub), torque=law)


@pytest.mark.parametrize("kp,kd,key", [(1e20, 0.0, "kp"), (1e12, 1.0, "kp"), (1.0, 1e9, "kd"), (0.0, 1e6, "kd")])
def test_a_pd_gain_whose_torque_is_round_off_is_refused(tmp_path, kp, kd, key):
    """kp = 1e20 recorded -346.9 N m of round-off torque and broke the energy balance (exit 0)."""
    code, out, err = cli("run", write(tmp_path, hub=PD.format(kp=kp, kd=kd)))
    assert_contract(code, out, err)
    assert code == 2 and without_notes(err).startswith(f"hubbeam: error: hub.torque.{key}:") and "time step" in err, err


@pytest.mark.parametrize("kp,kd", [(20.0, 5.0), (1e6, 1e3)])
def test_a_pd_gain_the_step_resolves_is_accepted(tmp_path, kp, kd):
    load_scenario(write(tmp_path, hub=PD.format(kp=kp, kd=kd)))


@pytest.mark.parametrize("value", ['name="abc', "name='abc", "beam.elements=[1, 2", "hub={motion=", 'name="a"b"'])
def test_a_malformed_set_value_is_refused_not_taken_as_text(tmp_path, value):
    """--set 'name="abc' (an unterminated string) ran as the name '"abc' (exit 0)."""
    code, out, err = cli("run", write(tmp_path), "--set", value)
    assert_contract(code, out, err)
    assert code == 2 and without_notes(err).startswith(f"hubbeam: error: --set {value}: not a valid TOML value"), err


def test_a_bare_word_is_still_a_string(tmp_path):
    code, out, err = cli("run", write(tmp_path), "--set", "name=plain_word", "--json")
    assert code == 0, err


def _closed_stdout():
    os.close(1)


@pytest.mark.parametrize("args", [["run", "{s}", "--json"], ["run", "{s}"], ["example", "exp1"]])
def test_a_closed_stdout_is_a_failed_write_not_success(tmp_path, args):
    """--json with stdout closed exited 0 with the result lost."""
    path = write(tmp_path)
    done = subprocess.run([sys.executable, "-m", "hubbeam.cli", *[a.format(s=path) for a in args]],
                          stderr=subprocess.PIPE, text=True, preexec_fn=_closed_stdout, timeout=300)
    assert done.returncode == 1, done.stderr
    assert_contract(done.returncode, "", done.stderr)
    assert "stdout is closed" in done.stderr


@pytest.mark.parametrize("args", [["run", "{s}", "--json"], ["run", "{s}"], ["example", "exp1"]])
def test_stdout_on_a_full_device_is_one_line_not_an_internal_error(tmp_path, args):
    """stdout on /dev/full printed "internal error: OSError" (exit 1)."""
    path = write(tmp_path)
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-m", "hubbeam.cli", *[a.format(s=path) for a in args]],
                              stdout=full, stderr=subprocess.PIPE, text=True, timeout=300)
    assert done.returncode == 1, done.stderr
    assert_contract(done.returncode, "", done.stderr)
    assert without_notes(done.stderr).startswith("hubbeam: cannot write results: stdout: cannot write (No space left on device)")


# ------------------------------------------------------------- 6. results lost after the computation
def test_a_run_without_sensors_writes_its_csv_with_the_times(tmp_path):
    """--csv of a scenario without sensors failed ("no valid index for a 0-dimensional object", exit 1)."""
    path = write(tmp_path, sensors="")
    code, out, err = cli("run", path, "--csv", tmp_path / "r.csv", "-o", tmp_path / "r.nc")
    assert code == 0, err
    lines = (tmp_path / "r.csv").read_text().splitlines()
    assert lines[0] == "time" and len(lines) == 102 and float(lines[-1]) == 0.2


@pytest.mark.parametrize("shape", [(1, 3), (3, 1), (1, 1)])
def test_an_applicability_map_of_one_row_or_column_is_drawn(tmp_path, shape):
    """A 1 x N grid wrote two of its three files and failed in matplotlib's contour."""
    import xarray as xr

    from hubbeam import plots

    h, r = shape
    ds = xr.Dataset({"frequency_error_pct": (("thickness", "ratio"), np.linspace(-5, 5, h * r).reshape(h, r)),
                     "deflection_error_pct": (("thickness", "ratio"), np.linspace(0, 30, h * r).reshape(h, r)),
                     "w_m_over_L": ("thickness", np.linspace(0.2, 0.6, h))},
                    coords={"thickness": np.linspace(0.001, 0.004, h), "ratio": np.linspace(0, 0.5, r)})
    plots.plot_applicability(ds, tmp_path / "a.png")
    assert (tmp_path / "a.png").stat().st_size > 0


# ------------------------------------------------------------- 8. stored states are trusted
@pytest.fixture(scope="module")
def state_file(tmp_path_factory):
    d = tmp_path_factory.mktemp("state")
    code, _, err = cli("run", write(d, analysis="output_dt = 0.02"), "-o", d / "r.nc", "--state")
    assert code == 0, err
    return d / "r.nc"


def _damaged(state_file, tmp_path, damage):
    import xarray as xr

    with xr.open_dataset(state_file) as ds:
        ds = ds.load()
    ds = damage(ds)
    path = tmp_path / "bad.nc"
    ds.to_netcdf(path, engine="h5netcdf")
    return path


def _repeat_a_time(ds):
    t = ds["time"].values.copy()
    t[3] = t[2]
    return ds.assign_coords(time=t)


def _shorter_strain(ds):
    strain = ds["state_beam1_surface_strain"]
    short = strain.isel(time=slice(0, 5)).rename(time="t_short").drop_vars("t_short", errors="ignore")
    return ds.drop_vars("state_beam1_surface_strain").assign(state_beam1_surface_strain=short)


def _nan_radius(ds):
    ds.attrs["state_hub_radius"] = float("nan")
    return ds


def _no_beams(ds):
    ds.attrs["state_beams"] = "[]"
    ds.attrs["state_formulations"] = "[]"
    return ds


def _one_station(ds):
    keep = ds.isel(state_beam1_station=slice(0, 1))
    return keep


@pytest.mark.parametrize("command,target", [("animate", "m.gif"), ("vtk", "series")])
@pytest.mark.parametrize("damage,message", [
    (_repeat_a_time, "time repeats at output 3"), (_shorter_strain, "state_beam1_surface_strain has shape (5, 9), expected (11, 9)"),
    (_nan_radius, "state_hub_radius is nan"), (_no_beams, "holds no beam"),
    (_one_station, "state_beam1_station has shape (1,)")])
def test_a_damaged_state_is_refused_before_anything_is_written(state_file, tmp_path, command, target, damage,
                                                              message):
    """An empty state or arrays of other lengths failed late ("cannot write (IndexError ...)")
    after writing part of the output; repeated times and a NaN hub radius were drawn silently."""
    bad = _damaged(state_file, tmp_path, damage)
    code, out, err = cli(command, bad, "-o", tmp_path / target)
    assert_contract(code, out, err)
    assert code == 2 and without_notes(err).startswith(f"hubbeam: error: result file {bad}: the stored state") and message in err, err
    assert not (tmp_path / target).exists() and no_temporary_files(tmp_path)


# ------------------------------------------------------------- 9. tables and keys beyond the limits
TORQUE_TABLE = 'motion = "free"\nradius = 0.1\ninertia = 1.0\n[hub.torque]\nlaw = "table"\nfile = "t.csv"'
DRIVE_TABLE = 'motion = "prescribed"\nradius = 0.1\n[hub.drive]\nprofile = "table"\nfile = "t.csv"'


@pytest.mark.parametrize("hub,column", [(TORQUE_TABLE, "torque"), (DRIVE_TABLE, "omega"), (DRIVE_TABLE, "theta")])
@pytest.mark.parametrize("rows,message", [
    ("0,0\n0.1,1e300\n0.2,0\n", "row 2 (line 3), column '{column}': '1e300' is outside the range"),
    ("0,0\n0.1,-1e151\n0.2,0\n", "row 2 (line 3), column '{column}': '-1e151' is outside the range"),
    ("0,0\n1e-300,1\n2e-300,0\n", "row 2 (line 3): 1e-300 s is 1e-300 s after the row before, closer than 1e-09 s"),
    ("0,0\n0.1,1\n0.1000000000001,0\n", "row 3 (line 4): 0.1000000000001 s is 1e-13 s after"),
    ("0,0\n1e300,1\n2e300,0\n", "row 2 (line 3), column 'time': '1e300' is outside the range"),
])
def test_a_table_beyond_the_scenarios_limits_is_refused_at_validation(tmp_path, hub, column, rows, message):
    """A 1e300 cell or times 0, 1e-300, 2e-300 passed validation and failed later with advice
    blaming the time step or the mesh."""
    (tmp_path / "t.csv").write_text(f"time,{column}\n" + rows)
    code, out, err = cli("run", write(tmp_path, hub=hub))
    assert_contract(code, out, err)
    key = "hub.torque.file" if column == "torque" else "hub.drive.file"
    assert code == 2 and without_notes(err).startswith(f"hubbeam: error: {key}: {tmp_path / 't.csv'}: ") and \
        message.format(column=column) in err, err
    assert "np.float64" not in err


@pytest.mark.parametrize("setting,message", [
    ("beam.damping.stiffness_proportional=1e100", "beam.damping.stiffness_proportional: must be <= 1000"),
    ("beam.damping.stiffness_proportional=1e4", "beam.damping.stiffness_proportional: must be <= 1000"),
    ("analysis.tolerance=1e-300", "analysis.tolerance: must be >= 1e-12"),
    ("analysis.tolerance=1e-13", "analysis.tolerance: must be >= 1e-12"),
])
def test_keys_beyond_their_meaningful_range_are_refused(tmp_path, setting, message):
    code, out, err = cli("run", write(tmp_path), "--set", setting)
    assert_contract(code, out, err)
    assert code == 2 and message in err, err


@pytest.mark.parametrize("setting", ["beam.damping.stiffness_proportional=1000.0", "analysis.tolerance=1e-12"])
def test_the_limits_themselves_are_accepted(tmp_path, setting):
    code, out, err = cli("run", write(tmp_path), "--set", setting, "--set", "analysis.t_end=0.01")
    assert code == 0, err


# ------------------------------------------------------------- 10. the API's argument types
@pytest.fixture(scope="module")
def free_hub(tmp_path_factory):
    return load_scenario(write(tmp_path_factory.mktemp("api"), analysis="output_dt = 0.02"))


def test_a_number_is_a_constant_torque_and_a_function_a_callable_law(free_hub):
    """torque=5 and torque=lambda ... ended in AttributeError ('int' object has no attribute 'compilable')."""
    from hubbeam.system.laws import TorqueLaw

    by_law, _ = api.run(free_hub, torque=TorqueLaw.constant(0.5))
    by_number, _ = api.run(free_hub, torque=0.5)
    by_function, _ = api.run(free_hub, torque=lambda t, theta, omega: 0.5)
    assert by_number.records["w"] == by_law.records["w"]
    np.testing.assert_allclose(by_function.records["w"], by_law.records["w"], rtol=1e-9, atol=1e-15)


@pytest.mark.parametrize("torque,error,text", [
    ("5", TypeError, "torque: expected a TorqueLaw, a number"), ([1.0], TypeError, "torque: expected"),
    (float("nan"), ValueError, "torque: must be a finite number"), (True, TypeError, "torque: expected"),
    (lambda t: 1.0, TypeError, "torque: the function must take (t, theta, omega)"),
    (lambda t, th, om: "x", TypeError, "torque: the function must take"),
    (lambda t, th, om: float("inf"), ValueError, "torque: the function returns inf")])
def test_a_torque_of_another_type_is_named(free_hub, torque, error, text):
    with pytest.raises(error) as info:
        api.run(free_hub, torque=torque)
    assert str(info.value).startswith(text), info.value


def test_sensors_by_name_and_a_single_name_is_one_sensor(free_hub):
    """sensors='tip' ended in AttributeError ('str' object has no attribute 'name')."""
    traj, _ = api.run(free_hub, sensors="w")
    assert list(traj.records) == ["w"]
    with pytest.raises(ScenarioError, match=r"^sensors\[0\]: the scenario has no sensor named 'tip'"):
        api.run(free_hub, sensors="tip")
    with pytest.raises(TypeError, match=r"^sensors: expected a list"):
        api.run(free_hub, sensors=3)
    with pytest.raises(TypeError, match=r"^sensors\[1\]: expected a Sensor"):
        api.run(free_hub, sensors=["w", 3])
    with pytest.raises(ScenarioError, match=r"duplicate sensor name 'w'"):
        api.run(free_hub, sensors=["w", "w"])


def test_linearize_takes_one_input_name_as_one_input(free_hub):
    """inputs="hub_torque" was read character by character ("unknown input 'h'")."""
    one = api.linearize(free_hub, inputs="hub_torque")
    listed = api.linearize(free_hub, inputs=["hub_torque"])
    np.testing.assert_array_equal(one.B, listed.B)
    with pytest.raises(TypeError, match=r"^inputs: expected a list of input names"):
        api.linearize(free_hub, inputs=5)
    with pytest.raises(TypeError, match=r"^inputs: every input is a name"):
        api.linearize(free_hub, inputs=[1])


def test_to_dataset_of_another_scenario_is_named(free_hub, tmp_path):
    """to_dataset(traj, other_scenario) ended in KeyError, or wrote the other scenario's attributes."""
    from hubbeam.io.results import to_dataset

    traj, _ = api.run(free_hub)
    assert list(to_dataset(traj, free_hub).data_vars) == ["w"]
    other = load_scenario(write(tmp_path, hub=FIXED, sensors=sensors(("a", "hub_angle"))))
    with pytest.raises(ValueError, match=r"^scenario: not the scenario this trajectory was run with"):
        to_dataset(traj, other)
    with pytest.raises(TypeError, match=r"^scenario: expected the Scenario"):
        to_dataset(traj, "s.toml")
    with pytest.raises(TypeError, match=r"^trajectory: expected the trajectory"):
        to_dataset({"w": [1.0]}, free_hub)
    bare = api.run(free_hub)[0]
    bare.scenario = None  # a trajectory made elsewhere: its sensors still must be the scenario's
    with pytest.raises(ValueError, match=r"^scenario: the trajectory's sensor 'w' is not one of this scenario's"):
        to_dataset(bare, other)


# ------------------------------------------------------------- also seen
@pytest.mark.parametrize("csv,key,message", [
    ("time,torque\n0,1\n0.1,2\n0.1,3\n", "hub.torque.file", "a duplicate time (0.1 after 0.1)"),
    ("time,theta\n0,0.1\n0.1,2\n0.2,3\n", "hub.drive.file", "the first theta must be 0 rad, the initial configuration "
                                                            "(found 0.1)"),
    ("time,omega\n0.5,0\n1,1\n2,3\n", "hub.drive.file", "the first time must be 0 s (found 0.5)")])
def test_messages_show_numbers_not_numpy_reprs(tmp_path, csv, key, message):
    """"a duplicate time (np.float64(0.1) after np.float64(0.1))"."""
    (tmp_path / "t.csv").write_text(csv)
    hub = TORQUE_TABLE if key == "hub.torque.file" else DRIVE_TABLE
    code, out, err = cli("run", write(tmp_path, hub=hub))
    assert code == 2 and message in err and "np." not in err, err


def test_a_measured_cell_that_is_not_a_number_shows_as_written(tmp_path):
    from tests.cli.helpers import EXAMPLES

    path = tmp_path / "m.csv"
    path.write_text("time,strain_P1\n" + "".join(f"{0.1 * k:g},{'nan' if k == 3 else np.sin(k)}\n" for k in range(8)))
    code, out, err = cli("identify", EXAMPLES / "exp1.toml", path, "--fit", "damping.linear")
    assert code == 2 and "row 5: not a number (nan)" in err and "np." not in err, err


def test_a_signal_after_the_command_is_one_line_not_a_silent_kill():
    """A signal in the last moments of a command (after its handlers were put back) killed it
    with the default action and no line."""
    code = ("import os, signal\nfrom hubbeam import interrupt\nwith interrupt.handling(final=True):\n    pass\n"
            "os.kill(os.getpid(), signal.SIGTERM)\nimport time; time.sleep(5)\nprint('not reached')")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 143, (done.returncode, done.stderr)
    assert done.stderr == "hubbeam: interrupted by SIGTERM after the command had finished (its results are complete)\n"
    assert done.stdout == ""


def test_switching_a_free_hub_to_fixed_drops_its_applied_torque_sensor_too(tmp_path):
    """--set hub.motion=fixed dropped hub.torque (with a note) and then refused the scenario's
    applied_torque sensor, even for modes, which records no sensors."""
    path = write(tmp_path, sensors=sensors(("w", "hub_angular_velocity"), ("tq", "applied_torque")),
                 analysis='output_dt = 0.02')
    code, out, err = cli("run", path, "--set", "hub.motion=fixed", "--set", "analysis.t_end=0.01", "--json")
    assert code == 0, err
    assert "hub.torque, sensors[1] ('tq', applied_torque) dropped (motion 'fixed' does not take them)" in err, err
    assert list(json.loads(out)["final"]) == ["w"]
    code, out, err = cli("modes", path, "--set", "hub.motion=fixed", "--set", "analysis.kind=modes")
    assert code == 0, err
    code, out, err = cli("run", path, "--set", "hub.motion=fixed", "--set", "sensors[1].name=tq2")
    assert code == 2 and "sensors[1].kind: applied_torque needs hub.motion = 'free'" in err, err
