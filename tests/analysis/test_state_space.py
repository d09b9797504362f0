"""The linear state space against the modal analyses, the system's own residual, the static
solution and the nonlinear simulation it linearises."""

import numpy as np
import pytest
from scipy.linalg import expm

from hubbeam import api
from hubbeam.analysis.state_space import input_columns, rest_matrices
from hubbeam.errors import ScenarioError
from hubbeam.io.scenario import load_example
from hubbeam.solvers.static import solve_static
from hubbeam.studies.campbell import campbell
from hubbeam.studies.variants import FORMULATIONS, variant
from hubbeam.system.laws import TorqueLaw
from tests.conftest import central_difference

SMALL = ["beam.elements=4", "analysis.load_steps=4"]
UNDAMPED = SMALL + ["damping.linear=0", "damping.quadratic=0"]
FIXED = ['hub.motion="fixed"']
SPIN = ['hub.motion="prescribed"', 'hub.drive.profile="constant"', "hub.drive.omega_s=2.0"]
FFR = ['beam.formulation="ffr"']


def exp1(*overrides):
    """exp1 (a 1.45 m plate at 45 deg twist sagging 0.2 m under gravity) with overrides."""
    return load_example("exp1", [o for group in overrides for o in group])


def elastic(model):
    f, zeta = model.modal_summary()
    return f, zeta


# ------------------------------------------------------------------ (a) frequencies
@pytest.mark.parametrize("hub", [FIXED, []], ids=["held", "free"])
@pytest.mark.parametrize("form", [[], FFR], ids=["ancf", "ffr"])
def test_undamped_frequencies_are_the_modal_analysis(hub, form):
    sc = exp1(UNDAMPED, hub, form)
    f, zeta = elastic(api.linearize(sc))
    modes = api.modes(sc).modes.frequencies_hz
    assert modes.size == 6
    np.testing.assert_allclose(f[: modes.size], modes, rtol=1e-6)
    assert np.max(np.abs(zeta)) < 1e-6  # no damping: purely imaginary eigenvalues


@pytest.mark.parametrize("form", ["ancf", "ffr+"])
def test_undamped_frequencies_about_steady_rotation_are_campbells(form):
    sc = variant(exp1(UNDAMPED, SPIN), FORMULATIONS[form])
    model = api.linearize(sc)
    assert "steadily rotating" in model.about and model.equilibrium.omega == 2.0
    f, zeta = elastic(model)
    ref = campbell(exp1(SMALL, SPIN), [2.0], formulations=(form,))["frequency_hz"].values[0, 0]
    np.testing.assert_allclose(f[: ref.size], ref, rtol=1e-6)
    assert np.max(np.abs(zeta)) < 1e-6
    # gyroscopic terms split the modes away from the non-rotating frequencies
    rest = elastic(api.linearize(variant(exp1(UNDAMPED, FIXED), FORMULATIONS[form])))[0]
    assert np.max(np.abs(f[:6] / rest[:6] - 1)) > 1e-3


def test_free_hub_rigid_rotation_is_a_double_zero_eigenvalue_left_out():
    """About the bent equilibrium the discrete model gives the rigid rotation a small frequency
    (modal.py's docstring): the pair nearest zero is that mode, the one ``modes`` leaves out."""
    sc = exp1(UNDAMPED)
    model = api.linearize(sc)
    s = np.sort(np.abs(np.linalg.eigvals(model.A))) / (2 * np.pi)
    assert model.rigid_modes == 1
    rigid = np.abs(api.modes(sc).modes.rigid_frequencies_hz)
    # (a near-zero eigenvalue of a stiff matrix: known to round-off relative to the largest, 1e-2 here)
    np.testing.assert_allclose(s[:2], [rigid[0], rigid[0]], rtol=2e-2)
    assert s[1] < 1e-2 * s[2]
    with_pd = api.linearize(exp1(UNDAMPED, [('hub.torque = {law = "pd", kp = 20.0, kd = 0.0, '
                                             'reference = {profile = "slew", angle = 0.5, T = 20.0}}')]))
    assert with_pd.rigid_modes == 0  # the servo mode is a mode like the others
    f_pd = elastic(with_pd)[0]
    assert f_pd.size == elastic(model)[0].size + 1


