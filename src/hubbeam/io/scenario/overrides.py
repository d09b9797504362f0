"""``--set KEY=VALUE`` overrides, and reading scenario files and bundled examples."""

from __future__ import annotations

import copy
import re
import tomllib
from pathlib import Path
from typing import Any

from hubbeam.errors import ScenarioError
from hubbeam.io.examples import example_text, examples_folder
from hubbeam.io.scenario.beams import beam_names_of, copy_azimuth
from hubbeam.io.scenario.hub import DRIVE_KEYS, TORQUE_KEYS
from hubbeam.io.scenario.model import Scenario, _format_loc, validate


_SEGMENT = re.compile(r"([^.\[\]]+)((?:\[(?:\d+|\*)\])*)")
_INDEX = re.compile(r"\[(\d+|\*)\]")
#: keys whose value selects which other keys of the same table apply
_SWITCHES = {"formulation", "motion", "profile", "law"}


def parse_override(text: str) -> tuple[list[str], object]:
    """'beam.elements=8' -> (['beam', 'elements'], 8); the value uses TOML syntax, a bare word is a string."""
    if "=" not in text:
        raise ScenarioError(f"--set {text}: expected KEY=VALUE")
    key, raw = text.split("=", 1)
    key = key.strip()
    if not key or any(not part for part in key.split(".")):
        raise ScenarioError(f"--set {text}: malformed key {key!r}")
    raw = raw.strip()
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError as exc:
        if raw[:1] in ('"', "'", "[", "{"):  # meant as a TOML string, array or table, and malformed
            reason = str(exc).split(" (at ")[0]
            hint = "; a string is KEY=\"text\" or a bare word" if raw[0] in "\"'" else ""
            raise ScenarioError(f"--set {text}: not a valid TOML value ({reason}{hint})") from None
        value = raw  # a bare word is a string: hub.motion=fixed
    return key.split("."), value


def _tokens(key: str, text: str) -> list:
    """'beams[1].tip_body.mass' -> ['beams', 1, 'tip_body', 'mass'] ('*' for [*])."""
    out: list = []
    for seg in key.split("."):
        m = _SEGMENT.fullmatch(seg)
        if not m:
            raise ScenarioError(f"--set {text}: malformed key {key!r}")
        out.append(m.group(1))
        out += [int(i) if i != "*" else "*" for i in _INDEX.findall(m.group(2))]
    return out


def _selected_beams(data: dict, sel, text: str) -> tuple[list, list[int]]:
    """(the beams (table index, copy, name) of the scenario data, the indices among them that
    the selector ``sel`` of ``beams[sel]`` / ``beams.sel`` picks: an index, a name or '*')."""
    single, many = data.get("beam"), data.get("beams")
    if isinstance(single, dict) and many is None:
        tables = [single]
    elif isinstance(many, list):
        tables = many
    else:
        raise ScenarioError(f"--set {text}: the scenario has no beams to address")
    beams = beam_names_of(tables)
    names = [name for _, _, name in beams]
    if sel == "*":
        return beams, list(range(len(beams)))
    if isinstance(sel, int):
        if sel >= len(beams):
            raise ScenarioError(f"--set {text}: beam index {sel} is out of range (the scenario has "
                                f"{len(beams)} beam{'s' if len(beams) > 1 else ''}: 0..{len(beams) - 1})")
        return beams, [sel]
    if sel not in names:
        raise ScenarioError(f"--set {text}: no beam named {sel!r} (beams: {', '.join(names)})")
    return beams, [names.index(sel)]


def _addresses(data: dict, tokens: list, text: str) -> list[tuple]:
    """The places a --set key addresses, with a beam named by index or name turned into its
    table: ('beam', ...) for a single [beam], ('beams', i, ...) for [[beams]]. Beams are counted
    copy by copy; a copy of a table with ``copies`` addresses that table (:func:`apply_overrides`
    gives a copy addressed alone a table of its own first), and ``beams[*]`` each table once."""
    head, rest = tokens[0], tokens[1:]
    single = data.get("beam")
    many = data.get("beams")
    if head == "beam":
        if isinstance(many, list) and single is None:
            count = len(beam_names_of(many))
            if count != 1:
                raise ScenarioError(f"--set {text}: the scenario has {count} beams; address one as "
                                    f"beams[i].KEY (0-based) or beams.NAME.KEY")
            return [("beams", 0, *rest)]
        return [("beam", *rest)]
    if head == "beams" and rest:
        sel, rest = rest[0], rest[1:]
        beams, picked = _selected_beams(data, sel, text)
        to = (lambda i: ("beam",)) if isinstance(single, dict) and many is None else (lambda i: ("beams", i))
        tables = list(dict.fromkeys(beams[k][0] for k in picked))
        return [address for i in tables for address in _expand(data, (*to(i), *rest), text)]
    return _expand(data, tuple(tokens), text)


