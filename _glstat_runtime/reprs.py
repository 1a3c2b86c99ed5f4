"""Short texts of values for the ``repr`` of result objects: never a whole array."""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["short_values"]

#: Arrays of at most this many values are shown in full.
SHOWN = 4


def short_values(values: Any, digits: int = 6) -> str:
    """A short text of a number or an array, for a ``repr``.

    Parameters
    ----------
    values : float or array_like
        The values (None gives ``"None"``).
    digits : int, optional
        Significant digits of each number shown.

    Returns
    -------
    str
        A scalar as a number, up to :data:`SHOWN` values as a list, a larger array as its
        shape and the range of its finite values: at most about 60 characters.

    Examples
    --------
    >>> short_values(0.123456789)
    '0.123457'
    >>> short_values([1, 10])
    '[1, 10]'
    >>> short_values(np.arange(10_000.0))
    '<10000 values in [0, 9999]>'
    """
    if values is None:
        return "None"
    a = np.asarray(values)
    if not np.issubdtype(a.dtype, np.number) and a.dtype != bool:
        return f"<array of shape {a.shape}, dtype {a.dtype}>"
    a = a.astype(float)
    if a.size <= SHOWN:
        text = [f"{v:.{digits}g}" for v in a.ravel()]
        return text[0] if a.ndim == 0 else "[" + ", ".join(text) + "]"
    shape = str(a.size) if a.ndim == 1 else "x".join(str(s) for s in a.shape)
    finite = a[np.isfinite(a)]
    if finite.size == 0:
        return f"<{shape} values, none finite>"
    return f"<{shape} values in [{finite.min():.{digits}g}, {finite.max():.{digits}g}]>"
