"""The bundled scenarios (package data in hubbeam/examples), by name.

Standard library only: ``hubbeam --help`` and ``hubbeam example NAME`` need these names and
texts, not the scenario models of :mod:`hubbeam.io.scenario` (pydantic, about 0.2 s to import).
"""

from __future__ import annotations

from importlib import resources

from hubbeam.errors import ScenarioError

#: the bundled scenarios (package data in hubbeam/examples)
EXAMPLES = ("cantilever", "exp1", "exp1_h4", "exp1_h1", "exp2", "rotor3", "spacecraft", "arm", "blade", "articulated",
            "deploy", "arm2")


def example_text(name: str) -> str:
    """The TOML text of a bundled scenario."""
    if name not in EXAMPLES:
        raise ScenarioError(f"example: unknown example {name!r} (available: {', '.join(EXAMPLES)})")
    return resources.files("hubbeam").joinpath("examples", f"{name}.toml").read_text(encoding="utf-8")
