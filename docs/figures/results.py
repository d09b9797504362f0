"""The figures of results drawn by hubbeam.plots, in its one style: `python docs/figures/results.py`
(about a minute).

- ``exp1_omega_p1.png`` (README): `hubbeam run exp1.toml`, hub speed and P1 strain
  (``plots.plot_timeseries`` with ``variables=["hub_omega", "strain_P1"]``);
- ``exp1_ancf_vs_ffr.png`` (comparison page): exp1 as ANCF, FFR and stiffened FFR
  (``plots.plot_comparison``);
- ``sweep_exp1.png`` (studies page): `hubbeam sweep exp1.toml --vary
  beam.thickness=0.0015:0.004:4 --set analysis.t_end=3.0 -o sweep.nc`, then
  ``plots.plot_sweep`` of strain_P1, hub_omega and tip_vertical;
- ``applicability_exp1.png`` (studies page): `hubbeam applicability -o DIR` (its figure);
- ``viewing_rotor3.png`` (3D view page): `hubbeam run rotor3.toml -o rotor3.nc --state`, the
  frame at t = 8 s that `hubbeam animate rotor3.nc` draws (``animate.save_frame``).
"""

from __future__ import annotations

import shutil
import sys
import tempfile
from pathlib import Path

import xarray as xr

from hubbeam import animate, api, plots
from hubbeam.cli import main as cli
from hubbeam.io.results import to_dataset, write_trajectory_netcdf
from hubbeam.io.scenario import example_text, load_example
from hubbeam.io.state import read_state

OUT = Path(__file__).resolve().parent


def run(name, overrides=(), state=False):
    scenario = load_example(name, list(overrides))
    traj, failure = api.run(scenario, state=state)
    if failure is not None:
        sys.exit(f"{name}: {failure}")
    print(f"{name} {' '.join(overrides)}: {traj.steps} steps, {traj.wall_time_s:.2f} s of integration")
    return scenario, traj


def main() -> None:
    scenario, traj = run("exp1")
    ds = to_dataset(traj, scenario)
    plots.plot_timeseries(ds, OUT / "exp1_omega_p1.png", variables=["hub_omega", "strain_P1"],
                          title="exp1 (ANCF, 6 elements, h = 2.5 mm): hub angular velocity and P1 strain")
    forms = {"ANCF": [], "FFR (paper, linear)": ['beam.formulation="ffr"'],
             "FFR + geometric stiffening": ['beam.formulation="ffr"', "beam.geometric_stiffening=true"]}
    runs = {label: to_dataset(*reversed(run("exp1", overrides))) for label, overrides in forms.items()}
    plots.plot_comparison(runs, OUT / "exp1_ancf_vs_ffr.png", ["strain_P1", "hub_omega", "tip_vertical"],
                          title="exp1, h = 2.5 mm, 6 elements: ANCF vs FFR")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "exp1.toml").write_text(example_text("exp1"))
        varied = ["--vary", "beam.thickness=0.0015:0.004:4", "--set", "analysis.t_end=3.0"]
        if cli(["sweep", str(tmp / "exp1.toml"), *varied, "-o", str(tmp / "sweep.nc")]) != 0:
            sys.exit("sweep failed")
        with xr.open_dataset(tmp / "sweep.nc") as sweep:
            title, subtitle = plots.run_title("exp1: sweep over beam.thickness", ["analysis.t_end=3.0"])
            plots.plot_sweep(sweep.load(), OUT / "sweep_exp1.png", ["strain_P1", "hub_omega", "tip_vertical"],
                             title=title, subtitle=subtitle)
        if cli(["applicability", "-o", str(tmp / "app")]) != 0:
            sys.exit("applicability failed")
        shutil.copyfile(tmp / "app" / "applicability.png", OUT / "applicability_exp1.png")
        scenario, traj = run("rotor3", state=True)
        write_trajectory_netcdf(traj, scenario, tmp / "rotor3.nc")
        state = read_state(tmp / "rotor3.nc")
        i = int(abs(state.times - 8.0).argmin())
        animate.save_frame(state, OUT / "viewing_rotor3.png", i)
        print(f"rotor3 frame at t = {state.times[i]:g} s")


if __name__ == "__main__":
    main()
