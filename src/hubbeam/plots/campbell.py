"""The Campbell diagram's figure, in the shared style (:mod:`hubbeam.plots.style`): the tracked
branches against hub speed in the rotating or (a symmetric rotor) the fixed frame, with the nP
lines, and a zoom on the lowest branches when the highest are far above them."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from hubbeam.plots.style import WIDTH, figure, finish, paper_style  # noqa: E402

#: a formulation's line style when several are drawn, and its name in the legend
FORMULATION_STYLES = {"ancf": "-", "ffr": "--", "ffr+": ":"}
FORMULATION_NAMES = {"ancf": "ANCF", "ffr": "FFR (paper, linear)", "ffr+": "FFR + geometric stiffening",
                     "scenario": "the scenario's formulations"}


def _ranges(f_all, frange):
    """The frequency ranges of the panels: ``frange``, or the whole and, when the highest branch
    reaches more than four times the top of the lowest third, a zoom on that third."""
    if frange is not None:
        return [tuple(frange)]
    finite = np.any(np.isfinite(f_all))
    top = float(np.nanmax(f_all)) if finite else 1.0
    low_top = float(np.nanmax(f_all[:, :, : max(1, f_all.shape[2] // 3)])) if finite else 1.0
    return [(0.0, 1.05 * top), (0.0, 1.25 * low_top)] if top > 4.0 * low_top else [(0.0, 1.05 * top)]


def _line_style(ds, k: int, b: int, form: str, by_harmonic: bool) -> str:
    """The formulation's line style; on a symmetric rotor drawn in one formulation, the
    harmonic's: collective solid, progressive (cyclic +n) dashed, regressive (-n) dotted,
    differential dash-dotted."""
    if not by_harmonic:
        return FORMULATION_STYLES.get(form, "-")
    p = ds["harmonic"].values[k, -1, b]
    blades = int(ds.attrs.get("blades", 0))
    return "-" if p == 0 else ("-." if 2 * p == blades else ("--" if p > 0 else ":"))


def _branch_label(ds, name: str, k: int, b: int, fixed: bool) -> str:
    values = [str(v) for v in ds[name].values[k, :, b] if v]
    names, counts = np.unique(values, return_counts=True)
    label = f"{b + 1}: {names[np.argmax(counts)] if names.size else ''}"
    if fixed:
        senses = [str(w) for w in ds["whirl"].values[k, :, b] if w]
        if "backward" in senses:
            label += " (backward whirl" + (", forward below)" if "forward" in senses else ")")
    return label


def plot_campbell(ds, path, title: str = "", frange: tuple[float, float] | None = None, frame: str = "rotating",
                  subtitle: str = "") -> None:
    """Campbell diagram of a :func:`hubbeam.studies.campbell.campbell` dataset: each
    formulation's tracked branches against hub speed (colour: the branch, with its label in the
    legend; line style: the formulation, or on a symmetric rotor drawn in one formulation the
    harmonic), with the nP lines (``np_line_hz``). ``frame`` "fixed": the branches'
    fixed-frame frequencies and labels (a symmetric rotor's dataset), a whirl that turns
    backward said in the legend. ``frange`` (Hz, low, high): one panel on that range. Without
    it, when the highest branch is far above the lowest, a second panel zooms on the lowest
    branches so they are not squashed. ``subtitle``: a second title line (the ``--set``
    overrides)."""
    omega = ds["omega"].values
    fixed = frame == "fixed"
    name, label_name = ("fixed_frequency_hz", "fixed_label") if fixed else ("tracked_frequency_hz", "tracked_label")
    ranges = _ranges(ds[name].values, frange)
    forms = [str(f) for f in ds["formulation"].values]
    count = ds.sizes["branch"]
    colours = plt.get_cmap("tab10" if count <= 10 else "tab20").colors
    by_harmonic = len(forms) == 1 and "harmonic" in ds
    with paper_style():
        fig, axes = figure(1, len(ranges), height=4.2, width=WIDTH * (1.0 if len(ranges) == 1 else 1.55))
        for ax, (lo, hi) in zip(axes[0], ranges):
            for k, form in enumerate(forms):
                f = ds[name].sel(formulation=form).values
                for b in range(f.shape[1]):
                    ax.plot(omega, f[:, b], _line_style(ds, k, b, form, by_harmonic), color=colours[b % len(colours)],
                            label=_branch_label(ds, label_name, k, b, fixed) if k == 0 else None)
            for form in forms if len(forms) > 1 else []:
                ax.plot([], [], FORMULATION_STYLES.get(form, "-"), color="k", label=FORMULATION_NAMES.get(form, form))
            for n, line in zip(ds["order"].values, ds["np_line_hz"].values):
                ax.plot(omega, line, color="0.55", lw=0.7)
                if lo <= line[-1] <= hi:
                    ax.annotate(f"{n}P", (omega[-1], line[-1]), fontsize=7, color="0.4")
            ax.set_ylim(lo, hi)
            ax.set_xlabel("hub speed (rad/s)")
            ax.set_ylabel(f"natural frequency, {frame} frame (Hz)")
            if ax is not axes[0, 0]:
                ax.set_title(f"zoom: {lo:g} to {hi:.3g} Hz")
        axes[0, -1].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                           title="branch: label" + (" (first formulation)" if len(forms) > 1 else ""))
        finish(fig, path, title, subtitle)
