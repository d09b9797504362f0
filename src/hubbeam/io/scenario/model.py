"""The scenario as a whole: its tables together, the checks across tables, one-line error messages
and validation."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

from pydantic import (
    BaseModel,
    Field,
)
import difflib
import unicodedata
from typing import get_args

from pydantic import ValidationError

from hubbeam.errors import ScenarioError
from hubbeam.io.scenario.analysis import Analysis, Damping, Environment, Loads
from hubbeam.io.scenario.base import Base
from hubbeam.io.scenario.beams import (MAX_BEAMS, Beam, ResolvedBeam, ResolvedTipBody, beam_names_of, copy_azimuth,
                                       span_sections)
from hubbeam.io.scenario.common import STEP_TOLERANCE, StrictTable
from hubbeam.io.scenario.controllers import Controller, check_controllers
from hubbeam.io.scenario.hub import Hub, HubTorque
from hubbeam.io.scenario.joints import resolved_joint
from hubbeam.io.scenario.sensors import BEAM_SENSORS, JOINT_SENSORS, Sensor


class Scenario(StrictTable):
    name: Annotated[str, Field(min_length=1, max_length=200)] = "scenario"
    single_beam: Beam | None = Field(default=None, alias="beam")  # a [beam] table
    beams: Annotated[list[Beam], Field(min_length=1, max_length=100)] | None = None  # [[beams]] tables
    hub: Hub = Hub()
    base: Base = Base()
    environment: Environment = Environment()
    damping: Damping = Damping()
    loads: Loads = Loads()
    analysis: Analysis = Analysis()
    sensors: list[Sensor] = []
    controllers: list[Controller] = []

    # ----------------------------------------------------------- beams
    @property
    def beam_tables(self) -> list[Beam]:
        """The beams as written ([beam] or [[beams]]), in order."""
        if self.single_beam is not None:
            return [self.single_beam]
        return list(self.beams or [])

    @property
    def beam_names(self) -> tuple[str, ...]:
        """Every beam's name, a table's copies one by one (:func:`~hubbeam.io.scenario.beams.beam_names_of`)."""
        return tuple(name for _, _, name in beam_names_of(self.beam_tables))

    @property
    def beam_places(self) -> list[tuple[int, int | None]]:
        """For every beam (copies one by one) its table's index and its copy's index (None: a
        table without copies)."""
        return [(i, k) for i, k, _ in beam_names_of(self.beam_tables)]

    def beam_key(self, k: int) -> str:
        """Where beam k (0-based, copies one by one) is written: ``beam``, ``beams[i]`` or, for
        a copy, ``beams[i]`` with the copy named (``beams[1] (copy 2 of 3)``)."""
        i, copy = self.beam_places[k]
        if self.single_beam is not None:
            return "beam"
        table = self.beam_tables[i]
        return f"beams[{i}]" + ("" if copy is None else f" (copy {copy + 1} of {table.copies})")

    @property
    def beam(self) -> Beam:
        """The one beam of a single-beam scenario (its table as written; the placement keys
        may be None: :meth:`resolved_beams` has them resolved)."""
        tables, names = self.beam_tables, self.beam_names
        if len(names) != 1:
            raise ScenarioError(
                f"beams: this scenario has {len(names)} beams ({', '.join(names)}) where one is expected")
        return tables[0]

    def beam_index(self, name: str | None = None) -> int:
        """0-based index of the beam called ``name``; None means the first beam (0)."""
        if name is None:
            return 0
        names = self.beam_names
        if name not in names:
            raise ScenarioError(f"beam: no beam named {name!r} (beams: {', '.join(names)})")
        return names.index(name)

    def resolved_beams(self) -> list[ResolvedBeam]:
        """Every beam with its defaults filled in (SI units, radians)."""
        loaded = self.beam_index(self.loads.beam)
        out = []
        tables = self.beam_tables
        for i, ((t, copy), name) in enumerate(zip(self.beam_places, self.beam_names)):
            b = tables[t]
            if b.shear_modulus is not None:
                g = b.shear_modulus
            else:
                nu = 0.33 if b.poisson_ratio is None else b.poisson_ratio
                g = b.youngs_modulus / (2.0 * (1.0 + nu))
            from hubbeam.elements.section import Section, saint_venant_torsion_constant

            if b.torsion_constant is not None:
                jt = b.torsion_constant
            else:
                jt = saint_venant_torsion_constant(b.width, b.thickness)
            tb = b.tip_body
            tip = None if tb is None else ResolvedTipBody(
                float(tb.mass), tuple(float(v) for v in tb.inertia), tuple(float(v) for v in tb.offset))
            zero = (0.0, 0.0, 0.0)
            out.append(ResolvedBeam(
                name=name, index=i, formulation=b.formulation, elements=b.elements, length=b.length, width=b.width,
                thickness=b.thickness, density=b.density, youngs_modulus=b.youngs_modulus, shear_modulus=g,
                torsion_constant=jt, gauss_points=b.gauss_points, geometric_stiffening=bool(b.geometric_stiffening),
                azimuth=math.radians(copy_azimuth(b.azimuth, copy, b.copies)) if b.parent is None else 0.0,
                radius=float(self.hub.radius if b.radius is None else b.radius) if b.parent is None else 0.0,
                twist=math.radians(self.hub.twist if b.twist is None else b.twist),
                precone=math.radians(b.precone), tip_body=tip,
                tip_force=tuple(float(v) for v in self.loads.tip_force) if i == loaded else zero,
                tip_moment=tuple(float(v) for v in self.loads.tip_moment) if i == loaded else zero,
                modes=b.modes,
                sections=span_sections(b, Section(b.width, b.thickness, b.density, b.youngs_modulus, g, jt)),
                structural_damping=float(b.damping.stiffness_proportional) if b.damping is not None else 0.0,
                parent=None if b.parent is None else self.beam_names.index(b.parent), joint=resolved_joint(b.joint),
            ))
        return out

    # ----------------------------------------------------------- derived values (single beam)
    @property
    def shear_modulus(self) -> float:
        """Shear modulus (Pa) of the single beam."""
        self.beam  # noqa: B018 - one beam expected
        return self.resolved_beams()[0].shear_modulus

    @property
    def twist_rad(self) -> float:
        """Twist (rad) of the single beam."""
        self.beam  # noqa: B018 - one beam expected
        return self.resolved_beams()[0].twist

    @property
    def output_dt(self) -> float:
        return self.analysis.output_dt if self.analysis.output_dt is not None else self.analysis.dt

    @property
    def columns(self) -> list[str]:
        """The result columns of the sensors, in order (without ``time``)."""
        return [c for s in self.sensors for c in s.columns]

    def to_dict(self) -> dict:
        """The scenario as plain data ([beam] or [[beams]] as written; absolute table paths);
        ``validate(scenario.to_dict())`` gives the scenario back."""
        return self.model_dump(by_alias=True, exclude_none=True)


def _nearest_multiples(value: float, step: float) -> str:
    n = value / step
    lo, hi = max(math.floor(n), 1), max(math.ceil(n), 1)
    vals = sorted({float(f"{k * step:.12g}") for k in (lo, hi)})
    return " or ".join(f"{v:.12g}" for v in vals)


def _is_multiple(value: float, step: float) -> bool:
    n = round(value / step)
    return n >= 1 and abs(n * step - value) <= STEP_TOLERANCE * value


def _cross_checks(s: Scenario) -> None:
    """Checks that involve several keys; each raises ScenarioError naming one key."""
    if any(unicodedata.category(c) == "Cc" for c in s.name):
        raise ScenarioError("name: must not contain control characters (NUL, tab, line breaks, ...)")
    if s.single_beam is not None and s.beams is not None:
        raise ScenarioError("beams: give one [beam] table or [[beams]] tables, not both")
    if s.single_beam is None and s.beams is None and s.base.motion != "free":
        raise ScenarioError("beam: required key is missing (a [beam] table, or [[beams]] tables for several beams; "
                            "only a free base may carry no beam)")
    tables, names, places = s.beam_tables, s.beam_names, s.beam_places
    where = "beam" if s.single_beam is not None else "beams"
    if s.single_beam is not None and s.single_beam.copies is not None:
        raise ScenarioError("beam.copies: a [beam] table is one beam; write [[beams]] with copies = N for N copies")
    if len(names) > MAX_BEAMS:
        raise ScenarioError(f"beams: {len(names)} beams in all (copies counted); at most {MAX_BEAMS}")
    seen: dict[str, int] = {}
    for k, name in enumerate(names):
        i, copy = places[k]
        if name in seen:
            how = "" if tables[i].name is not None or copy is not None else " by default"
            also = s.beam_key(seen[name])
            raise ScenarioError(f"beams[{i}].name: duplicate beam name {name!r}{how} (also {also})")
        seen[name] = k
    listed = ", ".join(names)

    hub = s.hub
    if hub.motion == "prescribed" and hub.drive is None:
        raise ScenarioError("hub.drive: required when hub.motion = 'prescribed'")
    if s.base.motion == "free":
        if hub.motion == "fixed" and "inertia" in hub.model_fields_set:
            raise ScenarioError("hub.inertia: a hub fixed to a free base is part of the base: include its inertia in "
                                "base.inertia (and its mass in base.mass)")
        if hub.motion != "fixed" and "inertia" not in hub.model_fields_set:
            raise ScenarioError(f"hub.inertia: required for a {hub.motion} hub on a free base (kg m^2 about the hub's "
                                "axis; its mass and its inertia across the axis belong to base.mass and base.inertia)")
    elif hub.motion == "free" and "inertia" not in hub.model_fields_set:
        raise ScenarioError("hub.inertia: required for motion = 'free' (kg m^2 about its axis)")

    _check_chains(s, where)

    if s.loads.beam is not None and s.loads.beam not in names:
        raise ScenarioError(f"loads.beam: no beam named {s.loads.beam!r} (beams: {listed})")
    for i, span in enumerate(s.loads.span):
        if span.beam is not None and span.beam not in names:
            raise ScenarioError(f"loads.span[{i}].beam: no beam named {span.beam!r} (beams: {listed})")

    a = s.analysis
    if a.kind == "dynamic":
        if a.dt > a.t_end:
            raise ScenarioError(f"analysis.dt: larger than analysis.t_end ({a.dt} > {a.t_end})")
        if a.output_dt is not None and a.output_dt < a.dt:
            raise ScenarioError(f"analysis.output_dt: smaller than analysis.dt ({a.output_dt} < {a.dt})")
        for key in ("output_dt", "t_end"):
            value = getattr(a, key)
            if value is not None and not math.isfinite(value / a.dt):  # too many steps to count in a float
                raise ScenarioError(f"analysis.{key}: {value:.12g} s is more steps of analysis.dt = {a.dt:.12g} s "
                                    "than a number can count")
        if a.output_dt is not None and not _is_multiple(a.output_dt, a.dt):
            raise ScenarioError(f"analysis.output_dt: {a.output_dt:.12g} s is not a whole multiple of analysis.dt = "
                                f"{a.dt:.12g} s (nearest valid: {_nearest_multiples(a.output_dt, a.dt)})")
        if not _is_multiple(a.t_end, a.dt):
            raise ScenarioError(f"analysis.t_end: {a.t_end:.12g} s is not a whole number of steps of analysis.dt = "
                                f"{a.dt:.12g} s (nearest valid: {_nearest_multiples(a.t_end, a.dt)})")

    if a.kind == "dynamic":
        _check_loop(s)

    columns: dict[str, int] = {}
    sensor_names: dict[str, int] = {}
    for i, sen in enumerate(s.sensors):
        if sen.name in sensor_names:  # whatever the kinds: the results hold one sensor per name
            raise ScenarioError(f"sensors[{i}].name: duplicate sensor name {sen.name!r} (also "
                                f"sensors[{sensor_names[sen.name]}])")
        sensor_names[sen.name] = i
        if sen.kind == "base_torque" and s.base.torque is None:
            raise ScenarioError(f"sensors[{i}].kind: base_torque needs an attitude law ([base.torque] of a free base)")
        if sen.kind == "applied_torque" and hub.motion != "free":
            raise ScenarioError(f"sensors[{i}].kind: applied_torque needs hub.motion = 'free' "
                                f"(motion is {hub.motion!r}; a prescribed hub's torque is hub_torque)")
        for col in sen.columns:
            if col == "time":
                raise ScenarioError(f"sensors[{i}].name: {sen.name!r} makes the column 'time', the time coordinate")
            if col in columns:
                j = columns[col]
                raise ScenarioError(f"sensors[{i}].name: {sen.name!r} makes the column {col!r}, which sensors[{j}] "
                                    f"({s.sensors[j].name!r}, {s.sensors[j].kind}) makes too")
            columns[col] = i
        if sen.beam is not None and sen.beam not in names:
            raise ScenarioError(f"sensors[{i}].beam: no beam named {sen.beam!r} (beams: {listed})")
        if not tables:
            if sen.kind in BEAM_SENSORS:
                raise ScenarioError(f"sensors[{i}].kind: a {sen.kind} sensor needs a beam (the scenario has none)")
            continue
        k = s.beam_index(sen.beam)
        b = tables[places[k][0]]
        of = f"{where}[{places[k][0]}]" if where == "beams" else "beam"
        label = f"beam {names[k]!r}" if len(names) > 1 else "the beam"
        if sen.x is not None and sen.x > b.length:
            raise ScenarioError(f"sensors[{i}].x: station {sen.x} m is beyond the length of {label} "
                                f"({of}.length = {b.length} m)")
        width, thickness = b.size_at(sen.x) if sen.x is not None else (b.width, b.thickness)
        if sen.y is not None and abs(sen.y) > width / 2 * (1 + 1e-12):
            raise ScenarioError(f"sensors[{i}].y: {sen.y} m is outside the section of {label} "
                                f"(|y| <= width/2 = {width / 2})")
        if sen.z is not None and abs(sen.z) > thickness / 2 * (1 + 1e-12):
            raise ScenarioError(
                f"sensors[{i}].z: {sen.z} m is outside the section of {label} (|z| <= thickness/2 = {thickness / 2})")


#: a PD law's loop may be at most this much faster than the time step: sqrt(kp / J) dt and kd dt / J
MAX_LOOP_RATE = 100.0
#: gains beyond this are left to :func:`hubbeam.limits.check_magnitudes` (the range of every number)
MAGNITUDE_LIMIT = 1e150


def rigid_inertia(s: Scenario) -> float:
    """The hub's inertia and the beams' and tip bodies' rigid inertia about j0 (kg m^2): the
    beams straight at their root radius, of their root section (an estimate of the inertia a
    torque law turns; the hub's own is a lower bound of it)."""
    total = s.hub.inertia
    for b in s.beam_tables:
        r = s.hub.radius if b.radius is None else b.radius
        outer = r + b.length  # products, not **: a radius near 1e103 gives inf (checked later), not OverflowError
        total += b.density * b.width * b.thickness * (outer * outer * outer - r * r * r) / 3.0
        if b.tip_body is not None:
            total += b.tip_body.mass * outer * outer
    return total


def _check_loop(s: Scenario) -> None:
    """A PD torque law whose loop the time step cannot resolve is refused: with J the rigid
    inertia about the axis, sqrt(kp / J) dt or kd dt / J above :data:`MAX_LOOP_RATE`. Each
    step the loop then amplifies the round-off of theta (and omega) by about (sqrt(kp / J)
    dt)^2 (kd dt / J), so that the torque is the gain times round-off: kp = 1e20 on a 50 kg m^2
    hub at dt = 5 ms recorded -346.9 N m of noise and broke the energy balance; the recorded
    torque of that model is within 1e-4 of a slower loop's at sqrt(kp / J) dt = 217, off by 1 %
    at 2170 and noise beyond. (Such a loop is also far faster than any actuator: 20 kHz at
    dt = 1 ms.)"""
    law = s.hub.torque_law
    if law is None or law.law != "pd":
        return
    J, dt = rigid_inertia(s), s.analysis.dt
    if not (math.isfinite(J) and J > 0) or max(law.kp, law.kd) >= MAGNITUDE_LIMIT:
        return  # beyond the range of every number: check_magnitudes names the key and that range
    for key, rate, what in (("kp", math.sqrt(law.kp / J) * dt, "sqrt(kp / J) dt"), ("kd", law.kd * dt / J, "kd dt / J")):
        if rate > MAX_LOOP_RATE:
            raise ScenarioError(f"hub.torque.{key}: {getattr(law, key):g} makes the loop far faster than the time step: "
                                f"{what} = {rate:.3g} with J = {J:.4g} kg m^2 (hub and beams about the axis) and "
                                f"analysis.dt = {dt:g} s, above {MAX_LOOP_RATE:g}; its torque would be the gain times "
                                "the round-off of the hub's motion. Use a smaller gain or a smaller analysis.dt")


#: most beams in one chain (a root on the hub and its descendants through parents)
MAX_CHAIN = 100


def _check_chains(s: Scenario, where: str) -> None:
    """Parents: an existing beam, not the beam itself, listed before its child, no loop, at most
    :data:`MAX_CHAIN` beams in one chain; sensors of joints on jointed beams. Beams are counted
    copy by copy (``copies = N``: each copy has the table's parent and joint)."""
    tables, names, places = s.beam_tables, s.beam_names, s.beam_places
    index = {name: i for i, name in enumerate(names)}

    def table_of(i):
        return tables[places[i][0]]

    for i, name in enumerate(names):
        t = places[i][0]
        b = tables[t]
        if b.parent is None:
            continue
        key = f"{where}[{t}].parent" if where == "beams" else "beam.parent"
        if b.parent == name:
            raise ScenarioError(f"{key}: a beam cannot be its own parent ({b.parent!r})")
        if b.parent not in index:
            raise ScenarioError(f"{key}: no beam named {b.parent!r} (beams: {', '.join(names)})")
        seen, j = {i}, index[b.parent]
        depth = 2
        while table_of(j).parent is not None and table_of(j).parent in index:
            if j in seen:
                raise ScenarioError(f"{key}: the parents of {name!r} make a loop "
                                    f"({' -> '.join(names[m] for m in sorted(seen))})")
            seen.add(j)
            j = index[table_of(j).parent]
            depth += 1
            if depth > MAX_CHAIN:
                raise ScenarioError(f"{key}: more than {MAX_CHAIN} beams in one chain")
        if index[b.parent] > i:
            raise ScenarioError(f"{key}: the parent {b.parent!r} must be listed before its child {name!r}")
    for i, sen in enumerate(s.sensors):
        if sen.kind not in JOINT_SENSORS:
            continue
        if not tables or (sen.beam is not None and sen.beam not in names):
            continue  # the sensors' own checks say so
        k = s.beam_index(sen.beam)
        joint = table_of(k).joint
        if joint is None or joint.kind != "revolute":
            raise ScenarioError(f"sensors[{i}].beam: a {sen.kind} sensor needs a beam on a revolute joint "
                                f"(beam {names[k]!r} is clamped)")
        sen.set_axes(joint.axis_names)


_TYPE_PARTS = {"function-after", "function-before", "function-wrap", "list[float]", "float", "int", "str", "bool",
               "constrained-float", "constrained-int", "constrained-str", "list[constrained-float]"}


def _format_loc(loc: tuple) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        elif part in _TYPE_PARTS or str(part).startswith(("<", "function-")):
            continue
        else:
            out += ("." if out else "") + str(part)
    return out


def _explain(err: dict) -> str:
    kind = err["type"]
    ctx = err.get("ctx", {})
    value = err.get("input")
    if kind == "extra_forbidden":
        return "unknown key"
    if kind == "missing":
        return "required key is missing"
    if kind in ("finite_number",):
        return f"must be a finite number (got {value})"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        op = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<", "less_than_equal": "<="}[kind]
        bound = next(iter(ctx.values()))
        return f"must be {op} {bound} (got {value})"
    if kind == "literal_error":
        expected = str(ctx.get("expected"))
        if len(expected) > 200:  # a long list of choices (the sensor kinds) reads without its quotes
            expected = expected.replace("'", "")
        shown = repr(value)
        return f"must be one of {expected} (got {shown if len(shown) <= 30 else shown[:27] + '...'})"
    if kind in ("too_short", "too_long"):
        n = ctx.get("min_length") if kind == "too_short" else ctx.get("max_length")
        bound = "at least" if kind == "too_short" else "at most"
        if ctx.get("min_length") == 3 or ctx.get("max_length") == 3:
            bound = "exactly"  # a 3-vector
        return f"must have {bound} {n} entr{'y' if n == 1 else 'ies'} (got {ctx.get('actual_length')})"
    if kind == "string_too_short":
        return "must not be empty"
    if kind == "string_too_long":
        return f"must be at most {ctx.get('max_length')} characters long"
    if kind == "string_pattern_mismatch":
        return f"must be an identifier: letters, digits and _, not starting with a digit (got {value!r})"
    if kind in ("float_type", "int_type", "string_type", "bool_type", "list_type", "model_type", "dict_type",
                "model_attributes_type"):
        want = {"float_type": "a number", "int_type": "an integer", "string_type": "a string",
                "bool_type": "true or false", "list_type": "a list", "model_type": "a table", "dict_type": "a table",
                "model_attributes_type": "a table"}[kind]
        return f"must be {want} (got {type(value).__name__} {value!r:.60})"
    msg = err["msg"]
    return msg.removeprefix("Value error, ")


def _first_error(errors: list) -> dict:
    """The error to report: an unknown key before the others (a misspelt required key is both
    unknown and missing, and the unknown one is what the user wrote), else the first."""
    return next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])