def test_low_frequency_torque_to_strain_is_the_quasi_static_inertial_bending():
    """Free hub, straight beam (no gravity, no drag): well below the first mode (1 Hz) a hub
    torque u accelerates hub and beam rigidly, theta'' = u / J (J = J_hub + rho A int r^2), and
    the beam carries its inertial load rho A r theta'' across it: bending moment at x
    M(x) = rho A theta'' int_x^L (R + s)(s - x) ds, of which the 45 deg twist puts cos 45 on the
    weak axis, strain M cos45 (h/2) / EI_y at the upper surface (Euler-Bernoulli, by hand)."""
    from scipy.integrate import quad

    sc = exp1(["beam.elements=8", "environment.gravity=[0.0, 0.0, 0.0]", "damping.linear=0",
               "damping.quadratic=0"])
    model = api.linearize(sc)
    w = 2 * np.pi * 0.03  # rad/s: quasi-static to 1e-3 (first mode 1.01 Hz)
    G = model.C @ np.linalg.solve(1j * w * np.eye(model.A.shape[0]) - model.A, model.B) + model.D
    R, L, b, h, rho, E, J_hub, x = 0.35, 1.45, 0.05, 0.0025, 2700.0, 70e9, 9.557, 0.3
    rho_a = rho * b * h
    J = J_hub + quad(lambda s: rho_a * (R + s) ** 2, 0, L)[0]
    moment = quad(lambda s: rho_a * (R + s) * (s - x), x, L)[0] / J  # per N m of hub torque
    strain = moment * np.sqrt(0.5) * (h / 2) / (E * b * h**3 / 12)
    np.testing.assert_allclose((1j * w * G[model.outputs.index("hub_omega"), 0]).real, 1 / J, rtol=2e-3)
    np.testing.assert_allclose(abs(G[model.outputs.index("strain_P1"), 0]), strain, rtol=5e-3)


# ------------------------------------------------------------------ damping and inputs
@pytest.mark.parametrize("form", [[], FFR], ids=["ancf", "ffr"])
def test_damping_matrix_is_the_velocity_derivative_of_the_residual_at_rest(form):
    sc = exp1(SMALL, form, ["damping.quadratic=0"])
    system = api.build_system(sc)
    eq = solve_static(system, load_steps=4)
    _, C, _, _ = rest_matrices(system, eq.x, eq.multipliers, eq.chart)
    lam = system.lambda_from_held(eq.multipliers, False)
    zx = system.layout.z_of_x
    zero = np.zeros(system.nx)

    def forces(v):
        return system.equations(eq.x, v, zero, lam, eq.chart, 0.0, 0.0, 0.0, 1.0, 1.0, want_matrix=False)[0][zx]

    C_fd = central_difference(forces, zero, 1e-3)  # the drag is linear in v here
    assert np.max(np.abs(C)) > 0
    np.testing.assert_allclose(C, C_fd, atol=1e-9 * np.max(np.abs(C)))
    # the quadratic drag (c2 |v| v) has no slope at rest: the same matrix
    C2 = rest_matrices(api.build_system(exp1(SMALL, form)), eq.x, eq.multipliers, eq.chart)[1]
    np.testing.assert_allclose(C2, C, atol=1e-12 * np.max(np.abs(C)))


def test_hub_torque_input_is_how_a_torque_law_enters():
    sc = exp1(SMALL)
    system = api.build_system(sc)
    eq = solve_static(system, load_steps=4)
    lam = system.lambda_from_held(eq.multipliers, False)
    zero = np.zeros(system.nx)
    B, names, units = input_columns(system, ["hub_torque"], eq.x, zero, zero, lam, eq.chart)
    zx = system.layout.z_of_x

    def forces(s):
        return s.equations(eq.x, zero, zero, lam, eq.chart, 0.0, 0.0, 0.0, 1.0, 1.0, want_matrix=False)[0][zx]

    pushed = system.with_hub(torque=TorqueLaw.constant(1.0))
    np.testing.assert_allclose(B[:, 0], forces(system) - forces(pushed), atol=1e-12)
    assert names == ["hub_torque"] and units == ["N m"]


NO_GRAVITY = ["environment.gravity=[0.0, 0.0, 0.0]"]


@pytest.mark.parametrize("form", [[], FFR + NO_GRAVITY], ids=["ancf", "ffr"])
def test_tip_force_input_is_the_tip_jacobian_transposed(form):
    """A dead force f at the tip centroid does the virtual work f . d r_tip: its generalized
    force is (d r_tip / dx)^T f (the tip position differenced, independent of the load code).
    FFR takes the tip force's moment about the body frame with the undeformed lever arm
    (FfrPart._tip_load), exact at a straight equilibrium: there without gravity."""
    system = api.build_system(exp1(SMALL, FIXED, form))
    eq = solve_static(system, load_steps=4)
    zero = np.zeros(system.nx)
    B, names, _ = input_columns(system, ["tip_force:" + system.beams[0].name], eq.x, zero, zero, eq.multipliers,
                                eq.chart)
    J = central_difference(lambda x: system.tip_position(x), eq.x, 1e-6)
    np.testing.assert_allclose(B, J.T, atol=1e-7)
    assert names == [f"tip_force_{a}_{system.beams[0].name}" for a in "xyz"]


