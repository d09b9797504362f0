"""Scenario loading: the bundled examples validate; malformed input gives one clear line."""

import copy
import math
import tomllib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hubbeam.cli import EXAMPLES, example_text
from hubbeam.io.examples import examples_folder
from hubbeam.io.scenario import (
    ResolvedBeam,
    ScenarioError,
    apply_overrides,
    load_example,
    load_scenario,
    validate,
    value_at,
)

BASE = tomllib.loads(example_text("exp1"))
ROTOR_COPIES = tomllib.loads(example_text("rotor3"))  # one [[beams]] table with copies = 3
#: the same rotor with its three blades in three tables: a --set on each copy alone writes each out
ROTOR = apply_overrides(ROTOR_COPIES, [f"beams[{k}].azimuth={120 * k}" for k in range(3)])
SPACECRAFT = tomllib.loads(example_text("spacecraft"))

BEAM = {"formulation": "ancf", "elements": 3, "length": 1.0, "width": 0.05, "thickness": 0.004, "density": 2700.0,
        "youngs_modulus": 70.0e9}


def two_beams(**hub) -> dict:
    """A prescribed hub with two beams (blade1 at 0 deg, blade2 at 180 deg)."""
    return {
        "name": "two",
        "hub": {"motion": "prescribed", "radius": 0.3, "twist": 10.0, "drive": {"profile": "constant", "omega_s": 1.0},
                **hub},
        "beams": [dict(BEAM, name="blade1"), dict(BEAM, name="blade2", azimuth=180.0, length=0.8)],
        "analysis": {"kind": "dynamic", "t_end": 0.1, "dt": 0.01},
        "sensors": [{"name": "tip", "kind": "tip_deflection"}],
    }


def error_of(data, overrides=(), base_dir=None) -> str:
    with pytest.raises(ScenarioError) as info:
        validate(apply_overrides(data, list(overrides)), base_dir)
    msg = str(info.value)
    assert "\n" not in msg
    return msg


# ----------------------------------------------------------------------------- bundled examples
@pytest.mark.parametrize("name", EXAMPLES)
def test_bundled_examples_are_valid_and_round_trip(name):
    sc = validate(tomllib.loads(example_text(name)), base_dir=examples_folder())  # its tables: next to it
    assert validate(sc.to_dict()) == sc
    beams = sc.resolved_beams()
    assert beams and all(isinstance(b, ResolvedBeam) for b in beams)
    if name in ("cantilever", "exp1", "exp1_h4", "exp1_h1", "exp2"):
        assert sc.beam.length == 1.45 and len(beams) == 1


def test_new_examples_model_what_they_say():
    rotor = load_example("rotor3")
    assert rotor.beam_names == ("blade1", "blade2", "blade3")
    assert [round(math.degrees(b.azimuth)) for b in rotor.resolved_beams()] == [0, 120, 240]
    assert all(b.tip_body is not None and b.radius == 0.2 for b in rotor.resolved_beams())
    assert rotor.hub.drive.profile == "spin_up" and rotor.environment.gravity[1] < 0
    assert {s.beam for s in rotor.sensors if s.kind == "tip_deflection"} == {"blade1", "blade2", "blade3"}
    space = load_example("spacecraft")
    assert space.hub.motion == "free" and space.hub.inertia == 50.0 and space.environment.gravity == [0, 0, 0]
    law = space.hub.torque_law
    assert law.law == "pd" and law.reference.profile == "slew" and law.reference.angle == 0.5
    assert [round(math.degrees(b.azimuth)) for b in space.resolved_beams()] == [0, 180]
    arm = load_example("arm")
    assert len(arm.resolved_beams()) == 1 and arm.beam.name == "link"
    assert arm.resolved_beams()[0].tip_body.offset != (0.0, 0.0, 0.0)
    assert arm.hub.torque_law.law == "pd" and arm.environment.gravity[1] < 0


# ----------------------------------------------------------------------------- resolution
def test_single_beam_and_the_same_as_beams_resolve_identically():
    single = validate(BASE)
    data = copy.deepcopy(BASE)
    data["beams"] = [data.pop("beam")]
    many = validate(data)
    assert single.resolved_beams() == many.resolved_beams()
    b = single.resolved_beams()[0]
    assert (b.name, b.index, b.azimuth, b.precone, b.tip_body) == ("beam1", 0, 0.0, 0.0, None)
    assert b.radius == 0.35 and b.twist == pytest.approx(math.pi / 4)
    assert b.shear_modulus == pytest.approx(70e9 / (2 * 1.33)) and single.shear_modulus == b.shear_modulus
    a, c = 0.05, 0.0025
    assert b.torsion_constant == pytest.approx(a * c**3 / 3 * (1 - 0.63 * c / a))
    assert b.gauss_points is None and b.geometric_stiffening is False
    assert b.tip_force == (0.0, 0.0, 0.0) and b.tip_moment == (0.0, 0.0, 0.0)
    assert single.twist_rad == b.twist and many.beam == single.beam


