"""run --plot: the panels it picks by itself, and --plot-vars."""

import matplotlib.image as mpimg
import pytest

from tests.cli.helpers import EXAMPLES, assert_contract, cli


@pytest.mark.parametrize("value, named", [("strain_P1,bogus", "'bogus'"), ("tip_sideways", "'tip_sideways'"),
                                          ("energy_drive,", "''")])
def test_unknown_variable_is_bad_input_naming_it(tmp_path, value, named):
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--plot", tmp_path / "f.png", "--plot-vars", value)
    assert_contract(code, out, err)
    assert code == 2
    assert "--plot-vars" in err and f"unknown variable {named}" in err
    assert not (tmp_path / "f.png").exists()


def test_plot_vars_needs_plot(tmp_path):
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--plot-vars", "strain_P1")
    assert_contract(code, out, err)
    assert code == 2 and "--plot-vars: needs --plot" in err


def test_default_and_chosen_panels_of_a_run(tmp_path):
    from hubbeam import api, plots
    from hubbeam.io.results import to_dataset
    from hubbeam.io.scenario import load_example

    scenario = load_example("exp1", ["analysis.t_end=0.2", "beam.elements=2"])
    traj, failure = api.run(scenario)
    assert failure is None
    ds = to_dataset(traj, scenario)
    panels = {p.members[0]: p.members for p in plots.timeseries_panels(ds)}
    # strains together, the hub speed, the tip components together, the energies without the
    # drive's work (zero throughout: the hub is free)
    assert panels == {"strain_P1": ["strain_P1", "strain_P2"], "hub_omega": ["hub_omega"],
                      "tip_radial": ["tip_radial", "tip_vertical", "tip_tangential"],
                      "energy_kinetic": ["energy_kinetic", "energy_strain", "energy_gravity", "energy_total",
                                         "energy_dissipated"]}
    assert float(abs(ds["energy_drive"]).max()) == 0.0
    # the command: a figure of 4 panels; with --plot-vars a sensor stands for its parts
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--set", "analysis.t_end=0.2", "--set", "beam.elements=2",
                         "--plot", tmp_path / "all.png")
    assert code == 0, err
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--set", "analysis.t_end=0.2", "--set", "beam.elements=2",
                         "--plot", tmp_path / "two.png", "--plot-vars", "tip,hub_omega")
    assert code == 0, err
    tall, short = mpimg.imread(tmp_path / "all.png"), mpimg.imread(tmp_path / "two.png")
    assert tall.shape[0] > 1.5 * short.shape[0]  # 4 panels against 2


def test_the_figure_is_titled_by_its_variant_and_says_nothing_but_the_plot(tmp_path, monkeypatch):
    """A --set variant's title names the overrides (not the baseline's title); what is not
    drawn is said on stderr, and with --state the recorded state's variables are not listed."""
    from hubbeam import plots

    seen = {}
    real = plots.plot_timeseries

    def spy(ds, path, title="", variables=None, subtitle=""):
        seen.update(title=title, subtitle=subtitle)
        return real(ds, path, title=title, variables=variables, subtitle=subtitle)

    monkeypatch.setattr(plots, "plot_timeseries", spy)
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--set", "analysis.t_end=0.1", "--set", "beam.elements=2",
                         "--set", 'beam.formulation="ffr"', "--plot", tmp_path / "v.png", "-o", tmp_path / "v.nc",
                         "--state")
    assert code == 0, err
    assert seen["title"] == "exp1" and seen["subtitle"] == ('analysis.t_end = 0.1; beam.elements = 2; '
                                                           'beam.formulation = "ffr"')
    note = [line for line in err.splitlines() if "not drawn" in line]
    assert note == ["hubbeam: note: --plot: not drawn (zero throughout; --plot-vars chooses): energy_drive"]
    assert "state_" not in err
