"""What can go wrong: bad input, and failures of a computation.

Bad input is a :class:`ScenarioError` (one line naming the key; exit status 2 on the command
line). Every failure of a computation is a :class:`ComputationError` that says where it
happened and what to try (exit status 1).
"""


class ScenarioError(ValueError):
    """Bad scenario input: the message names the key and says what is wrong."""


class ComputationError(RuntimeError):
    """A computation that did not succeed; ``partial`` holds the results up to the failure."""

    def __init__(self, message: str, partial=None):
        super().__init__(message)
        self.partial = partial


class ConvergenceError(ComputationError):
    """Newton did not converge (or its matrix was singular, or its increment not finite)."""


class ChartSingularityError(ComputationError):
    """A beam tangent reached the singular direction of its rotation chart."""
