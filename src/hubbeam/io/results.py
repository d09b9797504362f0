"""Time-series results as an xarray.Dataset; NetCDF and CSV writers."""

from __future__ import annotations

import json

import numpy as np
import xarray as xr

from hubbeam.sensors import UNITS


def to_dataset(trajectory, scenario) -> xr.Dataset:
    """One variable per sensor (multi-part sensors as NAME_PART), coordinate ``time`` (s)."""
    kinds = {s.name: s.kind for s in scenario.sensors}
    data = {}
    for name, values in trajectory.records.items():
        units = UNITS[kinds[name]]
        if values and isinstance(values[0], dict):
            for part in values[0]:
                data[f"{name}_{part}"] = ("time", np.array([v[part] for v in values]), {"units": units, "sensor": name})
        else:
            data[name] = ("time", np.array(values, dtype=float), {"units": units, "sensor": name})
    ds = xr.Dataset(data, coords={"time": ("time", np.array(trajectory.times), {"units": "s"})})
    ds.attrs["scenario"] = json.dumps(scenario.to_dict())
    ds.attrs["name"] = scenario.name
    ds.attrs["steps"] = trajectory.steps
    ds.attrs["newton_iterations"] = trajectory.newton_iterations
    return ds


def write_netcdf(ds: xr.Dataset, path) -> None:
    ds.to_netcdf(path, engine="h5netcdf")


def write_csv(ds: xr.Dataset, path) -> None:
    """CSV with a header row: time, then one column per variable."""
    ds.to_dataframe().to_csv(path)
