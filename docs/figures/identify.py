"""The identification figure of the Studies page: `python docs/figures/identify.py` (about a minute).

Makes synthetic data from exp1 (3 elements, 5 s, P1 strain every 0.01 s, drag c1 = 1.73 and
c2 = 1.4 as in the example) with 1 % noise of the peak strain (seed 2024), fits both drag
coefficients from (0.8, 0.5) with :func:`hubbeam.studies.identify.identify` (what
`hubbeam identify` runs), prints the fit and draws docs/figures/identify_exp1.png.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

from hubbeam import api, plots  # noqa: E402
from hubbeam.io.results import to_dataset  # noqa: E402
from hubbeam.io.scenario import load_example  # noqa: E402
from hubbeam.studies.identify import identify  # noqa: E402

OUT = Path(__file__).resolve().parent
MESH = ["beam.elements=3", "analysis.t_end=5.0", "analysis.output_dt=0.01"]


def main() -> None:
    truth = load_example("exp1", MESH)
    traj, failure = api.run(truth)
    if failure is not None:
        raise SystemExit(f"exp1: {failure}")
    ds = to_dataset(traj, truth)
    strain = ds["strain_P1"].values
    rng = np.random.default_rng(2024)
    measured = strain + rng.normal(0.0, 0.01 * np.abs(strain).max(), strain.size)
    start = load_example("exp1", MESH + ["damping.linear=0.8", "damping.quadratic=0.5"])
    names = ["damping.linear", "damping.quadratic"]
    fit = identify(start, ds["time"].values, measured, names, signal="strain_P1")
    for name, value, half in zip(names, fit.values, fit.ci95):
        print(f"{name} = {value:.4g} +- {half:.2g} (95 %)")
    print(f"correlation {fit.correlation[0][1]:.3f}, {fit.evaluations} simulations")
    title, subtitle = plots.run_title("exp1: fit of damping.linear, damping.quadratic", MESH)
    plots.plot_fit(fit.times, fit.measured, fit.fitted, OUT / "identify_exp1.png", "strain_P1", title=title,
                   kind="surface_strain", subtitle=subtitle)


if __name__ == "__main__":
    main()