SLEW = ['hub.motion="prescribed"', 'hub.drive.profile="slew"', "hub.drive.angle=0.5", "hub.drive.T=10.0"]


@pytest.mark.parametrize("drive, spin", [(SLEW, None), (SPIN, 2.0)], ids=["rest", "rotating"])
def test_static_gain_is_the_derivative_of_the_static_solution(drive, spin):
    """Held hub (at rest; turning at 2 rad/s with drag), tip force input: the DC gain
    D - C A^-1 B of tip deflection, drive torque and strain equals the change of the static
    (steady) solution with the tip force, a central difference of two solve_static solutions."""
    sensors = [('sensors=[{name = "tip", kind = "tip_deflection"}, {name = "drive", kind = "hub_torque"}, '
                '{name = "P1", kind = "surface_strain", x = 0.3, surface = "upper"}]')]
    sc = exp1(SMALL, drive, sensors)
    model = api.linearize(sc)
    assert model.inputs == ["tip_force_x_beam1", "tip_force_y_beam1", "tip_force_z_beam1"]
    gain = model.D - model.C @ np.linalg.solve(model.A, model.B)
    df = 0.01

    def static(fz):
        system = api.build_system(exp1(SMALL, drive, [f"loads.tip_force=[0.0, 0.0, {fz}]"]))
        sol = solve_static(system, load_steps=4, spin=spin)
        tip = system.tip_displacement(sol.x)
        strain = system.surface_strain(sol.x, sol.chart, 0.3, 0.0, 0.0025 / 2)
        return np.array([tip["radial"], tip["vertical"], tip["tangential"], system.drive_torque(sol.multipliers),
                         strain])

    fd = (static(df) - static(-df)) / (2 * df)
    rows = [model.outputs.index(n) for n in ("tip_radial", "tip_vertical", "tip_tangential", "drive", "P1")]
    np.testing.assert_allclose(gain[rows, 2], fd, rtol=1e-4, atol=1e-6 * np.max(np.abs(fd[:4])))
    np.testing.assert_allclose(gain[rows[4], 2], fd[4], rtol=1e-4)
    assert abs(fd[3]) > 0.1  # a force along z on a beam along x needs a holding torque
    # the drive reaction follows a force input at once: D != 0 there only
    assert abs(model.D[model.outputs.index("drive"), 2]) > 0
    others = [i for i, n in enumerate(model.outputs) if n != "drive"]
    assert np.all(model.D[others] == 0)


# ------------------------------------------------------------------ (c) outputs
def test_outputs_are_the_sensors_differenced_along_any_state_direction():
    """C times a random state direction against a central difference of the sensors (through
    the public sensor path, api.run's own measure) at two steps; D = 0 for a torque input."""
    from hubbeam.sensors import measure

    sc = exp1(SMALL)
    model = api.linearize(sc)
    assert model.outputs == ["strain_P1", "strain_P2", "hub_omega", "tip_radial", "tip_vertical",
                             "tip_tangential", "energy_kinetic", "energy_strain", "energy_gravity", "energy_total"]
    assert model.left_out == ["energy_dissipated", "energy_drive"]
    assert np.all(model.D == 0)
    system = api.build_system(sc)
    eq = model.equilibrium
    n = model.basis.shape[1]
    rng = np.random.default_rng(1)
    direction = rng.standard_normal(2 * n)
    direction /= np.linalg.norm(direction)

    class State:
        def __init__(self, s):
            self.t, self.x, self.v = 0.0, eq.x + model.basis @ s[:n], model.basis @ s[n:]
            self.lam, self.chart = eq.multipliers, eq.chart

    def read(s):
        out = []
        for sensor in sc.sensors:
            value = measure(sensor, system, State(s), {"dissipated": 0.0, "drive": 0.0})
            out += [value[k] for k in ("kinetic", "strain", "gravity", "total")] if sensor.kind == "energy" else \
                list(value.values()) if isinstance(value, dict) else [value]
        return np.array(out)

    np.testing.assert_allclose(read(np.zeros(2 * n)), model.output_offsets, rtol=1e-12, atol=1e-15)
    predicted = model.C @ direction
    errors = []
    for h in (1e-3, 5e-4):
        fd = (read(h * direction) - read(-h * direction)) / (2 * h)
        errors.append(np.abs(fd - predicted) / np.maximum(np.abs(predicted), 1e-12))
    assert np.all((errors[1] < 1e-5) | (errors[1] < 0.3 * errors[0]))  # converges as h^2


