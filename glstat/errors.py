"""Exceptions and warnings raised by glstat."""

__all__ = ["ConvergenceWarning", "FitError", "InvalidParameterError"]


class InvalidParameterError(ValueError):
    """Lambda parameters that do not define a valid GLD; the message names the condition."""


class FitError(RuntimeError):
    """A fit that cannot be carried out; the message says why and what could work instead."""


class ConvergenceWarning(RuntimeWarning):
    """An iteration reached its limit; the affected results are the best available estimate."""
