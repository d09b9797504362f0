"""Loads along the span (:mod:`hubbeam.system.span_loads`) against beam theory and against the
loads they are equivalent to."""

import numpy as np
import pytest

from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.elements.section import Section
from hubbeam.solvers.static import solve_static
from hubbeam.system.beam import AncfBeam
from hubbeam.system.multibody import MultibodySystem, single_beam_system
from hubbeam.system.span_loads import SpanLoad, span_stations

L = 1.0
SECTION = Section(0.05, 0.01, 2700.0, 7e10, 2.6e10, 1e-8)
EI = 7e10 * 0.05 * 0.01**3 / 12  # about the section's weak axis (thickness along z): 291.7 N m^2
BEAMS = {"ancf": lambda: AncfBeam(L, 8, SECTION, 5), "ffr": lambda: FfrBeam(L, 8, SECTION),
         "modal": lambda: FfrBeam(L, 8, SECTION, modes=12)}
#: relative error allowed against Euler-Bernoulli: the ANCF and nodal FFR cubics are exact for a
#: uniform load at the nodes up to the load's small geometric nonlinearity (1 mm on 1 m); 12
#: clamped-free modes of the modal beam carry the static shape of the uniform force to 2.7e-6 and
#: of the uniform moment to 9.7e-5 (measured; 6 modes: 1.6e-4 and 1.4e-3, 20 modes: 3.8e-7 and 3.2e-5)
TOLERANCE = {"ancf": 2e-6, "ffr": 2e-6, "modal": 2e-4}
#: the same for the tip slope under the uniform moment: the modal slope converges more slowly than
#: the deflection, 2.5e-3 with 12 modes (measured)
SLOPE_TOLERANCE = {"ancf": 2e-6, "ffr": 2e-6, "modal": 3e-3}


def loaded(beam, *loads, **mount):
    s = single_beam_system(beam, **mount)
    return MultibodySystem(s.beams, s.hub, s.gravity, s.damping, attachments=[f(s.beams[0]) for f in loads])


def static_tip(system):
    sol = solve_static(system, load_steps=1)
    return np.array(list(system.tip_displacement(sol.x).values())), sol


@pytest.mark.parametrize("formulation", ["ancf", "ffr", "modal"])
def test_a_uniform_load_bends_a_cantilever_by_q_L4_over_8EI(formulation):
    q = 8 * EI * 1e-3 / L**4  # 1 mm of tip deflection
    tip, _ = static_tip(loaded(BEAMS[formulation](), lambda p: SpanLoad.uniform(0, p, [0, 0, -q], [0, 0, 0])))
    assert tip[2] == pytest.approx(-q * L**4 / (8 * EI), rel=TOLERANCE[formulation])
    assert abs(tip[1]) < 1e-12


@pytest.mark.parametrize("formulation", ["ancf", "ffr", "modal"])
def test_a_uniform_moment_bends_a_cantilever_by_m_L3_over_3EI(formulation):
    """A moment m (N m/m) about +y along the span (the beam along +x): bending moment m (L - x),
    tip deflection -m L^3 / (3 EI) along z and tip slope -m L^2 / (2 EI)."""
    m = 3 * EI * 1e-3 / L**3
    system = loaded(BEAMS[formulation](), lambda p: SpanLoad.uniform(0, p, [0, 0, 0], [0, m, 0]))
    tip, sol = static_tip(system)
    assert tip[2] == pytest.approx(-m * L**3 / (3 * EI), rel=TOLERANCE[formulation])
    _, part, q, chart = next(iter(system.parts(sol.x, sol.chart)))
    tau = part.frames_at(q, chart, [L], system.root_pose(0, sol.x, sol.chart))[0][:, 0]
    assert np.arctan2(tau[2], tau[0]) == pytest.approx(-m * L**2 / (2 * EI), rel=SLOPE_TOLERANCE[formulation])


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_section_axes_on_a_twisted_preconed_mount_equal_the_global_load(formulation):
    """A force and a moment given on the root section frame [tau m n] of a mount with azimuth,
    twist and precone load the beam as the same vectors turned to global axes (R f, R m)."""
    mount = {"radius": 0.2, "twist": 0.4, "precone": 0.3, "azimuth": 0.7}
    beam = BEAMS[formulation]()
    R = single_beam_system(beam, **mount).beams[0].mount.frame(0.0)
    f_s, m_s = np.array([0.0, 0.6, -1.1]), np.array([0.05, 0.2, -0.3])
    x = [0.0, 0.3, L]
    values = np.array([[[*f_s, *m_s], [*(0.5 * f_s), *m_s], [*(0.1 * f_s), *(2 * m_s)]]])
    section, _ = static_tip(loaded(beam, lambda p: SpanLoad.table(0, p, x, [0.0], values, section_axes=True), **mount))
    turned = np.concatenate([values[..., :3] @ R.T, values[..., 3:] @ R.T], axis=-1)
    world, _ = static_tip(loaded(beam, lambda p: SpanLoad.table(0, p, x, [0.0], turned), **mount))
    assert np.linalg.norm(section) > 1e-4
    assert np.allclose(section, world, rtol=0, atol=1e-12)


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_a_constant_tip_table_is_the_constant_tip_load(formulation):
    """Statics: a tip force and moment given as a one-row time table, or as the beam's constant
    tip loads, reach the same equilibrium to Newton's tolerance."""
    force, moment = np.array([0.3, -2.0, 1.5]), np.array([0.1, 0.2, -0.4])
    beam = BEAMS[formulation]()
    table, _ = static_tip(loaded(beam, lambda p: SpanLoad.tip(0, p, [0.0], force, moment)))
    constant, _ = static_tip(single_beam_system(beam, tip_force=force, tip_moment=moment))
    assert np.linalg.norm(constant) > 1e-4
    assert np.allclose(table, constant, rtol=0, atol=1e-12)


