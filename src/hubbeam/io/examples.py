"""The bundled scenarios (package data in hubbeam/examples), by name.

Standard library only: ``hubbeam --help`` and ``hubbeam example NAME`` need these names and
texts, not the scenario models of :mod:`hubbeam.io.scenario` (pydantic, about 0.2 s to import).
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from hubbeam.errors import ScenarioError

#: the bundled scenarios (package data in hubbeam/examples)
EXAMPLES = ("cantilever", "exp1", "exp1_h4", "exp1_h1", "exp2", "rotor3", "spacecraft", "arm", "blade",
            "spacecraft3d", "platform", "tilted", "explorer", "articulated", "deploy", "arm2")
#: the bundled data files, by their file names: tables a bundled scenario reads (next to it) and
#: measured samples
DATA_FILES = ("platform_motion.csv", "exp1_strain_P1.csv")


def example_text(name: str) -> str:
    """The TOML text of a bundled scenario, or the text of a bundled data file (by its file name)."""
    if name in DATA_FILES:
        return resources.files("hubbeam").joinpath("examples", name).read_text(encoding="utf-8")
    if name not in EXAMPLES:
        raise ScenarioError(f"example: unknown example {name!r} (available: {', '.join(EXAMPLES + DATA_FILES)})")
    return resources.files("hubbeam").joinpath("examples", f"{name}.toml").read_text(encoding="utf-8")


def examples_folder() -> Path:
    """The folder of the bundled scenarios: a bundled scenario's table paths are relative to it."""
    return Path(str(resources.files("hubbeam").joinpath("examples")))
