"""Controller inputs on the frames' poses (hubbeam.system.pose_inputs, issue 28): a beam's tip
deflection (ANCF, FFR nodal and modal; on a free base, behind a joint, on a parent beam's tip),
a moving base's position and rotation vector, and their rates. Each against the sensor that
measures the same column (hubbeam.sensors: the compiled tip displacements of the records and
the rotation vector of the base's pose, code this module does not share), its derivatives
against central differences, the rates against the sensors along a run, and a static gain on
the base's rotation against the base's own attitude law."""

import numpy as np
import pytest

from hubbeam import api
from hubbeam.analysis.output_jacobian import Probe
from hubbeam.io.scenario import load_example, validate
from hubbeam.sensors import measure
from hubbeam.system.controller_inputs import input_values
from hubbeam.system.controllers import Controllers
from hubbeam.system.frames import evaluate_chains
from hubbeam.system.rotations import rotation_vector_matrix
from tests.system.test_controller_inputs import residual_jacobians, save

PARTS = ("radial", "vertical", "tangential")


def configured(name: str) -> dict:
    """The scenarios of the checks (plain data, no sensors or controllers): the bundled
    spacecraft3d (free bus) with panel_a on a flap joint, as ANCF beside a modal FFR panel_b
    ("ancf-joint"), or as nodal FFR beside an ANCF panel_b ("ffr-joint"); the two-link arm
    (fixed hub, the forearm on the upper arm's tip behind the elbow joint) with an FFR upper arm
    and an ANCF forearm ("arm-ffr-parent"), or the reverse, the forearm modal FFR ("arm-ancf-parent")."""
    if name.startswith("arm"):
        d = load_example("arm2").to_dict()
        upper, fore = d["beams"]
        if name == "arm-ffr-parent":
            upper.update(formulation="ffr", elements=2)
            fore.update(elements=2)
        else:
            upper.update(elements=2)
            fore.update(formulation="ffr", elements=3, modes=3)
        d["analysis"].update(start="rest")
    else:
        d = load_example("spacecraft3d").to_dict()
        a, b = d["beams"]
        a.update(elements=2, joint={"kind": "revolute", "axis": "flap", "stiffness": 400.0, "damping": 0.0})
        if name == "ancf-joint":
            b.update(formulation="ffr", elements=3, modes=3, geometric_stiffening=True)
        else:
            a.update(formulation="ffr")
            b.update(elements=2)
    d["sensors"] = []
    return d


def with_inputs(d: dict, tmp_path, gain_seed=None):
    """``d`` with a tip deflection sensor on every beam (and the base's position and rotation on
    a moving base), and a static-gain controller reading every column and its rate: D random
    (``gain_seed``) or zero, onto the base's x torque and every single-axis joint's motor."""
    beams = [b["name"] for b in d["beams"]]
    d["sensors"] = [{"name": f"tip_{b}", "kind": "tip_deflection", "beam": b} for b in beams]
    inputs = [f"tip_{b}_{p}" for b in beams for p in PARTS]
    outputs = [f"joint_torque_{b['name']}" for b in d["beams"] if "joint" in b]
    if d.get("base", {}).get("motion", "fixed") != "fixed":
        d["sensors"] += [{"name": "rot", "kind": "base_rotation"}, {"name": "pos", "kind": "base_position"}]
        inputs += [f"{s}_{c}" for s in ("rot", "pos") for c in "xyz"]
        outputs = ["base_torque_x"] + outputs
    inputs = [c + rate for c in inputs for rate in ("", "_rate")]
    D = np.zeros((len(outputs), len(inputs)))
    if gain_seed is not None:
        D = 50.0 * np.random.default_rng(gain_seed).normal(size=D.shape)
    d["controllers"] = [{"name": "k", "file": save(tmp_path, f"k{gain_seed}.npz", np.zeros((0, 0)),
                                                   np.zeros((0, len(inputs))), np.zeros((len(outputs), 0)), D),
                         "inputs": inputs, "outputs": outputs}]
    return validate(d, base_dir=tmp_path), inputs


def turned_state(system, seed=7):
    """A state far from rest: every coordinate and rate nudged at random, a moving base turned by
    2.3 rad about a skew axis (its Euler parameters not of unit norm: the inputs read e / |e|)."""
    x, F = system.initial_state()
    rng = np.random.default_rng(seed)
    x = x + 2e-2 * rng.normal(size=x.size)
    v = 0.3 * rng.normal(size=x.size)
    if system.layout.base_moves:
        e = system.layout.base_x.start + 3
        x[e:e + 4] = 1.3 * np.array([np.cos(1.15), *(np.sin(1.15) * np.array([0.6, -0.48, 0.64]))])
    return x, v, F


