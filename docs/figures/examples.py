"""The README figures of the bundled multi-beam examples: `python docs/figures/examples.py`.

Runs `rotor3`, `spacecraft` and `arm` through the public API (as `hubbeam run` does) and draws
docs/figures/example_{rotor3,spacecraft,arm}.png. Prints each run's integration time.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from hubbeam import api
from hubbeam.io.results import to_dataset
from hubbeam.io.scenario import load_example
from hubbeam.plots import style

OUT = Path(__file__).resolve().parent


def run(name):
    scenario = load_example(name)
    traj, failure = api.run(scenario)
    if failure is not None:
        sys.exit(f"{name}: {failure}")
    print(f"{name}: {traj.steps} steps, {traj.wall_time_s:.2f} s of integration")
    return scenario, to_dataset(traj, scenario)


def panels(ds, rows, path, title):
    """Stacked panels in hubbeam's figure style (:mod:`hubbeam.plots.style`)."""
    with style.paper_style():
        fig, axes = style.figure(len(rows), 1, sharex=True)
        t = ds["time"].values
        for ax, (label, curves) in zip(axes[:, 0], rows):
            for legend, values, line in curves:
                ax.plot(t, values, line, label=legend)
            ax.set_ylabel(label)
            if len(curves) > 1:
                ax.legend(loc="best")
        axes[-1, 0].set_xlabel("time (s)")
        style.finish(fig, path, title)


def reference(scenario, t):
    law = api.torque_law(scenario.hub.torque_law)
    return np.array([law.reference(ti)[0] for ti in t])


def main():
    sc, ds = run("rotor3")
    panels(ds, [
        ("hub speed (rad/s)", [("", ds["hub_omega"], "k-")]),
        ("tip lag (mm)", [(f"blade {k}", 1e3 * ds[f"tip{k}_tangential"], s) for k, s in ((1, "C0-"), (2, "C1--"),
                                                                                         (3, "C2:"))]),
        ("tip flap (mm)", [(f"blade {k}", 1e3 * ds[f"tip{k}_vertical"], s) for k, s in ((1, "C0-"), (2, "C1--"),
                                                                                         (3, "C2:"))]),
        ("drive torque (N m)", [("", ds["drive_torque"], "k-")]),
    ], OUT / "example_rotor3.png", "rotor3: three blades with tip masses, Kane's spin-up to 6 rad/s")

    sc, ds = run("spacecraft")
    t = ds["time"].values
    panels(ds, [
        ("slew angle (rad)", [("hub", ds["theta"], "k-"), ("reference", reference(sc, t), "C3--")]),
        ("PD torque (N m)", [("", ds["torque"], "k-")]),
        ("panel tip (mm)", [("panel a, tangential", 1e3 * ds["tip_a_tangential"], "C0-"),
                            ("panel b, tangential", 1e3 * ds["tip_b_tangential"], "C1--")]),
        ("root strain, panel a (\u00b5\u03b5)", [("", 1e6 * ds["root_strain_a"], "C0-")]),
    ], OUT / "example_spacecraft.png", "spacecraft: PD slew of a bus with two flexible panels")

    sc, ds = run("arm")
    t = ds["time"].values
    panels(ds, [
        ("joint angle (rad)", [("joint", ds["joint_angle"], "k-"), ("reference", reference(sc, t), "C3--")]),
        ("motor torque (N m)", [("", ds["motor_torque"], "k-")]),
        ("tip (mm)", [("tangential", 1e3 * ds["tip_tangential"], "C0-"),
                      ("vertical", 1e3 * ds["tip_vertical"], "C1--")]),
    ], OUT / "example_arm.png", "arm: a flexible link with a tip payload tracking a 1 rad slew")


if __name__ == "__main__":
    main()