def test_hub_radius_and_twist_are_defaults_for_every_beam():
    data = two_beams()
    data["beams"][1].update(radius=0.5, twist=-10.0, precone=5.0, shear_modulus=26e9, torsion_constant=1e-9,
                            tip_body={"mass": 0.2, "inertia": [1e-4, 2e-4, 2e-4], "offset": [0.01, 0.0, -0.02]})
    sc = validate(data)
    b1, b2 = sc.resolved_beams()
    assert (b1.name, b1.index, b1.radius, b1.twist) == ("blade1", 0, 0.3, pytest.approx(math.radians(10)))
    assert (b2.name, b2.index, b2.radius, b2.twist) == ("blade2", 1, 0.5, pytest.approx(math.radians(-10)))
    assert b2.azimuth == pytest.approx(math.pi) and b2.precone == pytest.approx(math.radians(5))
    assert b2.shear_modulus == 26e9 and b2.torsion_constant == 1e-9 and b2.length == 0.8
    assert b2.tip_body.mass == 0.2 and b2.tip_body.inertia == (1e-4, 2e-4, 2e-4) and b2.tip_body.offset == (0.01, 0.0, -0.02)
    assert b1.tip_body is None
    assert sc.beam_index(None) == 0 and sc.beam_index("blade2") == 1
    with pytest.raises(ScenarioError, match=r"^beam: no beam named 'x' \(beams: blade1, blade2\)"):
        sc.beam_index("x")
    with pytest.raises(ScenarioError, match="2 beams"):
        sc.beam  # noqa: B018


def test_default_beam_names_and_a_single_beam_may_carry_placement_keys():
    data = two_beams()
    for b in data["beams"]:
        del b["name"]
    assert validate(data).beam_names == ("beam1", "beam2")
    data = copy.deepcopy(BASE)
    data["beam"].update(name="plate", azimuth=30.0, radius=0.4, twist=20.0, precone=3.0, tip_body={"mass": 0.1})
    b = validate(data).resolved_beams()[0]
    assert (b.name, b.radius) == ("plate", 0.4)
    assert (b.azimuth, b.twist, b.precone) == pytest.approx(tuple(math.radians(v) for v in (30, 20, 3)))
    assert b.tip_body.inertia == (0.0, 0.0, 0.0) and b.tip_body.offset == (0.0, 0.0, 0.0)


def test_loads_apply_to_the_named_beam():
    data = two_beams()
    data["loads"] = {"tip_force": [1.0, 2.0, 3.0], "tip_moment": [0.0, 0.5, 0.0], "beam": "blade2"}
    b1, b2 = validate(data).resolved_beams()
    assert b1.tip_force == (0.0, 0.0, 0.0) and b2.tip_force == (1.0, 2.0, 3.0) and b2.tip_moment == (0.0, 0.5, 0.0)
    del data["loads"]["beam"]
    b1, b2 = validate(data).resolved_beams()
    assert b1.tip_force == (1.0, 2.0, 3.0) and b2.tip_force == (0.0, 0.0, 0.0)


def test_sensor_columns():
    sc = validate(ROTOR)
    assert sc.columns[:3] == ["tip1_radial", "tip1_vertical", "tip1_tangential"]
    assert "energy_drive" in sc.columns and "root_strain" in sc.columns


# ----------------------------------------------------------------------------- errors name their key
def test_overrides_use_toml_values_and_bare_words():
    sc = validate(apply_overrides(BASE, ["beam.elements=8", "beam.formulation=ancf", "hub.twist=30", 'name="x"']))
    assert sc.beam.elements == 8 and sc.hub.twist == 30.0 and sc.name == "x"


@pytest.mark.parametrize(
    "override,key",
    [
        ("beam.thickness=-1", "beam.thickness"),
        ("beam.thickness=0", "beam.thickness"),
        ("beam.length=nan", "beam.length"),
        ("beam.length=inf", "beam.length"),
        ("beam.elements=2.5", "beam.elements"),
        ("beam.poisson_ratio=0.5", "beam.poisson_ratio"),
        ("beam.poisson_ratio=-1", "beam.poisson_ratio"),
        ("beam.colour=1", "beam.colour"),
        ("hub.motion=spinning", "hub.motion"),
        ("hub.motion=prescribed", "hub.drive"),
        ("sensors=[{name='a', kind='surface_strain', x=2.0, surface='upper'}]", "sensors[0].x"),
        ("sensors=[{name='a', kind='surface_strain', x=-0.1, surface='upper'}]", "sensors[0].x"),
        ("environment.gravity=[0, 1]", "environment.gravity"),
        ("analysis.spectral_radius=1.5", "analysis.spectral_radius"),
        ("beam.shear_modulus=26e9", "beam.shear_modulus"),
        ("beam.geometric_stiffening=true", "beam.geometric_stiffening"),
        ("analysis=3", "analysis"),
        # placement and tip bodies
        ("beam.precone=80", "beam.precone"),
        ("beam.precone=-85", "beam.precone"),
        ("beam.radius=-0.1", "beam.radius"),
        ("beam.name='2nd'", "beam.name"),
        ("beam.tip_body={inertia=[0, 0, 0]}", "beam.tip_body.mass"),
        ("beam.tip_body={mass=-1}", "beam.tip_body.mass"),
        ("beam.tip_body={mass=1, inertia=[1, 0.2, 0.3]}", "beam.tip_body.inertia"),
        ("beam.tip_body={mass=1, inertia=[0, -1, 0]}", "beam.tip_body.inertia[1]"),
        ("beam.tip_body={mass=1, offset=[0, 0]}", "beam.tip_body.offset"),
        ("beam.tip_body={mass=1, colour=2}", "beam.tip_body.colour"),
        # hub torque and inertia
        ("hub.torque=[1, 2]", "hub.torque"),
        ("hub.torque=true", "hub.torque"),
        ("hub.torque=nan", "hub.torque"),
        ("hub.torque={kp=1}", "hub.torque.law"),
        ("hub.torque={law='spring'}", "hub.torque.law"),
        ("hub.torque={law='constant'}", "hub.torque.value"),
        ("hub.torque={law='constant', value=1, kp=2}", "hub.torque.kp"),
        ("hub.torque={law='table'}", "hub.torque.file"),
        ("hub.torque={law='table', file='no_such_torque.csv'}", "hub.torque.file"),
        ("hub.torque={law='pd', kp=1}", "hub.torque.reference"),
        ("hub.torque={law='pd', kp=-1, reference={profile='slew', angle=1.0, T=2.0}}", "hub.torque.kp"),
        ("hub.torque={law='pd', reference={profile='slew', angle=1.0, T=2.0}}", "hub.torque.kp"),
        ("hub.torque={law='pd', kp=1, reference={profile='slew', angle=1.0}}", "hub.torque.reference.T"),
        ("hub.torque={law='pd', kp=1, reference={profile='slew', angle=1.0, T=2.0, omega_s=1.0}}",
         "hub.torque.reference.omega_s"),
        ("hub.torque.kp=1", "--set hub.torque.kp=1"),
        # sensors
        ("sensors[0].beam='blade'", "sensors[0].beam"),
        ("sensors[2].beam='beam1'", "sensors[2].beam"),
        ("sensors[0].name='time'", "sensors[0].name"),
        ("sensors[0].name='tip_radial'", "sensors[3].name"),
        ("sensors[2].name='energy_total'", "sensors[4].name"),
        ("sensors[1].name='strain_P1'", "sensors[1].name"),
        ("sensors[0].y=0.01", "sensors[0].surface"),
        # the scenario name, steps
        ('name="a\\u0000b"', "name"),
        ('name="two\\nlines"', "name"),
        ('name=""', "name"),
        ("analysis.output_dt=0.0015", "analysis.output_dt"),
        ("analysis.t_end=1.0005", "analysis.t_end"),
        ("analysis.dt=0.003", "analysis.output_dt"),
        ("analysis.output_dt=1.797693134862316e305", "analysis.output_dt"),  # output_dt / dt overflows
        ("analysis.t_end=1.797693134862316e305", "analysis.t_end"),
        ("loads.beam='blade2'", "loads.beam"),
    ],
)
def test_bad_values_name_their_key(override, key):
    msg = error_of(BASE, [override])
    assert msg.startswith(key + ":"), msg


