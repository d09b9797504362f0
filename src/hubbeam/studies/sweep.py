"""Parameter sweeps on Dask: the cartesian product of varied scenario keys as independent tasks.

Each point is the scenario with ``--set``-style overrides, run by its own analysis kind
(dynamic: the sensors over time; static: tip displacement; modes: frequencies). Points
run on a ``dask.distributed`` cluster (a LocalCluster of one single-threaded worker
process per core by default, or any running scheduler). A point that fails is kept as
failed, with its message and whatever it produced, and the sweep goes on.
"""

from __future__ import annotations

import itertools
import logging
import os

import numpy as np
import xarray as xr

from hubbeam.io.scenario import Scenario, ScenarioError


def format_value(value: float, integral: bool) -> str:
    return str(int(round(value))) if integral else repr(float(value))


def grid(varied: dict[str, tuple[np.ndarray, bool]]) -> list[tuple[tuple[int, ...], list[str]]]:
    """[(index tuple, overrides)] over the cartesian product of the varied keys."""
    keys = list(varied)
    axes = [range(len(varied[k][0])) for k in keys]
    out = []
    for idx in itertools.product(*axes):
        out.append((idx, [f"{k}={format_value(varied[k][0][i], varied[k][1])}" for k, i in zip(keys, idx)]))
    return out


def evaluate(scenario_data: dict, overrides: list[str]) -> dict:
    """Run one point (in a worker): {'kind', 'values': {name: scalar or (times, values)}, 'failure'}."""
    from hubbeam import api
    from hubbeam.io.results import to_dataset
    from hubbeam.io.scenario import apply_overrides, validate
    from hubbeam.errors import ComputationError

    try:
        scenario = validate(apply_overrides(scenario_data, overrides))
    except ScenarioError as exc:
        return {"kind": None, "values": {}, "failure": str(exc)}
    kind = scenario.analysis.kind
    try:
        if kind == "static":
            d = api.static(scenario).to_dict()
            return {"kind": kind, "values": {f"tip_{k}": v for k, v in d["tip_displacement"].items()}, "failure": None}
        if kind == "modes":
            f = api.modes(scenario).to_dict()["frequencies_hz"]
            return {"kind": kind, "values": {"frequency_hz": np.array(f)}, "failure": None}
        traj, error = api.run(scenario)
        failure = None if error is None else str(error)
        values, units = {}, {}
        if traj is not None and traj.times:
            ds = to_dataset(traj, scenario)
            values = {name: (ds["time"].values, ds[name].values) for name in ds.data_vars}
            units = {name: ds[name].attrs.get("units", "") for name in ds.data_vars}
        return {"kind": kind, "values": values, "units": units, "failure": failure}
    except ComputationError as exc:
        return {"kind": kind, "values": {}, "failure": str(exc)}


def merged_times(results) -> np.ndarray | None:
    """The sweep's time coordinate: every output time of every point, sorted (None without a
    time series). Output times are exact (the double nearest the decimal k * output_dt), so a
    time two points share is one value here, and each point keeps its own times: points with
    different ``analysis.dt``, ``output_dt`` or ``t_end`` are not copied onto one another's axis."""
    axes = [val[0] for res in results.values() for val in res["values"].values() if isinstance(val, tuple)]
    if not axes:
        return None
    return np.unique(np.concatenate([np.asarray(t, dtype=float) for t in axes]))


def _merge(varied, points, results) -> xr.Dataset:
    keys = list(varied)
    shape = tuple(len(varied[k][0]) for k in keys)
    coords = {k: varied[k][0].round().astype(int) if varied[k][1] else varied[k][0] for k in keys}
    failed = np.zeros(shape, dtype=bool)
    message = np.full(shape, "", dtype=object)
    time = merged_times(results)
    # modes: as many as the point with the most (analysis.count may vary, up to its limit)
    modes = max([np.size(val) for res in results.values() for name, val in res["values"].items()
                 if name == "frequency_hz"], default=0)
    data: dict[str, np.ndarray] = {}
    for idx, _ in points:
        res = results[idx]
        failed[idx] = res["failure"] is not None
        message[idx] = res["failure"] or ""
        for name, val in res["values"].items():
            if isinstance(val, tuple):  # (times, values): each value at its own time (NaN at the others')
                arr = data.setdefault(name, np.full(shape + (time.size,), np.nan))
                at = np.searchsorted(time, np.asarray(val[0], dtype=float))
                arr[idx][at] = val[1]
            elif name == "frequency_hz":
                val = np.atleast_1d(np.asarray(val, dtype=float))
                arr = data.setdefault(name, np.full(shape + (modes,), np.nan))
                arr[idx][: val.size] = val
            else:
                arr = data.setdefault(name, np.full(shape, np.nan))
                arr[idx] = np.atleast_1d(np.asarray(val, dtype=float))[0]
    units = {}
    for res in results.values():
        units.update(res.get("units", {}))
    ds = xr.Dataset(coords=coords)
    for name, arr in data.items():
        if name == "frequency_hz":
            n = int(np.max(np.sum(np.isfinite(arr), axis=-1))) if arr.size else 0
            ds[name] = (keys + ["mode"], arr[..., :n])
            ds = ds.assign_coords(mode=np.arange(1, n + 1))
        elif arr.ndim == len(keys) + 1:
            ds[name] = (keys + ["time"], arr)
        else:
            ds[name] = (keys, arr)
    for name in data:
        ds[name].attrs["units"] = units.get(name, "Hz" if name == "frequency_hz" else "m" if name.startswith("tip_") else "")
    if time is not None:
        ds = ds.assign_coords(time=("time", time, {"units": "s", "note": "every point's output times; a point's "
                                                   "values are NaN at the times of other points that it has not"}))
    ds["failed"] = (keys, failed)
    ds["message"] = (keys, message.astype(str))
    return ds


