"""Integrity and damage probabilities of a surface, and their growth with area.

With F the distribution of the contact pressure at one of the n grid points of the analysed
area, an area ``k`` times larger (an ergodic surface) stays below the threshold ``Pd`` at all of
its ``k n`` points with probability (DESIGN §1 steps 7–8)

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

from .extremes import _Parent

__all__ = ["damage_probability", "guaranteed_threshold", "integrity_probability"]

_OUTSIDE = ("raise", "limit")


def _parents(dist) -> tuple[list[_Parent], bool]:
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
    return [_Parent(d) for d in dist], many


def _positive(name, value, *, at_least_one=False):
    arr = np.asarray(value, dtype=float)
    bad = ~np.isfinite(arr) | ((arr < 1) if at_least_one else (arr <= 0))
    if bad.any():
        first = arr[bad].ravel()[0] if arr.ndim else float(arr)
        need = "finite and >= 1" if at_least_one else "finite and > 0"
        raise ValueError(f"{name} must be {need}; got {first}")
    return arr


def _log_integrity(dist, threshold, n, area_factor, outside_support):
    if outside_support not in _OUTSIDE:
        raise ValueError(f"outside_support must be one of {_OUTSIDE}, got {outside_support!r}")
    parents, many = _parents(dist)
    n = _positive("n", n, at_least_one=True)
    k = _positive("area_factor", area_factor)
    x = np.asarray(threshold, dtype=float)
    if not np.isfinite(x).all():
        raise ValueError(f"threshold must be finite; got {x[~np.isfinite(x)].ravel()[0]}")
    kn = k * n
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
        out.append(np.broadcast_to(kn * logf, shape))
    return np.stack(out) if many else out[0]


def integrity_probability(
    dist,
    threshold,
    n,
    area_factor=1.0,
    *,
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
    n : array_like
        Number of points of the analysed area (>= 1).
    area_factor : array_like, optional
        k, the ratio of the area of interest to the analysed one (> 0). Default 1.
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
    y = _log_integrity(dist, threshold, n, area_factor, outside_support)
    out = np.exp(y)
    return out[()] if out.ndim == 0 else out


def damage_probability(
    dist,
    threshold,
    n,
    area_factor=1.0,
    *,
    outside_support: str = "raise",
):
    """Probability that some point of an area exceeds ``threshold``: ``1 - F^(k n)``.

    Computed as ``-expm1(k n log F(threshold))``, so it keeps full relative accuracy when
    it is tiny (e.g. 1e-15) and is correctly rounded when it is close to 1 (its complement
    is then :func:`integrity_probability`, which is relatively accurate).

    Parameters
    ----------
    dist, threshold, n, area_factor, outside_support
        As for :func:`integrity_probability`.

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
    y = _log_integrity(dist, threshold, n, area_factor, outside_support)
    out = -np.expm1(y)
    return out[()] if out.ndim == 0 else out


def guaranteed_threshold(dist, n, probability, area_factor=1.0):
    """Level that all ``k n`` points stay below with a given probability: ``Q(p^(1/(k n)))``.

    Parameters
    ----------
    dist : frozen continuous distribution, or a sequence of them
        As for :func:`integrity_probability`.
    n : array_like
        Number of points of the analysed area (>= 1).
    probability : array_like
        Required integrity probability p, strictly between 0 and 1.
    area_factor : array_like, optional
        k, the ratio of the area of interest to the analysed one (> 0). Default 1.

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
    n = _positive("n", n, at_least_one=True)
    k = _positive("area_factor", area_factor)
    p = np.asarray(probability, dtype=float)
    bad = ~((p > 0) & (p < 1))
    if bad.any():
        first = p[bad].ravel()[0] if p.ndim else float(p)
        raise ValueError(f"probability must be strictly between 0 and 1; got {first}")
    t = np.log(p) / (k * n)
    u = np.exp(t)
    q = -np.expm1(t)
    out = [par.quantile(u, q) for par in parents]
    res = np.stack(out) if many else out[0]
    return res[()] if res.ndim == 0 else res
