"""Tail-accurate access to a continuous distribution: the parent of the maxima, order
statistics and damage probabilities (:mod:`glstat.extremes`, :mod:`glstat.extremes.damage`).

``TailAccess(dist).tail(x)`` gives ``(F, log F, S, log S)`` at x, each to a few ulp in both
tails: ``log F`` is ``log1p(-sf)`` where ``sf < 1/2`` and ``logcdf`` elsewhere, and the
parent's ``logsf`` takes over where ``sf`` may underflow. ``lower(x)`` and ``upper(x)`` give
one side each, ``(F, log F)`` and ``(S, log S)``, with the same values and without the
other side's logarithms (the minimum and the maximum need one side only).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.stats import rv_continuous

from ..distributions.gld import GLD
from ..distributions.rv_gld import gld_fkml, gld_rs
from ..distributions.scipy_base import rv_continuous_frozen
from ..regions import rs_lambda2_sign

__all__ = ["SF_TINY", "TailAccess", "log1mexp"]

_LN2 = math.log(2.0)
#: below this the parent's sf may be subnormal or zero: its logsf takes over
SF_TINY = 1e-290


def _as_fast(dist):
    """A frozen ``gld_rs``/``gld_fkml`` with scalar parameters becomes a :class:`GLD`."""
    if isinstance(dist, GLD) or not isinstance(dist, rv_continuous_frozen):
        return dist
    gen = dist.dist
    if not isinstance(gen, (type(gld_rs), type(gld_fkml))):
        return dist
    shapes, loc, scale = gen._parse_args(*dist.args, **dist.kwds)
    values = [np.asarray(v, dtype=float) for v in (*shapes, loc, scale)]
    if any(v.ndim for v in values):
        return dist
    lam3, lam4, loc, scale = (float(v) for v in values)
    if isinstance(gen, type(gld_rs)):
        sign = float(rs_lambda2_sign(lam3, lam4))
        return GLD(loc, sign / scale, lam3, lam4, param="rs")
    return GLD(loc, 1.0 / scale, lam3, lam4, param="fkml")


def _is_discrete(dist: Any) -> bool:
    """Whether ``dist`` is a discrete distribution: scipy's new infrastructure gives both kinds
    ``pmf`` and ``pdf`` and tells them apart by class; a frozen ``rv_discrete`` has no ``pdf``."""
    names = {c.__name__ for c in type(dist).__mro__}
    if "DiscreteDistribution" in names:
        return True
    if "ContinuousDistribution" in names:
        return False
    return hasattr(dist, "pmf") and not callable(getattr(dist, "pdf", None))


class TailAccess:
    """Tail-accurate access to a continuous distribution.

    Accepts a ``glstat.GLD``, a frozen ``scipy.stats`` continuous distribution, a
    ``scipy.stats`` continuous distribution without shape parameters, a new-style
    ``scipy.stats`` distribution (``logccdf``/``iccdf``/``icdf`` names), or any object with
    ``logcdf``, ``logsf`` and ``isf`` methods (``sf``, ``cdf``, ``ppf``, ``logpdf`` and
    ``support`` are used when present).
    """

    def __init__(self, dist):
        if isinstance(dist, rv_continuous):
            if dist.numargs:
                raise TypeError(
                    f"dist is the unfrozen distribution {dist.name!r} with shape parameters "
                    f"{dist.shapes}; freeze it first, e.g. scipy.stats.{dist.name}(...)"
                )
            dist = dist()
        dist = _as_fast(dist)
        self.dist = dist

        def pick(*names):
            for name in names:
                f = getattr(dist, name, None)
                if callable(f):
                    return f
            return None

        self._logcdf = pick("logcdf")
        self._logsf = pick("logsf", "logccdf")
        self._isf = pick("isf", "iccdf")
        missing = [
            name
            for name, f in (("logcdf", self._logcdf), ("logsf", self._logsf), ("isf", self._isf))
            if f is None
        ]
        discrete = _is_discrete(dist)
        if missing or discrete:
            what = "is a discrete distribution" if discrete else (
                f"lacks {', '.join(missing)}"
            )
            raise TypeError(
                f"dist must be a continuous distribution with logcdf, logsf and isf methods "
                f"(a frozen scipy.stats distribution or a glstat.GLD); {type(dist).__name__} "
                f"{what}"
            )
        self._sf = pick("sf", "ccdf")
        self._cdf = pick("cdf")
        self._ppf = pick("ppf", "icdf")
        self._logpdf = pick("logpdf")
        support = pick("support")
        if support is None:
            self.a, self.b = -np.inf, np.inf
        else:
            a, b = support()
            self.a, self.b = float(np.asarray(a)), float(np.asarray(b))

    # elementary functions with fallbacks --------------------------------------------------
    def sf(self, x):
        return np.asarray(self._sf(x) if self._sf else np.exp(self._logsf(x)), dtype=float)

    def cdf(self, x):
        return np.asarray(self._cdf(x) if self._cdf else np.exp(self._logcdf(x)), dtype=float)

    def logcdf(self, x):
        return np.asarray(self._logcdf(x), dtype=float)

    def logsf(self, x):
        return np.asarray(self._logsf(x), dtype=float)

    def logpdf(self, x):
        if self._logpdf is None:
            raise TypeError(f"{type(self.dist).__name__} has no logpdf method")
        return np.asarray(self._logpdf(x), dtype=float)

    def isf(self, q):
        return np.asarray(self._isf(q), dtype=float)

    def ppf(self, u):
        if self._ppf is None:
            return self.isf(1.0 - np.asarray(u, dtype=float))
        return np.asarray(self._ppf(u), dtype=float)

    def quantile(self, u, q):
        """Q at the probability u whose complement is q (both given, each accurate)."""
        u, q = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(q, dtype=float))
        out = np.full(u.shape, np.nan)
        low = u <= 0.5
        high = q < 0.5
        if low.any():
            out[low] = self.ppf(u[low])
        if high.any():
            out[high] = self.isf(q[high])
        return out

    def _sf_split(self, x):
        """x flattened, a copy of the sf there, the mask where it is >= 1/2 and the cdf there."""
        x = np.asarray(x, dtype=float).reshape(-1)
        s = np.array(self.sf(x), dtype=float, copy=True).reshape(x.shape)
        lower = s >= 0.5
        fl = self.cdf(x[lower]).reshape(-1) if lower.any() else np.empty(0)
        return x, s, lower, fl

    def lower(self, x):
        """(F, log F) at x, as :meth:`tail` gives them, without the upper tail's logarithm."""
        shape = np.shape(x)
        x, s, lower, fl = self._sf_split(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            f = 1.0 - s
            logf = np.log1p(-s)
        if lower.any():
            with np.errstate(divide="ignore"):
                lfl = np.log(fl)
            deep = fl < SF_TINY
            if deep.any():
                lfl[deep] = self.logcdf(x[lower][deep])
            f[lower] = fl
            logf[lower] = lfl
        return f.reshape(shape), logf.reshape(shape)

    def upper(self, x):
        """(S, log S) at x with ``log S`` accurate in both tails: ``log1p(-F)`` where
        ``S >= 1/2``, ``log S`` below and the parent's ``logsf`` where S may underflow."""
        shape = np.shape(x)
        x, s, lower, fl = self._sf_split(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            logs = np.log(s)
            if lower.any():
                logs[lower] = np.log1p(-fl)
        deep = s < SF_TINY
        if deep.any():
            logs[deep] = self.logsf(x[deep])
        return s.reshape(shape), logs.reshape(shape)

    def tail(self, x):
        """(F, log F, S, log S) at x, each to a few ulp in both tails."""
        x = np.asarray(x, dtype=float)
        shape = x.shape
        x = x.reshape(-1)
        s = np.array(self.sf(x), dtype=float, copy=True).reshape(x.shape)
        with np.errstate(divide="ignore", invalid="ignore"):
            f = 1.0 - s
            logf = np.log1p(-s)
            logs = np.log(s)
        lower = s >= 0.5
        if lower.any():
            xl = x[lower]
            fl = self.cdf(xl).reshape(xl.shape)
            with np.errstate(divide="ignore"):
                lfl = np.log(fl)
            deep = fl < SF_TINY
            if deep.any():
                lfl[deep] = self.logcdf(xl[deep])
            f[lower] = fl
            logf[lower] = lfl
        deep = s < SF_TINY
        if deep.any():
            logs[deep] = self.logsf(x[deep])
        return f.reshape(shape), logf.reshape(shape), s.reshape(shape), logs.reshape(shape)


def log1mexp(y):
    """``log(1 - exp(y))`` for y <= 0, accurate for all y (``-inf`` at 0)."""
    y = np.asarray(y, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(y > -_LN2, np.log(-np.expm1(y)), np.log1p(-np.exp(y)))
