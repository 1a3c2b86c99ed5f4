"""The statistics of a sample against one distribution.

The probability integral transform (:func:`pit`), the Kolmogorov–Smirnov, Anderson–Darling
and Cramér–von Mises statistics (:func:`edf_statistics`), the binned Pearson chi-square, all
four at once (:func:`model_statistics`), and the limiting Anderson–Darling distribution for
known parameters (:func:`ad_asymptotic_sf`).
"""

from __future__ import annotations

import math

import numpy as np

from .._fit_engine.evaluate import gld_evaluate
from ..distributions.gld import GLD
from .inputs import as_float_array

__all__ = ["ad_asymptotic_sf", "check_bins", "edf_statistics", "evaluate_quietly", "model_statistics", "pit"]

_LOG_HALF = math.log(0.5)


# ---------------------------------------------------------------------------------------------
# EDF statistics
# ---------------------------------------------------------------------------------------------
def evaluate_quietly(dist, what: str, x) -> np.ndarray:
    """``dist.<what>(x)`` as a float array, without warnings.

    This runs in the bootstrap replicates, possibly in worker threads, so it never touches
    the process-wide warning filters: a GLD is evaluated by the compiled kernels directly
    (points where the inversion of Q reached its limit keep the best estimate), other
    distributions under ``numpy.errstate`` (thread-local).

    Parameters
    ----------
    dist : frozen continuous distribution
        A :class:`glstat.GLD` or anything with the method ``what``.
    what : str
        The method: ``"cdf"``, ``"sf"``, ``"logcdf"``, ``"logsf"``, ``"pdf"``, ``"logpdf"``,
        ``"ppf"``, ...
    x : array_like
        Where to evaluate it (points in data units, or probabilities for ``ppf``).

    Returns
    -------
    ndarray
        The values, float.
    """
    if isinstance(dist, GLD) and what in ("cdf", "sf", "logcdf", "logsf", "pdf", "logpdf"):
        return gld_evaluate(dist.param, what, x, dist.lambdas)[0]
    with np.errstate(all="ignore"):
        return np.asarray(getattr(dist, what)(x), dtype=float)


