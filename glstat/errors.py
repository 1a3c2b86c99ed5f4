"""Exceptions and warnings raised by glstat."""

__all__ = ["ConvergenceWarning", "FitError", "FitWarning", "InvalidParameterError"]


class InvalidParameterError(ValueError):
    """Lambda parameters that do not define a valid GLD; the message names the condition."""


class FitError(RuntimeError):
    """A fit that cannot be carried out; the message says why and what could work instead."""


class ConvergenceWarning(RuntimeWarning):
    """An iteration reached its limit; the affected results are the best available estimate."""


class FitWarning(UserWarning):
    """A fit that was carried out but describes the data poorly (support missing data points
    or a Kolmogorov–Smirnov distance beyond the 1 % critical value); the message says what to
    try instead."""
