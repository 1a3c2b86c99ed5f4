"""Arrays handed to the numba kernels."""

from __future__ import annotations

import numpy as np

__all__ = ["writeable_input"]


def writeable_input(v: np.ndarray) -> np.ndarray:
    """``v`` itself when numba may take it as a writeable array, else a copy.

    The kernels only read these inputs, but numba compiles a kernel once more for read-only
    arrays (broadcast views, arrays of the user): one array type per argument keeps the
    first call's compilation (and the cached kernel) the only one. The read-only bit of a
    read-only buffer (``v.data``) is asked instead of ``flags.writeable``, which warns (FutureWarning) for
    the views ``numpy.broadcast_arrays`` returns (about 0.15 µs: the array interface, which
    does not warn either, costs 1 µs, a tenth of a scalar cdf).
    """
    return v.copy() if v.data.readonly else v
