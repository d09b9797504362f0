"""Time-series results: one layout (:func:`trajectory_table`), as an xarray.Dataset or
written straight to NetCDF, and CSV.

A run's file has one variable per sensor (multi-part sensors as NAME_PART) on the
coordinate ``time`` (s), each with ``units`` and ``sensor`` attributes, and the whole
scenario (JSON), its name, the steps and the Newton iterations as file attributes, with
``partial`` (1 when the run stopped early: failed or interrupted, then also
``partial_reason`` and ``t_end``) and ``time_reached`` (s). Output time k is the double
nearest the decimal k * output_dt, so ``ds.sel(time=0.57)`` finds it.
:func:`write_trajectory_netcdf` writes that layout with h5netcdf alone: importing
xarray (and, through it, dask) costs about a second, which is most of a short run.
"""

from __future__ import annotations

import json

import numpy as np

from hubbeam.sensors import UNITS


def completion(trajectory, t_end: float | None = None, reason: str | None = None) -> dict:
    """File attributes saying how far a run got: ``partial`` (0 or 1), ``time_reached`` (s, the
    last output time) and, for a partial run, ``partial_reason`` and ``t_end`` (s, the time the
    scenario asked for)."""
    times = trajectory.times if trajectory is not None else []
    attrs = {"partial": int(reason is not None), "time_reached": float(times[-1]) if times else 0.0}
    if reason is not None:
        attrs["partial_reason"] = reason
        if t_end is not None:
            attrs["t_end"] = float(t_end)
    return attrs


def trajectory_table(trajectory, scenario, status: dict | None = None):
    """(times, {variable: (values, attrs)}, file attrs) of a run; ``status``: the attributes of
    :func:`completion` (default: a complete run). A record that an interruption left half
    made (its time but not all its sensors) is left out."""
    kinds = {s.name: s.kind for s in scenario.sensors}
    n = min([len(trajectory.times)] + [len(v) for v in trajectory.records.values()])
    variables = {}

    def add(column, data):
        if column in variables or column == "time":  # never overwrite a column (the scenario check should
            raise ValueError(f"sensors: two sensors make the column {column!r}")  # have refused such names)
        variables[column] = data

    for name, values in trajectory.records.items():
        values = values[:n]
        attrs = {"units": UNITS[kinds[name]], "sensor": name}
        if values and isinstance(values[0], dict):
            for part in values[0]:
                add(f"{name}_{part}", (np.array([v[part] for v in values], dtype=float), attrs))
        else:
            add(name, (np.array(values, dtype=float), attrs))
    attrs = {"scenario": json.dumps(scenario.to_dict()), "name": scenario.name, "steps": trajectory.steps,
             "newton_iterations": trajectory.newton_iterations}
    attrs.update(status if status is not None else completion(trajectory))
    return np.array(trajectory.times[:n], dtype=float), variables, attrs


def to_dataset(trajectory, scenario, status: dict | None = None):
    """The run as an xarray.Dataset (layout of :func:`trajectory_table`)."""
    import xarray as xr

    times, variables, attrs = trajectory_table(trajectory, scenario, status)
    ds = xr.Dataset({name: ("time", values, a) for name, (values, a) in variables.items()},
                    coords={"time": ("time", times, {"units": "s"})})
    ds.attrs.update(attrs)
    return ds


def trajectory_netcdf_bytes(trajectory, scenario, status: dict | None = None) -> bytes:
    """The run as the bytes of a NetCDF-4 file (layout of :func:`trajectory_table`)."""
    import io

    import h5netcdf

    times, variables, attrs = trajectory_table(trajectory, scenario, status)
    buffer = io.BytesIO()
    with h5netcdf.File(buffer, "w") as f:
        f.dimensions = {"time": times.size}
        t = f.create_variable("time", ("time",), float)
        t[:] = times
        t.attrs["units"] = "s"
        for name, (values, a) in variables.items():
            v = f.create_variable(name, ("time",), float)
            v[:] = values
            v.attrs.update(a)
        f.attrs.update(attrs)
    return buffer.getvalue()


def _write_bytes(data, path) -> None:
    # NetCDF is made in memory and written here with plain file I/O: HDF5 handles a failed
    # write (a full disk) badly, with messages on stderr and, at worst, a crash
    with open(path, "wb") as f:
        f.write(data)


def write_trajectory_netcdf(trajectory, scenario, path, status: dict | None = None) -> None:
    """The run as NetCDF-4 (layout of :func:`trajectory_table`; xarray.open_dataset reads it)."""
    _write_bytes(trajectory_netcdf_bytes(trajectory, scenario, status), path)


def write_netcdf(ds, path) -> None:
    """An xarray.Dataset (study results of any layout) as NetCDF-4."""
    _write_bytes(ds.to_netcdf(engine="h5netcdf"), path)


def write_csv(ds, path) -> None:
    """CSV with a header row: time, then one column per variable."""
    ds.to_dataframe().to_csv(path)
