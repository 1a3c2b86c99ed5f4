"""Validation of scalar arguments shared by the contact package."""

from __future__ import annotations

import numbers

import numpy as np

__all__ = ["real_scalar"]


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
