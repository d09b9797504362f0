"""Scenario variants and value ranges shared by the studies."""

from __future__ import annotations

import numpy as np

from hubbeam.io.scenario import Scenario, ScenarioError, apply_overrides, validate

#: formulation labels -> the overrides that select them
FORMULATIONS = {
    "ancf": ['beam.formulation="ancf"'],
    "ffr": ['beam.formulation="ffr"', "beam.geometric_stiffening=false"],
    "ffr+": ['beam.formulation="ffr"', "beam.geometric_stiffening=true"],
}


def variant(scenario: Scenario, overrides: list[str]) -> Scenario:
    """A copy of ``scenario`` with ``--set``-style overrides, validated again."""
    data = scenario.to_dict()
    if overrides and any(o.startswith("beam.formulation") for o in overrides):
        data["beam"].pop("gauss_points", None)  # an ANCF-only key
        data["beam"].pop("geometric_stiffening", None)
    return validate(apply_overrides(data, overrides))


#: at most this many values in one range
MAX_RANGE = 10_000


def parse_range(text: str, what: str) -> np.ndarray:
    """'START:STOP:N' -> N values from START to STOP (numpy.linspace); one number -> itself."""
    parts = text.split(":")
    try:
        values = [float(parts[0])] if len(parts) == 1 else [float(parts[0]), float(parts[1]), int(parts[2])]
    except (ValueError, IndexError):
        values = None
    if values is not None and len(parts) in (1, 3) and all(np.isfinite(values)):
        if len(parts) == 1:
            return np.array(values)
        start, stop, n = values
        if n > MAX_RANGE:
            raise ScenarioError(f"{what}: {n} values; at most {MAX_RANGE}")
        if n >= 1:
            return np.linspace(start, stop, n)
    raise ScenarioError(f"{what}: expected START:STOP:N with finite START and STOP and N >= 1 (got {text!r})")


def parse_vary(text: str) -> tuple[str, np.ndarray, bool]:
    """'KEY=START:STOP:N' -> (key, values, integral); integral when START and STOP are written
    as integers and every value is one (for keys such as beam.elements)."""
    key, sep, rng = text.partition("=")
    if not sep or not key.strip():
        raise ScenarioError(f"--vary: expected KEY=START:STOP:N (got {text!r})")
    values = parse_range(rng, f"--vary {key.strip()}")
    ends = rng.split(":")[:2]
    integral = all(e.strip().lstrip("+-").isdigit() for e in ends) and np.allclose(values, np.round(values))
    return key.strip(), values, bool(integral)
