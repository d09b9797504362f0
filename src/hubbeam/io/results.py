"""Time-series results: one layout (:func:`trajectory_table`), as an xarray.Dataset or
written straight to NetCDF, and CSV.

A run's file has one variable per sensor (multi-part sensors as NAME_PART) on the
coordinate ``time`` (s), each with ``units`` and ``sensor`` attributes, and the whole
scenario (JSON), its name, the steps and the Newton iterations as file attributes.
:func:`write_trajectory_netcdf` writes that layout with h5netcdf alone: importing
xarray (and, through it, dask) costs about a second, which is most of a short run.
"""

from __future__ import annotations

import json

import numpy as np

from hubbeam.sensors import UNITS


def trajectory_table(trajectory, scenario):
    """(times, {variable: (values, attrs)}, file attrs) of a run."""
    kinds = {s.name: s.kind for s in scenario.sensors}
    variables = {}
    for name, values in trajectory.records.items():
        attrs = {"units": UNITS[kinds[name]], "sensor": name}
        if values and isinstance(values[0], dict):
            for part in values[0]:
                variables[f"{name}_{part}"] = (np.array([v[part] for v in values], dtype=float), attrs)
        else:
            variables[name] = (np.array(values, dtype=float), attrs)
    attrs = {"scenario": json.dumps(scenario.to_dict()), "name": scenario.name, "steps": trajectory.steps,
             "newton_iterations": trajectory.newton_iterations}
    return np.array(trajectory.times, dtype=float), variables, attrs


def to_dataset(trajectory, scenario):
    """The run as an xarray.Dataset (layout of :func:`trajectory_table`)."""
    import xarray as xr

    times, variables, attrs = trajectory_table(trajectory, scenario)
    ds = xr.Dataset({name: ("time", values, a) for name, (values, a) in variables.items()},
                    coords={"time": ("time", times, {"units": "s"})})
    ds.attrs.update(attrs)
    return ds


def write_trajectory_netcdf(trajectory, scenario, path) -> None:
    """The run as NetCDF-4 (layout of :func:`trajectory_table`; xarray.open_dataset reads it)."""
    import h5netcdf

    times, variables, attrs = trajectory_table(trajectory, scenario)
    with h5netcdf.File(path, "w") as f:
        f.dimensions = {"time": times.size}
        t = f.create_variable("time", ("time",), float)
        t[:] = times
        t.attrs["units"] = "s"
        for name, (values, a) in variables.items():
            v = f.create_variable(name, ("time",), float)
            v[:] = values
            v.attrs.update(a)
        f.attrs.update(attrs)


def write_netcdf(ds, path) -> None:
    """An xarray.Dataset (study results of any layout) as NetCDF-4."""
    ds.to_netcdf(path, engine="h5netcdf")


def write_csv(ds, path) -> None:
    """CSV with a header row: time, then one column per variable."""
    ds.to_dataframe().to_csv(path)
