"""The Campbell diagram's figure (moved here unchanged from ``hubbeam/plots.py``; its style is
the Campbell study's: :mod:`hubbeam.plots.style` offers the shared one)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def plot_campbell(ds, path, title: str = "", frange: tuple[float, float] | None = None) -> None:
    """Campbell diagram of a :func:`hubbeam.studies.campbell.campbell` dataset: each
    formulation's tracked branches against hub speed (colour: the branch, with its label in the
    legend; line style: the formulation), with the 1x and 2x speed lines. ``frange`` (Hz, low,
    high): one panel on that range. Without it, when the highest branch is far above the
    lowest, a second panel zooms on the lowest branches so they are not squashed."""
    omega = ds["omega"].values
    f_all = ds["tracked_frequency_hz"].values
    top = float(np.nanmax(f_all)) if np.any(np.isfinite(f_all)) else 1.0
    low_top = float(np.nanmax(f_all[:, :, : max(1, f_all.shape[2] // 3)])) if np.any(np.isfinite(f_all)) else 1.0
    if frange is not None:
        ranges = [tuple(frange)]
    elif top > 4.0 * low_top:
        ranges = [(0.0, 1.05 * top), (0.0, 1.25 * low_top)]
    else:
        ranges = [(0.0, 1.05 * top)]
    fig, axes = plt.subplots(1, len(ranges), figsize=(8 if len(ranges) == 1 else 13, 5.5), squeeze=False)
    styles = {"ancf": "-", "ffr": "--", "ffr+": ":"}
    names = {"ancf": "ANCF", "ffr": "FFR (paper, linear)", "ffr+": "FFR + geometric stiffening"}
    forms = [str(f) for f in ds["formulation"].values]
    for ax, (lo, hi) in zip(axes[0], ranges):
        for k, form in enumerate(forms):
            f = ds["tracked_frequency_hz"].sel(formulation=form).values
            for b in range(f.shape[1]):
                label = f"{b + 1}: {ds['branch_label'].values[k, b]}" if k == 0 else None
                ax.plot(omega, f[:, b], styles.get(form, "-"), color=f"C{b % 10}", lw=1.4, label=label)
        for form in forms if len(forms) > 1 else []:
            ax.plot([], [], styles.get(form, "-"), color="k", lw=1.2, label=names.get(form, form))
        for mult in (1, 2):
            ax.plot(omega, mult * omega / (2 * np.pi), color="0.5", lw=0.8)
            y_end = mult * omega[-1] / (2 * np.pi)
            if lo <= y_end <= hi:
                ax.annotate(f"{mult}x", (omega[-1], y_end), fontsize=8, color="0.4")
        ax.set_ylim(lo, hi)
        ax.set_xlabel("hub speed (rad/s)")
        ax.set_ylabel("natural frequency (Hz)")
        ax.grid(alpha=0.3)
        ax.set_title(title if ax is axes[0, 0] else f"zoom: {lo:g} to {hi:.3g} Hz", fontsize=10)
    axes[0, -1].legend(loc="best", fontsize=7, title="branch: label" + (" (first formulation)" if len(forms) > 1 else ""),
                       title_fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)

