"""Integrity and damage probabilities of a surface, and their growth with area.

With F the distribution of the contact pressure at one of the n grid points of the analysed
area, an area ``k`` times larger (an ergodic surface) stays below the threshold ``Pd`` at all of
its ``k n`` points with probability (docs/method.md §7)

``integrity = F(Pd)^(k n) = exp(k n log F(Pd))``, ``damage = 1 - integrity``,

and the pressure that a ``k``-times area stays below with probability ``p`` is
``Q(p^(1/(k n)))``. ``log F`` is ``log1p(-sf)`` in the upper half and ``logcdf`` below it, the
damage probability is ``-expm1(k n log F)``, and ``1 - p^(1/(k n))`` is ``-expm1(log(p)/(k n))``
handed to ``isf``: no ``1 - x`` is ever formed from a number close to 1.

Several distributions at once (bootstrap hook)
----------------------------------------------
Every function here accepts, instead of one distribution,

* a list or tuple of distributions, or
* any object with a method ``__glstat_distributions__()`` returning such a sequence (the
  protocol through which a bootstrap result hands over its B fitted distributions),

and then returns an array with one leading axis over the distributions (length B) followed
by the broadcast shape of the other arguments; summaries such as confidence intervals are
taken over that axis by the caller.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from _glstat_runtime.validation import draws_or_count

from .counts import as_count
from .tails import TailAccess

__all__ = ["damage_probability", "guaranteed_threshold", "integrity_probability", "return_level",
           "return_period"]

_OUTSIDE = ("raise", "limit")


def _parents(dist) -> tuple[list[TailAccess], bool]:
    """The distributions to evaluate and whether a leading axis over them is wanted."""
    hook = getattr(dist, "__glstat_distributions__", None)
    if callable(hook):
        dist = list(hook())
        many = True
    elif isinstance(dist, Sequence) and not isinstance(dist, (str, bytes)):
        dist = list(dist)
        many = True
    else:
        dist = [dist]
        many = False
    if not dist:
        raise ValueError("dist is an empty sequence of distributions")
    return [TailAccess(d) for d in dist], many


def _positive(name, value, *, at_least_one=False):
    arr = np.asarray(value, dtype=float)
    bad = ~np.isfinite(arr) | ((arr < 1) if at_least_one else (arr <= 0))
    if bad.any():
        first = arr[bad].ravel()[0] if arr.ndim else float(arr)
        need = "finite and >= 1" if at_least_one else "finite and > 0"
        raise ValueError(f"{name} must be {need}; got {first}")
    return arr


def _draws(n, count):
    """(n as an array, None) for a fixed number of draws, or (None, CountDistribution)."""
    draws_or_count(n, count)
    if count is not None:
        return None, as_count(count)
    if n is None:
        raise TypeError("n (the number of points of the analysed area) or count (a random number "
                        "of them) is required")
    return _positive("n", n, at_least_one=True), None


def _log_integrity(dist, threshold, n, area_factor, outside_support, count=None, damage=False):
    """log integrity (or, with ``damage=True``, the damage probability) per distribution."""
    if outside_support not in _OUTSIDE:
        raise ValueError(f"outside_support must be one of {_OUTSIDE}, got {outside_support!r}")
    parents, many = _parents(dist)
    n, cnt = _draws(n, count)
    k = _positive("area_factor", area_factor)
    x = np.asarray(threshold, dtype=float)
    if not np.isfinite(x).all():
        raise ValueError(f"threshold must be finite; got {x[~np.isfinite(x)].ravel()[0]}")
    kn = k if cnt is not None else k * n
    shape = np.broadcast_shapes(x.shape, kn.shape)
    out = []
    for i, p in enumerate(parents):
        if outside_support == "raise":
            below = x < p.a
            above = x > p.b
            if below.any() or above.any():
                which = f"distribution {i} " if many else ""
                value = x[below].ravel()[0] if below.any() else x[above].ravel()[0]
                side, limit = ("below the lower", 0.0) if below.any() else ("above the upper", 1.0)
                raise ValueError(
                    f"threshold {value:g} is {side} end of the support [{p.a:g}, {p.b:g}] of "
                    f"{which}dist, where F is exactly {limit:g}; pass outside_support='limit' "
                    "to accept the limiting probabilities 0 and 1"
                )
        _, logf, _, _ = p.tail(x)  # evaluated once per threshold, then broadcast
        if cnt is None:
            y = kn * logf
            y = -np.expm1(y) if damage else y
        elif damage:
            y = cnt.damage(logf, k)
        else:
            y = cnt.log_integrity(logf, k)
        out.append(np.broadcast_to(y, shape))
    return np.stack(out) if many else out[0]


def integrity_probability(
    dist,
    threshold,
    n=None,
    area_factor=1.0,
    *,
    count=None,
    outside_support: str = "raise",
):
    """Probability that no point of an area exceeds ``threshold``: ``F(threshold)^(k n)``.

    Parameters
    ----------
    dist : frozen continuous distribution, or a sequence of them
        Distribution of the (contact) pressure at one point, e.g. a fitted ``glstat.GLD``;
        any object with ``logcdf``, ``logsf`` and ``isf`` works. A list/tuple of
        distributions, or an object with ``__glstat_distributions__()`` (module docstring),
        adds a leading axis over the distributions.
    threshold : array_like
        Pressure level, e.g. the hardness Pd, in the units of ``dist`` (e.g. MPa).
    n : array_like, optional
        Number of points of the analysed area (>= 1), one per output (broadcast).
    area_factor : array_like, optional
        k, the ratio of the area of interest to the analysed one (> 0). Default 1.
    count : glstat.PoissonCount, glstat.ObservedCounts or frozen scipy.stats discrete, optional
        A random number N of points (e.g. asperities in contact) instead of ``n``: the
        integrity is ``E[F^N]^k`` (``F^0 = 1``: an area without contact is intact); for a
        Poisson count ``exp(-k mu (1 - F))``. See :mod:`glstat.extremes.counts` for the area rule.
    outside_support : {"raise", "limit"}, optional
        A threshold outside the support of ``dist`` raises ``ValueError`` (default); with
        ``"limit"`` the exact limits 0 (below) and 1 (above) are returned.

    Returns
    -------
    float or ndarray
        Dimensionless probability in [0, 1]; shape: broadcast of threshold, n and
        area_factor (preceded by the distribution axis for a sequence).

    Raises
    ------
    ValueError
        Non-finite threshold, n < 1 or non-finite, area_factor <= 0 or non-finite, or a
        threshold outside the support with ``outside_support="raise"``.

    Examples
    --------
    >>> import scipy.stats
    >>> from glstat import integrity_probability
    >>> round(float(integrity_probability(scipy.stats.expon(), 30.0, 1e12)), 6)  # exp(-1e12 e^-30)
    0.910669
    """
    y = _log_integrity(dist, threshold, n, area_factor, outside_support, count)
    out = np.exp(y)
    return out[()] if out.ndim == 0 else out


def damage_probability(
    dist,
    threshold,
    n=None,
    area_factor=1.0,
    *,
    count=None,
    outside_support: str = "raise",
):
    """Probability that some point of an area exceeds ``threshold``: ``1 - F^(k n)``.

    Computed as ``-expm1(k n log F(threshold))``, so it keeps full relative accuracy when
    it is tiny (e.g. 1e-15) and is correctly rounded when it is close to 1 (its complement
    is then :func:`integrity_probability`, which is relatively accurate).

    Parameters
    ----------
    dist, threshold, n, area_factor, count, outside_support
        As for :func:`integrity_probability`. With ``count`` the damage ``1 - E[F^N]^k`` is
        summed from the positive terms ``P(N = n_j) (1 - F^(n_j))``, so it keeps full
        relative accuracy when tiny.

    Returns
    -------
    float or ndarray
        Dimensionless probability in [0, 1], shaped as for :func:`integrity_probability`.

    Raises
    ------
    ValueError
        As for :func:`integrity_probability`.

    Examples
    --------
    >>> import scipy.stats
    >>> from glstat import damage_probability
    >>> f"{float(damage_probability(scipy.stats.expon(), 60.0, 1e11)):.4e}"  # ~ 1e11 e^-60
    '8.7565e-16'
    """
    out = np.asarray(_log_integrity(dist, threshold, n, area_factor, outside_support, count,
                                    damage=True), dtype=float)
    return out[()] if out.ndim == 0 else out


def guaranteed_threshold(dist, n=None, probability=None, area_factor=1.0, *, damage=None, count=None):
    """Level that all ``k n`` points stay below with a given probability: ``Q(p^(1/(k n)))``.

    Parameters
    ----------
    dist : frozen continuous distribution, or a sequence of them
        As for :func:`integrity_probability`.
    n : array_like
        Number of points of the analysed area (>= 1).
    probability : array_like, optional
        Required integrity probability p, strictly between 0 and 1.
    area_factor : array_like, optional
        k, the ratio of the area of interest to the analysed one (> 0). Default 1.
    damage : array_like, optional
        The accepted damage probability ``1 - p`` instead of ``probability``, strictly
        between 0 and 1. Use it for levels near 1: ``probability=1 - 1e-15`` is rounded to
        the double nearest to it, 8 % away in the complement, while ``damage=1e-15`` is
        exact.
    count : glstat.PoissonCount, glstat.ObservedCounts or frozen scipy.stats discrete, optional
        A random number of points instead of ``n``: the level x with ``E[F(x)^N]^k = p``
        (a Poisson count has ``x = isf(-log(p) / (k mu))``). When ``p <= P(N = 0)^k`` every
        level qualifies and the lower end of the support is returned.

    Returns
    -------
    float or ndarray
        Threshold in the units of ``dist``; broadcast shape of n, probability and
        area_factor (preceded by the distribution axis for a sequence). It is the
        ``probability``-quantile of the maximum of ``k n`` draws, so
        ``integrity_probability(dist, guaranteed_threshold(dist, n, p, k), n, k) == p``.

    Raises
    ------
    ValueError
        probability outside (0, 1), n < 1 or non-finite, area_factor <= 0 or non-finite.
    """
    parents, many = _parents(dist)
    n, cnt = _draws(n, count)
    k = _positive("area_factor", area_factor)
    if (probability is None) == (damage is None):
        raise TypeError("give exactly one of probability (the integrity level) and damage (its "
                        "complement)")
    name = "probability" if damage is None else "damage"
    p = np.asarray(probability if damage is None else damage, dtype=float)
    bad = ~((p > 0) & (p < 1))
    if bad.any():
        first = p[bad].ravel()[0] if p.ndim else float(p)
        raise ValueError(f"{name} must be strictly between 0 and 1; got {first}")
    log_p = np.log(p) if damage is None else np.log1p(-p)
    if cnt is None:
        t = log_p / (k * n)
    else:
        t = cnt.log_f_for(np.broadcast_to(log_p / k, np.broadcast_shapes(log_p.shape, k.shape)))
    with np.errstate(invalid="ignore"):
        u = np.exp(t)
        q = -np.expm1(t)
    out = [par.quantile(u, q) for par in parents]
    res = np.stack(out) if many else out[0]
    return res[()] if res.ndim == 0 else res


def _check_period(period) -> np.ndarray:
    t = np.asarray(period, dtype=float)
    bad = ~(np.isfinite(t) & (t > 1.0))
    if bad.any():
        first = t[bad].ravel()[0] if t.ndim else float(t)
        raise ValueError(f"period must be finite and > 1 (blocks: a level exceeded once in T blocks "
                         f"on average), got {first}")
    return t


def return_level(dist, period, n=None, area_factor=1.0, *, count=None):
    """Return level of period T: the level the maximum of a block exceeds with probability 1/T.

    The convention of pyextremes and of block-maxima analysis: a block is ``n`` points (or a
    random ``count`` of them) of the distribution ``dist``, times ``area_factor``; the level
    is :func:`guaranteed_threshold` with ``damage=1/T``, ``Q((1 - 1/T)^(1/(k n)))``.

    Parameters
    ----------
    dist : frozen continuous distribution, or a sequence of them
        As for :func:`integrity_probability` (e.g. a fitted ``glstat.GLD`` of the pressure
        at one point, or of block maxima with ``n=1``).
    period : array_like
        Return period T in blocks (> 1), e.g. years for annual maxima or surfaces for the
        maximum of one surface.
    n : array_like, optional
        Points per block (>= 1); default 1 (without ``count``): ``dist`` is then the
        distribution of the block maximum itself.
    area_factor : array_like, optional
        k, blocks of ``k`` times the analysed area (> 0). Default 1.
    count : glstat.PoissonCount, glstat.ObservedCounts or frozen scipy.stats discrete, optional
        A random number of points per block instead of ``n``.

    Returns
    -------
    float or ndarray
        Level in the units of ``dist``; broadcast shape of period, n and area_factor
        (preceded by the distribution axis for a sequence).

    Raises
    ------
    ValueError
        period <= 1 or non-finite, n < 1, area_factor <= 0.

    See Also
    --------
    return_period : the inverse, 1 / P(block maximum > x).

    Examples
    --------
    >>> import scipy.stats
    >>> from glstat import return_level
    >>> round(float(return_level(scipy.stats.expon(), 100.0)), 4)   # -log(1/100)
    4.6052
    """
    t = _check_period(period)
    n = 1.0 if n is None and count is None else n
    return guaranteed_threshold(dist, n, area_factor=area_factor, damage=1.0 / t, count=count)


def return_period(dist, x, n=None, area_factor=1.0, *, count=None, outside_support: str = "raise"):
    """Return period of a level: 1 / P(maximum of a block > x), in blocks.

    The inverse of :func:`return_level`: ``1 / damage_probability(dist, x, n, area_factor)``.

    Parameters
    ----------
    dist, n, area_factor, count
        As for :func:`return_level`.
    x : array_like
        Level, in the units of ``dist``.
    outside_support : {"raise", "limit"}, optional
        As for :func:`damage_probability`; with ``"limit"`` a level above the support has
        the return period ``inf`` and one below it the period 1.

    Returns
    -------
    float or ndarray
        Return period in blocks (>= 1; ``inf`` where the block maximum cannot exceed ``x``),
        shaped as for :func:`damage_probability`.

    Raises
    ------
    ValueError
        As for :func:`damage_probability`.

    Examples
    --------
    >>> import scipy.stats
    >>> from glstat import return_period
    >>> round(float(return_period(scipy.stats.expon(), 4.6051701860)), 6)   # 1 / e^-x
    100.0
    """
    n = 1.0 if n is None and count is None else n
    d = np.asarray(damage_probability(dist, x, n, area_factor, count=count, outside_support=outside_support),
                   dtype=float)
    with np.errstate(divide="ignore"):
        out = 1.0 / d
    return out[()] if out.ndim == 0 else out
