"""identify: a measured file that is not a clean increasing series is bad input naming the file
and column (exit 2); the JSON never holds NaN; a perfect fit and an undetermined parameter are
reported for what they are (issue 15: "wrong answers with exit 0")."""

import json

import numpy as np
import pytest

from hubbeam.io.scenario import ScenarioError, load_example
from hubbeam.studies import identify as identify_module
from hubbeam.studies.identify import Identification, check_measured, identify, run_length
from tests.cli.helpers import EXAMPLES, assert_contract, cli, without_notes

EXP1 = EXAMPLES / "exp1.toml"
GOOD = [(0.1 * k, np.sin(k)) for k in range(8)]


def csv(rows, header="time,strain_P1"):
    return header + "\n" + "".join(",".join(str(v) for v in row) + "\n" for row in rows)


@pytest.mark.parametrize("text,message", [
    (csv([GOOD[0], GOOD[2], GOOD[1]] + GOOD[3:]), "column 'time' goes back at row 4"),
    (csv(GOOD[:3] + [GOOD[2]] + GOOD[3:]), "column 'time' repeats at row 5"),
    (csv(GOOD[:2] + [(0.2, "inf")] + GOOD[3:]), "column 'strain_P1', row 4: not finite"),
    (csv(GOOD[:2] + [(0.2, "nan")] + GOOD[3:]), "column 'strain_P1', row 4: not a number"),
    (csv(GOOD[:2] + [(0.2, "")] + GOOD[3:]), "column 'strain_P1', row 4: not a number"),
    (csv(GOOD[:2] + [(0.2, "abc")] + GOOD[3:]), "column 'strain_P1', row 4: not a number ('abc')"),
    (csv(GOOD[:2] + [("1e400", 0.5)] + GOOD[3:]), "column 'time', row 4: not finite"),
    (csv([(t, 1e-4) for t, _ in GOOD]), "column 'strain_P1' is constant"),
    (csv(GOOD[:3]), "3 samples; at least 5"),
    (csv([(t - 1.0, v) for t, v in GOOD]), "column 'time' starts at -1 s"),
    (csv(GOOD, header="t,strain_P1"), "no column 'time'"),
    ("", "cannot read as CSV"),
    ("\0\0\0", "not a text file"),
])
def test_bad_measured_files_are_bad_input(tmp_path, text, message):
    path = tmp_path / "measured.csv"
    path.write_text(text)
    code, out, err = cli("identify", EXP1, path, "--fit", "damping.linear", "--json")
    assert code == 2, err
    assert_contract(code, out, err)
    assert without_notes(err).startswith(f"hubbeam: error: {path}") and message in err, err
    assert out == ""


@pytest.mark.parametrize("args,message", [
    (["--fit", "beam.elements"], "--fit beam.elements: cannot be varied continuously"),
    (["--fit", "name"], "--fit name: not a number"),
    (["--fit", "beam.nonsense"], "--fit beam.nonsense: not a key"),
    (["--fit", "damping.linear", "damping.linear"], "--fit: a key is given twice"),
    (["--fit", "hub.twist", "--set", "hub.twist=-45.0"], "--fit hub.twist: the fit keeps parameters >= 0"),
    (["--fit", "damping.linear", "--signal", "tip"], "--signal tip: not a column"),
    (["--fit", "damping.linear", "--set", "analysis.dt=1e-9"], "analysis.dt"),
])
def test_bad_fit_requests_fail_before_simulating(tmp_path, args, message):
    path = tmp_path / "m.csv"
    path.write_text(csv([(t, v, v) for t, v in GOOD], "time,strain_P1,tip"))
    code, out, err = cli("identify", EXP1, path, *args)
    assert code == 2, err
    assert_contract(code, out, err)
    assert message in err, err


def test_the_model_runs_to_the_next_step_after_the_last_sample():
    sc = load_example("exp1", ["analysis.dt=0.002"])
    assert run_length(sc, 0.4) == 0.4  # decimal: not 0.4000000000000001
    assert run_length(sc, 0.4001) == 0.402
    assert run_length(sc, 0.0) == 0.002