def run_on_dask(func, arguments: list[tuple], scheduler: str | None = None, workers: int | None = None,
                progress=None) -> list:
    """``func(*args)`` for every tuple of ``arguments`` as independent Dask tasks, on a running
    scheduler or a LocalCluster (one single-threaded worker process per core). Results come
    back in the order of ``arguments``; a task that raises gives ``{"failure": message}``.
    ``progress(done, total)`` after each task."""
    from dask.distributed import as_completed

    from hubbeam import interrupt

    client, cluster = connect(scheduler, workers)
    results = [None] * len(arguments)
    try:
        futures = {client.submit(func, *args, pure=False): k for k, args in enumerate(arguments)}
        for done, fut in enumerate(as_completed(futures), 1):
            try:
                results[futures[fut]] = fut.result()
            except Exception as exc:  # a task or a worker died: that point fails, the rest go on
                results[futures[fut]] = {"failure": f"{exc.__class__.__name__}: {exc}"}
            if progress:
                progress(done, len(arguments))
    except BaseException as exc:  # interrupted: the finished tasks' results go with the exception
        exc.partial = list(results)
        raise
    finally:
        with interrupt.deferred():  # a second signal must not leave worker processes behind
            if cluster is not None:
                cluster.close()
            client.close()
    return results


#: seconds to wait for a Dask scheduler given by address
SCHEDULER_TIMEOUT = 5


def connect(scheduler: str | None, workers: int | None):
    """(client, cluster): a client of the scheduler at ``scheduler`` (ScenarioError naming
    --scheduler when none answers within SCHEDULER_TIMEOUT s), or of a new LocalCluster."""
    from dask.distributed import Client, LocalCluster

    if scheduler:
        try:
            return Client(scheduler, timeout=SCHEDULER_TIMEOUT), None
        except Exception as exc:  # OSError (timed out, refused), ValueError or TypeError (a malformed address)
            reason = (str(exc).splitlines() or [exc.__class__.__name__])[0][:200]
            raise ScenarioError(f"--scheduler {scheduler}: no Dask scheduler answers there ({reason})") from None
    from hubbeam import interrupt

    cluster = client = None
    try:
        with interrupt.children_spared():  # a Ctrl-C to the process group stops us, and we stop the workers
            cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.CRITICAL)
            client = Client(cluster)
    except BaseException:
        with interrupt.deferred():
            if client is not None:
                client.close()
            if cluster is not None:
                cluster.close()
        raise
    return client, cluster


def sweep(scenario: Scenario, varied: dict[str, tuple[np.ndarray, bool]], scheduler: str | None = None,
          workers: int | None = None, progress=None) -> xr.Dataset:
    """Run the cartesian product of ``varied`` ({key: (values, integral)}) on Dask and merge
    the points into one Dataset with one dimension per varied key (plus 'time' or 'mode'),
    and 'failed' / 'message' per point. ``progress(done, total)`` after each point."""
    points = grid(varied)
    data = scenario.to_dict()
    try:
        outcomes = run_on_dask(evaluate, [(data, overrides) for _, overrides in points], scheduler, workers, progress)
    except BaseException as exc:  # interrupted: the points done so far, the others failed as not run
        done = getattr(exc, "partial", None)
        if isinstance(done, list) and any(r is not None for r in done):
            exc.partial = _dataset(scenario, varied, points, done, partial=f"{exc}")
        else:
            exc.partial = None
        raise
    return _dataset(scenario, varied, points, outcomes)


def _dataset(scenario, varied, points, outcomes, partial: str | None = None) -> xr.Dataset:
    results = {}
    for (idx, _), res in zip(points, outcomes):
        res = {"failure": "not run: the sweep was stopped before this point"} if res is None else res
        res.setdefault("values", {})
        res.setdefault("failure", None)
        results[idx] = res
    ds = _merge(varied, points, results)
    ds.attrs["scenario"] = scenario.name
    ds.attrs["varied"] = ", ".join(varied)
    ds.attrs["partial"] = int(partial is not None)
    if partial is not None:
        ds.attrs["partial_reason"] = partial
        ds.attrs["points_done"] = int(sum(r is not None for r in outcomes))
    return ds