def _split_copies(data: dict, overrides: list[str]) -> None:
    """Give every copy of a ``copies`` table that a --set addresses alone (``beams[i]`` or
    ``beams.NAME``, not ``beams[*]``) a table of its own, in place: the table is replaced by its
    copies, each with its name and azimuth written out and no ``copies`` key, so that the
    --set changes that copy only."""
    many = data.get("beams")
    if not isinstance(many, list):
        return
    split: set[int] = set()
    for text in overrides:
        key = text.split("=", 1)[0].strip()
        tokens = _tokens(key, text)
        if tokens[0] == "beams" and len(tokens) > 2 and tokens[1] != "*":
            beams, picked = _selected_beams(data, tokens[1], text)
            split.update(beams[k][0] for k in picked if beams[k][1] is not None)
    if not split:
        return
    out = []
    for i, table in enumerate(many):
        if i not in split:
            out.append(table)
            continue
        copies = beam_names_of([table])
        for _, k, name in copies:
            one = {key: copy.deepcopy(value) for key, value in table.items() if key != "copies"}
            azimuth = table.get("azimuth", 0.0)
            one["name"] = name
            if isinstance(azimuth, (int, float)) and not isinstance(azimuth, bool):
                one["azimuth"] = copy_azimuth(float(azimuth), k, len(copies))
            out.append(one)
    data["beams"] = out


def _expand(data: dict, address: tuple, text: str) -> list[tuple]:
    """``address`` with every ``[*]`` replaced by each index of that list."""
    if "*" not in address:
        return [address]
    k = address.index("*")
    node = _get(data, address[:k])
    if not isinstance(node, list):
        raise ScenarioError(f"--set {text}: {_show(address[:k])} is not a list")
    return [a for i in range(len(node)) for a in _expand(data, (*address[:k], i, *address[k + 1:]), text)]


def _canonical(address: tuple) -> tuple:
    return ("beams", 0, *address[1:]) if address[:1] == ("beam",) else address


def _set(data: dict, address: tuple, value, text: str) -> None:
    node: Any = data
    for k, part in enumerate(address[:-1]):
        shown = _show(address[:k + 1])
        if isinstance(part, int) or part == "*":
            if not isinstance(node, list):
                raise ScenarioError(f"--set {text}: {_show(address[:k])} is not a list")
            if part == "*" or part >= len(node):
                raise ScenarioError(f"--set {text}: index {part} of {_show(address[:k])} is out of range "
                                    f"({len(node)} entries)")
            node = node[part]
        else:
            if not isinstance(node, dict):
                raise ScenarioError(f"--set {text}: {_show(address[:k])} is not a table")
            node = node.setdefault(part, {})
            if not isinstance(node, (dict, list)):
                raise ScenarioError(f"--set {text}: {shown} is not a table (it is {node!r}; set the whole "
                                    f"{shown} instead, e.g. {shown}={{...}})")
        if not isinstance(node, (dict, list)):
            raise ScenarioError(f"--set {text}: {shown} is not a table")
    last = address[-1]
    if isinstance(last, int):
        if not isinstance(node, list) or last >= len(node):
            raise ScenarioError(f"--set {text}: index {last} of {_show(address[:-1])} is out of range")
        node[last] = value
    else:
        if not isinstance(node, dict):
            raise ScenarioError(f"--set {text}: {_show(address[:-1])} is not a table")
        node[last] = value


def _show(address: tuple) -> str:
    out = ""
    for part in address:
        out += f"[{part}]" if isinstance(part, int) else ("." if out else "") + str(part)
    return out


def _get(data: Any, address: tuple):
    node = data
    for part in address:
        if isinstance(part, int):
            if not isinstance(node, list) or part >= len(node):
                return None
            node = node[part]
        else:
            if not isinstance(node, dict) or part not in node:
                return None
            node = node[part]
    return node


def _prune(data: dict, switch: tuple, set_paths: set) -> list[str]:
    """After --set switched ``switch`` (a formulation, motion, profile or law), drop the keys of
    the old choice that the new one does not take (unless they are set by --set as well).
    Returns the dropped keys' names."""
    table = _get(data, switch[:-1])
    value = table.get(switch[-1]) if isinstance(table, dict) else None
    if not isinstance(table, dict) or not isinstance(value, str):
        return []
    key = switch[-1]
    dropped = []

    def drop(*names):
        for name in names:
            if _canonical(switch[:-1] + (name,)) not in set_paths and name in table:
                table.pop(name)
                dropped.append(name)

    if key == "formulation":
        drop(*{"ancf": ("geometric_stiffening", "modes"), "ffr": ("gauss_points",)}.get(value, ()))
    elif key == "motion" and switch[:-1] == ("hub",):
        if value != "free":
            drop("torque")
            dropped += _drop_sensors(data, "applied_torque", set_paths)
        if value != "prescribed":
            drop("drive")
    elif key == "profile" and value in DRIVE_KEYS:
        drop(*(k for k in ("omega_s", "T", "t1", "angle", "file", "interpolation", "smoothing")
               if k not in DRIVE_KEYS[value][0]))
    elif key == "law" and value in TORQUE_KEYS:
        drop(*(k for k in ("value", "file", "kp", "kd", "reference") if k not in TORQUE_KEYS[value][0]))
    return dropped