def test_check_measured_returns_clean_arrays():
    t, y = check_measured([0, 1, 2, 3, 4], [0, 1, 0, 1, 0])
    assert t.dtype == float and y.dtype == float
    with pytest.raises(ScenarioError, match="sample 2"):
        check_measured([0, 1, 1, 3, 4], [0, 1, 0, 1, 0])


def fake_model(monkeypatch, function):
    """identify with a cheap analytic model instead of a simulation."""
    monkeypatch.setattr(identify_module, "model_signal",
                        lambda sc, names, values, signal, times, plan=None: function(values, times))


def test_a_perfect_fit_reports_a_floored_interval_and_says_so(monkeypatch):
    sc = load_example("exp1")
    times = np.linspace(0, 2, 50)
    fake_model(monkeypatch, lambda p, t: p[0] * np.sin(3 * t))
    fit = identify(sc, times, 1.73 * np.sin(3 * times), ["damping.linear"])
    d = fit.to_dict()
    p = d["parameters"]["damping.linear"]
    assert abs(p["value"] - 1.73) < 1e-6
    assert d["ci95_basis"] == "floor" and any("perfect fit" in n for n in d["notes"])
    assert 0 < p["ci95"] < 1e-4  # neither 0.0 nor NaN: the floor, an upper bound of the numerical uncertainty
    json.dumps(d, allow_nan=False)


def test_noisy_data_report_intervals_from_the_residuals(monkeypatch):
    sc = load_example("exp1")
    times = np.round(np.linspace(0, 2, 201), 12)  # every 10 ms: the model records there (no note)
    fake_model(monkeypatch, lambda p, t: p[0] * np.sin(3 * t))
    noise = 0.05 * np.random.default_rng(1).standard_normal(times.size)
    d = identify(sc, times, 1.73 * np.sin(3 * times) + noise, ["damping.linear"]).to_dict()
    assert d["ci95_basis"] == "residuals" and d["notes"] == []
    p = d["parameters"]["damping.linear"]
    assert abs(p["value"] - 1.73) < p["ci95"] < 0.05


def test_a_parameter_the_signal_ignores_has_no_interval_and_a_note(monkeypatch):
    sc = load_example("exp1")
    times = np.linspace(0, 2, 50)
    fake_model(monkeypatch, lambda p, t: p[0] * np.sin(3 * t))  # the second parameter does nothing
    noise = 0.01 * np.random.default_rng(2).standard_normal(times.size)
    fit = identify(sc, times, 1.73 * np.sin(3 * times) + noise, ["damping.linear", "damping.quadratic"])
    d = fit.to_dict()
    text = json.dumps(d, allow_nan=False)  # would raise on NaN or Infinity
    assert "NaN" not in text and "Infinity" not in text
    assert d["parameters"]["damping.quadratic"]["ci95"] is None
    assert any("damping.quadratic: the signal does not depend on it" in n for n in d["notes"])
    assert all(c is None for row in d["correlation"] for c in row)


def test_to_dict_never_holds_nan():
    fit = Identification(["a"], np.array([1.0]), np.array([0.5]), np.array([np.nan]), np.array([[np.inf]]), 0.1, 3,
                         np.zeros(5), np.zeros(5), np.zeros(5), "ok")
    d = fit.to_dict()
    assert d["parameters"]["a"]["ci95"] is None and d["correlation"] == [[None]]


def test_cli_json_replaces_non_finite_values_and_says_where(capsys):
    from hubbeam.cli.common import print_json

    print_json({"final": {"x": float("nan"), "y": [1.0, float("inf")]}, "ok": 2.0})
    d = json.loads(capsys.readouterr().out)
    assert d["final"] == {"x": None, "y": [1.0, None]} and d["ok"] == 2.0
    assert d["non_finite"]["paths"] == ["final.x", "final.y[1]"]
