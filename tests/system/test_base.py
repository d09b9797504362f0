"""A free base in motion, verified against what does not share the code's derivation.

- A rigid body alone, torque-free, spun near its intermediate principal axis: its body
  angular velocity against Euler's equations I w' + w x I w = 0 integrated by scipy's DOP853 at
  rtol 1e-12 (the flips of the intermediate-axis instability at the right times), and second
  order in dt.
- A free bus tumbling with damped flexible beams (ANCF and FFR, tip bodies) and no external
  force: the linear momentum and the angular momentum about the system's centre of mass are
  conserved and total + dissipated is constant, each to a tolerance that shrinks as dt^2; the
  centre of mass moves on a straight line at P / m, m summed here from the scenario's data.
- Rotational invariance: a hub turned by ``hub.orientation`` (R_h) under gravity g equals an
  upright hub under R_h^T g; the upright model turned as a whole by ``base.initial.rotation``
  (R_0) under R_0 R_h^T g, and both turns together under g, equal it too (tip deflections in
  the hub frame, strains, hub angle; statics and a run; ANCF and FFR beams).

Every run here uses full Newton at tolerance 1e-12 (``analysis.newton = "full"``): the default
modified Newton at 1e-9 stops early at small dt, which would hide the integration error's rate.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from hubbeam import api
from hubbeam.io.results import to_dataset
from hubbeam.io.scenario import validate

#: full Newton to 1e-12: the integration error, not the Newton tolerance, is what these tests see
TIGHT = {"newton": "full", "tolerance": 1e-12}


def run(data: dict) -> dict[str, np.ndarray]:
    """The run of a scenario given as a dict: {column: values} and "time"."""
    scenario = validate(data)
    trajectory, failure = api.run(scenario)
    assert failure is None, failure
    ds = to_dataset(trajectory, scenario)
    out = {name: ds[name].values for name in ds.data_vars}
    out["time"] = ds["time"].values
    return out


def vector(result: dict, name: str) -> np.ndarray:
    """A three-part sensor's columns as (n, 3)."""
    return np.column_stack([result[f"{name}_{c}"] for c in "xyz"])


