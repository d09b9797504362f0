"""A run stopped by SIGINT, SIGTERM or SIGHUP writes what it has (valid NetCDF and CSV, marked
partial with the time reached), says so in one line and exits 128 + the signal number; a
signal during start-up is one line too, never a traceback. Real subprocesses, real signals."""

import signal
import time

import numpy as np
import pytest

from tests.cli.helpers import EXAMPLES, assert_contract, finish, hubbeam, no_temporary_files, popen

LONG = ["--set", "analysis.t_end=2000.0"]  # minutes of integration: always stopped before the end


@pytest.fixture(scope="module")
def start_up():
    """Seconds from launch to the end of a run of a few steps (imports, model, compiled loop)."""
    start = time.perf_counter()
    out = hubbeam("run", EXAMPLES / "exp1.toml", "--set", "analysis.t_end=0.01")
    assert out.returncode == 0, out.stderr
    return time.perf_counter() - start


def stopped_run(tmp_path, sig, start_up, extra=()):
    """A long run sent ``sig`` once it integrates; (completed process, seconds to stop)."""
    nc, csv = tmp_path / "r.nc", tmp_path / "r.csv"
    for delay in (start_up + 1.5, 2 * start_up + 4):  # a second try on a slow, busy machine
        proc = popen("run", EXAMPLES / "exp1.toml", *LONG, "-o", nc, "--csv", csv, *extra)
        time.sleep(delay)
        sent = time.perf_counter()
        proc.send_signal(sig)
        stdout, stderr = finish(proc)
        stopped = time.perf_counter() - sent
        if "before the time integration started" not in stderr:
            return proc.returncode, stdout, stderr, stopped
    return proc.returncode, stdout, stderr, stopped


def check_partial(tmp_path, code, stdout, stderr, sig, expected):
    import pandas as pd
    import xarray as xr

    assert code == expected, stderr
    assert_contract(code, stdout, stderr)
    assert stdout == ""
    name = signal.Signals(sig).name
    assert f"interrupted by {name} at t = " in stderr and "marked partial" in stderr, stderr
    with xr.open_dataset(tmp_path / "r.nc") as ds:
        assert ds.attrs["partial"] == 1
        assert ds.attrs["partial_reason"] == f"interrupted by {name}"
        reached = float(ds.attrs["time_reached"])
        assert 0.0 < reached < 2000.0 and float(ds["time"][-1]) == reached
        assert ds.attrs["t_end"] == 2000.0
        assert np.all(np.isfinite(ds["strain_P1"].values))
        columns = set(ds.data_vars)
        n = ds.sizes["time"]
    table = pd.read_csv(tmp_path / "r.csv")
    assert set(table.columns) == columns | {"time"} and len(table) == n
    assert table["time"].iloc[-1] == reached
    assert f"t = {reached:g} s" in stderr
    assert no_temporary_files(tmp_path)


@pytest.mark.parametrize("sig,expected", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_stopped_run_writes_its_partial_results(tmp_path, start_up, sig, expected):
    code, stdout, stderr, stopped = stopped_run(tmp_path, sig, start_up)
    check_partial(tmp_path, code, stdout, stderr, sig, expected)
    assert stopped < 15, stopped  # the loop noticed within a second; the rest is writing the files


@pytest.mark.slow
def test_sighup_too(tmp_path, start_up):
    code, stdout, stderr, _ = stopped_run(tmp_path, signal.SIGHUP, start_up)
    check_partial(tmp_path, code, stdout, stderr, signal.SIGHUP, 129)


@pytest.mark.parametrize("delay", [0.4, 1.2])
def test_sigint_during_start_up_is_one_line(tmp_path, delay):
    proc = popen("run", EXAMPLES / "exp1.toml", *LONG, "-o", tmp_path / "r.nc")
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    stdout, stderr = finish(proc)
    assert proc.returncode == 130, stderr
    assert_contract(proc.returncode, stdout, stderr)
    assert "interrupted by SIGINT" in stderr
    assert no_temporary_files(tmp_path)


def test_in_process_interruption_keeps_the_trajectory(monkeypatch):
    """The library side: an exception raised between chunks (here by the progress callback,
    as the CLI's signal handler does) carries the trajectory so far."""
    from hubbeam import api
    from hubbeam.interrupt import Interrupted
    from hubbeam.io.scenario import load_example

    sc = load_example("exp1", ["beam.elements=2", "analysis.t_end=2.0"])
    calls = []

    def progress(t):
        calls.append(t)
        if len(calls) == 3:  # chunks double from 8 steps: a 2000-step run has at least 8
            raise Interrupted(signal.SIGINT)

    with pytest.raises(Interrupted) as info:
        api.run(sc, progress)
    traj = info.value.partial
    assert traj is not None and 0 < traj.times[-1] < 2.0
    assert all(len(v) == len(traj.times) for v in traj.records.values())


class FakeCase:
    """A stand-in for a reproduction case: sleeps ``seconds`` in the worker."""

    def __init__(self, key, seconds):
        self.key, self.seconds = key, seconds


def fake_run_case(case):
    from hubbeam.reproduce.runner import Outcome

    time.sleep(case.seconds)
    return Outcome(case, None, None, case.seconds)


def test_reproduce_workers_stop_at_once_when_interrupted(monkeypatch):
    """An interruption while the pool runs stops the worker processes now (they inherit the
    CLI's handlers by fork, which must not keep SIGTERM from ending them), not after their runs."""
    import multiprocessing

    from hubbeam import interrupt
    from hubbeam.reproduce import runner

    monkeypatch.setattr(runner, "run_case", fake_run_case)
    cases = [FakeCase("quick", 0.1)] + [FakeCase(f"slow{k}", 60) for k in range(3)]

    raised = []

    def progress(done, total, outcome):
        raised.append(time.perf_counter())
        raise interrupt.Interrupted(signal.SIGINT)

    with interrupt.handling(), pytest.raises(interrupt.Interrupted):
        runner.run_cases(cases, jobs=2, progress=progress)
    assert time.perf_counter() - raised[0] < 1.5  # terminate() works: no 2 s wait before kill()
    time.sleep(0.2)
    assert not [p for p in multiprocessing.active_children() if p.is_alive()]


def test_a_swallowed_interruption_is_raised_again():
    """A library's bare ``except:`` may swallow the exception a signal raised; the signal is
    remembered and raised again at the next check (between chunks of work)."""
    import os

    from hubbeam import interrupt

    with interrupt.handling():
        try:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(1)  # the handler raises here
        except BaseException:  # noqa: S110 - what a careless library does
            pass
        with pytest.raises(interrupt.Interrupted) as info:
            interrupt.check()
    assert info.value.exit_code == 143
    interrupt.check()  # outside handling(): nothing pending