def _drop_sensors(data: dict, kind: str, set_paths: set) -> list[str]:
    """Drop the sensors of ``kind`` (a --set that switched hub.motion away from 'free' drops
    the applied_torque sensors with the torque law), unless a --set names them. Returns
    their descriptions, "sensors[i] (NAME, KIND)", for the note."""
    sensors = data.get("sensors")
    if not isinstance(sensors, list):
        return []
    keep, out = [], []
    for i, sensor in enumerate(sensors):
        named = any(p[:2] == ("sensors", i) or p == ("sensors",) for p in set_paths)
        if isinstance(sensor, dict) and sensor.get("kind") == kind and not named:
            out.append(f"sensors[{i}] ({sensor.get('name')!r}, {kind})")
        else:
            keep.append(sensor)
    data["sensors"] = keep
    return out


def apply_overrides(data: dict, overrides: list[str], dropped: list[str] | None = None) -> dict:
    """Apply --set overrides to parsed TOML data (a new dict is returned).

    Keys are dotted paths; a list entry is addressed by a 0-based index (``sensors[1].x``);
    a beam by index or name (``beams[1].twist``, ``beams.blade2.twist``, and ``beams[*].KEY``
    for every beam), a table's copies one by one (a copy addressed alone gets a table of its
    own, :func:`_split_copies`); ``beam.KEY`` addresses the one beam of a single-beam scenario. A key may
    be set once. A relative ``file`` value is taken relative to the current directory.
    Switching a formulation, hub.motion, a drive profile or a torque law drops the keys of
    the old choice that the new one does not take; each drop is added to ``dropped`` (when
    given) as a line naming the --set and the keys.
    """
    data = copy.deepcopy(data)
    for text in overrides or []:
        parse_override(text)  # checks the KEY=VALUE form before anything is read
    _split_copies(data, list(overrides or []))
    set_paths: dict[tuple, str] = {}
    switches = []
    for text in overrides or []:
        _, value = parse_override(text)  # checks the KEY=VALUE form
        key = text.split("=", 1)[0].strip()
        for address in _addresses(data, _tokens(key, text), text):
            canon = _canonical(address)
            for other, other_text in set_paths.items():
                other_key = other_text.split("=", 1)[0].strip()
                also = "" if other_key == key else f" (also as {other_key})"
                if other == canon:
                    raise ScenarioError(f"--set {key}: given more than once{also}")
                n = min(len(other), len(canon))
                if other[:n] == canon[:n]:
                    raise ScenarioError(f"--set {key}: overlaps --set {other_key} (set a key or its table once)")
            if address[-1] == "file" and isinstance(value, str) and value:
                value = str(Path(value).expanduser().absolute())  # a path typed here: from the current directory
            _set(data, address, value, text)
            set_paths[canon] = text
            if isinstance(address[-1], str) and address[-1] in _SWITCHES:
                switches.append(address)
    for address in switches:
        names = _prune(data, address, set(set_paths))
        if names and dropped is not None:
            text = set_paths[_canonical(address)].strip()
            table = _format_loc(address[:-1])  # the table switched (beams[*] names each beam)
            choice = f"{address[-1]} {_get(data, address)!r}"
            keys = [n if n.startswith("sensors[") else f"{table}.{n}" for n in names]
            dropped.append(f"--set {text}: {', '.join(keys)} dropped ({choice} does not "
                           f"take {'it' if len(names) == 1 else 'them'})")
    return data


def value_at(data: dict, key: str):
    """The value a --set key addresses in parsed scenario data (None if not set there); a copy
    of a ``copies`` table has the table's values but its own name and azimuth."""
    data = copy.deepcopy(data)
    _split_copies(data, [key])
    addresses = _addresses(data, _tokens(key, key), key)
    if len(addresses) != 1:
        raise ScenarioError(f"{key}: addresses {len(addresses)} values; name one")
    return _get(data, addresses[0])


def load_example(name: str, overrides: list[str] | None = None, dropped: list[str] | None = None) -> Scenario:
    """A bundled scenario, overridden and validated (``dropped``: see :func:`apply_overrides`); its
    tables are the bundled ones next to it."""
    return validate(apply_overrides(tomllib.loads(example_text(name)), overrides or [], dropped),
                    base_dir=examples_folder())


def load_scenario(source: str | Path, overrides: list[str] | None = None,
                  dropped: list[str] | None = None) -> Scenario:
    """Read, override and validate a scenario file (relative table paths: relative to the file;
    ``dropped``: see :func:`apply_overrides`)."""
    path = Path(source)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ScenarioError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise ScenarioError(f"{path}: is a directory, not a scenario file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ScenarioError(f"{path}: cannot read ({exc.__class__.__name__})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(f"{path}: malformed TOML ({exc})") from None
    return validate(apply_overrides(data, overrides or [], dropped), base_dir=path.absolute().parent)
