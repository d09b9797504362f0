"""No "internal error" reachable from the command line (issue 15): inputs that used to end in a
ZeroDivisionError, an OverflowError, a 74 GiB allocation, an endless read or a 30 s wait are
now bad input (exit 2, one line naming the key) or a failed computation that says where and
what to try (exit 1)."""

import time

import pytest

from tests.cli.helpers import EXAMPLES, assert_contract, cli, without_notes

EXP1 = EXAMPLES / "exp1.toml"
CANTILEVER = EXAMPLES / "cantilever.toml"


@pytest.mark.parametrize("args,code,text", [
    (["static", CANTILEVER, "--set", "loads.tip_force=[0.0,-1e4,0.0]", "--set", "beam.elements=2"], 1,
     "try more beam.elements"),
    (["run", EXP1, "--set", "analysis.dt=1e-300"], 2, "analysis.dt: 1e-300 s is below"),
    (["run", EXP1, "--set", "analysis.t_end=1e300"], 2, "analysis.dt: analysis.t_end / analysis.dt"),
    (["run", EXP1, "--set", "analysis.t_end=1e6", "--set", "analysis.dt=1e-6"], 2, "1e+12 steps"),
    (["run", EXP1, "--set", "analysis.t_end=2000.0", "--set", "analysis.output_dt=0.0001",
      "--set", "analysis.dt=0.0001"], 2, "analysis.output_dt: "),
    (["run", "/dev/zero"], 2, "/dev/zero: not a regular file"),
    (["run", EXP1, "--set", "beam.width=5.6e102"], 2, "beam.width: with beam.width = 5.6e+102"),
    (["modes", CANTILEVER, "--set", "beam.thickness=1e-80"], 2, "beam.thickness: "),
    (["campbell", EXP1, "--omega", "0:1000:3", "--set", "beam.elements=2", "--formulations", "ancf"], 1,
     "Campbell diagram, ancf at omega = 500 rad/s"),
])
def test_former_internal_errors(args, code, text):
    start = time.perf_counter()
    got, out, err = cli(*args)
    assert got == code, err
    assert_contract(got, out, err)
    assert text in err, err
    assert time.perf_counter() - start < 30


def test_an_output_step_beyond_the_run_is_fine(tmp_path):
    code, out, err = cli("run", EXP1, "--set", "analysis.output_dt=1e300", "--set", "analysis.t_end=0.01",
                         "--set", "beam.elements=2", "-o", tmp_path / "r.nc")
    assert code == 0, err


def test_an_unreachable_scheduler_fails_within_seconds(tmp_path):
    start = time.perf_counter()
    code, out, err = cli("sweep", EXP1, "--vary", "beam.thickness=0.002:0.003:2", "--set", "analysis.t_end=0.01",
                         "-o", tmp_path / "s.nc", "--scheduler", "tcp://127.0.0.1:9")
    assert code == 2 and without_notes(err).startswith("hubbeam: error: --scheduler tcp://127.0.0.1:9: no Dask scheduler"), err
    assert_contract(code, out, err)
    assert time.perf_counter() - start < 15
    assert not (tmp_path / "s.nc").exists()
