"""Failures of a computation, each saying where it happened and what to try.

Every failure of a computation (as opposed to bad input, :class:`hubbeam.io.scenario.ScenarioError`)
is a :class:`ComputationError`; the command line turns it into exit status 1 and its message.
"""


class ComputationError(RuntimeError):
    """A computation that did not succeed; ``partial`` holds the results up to the failure."""

    def __init__(self, message: str, partial=None):
        super().__init__(message)
        self.partial = partial


class ConvergenceError(ComputationError):
    """Newton did not converge (or its matrix was singular, or its increment not finite)."""


class ChartSingularityError(ComputationError):
    """A beam tangent reached the singular direction of its rotation chart."""
