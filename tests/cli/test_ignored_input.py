"""Input the command cannot honour is refused, not ignored (issue 15: "silently ignored input").
The scenario validator's own cases (hub.torque on a fixed hub, output_dt not a multiple of dt,
...) are tested with the validator."""

from tests.cli.helpers import EXAMPLES, assert_contract, cli, without_notes

EXP1 = EXAMPLES / "exp1.toml"


def test_a_repeated_vary_key_is_refused(tmp_path):
    code, out, err = cli("sweep", EXP1, "--vary", "beam.thickness=0.001:0.002:2", "--vary",
                         "beam.thickness=0.003:0.004:2", "-o", tmp_path / "s.nc")
    assert code == 2 and "--vary beam.thickness: given twice" in err, err
    assert_contract(code, out, err)


def test_every_corner_of_a_sweep_is_validated_first(tmp_path):
    code, out, err = cli("sweep", EXP1, "--vary", "beam.thickness=0.001:0.002:3", "--vary",
                         "analysis.dt=0.001:1e-12:2", "-o", tmp_path / "s.nc")
    assert code == 2 and "analysis.dt" in err and "beam.thickness=0.001" in err, err


def test_run_refuses_targets_a_static_or_modes_analysis_cannot_fill(tmp_path):
    code, out, err = cli("run", EXAMPLES / "cantilever.toml", "-o", tmp_path / "x.nc")
    assert code == 2 and "-o: analysis.kind = 'modes' gives no time series" in err, err


def test_a_formulation_given_twice_is_refused():
    code, out, err = cli("campbell", EXP1, "--omega", "0:1:2", "--formulations", "ancf,ffr,ancf")
    assert code == 2 and "--formulations" in err, err


def test_too_many_workers_or_values_are_refused(tmp_path):
    code, out, err = cli("sweep", EXP1, "--vary", "beam.thickness=0.001:0.002:20000", "-o", tmp_path / "s.nc")
    assert code == 2 and "at most 10000" in err, err
    code, out, err = cli("sweep", EXP1, "--vary", "beam.thickness=0.001:0.002:2", "--workers", "100000",
                         "-o", tmp_path / "s.nc")
    assert code == 2 and "--workers" in err, err


def test_a_measured_row_that_is_not_a_number_is_refused_not_dropped(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text("time,strain_P1\n0,1\n0.1,2\n0.2,\n0.3,1\n0.4,2\n0.5,3\n")
    code, out, err = cli("identify", EXP1, path, "--fit", "damping.linear")
    assert code == 2 and "row 4: not a number" in err, err


def test_a_misspelt_vary_key_is_named_at_the_corner_it_was_found(tmp_path):
    code, out, err = cli("sweep", EXP1, "--vary", "beam.thikness=0.002:0.004:3", "-o", tmp_path / "s.nc")
    assert_contract(code, out, err)
    assert code == 2 and without_notes(err) == ("hubbeam: error: --vary: at beam.thikness=0.002 (a corner of the ranges): "
                                         "beam.thikness: unknown key (did you mean thickness?)"), err


def test_keys_a_switch_drops_are_named_in_a_note(tmp_path):
    code, out, err = cli("run", EXP1, "--set", "hub.motion=fixed", "--set", "analysis.t_end=0.01")
    assert_contract(code, out, err)
    assert code == 0 and "hubbeam: note: --set hub.motion=fixed: hub.torque dropped (motion 'fixed' does not take it)" \
        in err, err
