"""Campbell diagram: natural frequencies about the steadily rotating state against hub speed."""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam import api
from hubbeam.io.scenario import Scenario
from hubbeam.errors import ComputationError
from hubbeam.solvers.modal import rotating_modal_analysis
from hubbeam.solvers.static import solve_static
from hubbeam.studies.variants import FORMULATIONS, variant


def campbell(scenario: Scenario, speeds, count: int = 6, formulations=("ancf", "ffr", "ffr+"),
             progress=None) -> xr.Dataset:
    """Frequencies (Hz) of the lowest ``count`` modes about the steadily rotating state at
    each hub speed (rad/s), for each formulation: a Dataset ``frequency_hz`` over
    (formulation, omega, mode). The hub is driven at constant speed; the drag is left out
    (undamped modes about the undamped steady state). Each speed continues from the steady
    state of the previous one. ``progress(done, total)`` after each point."""
    speeds = np.asarray(speeds, dtype=float)
    out = np.full((len(formulations), speeds.size, count), np.nan)
    total, done = len(formulations) * speeds.size, 0
    for i, form in enumerate(formulations):
        x0 = chart = None
        for j, omega in enumerate(speeds):
            sc = variant(scenario, FORMULATIONS[form] + [
                'hub.motion="prescribed"', 'hub.drive.profile="constant"', f"hub.drive.omega_s={max(omega, 1e-12)}",
                "damping.linear=0.0", "damping.quadratic=0.0"])
            system = api.build_system(sc)
            try:
                steady = solve_static(system, load_steps=sc.analysis.load_steps if x0 is None else 2, x0=x0,
                                      chart=chart, spin=omega)
                x0, chart = steady.x, steady.chart
                f = rotating_modal_analysis(system, steady, omega, count=count).frequencies_hz
            except (ComputationError, np.linalg.LinAlgError) as exc:  # say where: which speed, which formulation
                raise ComputationError(f"Campbell diagram, {form} at omega = {omega:g} rad/s: {exc}") from exc
            out[i, j, : f.size] = f
            done += 1
            if progress:
                progress(done, total)
    ds = xr.Dataset({"frequency_hz": (("formulation", "omega", "mode"), out, {"units": "Hz"})},
                    coords={"formulation": list(formulations), "omega": ("omega", speeds, {"units": "rad/s"}),
                            "mode": np.arange(1, count + 1)})
    ds.attrs["scenario"] = scenario.name
    return ds
