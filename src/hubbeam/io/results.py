"""Time-series results: one layout (:func:`trajectory_table`), as an xarray.Dataset or
written straight to NetCDF, and CSV.

A run's file has one variable per sensor (multi-part sensors as NAME_PART) on the
coordinate ``time`` (s), each with ``units`` and ``sensor`` attributes, and the whole
scenario (JSON), its name, the steps and the Newton iterations as file attributes, with
``partial`` (1 when the run stopped early: failed or interrupted, then also
``partial_reason`` and ``t_end``) and ``time_reached`` (s). Output time k is the double
nearest the decimal k * output_dt, so ``ds.sel(time=0.57)`` finds it.
A run with a recorded state (``--state``, :mod:`hubbeam.snapshots`) adds the variables of
:func:`state_table`, every one named ``state_...`` (docs/viewing.md); the CSV keeps the
time series alone.
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


def complete_records(trajectory) -> int:
    """Output records that have their time, every sensor and (with a recorder) the state."""
    counts = [len(trajectory.times)] + [len(v) for v in trajectory.records.values()]
    if getattr(trajectory, "recorder", None) is not None:
        counts.append(len(trajectory.snapshots))
    return min(counts)


#: the dimension of the global components x, y, z of the recorded state's vectors
STATE_XYZ = "state_xyz"


def state_table(trajectory):
    """The recorded state of a run (:mod:`hubbeam.snapshots`) as NetCDF variables: (dimension
    sizes, {variable: (dimensions, values, attrs)}, file attrs); empty without a recorder.

    ``state_hub_angle`` (time; rad), ``state_hub_origin`` and ``state_base_origin`` (time,
    state_xyz; m), ``state_hub_axes`` and ``state_base_axes`` (time, state_xyz, state_axis: the
    frames' axes as columns; the hub's at theta) and, for every beam NAME, on its own dimension
    ``state_NAME_station`` (a coordinate: m from the root along the undeformed beam):
    ``state_NAME_width``, ``state_NAME_thickness`` (m), ``state_NAME_reference`` (station,
    state_xyz; m: the undeformed centre line with the hub at theta = 0), ``state_NAME_centre_line`` (time,
    station, state_xyz; m, global), ``state_NAME_m``, ``state_NAME_n`` (the section frame's
    unit vectors along the width and the thickness, global) and ``state_NAME_surface_strain``
    (time, station; the axial strain on the upper surface z = +h/2). File attributes:
    ``state_beams`` (JSON list of the beam names in order), ``state_formulations``,
    ``state_hub_radius`` (m), ``state_points_per_element``, ``state_tip_bodies`` (JSON list,
    per beam: null or its tip body's mass (kg), inertia (kg m^2) and offset (m, tip section
    frame)) and, with joints, ``state_joints`` (JSON list of the beams whose root is a hinge: their
    first station)."""
    rec = getattr(trajectory, "recorder", None)
    if rec is None:
        return {}, {}, {}
    snaps = trajectory.snapshots[:complete_records(trajectory)]
    dims = {STATE_XYZ: 3, "state_axis": 3}
    out = {"state_hub_angle": (("time",), np.array([s.hub_angle for s in snaps], dtype=float),
                               {"units": "rad", "long_name": "hub angle theta"})}
    for frame in ("hub", "base"):
        out[f"state_{frame}_origin"] = (("time", STATE_XYZ), np.array([getattr(s, f"{frame}_origin") for s in snaps],
                                                                      dtype=float).reshape(len(snaps), 3),
                                        {"units": "m", "long_name": f"the {frame} frame's origin, global x y z"})
        out[f"state_{frame}_axes"] = (("time", STATE_XYZ, "state_axis"),
                                      np.array([getattr(s, f"{frame}_axes") for s in snaps], dtype=float).reshape(
                                          len(snaps), 3, 3),
                                      {"units": "1", "long_name": f"the {frame} frame's axes (columns), global x y z"})
    for k, name in enumerate(rec.names):
        station = f"state_{name}_station"
        dims[station] = rec.stations[k].size
        beam = {"beam": name, "formulation": rec.formulations[k]}

        def over_time(field, k=k, n_stations=dims[station]):
            values = np.array([getattr(s.beams[k], field) for s in snaps], dtype=float)
            return values.reshape((len(snaps), n_stations) + values.shape[2:])

        out[station] = ((station,), np.asarray(rec.stations[k], dtype=float),
                        {"units": "m", "long_name": "span station, from the root along the undeformed beam", **beam})
        out[f"state_{name}_width"] = ((station,), np.asarray(rec.widths[k], dtype=float),
                                      {"units": "m", "long_name": "section width (along m)", **beam})
        out[f"state_{name}_thickness"] = ((station,), np.asarray(rec.thicknesses[k], dtype=float),
                                          {"units": "m", "long_name": "section thickness (along n)", **beam})
        out[f"state_{name}_reference"] = ((station, STATE_XYZ), np.asarray(rec.local_references[k], dtype=float),
                                          {"units": "m", "long_name": "undeformed centre line in the hub's frame at "
                                                                      "theta = 0 (its x y z axes)", **beam})
        out[f"state_{name}_centre_line"] = (("time", station, STATE_XYZ), over_time("centre_line"),
                                            {"units": "m", "long_name": "deformed centre line, global x y z", **beam})
        out[f"state_{name}_m"] = (("time", station, STATE_XYZ), over_time("m"),
                                  {"units": "1", "long_name": "section unit vector m (width direction), global", **beam})
        out[f"state_{name}_n"] = (("time", station, STATE_XYZ), over_time("n"),
                                  {"units": "1", "long_name": "section unit vector n (thickness direction), global",
                                   **beam})
        out[f"state_{name}_surface_strain"] = (("time", station), over_time("strain"),
                                               {"units": "1", "long_name": "axial strain on the upper surface z = +h/2",
                                                **beam})
    attrs = {"state_beams": json.dumps(list(rec.names)), "state_formulations": json.dumps(list(rec.formulations)),
             "state_hub_radius": float(rec.hub_radius), "state_points_per_element": int(rec.points_per_element),
             "state_tip_bodies": json.dumps(list(getattr(rec, "tip_bodies", ())))}
    if getattr(rec, "joints", ()):  # the beams whose root is a hinge (their first station)
        attrs["state_joints"] = json.dumps(list(rec.joints))
    return dims, out, attrs


def check_pair(trajectory, scenario) -> None:
    """TypeError or ValueError naming the argument when ``trajectory`` (of :func:`hubbeam.api.run`)
    and ``scenario`` do not belong together: not a trajectory or not a Scenario, a scenario
    other than the one the run was made with (its sensors aside), or sensors the scenario does
    not have (of other kinds)."""
    from hubbeam.io.scenario import Scenario

    if not (hasattr(trajectory, "times") and isinstance(getattr(trajectory, "records", None), dict)):
        raise TypeError(f"trajectory: expected the trajectory of hubbeam.api.run (got {type(trajectory).__name__})")
    if not isinstance(scenario, Scenario):
        raise TypeError(f"scenario: expected the Scenario the trajectory was run with (got {type(scenario).__name__})")
    ran = getattr(trajectory, "scenario", None)
    if isinstance(ran, Scenario):
        mine, theirs = scenario.to_dict(), ran.to_dict()
        differ = [k for k in sorted(set(mine) | set(theirs)) if k != "sensors" and mine.get(k) != theirs.get(k)]
        if differ:
            raise ValueError(f"scenario: not the scenario this trajectory was run with (they differ in "
                             f"{', '.join(differ)}); pass that one")
    own = {s.name: s for s in scenario.sensors}
    for name, values in trajectory.records.items():
        sensor = own.get(name)
        parts = None if not values or not isinstance(values[0], dict) else tuple(values[0])
        if sensor is None or (values and parts != sensor.parts):
            raise ValueError(f"scenario: the trajectory's sensor {name!r} is not one of this scenario's "
                             f"({', '.join(own) or 'none'}); pass the scenario the trajectory was run with")


def trajectory_table(trajectory, scenario, status: dict | None = None):
    """(times, {variable: (values, attrs)}, file attrs) of a run; ``status``: the attributes of
    :func:`completion` (default: a complete run). A record that an interruption left half
    made (its time but not all its sensors) is left out."""
    check_pair(trajectory, scenario)
    kinds = {s.name: s.kind for s in scenario.sensors}
    n = complete_records(trajectory)
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
    for event in getattr(trajectory, "latches", None) or []:  # a joint's latch: time (s), impulse (N m s), energy (J)
        attrs.update({f"latch_{event.beam}_time": event.time, f"latch_{event.beam}_impulse": event.impulse,
                      f"latch_{event.beam}_energy": event.energy})
    attrs.update(status if status is not None else completion(trajectory))
    return np.array(trajectory.times[:n], dtype=float), variables, attrs


def to_dataset(trajectory, scenario, status: dict | None = None):
    """The run as an xarray.Dataset (layout of :func:`trajectory_table`)."""
    import xarray as xr

    times, variables, attrs = trajectory_table(trajectory, scenario, status)
    _, state, state_attrs = state_table(trajectory)
    data = {name: ("time", values, a) for name, (values, a) in variables.items()}
    data.update({name: (dims, values, a) for name, (dims, values, a) in state.items() if dims != (name,)})
    coords = {"time": ("time", times, {"units": "s"})}
    coords.update({name: (dims, values, a) for name, (dims, values, a) in state.items() if dims == (name,)})
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(attrs)
    ds.attrs.update(state_attrs)
    return ds


def trajectory_netcdf_bytes(trajectory, scenario, status: dict | None = None) -> bytes:
    """The run as the bytes of a NetCDF-4 file (layout of :func:`trajectory_table`)."""
    import io

    import h5netcdf

    times, variables, attrs = trajectory_table(trajectory, scenario, status)
    state_dims, state, state_attrs = state_table(trajectory)
    buffer = io.BytesIO()
    with h5netcdf.File(buffer, "w") as f:
        f.dimensions = {"time": times.size, **state_dims}
        t = f.create_variable("time", ("time",), float)
        t[:] = times
        t.attrs["units"] = "s"
        for name, (values, a) in variables.items():
            v = f.create_variable(name, ("time",), float)
            v[:] = values
            v.attrs.update(a)
        for name, (dims, values, a) in state.items():
            v = f.create_variable(name, dims, float)
            v[...] = values
            v.attrs.update(a)
        f.attrs.update(attrs)
        f.attrs.update(state_attrs)
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


def time_series(ds) -> list[str]:
    """The variables of a dataset that are series over time alone (a recorded state's are not)."""
    state = "state_beams" in ds.attrs  # then no sensor is named state_... (api.run refuses it)
    return [name for name in ds.data_vars if ds[name].dims == ("time",) and not (state and name.startswith("state_"))]


def write_csv(ds, path) -> None:
    """CSV with a header row: time, then one column per time series (:func:`time_series`); a
    run without sensors gives the time column alone (its output times)."""
    import pandas as pd

    names = time_series(ds)
    table = ds[names].to_dataframe() if names else pd.DataFrame(index=pd.Index(ds["time"].values, name="time"))
    table.to_csv(path)