@pytest.mark.parametrize(
    "override,key,text",
    [
        ("beams[1].precone=85", "beams[1].precone", "Cardan"),
        ("beams[2].tip_body.inertia=[1, 0, 0]", "beams[2].tip_body.inertia", "rigid body"),
        ("beams[1].name='blade1'", "beams[1].name", "duplicate beam name 'blade1'"),
        ("beams.blade2.gauss_points=1", "beams[1].gauss_points", ">= 2"),
        ("sensors[0].beam='blade7'", "sensors[0].beam", "(beams: blade1, blade2, blade3)"),
        ("sensors[4].beam='blade1'", "sensors[4].beam", "hub"),
        ("sensors[3].x=1.2", "sensors[3].x", "beams[0].length = 1.0"),
        ("sensors[3].beam='blade2'", None, None),
        ("sensors[4].kind='applied_torque'", "sensors[4].kind", "free"),
        ("sensors[0].name='tip2'", "sensors[1].name", "duplicate sensor name 'tip2'"),
        # the same name on kinds whose columns differ (tip1 and tip1_radial, ...): the records are kept by
        # name, so the second replaced the first and the hub's speed was lost without a word
        ("sensors[4].name='tip1'", "sensors[4].name", "duplicate sensor name 'tip1' (also sensors[0])"),
        ("sensors[4].name='energy_kinetic'", "sensors[6].name", "'energy_kinetic'"),
        ("analysis.output_dt=0.015", "analysis.output_dt", "nearest valid: 0.014 or 0.016"),
        ("analysis.t_end=12.003", "analysis.t_end", "nearest valid: 12.002 or 12.004"),
        ("hub.torque=1.0", "hub.torque", "only for hub.motion = 'free'"),
        ("hub.drive.angle=1.0", "hub.drive.angle", "not a key of profile 'spin_up'"),
        ("hub.drive.profile='slew'", "hub.drive.angle", "required for profile 'slew'"),
        ("loads.beam='blade4'", "loads.beam", "no beam named 'blade4'"),
        ("beams=[]", "beams", "at least 1"),
    ],
)
def test_multi_beam_errors_name_their_key(override, key, text):
    if key is None:
        validate(apply_overrides(ROTOR, [override]))
        return
    msg = error_of(ROTOR, [override])
    assert msg.startswith(key + ":") and text in msg, msg


def test_station_checks_use_the_named_beam():
    data = two_beams()
    data["sensors"] = [{"name": "s", "kind": "surface_strain", "x": 0.9, "surface": "upper", "beam": "blade2"}]
    msg = error_of(data)
    assert msg.startswith("sensors[0].x:") and "'blade2'" in msg and "beams[1].length = 0.8" in msg
    data["sensors"][0]["beam"] = "blade1"
    validate(data)
    data["sensors"][0] = {"name": "s", "kind": "surface_strain", "x": 0.5, "y": 0.0, "z": 0.003, "beam": "blade2"}
    assert error_of(data).startswith("sensors[0].z:")
    data["sensors"][0] = {"name": "e", "kind": "energy", "beam": "blade2"}
    validate(data)


def test_beam_and_beams_together_or_neither():
    data = copy.deepcopy(ROTOR)
    data["beam"] = copy.deepcopy(BASE["beam"])
    assert error_of(data).startswith("beams: give one [beam] table or [[beams]] tables, not both")
    data = copy.deepcopy(BASE)
    del data["beam"]
    assert error_of(data).startswith("beam: required key is missing")


def test_missing_required_key():
    data = copy.deepcopy(BASE)
    del data["beam"]["length"]
    with pytest.raises(ScenarioError, match=r"^beam.length: required key is missing"):
        validate(data)
    data = copy.deepcopy(ROTOR)
    del data["beams"][2]["density"]
    with pytest.raises(ScenarioError, match=r"^beams\[2\].density: required key is missing"):
        validate(data)


