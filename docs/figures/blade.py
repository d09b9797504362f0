"""The README figures of the bundled `blade` example: `python docs/figures/blade.py`.

Runs `blade` (a tapered, pretwisted blade spun up on a prescribed hub) through the public
API, as `hubbeam run` does, and draws docs/figures/example_blade.png; computes its Campbell
diagram (ANCF, as `hubbeam campbell blade.toml --omega 0:20:11 --formulations ancf`) with the
pretwist and without it (`--set beam.sections[1].pretwist=0`) and draws
docs/figures/campbell_blade.png. Prints the integration time and the frequencies at rest.
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from hubbeam import api  # noqa: E402
from hubbeam.io.results import to_dataset  # noqa: E402
from hubbeam.io.scenario import load_example  # noqa: E402
from hubbeam.studies.campbell import campbell  # noqa: E402

OUT = Path(__file__).resolve().parent
SPEEDS = np.linspace(0.0, 20.0, 11)  # rad/s
COUNT = 5


def time_history():
    scenario = load_example("blade")
    traj, failure = api.run(scenario)
    if failure is not None:
        sys.exit(f"blade: {failure}")
    print(f"blade: {traj.steps} steps, {traj.wall_time_s:.2f} s of integration")
    ds = to_dataset(traj, scenario)
    t = ds["time"].values
    rows = [
        ("hub speed (rad/s)", [("", ds["hub_omega"], "k-")]),
        ("tip (mm)", [("flap (vertical)", 1e3 * ds["tip_vertical"], "C0-"),
                      ("lag (tangential)", 1e3 * ds["tip_tangential"], "C1--")]),
        ("upper-face strain (1e-6)", [("x = 0.05 m", 1e6 * ds["root_strain"], "C0-"),
                                      ("x = 0.6 m", 1e6 * ds["mid_strain"], "C2--")]),
        ("drive torque (N m)", [("", ds["drive_torque"], "k-")]),
    ]
    fig, axes = plt.subplots(len(rows), 1, figsize=(8, 2.0 * len(rows) + 0.6), sharex=True)
    for ax, (label, curves) in zip(axes, rows):
        for legend, values, style in curves:
            ax.plot(t, values, style, lw=1.4, label=legend)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        if len(curves) > 1:
            ax.legend(fontsize=8, loc="best")
    axes[-1].set_xlabel("time (s)")
    fig.suptitle("blade: a tapered blade pretwisted by -25 deg, spun up to 10 rad/s")
    fig.tight_layout()
    fig.savefig(OUT / "example_blade.png", dpi=110)
    plt.close(fig)


def campbell_figure():
    twisted = load_example("blade")
    flat = load_example("blade", ["beam.sections[1].pretwist=0.0"])
    ds = {label: campbell(sc, SPEEDS, count=COUNT, formulations=("ancf",))["frequency_hz"].sel(formulation="ancf")
          for label, sc in (("pretwist -25 deg", twisted), ("no pretwist", flat))}
    for label, f in ds.items():
        print(f"{label}: frequencies at rest (Hz) {np.round(f.values[0], 3).tolist()}, "
              f"at {SPEEDS[-1]:g} rad/s {np.round(f.values[-1], 3).tolist()}")
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for (label, f), style in zip(ds.items(), ("-o", "--s")):
        for k in range(COUNT):
            ax.plot(SPEEDS, f.values[:, k], style, color=f"C{k}", ms=3.5, lw=1.3,
                    label=label if k == 0 else None, mfc="white" if style == "--s" else None)
    for n in (1, 2, 3):
        ax.plot(SPEEDS, n * SPEEDS / (2 * np.pi), "k:", lw=0.8)
        ax.annotate(f"{n}P", (SPEEDS[-1], n * SPEEDS[-1] / (2 * np.pi)), fontsize=8, xytext=(3, 0),
                    textcoords="offset points", va="center")
    ax.set_xlabel("hub speed (rad/s)")
    ax.set_ylabel("frequency (Hz)")
    ax.set_title("blade: Campbell diagram (ANCF), with and without the pretwist")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)
    fig.tight_layout()
    fig.savefig(OUT / "campbell_blade.png", dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    time_history()
    campbell_figure()
