"""Validation of scalar arguments shared by the contact package."""

from __future__ import annotations

import math
import numbers

import numpy as np

__all__ = ["finite_separation", "positive_pressure", "real_scalar"]


def real_scalar(value) -> float | None:
    """``value`` as a Python float when it is one real number, else None.

    Parameters
    ----------
    value : object
        Candidate scalar: a Python or NumPy integer or float, or a 0-d integer or float
        array, in whatever unit the caller expects.

    Returns
    -------
    float or None
        ``float(value)`` (NaN and infinities included, for the caller to judge), or None
        for booleans, strings, complex numbers, arrays with ``ndim > 0`` and other objects.
    """
    if isinstance(value, bool | np.bool_ | str | bytes) or np.ndim(value) != 0:
        return None
    if isinstance(value, np.ndarray | np.generic):
        if value.dtype.kind not in "iuf":
            return None
        return float(value)
    if isinstance(value, numbers.Real):
        return float(value)
    return None


def positive_pressure(value) -> float:
    """``value`` as a nominal pressure: one real, finite, positive number.

    Parameters
    ----------
    value : object
        The imposed nominal pressure in pascals (compressive positive).

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    ValueError
        Not one real number (see :func:`real_scalar`), or not finite and positive.
    """
    p = real_scalar(value)
    if p is None or not (math.isfinite(p) and p > 0):
        raise ValueError(
            f"nominal_pressure must be a positive finite pressure in pascals, got "
            f"{value!r}; a compressive load is positive"
        )
    return p


def finite_separation(value) -> float:
    """``value`` as the height of the flat: one real, finite number.

    Parameters
    ----------
    value : object
        The separation in metres, in the surface's height coordinate.

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    ValueError
        Not one real number (see :func:`real_scalar`), or not finite.
    """
    d = real_scalar(value)
    if d is None or not math.isfinite(d):
        raise ValueError(f"separation must be a finite height in metres, got {value!r}")
    return d
