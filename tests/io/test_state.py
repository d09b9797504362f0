"""A run's NetCDF file with --state: the sensors as before, the state's variables, units and
dimensions, and read back by hubbeam.io.state."""

import json

import numpy as np
import pytest
import xarray as xr

from hubbeam import api
from hubbeam.errors import ScenarioError
from hubbeam.io.results import to_dataset, write_csv, write_trajectory_netcdf
from hubbeam.io.scenario import load_example
from hubbeam.io.state import NO_STATE, hub_rotation, read_state

SHORT = ["analysis.t_end=0.04", "analysis.output_dt=0.01"]


@pytest.fixture(scope="module")
def rotor_run():
    scenario = load_example("rotor3", SHORT)
    plain, failure = api.run(scenario)
    assert failure is None
    traj, failure = api.run(scenario, state=True)
    assert failure is None
    return scenario, plain, traj


def test_the_sensor_variables_stay_as_they_are(rotor_run, tmp_path):
    scenario, plain, traj = rotor_run
    write_trajectory_netcdf(plain, scenario, tmp_path / "plain.nc")
    write_trajectory_netcdf(traj, scenario, tmp_path / "state.nc")
    with xr.open_dataset(tmp_path / "plain.nc") as a, xr.open_dataset(tmp_path / "state.nc") as b:
        for name in a.data_vars:
            np.testing.assert_array_equal(a[name].values, b[name].values)
            assert a[name].attrs == b[name].attrs and a[name].dims == b[name].dims
        for key, value in a.attrs.items():
            assert b.attrs[key] == value
        added = set(b.data_vars) - set(a.data_vars)
        assert all(name.startswith("state_") for name in added)
        assert json.loads(b.attrs["state_beams"]) == ["blade1", "blade2", "blade3"]
        n = 4 * 4 + 1  # 4 elements, 4 pieces each
        line = b["state_blade2_centre_line"]
        assert line.dims == ("time", "state_blade2_station", "state_xyz") and line.shape == (5, n, 3)
        assert line.attrs["units"] == "m" and b["state_blade2_m"].attrs["units"] == "1"
        assert b["state_blade2_surface_strain"].dims == ("time", "state_blade2_station")
        assert b["state_blade2_station"].attrs["units"] == "m"
        assert b["state_hub_angle"].attrs["units"] == "rad"
        np.testing.assert_array_equal(b["state_blade1_width"].values, 0.06)
        np.testing.assert_array_equal(b["state_blade1_thickness"].values, 0.004)


def test_the_csv_keeps_the_time_series_alone(rotor_run, tmp_path):
    scenario, plain, traj = rotor_run
    write_csv(to_dataset(plain, scenario), tmp_path / "plain.csv")
    write_csv(to_dataset(traj, scenario), tmp_path / "state.csv")
    assert (tmp_path / "plain.csv").read_text() == (tmp_path / "state.csv").read_text()


def test_read_state_gives_back_what_was_recorded(rotor_run, tmp_path):
    scenario, _, traj = rotor_run
    write_trajectory_netcdf(traj, scenario, tmp_path / "state.nc")
    state = read_state(tmp_path / "state.nc")
    assert state.name == "rotor3" and state.hub_radius == 0.2
    np.testing.assert_array_equal(state.times, traj.times)
    np.testing.assert_array_equal(state.hub_angle, [s.hub_angle for s in traj.snapshots])
    for k, beam in enumerate(state.beams):
        np.testing.assert_array_equal(beam.centre_line, [s.beams[k].centre_line for s in traj.snapshots])
        np.testing.assert_array_equal(beam.surface_strain, [s.beams[k].strain for s in traj.snapshots])
        # deflection: measured from the undeformed blade turned with the hub; the tip's equals the
        # tip sensor's (radial, vertical, tangential) in the blade's own hub frame
        disp = state.displacement(k)
        for i, t in enumerate(state.times):
            psi = np.radians(120.0 * k)
            A = hub_rotation(state.hub_angle[i] + psi)[0]
            sensor = traj.records[f"tip{k + 1}"][i]
            np.testing.assert_allclose(A.T @ disp[i, -1], [sensor["radial"], sensor["vertical"], sensor["tangential"]],
                                       atol=1e-12)


def test_a_file_without_state_or_not_netcdf_is_one_clear_line(rotor_run, tmp_path):
    scenario, plain, _ = rotor_run
    write_trajectory_netcdf(plain, scenario, tmp_path / "plain.nc")
    with pytest.raises(ScenarioError, match="--state"):
        read_state(tmp_path / "plain.nc")
    assert "--state" in NO_STATE
    (tmp_path / "text.nc").write_text("not netcdf")
    with pytest.raises(ScenarioError, match="not a NetCDF"):
        read_state(tmp_path / "text.nc")
    with pytest.raises(ScenarioError, match="no such file"):
        read_state(tmp_path / "missing.nc")


def test_a_sensor_named_like_the_state_is_refused_with_state():
    scenario = load_example("exp1", SHORT + ['sensors[0].name="state_hub_angle"'])
    with pytest.raises(ScenarioError, match=r"sensors\[0\].name"):
        api.run(scenario, state=True)
