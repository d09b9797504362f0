"""Controllers' inputs beyond the hub and outputs on the base and the joints
(hubbeam.system.controller_inputs, issue 28): each input against the sensor that measures the same
column, the Newton matrix's controller entries against central differences of the residual, and
the outputs' power against the energy balance of a run."""

import numpy as np
import pytest

from hubbeam import api
from hubbeam.io.scenario import load_example, validate
from hubbeam.sensors import measure
from hubbeam.system.controllers import Controllers, controller_values

SENSORS = [
    {"name": "w", "kind": "base_angular_velocity"},
    {"name": "psi", "kind": "joint_angle", "beam": "panel_a"},
    {"name": "psi_dot", "kind": "joint_rate", "beam": "panel_a"},
    {"name": "eps_a", "kind": "surface_strain", "beam": "panel_a", "x": 0.7, "surface": "upper"},
    {"name": "eps_b", "kind": "surface_strain", "beam": "panel_b", "x": 0.5, "y": 0.1, "z": 0.002},
    {"name": "e", "kind": "energy"},
]
#: every input form: the base's rate (3), a joint angle and its rates, an ANCF strain and its rate,
#: an FFR strain (modal, geometrically stiffened: a quadratic form) and its rate
INPUTS = ["w_x", "w_y", "w_z", "psi", "psi_rate", "psi_dot", "eps_a", "eps_a_rate", "eps_b", "eps_b_rate"]
OUTPUTS = ["base_torque_x", "base_torque_y", "base_torque_z", "joint_torque_panel_a"]


def save(tmp_path, name, A, B, C, D):
    path = tmp_path / name
    np.savez(path, A=np.asarray(A, dtype=float), B=np.asarray(B, dtype=float), C=np.asarray(C, dtype=float),
             D=np.asarray(D, dtype=float))
    return str(path)


def model(tmp_path, scale=1.0, t_end=0.5, base_law=True):
    """spacecraft3d made small and mixed: panel_a ANCF (2 elements) on a flap joint with a spring,
    panel_b modal FFR (3 modes, geometric stiffening), a 2-state controller with every input form
    and every output (``scale`` multiplies B, C, D: 0 gives the same layout without the loop)."""
    d = load_example("spacecraft3d").to_dict()
    a, b = d["beams"]
    a.update(elements=2, joint={"kind": "revolute", "axis": "flap", "stiffness": 400.0, "damping": 0.0})
    b.update(formulation="ffr", elements=3, modes=3, geometric_stiffening=True)
    if not base_law:
        d["base"].pop("torque")
    d["analysis"].update(t_end=t_end, dt=5e-3)
    d["sensors"] = SENSORS
    rng = np.random.default_rng(3)
    n, m, p = 2, len(INPUTS), len(OUTPUTS)
    A = np.array([[-3.0, 1.0], [-1.0, -2.0]])
    B = scale * rng.normal(size=(n, m))
    C = scale * rng.normal(size=(p, n))
    D = scale * rng.normal(size=(p, m))
    D[:, INPUTS.index("eps_a")] *= 100.0  # strains are ~1e-4: a gain that moves something
    d["controllers"] = [{"name": "k", "file": save(tmp_path, f"k{scale}.npz", A, B, C, D), "inputs": INPUTS,
                         "outputs": OUTPUTS}]
    return validate(d, base_dir=tmp_path)


def moving_state(system, seed=5):
    """A state away from rest: the initial one, every coordinate and rate nudged at random (the
    base's Euler parameters kept on their norm), the charts the initial ones."""
    x, F = system.initial_state()
    rng = np.random.default_rng(seed)
    x = x + 1e-3 * rng.normal(size=x.size)
    e = system.layout.base_x.start + 3
    x[e:e + 4] /= np.linalg.norm(x[e:e + 4])
    v = 0.05 * rng.normal(size=x.size)
    return x, v, F


def residual_jacobians(system, x, v, F, h=1e-7):
    """(dres/dx, dres/dv) of the force rows by central differences, and the Newton matrix's
    (coef_k = 1) and (coef_c = 1) parts (dense, z order)."""
    lam = np.zeros(system.layout.n_lambda)
    acc = np.zeros_like(x)
    zx = system.layout.z_of_x

    def res(xx, vv):
        return system.equations(xx, vv, acc, lam, F, 0.3, 0.0, 0.0, 1.0, 1.0, want_matrix=False)[0]

    Jx, Jv = np.zeros((system.layout.nz, x.size)), np.zeros((system.layout.nz, x.size))
    for j in range(x.size):
        d = np.zeros(x.size)
        d[j] = h
        Jx[:, j] = (res(x + d, v) - res(x - d, v)) / (2 * h)
        Jv[:, j] = (res(x, v + d) - res(x, v - d)) / (2 * h)
    Kx = system.equations(x, v, acc, lam, F, 0.3, 0.0, 0.0, 1.0, 1.0)[1].to_dense()[:, zx]
    Cv = system.equations(x, v, acc, lam, F, 0.3, 0.0, 1.0, 0.0, 1.0)[1].to_dense()[:, zx]
    return Jx, Jv, Kx, Cv


