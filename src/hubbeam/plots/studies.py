"""Figures of the studies: curves against a parameter (reproduction tables), a fit to a
measurement (``identify``), the FFR applicability map and a sweep's results."""

from __future__ import annotations

import numpy as np

from hubbeam.plots import style
from hubbeam.plots.timeseries import variable_label

#: markers of the curves of :func:`plot_xy`, so that equal curves still show
MARKERS = "osv^D"


def plot_xy(series: dict, path, xlabel: str, ylabel: str, title: str = "", vline: float | None = None,
            subtitle: str = "") -> None:
    """Curves y(x) ({legend: (x, y)}) with markers; an optional dashed vertical line."""
    with style.paper_style():
        fig, axes = style.figure(1, 1, height=3.4)
        ax = axes[0, 0]
        for k, (label, (x, y)) in enumerate(series.items()):
            ax.plot(x, y, marker=MARKERS[k % len(MARKERS)], ms=5 - k % 3, label=label, **style.styled(k))
        if vline is not None:
            ax.axvline(vline, color="k", ls="--", lw=0.8)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.legend(loc="best")
        style.finish(fig, path, title, subtitle)


def plot_fit(times, measured, fitted, path, signal: str, title: str = "", kind: str | None = None,
             subtitle: str = "") -> None:
    """Measured data and the fitted model, with the residual below; ``kind`` (the signal's
    sensor kind) gives its physical name and unit (strain in microstrain, ...)."""
    measured, fitted = np.asarray(measured, dtype=float), np.asarray(fitted, dtype=float)
    q = style.quantity(kind, np.concatenate([measured, fitted])) if kind else style.Quantity(signal, "")
    with style.paper_style():
        fig, axes = style.figure(2, 1, height=4.2, sharex=True, gridspec_kw={"height_ratios": [3, 1]})
        ax, axr = axes[:, 0]
        ax.plot(times, q.factor * measured, ".", ms=2.5, color="0.45", label=f"measured {signal}")
        ax.plot(times, q.factor * fitted, "-", color="C0", lw=1.3, label="fitted model")
        ax.set_ylabel(q.label)
        ax.legend(loc="best")
        axr.plot(times, q.factor * (measured - fitted), ".", ms=2.5, color="C3")
        axr.set_ylabel(style.axis_label("residual", q.unit))
        axr.set_xlabel("time (s)")
        style.finish(fig, path, title, subtitle)


def plot_applicability(ds, path, title: str = "", subtitle: str = "") -> None:
    """FFR's frequency and deflection errors against ANCF over (w_m / L, omega / omega_1), with
    the paper's 38 % and 33 % lines and the +-5 % and +-20 % contours."""
    x = np.repeat(ds["w_m_over_L"].values[:, None], ds.sizes["ratio"], axis=1)
    y = np.repeat(ds["ratio"].values[None, :], ds.sizes["thickness"], axis=0)
    order = np.argsort(ds["w_m_over_L"].values)
    with style.paper_style():
        fig, axes = style.figure(1, 2, height=3.3, sharey=True)
        for ax, name, label in zip(axes[0], ("frequency_error_pct", "deflection_error_pct"),
                                   ("first-frequency error of FFR (%)", "tip-deflection error of FFR (%)")):
            z = ds[name].values
            level = float(np.nanmax(np.abs(z))) if np.any(np.isfinite(z)) else 1.0
            cs = ax.contourf(x[order], y[order], z[order], levels=21, cmap="RdBu_r", vmin=-level, vmax=level)
            lines = ax.contour(x[order], y[order], np.abs(z[order]), levels=[5, 20], colors="k", linewidths=0.7)
            ax.clabel(lines, fmt="%g %%", fontsize=7)
            ax.plot(x, y, "k.", ms=2)
            ax.axvline(0.38, color="C2", ls="--", lw=1.1, label="paper: $w_m$ = 38 % of $L$")
            ax.axhline(0.33, color="C1", ls="--", lw=1.1, label="paper: $\\Omega$ = 33 % of $\\omega_1$")
            fig.colorbar(cs, ax=ax, label=label)
            ax.set_xlabel("peak deflection after release $w_m / L$ (ANCF)")
            ax.grid(False)
        axes[0, 0].set_ylabel("hub speed $\\Omega / \\omega_1$")
        axes[0, 0].legend(loc="upper right")
        style.finish(fig, path, title, subtitle)


def plot_sweep(ds, path, variables: list[str] | None = None, title: str = "", subtitle: str = "") -> None:
    """A sweep's results, one panel per variable (at most 4): time series (one curve per
    point) or values against the first varied key (one curve per value of the others); each
    variable's physical name and unit as a run's figure has them."""
    keys = [d for d in ds["failed"].dims]
    names = variables or [n for n in ds.data_vars if n not in ("failed", "message") and ds[n].dtype.kind == "f"][:4]
    with style.paper_style():
        fig, axes = style.figure(len(names), 1, height=2.1 * len(names) + 0.8)
        for ax, name in zip(axes[:, 0], names):
            da = ds[name]
            label, factor = variable_label(ds, name)
            stacked = da.stack(point=keys)
            if "time" in da.dims or "mode" in da.dims:
                axis = "time" if "time" in da.dims else "mode"
                for k in range(stacked.sizes["point"]):
                    curve = stacked.isel(point=k)
                    legend = ", ".join(f"{key} = {curve[key].item():g}" for key in keys)
                    ax.plot(ds[axis].values, factor * curve.values, marker="o" if axis == "mode" else None,
                            ms=3, label=legend, **style.styled(k))
                ax.set_xlabel("time (s)" if axis == "time" else "mode")
            else:
                first = keys[0]
                rest = [k for k in keys if k != first]
                lines = da.stack(rest_=rest) if rest else da.expand_dims(rest_=[0])
                for k in range(lines.sizes["rest_"]):
                    legend = (", ".join(f"{key} = {lines.isel(rest_=k)[key].item():g}" for key in rest) if rest
                              else None)
                    ax.plot(ds[first].values, factor * lines.isel(rest_=k).values, marker="o", ms=3, label=legend,
                            **style.styled(k))
                ax.set_xlabel(first)
            ax.set_ylabel(label)
        if any(ax.get_legend_handles_labels()[1] for ax in axes[:, 0]):
            axes[0, 0].legend(loc="best", ncol=1 + (len(axes[0, 0].get_lines()) > 6))
        style.finish(fig, path, title, subtitle)
