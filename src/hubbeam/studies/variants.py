"""Scenario variants and value ranges shared by the studies."""

from __future__ import annotations

import numpy as np

from hubbeam.io.scenario import ResolvedBeam, Scenario, ScenarioError, apply_overrides, validate

#: formulation labels -> the overrides that select them, for every beam of a scenario
#: (``beams[*]`` addresses each beam of a [beam] table or of [[beams]] tables)
FORMULATIONS = {
    "ancf": ['beams[*].formulation="ancf"'],
    "ffr": ['beams[*].formulation="ffr"', "beams[*].geometric_stiffening=false"],
    "ffr+": ['beams[*].formulation="ffr"', "beams[*].geometric_stiffening=true"],
}


def variant(scenario: Scenario, overrides: list[str]) -> Scenario:
    """A copy of ``scenario`` with ``--set``-style overrides, validated again. Switching a
    formulation, hub.motion, a drive profile or a torque law drops the keys the new choice
    does not take (:func:`hubbeam.io.scenario.apply_overrides`)."""
    return validate(apply_overrides(scenario.to_dict(), list(overrides or [])))


def with_formulation(scenario: Scenario, form: str, extra_overrides=()) -> Scenario:
    """``scenario`` with every beam switched to formulation label ``form`` (a key of
    :data:`FORMULATIONS`) and further ``--set``-style overrides."""
    if form not in FORMULATIONS:
        raise ScenarioError(f"formulation: unknown {form!r} (use {', '.join(FORMULATIONS)})")
    return variant(scenario, FORMULATIONS[form] + list(extra_overrides))


def single_beam(scenario: Scenario, study: str) -> ResolvedBeam:
    """The one beam of a single-beam scenario, resolved; a clear ScenarioError for a study
    (``study``, e.g. "the applicability map") that handles one beam only."""
    beams = scenario.resolved_beams()
    if len(beams) != 1:
        raise ScenarioError(f"beams: {study} handles a scenario with one beam; this one has {len(beams)} "
                            f"({', '.join(b.name for b in beams)})")
    return beams[0]


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
