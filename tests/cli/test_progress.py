"""Notes on stderr (docs/reliability.md): plain progress lines every PROGRESS_EVERY seconds when
stderr is not a terminal (none from a short command), and the one line before the first
compile."""

import re

import pytest

from hubbeam.cli import common as cli_module
from tests.cli.helpers import EXAMPLES, assert_contract, cli

PROGRESS = re.compile(r"^hubbeam: note: run t = ([0-9.e+-]+) of 0\.3 s \((\d+) %\)$")


def test_progress_line_formats(monkeypatch, capsys):
    monkeypatch.setattr(cli_module, "PROGRESS_EVERY", 0.0)
    update, finish = cli_module.progress_bar(20.0)
    update(3.2)
    finish()
    points, _ = cli_module.progress_bar(12, label="sweep", unit="points")
    points(3)
    counted, _ = cli_module.progress_bar(None, label="identify", unit="simulations")
    counted(7)
    assert capsys.readouterr().err.splitlines() == ["hubbeam: note: run t = 3.2 of 20 s (16 %)",
                                                    "hubbeam: note: sweep 3 of 12 points (25 %)",
                                                    "hubbeam: note: identify: 7 simulations so far"]


def test_no_line_before_the_interval(monkeypatch, capsys):
    monkeypatch.setattr(cli_module, "PROGRESS_EVERY", 3600.0)
    update, _ = cli_module.progress_bar(20.0)
    for t in (1.0, 10.0, 20.0):
        update(t)
    assert capsys.readouterr().err == ""


def test_a_run_reports_progress_when_stderr_is_not_a_terminal(monkeypatch):
    monkeypatch.setattr(cli_module, "PROGRESS_EVERY", 0.0)  # a line at every report
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--set", "analysis.t_end=0.3", "--set", "beam.elements=2")
    assert_contract(code, out, err)
    assert code == 0
    lines = [PROGRESS.match(ln) for ln in err.splitlines() if ln.startswith("hubbeam: note: run")]
    assert len(lines) >= 5 and all(lines), err
    times = [float(m.group(1)) for m in lines]
    assert times == sorted(times) and times[-1] == pytest.approx(0.3)
    assert int(lines[-1].group(2)) == 100


def test_a_short_run_prints_nothing_on_stderr():
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--set", "analysis.t_end=0.05", "--set", "beam.elements=2")
    assert code == 0
    assert [ln for ln in err.splitlines() if "compiling the solver" not in ln] == []


def test_the_compile_note_comes_once_when_the_cache_is_cold(monkeypatch, tmp_path):
    from hubbeam.solvers import compiled_alpha

    monkeypatch.setattr(compiled_alpha, "cache_is_cold", lambda function=None: True)
    # a bad option found after the scenario is read: the note, then the one error line
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--plot", tmp_path / "a.png", "--plot-vars", "nothing")
    assert_contract(code, out, err)
    assert code == 2
    notes = [ln for ln in err.splitlines() if ln.startswith("hubbeam: note:")]
    assert notes == ["hubbeam: note: compiling the solver for this machine (first run only, about a minute)"]
    monkeypatch.setattr(compiled_alpha, "cache_is_cold", lambda function=None: False)
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--plot", tmp_path / "a.png", "--plot-vars", "nothing")
    assert code == 2 and "compiling" not in err
