"""Checks of the arguments the statistics share (one rule per check)."""

from __future__ import annotations

import numbers

import numpy as np

__all__ = ["FIT_METHODS", "PARAMS", "check_level", "check_method", "check_n_resamples", "check_param",
           "real_values"]

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


def real_values(data, name: str = "data") -> tuple[np.ndarray, np.ndarray | None]:
    """A flat float copy of data that must be real numbers, and which entries are not masked.

    Parameters
    ----------
    data : array_like
        Integers or reals of any shape: a NumPy array, a list, a pandas Series of a numeric
        dtype (nullable dtypes included: ``pd.NA`` becomes NaN), an object array holding
        numbers, or a :class:`numpy.ma.MaskedArray` (masked entries are missing values).
    name : str
        The argument's name in messages.

    Returns
    -------
    values : ndarray
        1-d float array, a new array (the caller's data are never modified); non-finite values
        are kept, masked entries included with their underlying value.
    keep : ndarray of bool or None
        For a masked array, True where the entry is not masked; None otherwise.

    Raises
    ------
    TypeError
        Complex numbers, dates or times, booleans, strings, or objects that are not real
        numbers (``None``, ``pandas.NA`` in an object array, ...).
    """
    keep = None
    if isinstance(data, np.ma.MaskedArray):
        keep = ~np.ma.getmaskarray(data).ravel()
        data = np.ma.getdata(data)
    elif hasattr(data, "to_numpy") and hasattr(data, "dtype") and not isinstance(data, np.ndarray):
        if getattr(data.dtype, "kind", "O") in "iuf":  # pandas numeric data: NA becomes NaN
            data = data.to_numpy(dtype=float, na_value=np.nan)
    arr = np.asarray(data)
    kind = arr.dtype.kind
    if kind == "c":
        raise TypeError(f"{name} are complex ({arr.dtype}); pass real numbers: the real part, the "
                        "modulus or another real quantity, explicitly")
    if kind in "mM":
        raise TypeError(f"{name} are dates or times ({arr.dtype}), not numbers; convert them to a "
                        "real quantity (e.g. durations in seconds) first")
    if kind in "bSUV":
        raise TypeError(f"{name} must be real numbers, got an array of dtype {arr.dtype}")
    if kind == "O":
        try:
            values = np.array(arr, dtype=float).ravel()
        except (TypeError, ValueError):
            flat = arr.ravel()
            bad = next((v for v in flat if not isinstance(v, int | float | np.integer | np.floating)
                        or isinstance(v, bool)), None)
            raise TypeError(f"{name} must be real numbers, got an object array holding {bad!r} "
                            f"({type(bad).__name__}); convert missing values to NaN first (e.g. "
                            "series.to_numpy(dtype=float, na_value=np.nan))") from None
        if any(isinstance(v, bool | np.bool_) for v in arr.ravel()):
            raise TypeError(f"{name} must be real numbers, got booleans in an object array")
    else:
        values = np.array(arr, dtype=float, copy=True).ravel()
    return values, keep
