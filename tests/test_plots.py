"""Which panels plot_timeseries draws (plots.timeseries_panels)."""

import json

import numpy as np
import pytest
import xarray as xr

from hubbeam import plots


def _dataset(n_strains=2, tips=1):
    t = np.linspace(0.0, 1.0, 11)
    sensors, data = [], {}

    def add(name, kind, units, columns):
        sensors.append({"name": name, "kind": kind})
        for column, values in columns.items():
            data[column] = xr.DataArray(values, dims="time", attrs={"units": units, "sensor": name})

    for i in range(n_strains):
        add(f"strain_{i}", "surface_strain", "1", {f"strain_{i}": 1e-4 * np.sin(t + i)})
    add("omega", "hub_angular_velocity", "rad/s", {"omega": t})
    add("angle", "hub_angle", "rad", {"angle": t ** 2})
    for k in range(tips):
        add(f"tip{k}", "tip_deflection", "m", {f"tip{k}_radial": 0 * t, f"tip{k}_vertical": -t, f"tip{k}_tangential": t})
    add("torque", "hub_torque", "N m", {"torque": 0.0 * t})
    add("energy", "energy", "J", {"energy_kinetic": t, "energy_drive": 1e-20 * t, "energy_total": 1.0 + 0 * t})
    ds = xr.Dataset(data, coords={"time": t})
    ds.attrs["scenario"] = json.dumps({"sensors": sensors})
    return ds


def test_grouped_by_kind_flat_zero_left_out():
    panels = plots.timeseries_panels(_dataset(tips=2))
    assert [m for _, m in panels] == [["strain_0", "strain_1"], ["omega"], ["angle"],
                                      ["tip0_vertical", "tip0_tangential", "tip1_vertical", "tip1_tangential"],
                                      ["energy_kinetic", "energy_total"]]
    assert [label.split("\n")[0] for label, _ in panels] == ["surface strain", "hub speed", "hub angle",
                                                             "tip deflection", "energy"]


def test_at_most_max_panels_and_chosen_variables_drawn_as_given(tmp_path):
    ds = _dataset()
    for k in range(8):  # more kinds than panels
        ds[f"extra{k}"] = xr.DataArray(np.ones(11) * (k + 1), dims="time", attrs={"units": f"u{k}", "sensor": f"x{k}"})
    assert len(plots.timeseries_panels(ds)) == plots.MAX_PANELS
    chosen = plots.timeseries_panels(ds, ["torque", "omega", "tip0_radial"])
    assert [m for _, m in chosen] == [["torque"], ["omega"], ["tip0_radial"]]  # zero, but asked for
    plots.plot_timeseries(ds, tmp_path / "f.png")
    assert (tmp_path / "f.png").stat().st_size > 5000


def test_nothing_to_draw_is_an_error(tmp_path):
    t = np.linspace(0, 1, 5)
    ds = xr.Dataset({"a": xr.DataArray(0 * t, dims="time", attrs={"units": "m"})}, coords={"time": t})
    with pytest.raises(ValueError, match="nothing to plot"):
        plots.plot_timeseries(ds, tmp_path / "f.png")