def _models_in(annotation) -> list:
    """The pydantic models an annotation can hold (through Optional, Union, list, Annotated)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    return [m for arg in get_args(annotation) for m in _models_in(arg)]


def _keys_of_table(loc: tuple) -> list[str]:
    """The keys the scenario's table at ``loc`` (a pydantic error location) can have."""
    def keys(model) -> dict:  # as written in a file: by alias where a field has one
        return {f.alias or name: f for name, f in model.model_fields.items()}

    models = [Scenario]
    for part in loc:
        if isinstance(part, int):
            continue
        fields = [keys(m)[part] for m in models if part in keys(m)]
        if fields:
            models = [m for f in fields for m in _models_in(f.annotation)]
    return sorted({key for m in models for key in keys(m)})


def _did_you_mean(unknown: dict, errors: list) -> str:
    """' (did you mean NAME?)' for an unknown key close to a key of its table: one missing from
    it first (a misspelt required key), else any of its keys."""
    table, name = unknown["loc"][:-1], str(unknown["loc"][-1])
    missing = [str(e["loc"][-1]) for e in errors if e["type"] == "missing" and e["loc"][:-1] == table]
    close = (difflib.get_close_matches(name, missing, n=1, cutoff=0.6)
             or difflib.get_close_matches(name, _keys_of_table(table), n=1, cutoff=0.75))
    return f" (did you mean {close[0]}?)" if close else ""