def test_stations_integrate_a_linear_load_on_cubics_exactly():
    """The stations of a table in x: Gauss points on every piece between element boundaries and
    the table's x values; their weights sum to the loaded length, and the moment of a linear
    load about the root, int x (a + b x) dx, comes out exactly."""
    part = loaded(BEAMS["ancf"]()).beams[0]
    x, w = span_stations(part, 0.13, 0.81, [0.13, 0.5, 0.81])
    assert np.all(np.diff(x) > 0) and x[0] > 0.13 and x[-1] < 0.81
    assert w.sum() == pytest.approx(0.68, rel=1e-14)
    exact = lambda s: 2.0 * s**2 / 2 + 3.0 * s**3 / 3
    assert (w * x * (2.0 + 3.0 * x)).sum() == pytest.approx(exact(0.81) - exact(0.13), rel=1e-13)


# ---------------------------------------------------------------- runs of scenarios
def scenario(formulation: str, tmp_path, dt: float = 1e-3, t_end: float = 0.3, **loads) -> dict:
    """A free hub (inertia 0.5 kg m^2) carrying one beam on a twisted, preconed mount."""
    beam = {"formulation": formulation, "elements": 4, "length": 0.8, "width": 0.04, "thickness": 0.004,
            "density": 2700.0, "youngs_modulus": 7e10, "precone": 10.0}
    return {"name": "loads", "beam": beam, "hub": {"motion": "free", "inertia": 0.5, "radius": 0.1, "twist": 30.0},
            "environment": {"gravity": [0.0, 0.0, 0.0]}, "loads": loads,
            "analysis": {"t_end": t_end, "dt": dt, "tolerance": 1e-11},
            "sensors": [{"name": "energy", "kind": "energy"}, {"name": "tip", "kind": "tip_deflection"},
                        {"name": "omega", "kind": "hub_angular_velocity"}]}


def run(data: dict, base_dir) -> dict:
    from hubbeam import api
    from hubbeam.io.results import to_dataset
    from hubbeam.io.scenario import validate

    s = validate(data, base_dir)
    trajectory, failure = api.run(s)
    assert failure is None, failure
    ds = to_dataset(trajectory, s)
    return {name: ds[name].values for name in ds.data_vars}


