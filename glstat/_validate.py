"""Checks of the arguments the statistics share (one rule per check)."""

from __future__ import annotations

import numbers

import numpy as np

__all__ = ["FIT_METHODS", "PARAMS", "check_level", "check_method", "check_n_resamples", "check_param"]

#: The parameterisations of the GLD.
PARAMS = ("rs", "fkml")
#: The fitting methods of :func:`glstat.fit`.
FIT_METHODS = ("moments", "percentiles", "lmoments", "mle", "mps", "starship")


def check_n_resamples(n_resamples, allow_zero: bool = False) -> int:
    """A number of bootstrap resamples: an integer >= 2, or 0 (no bootstrap) where
    ``allow_zero``."""
    if isinstance(n_resamples, (bool, np.bool_)) or not isinstance(n_resamples, numbers.Integral):
        raise TypeError(f"n_resamples must be an integer, got {n_resamples!r}")
    if allow_zero and n_resamples == 0:
        return 0
    if n_resamples < 2:
        raise ValueError(f"n_resamples must be {'0 (no bootstrap) or ' if allow_zero else ''}"
                         f">= 2, got {n_resamples}")
    return int(n_resamples)


def check_level(confidence_level, name: str = "confidence_level") -> float:
    """A confidence level or probability: a real number strictly between 0 and 1 (``name``
    is the argument's name in messages)."""
    if isinstance(confidence_level, (bool, np.bool_)) or not isinstance(confidence_level, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {confidence_level!r}")
    c = float(confidence_level)
    if not 0.0 < c < 1.0:
        raise ValueError(f"{name} must be strictly between 0 and 1, got {c}")
    return c


def check_param(param) -> str:
    """A parameterisation, ``"rs"`` or ``"fkml"`` in any case; returned in lower case."""
    p = str(param).lower()
    if p not in PARAMS:
        raise ValueError(f"param must be 'rs' or 'fkml', got {param!r}")
    return p


def check_method(method) -> str:
    """A fitting method: one of :data:`FIT_METHODS`."""
    if method not in FIT_METHODS:
        raise ValueError(f"method must be one of {FIT_METHODS}, got {method!r}")
    return method
