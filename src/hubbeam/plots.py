"""Figures (matplotlib, Agg backend). Numerics never import this module."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def plot_deformed(system, x_ref, F_ref, x, F, path, title: str = "") -> None:
    """Three views of every beam's undeformed and deformed centre line, the tips marked."""
    fig, axes = plt.subplots(1, 3, figsize=(12, 4))
    views = [(0, 1, "x (m)", "y (m), vertical"), (0, 2, "x (m)", "z (m)"), (2, 1, "z (m)", "y (m), vertical")]
    for k in range(len(system.beams)):
        ref = system.centre_line(x_ref, F_ref, k, 12)
        cur = system.centre_line(x, F, k, 12)
        for ax, (i, j, xl, yl) in zip(axes, views):
            ax.plot(ref[:, i], ref[:, j], "k--", lw=1, label="undeformed" if k == 0 else None)
            ax.plot(cur[:, i], cur[:, j], "C0-", lw=2, label="deformed" if k == 0 else None)
            ax.plot(cur[-1, i], cur[-1, j], "C3o", ms=4)
    for ax, (i, j, xl, yl) in zip(axes, views):
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
    axes[0].legend(loc="best", fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


#: at most this many panels in a figure of a run's results drawn without a choice of variables
MAX_PANELS = 6

#: the axis label of a panel of each sensor kind
KIND_LABELS = {"surface_strain": "surface strain", "hub_angle": "hub angle", "hub_angular_velocity": "hub speed",
               "hub_torque": "drive torque", "applied_torque": "applied torque", "tip_deflection": "tip deflection",
               "energy": "energy", "angular_momentum": "angular momentum", "constraint_violation": "constraint violation"}


def _sensor_kinds(ds) -> dict[str, str]:
    """{sensor name: kind} from the scenario stored in a run's attributes ({} if there is none)."""
    import json

    try:
        return {s["name"]: s["kind"] for s in json.loads(ds.attrs["scenario"]).get("sensors", [])}
    except (KeyError, TypeError, ValueError):
        return {}


def _is_flat_zero(values, scale: float) -> bool:
    """No finite value, or every value zero to 1e-12 of the panel's largest (round-off)."""
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    return finite.size == 0 or float(np.max(np.abs(finite))) <= 1e-12 * scale


def timeseries_panels(ds, variables: list[str] | None = None) -> list[tuple[str, list[str]]]:
    """[(axis label, variable names)]: a run's variables grouped one panel per sensor kind and
    unit (the three tip components together, all strains together, the energies together), in
    the order they first appear. Without ``variables``: every time series (not a recorded
    state), leaving out those that
    are zero throughout (to round-off) and panels beyond :data:`MAX_PANELS`."""
    from hubbeam.io.results import time_series

    kinds = _sensor_kinds(ds)
    names = time_series(ds) if variables is None else list(variables)
    groups: dict[tuple[str, str], list[str]] = {}
    for name in names:
        units = str(ds[name].attrs.get("units", ""))
        kind = kinds.get(str(ds[name].attrs.get("sensor", name)), units)
        groups.setdefault((kind, units), []).append(name)
    panels = []
    for (kind, units), members in groups.items():
        if variables is None:
            scale = max([float(np.nanmax(np.abs(ds[n].values), initial=0.0)) for n in members] + [0.0])
            members = [n for n in members if not _is_flat_zero(ds[n].values, scale)]
            if not members or scale == 0.0:
                continue
        label = KIND_LABELS.get(kind, members[0] if len(members) == 1 else kind)
        panels.append((f"{label}\n({units or '-'})", members))
    return panels if variables is not None else panels[:MAX_PANELS]


def plot_timeseries(ds, path, title: str = "", variables: list[str] | None = None) -> None:
    """A run's variables over time, grouped into panels by :func:`timeseries_panels` (default:
    every variable that is not zero throughout, at most MAX_PANELS panels)."""
    panels = timeseries_panels(ds, variables)
    if not panels:
        raise ValueError("nothing to plot: every variable is zero throughout the run")
    fig, axes = plt.subplots(len(panels), 1, figsize=(9, 2.0 * len(panels) + 0.7), sharex=True, squeeze=False)
    for ax, (label, members) in zip(axes[:, 0], panels):
        for name in members:
            ax.plot(ds["time"].values, ds[name].values, lw=1, label=name)
        ax.set_ylabel(label, fontsize=8)
        ax.grid(alpha=0.3)
        if len(members) > 1:
            ax.legend(loc="best", fontsize=7, ncol=min(len(members), 3))
    axes[-1, 0].set_xlabel("time (s)")
    left_out = [n for n in (ds.data_vars if variables is None else ()) if not any(n in m for _, m in panels)]
    if left_out:
        fig.text(0.01, 0.005, "not drawn (zero throughout, or beyond " f"{MAX_PANELS} panels): " + ", ".join(left_out),
                 fontsize=7, color="0.4")
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0.02 if left_out else 0, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_comparison(datasets: dict, path, variables: list[str], title: str = "") -> None:
    """The same variables of several runs ({label: dataset}) over time, one panel each."""
    fig, axes = plt.subplots(len(variables), 1, figsize=(9, 2.4 * len(variables) + 0.6), sharex=True, squeeze=False)
    for ax, name in zip(axes[:, 0], variables):
        for k, (label, ds) in enumerate(datasets.items()):
            ax.plot(ds["time"].values, ds[name].values, lw=1, color=f"C{k}", ls=("-", "--", "-.", ":")[k % 4],
                    label=label)
        units = next(iter(datasets.values()))[name].attrs.get("units", "")
        ax.set_ylabel(f"{name}\n({units})", fontsize=8)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(loc="best", fontsize=8)
    axes[-1, 0].set_xlabel("time (s)")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_xy(series: dict, path, xlabel: str, ylabel: str, title: str = "", vline: float | None = None) -> None:
    """Curves y(x) ({label: (x, y)}) with markers; an optional dashed vertical line."""
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for k, (label, (x, y)) in enumerate(series.items()):  # marker and dashes differ, so that equal curves show
        ax.plot(x, y, marker="osv^D"[k % 5], ls=("-", "--", "-.", ":")[k % 4], color=f"C{k}", label=label, lw=1.2,
                ms=6 - k % 3)
    if vline is not None:
        ax.axvline(vline, color="k", ls="--", lw=0.8)
    _finish_single(fig, ax, path, xlabel, ylabel, title)


def _finish_single(fig, ax, path, xlabel: str, ylabel: str, title: str) -> None:
    """Labels, grid, legend and title of a one-panel figure; save and close it."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_campbell(ds, path, title: str = "", frange: tuple[float, float] | None = None, frame: str = "rotating") -> None:
    """Campbell diagram of a :func:`hubbeam.studies.campbell.campbell` dataset: each
    formulation's tracked branches against hub speed (colour: the branch, with its label in the
    legend; line style: the formulation), with the nP lines (``np_line_hz``). ``frame``
    "fixed": the branches' fixed-frame frequencies and labels (a symmetric rotor's dataset), a
    whirl that turns backward said in the legend. ``frange`` (Hz, low, high): one panel on that
    range. Without it, when the highest branch is far above the lowest, a second panel zooms on
    the lowest branches so they are not squashed."""
    omega = ds["omega"].values
    fixed = frame == "fixed"
    name, label_name = ("fixed_frequency_hz", "fixed_label") if fixed else ("tracked_frequency_hz", "tracked_label")
    f_all = ds[name].values
    finite = np.any(np.isfinite(f_all))
    top = float(np.nanmax(f_all)) if finite else 1.0
    low_top = float(np.nanmax(f_all[:, :, : max(1, f_all.shape[2] // 3)])) if finite else 1.0
    if frange is not None:
        ranges = [tuple(frange)]
    elif top > 4.0 * low_top:
        ranges = [(0.0, 1.05 * top), (0.0, 1.25 * low_top)]
    else:
        ranges = [(0.0, 1.05 * top)]
    fig, axes = plt.subplots(1, len(ranges), figsize=(10 if len(ranges) == 1 else 15, 5.5), squeeze=False)
    styles = {"ancf": "-", "ffr": "--", "ffr+": ":"}
    names = {"ancf": "ANCF", "ffr": "FFR (paper, linear)", "ffr+": "FFR + geometric stiffening",
             "scenario": "the scenario's formulations"}
    forms = [str(f) for f in ds["formulation"].values]
    orders = ds["order"].values
    lines = ds["np_line_hz"].values
    count = ds.sizes["branch"]
    colours = plt.get_cmap("tab10" if count <= 10 else "tab20").colors
    # one formulation on a symmetric rotor: the line style tells the harmonic (the formulation's otherwise)
    by_harmonic = len(forms) == 1 and "harmonic" in ds

    def style(k, b, form):
        if not by_harmonic:
            return styles.get(form, "-")
        p = ds["harmonic"].values[k, -1, b]
        blades = int(ds.attrs.get("blades", 0))
        return "-" if p == 0 else ("-." if 2 * p == blades else ("--" if p > 0 else ":"))

    for ax, (lo, hi) in zip(axes[0], ranges):
        for k, form in enumerate(forms):
            f = ds[name].sel(formulation=form).values
            for b in range(f.shape[1]):
                label = None
                if k == 0:
                    label = f"{b + 1}: {_most_common_label(ds[label_name].values[k, :, b])}"
                    if fixed:
                        senses = [str(w) for w in ds["whirl"].values[k, :, b] if w]
                        if "backward" in senses:
                            label += " (backward whirl" + (", forward below)" if "forward" in senses else ")")
                ax.plot(omega, f[:, b], style(k, b, form), color=colours[b % len(colours)], lw=1.4, label=label)
        for form in forms if len(forms) > 1 else []:
            ax.plot([], [], styles.get(form, "-"), color="k", lw=1.2, label=names.get(form, form))
        for n, line in zip(orders, lines):
            ax.plot(omega, line, color="0.5", lw=0.8)
            if lo <= line[-1] <= hi:
                ax.annotate(f"{n}P", (omega[-1], line[-1]), fontsize=8, color="0.4")
        ax.set_ylim(lo, hi)
        ax.set_xlabel("hub speed (rad/s)")
        ax.set_ylabel(f"natural frequency, {frame} frame (Hz)")
        ax.grid(alpha=0.3)
        ax.set_title(title if ax is axes[0, 0] else f"zoom: {lo:g} to {hi:.3g} Hz", fontsize=10)
    axes[0, -1].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7, borderaxespad=0.0,
                       title="branch: label" + (" (first formulation)" if len(forms) > 1 else ""), title_fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _most_common_label(values) -> str:
    names, counts = np.unique([str(v) for v in values if v], return_counts=True)
    return str(names[np.argmax(counts)]) if names.size else ""


def plot_fit(times, measured, fitted, path, signal: str, title: str = "") -> None:
    """Measured data and the fitted model, with the residual below."""
    fig, (ax, axr) = plt.subplots(2, 1, figsize=(9, 5.5), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    ax.plot(times, measured, ".", ms=3, color="0.4", label="measured")
    ax.plot(times, fitted, "-", color="C0", lw=1.4, label="fitted model")
    ax.set_ylabel(signal)
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    axr.plot(times, np.asarray(measured) - np.asarray(fitted), ".", ms=3, color="C3")
    axr.set_ylabel("residual")
    axr.set_xlabel("time (s)")
    axr.grid(alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_applicability(ds, path, title: str = "") -> None:
    """FFR's frequency and deflection errors against ANCF over (w_m / L, omega / omega_1), with
    the paper's 38 % and 33 % lines and the +-5 % and +-20 % contours."""
    x = np.repeat(ds["w_m_over_L"].values[:, None], ds.sizes["ratio"], axis=1)
    y = np.repeat(ds["ratio"].values[None, :], ds.sizes["thickness"], axis=0)
    order = np.argsort(ds["w_m_over_L"].values)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    for ax, name, label in zip(axes, ("frequency_error_pct", "deflection_error_pct"),
                               ("first-frequency error of FFR (%)", "tip-deflection error of FFR (%)")):
        z = ds[name].values
        level = float(np.nanmax(np.abs(z))) if np.any(np.isfinite(z)) else 1.0
        cs = ax.contourf(x[order], y[order], z[order], levels=21, cmap="RdBu_r", vmin=-level, vmax=level)
        lines = ax.contour(x[order], y[order], np.abs(z[order]), levels=[5, 20], colors="k", linewidths=0.8)
        ax.clabel(lines, fmt="%g %%", fontsize=8)
        ax.plot(x, y, "k.", ms=3)
        ax.axvline(0.38, color="C2", ls="--", lw=1.2, label="paper: w_m = 38 % of L")
        ax.axhline(0.33, color="C1", ls="--", lw=1.2, label="paper: omega = 33 % of omega_1")
        fig.colorbar(cs, ax=ax, label=label)
        ax.set_xlabel("peak deflection w_m / L after release (ANCF)")
        ax.set_title(label)
    axes[0].set_ylabel("hub speed omega / omega_1")
    axes[0].legend(loc="upper right", fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_sweep(ds, path, variables: list[str] | None = None, title: str = "") -> None:
    """A sweep's results: time series (one curve per point) or values against the first
    varied key (one curve per value of the others), one panel per variable (at most 4)."""
    keys = [d for d in ds["failed"].dims]
    names = variables or [n for n in ds.data_vars if n not in ("failed", "message") and ds[n].dtype.kind == "f"][:4]
    fig, axes = plt.subplots(len(names), 1, figsize=(9, 2.6 * len(names) + 0.6), squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        da = ds[name]
        stacked = da.stack(point=keys)
        for k in range(stacked.sizes["point"]):
            curve = stacked.isel(point=k)
            label = ", ".join(f"{key} = {curve[key].item():g}" for key in keys)
            if "time" in da.dims:
                ax.plot(ds["time"].values, curve.values, lw=1, label=label)
            elif "mode" in da.dims:
                ax.plot(ds["mode"].values, curve.values, "o-", lw=1, label=label)
        if "time" not in da.dims and "mode" not in da.dims:
            first = keys[0]
            rest = [k for k in keys if k != first]
            lines = da.stack(rest_=rest) if rest else da.expand_dims(rest_=[0])
            for k in range(lines.sizes["rest_"]):
                ax.plot(ds[first].values, lines.isel(rest_=k).values, "o-", lw=1)
            ax.set_xlabel(first)
        else:
            ax.set_xlabel("time (s)" if "time" in da.dims else "mode")
        ax.set_ylabel(f"{name}\n({da.attrs.get('units', '')})", fontsize=8)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(loc="best", fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_mode_shapes(ds, path, half_widths, count: int = 6, title: str = "") -> None:
    """The lowest ``count`` modes of a :meth:`hubbeam.api.ModalResult.shapes_dataset`: each
    beam's centre-line displacement (flap, lag, axial) and its twist times the half of the
    section's larger side (``half_widths``, m, per beam: the edge's displacement from the twist)
    along the span, one panel per mode, scaled so that the largest curve of the mode reaches 1
    (complex shapes: their real part after the phase turn)."""
    count = min(count, ds.sizes["mode"])
    cols = min(count, 3)
    rows = -(-count // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.2 * rows), squeeze=False, sharex=True)
    styles = ["-", "--", ":", "-."]
    colours = {"flap": "C0", "lag": "C1", "axial": "C2", "twist": "C3"}
    for i, ax in enumerate(axes.ravel()):
        if i >= count:
            ax.axis("off")
            continue
        m = ds.isel(mode=i)
        curves = []
        for k, beam in enumerate(ds["beam"].values):
            x = m["x"].values[k]
            keep = np.isfinite(x)
            s = x[keep] / x[keep][-1]
            d = m["displacement"].values[k][keep]
            parts = {name: d[:, j] for j, name in enumerate(("axial", "flap", "lag"))}
            parts["twist"] = m["twist"].values[k][keep] * half_widths[k]
            curves += [(beam, k, name, s, y) for name, y in parts.items()]
        scale = max(max(float(np.max(np.abs(y))) for *_, y in curves), 1e-300)
        for beam, k, name, s, y in curves:
            label = (name if name != "twist" else "twist x b/2") if k == 0 else None
            ax.plot(s, y / scale, styles[k % len(styles)], color=colours[name], lw=1.4, label=label)
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set_title(f"mode {int(m['mode'])}: {float(m['frequency_hz']):.4g} Hz, {str(m['label'].values)}", fontsize=9)
        ax.set_ylim(-1.1, 1.1)
        ax.grid(alpha=0.3)
        if i % cols == 0:
            ax.set_ylabel("normalised shape")
        if i >= count - cols:
            ax.set_xlabel("x / L (root to tip)")
    axes[0, 0].legend(loc="best", fontsize=7)
    if ds.sizes["beam"] > 1:
        title += " (beams: " + ", ".join(f"{b} {styles[k % len(styles)]}" for k, b in enumerate(ds["beam"].values)) + ")"
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