def compiled_inputs(system, F):
    """u(x, v) -> (u, cols, dx, dv, count): the controller's inputs as the step evaluates them."""
    model = system.model()
    pack = next(p for p in model.parts if isinstance(p, Controllers))
    ctx = model.context

    def inputs(x, v):
        evaluate_chains(ctx.chains, x, F, 2)
        return input_values(pack, ctx, F, x, v)
    return inputs


def sensor_value(scenario, system, name, x, v, F):
    columns = {c: s for s in scenario.sensors for c in s.columns}
    s = columns[name]
    value = measure(s, system, Probe(0.3, x, v, np.zeros(system.layout.n_lambda), F), {})
    return value[name[len(s.name) + 1:]]


@pytest.mark.parametrize("config", [
    "ancf-joint", "ffr-joint",
    # the arms' models are tested nowhere else in the default run (compiling each is most of a minute)
    pytest.param("arm-ffr-parent", marks=pytest.mark.slow), pytest.param("arm-ancf-parent", marks=pytest.mark.slow),
])
def test_each_input_is_its_sensor_and_its_derivatives_are_exact(tmp_path, config):
    # value: the sensor at the state; rate: a central difference of the sensor along x + s v (the
    # state's motion, h = 1e-6: error ~1e-11); du/dx and du/dv: central differences of the compiled
    # input over every coordinate (h = 1e-6). Measured errors: values 1e-16 relative, rates
    # < 1e-9, derivatives < 1e-9 of their largest entry.
    scenario, inputs = with_inputs(configured(config), tmp_path)
    system = api.build_system(scenario)
    x, v, F = turned_state(system)
    compute = compiled_inputs(system, F)
    u, cols, dx, dv, count = compute(x, v)
    h = 1e-6
    n = x.size
    fd_x, fd_v = np.zeros((len(inputs), n)), np.zeros((len(inputs), n))
    for j in range(n):
        d = np.zeros(n)
        d[j] = h
        fd_x[:, j] = (compute(x + d, v)[0] - compute(x - d, v)[0]) / (2 * h)
        fd_v[:, j] = (compute(x, v + d)[0] - compute(x, v - d)[0]) / (2 * h)
    for i, name in enumerate(inputs):
        if name.endswith("_rate"):
            column = name[:-len("_rate")]
            expected = (sensor_value(scenario, system, column, x + h * v, v, F)
                        - sensor_value(scenario, system, column, x - h * v, v, F)) / (2 * h)
            scale = max(abs(expected), 1e-2)
            assert abs(u[i] - expected) < 1e-7 * scale, (name, u[i], expected)
        else:
            expected = sensor_value(scenario, system, name, x, v, F)
            assert abs(u[i] - expected) < 1e-12 * max(abs(expected), 1e-2), (name, u[i], expected)
        ours_x, ours_v = np.zeros(n), np.zeros(n)
        np.add.at(ours_x, cols[i, :count[i]], dx[i, :count[i]])
        np.add.at(ours_v, cols[i, :count[i]], dv[i, :count[i]])
        scale = max(np.max(np.abs(fd_x[i])), np.max(np.abs(fd_v[i])), 1e-2)  # round-off of the differences: ~1e-10
        assert np.max(np.abs(ours_x - fd_x[i])) < 1e-7 * scale, name
        assert np.max(np.abs(ours_v - fd_v[i])) < 1e-7 * scale, name
    turned = [i for i, name in enumerate(inputs) if name.endswith("_rate") and np.any(fd_x[i])]
    assert len(turned) >= len(inputs) // 3  # the rates' du/dx are checked where they are not zero