def test_a_misspelt_key_is_named_with_the_key_it_is_close_to():
    """A misspelt required key is both unknown and missing: the error names what the user
    wrote and suggests the key of that table it is close to (required or not); a key close to
    none gets no suggestion."""
    data = copy.deepcopy(BASE)
    data["beam"]["thiknes"] = data["beam"].pop("thickness")
    assert error_of(data) == "beam.thiknes: unknown key (did you mean thickness?)"
    data = copy.deepcopy(ROTOR)
    data["beams"][1]["densty"] = data["beams"][1].pop("density")
    assert error_of(data) == "beams[1].densty: unknown key (did you mean density?)"
    for override, error in (("beam.poison_ratio=0.3", "beam.poison_ratio: unknown key (did you mean poisson_ratio?)"),
                            ("analysis.dtt=0.001", "analysis.dtt: unknown key (did you mean dt?)"),
                            ('sensors[0].surfce="upper"', "sensors[0].surfce: unknown key (did you mean surface?)"),
                            ("beam.zzz=1", "beam.zzz: unknown key")):
        assert error_of(apply_overrides(copy.deepcopy(BASE), [override])) == error


def test_a_free_hub_needs_its_inertia_and_torque_is_for_a_free_hub_only():
    data = copy.deepcopy(BASE)
    del data["hub"]["inertia"]
    assert error_of(data) == "hub.inertia: required for motion = 'free' (kg m^2 about its axis)"
    data = copy.deepcopy(load_example("cantilever").to_dict())
    assert error_of(data, ["hub.torque=0.0"]).startswith("hub.torque: only for hub.motion = 'free' (motion is 'fixed')")
    sc = validate(data)  # a fixed hub needs no inertia
    assert "inertia" not in sc.to_dict()["hub"] and "torque" not in sc.to_dict()["hub"]
    assert sc.hub.torque_law is None


def test_a_drive_or_torque_the_motion_does_not_take_is_reported_before_what_its_table_lacks():
    expected = "hub.drive: only with hub.motion = 'prescribed' (motion is 'free')"
    assert error_of(BASE, ["hub.drive.profile='slew'"]) == expected
    cantilever = load_example("cantilever").to_dict()
    assert error_of(cantilever, ["hub.torque.law='pd'"]).startswith("hub.torque: only for hub.motion = 'free' (motion "
                                                                    "is 'fixed')")


def test_torque_laws():
    sc = validate(BASE)
    assert sc.hub.torque_law.law == "constant" and sc.hub.torque_law.value == 0.0
    sc = validate(apply_overrides(BASE, ["hub.torque={law='constant', value=2.5}"]))
    assert sc.hub.torque_law.value == 2.5
    sc = validate(apply_overrides(BASE, ["hub.torque={law='pd', kd=3, reference={profile='spin_up', omega_s=0.5, T=10}}"]))
    law = sc.hub.torque_law
    assert (law.kp, law.kd, law.reference.omega_s, law.reference.T) == (0.0, 3.0, 0.5, 10.0)
    assert sc.to_dict()["hub"]["torque"] == {"law": "pd", "kd": 3.0,
                                             "reference": {"profile": "spin_up", "omega_s": 0.5, "T": 10.0}}
    assert validate(sc.to_dict()) == sc


