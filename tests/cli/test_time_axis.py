"""Output times are the doubles nearest the decimal k * output_dt, and the last is t_end exactly
(issue 15: round-off used to accumulate, 20.00000000000146, and ``ds.sel(time=20.0)`` failed)."""

from decimal import Decimal

import numpy as np
import pytest

from hubbeam import api
from hubbeam.io import results
from hubbeam.io.scenario import load_example
from hubbeam.simulation import simulate


@pytest.fixture(scope="module")
def short_run():
    """exp1, 2 elements, 1.0 s at dt = 1 ms, output every 10 ms (1000 steps)."""
    sc = load_example("exp1", ["beam.elements=2", "analysis.t_end=1.0", "analysis.dt=0.001", "analysis.output_dt=0.01"])
    traj, failure = api.run(sc)
    assert failure is None
    return sc, traj


def test_every_output_time_is_the_decimal_multiple(short_run):
    _, traj = short_run
    assert len(traj.times) == 101
    expected = [float(Decimal(k) * Decimal("0.01")) for k in range(101)]
    assert traj.times == expected  # exact, not approximately
    assert 57 * 0.01 != 0.57 and traj.times[57] == 0.57  # the decimal value, not k * output_dt in doubles
    assert traj.times[-1] == 1.0


def test_sel_finds_decimal_times_in_the_netcdf(short_run, tmp_path):
    import xarray as xr

    sc, traj = short_run
    path = tmp_path / "r.nc"
    results.write_trajectory_netcdf(traj, sc, path)
    with xr.open_dataset(path) as ds:
        assert float(ds.sel(time=0.57)["time"]) == 0.57
        assert float(ds.sel(time=1.0)["time"]) == 1.0
        assert ds.attrs["partial"] == 0 and ds.attrs["time_reached"] == 1.0
        assert np.isfinite(ds.sel(time=0.57)["strain_P1"].values)


def test_output_step_not_dividing_the_run_ends_at_t_end():
    """The last record is the last step even when it is not a multiple of the output step."""
    sc = load_example("exp1", ["beam.elements=2", "analysis.t_end=0.05", "analysis.dt=0.001",
                               "analysis.output_dt=0.02"])
    traj, failure = api.run(sc)
    assert failure is None
    assert traj.times == [0.0, 0.02, 0.04, 0.05]


def test_chunking_does_not_change_the_steps(monkeypatch):
    """Chunks adapt to the measured time per step (so a signal is noticed within a second);
    the steps and the records are the same bit for bit whatever the chunks are."""
    import hubbeam.simulation as simulation

    sc = load_example("exp1", ["beam.elements=2", "analysis.t_end=0.3", "analysis.dt=0.001",
                               "analysis.output_dt=0.01"])
    a = sc.analysis

    def run():
        traj = simulate(api.build_system(sc), sc.sensors, a.t_end, a.dt, a.spectral_radius, sc.output_dt)
        return results.trajectory_table(traj, sc)[:2]

    times, reference = run()
    monkeypatch.setattr(simulation, "CHUNK_SECONDS", 1e-9)  # one step per chunk
    times_1, chunked = run()
    assert np.array_equal(times, times_1)
    for name, (values, _) in reference.items():
        assert np.array_equal(values, chunked[name][0]), name


def test_control_returns_to_python_at_least_every_half_second(monkeypatch):
    """The compiled loop returns to Python (where a signal is handled) often: the progress
    callback, called after every chunk, never waits more than about 2 x CHUNK_SECONDS, even
    when 1 % of the run (the other bound on a chunk) is the whole run."""
    import time

    import hubbeam.simulation as simulation

    monkeypatch.setattr(simulation, "PROGRESS_UPDATES", 1)
    # a run of about a second here (12 000 steps of 12 elements), long enough for the chunks to
    # grow from 8 steps to about CHUNK_SECONDS
    sc = load_example("exp1", ["beam.elements=12", "analysis.t_end=6.0", "analysis.dt=0.0005"])
    calls = []
    traj, failure = api.run(sc, progress=lambda t: calls.append(time.perf_counter()))
    assert failure is None and len(calls) > 10
    gaps = np.diff(calls)
    assert gaps.max() < 0.9, gaps.max()
    assert gaps.max() > 0.1, gaps.max()  # chunks are not needlessly short either


def test_a_short_run_is_not_cut_into_a_hundred_chunks(monkeypatch):
    """A chunk lasts at least about MIN_CHUNK_SECONDS of computing once the speed is known, so a
    run that takes less than that is not cut into 1 % chunks (each return to Python measures the
    records and checks the compiled call's arguments anew): with both bounds far above this run's
    time the chunks only double from 8 steps (8, 16, ..., 256: 7 chunks for 1000 steps, where
    1 % chunks are 100 or more), and the records are the same bit for bit as with 1 % chunks."""
    import hubbeam.simulation as simulation

    sc = load_example("exp1", ["beam.elements=2", "analysis.t_end=1.0", "analysis.dt=0.001",
                               "analysis.output_dt=0.01"])
    a = sc.analysis

    def run():
        calls = []
        traj = simulate(api.build_system(sc), sc.sensors, a.t_end, a.dt, a.spectral_radius, sc.output_dt,
                        progress=calls.append)
        return len(calls), results.trajectory_table(traj, sc)[:2]

    monkeypatch.setattr(simulation, "CHUNK_SECONDS", 1e9)
    monkeypatch.setattr(simulation, "MIN_CHUNK_SECONDS", 1e9)
    chunks, (times, long_chunks) = run()
    assert chunks == 7  # 8 + 16 + ... + 256 = 504, then the remaining 496
    monkeypatch.setattr(simulation, "MIN_CHUNK_SECONDS", 0.0)
    chunks_1, (times_1, short_chunks) = run()
    assert chunks_1 >= 100
    assert np.array_equal(times, times_1)
    for name, (values, _) in long_chunks.items():
        assert np.array_equal(values, short_chunks[name][0]), name
