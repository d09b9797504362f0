"""Failures of a computation, each saying where it happened and what to try."""


class ComputationError(RuntimeError):
    """A computation that did not succeed; ``partial`` holds the results up to the failure."""

    def __init__(self, message: str, partial=None):
        super().__init__(message)
        self.partial = partial


class ConvergenceError(ComputationError):
    """Newton did not converge."""