@pytest.mark.parametrize("config", ["ffr-joint", pytest.param("arm-ancf-parent", marks=pytest.mark.slow)])
def test_the_newton_matrix_entries_of_tip_and_base_inputs_are_the_residuals_derivatives(tmp_path, config):
    # a random static gain from every new input to the base's torque and the joints' motors: the
    # controller's entries of the Newton matrix (the system's less the same system without the
    # gain) against central differences of the residual along x and v; a band too narrow for the
    # columns an input reads (the forearm's tip, the parent's coordinates) would drop entries
    d = configured(config)
    system = api.build_system(with_inputs(d, tmp_path, gain_seed=3)[0])
    plain = api.build_system(with_inputs(configured(config), tmp_path)[0])
    x, v, F = turned_state(system)
    x = system.initial_state()[0] + 0.05 * (x - system.initial_state()[0])  # a state the charts hold
    Jx, Jv, Kx, Cv = residual_jacobians(system, x, v, F)
    Jx0, Jv0, Kx0, Cv0 = residual_jacobians(plain, x, v, F)
    fd_x, fd_v = Jx - Jx0, Jv - Jv0
    assert np.max(np.abs(fd_x)) > 1.0 and np.max(np.abs(fd_v)) > 1.0
    assert np.max(np.abs((Kx - Kx0) - fd_x)) < 1e-6 * np.max(np.abs(fd_x))
    assert np.max(np.abs((Cv - Cv0) - fd_v)) < 1e-6 * np.max(np.abs(fd_v))


def test_the_base_rotations_rate_is_the_inverse_of_its_tangent_map_on_omega(tmp_path):
    # the rate of the rotation vector against omega = T(phi) phi' (T = I + (1 - cos a) / a^2 [phi]x
    # + (a - sin a) / a^3 [phi]x^2, the global angular velocity of R = exp([phi]x)): at a large
    # angle (2.3 rad), near zero (1e-5 rad) and on each side of where G's derivatives change from
    # their series to their closed forms (|b| / a = 0.29, 0.31), omega the base frame's (Jw v);
    # and there the derivatives of the angle and its rate against central differences (h = 1e-7)
    scenario, inputs = with_inputs(configured("ancf-joint"), tmp_path)
    system = api.build_system(scenario)
    x, v, F = turned_state(system)
    compute = compiled_inputs(system, F)
    rows = [inputs.index(f"rot_{c}_rate") for c in "xyz"]
    angle_rows = [inputs.index(f"rot_{c}") for c in "xyz"]
    e = system.layout.base_x.start + 3
    for half in (1.15, 5e-6, np.arctan(0.29), np.arctan(0.31)):
        x[e:e + 4] = 0.8 * np.array([np.cos(half), *(np.sin(half) * np.array([0.6, -0.48, 0.64]))])
        u, cols, dx, dv, count = compute(x, v)
        for i in rows + angle_rows:
            assert list(cols[i, :count[i]]) == list(range(e, e + 4))
            for k in range(4):
                d = np.zeros(x.size)
                d[e + k] = 1e-7
                assert abs(dx[i, k] - (compute(x + d, v)[0][i] - compute(x - d, v)[0][i]) / 2e-7) < 1e-7
                assert abs(dv[i, k] - (compute(x, v + d)[0][i] - compute(x, v - d)[0][i]) / 2e-7) < 1e-7
        phi, rate = u[angle_rows], u[rows]
        a = np.linalg.norm(phi)
        assert abs(a - 2 * half) < 1e-12
        K = np.array([[0.0, -phi[2], phi[1]], [phi[2], 0.0, -phi[0]], [-phi[1], phi[0], 0.0]])
        T = np.eye(3) + (1 - np.cos(a)) / a ** 2 * K + (a - np.sin(a)) / a ** 3 * K @ K
        _, R, _, omega = system.base_motion(x, v)
        assert np.allclose(R, rotation_vector_matrix(phi), atol=1e-12)
        assert np.max(np.abs(T @ rate - omega)) < 1e-9 * np.max(np.abs(omega))


def states_of_a_run(scenario):
    """(system, times, records, states): a run of ``scenario`` with every output time's (x, v,
    charts) kept beside the sensors' records (a recorder of :func:`hubbeam.simulation.simulate`)."""
    from hubbeam.simulation import initial_state, simulate
    from hubbeam.solvers.newton_control import NewtonOptions

    system = api.build_system(scenario)
    a = scenario.analysis
    traj = simulate(system, scenario.sensors, a.t_end, a.dt, a.spectral_radius, scenario.output_dt,
                    newton=NewtonOptions(tolerance=a.tolerance), state=initial_state(system, a.load_steps, a.start),
                    recorder=lambda system, s: (s.x.copy(), s.v.copy(), np.array(s.chart, copy=True)))
    return system, np.asarray(traj.times), traj.records, traj.snapshots


