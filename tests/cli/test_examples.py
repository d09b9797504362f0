"""Every bundled example runs through the command line as a user would start it: printed by
``hubbeam example``, then ``hubbeam run`` (a dynamic one for a few steps, writing its NetCDF)."""

import json

import pytest

from hubbeam.cli import main
from hubbeam.io.examples import DATA_FILES
from hubbeam.io.scenario import EXAMPLES, load_example


#: examples whose models no other default test compiles (chains of joints with motors, a latch on
#: a free bus: each about 3 minutes of compiling on a cold cache); they run with ``-m slow``
SLOW_EXAMPLES = {"arm2", "deploy"}


@pytest.mark.parametrize("name", [pytest.param(n, marks=[pytest.mark.slow] if n in SLOW_EXAMPLES else [])
                                  for n in EXAMPLES])
def test_each_bundled_example_runs(name, tmp_path, capsys, monkeypatch):
    import xarray as xr

    monkeypatch.chdir(tmp_path)
    for data in DATA_FILES:  # the tables a scenario reads, next to it (as its comments say)
        assert main(["example", data]) == 0
        (tmp_path / data).write_text(capsys.readouterr().out)
    assert main(["example", name]) == 0
    (tmp_path / f"{name}.toml").write_text(capsys.readouterr().out)
    if load_example(name).analysis.kind != "dynamic":  # a static or modal example: its JSON result
        assert main(["run", f"{name}.toml", "--json"]) == 0
        assert json.loads(capsys.readouterr().out)
        return
    code = main(["run", f"{name}.toml", "--set", "analysis.t_end=0.02", "--set", "analysis.output_dt=0.01",
                 "-o", "out.nc"])
    assert code == 0, capsys.readouterr().err
    with xr.open_dataset(tmp_path / "out.nc") as ds:
        assert ds.sizes["time"] == 3 and float(ds["time"][-1]) == pytest.approx(0.02)
        assert len(ds.data_vars) > 0
