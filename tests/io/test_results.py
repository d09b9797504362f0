"""A run's NetCDF file written directly (h5netcdf) has the layout of the xarray Dataset."""

import numpy as np
import xarray as xr

from hubbeam import api
from hubbeam.io.results import to_dataset, write_trajectory_netcdf
from hubbeam.io.scenario import load_example


def test_trajectory_netcdf_reads_back_as_the_dataset(tmp_path):
    scenario = load_example("cantilever", ['analysis.kind="dynamic"', "analysis.t_end=0.02", "analysis.dt=0.005",
                                           "beam.elements=2"])
    traj, failure = api.run(scenario)
    assert failure is None
    path = tmp_path / "run.nc"
    write_trajectory_netcdf(traj, scenario, path)
    expected = to_dataset(traj, scenario)
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        assert set(ds.data_vars) == set(expected.data_vars) == {"tip_radial", "tip_vertical", "tip_tangential"}
        np.testing.assert_array_equal(ds.time.values, expected.time.values)
        for name in expected.data_vars:
            np.testing.assert_array_equal(ds[name].values, expected[name].values)
            assert ds[name].attrs == expected[name].attrs
        assert ds.time.attrs["units"] == "s"
        assert {k: ds.attrs[k] for k in ("name", "scenario")} == {k: expected.attrs[k] for k in ("name", "scenario")}
        assert int(ds.attrs["steps"]) == traj.steps == 4


def test_benchmark_scenarios_load_and_run(tmp_path):
    """benchmarks/case_a.toml and case_b.toml (issue 6) are valid scenarios that run."""
    from pathlib import Path

    from hubbeam.io.scenario import load_scenario

    here = Path(__file__).resolve().parents[2] / "benchmarks"
    for name, part in (("case_a.toml", "vertical"), ("case_b.toml", "tangential")):
        scenario = load_scenario(here / name, ["analysis.t_end=0.005"])
        traj, failure = api.run(scenario)
        assert failure is None and traj.steps == 5
        assert np.isfinite(traj.records["tip"][-1][part])
