"""A run's time series as stacked, labelled panels (``hubbeam run --plot``), and runs compared.

Each panel holds one physical quantity (:func:`hubbeam.plots.style.quantity`) in its display
unit: the strain gauges together (microstrain), the hub angle, the hub speed, each torque, the
tip deflections (together for one beam; with several beams one panel per direction, a curve
per beam), the energies. Curves are named by what they measure (a gauge by its station and
face, a tip by its direction and beam, an energy by its part), never by the result column.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import numpy as np

from hubbeam.plots import style

#: at most this many panels in a figure of a run's results drawn without a choice of variables
MAX_PANELS = 6
#: sensor kinds that measure one beam (the first when the sensor names none)
BEAM_KINDS = ("surface_strain", "tip_deflection")


@dataclass
class Panel:
    """One panel: its axis ``label`` ("name (unit)"), the variables it draws (``members``),
    each one's legend (``legends``), and the :class:`~hubbeam.plots.style.Quantity` that
    scales them."""

    label: str
    members: list[str]
    quantity: style.Quantity
    legends: list[str] = field(default_factory=list)


def _scenario(ds) -> dict:
    """The scenario stored in a run's attributes ({} if there is none or it is not JSON)."""
    for key in ("scenario", "scenario_toml"):  # a run's "scenario"; a sweep's "scenario_toml" (the same JSON)
        try:
            value = json.loads(ds.attrs[key])
        except (KeyError, TypeError, ValueError):
            continue
        if isinstance(value, dict):
            return value
    return {}


def _sensor_of(name: str, attrs, sensors: dict) -> dict:
    """The scenario table of the sensor that made the column ``name`` (its ``sensor``
    attribute, else the sensor whose name the column is or starts with, NAME_PART)."""
    own = sensors.get(str(attrs.get("sensor", name)))
    if own is not None:
        return own
    for sensor_name, sensor in sensors.items():
        if name.startswith(sensor_name + "_") and "_" not in name[len(sensor_name) + 1:]:
            return sensor
    return {"name": name, "kind": str(attrs.get("units", "")) or name}


def _is_flat_zero(values, scale: float) -> bool:
    """No finite value, or every value zero to 1e-12 of the panel's largest (round-off)."""
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    return finite.size == 0 or float(np.max(np.abs(finite))) <= 1e-12 * scale


def _describe(name: str, sensor: dict, several_beams: bool, first_beam: str | None) -> tuple[str, str | None, str]:
    """(kind, part or None, legend) of a result column of the sensor ``sensor`` (its scenario table)."""
    kind = str(sensor.get("kind", ""))
    sensor_name = str(sensor.get("name", name))
    part = name[len(sensor_name) + 1:] if name.startswith(sensor_name + "_") else None
    beam = sensor.get("beam") or (first_beam if several_beams and kind in BEAM_KINDS else None)
    where = f"{beam}, " if beam and several_beams else ""
    if kind == "surface_strain" and sensor.get("x") is not None:
        face = (f"{sensor['surface']} face" if sensor.get("surface") else
                f"y = {float(sensor.get('y', 0.0)):g} m, z = {float(sensor.get('z', 0.0)):g} m")
        return kind, part, f"{where}x = {float(sensor['x']):g} m, {face}"
    if part is not None:
        return kind, part, f"{where}{style.PART_NAMES.get(part, part.replace('_', ' '))}"
    if kind in style.QUANTITIES and kind not in BEAM_KINDS:
        return kind, None, where + style.QUANTITIES[kind].name
    return kind, None, where + name.replace("_", " ")


def timeseries_panels(ds, variables: list[str] | None = None) -> list[Panel]:
    """The panels of a run's figure, in the order their variables first appear: one per
    physical quantity (sensor kind), tip deflections of several beams one panel per
    direction. Without ``variables``: every time series (not a recorded state), leaving out
    those that are zero throughout (to round-off) and the panels beyond :data:`MAX_PANELS`."""
    panels = _panels(ds, variables)
    return panels if variables is not None else panels[:MAX_PANELS]