# ------------------------------------------------------------------ (b) the nonlinear response
def test_step_response_is_the_nonlinear_response_to_first_order():
    """A hub-torque step of amplitude u on the free hub (exp1: bent 0.2 m by gravity, drag on),
    the nonlinear simulation (api.run's integrator, from the equilibrium the model is linearised
    about) against u times the linear step response (matrix exponential): the difference is the
    nonlinear remainder, so relative to the response it grows like u (absolute: like u^2).

    The run starts from ``linearize``'s own equilibrium: api.run(start = "equilibrium") moves a
    free hub's state to the axis chart, a different discretisation of the twist (its
    frequencies differ by 0.4 % at 4 elements, 1e-5 at 16), which is not exactly at rest there."""
    from hubbeam.simulation import simulate
    from hubbeam.solvers import generalized_alpha as ga
    from hubbeam.solvers import newton_control as nc

    sensors = [('sensors=[{name = "P1", kind = "surface_strain", x = 0.3, surface = "upper"}, '
                '{name = "tip", kind = "tip_deflection"}, {name = "omega", kind = "hub_angular_velocity"}]')]
    sc = exp1(SMALL, sensors)
    model = api.linearize(sc)
    eq = model.equilibrium
    n, m = model.A.shape[0], model.B.shape[1]
    errors = []
    for u in (2.0, 4.0):  # N m: the hub reaches 0.06 / 0.12 rad/s in 0.3 s
        system = api.build_system(exp1(SMALL, sensors, [f"hub.torque={u}"]))
        traj = simulate(system, sc.sensors, 0.3, 2e-4, 0.9, 0.01, newton=nc.NewtonOptions(tolerance=1e-12),
                        state=ga.init(system, eq.x, eq.chart))
        nonlinear = np.column_stack([traj.records["P1"]] + [[r[k] for r in traj.records["tip"]]
                                                           for k in ("radial", "vertical", "tangential")]
                                    + [traj.records["omega"]])
        linear = []
        for t in traj.times:
            E = expm(np.block([[model.A, model.B], [np.zeros((m, n + m))]]) * t)
            linear.append(model.C @ E[:n, n:] @ [u] + model.D @ [u])
        linear = np.array(linear)
        scale = np.max(np.abs(linear), axis=0)
        assert np.all(scale > 0)
        errors.append(np.max(np.abs(nonlinear - model.output_offsets - linear), axis=0) / scale)
    assert np.all(errors[0] < 0.03), errors[0]  # the linear model is close (0.02 % to 1.8 %) ...
    np.testing.assert_allclose(errors[1] / errors[0], 2.0, rtol=0.1)  # ... and the rest is second order


# ------------------------------------------------------------------ interface
def test_to_control_and_dataset_keep_names_and_matrices():
    control = pytest.importorskip("control")
    model = api.linearize(exp1(SMALL))
    ss = model.to_control()
    assert isinstance(ss, control.StateSpace)
    np.testing.assert_array_equal(ss.A, model.A)
    np.testing.assert_array_equal(ss.C, model.C)
    assert ss.input_labels == model.inputs and ss.output_labels == model.outputs
    ds = model.to_dataset()
    assert ds["A"].dims == ("state_rate", "state") and ds["C"].dims == ("output", "state")
    assert list(ds["output"].values) == model.outputs


@pytest.mark.parametrize("inputs, message", [
    (["hub_torque"], "needs a free hub"), (["tip_force:nope"], "no beam of that name"),
    (["torque"], "unknown input"), (["tip_force", "tip_force:beam1"], "given twice")])
def test_bad_inputs_are_scenario_errors(inputs, message):
    with pytest.raises(ScenarioError, match=message):
        api.linearize(exp1(SMALL, FIXED), inputs)


def test_the_bode_example_of_the_docs_runs(tmp_path, monkeypatch, capsys):
    pytest.importorskip("control")
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "docs" / "state_space.md").read_text()
    code = text.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "state_space.md", "exec"), {})  # noqa: S102 (the documented example itself)
    assert "peak gain 0.000128 /(N m) at 1.015 Hz" in capsys.readouterr().out
    assert (tmp_path / "bode_exp1.png").stat().st_size > 0
