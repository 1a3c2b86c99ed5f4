"""Warning-free evaluation of a GLD given by its lambdas, for code that may run in worker threads.

:class:`glstat.GLD` methods warn (``ConvergenceWarning``) when the inversion of Q hits its
iteration limit. Silencing that with ``warnings.catch_warnings`` changes the process-wide
warning filters, which is not safe while other threads run. These helpers call the same
compiled kernels and return the number of such points instead of warning.
"""

from __future__ import annotations

import math

import numpy as np

from .._core import inverse_table, quantile_function
from .._core.arrays import writeable_input
from .kernels import shape_valid

__all__ = ["FAMILY", "gld_evaluate", "gld_support", "lambdas_valid"]

FAMILY = {"rs": quantile_function.RS, "fkml": quantile_function.FKML}

# what = 0 cdf, 1 sf, 2 logcdf, 3 logsf, 4 pdf, 5 logpdf (the kernels' codes)
_WHAT = {"cdf": 0, "sf": 1, "logcdf": 2, "logsf": 3, "pdf": 4, "logpdf": 5}
# from this many points on, the interpolation table is cheaper than the per-point solver
# (the threshold glstat.distributions uses)
_TABLE_MIN_POINTS = 2_000


def gld_evaluate(param: str, what: str, x, lambdas) -> tuple[np.ndarray, int]:
    """A cdf-type function of the GLD with ``lambdas`` at the points ``x``, without warning.

    Parameters
    ----------
    param : {"rs", "fkml"}
        Parameterisation.
    what : {"cdf", "sf", "logcdf", "logsf", "pdf", "logpdf"}
        The function.
    x : array_like
        Points, in the units of the data.
    lambdas : sequence of 4 float
        (lambda1, lambda2, lambda3, lambda4) of a valid GLD.

    Returns
    -------
    values : ndarray
        Same shape as ``x``; the density in 1/(units of the data).
    n_limit : int
        Number of points where the inversion of Q reached its iteration limit (their values
        are the best estimate found; :class:`glstat.GLD` would warn).
    """
    l1, l2, l3, l4 = (float(v) for v in lambdas)
    arr = np.asarray(x, dtype=float)
    y = writeable_input(np.ascontiguousarray(arr.ravel()))
    out = np.empty(y.shape)
    status = np.zeros(y.shape, dtype=np.int64)
    fam = FAMILY[param]
    if y.size >= _TABLE_MIN_POINTS:
        inverse_table.invert_table_kernel(y, l3, l4, fam, _WHAT[what], out, status, l1, abs(l2))
    else:
        quantile_function.invert_kernel(y, np.array([l3]), np.array([l4]), fam, _WHAT[what], out,
                                        status, l1, abs(l2))
    return out.reshape(arr.shape), int(status.sum())


def gld_support(param: str, lambdas) -> tuple[float, float]:
    """End points of the support of the GLD with ``lambdas`` (units of the data)."""
    l1, l2, l3, l4 = (float(v) for v in lambdas)
    lo = np.empty(1)
    hi = np.empty(1)
    quantile_function.support_kernel(np.array([l3]), np.array([l4]), FAMILY[param], lo, hi)
    s = 1.0 / abs(l2)
    return l1 + float(lo[0]) * s, l1 + float(hi[0]) * s


def lambdas_valid(param: str, lambdas) -> bool:
    """True when ``lambdas`` define a GLD (the conditions :func:`glstat.regions.check_lambdas`
    checks: finite values, lambda2 non-zero with the sign the RS region or FKML needs)."""
    l1, l2, l3, l4 = (float(v) for v in lambdas)
    if not (math.isfinite(l1) and math.isfinite(l2) and l2 != 0.0):
        return False
    fam = FAMILY[param]
    if not shape_valid(fam, l3, l4):
        return False
    need = float(quantile_function.rs_sign(l3, l4)) if param == "rs" else 1.0
    return (l2 > 0.0) == (need > 0.0)
