"""Which panels plot_timeseries draws (plots.timeseries_panels)."""

import json

import numpy as np
import pytest
import xarray as xr

from hubbeam import plots


def _dataset(n_strains=2, tips=1):
    t = np.linspace(0.0, 1.0, 11)
    sensors, data = [], {}

    def add(name, kind, units, columns):
        sensors.append({"name": name, "kind": kind})
        for column, values in columns.items():
            data[column] = xr.DataArray(values, dims="time", attrs={"units": units, "sensor": name})

    for i in range(n_strains):
        add(f"strain_{i}", "surface_strain", "1", {f"strain_{i}": 1e-4 * np.sin(t + i)})
    add("omega", "hub_angular_velocity", "rad/s", {"omega": t})
    add("angle", "hub_angle", "rad", {"angle": t ** 2})
    for k in range(tips):
        add(f"tip{k}", "tip_deflection", "m", {f"tip{k}_radial": 0 * t, f"tip{k}_vertical": -t, f"tip{k}_tangential": t})
    add("torque", "hub_torque", "N m", {"torque": 0.0 * t})
    add("energy", "energy", "J", {"energy_kinetic": t, "energy_drive": 1e-20 * t, "energy_total": 1.0 + 0 * t})
    ds = xr.Dataset(data, coords={"time": t})
    ds.attrs["scenario"] = json.dumps({"sensors": sensors})
    return ds


def test_grouped_by_quantity_flat_zero_left_out():
    panels = plots.timeseries_panels(_dataset(tips=1))
    assert [p.members for p in panels] == [["strain_0", "strain_1"], ["omega"], ["angle"],
                                           ["tip0_vertical", "tip0_tangential"], ["energy_kinetic", "energy_total"]]
    # physical names and display units, never "(1)"; strain in microstrain, a short length in mm
    assert [p.label for p in panels] == ["surface strain (\u00b5\u03b5)", "hub speed (rad/s)", "hub angle (rad)",
                                         "tip deflection (m)", "energy (J)"]
    assert panels[0].quantity.factor == 1e6
    assert panels[3].legends == ["vertical", "tangential"]  # the parts, not the column names
    assert panels[4].legends == ["kinetic", "total (kinetic + strain + gravity)"]
    assert plots.timeseries_panels(_dataset(tips=1), ["tip0_radial"])[0].label == "tip deflection (mm)"  # zeros


def test_tips_of_several_beams_one_panel_per_direction():
    ds = _dataset(tips=2)
    sensors = json.loads(ds.attrs["scenario"])
    for s in sensors["sensors"]:
        if s["kind"] == "tip_deflection":
            s["beam"] = f"blade{s['name'][-1]}"
    ds.attrs["scenario"] = json.dumps(dict(sensors, beams=[{"name": "blade0"}, {"name": "blade1"}]))
    panels = {p.label: p for p in plots.timeseries_panels(ds)}
    assert panels["tip vertical (m)"].members == ["tip0_vertical", "tip1_vertical"]
    assert panels["tip vertical (m)"].legends == ["blade0", "blade1"]
    assert panels["surface strain (\u00b5\u03b5)"].legends[0] == "blade0, strain 0"  # no station: its name
    assert panels["hub speed (rad/s)"].legends == ["hub speed"]  # the hub belongs to no beam


def test_at_most_max_panels_and_chosen_variables_drawn_as_given(tmp_path):
    ds = _dataset()
    for k in range(8):  # more kinds than panels
        ds[f"extra{k}"] = xr.DataArray(np.ones(11) * (k + 1), dims="time", attrs={"units": f"u{k}", "sensor": f"x{k}"})
    assert len(plots.timeseries_panels(ds)) == plots.MAX_PANELS
    chosen = plots.timeseries_panels(ds, ["torque", "omega", "tip0_radial"])
    assert [p.members for p in chosen] == [["torque"], ["omega"], ["tip0_radial"]]  # zero, but asked for
    left_out = plots.plot_timeseries(ds, tmp_path / "f.png")
    assert (tmp_path / "f.png").stat().st_size > 5000
    # what is not drawn is returned (the command says it on stderr), not written in the image
    assert left_out["tip0_radial"] == "zero throughout" and left_out["energy_drive"] == "zero throughout"
    assert left_out["extra7"] == f"beyond {plots.MAX_PANELS} panels"
    assert plots.plot_timeseries(ds, tmp_path / "g.pdf", variables=["omega"]) == {}
    assert (tmp_path / "g.pdf").read_bytes().startswith(b"%PDF")


def test_run_title_names_the_overrides():
    title, subtitle = plots.run_title("exp1", ["beam.formulation=\"ffr\"", "beam.elements=8"], "partial")
    assert title == "exp1 (partial)" and subtitle == 'beam.formulation = "ffr"; beam.elements = 8'
    assert plots.run_title("exp1") == ("exp1", "")


def test_nothing_to_draw_is_an_error(tmp_path):
    t = np.linspace(0, 1, 5)
    ds = xr.Dataset({"a": xr.DataArray(0 * t, dims="time", attrs={"units": "m"})}, coords={"time": t})
    with pytest.raises(ValueError, match="nothing to plot"):
        plots.plot_timeseries(ds, tmp_path / "f.png")
