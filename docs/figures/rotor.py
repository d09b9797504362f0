"""The figures of docs/rotor.md: `python docs/figures/rotor.py`.

1. The Campbell diagram of docs/figures/rotor_tapered.toml (three tapered, pretwisted blades)
   at 41 speeds from 0 to 10 rad/s, 12 branches, in the rotating and in the fixed frame:
   docs/figures/rotor_campbell_rotating.png and rotor_campbell_fixed.png, the figures of
   `hubbeam campbell rotor_tapered.toml --omega 0:10:41 --count 12 --frame rotating|fixed -o FIG`
   (computed once here through the same function). Prints the branches at 0, 5 and 10 rad/s.
2. The bundled rotor3 driven by a measured speed log: Kane's spin-up to 6 rad/s in 8 s
   sampled at 100 Hz, clean and with 0.02 rad/s of white noise (seeded), the noisy one run as
   it is and with `smoothing = 2` (Hz): docs/figures/rotor_speed_log.png, the drive torque of
   each (and the noisy one interpolated linearly, unsmoothed); the logs are written to
   docs/figures/speed_log_{clean,noisy}.csv. Prints each run's drive torque range and the
   largest difference from the clean run.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

from hubbeam import api, plots  # noqa: E402
from hubbeam.plots.style import figure, finish, paper_style  # noqa: E402
from hubbeam.io.results import to_dataset  # noqa: E402
from hubbeam.io.scenario import load_example  # noqa: E402
from hubbeam.studies.campbell import campbell  # noqa: E402
from hubbeam.system.laws import DriveProfile  # noqa: E402

OUT = Path(__file__).resolve().parent


def campbell_figures():
    scenario = api.load_scenario(OUT / "rotor_tapered.toml")
    start = time.perf_counter()
    ds = campbell(scenario, np.linspace(0.0, 10.0, 41), count=12)
    print(f"rotor_tapered: 41 speeds, 12 branches in {time.perf_counter() - start:.0f} s; "
          f"uncertain matches: {ds.attrs['uncertain'] or 'none'}")
    for frame in ("rotating", "fixed"):
        plots.plot_campbell(ds, OUT / f"rotor_campbell_{frame}.png",
                            title=f"Campbell diagram ({frame} frame): rotor_tapered", frame=frame)
    f, fixed = ds["tracked_frequency_hz"].values[0], ds["fixed_frequency_hz"].values[0]
    for b in range(f.shape[1]):
        print(f"  {b + 1:2d} {ds['tracked_label'].values[0, -1, b]:18s} {f[0, b]:7.3f} {f[20, b]:7.3f} {f[-1, b]:7.3f} Hz"
              f" | {ds['fixed_label'].values[0, -1, b]:24s} {fixed[20, b]:7.3f} {fixed[-1, b]:7.3f} Hz "
              f"{ds['whirl'].values[0, -1, b]}")


def speed_log_figure():
    rows = np.round(np.arange(0.0, 12.0 + 1e-9, 0.01), 10)
    spin = DriveProfile("spin_up", 6.0, 8.0)
    clean = np.array([spin(t)[1] for t in rows])
    noisy = clean + np.random.default_rng(27).normal(0.0, 0.02, rows.size)
    noisy[0] = 0.0  # the log starts at rest
    for name, values in (("clean", clean), ("noisy", noisy)):
        np.savetxt(OUT / f"speed_log_{name}.csv", np.column_stack([rows, values]), delimiter=",", fmt="%.6f",
                   header="time,omega", comments="")
    runs = {}
    for label, file, extra in (("clean log", "clean", ""), ("noisy log, as it is", "noisy", ""),
                               ("noisy log, interpolation = linear", "noisy", ', interpolation = "linear"'),
                               ("noisy log, smoothing = 2 Hz", "noisy", ", smoothing = 2.0")):
        drive = f'hub.drive={{profile = "table", file = "{OUT / f"speed_log_{file}.csv"}"{extra}}}'
        scenario = load_example("rotor3", [drive])
        traj, failure = api.run(scenario)
        if failure is not None:
            sys.exit(f"rotor3, {label}: {failure}")
        runs[label] = to_dataset(traj, scenario)
        torque = runs[label]["drive_torque"].values
        print(f"rotor3, {label}: drive torque {torque.min():.3f} to {torque.max():.3f} N m, first sample "
              f"{torque[0]:.4f} N m")
    reference = runs["clean log"]["drive_torque"].values
    for label in list(runs)[1:]:
        print(f"  {label}: largest difference from the clean log's torque "
              f"{np.max(np.abs(runs[label]['drive_torque'].values - reference)):.3f} N m")
    with paper_style():
        fig, axes = figure(3, 1, height=6.4, sharex=True)
        axes = axes[:, 0]
        t = runs["clean log"]["time"].values
        axes[0].plot(rows, noisy, ".", ms=1.0, color="0.6", label="noisy log (100 Hz, 0.02 rad/s noise)")
        axes[0].plot(t, runs["clean log"]["hub_omega"], "k-", label="clean log")
        axes[0].set_ylabel("hub speed (rad/s)")
        for label, style, lw in (("noisy log, as it is", "C3-", 0.4), ("noisy log, interpolation = linear", "C1-", 0.5)):
            axes[1].plot(t, runs[label]["drive_torque"], style, lw=lw, label=label)
        axes[1].set_ylabel("drive torque (N m)")
        for label, style in (("clean log", "k-"), ("noisy log, smoothing = 2 Hz", "C0--")):
            axes[2].plot(t, runs[label]["drive_torque"], style, label=label)
        axes[2].set_ylabel("drive torque (N m)")
        axes[2].set_xlabel("time (s)")
        for ax in axes:
            ax.legend(loc="upper right")
        finish(fig, OUT / "rotor_speed_log.png", "rotor3 driven by a measured speed log: Kane's spin-up to 6 rad/s in 8 s")
    return runs


if __name__ == "__main__":
    for make in (campbell_figures, speed_log_figure):
        make()