def validate(data: dict, base_dir: str | Path | None = None) -> Scenario:
    """A validated Scenario from a plain dict (parsed TOML), or ScenarioError. Relative table
    paths (``file`` keys) are taken relative to ``base_dir`` (default: the current directory)."""
    if not isinstance(data, dict):
        raise ScenarioError("scenario: must be a TOML table")
    try:
        scenario = Scenario.model_validate(data, context={"base_dir": base_dir})
    except ValidationError as exc:
        err = _first_error(exc.errors())
        key = _format_loc(err["loc"]) or "scenario"
        reason = _explain(err)
        if err["type"] == "extra_forbidden":
            reason += _did_you_mean(err, exc.errors())
        # validators report "key: reason" for a key of their own model
        if err["type"] == "value_error" and ": " in reason and not reason.startswith(" "):
            sub, reason = reason.split(": ", 1)
            key = f"{key}.{sub}" if key != "scenario" else sub
        raise ScenarioError(f"{key}: {reason}") from None
    _cross_checks(scenario)
    _check_tables(scenario)
    check_controllers(scenario)
    return scenario


def table_files(s: Scenario) -> list[tuple[str, str, str]]:
    """(kind "drive", "torque" or "pose", key, absolute path) of every CSV table the scenario
    reads: its inputs, which no output of a command may overwrite."""
    hub = s.hub
    tables = []
    if s.base.file is not None:
        tables.append(("pose", "base.file", s.base.file))
    if hub.drive is not None and hub.drive.profile == "table":
        tables.append(("drive", "hub.drive.file", hub.drive.file))
    torque = hub.torque if isinstance(hub.torque, HubTorque) else None
    if torque is not None and torque.law == "table":
        tables.append(("torque", "hub.torque.file", torque.file))
    if torque is not None and torque.reference is not None and torque.reference.profile == "table":
        tables.append(("drive", "hub.torque.reference.file", torque.reference.file))
    where = "beam" if s.single_beam is not None else "beams"
    for i, b in enumerate(s.beam_tables):
        motor = b.joint.torque if b.joint is not None else None
        if motor is None:
            continue
        key = f"{where}[{i}].joint.torque" if where == "beams" else "beam.joint.torque"
        if motor.law == "table":
            tables.append(("torque", f"{key}.file", motor.file))
        if motor.reference is not None and motor.reference.profile == "table":
            tables.append(("drive", f"{key}.reference.file", motor.reference.file))
    for what in ("tip_force", "tip_moment"):
        path = getattr(s.loads, f"{what}_file")
        if path is not None:
            tables.append((what, f"loads.{what}_file", path))
    for i, span in enumerate(s.loads.span):
        if span.file is not None:
            tables.append(("span", f"loads.span[{i}].file", span.file))
    return tables


def _check_tables(s: Scenario) -> None:
    """The numbers of the CSV tables a scenario names (columns, rows, times)."""
    tables = table_files(s)
    if not tables:
        return
    from hubbeam.io.tables import (FORCE_COLUMNS, MOMENT_COLUMNS, read_drive_table, read_pose_table, read_span_table,
                                   read_tip_table, read_torque_table)

    readers = {"drive": read_drive_table, "torque": read_torque_table, "pose": read_pose_table}
    for what, key, path in tables:
        if what == "drive":
            drive = s.hub.drive if key == "hub.drive.file" else s.hub.torque.reference
            read_drive_table(path, key, interpolation=drive.interpolation, smoothing=drive.smoothing)
        elif what in ("tip_force", "tip_moment"):
            read_tip_table(path, key, FORCE_COLUMNS if what == "tip_force" else MOMENT_COLUMNS)
        elif what == "span":
            continue  # below, with its beam's length
        else:
            readers[what](path, key)
    for i, span in enumerate(s.loads.span):
        if span.file is not None:
            read_span_table(span.file, f"loads.span[{i}].file", s.resolved_beams()[s.beam_index(span.beam)].length)