SPAN_TABLE = """time,x,fx,fy,fz,mx,my,mz
0.0,0.0,0,0,0,0,0,0
0.0,0.8,0,0,0,0,0,0
0.1,0.0,0.5,-1.0,2.0,0.0,0.1,0.0
0.1,0.8,0.0,-3.0,0.5,0.2,0.0,-0.1
0.2,0.0,0,0,-1.0,0,0,0
0.2,0.8,0,1.0,0,0,0,0.05
"""


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_a_span_load_in_time_does_the_work_the_energy_sensor_counts(formulation, tmp_path):
    """A distributed force and moment varying in time and along the span, on the section axes of
    a beam on a free hub (so that it also turns the hub): total energy - its start = the drive's
    work (the loads' power integrated) - the dissipated energy, to the integrator's error."""
    (tmp_path / "span.csv").write_text(SPAN_TABLE)
    r = run(scenario(formulation, tmp_path, span=[{"file": "span.csv", "axes": "section"}]), tmp_path)
    work = r["energy_drive"]
    balance = r["energy_total"] - r["energy_total"][0] - work + r["energy_dissipated"]
    assert np.max(np.abs(work)) > 1e-3  # the load does work
    assert np.max(np.abs(r["omega"])) > 1e-2  # and turns the hub
    assert np.max(np.abs(balance)) < 1e-3 * np.max(np.abs(work))


def test_constant_tip_loads_do_the_work_the_energy_sensor_counts(tmp_path):
    """The constant ``[loads]`` tip force and moment on a beam on a free hub (they bend the beam
    and turn the hub from t = 0): total energy - its start = the drive's work - the dissipated
    energy. A modal FFR beam (3 modes) integrated without numerical dissipation (spectral radius
    1), so that the balance closes to the integrator's error (measured 9.8e-8, 3.0e-8, 1.0e-8 J
    at dt = 2, 1, 0.5 ms against 0.10 J of work); before the tip loads' power entered the
    drive's work it was off by the whole work. (ANCF beams need numerical dissipation against
    the high modes that the sudden load excites: there the test below compares the work with
    that of the same load from a table.)"""
    data = scenario("ffr", tmp_path, t_end=0.3, tip_force=[0.3, -2.0, 1.5], tip_moment=[0.1, 0.2, -0.4])
    data["beam"]["modes"] = 3
    data["analysis"]["spectral_radius"] = 1.0
    r = run(data, tmp_path)
    work = r["energy_drive"]
    balance = r["energy_total"] - r["energy_total"][0] - work + r["energy_dissipated"]
    assert np.max(np.abs(work)) > 0.05  # the loads do work
    assert np.max(np.abs(r["omega"])) > 0.1  # and turn the hub
    assert np.max(np.abs(balance)) < 1e-5 * np.max(np.abs(work))


@pytest.mark.parametrize("formulation", ["ancf", "ffr"])
def test_a_constant_tip_table_runs_as_the_constant_tip_load(formulation, tmp_path):
    """A tip force from a one-row table and the same constant ``[loads]`` tip force: the same run,
    and the same work of the loads in the energy sensor's drive part, to round-off (the same generalized force, no load stiffness in either's Newton matrix). With a
    tip moment too, the same run to Newton's tolerance: the constant ANCF tip moment puts its load
    stiffness into the Newton matrix and the table's does not, so Newton's iterates differ."""
    (tmp_path / "f.csv").write_text("time,fx,fy,fz\n0.0,0.3,-2.0,1.5\n")
    (tmp_path / "m.csv").write_text("time,mx,my,mz\n0.0,0.1,0.2,-0.4\n")
    # round-off: 50 ulp of the tip's position (0.9 m from the axis; measured 2.2e-16 m); Newton's
    # tolerance: 1e-11 of the length per step
    cases = {"force": ({"tip_force_file": "f.csv"}, {"tip_force": [0.3, -2.0, 1.5]}, 1e-14),
             "both": ({"tip_force_file": "f.csv", "tip_moment_file": "m.csv"},
                      {"tip_force": [0.3, -2.0, 1.5], "tip_moment": [0.1, 0.2, -0.4]}, 1e-9)}
    for table_loads, constant_loads, tolerance in cases.values():
        tables = run(scenario(formulation, tmp_path, t_end=0.1, **table_loads), tmp_path)
        constant = run(scenario(formulation, tmp_path, t_end=0.1, **constant_loads), tmp_path)
        for name in ("tip_radial", "tip_vertical", "tip_tangential", "omega"):
            size = np.max(np.abs(constant[name]))
            assert size > 1e-5
            assert np.max(np.abs(tables[name] - constant[name])) < tolerance, (name, tolerance)
        # the drive's work: the table's counted by the span loads' power, the constant load's by
        # its beam's (ancf_drive_power, ffr_drive_power), each from its own generalized force
        work = np.max(np.abs(constant["energy_drive"]))
        assert work > 1e-3
        assert np.max(np.abs(tables["energy_drive"] - constant["energy_drive"])) < 1e-6 * work
