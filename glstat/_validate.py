"""Checks of the arguments the statistics share (one rule per check)."""

from __future__ import annotations

import numbers

import numpy as np

__all__ = ["check_level", "check_n_resamples"]


def check_n_resamples(n_resamples) -> int:
    """A number of bootstrap resamples: an integer >= 2."""
    if isinstance(n_resamples, (bool, np.bool_)) or not isinstance(n_resamples, numbers.Integral):
        raise TypeError(f"n_resamples must be an integer, got {n_resamples!r}")
    if n_resamples < 2:
        raise ValueError(f"n_resamples must be >= 2, got {n_resamples}")
    return int(n_resamples)


def check_level(confidence_level) -> float:
    """A confidence level: a real number strictly between 0 and 1."""
    if isinstance(confidence_level, (bool, np.bool_)) or not isinstance(confidence_level, numbers.Real):
        raise TypeError(f"confidence_level must be a real number, got {confidence_level!r}")
    c = float(confidence_level)
    if not 0.0 < c < 1.0:
        raise ValueError(f"confidence_level must be strictly between 0 and 1, got {c}")
    return c
