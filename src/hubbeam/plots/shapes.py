"""Figures of a deformed state and of mode shapes (``hubbeam static --plot``, ``modes --plot``)."""

from __future__ import annotations

import numpy as np

from hubbeam.plots import style


def plot_deformed(system, x_ref, F_ref, x, F, path, title: str = "", subtitle: str = "") -> None:
    """Three views of every beam's undeformed and deformed centre line, the tips marked."""
    views = [(0, 1, "x (m)", "y along the hub axis (m)"), (0, 2, "x (m)", "z (m)"),
             (2, 1, "z (m)", "y along the hub axis (m)")]
    with style.paper_style():
        fig, axes = style.figure(1, 3, height=2.9)
        axes = axes[0]
        for k in range(len(system.beams)):
            ref = system.centre_line(x_ref, F_ref, k, 12)
            cur = system.centre_line(x, F, k, 12)
            for ax, (i, j, _, _) in zip(axes, views):
                ax.plot(ref[:, i], ref[:, j], color="0.5", linestyle="--", lw=0.9,
                        label="undeformed" if k == 0 else None)
                ax.plot(cur[:, i], cur[:, j], color="C0", lw=1.6, label="deformed" if k == 0 else None)
                ax.plot(cur[-1, i], cur[-1, j], "o", color="C3", ms=3.5, label="tip" if k == 0 else None)
        for ax, (_, _, xl, yl) in zip(axes, views):
            ax.set_xlabel(xl)
            ax.set_ylabel(yl)
            ax.set_aspect("equal", adjustable="datalim")
        axes[0].legend(loc="best")
        style.finish(fig, path, title, subtitle)


#: the curves of a mode shape's panel: the centre line's displacement along the beam's axis
#: frame and the twist (times the half width: the section edge's displacement)
SHAPE_PARTS = {"flap": ("flap", "C0"), "lag": ("lag", "C1"), "axial": ("axial", "C2"),
               "twist": ("twist \u00d7 b/2", "C3")}


def plot_mode_shapes(ds, path, half_widths, count: int = 6, title: str = "", subtitle: str = "") -> None:
    """The lowest ``count`` modes of a :meth:`hubbeam.api.ModalResult.shapes_dataset`: each
    beam's centre-line displacement (flap, lag, axial) and its twist times the half of the
    section's larger side (``half_widths``, m, per beam: the edge's displacement from the twist)
    along the span, one panel per mode, scaled so that the largest curve of the mode reaches 1
    (complex shapes: their real part after the phase turn). Several beams: one line style each,
    named in the legend."""
    count = min(count, ds.sizes["mode"])
    cols = min(count, 3)
    rows = -(-count // cols)
    beams = [str(b) for b in ds["beam"].values]
    with style.paper_style():
        fig, axes = style.figure(rows, cols, height=2.1 * rows + 0.8, sharex=True)
        for i, ax in enumerate(axes.ravel()):
            if i >= count:
                ax.axis("off")
                continue
            m = ds.isel(mode=i)
            curves = []
            for k in range(len(beams)):
                x = m["x"].values[k]
                keep = np.isfinite(x)
                s = x[keep] / x[keep][-1]
                d = m["displacement"].values[k][keep]
                parts = {name: d[:, j] for j, name in enumerate(("axial", "flap", "lag"))}
                parts["twist"] = m["twist"].values[k][keep] * half_widths[k]
                curves += [(k, name, s, y) for name, y in parts.items()]
            scale = max(max(float(np.max(np.abs(y))) for *_, y in curves), 1e-300)
            for k, name, s, y in curves:
                label, colour = SHAPE_PARTS[name]
                ax.plot(s, y / scale, linestyle=style.DASHES[k % len(style.DASHES)], color=colour,
                        label=(label if len(beams) == 1 else f"{beams[k]}: {label}") if k == 0 or i == 0 else None)
            ax.axhline(0.0, color="0.6", lw=0.5)
            ax.set_title(f"{int(m['mode'])}: {float(m['frequency_hz']):.4g} Hz, {str(m['label'].values)}")
            ax.set_ylim(-1.1, 1.1)
            if i % cols == 0:
                ax.set_ylabel("shape (largest = 1)")
            if i >= count - cols:
                ax.set_xlabel("x / L (root to tip)")
        handles, labels = axes[0, 0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="lower center", ncol=4, bbox_to_anchor=(0.5, 0.0))
        fig.tight_layout(rect=(0, 0.06 * (1 + (len(labels) > 4)) / rows ** 0.5, 1, 1))
        style.finish(fig, path, title, subtitle, layout=False)
