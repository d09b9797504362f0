"""The scenario reference (docs/scenario.md) against the scenario models of the package io/scenario/.

Each model has a table in the page, introduced by ``<!-- keys of MODEL -->``: one row per key
(first column the key in backticks, the third its default). Every field of every model a
scenario can hold must have a row, every row must be a field, and a default the page states
as a value must be the model's. Choices (``<!-- values of MODEL.FIELD -->``: drive profiles,
torque laws, sensor kinds) must list exactly the values the model accepts.
"""

from __future__ import annotations

import math
import re
import tomllib
import typing
from pathlib import Path

import pytest
from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from hubbeam.io import scenario as sc

PAGE = Path(__file__).resolve().parents[2] / "docs" / "scenario.md"


def _tables(marker: str) -> dict[str, list[list[str]]]:
    """{name: rows} of the tables introduced by ``<!-- MARKER NAME -->`` (rows: cells, header
    and separator left out; ``\\|`` inside a cell is a literal bar)."""
    lines = PAGE.read_text(encoding="utf-8").splitlines()
    out: dict[str, list[list[str]]] = {}
    for i, line in enumerate(lines):
        m = re.fullmatch(rf"<!-- {marker} (\S+) -->", line.strip())
        if not m:
            continue
        rows = []
        for row in lines[i + 3:]:
            if not row.startswith("|"):
                break
            cells = [c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", row.strip())[1:-1]]
            rows.append(cells)
        assert m.group(1) not in out, f"two tables for {m.group(1)}"
        out[m.group(1)] = rows
    return out


def _key(cell: str) -> str:
    m = re.fullmatch(r"`([^`]+)`.*", cell)
    assert m, f"a key cell is `key`: {cell!r}"
    return m.group(1).strip('"')


def _models(root=sc.Scenario) -> dict[str, type[BaseModel]]:
    """Every model a scenario holds, by class name (walks the field annotations)."""
    found: dict[str, type[BaseModel]] = {}

    def walk(tp):
        if isinstance(tp, type) and issubclass(tp, BaseModel):
            if tp.__name__ not in found:
                found[tp.__name__] = tp
                for f in tp.model_fields.values():
                    walk(f.annotation)
            return
        for arg in typing.get_args(tp):
            walk(arg)

    walk(root)
    return found


MODELS = _models()
KEYS = _tables("keys of")
VALUES = _tables("values of")


def _field_names(model: type[BaseModel]) -> set[str]:
    return {f.alias or name for name, f in model.model_fields.items()}


def test_the_walk_finds_the_scenario_models():
    # the walk is what makes the other tests complete: it must reach nested tables
    assert {"Scenario", "Beam", "TipBody", "Hub", "Drive", "HubTorque", "Environment", "Damping", "Loads",
            "Analysis", "Sensor"} <= set(MODELS)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_key_has_a_row_and_every_row_is_a_key(name):
    assert name in KEYS, f"docs/scenario.md has no '<!-- keys of {name} -->' table"
    documented = [_key(row[0]) for row in KEYS[name]]
    assert len(documented) == len(set(documented)), f"{name}: a key documented twice"
    fields = _field_names(MODELS[name])
    assert set(documented) - fields == set(), f"{name}: rows for keys the code does not have"
    assert fields - set(documented) == set(), f"{name}: keys missing from the reference"


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_row_gives_a_unit_a_default_and_a_meaning(name):
    for row in KEYS.get(name, []):
        assert len(row) == 4 and all(row), f"{name}: a row needs key, type/unit, default, meaning: {row}"


def _value(cell: str):
    """The TOML value a default cell states (backticks removed; what follows " (" or ";" is a
    remark), or None for words."""
    text = re.split(r" \(|;", cell.replace("`", ""), maxsplit=1)[0].strip()
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return None


def _same(a, b) -> bool:
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return math.isclose(a, b, rel_tol=1e-12, abs_tol=0.0)
    return a == b


@pytest.mark.parametrize("name", sorted(MODELS))
def test_the_stated_defaults_are_the_code_s(name):
    model = MODELS[name]
    fields = {f.alias or n: f for n, f in model.model_fields.items()}
    # keys a choice requires (a drive profile's omega_s, a law's value): their model default is a
    # neutral placeholder, and the reference says which choices require them
    choices = model._keys if issubclass(model, sc.KeyedChoice) else {}
    by_choice = {k for _, required in choices.values() for k in required}
    for row in KEYS.get(name, []):
        key, default = _key(row[0]), row[2]
        field = fields.get(key)
        if field is None:
            continue  # reported by the test above
        if field.default is PydanticUndefined or key in by_choice:
            assert "required" in default, f"{name}.{key}: a required key, documented with default {default!r}"
            continue
        stated = _value(default)
        if isinstance(field.default, (int, float, str, list)) and not isinstance(field.default, BaseModel):
            if isinstance(field.default, float) and math.isinf(field.default):
                assert default == "never", f"{name}.{key}: default inf, documented as {default!r}"
                continue
            if field.default == []:
                assert default == "none", f"{name}.{key}: default empty, documented as {default!r}"
                continue
            assert stated is not None and _same(stated, field.default), (
                f"{name}.{key}: the code's default is {field.default!r}, the reference says {default!r}")


@pytest.mark.parametrize("spec", ["Drive.profile", "HubTorque.law", "Sensor.kind"])
def test_every_choice_is_listed(spec):
    model, field = spec.split(".")
    assert spec in VALUES, f"docs/scenario.md has no '<!-- values of {spec} -->' table"
    listed = [_key(row[0]) for row in VALUES[spec]]
    accepted = set(typing.get_args(MODELS[model].model_fields[field].annotation))
    assert len(listed) == len(set(listed))
    assert set(listed) == accepted


def test_every_bundled_example_is_listed():
    text = PAGE.read_text(encoding="utf-8")
    section = text.split("## Bundled scenarios", 1)[1]
    for name in sc.EXAMPLES:
        assert f"`{name}`" in section, name


def _subcommands():
    import argparse

    from hubbeam.cli.parser import build_parser

    parser = build_parser()
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return action.choices


def test_every_command_and_option_is_in_the_commands_page():
    page = (PAGE.parent / "commands.md").read_text(encoding="utf-8")
    shared = {"--set", "--json", "-h", "--help"}  # described once at the top of the page
    for name, sub in _subcommands().items():
        rows = [line for line in page.splitlines() if line.startswith(f"| `hubbeam {name} ") or
                line.startswith(f"| `hubbeam {name}`")]
        assert len(rows) == 1, f"hubbeam {name}: expected one row in docs/commands.md"
        for action in sub._actions:
            options = [o for o in action.option_strings if o not in shared]
            if options:
                assert any(o in rows[0] for o in options), f"hubbeam {name}: option {options} not in its row"
    for option in ("--set", "--json", "--version"):
        assert option in page