def zero_crossings(t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Times where y changes sign, by linear interpolation between records."""
    k = np.flatnonzero(np.sign(y[1:]) != np.sign(y[:-1]))
    return t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])


# --------------------------------------------------------------------------- a rigid body alone
#: principal moments (kg m^2) and the spin near the intermediate axis (rad/s, body axes): the
#: perturbation grows at w_y sqrt((J_y - J_x)(J_z - J_y) / (J_x J_z)) = 0.71 rad/s, and the body
#: flips three times in 40 s (at 8.2, 22.2 and 36.1 s)
RIGID_INERTIA = np.array([2.0, 3.0, 4.0])
RIGID_SPIN = np.array([0.05, 2.0, 0.05])


def rigid_body(t_end: float, dt: float, output_dt: float = 0.01, **base) -> dict:
    return {"name": "rigid", "environment": {"gravity": [0.0, 0.0, 0.0]},
            "base": {"motion": "free", "mass": 100.0, "inertia": RIGID_INERTIA.tolist(),
                     "initial": {"angular_velocity": RIGID_SPIN.tolist(), "rotation": [0.4, -0.3, 1.1],
                                 "velocity": [0.2, 0.0, -0.1]}, **base},
            "analysis": {"t_end": t_end, "dt": dt, "output_dt": output_dt, **TIGHT},
            "sensors": [{"name": "w", "kind": "base_angular_velocity"}]}


def euler_equations(t_end: float, times: np.ndarray) -> np.ndarray:
    """The body angular velocity (n, 3) of Euler's torque-free equations (DOP853, rtol 1e-12)."""
    J = RIGID_INERTIA

    def rhs(_, w):
        return [(J[1] - J[2]) * w[1] * w[2] / J[0], (J[2] - J[0]) * w[2] * w[0] / J[1],
                (J[0] - J[1]) * w[0] * w[1] / J[2]]

    sol = solve_ivp(rhs, (0.0, t_end), RIGID_SPIN, method="DOP853", rtol=1e-12, atol=1e-14, t_eval=times)
    return sol.y.T


def test_a_torque_free_rigid_body_flips_about_its_intermediate_axis_as_eulers_equations_say():
    """40 s at dt = 5 ms: three flips of w_y, each within 2 ms of Euler's (measured: 0.23 ms at
    most), and w within 1e-3 rad/s of it throughout (measured 3.3e-4 of 2 rad/s)."""
    result = run(rigid_body(40.0, 0.005))
    t, w = result["time"], vector(result, "w")
    reference = euler_equations(40.0, t)
    flips, expected = zero_crossings(t, w[:, 1]), zero_crossings(t, reference[:, 1])
    assert expected.size == 3 and flips.size == 3
    assert np.max(np.abs(flips - expected)) < 2e-3
    assert np.max(np.abs(w - reference)) < 1e-3


def test_the_rigid_body_converges_at_second_order_in_dt():
    """The error against Euler's equations over 10 s at dt = 20, 10, 5 ms falls by about 4 at
    each halving (measured 1.4e-3, 3.6e-4, 8.9e-5 rad/s)."""
    errors = []
    for dt in (0.02, 0.01, 0.005):
        result = run(rigid_body(10.0, dt, output_dt=0.02))
        errors.append(np.max(np.abs(vector(result, "w") - euler_equations(10.0, result["time"]))))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(rates > 1.8), errors


# --------------------------------------------------------------------------- a tumbling flexible system
def panel(name: str, formulation: str, azimuth: float, length: float, tip_mass: float, twist: float) -> dict:
    """An aluminium strip 200 x 5 mm with structural damping and a tip body."""
    return {"name": name, "formulation": formulation, "azimuth": azimuth, "elements": 3, "length": length,
            "width": 0.2, "thickness": 0.005, "density": 2700.0, "youngs_modulus": 70e9, "poisson_ratio": 0.33,
            "twist": twist, "damping": {"stiffness_proportional": 0.02},
            "tip_body": {"mass": tip_mass, "inertia": [1e-3, 2e-3, 1.5e-3], "offset": [0.02, 0.01, 0.01]}}


TUMBLER_BEAMS = [panel("a", "ancf", 0.0, 1.5, 0.5, 30.0), panel("b", "ffr", 170.0, 1.2, 0.4, 0.0)]
#: a bus with a full inertia matrix and an offset centre of mass, its hub placed and turned on it
TUMBLER_BASE = {"motion": "free", "mass": 50.0, "inertia": [[20.0, 1.0, -0.5], [1.0, 25.0, 0.8], [-0.5, 0.8, 30.0]],
                "centre_of_mass": [0.05, -0.02, 0.03],
                "initial": {"position": [1.0, -2.0, 0.5], "rotation": [0.3, -0.5, 0.7], "velocity": [0.1, -0.2, 0.05],
                            "angular_velocity": [1.0, 1.5, -0.8]}}


def tumbler(dt: float, t_end: float = 2.0) -> dict:
    return {"name": "tumbler", "base": TUMBLER_BASE, "beams": TUMBLER_BEAMS,
            "hub": {"radius": 0.5, "position": [0.1, 0.0, -0.1], "orientation": [10.0, 0.0, 20.0]},
            "environment": {"gravity": [0.0, 0.0, 0.0]},
            "analysis": {"t_end": t_end, "dt": dt, "output_dt": 0.04, **TIGHT},
            "sensors": [{"name": "P", "kind": "linear_momentum"}, {"name": "H", "kind": "system_angular_momentum"},
                        {"name": "c", "kind": "centre_of_mass"}, {"name": "energy", "kind": "energy"},
                        {"name": "w", "kind": "base_angular_velocity"},
                        {"name": "tip_a", "kind": "tip_deflection", "beam": "a"},
                        {"name": "tip_b", "kind": "tip_deflection", "beam": "b"}]}


def total_mass() -> float:
    """The whole system's mass (kg) from the scenario's numbers: bus, strips, tip bodies."""
    return TUMBLER_BASE["mass"] + sum(b["density"] * b["width"] * b["thickness"] * b["length"] + b["tip_body"]["mass"]
                                      for b in TUMBLER_BEAMS)


@pytest.fixture(scope="module")
def tumbling():
    return {dt: run(tumbler(dt)) for dt in (0.004, 0.002, 0.001)}


@pytest.mark.slow  # a validation run that compiles its own models (minutes on a cold cache)
def test_a_tumbling_flexible_system_conserves_its_momenta_and_energy_to_second_order(tumbling):
    """Over 2 s of tumbling at 1 to 1.5 rad/s (the panels bend by up to 16 mm and their damping
    takes 8.0e-3 J), the largest change of P (13.5 N s), of H about the centre of mass (61 N m s)
    and of total + dissipated (63.5 J) falls by 4 at each halving of dt. Measured at dt = 4, 2,
    1 ms: P 8.6e-5, 2.1e-5, 5.4e-6 N s; H 9.8e-5, 2.5e-5, 6.2e-6 N m s; total + dissipated
    1.8e-4, 4.5e-5, 1.1e-5 J (0.14 % of the dissipated energy at 1 ms).

    The ANCF panel has 3 elements: its discrete strain energy is not exactly invariant under a
    rigid rotation of a *bent* beam (the twist is a cubic in the chart, docs/ancf.md), which
    shows as a drift of H that the mesh removes and dt does not (a 3 mm panel: 1.9e-4 N m s with
    3 elements, 4.6e-6 with 6, at dt = 1 ms); at 5 mm and 3 elements it is below the dt error."""
    drifts = {"P": [], "H": [], "E": []}
    for dt, r in tumbling.items():
        P, H = vector(r, "P"), vector(r, "H")
        E = r["energy_total"] + r["energy_dissipated"]
        drifts["P"].append(np.max(np.abs(P - P[0])) / np.max(np.abs(P[0])))
        drifts["H"].append(np.max(np.abs(H - H[0])) / np.max(np.abs(H[0])))
        drifts["E"].append(np.max(np.abs(E - E[0])) / E[0])
        assert r["energy_dissipated"][-1] > 1e-4 * E[0]  # the damping works
        assert np.max(np.abs(E - E[0])) < 0.05 * r["energy_dissipated"][-1]
        assert np.max(np.abs(r["energy_drive"])) < 1e-15 * E[0]  # no torque, no prescribed motion (measured 5e-28 J)
    for name, d in drifts.items():
        rates = np.log2(np.array(d[:-1]) / np.array(d[1:]))
        assert np.all(rates > 1.8), (name, d)
        assert d[-1] < 1e-6, (name, d)


@pytest.mark.slow  # a validation run that compiles its own models (minutes on a cold cache)
def test_the_centre_of_mass_moves_on_a_straight_line_at_the_momentum_over_the_mass(tumbling):
    """The centre of mass stays on the least-squares line through its records (off it by
    3.8e-7, 9.6e-8, 2.4e-8 m at dt = 4, 2, 1 ms) and moves along it at P / m, m summed from the
    scenario's numbers (the slope within 9e-8 m/s of 0.27 m/s at 1 ms)."""
    off = []
    for r in tumbling.values():
        t, c, P = r["time"], vector(r, "c"), vector(r, "P")
        A = np.column_stack([np.ones_like(t), t])
        coef, *_ = np.linalg.lstsq(A, c, rcond=None)
        off.append(np.max(np.abs(A @ coef - c)))
    assert off[-1] < 1e-7 and np.log2(off[0] / off[1]) > 1.8 and np.log2(off[1] / off[2]) > 1.8, off
    np.testing.assert_allclose(coef[1], P[0] / total_mass(), rtol=1e-6)


@pytest.mark.slow  # a validation run that compiles its own models (minutes on a cold cache)
def test_the_tumbling_state_converges_at_second_order(tumbling):
    """The tip deflections and the bus's angular velocity at 2 s: the differences between
    dt = 4, 2 and 1 ms fall by about 4 (Richardson)."""
    last = [np.concatenate([vector(r, "w")[-1], [r[f"tip_{k}_{p}"][-1] for k in "ab"
                                                  for p in ("radial", "vertical", "tangential")]])
            for r in tumbling.values()]
    d1, d2 = np.max(np.abs(last[0] - last[1])), np.max(np.abs(last[1] - last[2]))
    assert np.log2(d1 / d2) > 1.8, (d1, d2)


# --------------------------------------------------------------------------- rotational invariance
#: a free hub (its angle follows from the gravity torque about a tilted axis) with an ANCF and
#: an FFR strip laid flat, the FFR one with geometric stiffening
INVARIANT_BEAMS = [{"name": f"b{k}", "formulation": f, "azimuth": az, "elements": 4, "length": 1.0, "width": 0.05,
                    "thickness": 0.004, "density": 2700.0, "youngs_modulus": 70e9, "poisson_ratio": 0.33,
                    **({"geometric_stiffening": True} if f == "ffr" else {})}
                   for k, (f, az) in enumerate((("ancf", 0.0), ("ffr", 120.0)))]
INVARIANT_SENSORS = ([{"name": f"tip{k}", "kind": "tip_deflection", "beam": f"b{k}"} for k in range(2)]
                     + [{"name": f"strain{k}", "kind": "surface_strain", "beam": f"b{k}", "x": 0.05,
                         "surface": "upper"} for k in range(2)]
                     + [{"name": "theta", "kind": "hub_angle"}])
G = np.array([0.0, -9.81, 0.0])
HUB_TURN = np.array([20.0, -35.0, 50.0])  # deg, hub.orientation
BASE_TURN = np.array([0.4, -1.0, 2.2])  # rad, base.initial.rotation


def invariant(gravity, hub_orientation=(0.0, 0.0, 0.0), base_rotation=(0.0, 0.0, 0.0)) -> dict:
    return {"name": "turned", "hub": {"motion": "free", "inertia": 0.3, "radius": 0.2, "twist": 90.0,
                                      "orientation": list(hub_orientation)},
            "base": {"motion": "fixed", "initial": {"rotation": list(base_rotation)}},
            "beams": INVARIANT_BEAMS, "environment": {"gravity": list(gravity)},
            "analysis": {"t_end": 0.3, "dt": 0.002, "output_dt": 0.01, **TIGHT}, "sensors": INVARIANT_SENSORS}


def turned_models() -> dict[str, dict]:
    """The same model four ways: upright under u = R_h^T g; the hub turned by R_h under g; the
    upright model turned by R_0 (a fixed base's initial rotation) under R_0 u; both under R_0 g."""
    R_h = Rotation.from_rotvec(np.radians(HUB_TURN)).as_matrix()
    R_0 = Rotation.from_rotvec(BASE_TURN).as_matrix()
    upright = R_h.T @ G
    return {"upright": invariant(upright), "hub turned": invariant(G, HUB_TURN),
            "base turned": invariant(R_0 @ upright, base_rotation=BASE_TURN),
            "both turned": invariant(R_0 @ R_h @ upright, HUB_TURN, BASE_TURN)}


# slow: a long validation run (CI runs it: python -m pytest -q -m slow)
@pytest.mark.slow
def test_a_turned_model_runs_as_the_upright_one_under_the_gravity_turned_back():
    """0.3 s from straight: every tip deflection part (to 1e-12 of the 1 m beams), strain (to
    1e-10 of its peak) and the hub angle (0.14 rad: the tilted axis makes gravity turn the free
    hub; to 1e-12 rad) equal the upright model's (measured: 1.5e-15 m, 1e-15 of the strain,
    5e-16 rad: round-off, since the Newton tolerance is 1e-12)."""
    results = {name: run(data) for name, data in turned_models().items()}
    reference = results.pop("upright")
    assert np.max(np.abs(reference["theta"])) > 0.1  # the gravity torque about the axis turns the hub
    for name, r in results.items():
        for column, values in reference.items():
            if column == "time":
                continue
            tolerance = 1e-10 * np.max(np.abs(values)) if column.startswith("strain") else 1e-12
            assert np.max(np.abs(r[column] - values)) <= tolerance, (name, column)


def test_a_turned_model_has_the_upright_ones_static_equilibrium():
    """``static`` (hub held at theta = 0): each beam's tip displacement in its hub frame equals
    the upright model's to 1e-12 m (measured 2e-16 m on 22 mm)."""
    answers = {name: api.static(validate(data)).to_dict() for name, data in turned_models().items()}
    reference = answers.pop("upright")
    for name, answer in answers.items():
        for beam in ("b0", "b1"):
            got, want = answer["beams"][beam]["tip_displacement"], reference["beams"][beam]["tip_displacement"]
            for part in ("radial", "vertical", "tangential"):
                assert got[part] == pytest.approx(want[part], abs=1e-12), (name, beam, part)
        assert abs(reference["beams"]["b0"]["tip_displacement"]["vertical"]) > 0.01