@pytest.fixture(scope="module")
def systems(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("ctrl")
    return tmp, api.build_system(model(tmp)), api.build_system(model(tmp, scale=0.0))


def test_each_input_is_its_sensors_value_or_rate(systems):
    # the compiled inputs against the sensors (hubbeam.sensors: independent Python code); the rates
    # against a central difference of the sensor along the state's motion (x + s v)
    from hubbeam.analysis.output_jacobian import Probe

    tmp, system, _ = systems
    scenario = model(tmp)
    x, v, F = moving_state(system)
    u = controller_values(system, x, v, F)[0]
    columns = {c: s for s in scenario.sensors for c in s.columns}

    def sensor(name, xx, vv):
        s = columns[name]
        value = measure(s, system, Probe(0.3, xx, vv, np.zeros(system.layout.n_lambda), F), {})
        return value[name[len(s.name) + 1:]] if isinstance(value, dict) else value

    h = 1e-6
    for i, name in enumerate(INPUTS):
        if name.endswith("_rate"):
            base = name[:-len("_rate")]
            expected = (sensor(base, x + h * v, v) - sensor(base, x - h * v, v)) / (2 * h)
        else:
            expected = sensor(name, x, v)
        assert abs(u[i] - expected) < 1e-6 * max(abs(expected), 1e-3), name


def test_the_newton_matrix_entries_of_the_loop_are_the_residuals_derivatives(systems):
    # the controller's entries (the system's less the same system with B = C = D = 0: same layout)
    # against central differences of the residual, along x (coef_k) and v (coef_c): exact, every
    # input form and every output (the base torque's db/dx included)
    _, system, plain = systems
    x, v, F = moving_state(system)
    Jx, Jv, Kx, Cv = residual_jacobians(system, x, v, F)
    Jx0, Jv0, Kx0, Cv0 = residual_jacobians(plain, x, v, F)
    fd_x, fd_v = Jx - Jx0, Jv - Jv0
    ours_x, ours_v = Kx - Kx0, Cv - Cv0
    assert np.max(np.abs(fd_x)) > 1.0 and np.max(np.abs(fd_v)) > 1.0  # the loop is there
    assert np.max(np.abs(ours_x - fd_x)) < 1e-6 * np.max(np.abs(fd_x))
    assert np.max(np.abs(ours_v - fd_v)) < 1e-6 * np.max(np.abs(fd_v))


@pytest.mark.slow  # a validation run that compiles its own models (minutes on a cold cache)
def test_the_energy_balance_closes_with_base_and_joint_torques(tmp_path):
    # a run with only the controller acting on the base and the joint (no attitude law), kicked by
    # the initial rates: E(t) - E(0) = the drive work (the controller's power) to the integrator's
    # tolerance; leaving the controller's power out leaves a residual the size of its work
    scenario = model(tmp_path, scale=20.0, t_end=1.0, base_law=False)
    d = scenario.to_dict()
    d["base"]["initial"] = {"angular_velocity": [0.02, -0.03, 0.05]}
    scenario = validate(d, base_dir=tmp_path)
    traj, failure = api.run(scenario)
    assert failure is None
    r = traj.records["e"]
    total, drive, dissipated = (np.array([e[p] for e in r]) for p in ("total", "drive", "dissipated"))
    work = np.max(np.abs(drive - drive[0]))
    assert work > 1e-3 * np.max(np.abs(total))
    residual = (total - total[0]) - (drive - drive[0]) + (dissipated - dissipated[0])
    assert np.max(np.abs(residual)) < 1e-3 * work


def test_a_pack_is_built_for_the_controllers(systems):
    _, system, _ = systems
    assert any(isinstance(p, Controllers) for p in system.model().parts)


def bus(tmp_path, controllers=(), torque=None, t_end=8.0):
    """The bundled spacecraft (free bus, two panels with tip bodies) with its panels as modal FFR
    (4 elements, 2 modes each: a 10-state linear model), no torque law but ``torque``, a strain
    gauge at panel_a's root and ``controllers``."""
    d = load_example("spacecraft").to_dict()
    d["hub"].pop("torque")
    if torque is not None:
        d["hub"]["torque"] = torque
    for b in d["beams"]:
        b.update(formulation="ffr", elements=4, modes=2)
    d["analysis"]["t_end"] = t_end
    d["sensors"] = [{"name": "omega", "kind": "hub_angular_velocity"},
                    {"name": "eps", "kind": "surface_strain", "beam": "panel_a", "x": 0.05, "surface": "upper"},
                    {"name": "tip", "kind": "tip_deflection", "beam": "panel_a"},
                    {"name": "e", "kind": "energy"}]
    d["controllers"] = list(controllers)
    return validate(d, base_dir=tmp_path)


#: where the gain that damps the bus's mode to 0.07 lies (the damping ratio grows with the gain in
#: each: 0.069 at k = 1e4 on the strain's rate, 0.045 at -10 and 0.13 at -30 on the tip's velocity)
BRACKETS = {"eps": (1e2, 2e4), "tip_tangential": (-30.0, -1.0)}


@pytest.mark.parametrize("column", [pytest.param("eps", marks=pytest.mark.slow),  # a long run: CI's slow run
                                    "tip_tangential"])
def test_rate_feedback_designed_on_the_linear_model_damps_the_run_as_designed(tmp_path, column):
    # Design: on `linearize --open-loop` (10 states), the gain k of the hub torque -k u' (u the
    # root strain eps, or the tip's tangential deflection of panel_a, m: a tip-velocity feedback)
    # that gives the mode turning the bus (6.06 rad/s, undamped in the plant) a damping ratio of
    # 0.07 (k = 1.01e4 N m s per unit strain; k = -15.7 N m s/m on the tip's velocity).
    # Verify: the nonlinear run, kicked by a 1 N m torque pulse (omega ~ 3.5e-3 rad/s: small
    # amplitude), fitted after the pulse (t >= 1 s), decays at the closed-loop linear model's rate.
    # Measured (strain; tip): decay rate 3.2e-4; 2.5e-4, frequency 7.6e-5; 7.9e-5 apart
    # (relative); the frequency is generalized-alpha's period error (w h)^2 / 12 = 7.7e-5 at
    # dt = 5 ms. Tolerances as tests/system/test_controllers.py's: 1 % on the decay rate (the fit's
    # and the discretisation's error), 5e-4 on the frequency. The energy balance closes with the
    # controller's power in the drive work (measured 4.6e-8 J of a 4.3e-4 J swing). 4.5 s warm.
    from scipy.optimize import brentq

    from tests.system.test_controllers import decay_fit, pulse

    plant = api.linearize(bus(tmp_path), open_loop=True)
    row, col = plant.outputs.index(column), plant.inputs.index("hub_torque")
    assert plant.C[row] @ plant.B[:, col] == 0.0  # the input's rate has no feedthrough
    rate_row = plant.C[row] @ plant.A
    open_poles = plant.eigenvalues()
    mode = open_poles[np.argmin(np.abs(open_poles - 6.06j))]
    assert abs(mode.real) < 1e-9 * abs(mode)

    def damping(k):
        poles = np.linalg.eigvals(plant.A - k * np.outer(plant.B[:, col], rate_row))
        p = poles[np.argmin(np.abs(poles - mode))]
        return -p.real / abs(p)

    k = brentq(lambda g: damping(g) - 0.07, *BRACKETS[column])
    np.savez(tmp_path / "damper.npz", A=np.zeros((0, 0)), B=np.zeros((0, 1)), C=np.zeros((1, 0)), D=[[-k]])
    table, _ = pulse(tmp_path)
    scenario = bus(tmp_path, [{"file": str(tmp_path / "damper.npz"), "inputs": [column + "_rate"],
                               "outputs": ["hub_torque"]}], torque=table)
    poles = api.linearize(scenario).eigenvalues()
    target = poles[np.argmin(np.abs(poles - mode))]
    assert abs(-target.real / abs(target) - 0.07) < 1e-6  # linearize closes the loop as designed
    traj, failure = api.run(scenario)
    assert failure is None
    t = np.asarray(traj.times)
    omega = np.asarray(traj.records["omega"])
    assert 1e-3 < np.max(np.abs(omega)) < 1e-2
    keep = t >= 1.0
    (p, s, w, s2, w2), misfit = decay_fit(t[keep], omega[keep], [-1.0, 0.0, abs(mode.imag), 0.0, 29.0])
    assert misfit < 5e-3
    assert abs(s - target.real) < 1e-2 * abs(target.real)
    assert abs(w - abs(target.imag)) < 5e-4 * abs(target.imag)
    r = traj.records["e"]
    total, drive = (np.array([e[part] for e in r]) for part in ("total", "drive"))
    swing = np.max(np.abs(total - total[0]))
    assert np.max(np.abs((total - total[0]) - (drive - drive[0]))) < 1e-3 * swing


def test_a_python_law_adds_the_same_terms_as_its_static_gain(systems):
    # A Python law y = D u + C s0 ... here a static gain y = D u (the model's D) given as a function:
    # its residual and Newton matrix (dy/du by central differences: exact for a linear law up to
    # round-off) are the linear controller's without states, checked against central differences
    # of the residual as above; the law's outputs in the sensors are its y
    tmp, _, plain = systems
    scenario = model(tmp, scale=0.0)
    rng = np.random.default_rng(11)
    D = rng.normal(size=(len(OUTPUTS), len(INPUTS)))
    D[:, INPUTS.index("eps_a")] *= 100.0
    calls = []

    def law(t, u):
        calls.append(t)
        return D @ u

    system = api.build_system(scenario, laws=[{"function": law, "inputs": INPUTS, "outputs": OUTPUTS}])
    assert not system.compiled
    x, v, F = moving_state(system)
    Jx, Jv, Kx, Cv = residual_jacobians(system, x, v, F)
    Jx0, Jv0, Kx0, Cv0 = residual_jacobians(plain, x, v, F)
    assert np.max(np.abs(Jx - Jx0)) > 1.0
    assert np.max(np.abs((Kx - Kx0) - (Jx - Jx0))) < 1e-6 * np.max(np.abs(Jx - Jx0))
    assert np.max(np.abs((Cv - Cv0) - (Jv - Jv0))) < 1e-6 * np.max(np.abs(Jv - Jv0))
    assert calls and set(calls) == {0.3}
    u = controller_values(systems[1], x, v, F)[0]  # the same inputs, from the compiled controller
    y = D @ u
    torques = system.controller_torques(0.3, x, v, F)
    assert np.allclose(torques[2], y[:3], rtol=1e-12, atol=0.0)
    assert torques[1] == {0: pytest.approx(y[3], rel=1e-12)}


def test_linearize_closes_a_loop_on_the_base_and_a_joint(systems):
    # the controller's outputs base_torque_x|y|z and joint_torque_panel_a become inputs of the plant
    # for the closing (linearize's name joint_torque:panel_a), then are left out: the closed model
    # has the plant's inputs and the controller's 2 states, and its A differs from the plant's
    tmp = systems[0]
    scenario = model(tmp)
    closed = api.linearize(scenario, inputs=["base_torque_x"])
    plant = api.linearize(scenario, inputs=["base_torque_x"], open_loop=True)
    assert closed.inputs == plant.inputs == ["base_torque_x"]
    assert closed.A.shape[0] == plant.A.shape[0] + 2
    assert closed.states[-2:] == ["k_s1", "k_s2"]
    assert np.max(np.abs(closed.A[:plant.A.shape[0], :plant.A.shape[0]] - plant.A)) > 1.0  # the loop's D (measured 193)


def test_a_large_slew_with_the_strain_rate_feedback_stays_stable_and_its_energy_balance_closes(tmp_path):
    # The large-amplitude check: the bundled spacecraft's PD law (kp 20, kd 75) slews the
    # bus by 3 rad (172 deg) in 10 s, peak rate 0.64 rad/s (far from the linear model's small
    # amplitude), with the strain-rate damper of the test above in the loop (k = 1.014e4, that
    # test's design). The run completes and settles; E(t) - E(0) equals the drive work, which
    # holds the law's and the controller's power: measured 1.4e-5 J of 23.4 J. The controller's
    # own work is 0.23 J (the drive work with it minus without it): leaving its power out of the
    # balance would leave a residual about 1e4 times the tolerance.
    np.savez(tmp_path / "damper.npz", A=np.zeros((0, 0)), B=np.zeros((0, 1)), C=np.zeros((1, 0)), D=[[-1.014e4]])
    law = {"law": "pd", "kp": 20.0, "kd": 75.0, "reference": {"profile": "slew", "angle": 3.0, "T": 10.0}}
    works = []
    for controllers in ([{"file": str(tmp_path / "damper.npz"), "inputs": ["eps_rate"], "outputs": ["hub_torque"]}],
                        []):
        traj, failure = api.run(bus(tmp_path, controllers, torque=law, t_end=30.0))
        assert failure is None
        omega = np.asarray(traj.records["omega"])
        assert 0.5 < np.max(np.abs(omega)) < 1.0
        assert abs(omega[-1]) < 0.05 * np.max(np.abs(omega))  # settling at the slew's end angle
        r = traj.records["e"]
        total, drive, dissipated = (np.array([e[p] for e in r]) for p in ("total", "drive", "dissipated"))
        residual = (total - total[0]) - (drive - drive[0]) + (dissipated - dissipated[0])
        assert np.max(np.abs(residual)) < 1e-5 * np.max(np.abs(drive))
        works.append(drive[-1] - drive[0])
    assert abs(works[0] - works[1]) > 100.0 * 1e-5 * abs(works[0])  # the controller did work of its own
