"""Campbell diagram: natural frequencies about the steadily rotating state against hub speed,
each mode labelled by its kinetic energy and the modes followed from speed to speed by their
shape (MAC tracking, :mod:`hubbeam.solvers.mode_shapes`)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from hubbeam import api
from hubbeam.errors import ComputationError
from hubbeam.io.scenario import Scenario
from hubbeam.solvers.modal import rotating_modal_analysis
from hubbeam.solvers.mode_shapes import energy_fractions, match_modes, mode_label, motions_of
from hubbeam.solvers.static import solve_static
from hubbeam.studies.variants import FORMULATIONS, variant


def spare_modes(count: int) -> int:
    """Modes computed beyond ``count`` at every speed, so that a tracked branch can be found
    when it climbs above a mode that was higher at the previous speed."""
    return max(2, count // 2)


def campbell(scenario: Scenario, speeds, count: int = 6, formulations=("ancf", "ffr", "ffr+"),
             progress=None) -> xr.Dataset:
    """Frequencies (Hz) of the lowest ``count`` modes about the steadily rotating state at each
    hub speed (rad/s), for each formulation. The hub is driven at constant speed; the drag is
    left out (undamped modes about the undamped steady state). Each speed continues from the
    steady state of the previous one. ``progress(done, total)`` after each point.

    The Dataset holds, over (formulation, omega, mode), the ascending ``frequency_hz``, their
    ``label`` and ``energy_fraction`` (over ``motion``); and over (formulation, omega, branch)
    the *tracked* modes: branch b starts as the b-th mode at the first speed and continues at
    every next speed with the mode (among ``count`` + :func:`spare_modes` computed) that the
    assignment maximising the summed MAC with the previous speed's shapes gives it:
    ``tracked_frequency_hz``, ``tracked_label`` and ``mac`` (the MAC of that match, 1 at the
    first speed); ``branch_label`` (formulation, branch) is the label a branch has at most speeds."""
    speeds = np.asarray(speeds, dtype=float)
    computed = count + spare_modes(count)
    nf, ns = len(formulations), speeds.size
    freq = np.full((nf, ns, computed), np.nan)
    labels = np.full((nf, ns, computed), "", dtype=object)
    motions = motions_of(api.build_system(scenario))  # joints add their hinges' parts
    fractions = np.full((nf, ns, computed, len(motions)), np.nan)
    tracked = np.full((nf, ns, count), np.nan)
    tracked_labels = np.full((nf, ns, count), "", dtype=object)
    mac = np.full((nf, ns, count), np.nan)
    total, done = nf * ns, 0
    for i, form in enumerate(formulations):
        x0 = chart = previous = None
        for j, omega in enumerate(speeds):
            # no sensors: the diagram reads none, and a free hub's (applied torque) do not hold on a driven one
            sc = variant(scenario, FORMULATIONS[form] + [
                'hub.motion="prescribed"', 'hub.drive.profile="constant"', f"hub.drive.omega_s={max(omega, 1e-12)}",
                "damping.linear=0.0", "damping.quadratic=0.0", "sensors=[]"])
            system = api.build_system(sc)
            try:
                steady = solve_static(system, load_steps=sc.analysis.load_steps if x0 is None else 2, x0=x0,
                                      chart=chart, spin=omega)
                x0, chart = steady.x, steady.chart
                modes = rotating_modal_analysis(system, steady, omega, count=computed)
                shares = [energy_fractions(system, steady.x, steady.chart, u) for u in modes.shapes.T]
            except (ComputationError, np.linalg.LinAlgError, ValueError) as exc:  # say where
                raise ComputationError(f"Campbell diagram, {form} at omega = {omega:g} rad/s: {exc}") from exc
            f, shapes = modes.frequencies_hz, modes.shapes
            n = f.size
            freq[i, j, :n] = f
            labels[i, j, :n] = [mode_label(s) for s in shares]
            fractions[i, j, :n] = [[s.get(k, 0.0) for k in motions] for s in shares]
            if previous is None:
                index, match = np.arange(min(count, n)), np.ones(min(count, n))
            else:
                index, match = match_modes(previous, shapes)
            m = index.size
            tracked[i, j, :m], tracked_labels[i, j, :m], mac[i, j, :m] = f[index], labels[i, j, index], match
            previous = shapes[:, index]
            done += 1
            if progress:
                progress(done, total)
    branch_labels = np.array([[_most_common(tracked_labels[i, :, b]) for b in range(count)] for i in range(nf)],
                             dtype=object)
    ds = xr.Dataset({"frequency_hz": (("formulation", "omega", "mode"), freq[:, :, :count], {"units": "Hz"}),
                     "label": (("formulation", "omega", "mode"), labels[:, :, :count]),
                     "energy_fraction": (("formulation", "omega", "mode", "motion"), fractions[:, :, :count],
                                         {"units": "1"}),
                     "tracked_frequency_hz": (("formulation", "omega", "branch"), tracked, {"units": "Hz"}),
                     "tracked_label": (("formulation", "omega", "branch"), tracked_labels),
                     "mac": (("formulation", "omega", "branch"), mac, {"units": "1",
                             "long_name": "MAC of the match with the previous speed"}),
                     "branch_label": (("formulation", "branch"), branch_labels)},
                    coords={"formulation": list(formulations), "omega": ("omega", speeds, {"units": "rad/s"}),
                            "mode": np.arange(1, count + 1), "branch": np.arange(1, count + 1),
                            "motion": list(motions)})
    ds.attrs["scenario"] = scenario.name
    return ds


def _most_common(values) -> str:
    names, counts = np.unique([str(v) for v in values if v], return_counts=True)
    return str(names[np.argmax(counts)]) if names.size else ""
