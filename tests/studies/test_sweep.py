"""Sweeps on a Dask LocalCluster: the grid, the merge, failed points kept as failed."""

import numpy as np

from hubbeam.io.scenario import load_example
from hubbeam.studies.sweep import sweep
from hubbeam.studies.variants import parse_vary


def test_parse_vary_integral_and_float_keys():
    key, values, integral = parse_vary("beam.elements=2:6:3")
    assert key == "beam.elements" and integral and list(values) == [2, 4, 6]
    key, values, integral = parse_vary("beam.thickness=0.001:0.004:4")
    assert not integral and values[-1] == 0.004


def test_dynamic_sweep_on_a_local_cluster_keeps_failed_points():
    """Two meshes x two steps; dt = 4 ms is larger than output_dt = 2 ms, which the scenario
    refuses: those points fail with that message, the others run."""
    scenario = load_example("exp1", ["analysis.t_end=0.02", "analysis.output_dt=0.002"])
    varied = {"beam.elements": (np.array([2.0, 3.0]), True), "analysis.dt": (np.array([0.001, 0.004]), False)}
    done = []
    ds = sweep(scenario, varied, workers=2, progress=lambda k, n: done.append(k))
    assert done[-1] == 4
    assert ds["strain_P1"].dims == ("beam.elements", "analysis.dt", "time")
    assert list(ds["beam.elements"].values) == [2, 3]
    assert ds["failed"].values.tolist() == [[False, True], [False, True]]
    assert "output_dt" in str(ds["message"].values[0, 1])
    ok = ds["strain_P1"].sel({"analysis.dt": 0.001})
    assert np.all(np.isfinite(ok.values)) and ok.sizes["time"] == 11
    assert np.all(np.isnan(ds["strain_P1"].sel({"analysis.dt": 0.004}).values))


def test_sweep_plot(tmp_path):
    import xarray as xr

    from hubbeam.plots import plot_sweep

    t = np.linspace(0, 1, 5)
    ds = xr.Dataset({"strain_P1": (("beam.thickness", "time"), np.outer([1.0, 2.0], t), {"units": "1"}),
                     "failed": (("beam.thickness",), [False, False])},
                    coords={"beam.thickness": [0.002, 0.003], "time": t})
    plot_sweep(ds, tmp_path / "s.png")
    assert (tmp_path / "s.png").stat().st_size > 5000
