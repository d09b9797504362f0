"""The outputs' derivatives by parts (one central difference moves a coordinate of every beam
at once) against the definition: a central difference of every sensor, measured through the
public sensor path (hubbeam.sensors.measure), along each state direction of the model."""

import numpy as np
import pytest

from hubbeam import api
from hubbeam.analysis.output_jacobian import Scope, linear_outputs
from hubbeam.io.scenario import load_example
from hubbeam.sensors import measure

#: every sensor kind that has a linear output, on two beams (the second's own sensors too)
SENSORS = ('sensors=[{name = "theta", kind = "hub_angle"}, {name = "omega", kind = "hub_angular_velocity"}, '
           '{name = "tip_a", kind = "tip_deflection", beam = "panel_a"}, '
           '{name = "tip_b", kind = "tip_deflection", beam = "panel_b"}, '
           '{name = "strain_b", kind = "surface_strain", beam = "panel_b", x = 0.1, surface = "upper"}, '
           '{name = "momentum", kind = "angular_momentum"}, {name = "energy", kind = "energy"}, '
           '{name = "energy_b", kind = "energy", beam = "panel_b"}{torque}]')
SMALL = ["beams[*].elements=2", "analysis.load_steps=2"]
#: the panels sag under gravity along the hub axis (a bent equilibrium, strain energy, a chart
#: that is not the axis chart), panel b is FFR
BENT = SMALL + ["environment.gravity=[0.0, -9.81, 0.0]", 'beams[1].formulation="ffr"',
                "beams[1].twist=90.0", "beams[0].twist=90.0"]
SPIN = ['hub.motion="prescribed"', 'hub.drive={profile = "constant", omega_s = 1.5}']


def reference_C(model, scenario, h=1e-6):
    """d(sensors)/d(state) by central differences of hubbeam.sensors.measure along each state
    (x = x0 + N y, v = the equilibrium's velocity at x (rigid rotation) + N y'), multipliers fixed."""
    system = api.build_system(scenario)
    eq = model.equilibrium
    n = model.basis.shape[1]
    omega = eq.omega

    class State:
        def __init__(self, s):
            self.t = 0.0
            self.x = eq.x + model.basis @ s[:n]
            base = system.steady_rotation_rates(self.x, eq.chart, omega)[0] if omega else np.zeros(system.nx)
            self.v = base + model.basis @ s[n:]
            self.lam, self.chart = eq.multipliers, eq.chart

    def read(s):
        out = []
        for sensor in scenario.sensors:
            value = measure(sensor, system, State(s), {"dissipated": 0.0, "drive": 0.0})
            if isinstance(value, dict):
                out += [value[k] for k in value if k not in ("dissipated", "drive")]
            else:
                out.append(value)
        return np.array(out)

    columns = []
    for j in range(2 * n):
        e = np.zeros(2 * n)
        e[j] = h
        columns.append((read(e) - read(-e)) / (2 * h))
    return np.array(columns).T


@pytest.mark.parametrize("overrides, torque", [
    pytest.param(BENT, ', {name = "torque", kind = "applied_torque"}', marks=pytest.mark.slow),  # a long run: CI's slow run
    (SMALL + SPIN, ', {name = "drive", kind = "hub_torque"}')],
                         ids=["free-bent-ancf-ffr", "rotating"])
def test_grouped_differences_equal_every_sensor_differenced_along_every_state(overrides, torque):
    sc = load_example("spacecraft", overrides + [SENSORS.replace("{torque}", torque)])
    model = api.linearize(sc)
    reference = reference_C(model, sc)
    n = model.basis.shape[1]
    drive = model.outputs.index("drive") if "drive" in model.outputs else None
    for i, name in enumerate(model.outputs):
        if i == drive:
            continue  # reads the multipliers: they move with the state (lam_y), which the reference holds fixed
        scale = max(np.max(np.abs(reference[i])), 1e-300)
        if name.startswith("energy"):  # the total is stationary at the equilibrium: its parts' round-off
            scale = max(np.max(np.abs(reference[j])) for j, other in enumerate(model.outputs)
                        if other.startswith(name.split("_")[0] + "_") and other.count("_") == name.count("_"))
        np.testing.assert_allclose(model.C[i], reference[i], atol=2e-6 * scale, err_msg=name)
    # the momentum about rest is linear in the velocities: its row is exact there
    if model.equilibrium.omega == 0:
        system = api.build_system(sc)
        exact = [system.angular_momentum(model.equilibrium.x, model.basis[:, j], model.equilibrium.chart)
                 for j in range(n)]
        np.testing.assert_allclose(model.C[model.outputs.index("momentum"), n:], exact, atol=1e-7 * np.max(np.abs(exact)))
        np.testing.assert_array_equal(model.C[model.outputs.index("momentum"), :n], 0.0)


def test_each_sensor_is_split_by_what_it_reads():
    sc = load_example("spacecraft", SMALL)
    system = api.build_system(sc)
    x, F = system.initial_state(0.0)
    outputs, left_out = linear_outputs(sc.sensors, system, x, F)
    scopes = {o.names[0]: o.scope for o in outputs}
    assert scopes["theta"] is scopes["torque"] is Scope.HUB
    assert scopes["tip_a_radial"] is scopes["root_strain_a"] is Scope.BEAM
    assert scopes["energy_kinetic"] is Scope.SUM
    assert scopes["momentum"] is Scope.WHOLE  # every kind's momenta: differenced coordinate by coordinate
    assert left_out == ["energy_dissipated", "energy_drive"]


def test_progress_reaches_its_total():
    seen = []
    api.linearize(load_example("spacecraft", SMALL), progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1][0] == seen[-1][1] and all(a <= b for (a, _), (b, _) in zip(seen, seen[1:]))
