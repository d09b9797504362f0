"""Where is the paper's linear FFR good enough? A map of its error against ANCF.

The paper's rules of thumb: FFR's frequency error grows once the peak deflection w_m
along k_b exceeds 38 % of L (Sec. 5), and its tip-deflection error once the hub speed
exceeds 33 % of the first natural frequency (Sec. 6). The map measures both errors over
a grid of plate thickness (which sets the deflection under gravity) and hub speed, for
a scenario's beam and hub (default: experiment 1's):

- w_m / L: the peak tip deflection along k_b in the first ``release_s`` seconds after the
  beam is released from straight under gravity (ANCF, free hub: the paper's definition);
- omega / omega_1: a steady hub speed over the first natural frequency (rad/s) of the
  clamped beam at rest (ANCF, about its gravity-sagged state);
- frequency error: FFR's first natural frequency about the steadily rotating, sagged state
  against ANCF's (modal analyses, undamped);
- deflection error: the size of FFR's steady tip displacement (centrifugal, gravity, drag)
  against ANCF's.

These are steady-state and modal counterparts of the paper's transient measures: they
isolate the model error from start-up transients and cost seconds per point. Points run
as independent Dask tasks (:func:`hubbeam.studies.sweep.run_on_dask`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam.io.scenario import Scenario
from hubbeam.studies.sweep import run_on_dask


def _deflection_along_n(beam, tip: dict) -> float:
    """The tip displacement along the root section's n (the weak-axis bending direction):
    n = sin(beta) (cos(p) j0 - sin(p) i_k) + cos(beta) k_k for twist beta and precone p."""
    sb, cb = np.sin(beam.twist), np.cos(beam.twist)
    sp, cp = np.sin(beam.precone), np.cos(beam.precone)
    return -sb * sp * tip["radial"] + sb * cp * tip["vertical"] + cb * tip["tangential"]


def peak_deflection(data: dict, thickness: float, release_s: float) -> dict:
    """w_m / L after a release under gravity (ANCF, free hub, the scenario's drag)."""
    from hubbeam import api
    from hubbeam.io.scenario import Sensor, apply_overrides, validate
    from hubbeam.studies.variants import single_beam, with_formulation

    sc = with_formulation(validate(apply_overrides(data, [f"beams[0].thickness={float(thickness)!r}"])), "ancf",
                          ['hub.motion="free"', f"analysis.t_end={float(release_s)!r}"])
    beam = single_beam(sc, "the applicability map")
    traj, failure = api.run(sc, sensors=[Sensor(name="tip", kind="tip_deflection")])
    if failure is not None:
        raise failure
    w = np.array([_deflection_along_n(beam, r) for r in traj.records["tip"]])
    return {"w_m_over_L": float(np.max(np.abs(w)) / beam.length)}


def model_errors(data: dict, thickness: float, ratio: float) -> dict:
    """FFR against ANCF at one (thickness, omega / omega_1) point."""
    from hubbeam import api
    from hubbeam.io.scenario import apply_overrides, validate
    from hubbeam.solvers.modal import modal_analysis, rotating_modal_analysis
    from hubbeam.solvers.static import solve_static
    from hubbeam.studies.variants import with_formulation

    sc = validate(apply_overrides(data, [f"beams[0].thickness={float(thickness)!r}"]))
    rest = api.build_system(with_formulation(sc, "ancf", ['hub.motion="fixed"']))
    load_steps = sc.analysis.load_steps
    omega1 = 2 * np.pi * modal_analysis(rest, solve_static(rest, load_steps=load_steps), count=1).frequencies_hz[0]
    omega = ratio * omega1
    out = {"omega_1": float(omega1), "omega": float(omega)}
    for form in ("ancf", "ffr"):
        system = api.build_system(with_formulation(sc, form, [
            'hub.motion="prescribed"', 'hub.drive.profile="constant"', f"hub.drive.omega_s={float(max(omega, 1e-12))!r}"]))
        steady = solve_static(system, load_steps=load_steps, spin=omega)
        out[f"{form}_deflection"] = float(np.linalg.norm(list(system.tip_displacement(steady.x).values())))
        out[f"{form}_frequency"] = float(rotating_modal_analysis(system, steady, omega, count=1).frequencies_hz[0])
    out["frequency_error_pct"] = 100 * (out["ffr_frequency"] / out["ancf_frequency"] - 1)
    out["deflection_error_pct"] = 100 * (out["ffr_deflection"] / out["ancf_deflection"] - 1)
    return out


def applicability_map(scenario: Scenario, thicknesses, ratios, release_s: float = 1.5, scheduler=None,
                      workers=None, progress=None) -> xr.Dataset:
    """The map over (thickness, ratio) as a Dataset (see the module doc). One beam only."""
    from hubbeam.studies.variants import single_beam

    single_beam(scenario, "the applicability map")
    thicknesses, ratios = np.asarray(thicknesses, float), np.asarray(ratios, float)
    data = scenario.to_dict()
    peaks = [(peak_deflection, (data, h, release_s)) for h in thicknesses]
    points = [(model_errors, (data, h, r)) for h in thicknesses for r in ratios]
    results = run_on_dask(_call, peaks + points, scheduler, workers, progress)
    peak, grid = results[: len(peaks)], results[len(peaks):]
    shape = (thicknesses.size, ratios.size)
    names = ["omega_1", "omega", "ancf_frequency", "ffr_frequency", "ancf_deflection", "ffr_deflection",
             "frequency_error_pct", "deflection_error_pct"]
    arrays = {n: np.full(shape, np.nan) for n in names}
    message = np.full(shape, "", dtype=object)
    for k, res in enumerate(grid):
        i, j = divmod(k, ratios.size)
        if "failure" in res:
            message[i, j] = res["failure"]
            continue
        for n in names:
            arrays[n][i, j] = res[n]
    wm = np.array([p.get("w_m_over_L", np.nan) for p in peak])
    ds = xr.Dataset({n: (("thickness", "ratio"), a) for n, a in arrays.items()},
                    coords={"thickness": ("thickness", thicknesses, {"units": "m"}), "ratio": ratios})
    ds["w_m_over_L"] = ("thickness", wm)
    ds["message"] = (("thickness", "ratio"), message.astype(str))
    ds.attrs["scenario"] = scenario.name
    return ds


def _call(func, args):
    try:
        return func(*args)
    except Exception as exc:  # a point that fails is recorded, the map goes on
        return {"failure": f"{exc.__class__.__name__}: {exc}"}
