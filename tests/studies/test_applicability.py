"""The FFR applicability map on a LocalCluster: FFR's errors grow with deflection and speed."""

import numpy as np

from hubbeam.io.scenario import load_example
from hubbeam.studies.applicability import applicability_map


def test_errors_grow_with_deflection_and_speed():
    ds = applicability_map(load_example("exp1", ["beam.elements=4"]), [0.0015, 0.004], [0.0, 0.4], release_s=1.0,
                           workers=2)
    assert (ds["message"] == "").all()
    wm = ds["w_m_over_L"].values
    assert wm[0] > wm[1] > 0.05  # the thinner plate deflects more
    f = np.abs(ds["frequency_error_pct"].values)
    d = np.abs(ds["deflection_error_pct"].values)
    assert f[0, 0] > f[1, 0] and d[0, 0] > d[1, 0]  # more deflection, more error
    assert f[1, 1] > f[1, 0] and d[1, 1] > d[1, 0]  # faster, more error
    assert f[1, 0] < 2.0  # thick plate at rest: FFR is good
    assert np.allclose(ds["omega"].values[:, 1], 0.4 * ds["omega_1"].values[:, 1])


def test_the_static_and_steady_solutions_take_the_scenarios_load_steps(monkeypatch):
    """The map's equilibria (the rest modes and both formulations' steady rotation) use
    analysis.load_steps like every other analysis (its dynamic part goes through api.run)."""
    from hubbeam.solvers import static
    from hubbeam.studies.applicability import model_errors

    seen = []
    solve = static.solve_static

    def recording(system, *args, **kwargs):
        seen.append(kwargs.get("load_steps"))
        return solve(system, *args, **kwargs)

    monkeypatch.setattr(static, "solve_static", recording)
    data = load_example("exp1", ["beam.elements=2", "analysis.load_steps=3"]).to_dict()
    out = model_errors(data, 0.004, 0.3)
    assert seen == [3, 3, 3]
    assert np.isfinite(out["frequency_error_pct"])