def _panels(ds, variables: list[str] | None) -> list[Panel]:
    from hubbeam.io.results import time_series

    scenario = _scenario(ds)
    sensors = {str(s.get("name")): s for s in scenario.get("sensors", []) if isinstance(s, dict)}
    beams = [b.get("name") for b in scenario.get("beams") or [] if isinstance(b, dict)]
    tip_beams = {s.get("beam") for s in sensors.values() if s.get("kind") == "tip_deflection"}
    several = len(beams) > 1
    names = time_series(ds) if variables is None else list(variables)
    groups: dict[tuple, list[tuple[str, str]]] = {}
    for name in names:
        units = str(ds[name].attrs.get("units", ""))
        sensor = _sensor_of(name, ds[name].attrs, sensors)
        kind, part, legend = _describe(name, sensor, several, beams[0] if beams else None)
        key = (kind, units, part) if kind == "tip_deflection" and len(tip_beams) > 1 else (kind, units, None)
        if key[2] is not None:  # one panel per direction: the curves are the beams
            legend = sensor.get("beam") or (beams[0] if beams else name)
        groups.setdefault(key, []).append((name, legend))
    panels = []
    for (kind, units, part), members in groups.items():
        if variables is None:
            scale = max([float(np.nanmax(np.abs(ds[n].values), initial=0.0)) for n, _ in members] + [0.0])
            members = [(n, legend) for n, legend in members if not _is_flat_zero(ds[n].values, scale)]
            if not members or scale == 0.0:
                continue
        values = np.concatenate([np.ravel(ds[n].values) for n, _ in members])
        q = style.quantity(kind, values, units)
        if part is not None:  # "tip radial", ...
            q = style.Quantity(f"tip {style.PART_NAMES.get(part, part)}" if kind == "tip_deflection" else
                               f"{q.name}, {style.PART_NAMES.get(part, part)}", q.unit, q.factor)
        panels.append(Panel(q.label, [n for n, _ in members], q, [legend for _, legend in members]))
    return panels


def left_out(ds) -> dict[str, str]:
    """{variable: why} for the time series the default figure of a run does not draw: "zero
    throughout" (to round-off) or "beyond MAX_PANELS panels". A recorded state's variables
    are not time series."""
    from hubbeam.io.results import time_series

    every = _panels(ds, None)
    drawn = {n for p in every[:MAX_PANELS] for n in p.members}
    beyond = {n for p in every[MAX_PANELS:] for n in p.members}
    return {n: f"beyond {MAX_PANELS} panels" if n in beyond else "zero throughout" for n in time_series(ds)
            if n not in drawn}


def variable_label(ds, name: str) -> tuple[str, float]:
    """(axis label, factor) of one variable drawn alone: its quantity and display unit, with
    what the legend would say ("radial tip deflection (mm)", "surface strain (\u00b5\u03b5)" over
    the gauge's place)."""
    panel = _panels(ds, [name])[0]
    q, legend = panel.quantity, panel.legends[0]
    if legend == q.name:
        return panel.label, q.factor
    if "_" in name and legend in style.PART_NAMES.values():  # a part: "radial tip deflection"
        return style.axis_label(f"{legend.split(' (')[0]} {q.name}", q.unit), q.factor
    return f"{panel.label}\n{legend}", q.factor


def plot_timeseries(ds, path, title: str = "", variables: list[str] | None = None, subtitle: str = ""
                    ) -> dict[str, str]:
    """A run's variables over time in the panels of :func:`timeseries_panels` (default: every
    variable that is not zero throughout, at most MAX_PANELS panels); ``title`` and
    ``subtitle`` (:func:`hubbeam.plots.style.run_title`). Returns {variable: why} for the
    time series it left out (:func:`left_out`; the caller says so: nothing but the plot is in
    the image)."""
    panels = timeseries_panels(ds, variables)
    if not panels:
        raise ValueError("nothing to plot: every variable is zero throughout the run")
    t = ds["time"].values
    with style.paper_style():
        fig, axes = style.figure(len(panels), 1, sharex=True)
        for ax, panel in zip(axes[:, 0], panels):
            for k, (name, legend) in enumerate(zip(panel.members, panel.legends)):
                ax.plot(t, panel.quantity.factor * ds[name].values, label=legend, **style.styled(k))
            ax.set_ylabel(panel.label)
            if len(panel.members) > 1 or panel.legends[0] != panel.quantity.name:  # a gauge: where it is
                ax.legend(loc="best", ncol=min(len(panel.members), 3))
        axes[-1, 0].set_xlabel("time (s)")
        axes[-1, 0].set_xlim(float(t[0]), float(t[-1])) if t.size > 1 else None
        style.finish(fig, path, title, subtitle)
    return left_out(ds) if variables is None else {}


def plot_comparison(datasets: dict, path, variables: list[str], title: str = "", subtitle: str = "") -> None:
    """The same variables of several runs ({legend: dataset}) over time, one panel each
    (the physical name and unit of the first run's variable)."""
    first = next(iter(datasets.values()))
    with style.paper_style():
        fig, axes = style.figure(len(variables), 1, sharex=True)
        for ax, name in zip(axes[:, 0], variables):
            label, factor = variable_label(first, name)
            for k, (legend, ds) in enumerate(datasets.items()):
                ax.plot(ds["time"].values, factor * ds[name].values, label=legend, **style.styled(k))
            ax.set_ylabel(label)
        axes[0, 0].legend(loc="best")
        axes[-1, 0].set_xlabel("time (s)")
        style.finish(fig, path, title, subtitle)