# ----------------------------------------------------------------------------- drive profiles and tables
@pytest.mark.parametrize(
    "drive,error",
    [
        ({"profile": "constant", "omega_s": 1.0}, None),
        ({"profile": "constant"}, "hub.drive.omega_s: required for profile 'constant'"),
        ({"profile": "constant", "omega_s": 1.0, "T": 2.0}, "hub.drive.T: not a key of profile 'constant'"),
        ({"profile": "exponential", "omega_s": 1.0, "T": 2.0}, None),
        ({"omega_s": 1.0, "T": 2.0, "t1": 1.5}, None),
        ({"profile": "exponential", "omega_s": 1.0}, "hub.drive.T: required for profile 'exponential'"),
        ({"profile": "exponential", "omega_s": 1.0, "T": 2.0, "t1": 0.0}, "hub.drive.t1: must be > 0"),
        ({"profile": "spin_up", "omega_s": 1.0, "T": 2.0, "t1": 1.0}, "hub.drive.t1: not a key of profile 'spin_up'"),
        ({"profile": "slew", "angle": 0.5, "T": 2.0}, None),
        ({"profile": "slew", "angle": 0.5, "T": 2.0, "omega_s": 1.0}, "hub.drive.omega_s: not a key of profile 'slew'"),
        ({"profile": "slew", "T": 2.0}, "hub.drive.angle: required for profile 'slew'"),
        ({"profile": "slew", "angle": 0.5, "T": -2.0}, "hub.drive.T: must be > 0"),
        ({"profile": "table"}, "hub.drive.file: required for profile 'table'"),
        ({"profile": "table", "file": "nope.csv", "omega_s": 1.0}, "hub.drive.omega_s: not a key of profile 'table'"),
        ({"profile": "table", "file": "nope.csv"}, "hub.drive.file: no such file"),
        ({"profile": "table", "file": ""}, "hub.drive.file: must not be empty"),
        ({"profile": "warp"}, "hub.drive.profile: must be one of"),
    ],
)
def test_drive_profiles_take_only_their_own_keys(drive, error, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    data = copy.deepcopy(load_example("exp2").to_dict())
    data["hub"]["drive"] = drive
    if error is None:
        assert validate(data).hub.drive.model_dump() == {"profile": drive.get("profile", "exponential"), **drive}
    else:
        assert error_of(data).startswith(error), error_of(data)


def _scenario_with_table(tmp_path, rows="time,omega\n0,0\n1,1\n2,2\n3,2\n"):
    folder = tmp_path / "case"
    folder.mkdir()
    (folder / "omega.csv").write_text(rows)
    text = example_text("exp2").split("[hub.drive]")[0] + '[hub.drive]\nprofile = "table"\nfile = "omega.csv"\n'
    text += "\n[analysis]\nkind = 'dynamic'\nt_end = 1.0\ndt = 0.01\n"
    (folder / "s.toml").write_text(text)
    return folder


def test_a_relative_table_path_is_relative_to_the_scenario_file(tmp_path, monkeypatch):
    folder = _scenario_with_table(tmp_path)
    monkeypatch.chdir(tmp_path)
    sc = load_scenario(folder / "s.toml")
    assert sc.hub.drive.file == str(folder / "omega.csv")
    assert sc.to_dict()["hub"]["drive"] == {"profile": "table", "file": str(folder / "omega.csv")}
    assert validate(sc.to_dict()) == sc  # variants keep working from anywhere
    data = tomllib.loads((folder / "s.toml").read_text())
    with pytest.raises(ScenarioError, match=r"^hub.drive.file: no such file .*omega.csv"):
        validate(data)  # a dict: relative to the current directory
    monkeypatch.chdir(folder)
    assert validate(data).hub.drive.file == str(folder / "omega.csv")
    # a --set path is relative to the current directory
    (tmp_path / "other.csv").write_text("time,theta\n0,0\n1,0.5\n2,1\n")
    monkeypatch.chdir(tmp_path)
    sc = load_scenario(folder / "s.toml", ['hub.drive.file="other.csv"'])
    assert sc.hub.drive.file == str(tmp_path / "other.csv")


def test_a_bad_table_names_the_key(tmp_path):
    folder = _scenario_with_table(tmp_path, rows="time,torque\n0,1\n1,2\n2,3\n")
    with pytest.raises(ScenarioError, match=r"^hub.drive.file: .*omega.*theta"):
        load_scenario(folder / "s.toml")


def test_torque_table_file(tmp_path):
    (tmp_path / "torque.csv").write_text("time,torque\n0,1\n5,0\n")
    sc = validate(apply_overrides(BASE, ["hub.torque={law='table', file='torque.csv'}"]), base_dir=tmp_path)
    assert sc.hub.torque_law.file == str(tmp_path / "torque.csv")


# ----------------------------------------------------------------------------- --set
def test_set_addresses_a_beam_by_index_and_by_name():
    by_index = validate(apply_overrides(ROTOR, ["beams[1].twist=30", "beams[0].tip_body.mass=0.3"]))
    by_name = validate(apply_overrides(ROTOR, ["beams.blade2.twist=30", "beams.blade1.tip_body.mass=0.3"]))
    assert by_index == by_name
    b = by_index.resolved_beams()
    assert b[1].twist == pytest.approx(math.radians(30)) and b[0].twist == pytest.approx(math.pi / 2)
    assert b[0].tip_body.mass == 0.3 and b[2].tip_body.mass == 0.0972
    every = validate(apply_overrides(ROTOR, ["beams[*].elements=2"]))
    assert [x.elements for x in every.resolved_beams()] == [2, 2, 2]
    sc = validate(apply_overrides(SPACECRAFT, ["hub.torque.kp=10", "hub.torque.reference.angle=0.25"]))
    assert sc.hub.torque_law.kp == 10 and sc.hub.torque_law.reference.angle == 0.25
    sc = validate(apply_overrides(ROTOR, ["sensors[3].x=0.5"]))
    assert sc.sensors[3].x == 0.5
    assert value_at(ROTOR, "beams.blade3.azimuth") == 240.0 and value_at(BASE, "beams[0].length") == 1.45


def test_set_on_a_single_beam_by_index_name_or_beam():
    a = validate(apply_overrides(BASE, ["beam.elements=3"]))
    b = validate(apply_overrides(BASE, ["beams[0].elements=3"]))
    c = validate(apply_overrides(BASE, ["beams.beam1.elements=3"]))
    assert a == b == c and "beams" not in b.to_dict()
    named = copy.deepcopy(BASE)
    named["beam"]["name"] = "plate"
    assert validate(apply_overrides(named, ["beams.plate.elements=3"])).beam.elements == 3
    one = copy.deepcopy(BASE)
    one["beams"] = [one.pop("beam")]
    assert validate(apply_overrides(one, ["beam.elements=3"])).beams[0].elements == 3
    tip = validate(apply_overrides(BASE, ["beams[0].tip_body.mass=0.3"]))
    assert tip.resolved_beams()[0].tip_body.mass == 0.3


@pytest.mark.parametrize(
    "data,overrides,text",
    [
        (ROTOR, ["beam.elements=3"], "--set beam.elements=3: the scenario has 3 beams; address one as beams[i]"),
        (ROTOR, ["beams[3].twist=30"], "--set beams[3].twist=30: beam index 3 is out of range"),
        (ROTOR, ["beams.rotor.twist=30"], "--set beams.rotor.twist=30: no beam named 'rotor' (beams: blade1, blade2, blade3)"),
        (BASE, ["beams[1].twist=30"], "--set beams[1].twist=30: beam index 1 is out of range"),
        (BASE, ["beams.blade2.twist=30"], "--set beams.blade2.twist=30: no beam named 'blade2' (beams: beam1)"),
        (BASE, ["beam.elements=3", "beam.elements=4"], "--set beam.elements: given more than once"),
        (BASE, ["beam.elements=3", "beams[0].elements=4"], "--set beams[0].elements: given more than once (also as beam.elements)"),
        (ROTOR, ["beams[1].twist=3", "beams.blade2.twist=4"], "--set beams.blade2.twist: given more than once"),
        (ROTOR, ["beams[*].twist=3", "beams.blade2.twist=4"], "--set beams.blade2.twist: given more than once"),
        (SPACECRAFT, ["hub.torque={law='constant', value=1}", "hub.torque.value=2"], "--set hub.torque.value: overlaps"),
        (BASE, ["sensors[7].x=1"], "--set sensors[7].x=1: index 7 of sensors is out of range"),
        (BASE, ["beam..x=1"], "--set beam..x=1: malformed key"),
        (BASE, ["beams[x].twist=1"], "--set beams[x].twist=1: malformed key"),
        (BASE, ["beam.elements"], "--set beam.elements: expected KEY=VALUE"),
        (BASE, ["hub.torque.kp=1"], "--set hub.torque.kp=1: hub.torque is not a table"),
    ],
)
def test_bad_set_is_one_line_naming_the_set(data, overrides, text):
    with pytest.raises(ScenarioError) as info:
        validate(apply_overrides(data, overrides))
    assert str(info.value).startswith(text), str(info.value)
    assert "\n" not in str(info.value)


def test_switching_a_choice_by_set_drops_the_keys_it_does_not_take():
    sc = validate(apply_overrides(BASE, ['hub.motion="fixed"']))  # exp1's torque = 0.0 goes with the free hub
    assert "torque" not in sc.to_dict()["hub"]
    exp2 = load_example("exp2").to_dict()
    sc = validate(apply_overrides(exp2, ['hub.drive.profile="constant"', "hub.drive.omega_s=1.0"]))
    assert sc.to_dict()["hub"]["drive"] == {"profile": "constant", "omega_s": 1.0}
    sc = validate(apply_overrides(exp2, ['hub.drive.profile="slew"', "hub.drive.angle=1.0"]))
    assert sc.to_dict()["hub"]["drive"] == {"profile": "slew", "T": 100.0, "angle": 1.0}
    data = copy.deepcopy(BASE)
    data["beam"]["gauss_points"] = 4
    sc = validate(apply_overrides(data, ['beam.formulation="ffr"']))
    assert sc.beam.formulation == "ffr" and sc.beam.gauss_points is None
    sc = validate(apply_overrides(SPACECRAFT, ["hub.torque.law='constant'", "hub.torque.value=1.0"]))
    assert sc.to_dict()["hub"]["torque"] == {"law": "constant", "value": 1.0}
    # what a file says stays checked
    data = copy.deepcopy(exp2)
    data["hub"]["drive"]["profile"] = "constant"
    assert error_of(data).startswith("hub.drive.T: not a key of profile 'constant'")


def test_what_a_switch_drops_is_said():
    dropped = []
    apply_overrides(BASE, ['hub.motion="fixed"'], dropped)
    assert dropped == ["--set hub.motion=\"fixed\": hub.torque dropped (motion 'fixed' does not take it)"]
    dropped = []
    apply_overrides(SPACECRAFT, ["hub.torque.law='constant'", "hub.torque.value=1.0", "name='x'"], dropped)
    assert dropped == ["--set hub.torque.law='constant': hub.torque.kp, hub.torque.kd, hub.torque.reference dropped "
                       "(law 'constant' does not take them)"]
    dropped = []
    apply_overrides(BASE, ['hub.motion="free"', 'beam.formulation="ffr"'], dropped)  # nothing to drop
    assert dropped == []
    data = copy.deepcopy(ROTOR)
    for beam in data["beams"]:
        beam["gauss_points"] = 4
    dropped = []
    apply_overrides(data, ['beams[*].formulation="ffr"'], dropped)  # each beam named, once
    assert dropped == [f"--set beams[*].formulation=\"ffr\": beams[{k}].gauss_points dropped (formulation 'ffr' does "
                       "not take it)" for k in range(3)]


def test_analysis_steps_only_for_dynamic_analyses():
    validate(apply_overrides(BASE, ["analysis.kind='static'", "analysis.t_end=1.0005"]))
    validate(apply_overrides(BASE, ["analysis.output_dt=0.003"]))  # 3 steps
    validate(apply_overrides(BASE, ["analysis.dt=0.002", "analysis.t_end=0.3"]))  # 0.3 / 0.002 in floating point


# ----------------------------------------------------------------------------- studies
def test_formulations_switch_every_beam():
    from hubbeam.studies.variants import FORMULATIONS, single_beam, variant, with_formulation

    rotor = validate(ROTOR)
    for form, (name, stiff) in {"ancf": ("ancf", False), "ffr": ("ffr", False), "ffr+": ("ffr", True)}.items():
        sc = with_formulation(rotor, form, ["beams[*].elements=2"])
        assert [(b.formulation, b.geometric_stiffening, b.elements) for b in sc.resolved_beams()] == [(name, stiff, 2)] * 3
        assert variant(rotor, FORMULATIONS[form]).resolved_beams()[0].formulation == name
        single = with_formulation(validate(BASE), form)
        assert (single.beam.formulation, single.beam.geometric_stiffening) == (name, stiff)
    back = with_formulation(with_formulation(rotor, "ffr+"), "ancf")
    assert all(b.geometric_stiffening is False for b in back.resolved_beams())
    with pytest.raises(ScenarioError, match="formulation: unknown 'abc'"):
        with_formulation(rotor, "abc")
    assert single_beam(validate(BASE), "x").length == 1.45
    with pytest.raises(ScenarioError, match=r"^beams: the map handles a scenario with one beam; this one has 3"):
        single_beam(rotor, "the map")


def test_variant_to_a_prescribed_constant_drive_from_a_free_hub_with_torque():
    from hubbeam.studies.variants import with_formulation

    sc = with_formulation(validate(BASE), "ffr", ['hub.motion="prescribed"', 'hub.drive.profile="constant"',
                                                  "hub.drive.omega_s=1.0"])
    assert sc.hub.motion == "prescribed" and sc.hub.torque_law is None
    with pytest.raises(ScenarioError, match=r"^hub.inertia: required"):
        with_formulation(load_example("cantilever"), "ancf", ['hub.motion="free"'])


# ----------------------------------------------------------------------------- files and fuzzing
def test_file_errors(tmp_path):
    with pytest.raises(ScenarioError, match="no such file"):
        load_scenario(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[beam\nlength = 1")
    with pytest.raises(ScenarioError, match="malformed TOML"):
        load_scenario(bad)
    with pytest.raises(ScenarioError, match="directory"):
        load_scenario(tmp_path)


def _paths(data, prefix=()):
    for k, v in data.items():
        if isinstance(v, dict):
            yield from _paths(v, prefix + (k,))
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for i, x in enumerate(v):
                yield from _paths(x, prefix + (k, i))
        else:
            yield prefix + (k,)


ROOTS = {"beam", "beams", "hub", "environment", "damping", "loads", "analysis", "sensors", "name", "scenario"}
JUNK = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**6, 10**6), st.text(max_size=5), st.booleans(),
    st.lists(st.floats(allow_nan=True), max_size=4), st.none(), st.dictionaries(st.text(max_size=3), st.integers(), max_size=2),
)


def _mutate(base, path, value, drop):
    data = copy.deepcopy(base)
    node = data
    for part in path[:-1]:
        node = node[part]
    if drop:
        del node[path[-1]]
    elif value is None:
        node[str(path[-1]) + "_x"] = 1
    else:
        node[path[-1]] = value
    try:
        sc = validate(data)
    except ScenarioError as exc:
        msg = str(exc)
        assert "\n" not in msg and ": " in msg and len(msg) < 400
        root = msg.split(":")[0].split("[")[0].split(".")[0]
        assert root in ROOTS | {str(path[-1]) + "_x"}, msg
        return
    # what validates is physically meaningful
    for b in sc.resolved_beams():
        assert b.length > 0 and b.thickness > 0 and b.elements >= 1 and abs(b.precone) < math.radians(80)
    assert all(math.isfinite(g) for g in sc.environment.gravity)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(path=st.sampled_from([p for p in _paths(BASE) if p != ("name",)]), value=JUNK, drop=st.booleans())
def test_mutated_scenarios_fail_cleanly_or_validate(path, value, drop):
    _mutate(BASE, path, value, drop)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(path=st.sampled_from([p for p in _paths(SPACECRAFT) if p != ("name",)]), value=JUNK, drop=st.booleans())
def test_mutated_multi_beam_scenarios_fail_cleanly_or_validate(path, value, drop):
    _mutate(SPACECRAFT, path, value, drop)


@settings(max_examples=100, deadline=None)
@given(text=st.text(max_size=200))
def test_arbitrary_text_never_crashes_the_loader(tmp_path_factory, text):
    path = tmp_path_factory.mktemp("s") / "s.toml"
    path.write_text(text, encoding="utf-8")
    try:
        load_scenario(path)
    except ScenarioError as exc:
        assert "\n" not in str(exc).strip() or "malformed TOML" in str(exc)


@settings(max_examples=200, deadline=None)
@given(key=st.text(alphabet="beams[]0123*.xyz_tip", max_size=20), value=st.sampled_from(["1", "'a'", "[1]", "{a=1}"]))
def test_arbitrary_set_keys_fail_cleanly(key, value):
    try:
        validate(apply_overrides(ROTOR, [f"{key}={value}"]))
    except ScenarioError as exc:
        assert "\n" not in str(exc)


def test_a_beam_energy_sensor_has_the_beam_parts_only():
    data = two_beams()
    data["sensors"] = [{"name": "e", "kind": "energy", "beam": "blade2"}, {"name": "e_drive", "kind": "hub_angle"}]
    sc = validate(data)
    assert sc.columns == ["e_kinetic", "e_strain", "e_gravity", "e_total", "e_drive"]
    del data["sensors"][0]["beam"]
    assert error_of(data).startswith("sensors[1].name: 'e_drive' makes the column 'e_drive'")


def test_star_addresses_every_entry_of_a_list():
    sc = validate(apply_overrides(ROTOR, ["beams[*].tip_body.offset=[0, 0, 0]"]))
    assert all(b.tip_body.offset == (0.0, 0.0, 0.0) for b in sc.resolved_beams())
    data = copy.deepcopy(ROTOR)
    data["sensors"] = [s for s in data["sensors"] if s["kind"] == "tip_deflection"]
    sc = validate(apply_overrides(data, ["sensors[*].beam='blade3'"]))
    assert {s.beam for s in sc.sensors} == {"blade3"}
    assert error_of(BASE, ["analysis[*].dt=1"]).startswith("--set analysis[*].dt=1: analysis is not a list")


def test_control_characters_in_the_name():
    for name in ("a\x00b", "a\tb", "a\x7fb", "a\x85b", "two\nlines"):
        assert error_of(dict(BASE, name=name)).startswith("name: must not contain control")
    assert validate(dict(BASE, name="Rotor 3, été")).name == "Rotor 3, été"


# ----------------------------------------------------------------------------- copies
def test_copies_are_the_tables_written_out():
    """rotor3 with copies = 3 is its three blades written out one table each: the same resolved
    beams (names, azimuths 0, 120, 240 deg, every key), so the same model; to_dict keeps the
    copies and gives the scenario back."""
    with_copies, written = validate(ROTOR_COPIES), validate(ROTOR)
    assert len(ROTOR_COPIES["beams"]) == 1 and len(ROTOR["beams"]) == 3
    assert with_copies.resolved_beams() == written.resolved_beams()
    assert with_copies.beam_names == ("blade1", "blade2", "blade3")
    assert validate(with_copies.to_dict()) == with_copies and with_copies.to_dict()["beams"][0]["copies"] == 3


def test_copies_names_azimuths_and_places():
    data = copy.deepcopy(BASE)
    blade = data.pop("beam")
    data["beams"] = [{**blade, "copies": 4, "azimuth": 10.0}, {**blade, "name": "tail"}, blade]
    sc = validate(data)
    assert sc.beam_names == ("blade1", "blade2", "blade3", "blade4", "tail", "beam6")
    assert [round(math.degrees(b.azimuth), 9) for b in sc.resolved_beams()] == [10, 100, 190, 280, 0, 0]
    assert sc.beam_places == [(0, 0), (0, 1), (0, 2), (0, 3), (1, None), (2, None)]
    assert sc.beam_key(2) == "beams[0] (copy 3 of 4)" and sc.beam_key(4) == "beams[1]"
    data["beams"][0]["name"] = "rotor"
    assert validate(data).beam_names[:4] == ("rotor1", "rotor2", "rotor3", "rotor4")


def test_a_copy_addressed_alone_gets_a_table_of_its_own():
    """--set on one copy (by name or index) writes the table's copies out, each with its name
    and azimuth, and changes that copy only; beams[*] sets the shared table once; value_at reads a
    copy's own name and azimuth."""
    stiff = validate(apply_overrides(ROTOR_COPIES, ["beams.blade2.youngs_modulus=70.07e9"]))
    assert [b.youngs_modulus for b in stiff.resolved_beams()] == [70e9, 70.07e9, 70e9]
    assert [round(math.degrees(b.azimuth)) for b in stiff.resolved_beams()] == [0, 120, 240]
    assert len(stiff.to_dict()["beams"]) == 3 and "copies" not in stiff.to_dict()["beams"][1]
    heavy = validate(apply_overrides(ROTOR_COPIES, ["beams[2].tip_body.mass=0.2"]))
    assert [b.tip_body.mass for b in heavy.resolved_beams()] == [0.0972, 0.0972, 0.2]
    every = apply_overrides(ROTOR_COPIES, ["beams[*].elements=2"])
    assert len(every["beams"]) == 1 and [b.elements for b in validate(every).resolved_beams()] == [2, 2, 2]
    assert value_at(ROTOR_COPIES, "beams.blade3.azimuth") == 240.0 and value_at(ROTOR_COPIES, "beams[1].name") == "blade2"
    assert value_at(ROTOR_COPIES, "beams[2].length") == 1.0


@pytest.mark.parametrize("change, overrides, key, text", [
    (lambda d: d["beams"][0].update(copies=1), [], "beams[0].copies", ">= 2"),
    (lambda d: d["beams"][0].update(copies=101), [], "beams[0].copies", "<= 100"),
    (lambda d: d["beams"][0].update(copies=2.5), [], "beams[0].copies", "an integer"),
    (lambda d: d["beams"].append({**d["beams"][0], "copies": 98}), [], "beams", "101 beams in all"),
    (lambda d: d["beams"].append({**d["beams"][0], "copies": 2, "name": None}), [], "beams[1].name",
     "duplicate beam name 'blade1' (also beams[0] (copy 1 of 3))"),
    (lambda d: None, ["beams[3].elements=2"], "--set beams[3].elements=2", "out of range (the scenario has 3 beams"),
    (lambda d: None, ["beam.elements=2"], "--set beam.elements=2", "the scenario has 3 beams"),
    (lambda d: None, ["sensors[0].beam='blade4'"], "sensors[0].beam", "(beams: blade1, blade2, blade3)"),
])
def test_copies_errors_name_their_key(change, overrides, key, text):
    data = copy.deepcopy(ROTOR_COPIES)
    change(data)
    data["beams"] = [{k: v for k, v in b.items() if v is not None} for b in data["beams"]]
    msg = error_of(data, overrides)
    assert msg.startswith(key + ":") and text in msg, msg


def test_a_single_beam_table_has_no_copies():
    data = copy.deepcopy(BASE)
    data["beam"]["copies"] = 3
    assert error_of(data).startswith("beam.copies: a [beam] table is one beam; write [[beams]] with copies = N")


# ----------------------------------------------------------------------------- drive table options
def test_drive_table_options_belong_to_table_drives(tmp_path):
    log = tmp_path / "log.csv"
    log.write_text("time,omega\n0,0\n1,1\n2,2\n3,2\n4,2\n5,2\n")
    data = copy.deepcopy(ROTOR_COPIES)
    data["hub"]["drive"] = {"profile": "table", "file": str(log), "interpolation": "linear", "smoothing": 0.5}
    drive = validate(data).hub.drive
    assert (drive.interpolation, drive.smoothing) == ("linear", 0.5)
    assert error_of(data, ["hub.drive.interpolation='cubic'"]).startswith("hub.drive.interpolation: must be one of")
    assert error_of(data, ["hub.drive.smoothing=0"]).startswith("hub.drive.smoothing: must be > 0")
    dropped = []
    switched = validate(apply_overrides(data, ["hub.drive.profile='constant'", "hub.drive.omega_s=1.0"], dropped))
    assert switched.hub.drive.profile == "constant" and "hub.drive.interpolation, hub.drive.smoothing" in dropped[0]
    spin = copy.deepcopy(ROTOR_COPIES)
    spin["hub"]["drive"]["smoothing"] = 1.0
    assert error_of(spin).startswith("hub.drive.smoothing: not a key of profile 'spin_up'")
    (tmp_path / "angle.csv").write_text("time,theta\n0,0\n1,1\n2,3\n")
    data["hub"]["drive"] = {"profile": "table", "file": str(tmp_path / "angle.csv"), "interpolation": "linear"}
    assert error_of(data).startswith("hub.drive.interpolation: 'linear' is for an omega table")
