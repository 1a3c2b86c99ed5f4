"""Validation of scalar arguments shared by the contact package."""

from __future__ import annotations

import math
import numbers

import numpy as np

__all__ = [
    "elastic_constants",
    "finite_separation",
    "positive_finite",
    "positive_pressure",
    "real_array",
    "real_scalar",
]


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
    try:
        return positive_finite(value, "nominal_pressure", "pressure in pascals")
    except ValueError as exc:
        raise ValueError(f"{exc}; a compressive load is positive") from None


def positive_finite(value, name: str, what: str) -> float:
    """``value`` as one real, finite, positive number.

    Parameters
    ----------
    value : object
        The candidate number, in the unit ``what`` names.
    name : str
        The argument's name, for messages.
    what : str
        What the number is, with its unit, for messages (e.g. ``"length in metres"``).

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    ValueError
        Not one real number (see :func:`real_scalar`), or not finite and positive.
    """
    x = real_scalar(value)
    if x is None or not (math.isfinite(x) and x > 0):
        raise ValueError(f"{name} must be a positive finite {what}, got {value!r}")
    return x


def elastic_constants(E, nu, which: str = "") -> tuple[float, float]:
    """``(E, nu)`` of one body as floats: a positive finite Young's modulus and a Poisson
    ratio in (-1, 0.5].

    Parameters
    ----------
    E : object
        Young's modulus in pascals.
    nu : object
        Poisson ratio (dimensionless).
    which : str, optional
        Suffix of the argument names in messages, e.g. ``"2 (counter_face)"``.

    Returns
    -------
    E, nu : float
        ``float(E)``, ``float(nu)``.

    Raises
    ------
    ValueError
        Not one real number each (see :func:`real_scalar`), or outside the ranges.
    """
    e = positive_finite(E, f"E{which}", "Young's modulus in pascals")
    n = real_scalar(nu)
    if n is None or not (-1.0 < n <= 0.5):
        raise ValueError(
            f"nu{which} must be a Poisson ratio in (-1, 0.5], got {nu!r}; "
            "0.5 is incompressible, typical metals are near 0.3"
        )
    return e, n


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


def real_array(value, name: str = "heights") -> tuple[np.ndarray, np.ndarray | None]:
    """``value`` as a new float64 array, and the mask of a masked array.

    Parameters
    ----------
    value : array_like
        Real numbers: integers, floats or booleans-free numeric data; a
        :class:`numpy.ma.MaskedArray` marks its masked entries as missing.
    name : str
        What the values are, for messages.

    Returns
    -------
    values : ndarray of float64
        A copy (the caller's data are never modified); masked entries are NaN.
    mask : ndarray of bool or None
        True at the masked entries of a masked array with any masked entry, else None.

    Raises
    ------
    TypeError
        Complex numbers, dates/times, strings, booleans, or objects that are not real
        numbers (``None``, ``pandas.NA``, ...).
    """
    mask = None
    if isinstance(value, np.ma.MaskedArray):
        m = np.ma.getmaskarray(value)
        mask = m.copy() if m.any() else None
        data = np.ma.getdata(value)
    else:
        data = value
    arr = np.asarray(data)
    kind = arr.dtype.kind
    if kind == "c":
        raise TypeError(f"{name} are complex ({arr.dtype}); pass real numbers (e.g. .real or abs())")
    if kind in "mM":
        raise TypeError(f"{name} are dates or times ({arr.dtype}), not numbers")
    if kind in "SUVb":
        raise TypeError(f"{name} must be real numbers, got an array of dtype {arr.dtype}")
    if kind == "O":
        try:
            out = np.array(arr, dtype=float)
        except (TypeError, ValueError):
            bad = next((v for v in arr.ravel() if not isinstance(v, numbers.Real)
                        or isinstance(v, bool | np.bool_)), None)
            raise TypeError(
                f"{name} must be real numbers, got an object array holding {bad!r} "
                f"({type(bad).__name__}); convert missing values to NaN first"
            ) from None
    else:
        out = np.array(arr, dtype=float, copy=True)
    if mask is not None:
        out[mask] = np.nan
    return out, mask
