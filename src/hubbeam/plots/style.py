"""One style for every hubbeam figure: sizes, fonts and lines, titles, and the physical name and
unit of each quantity.

A figure is made inside :func:`paper_style` (matplotlib's rc parameters of :data:`RC`), laid
out by :func:`figure` and saved by :func:`finish` (the title, then nothing but the axes: what a
figure leaves out is for its caller to say, on the terminal). :func:`run_title` gives the
title of a scenario's figure: its name and, on a second line, the ``--set`` overrides that
made it, so that a variant never carries its baseline's title. :func:`quantity` gives a
sensor kind's physical name and display unit (strain in microstrain, lengths in mm when they
stay below 0.1 m, ...); :func:`axis_label` writes "name (unit)". Every figure of hubbeam
draws with these (the Campbell diagram's, :mod:`hubbeam.plots.campbell`, can adopt them the
same way: ``with paper_style(): fig, axes = figure(...); ...; finish(fig, path, *run_title(...))``).
"""

from __future__ import annotations

import contextlib
import textwrap
from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

#: width of a figure (inches): a two-column page's text width
WIDTH = 7.0
#: height of one row of panels in a stacked figure (inches)
ROW_HEIGHT = 1.75
#: resolution of raster files (PNG); vector files (PDF, SVG, EPS) keep the lines
DPI = 150

#: matplotlib's rc parameters of every figure
RC = {
    "font.size": 9.0,
    "axes.titlesize": 9.0,
    "axes.labelsize": 9.0,
    "xtick.labelsize": 8.0,
    "ytick.labelsize": 8.0,
    "legend.fontsize": 7.5,
    "legend.frameon": False,
    "figure.titlesize": 10.0,
    "lines.linewidth": 1.2,
    "axes.linewidth": 0.6,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.5,
    "savefig.dpi": DPI,
    "pdf.fonttype": 42,  # TrueType in PDF: editable text, accepted by journals
    "ps.fonttype": 42,
    "svg.fonttype": "none",
    "axes.formatter.useoffset": False,
    "axes.formatter.limits": (-4, 5),
}

#: line styles cycled with the colours, so that curves stay apart in grey print
DASHES = ("-", "--", "-.", ":")


@contextlib.contextmanager
def paper_style():
    """matplotlib's rc parameters of :data:`RC` inside the block."""
    with matplotlib.rc_context(RC):
        yield


def figure(rows: int = 1, cols: int = 1, height: float | None = None, width: float = WIDTH, **kwargs):
    """(fig, axes (rows x cols array)): a figure of stacked panels (``height`` in inches; default
    :data:`ROW_HEIGHT` a row, plus room for the title)."""
    height = ROW_HEIGHT * rows + 0.7 if height is None else height
    return plt.subplots(rows, cols, figsize=(width, height), squeeze=False, **kwargs)


def finish(fig, path, title: str = "", subtitle: str = "", layout: bool = True) -> None:
    """Title the figure (``subtitle``: a smaller second line), lay it out (``layout``: by
    ``tight_layout``; False when the caller did), save it (the format from the file
    extension) and close it."""
    if title or subtitle:
        text = title + (f"\n{subtitle}" if subtitle else "")
        fig.suptitle(text, fontsize=RC["figure.titlesize"] if not subtitle else RC["figure.titlesize"] - 0.5)
    if layout:
        fig.tight_layout()
    elif title or subtitle:  # keep the caller's layout, make room for the title above it
        fig.subplots_adjust(top=1.0 - (0.6 + 0.17 * (subtitle.count("\n") + bool(subtitle))) / fig.get_figheight())
    fig.savefig(path)
    plt.close(fig)


def run_title(name: str, overrides=(), note: str = "", width: int = 110) -> tuple[str, str]:
    """(title, subtitle) of a scenario's figure: ``name`` (and ``note``, e.g. "partial"), and
    the overrides ("KEY=VALUE" strings, as ``--set`` gives them) written "KEY = VALUE" on a
    second line, wrapped at ``width`` characters."""
    title = name + (f" ({note})" if note else "")
    parts = []
    for text in overrides or ():
        key, eq, value = str(text).partition("=")
        parts.append(f"{key.strip()} = {value.strip()}" if eq else str(text).strip())
    return title, "\n".join(textwrap.wrap("; ".join(parts), width)) if parts else ""


@dataclass(frozen=True)
class Quantity:
    """A physical quantity as a figure shows it: ``name`` (for an axis), the display ``unit``
    and the ``factor`` from SI (displayed value = factor x SI value)."""

    name: str
    unit: str
    factor: float = 1.0

    @property
    def label(self) -> str:
        return axis_label(self.name, self.unit)


#: sensor kind -> its quantity in SI display units (lengths and angles: see :func:`quantity`)
QUANTITIES = {
    "surface_strain": Quantity("surface strain", "\u00b5\u03b5", 1e6),
    "hub_angle": Quantity("hub angle", "rad"),
    "hub_angular_velocity": Quantity("hub speed", "rad/s"),
    "hub_torque": Quantity("drive torque", "N m"),
    "applied_torque": Quantity("applied torque", "N m"),
    "tip_deflection": Quantity("tip deflection", "m"),
    "energy": Quantity("energy", "J"),
    "angular_momentum": Quantity("angular momentum", "N m s"),
    "constraint_violation": Quantity("constraint violation", "m"),
}

#: the parts of a multi-part sensor as a legend names them
PART_NAMES = {
    "radial": "radial", "vertical": "vertical", "tangential": "tangential",
    "kinetic": "kinetic", "strain": "strain", "gravity": "gravity", "total": "total (kinetic + strain + gravity)",
    "dissipated": "dissipated", "drive": "work of the drive",
}


def quantity(kind: str, values=None, units: str = "") -> Quantity:
    """The :class:`Quantity` of a sensor kind; a length (m) whose ``values`` stay below 0.1 m
    is shown in mm. An unknown kind: a quantity named after it in ``units`` (its SI unit)."""
    q = QUANTITIES.get(kind)
    if q is None:
        return Quantity(str(kind).replace("_", " "), units if units not in ("", "1") else "-")
    if q.unit == "m" and values is not None:
        finite = np.asarray(values, dtype=float)
        finite = finite[np.isfinite(finite)]
        if finite.size and float(np.max(np.abs(finite))) < 0.1:
            return Quantity(q.name, "mm", 1e3)
    return q


def axis_label(name: str, unit: str) -> str:
    """"name (unit)"; a quantity without unit (a ratio): its name alone."""
    return f"{name} ({unit})" if unit and unit not in ("1", "-") else name


def styled(k: int) -> dict:
    """Colour and dashes of the k-th curve of a panel."""
    return {"color": f"C{k % 10}", "linestyle": DASHES[k % len(DASHES)]}