def pit(dist, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Probability integral transform of a sorted sample.

    Parameters
    ----------
    dist : frozen continuous distribution
        Anything with ``logcdf`` and ``logsf``.
    x : ndarray
        The sorted sample, in the units of ``dist``.

    Returns
    -------
    u, logf, logs : ndarray
        ``u = F(x)``, ``log F(x)`` and ``log(1 - F(x))``, with the shape of ``x``. ``u`` is
        taken from log F below the median and from log(1 - F) above it, so that it carries
        the accuracy of whichever tail it lies in.
    """
    logf = evaluate_quietly(dist, "logcdf", x).reshape(x.shape)
    logs = evaluate_quietly(dist, "logsf", x).reshape(x.shape)
    with np.errstate(all="ignore"):
        u = np.where(logf <= _LOG_HALF, np.exp(logf), -np.expm1(logs))
    return u, logf, logs


def _edf_from_pit(u: np.ndarray, logf: np.ndarray, logs: np.ndarray) -> tuple[float, float, float]:
    n = u.size
    i = np.arange(1, n + 1, dtype=float)
    d = max(float(np.max(i / n - u)), float(np.max(u - (i - 1) / n)))
    with np.errstate(invalid="ignore"):
        terms = (2.0 * i - 1.0) * (logf + logs[::-1])
    if np.any(np.isnan(terms)):
        a2 = math.nan
    elif np.any(np.isneginf(terms)):
        a2 = math.inf
    else:
        a2 = -n - math.fsum(terms) / n
    w2 = 1.0 / (12.0 * n) + math.fsum(((2.0 * i - 1.0) / (2.0 * n) - u) ** 2)
    return d, a2, w2


def edf_statistics(data, dist) -> tuple[float, float, float]:
    """Kolmogorov–Smirnov, Anderson–Darling and Cramér–von Mises statistics of a sample.

    Parameters
    ----------
    data : array_like
        Finite sample (any shape; flattened), in the units of ``dist``.
    dist : frozen continuous distribution
        Anything with ``logcdf`` and ``logsf`` (a :class:`glstat.GLD`, a frozen
        ``scipy.stats`` distribution).

    Returns
    -------
    ks, ad, cvm : float
        Dimensionless. With ``u_i = F(x_(i))`` for the sorted sample:
        ``ks = max_i max(i/n - u_i, u_i - (i-1)/n)``;
        ``ad = A² = -n - (1/n) Σ (2i-1) [ln F(x_(i)) + ln(1 - F(x_(n+1-i)))]``;
        ``cvm = W² = 1/(12n) + Σ (u_i - (2i-1)/(2n))²``.
        ``A²`` uses ``logcdf`` and ``logsf``, so it stays finite when tail probabilities
        underflow; it is ``inf`` only when a point lies outside the support.

    Raises
    ------
    ValueError
        Empty or non-finite data.
    TypeError
        Non-numeric data.
    """
    x = as_float_array(data)
    if x.size == 0:
        raise ValueError("data are empty: the EDF statistics need at least one point")
    if not np.all(np.isfinite(x)):
        raise ValueError("data contain non-finite values (NaN or inf)")
    x = np.sort(x)
    return _edf_from_pit(*pit(dist, x))


# ---------------------------------------------------------------------------------------------
# binned chi-square
# ---------------------------------------------------------------------------------------------
def _n_cells(n: int, bins) -> int:
    """Number of cells for ``bins`` = "auto" or an integer (equiprobable under the model)."""
    if isinstance(bins, str):
        if bins != "auto":
            raise ValueError(f"bins must be 'auto', an integer or a sequence of cut points, got {bins!r}")
        # Moore's 2 n^(2/5) equiprobable cells, at most n/5 so that every expected count is >= 5
        return int(min(math.ceil(2.0 * n**0.4), n // 5))
    m = int(bins)
    if m != bins or m < 2:
        raise ValueError(f"an integer bins must be >= 2, got {bins!r}")
    return m


def check_bins(bins):
    """The chi-square cells as given to :func:`glstat.gof_report`, checked.

    Parameters
    ----------
    bins : "auto", int or sequence of float
        ``"auto"``, a number of equiprobable cells (>= 2), or increasing finite cut points.

    Returns
    -------
    str, int or ndarray
        ``"auto"``, the integer, or the cut points as a float array.

    Raises
    ------
    ValueError
        Another string, an integer below 2 or not integral, or cut points that are not finite
        and strictly increasing.
    """
    if isinstance(bins, str):
        _n_cells(10, bins)
        return bins
    if np.ndim(bins) == 0:
        _n_cells(10, bins)
        return int(bins)
    cuts = np.asarray(bins, dtype=float).ravel()
    if cuts.size < 1 or not np.all(np.isfinite(cuts)) or np.any(np.diff(cuts) <= 0):
        raise ValueError("bins as a sequence must be finite, strictly increasing cut points (at least one)")
    return cuts


def _chi_square(dist, x: np.ndarray, bins) -> tuple[float, int]:
    """Pearson chi-square of sorted ``x`` and the number of cells (0 when too few points)."""
    n = x.size
    if isinstance(bins, np.ndarray):
        cuts = bins
        cdf = evaluate_quietly(dist, "cdf", cuts)
        sf = evaluate_quietly(dist, "sf", cuts)
        # cell probabilities from the cdf below the median and the sf above it
        p = np.empty(cuts.size + 1)
        p[0] = cdf[0]
        p[-1] = sf[-1]
        p[1:-1] = np.where(cdf[1:] <= 0.5, cdf[1:] - cdf[:-1], sf[:-1] - sf[1:])
        expected = n * p
    else:
        m = _n_cells(n, bins)
        if m < 2:
            return math.nan, 0
        cuts = evaluate_quietly(dist, "ppf", np.arange(1, m) / m)
        expected = np.full(m, n / m)
    observed = np.diff(np.concatenate(([0], np.searchsorted(x, cuts, side="right"), [n])))
    with np.errstate(divide="ignore", invalid="ignore"):
        contrib = np.where(observed == expected, 0.0, (observed - expected) ** 2 / expected)
    return float(np.sum(contrib)), int(expected.size)


# ---------------------------------------------------------------------------------------------
# all statistics of one model
# ---------------------------------------------------------------------------------------------
def model_statistics(dist, x: np.ndarray, bins) -> dict[str, float]:
    """The EDF statistics and the binned chi-square of a sorted sample against one model.

    Parameters
    ----------
    dist : frozen continuous distribution
        The model.
    x : ndarray
        The sorted finite sample, in the units of ``dist``.
    bins : "auto", int or ndarray
        The cells, as returned by :func:`check_bins`.

    Returns
    -------
    dict
        ``ks``, ``ad``, ``cvm`` (see :func:`edf_statistics`), ``chi2`` (Pearson) and
        ``chi2_bins`` (the number of cells; 0 with NaN ``chi2`` when there are too few points
        for two cells).
    """
    u, logf, logs = pit(dist, x)
    d, a2, w2 = _edf_from_pit(u, logf, logs)
    chi2, cells = _chi_square(dist, x, bins)
    return {"ks": d, "ad": a2, "cvm": w2, "chi2": chi2, "chi2_bins": cells}


# ---------------------------------------------------------------------------------------------
# A² asymptotic distribution (parameters known)
# ---------------------------------------------------------------------------------------------
def ad_asymptotic_sf(a2: float) -> float:
    """Upper-tail probability of the limiting Anderson–Darling distribution (case 0).

    Parameters
    ----------
    a2 : float
        The statistic A² (dimensionless).

    Returns
    -------
    float
        P(A² > a2) in the limit of a large sample from a fully specified distribution: the
        approximation of the limiting distribution function by Marsaglia & Marsaglia,
        *Evaluating the Anderson–Darling distribution*, J. Stat. Softw. 9(2), 2004 (absolute
        error below about 2e-6). 1 for a2 <= 0, 0 for +inf, NaN for NaN.
    """
    z = float(a2)
    if not math.isfinite(z):
        return 0.0 if z > 0 else math.nan
    if z <= 0:
        return 1.0
    if z < 2.0:
        poly = 2.00012 + (0.247105 - (0.0649821 - (0.0347962 - (0.011672 - 0.00168691 * z) * z) * z) * z) * z
        return float(min(1.0, max(0.0, 1.0 - math.exp(-1.2337141 / z) / math.sqrt(z) * poly)))
    poly = 1.0776 - (2.30695 - (0.43424 - (0.082433 - (0.008056 - 0.0003146 * z) * z) * z) * z) * z
    return float(-math.expm1(-math.exp(poly)))