@pytest.mark.slow  # a validation run that compiles its own models (minutes on a cold cache)
@pytest.mark.parametrize("config", ["ancf-joint", "arm-ffr-parent"])
def test_the_rates_are_the_recorded_sensors_time_derivatives_along_a_run(tmp_path, config):
    # A run driven smoothly (the spacecraft's base slewing 0.5 rad in 1 s under its attitude law,
    # the panels following; the arm from its gravity equilibrium, both motors slewing), the
    # controller's gain zero: at every output time (each step, dt = 1 ms) the compiled rate inputs
    # at the step's state against a central difference in time of the recorded sensor (the
    # records' compiled tip displacements, the base pose's rotation vector). Measured: at most
    # 2.9e-4 (spacecraft) and 1.1e-3 (arm) of each rate's range, 3 to 4 times less at 0.5 ms
    # (the difference's error h^2 u(3) / 6). A kick by initial rates instead (a released joint
    # spring, an initial base spin) leaves the index-3 integrator's velocities ringing for tens of
    # steps: there even the base's velocity, v itself, is 16 % off its position's central difference.
    d = configured(config)
    d["analysis"].update(t_end=0.3 if config == "ancf-joint" else 0.2, dt=1e-3, output_dt=1e-3)
    if config == "ancf-joint":
        d["base"]["torque"]["slew"].update(angle=0.5, T=1.0)
    else:
        d["analysis"].update(start="equilibrium")
    scenario, inputs = with_inputs(d, tmp_path)
    system, times, records, states = states_of_a_run(scenario)
    h = times[1] - times[0]
    columns = {c: s for s in scenario.sensors for c in s.columns}
    checked = 0
    for i, name in enumerate(inputs):
        if not name.endswith("_rate"):
            continue
        column = name[:-len("_rate")]
        s = columns[column]
        series = np.array([r[column[len(s.name) + 1:]] for r in records[s.name]])
        rate = np.array([compiled_inputs(system, F)(x, v)[0][i] for x, v, F in states[1:-1]])
        difference = (series[2:] - series[:-2]) / (2 * h)
        spread = np.max(np.abs(rate))
        if spread < 1e-12:  # a modal panel's vertical deflection (no such mode among its 3): zero
            assert np.max(np.abs(difference)) < 1e-12, name
            continue
        assert np.max(np.abs(rate - difference)) < 5e-3 * spread, name
        checked += 1
    assert checked >= 6


# slow: a long validation run (CI runs it: python -m pytest -q -m slow)
@pytest.mark.slow
def test_a_static_gain_on_the_base_rotation_and_rate_is_the_bases_attitude_law(tmp_path):
    # The base's own PD attitude law toward the identity (no target, no slew) is tau = -kp phi -
    # kd w in base axes, phi the rotation vector of the base's rotation R (R phi = phi: the same
    # in global and base axes) and w the angular velocity in base axes; the controller
    # D = [-diag(kp), -diag(kd)] from base_rotation_x|y|z and base_angular_velocity_x|y|z to
    # base_torque_x|y|z is the same torque at the same instant and Newton iteration. Started
    # turned by 0.98 rad and spinning, 1 s (the law turns it 0.2 rad back): the two runs' rotation
    # vectors agree to the Newton tolerance (measured: 1.3e-13 rad)
    kp, kd = [25.0, 138.0, 145.0], [100.0, 550.0, 580.0]
    d = configured("ancf-joint")
    d["base"]["torque"] = {"law": "pd", "kp": kp, "kd": kd}
    d["base"]["initial"] = {"rotation": [0.5, -0.6, 0.6], "angular_velocity": [0.1, 0.2, -0.1]}
    d["analysis"].update(t_end=1.0, dt=5e-3, output_dt=0.05)
    d["sensors"] = [{"name": "rot", "kind": "base_rotation"}, {"name": "w", "kind": "base_angular_velocity"}]
    law, failure = api.run(validate(d, base_dir=tmp_path))
    assert failure is None
    D = np.hstack([-np.diag(kp), -np.diag(kd)])
    d["base"].pop("torque")
    d["controllers"] = [{"file": save(tmp_path, "att.npz", np.zeros((0, 0)), np.zeros((0, 6)), np.zeros((3, 0)), D),
                         "inputs": [f"{s}_{c}" for s in ("rot", "w") for c in "xyz"],
                         "outputs": ["base_torque_x", "base_torque_y", "base_torque_z"]}]
    loop, failure = api.run(validate(d, base_dir=tmp_path))
    assert failure is None
    a, b = (np.array([[r[c] for c in "xyz"] for r in run.records["rot"]]) for run in (law, loop))
    assert np.max(np.abs(a - a[0])) > 0.15  # the law turned the base (0.2 rad about y)
    assert np.max(np.abs(a - b)) < 1e-8 * np.max(np.abs(a))
