"""The machinery shared by the distributions of the maximum and of the order statistics
(:mod:`glstat.extremes`): a shape-free ``rv_continuous`` whose functions come from a parent
distribution through its quantile at a probability and its complement, and its frozen
distribution with direct methods.

Moments integrate the distribution's own quantile function over its uniform variable
``v in (0, 1)`` after the substitution ``v = 1 / (1 + exp(-z))``:
``E[g(X)] = integral g(Q_X(v(z))) v (1 - v) dz`` over the real line, by the trapezoidal rule
on ``z in [-700, 700]`` with step 1/4 (the module docstring of :mod:`glstat.extremes` gives
the accuracy and when a moment is NaN).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import rv_continuous

from ..distributions.scipy_base import rv_continuous_frozen

__all__ = ["ExtremeFrozen", "ExtremeGen", "flat"]


# nodes of the moment quadrature in z = logit(v)
_QUAD_H = 0.25
_QUAD_Z = np.arange(-2800, 2801) * _QUAD_H
_QUAD_LOGV = -np.logaddexp(0.0, -_QUAD_Z)
_QUAD_LOG1MV = -np.logaddexp(0.0, _QUAD_Z)
_QUAD_W = np.exp(_QUAD_LOGV + _QUAD_LOG1MV) * _QUAD_H


def flat(method):
    """Run ``method`` on a 1-D float copy of its argument and restore the argument's shape."""

    def wrapper(self, x):
        x = np.asarray(x, dtype=float)
        out = np.asarray(method(self, x.reshape(-1)), dtype=float)
        return out.reshape(x.shape)

    wrapper.__name__ = method.__name__
    wrapper.__doc__ = method.__doc__
    return wrapper


def _scalar_out(out):
    """A 0-d array as a numpy scalar; any other array as it is."""
    return out[()] if out.ndim == 0 else out


def _valid_range(g):
    """Largest index range ``[lo, hi)`` around the middle node where g is usable.

    g holds quantiles at increasing probabilities; the range grows outwards from the middle
    while the values are finite and non-decreasing up to a relative 1e-10.
    """
    mid = g.size // 2
    if not np.isfinite(g[mid]):
        return mid, mid
    with np.errstate(invalid="ignore", over="ignore"):
        tol = 1e-10 * np.maximum(np.abs(g[1:]), np.abs(g[:-1]))
        step_ok = np.isfinite(g[1:]) & np.isfinite(g[:-1]) & (g[1:] >= g[:-1] - tol)
    # step_ok[i] refers to the pair (i, i + 1)
    up = np.flatnonzero(~step_ok[mid:])
    hi = g.size if up.size == 0 else mid + int(up[0]) + 1
    down = np.flatnonzero(~step_ok[:mid])
    lo = 0 if down.size == 0 else int(down[-1]) + 1
    return lo, hi



class ExtremeGen(rv_continuous):
    """Shape-free ``rv_continuous`` whose functions come from a parent distribution."""

    def __init__(self, parent=None, order=None, **kwargs):
        if parent is None or order is None:
            raise TypeError("the parent distribution and the order parameters are required")
        self._parent = parent
        self._order = order
        kwargs.setdefault("a", parent.a)
        kwargs.setdefault("b", parent.b)
        super().__init__(**kwargs)
        self._moment_cache = None

    def _updated_ctor_param(self):
        dct = super()._updated_ctor_param()
        dct["parent"] = self._parent
        dct["order"] = self._order
        return dct

    # functions of v and of its complement, both accurate -------------------------------
    # Subclasses define ``_quantile_vq(v, q, logv, logq)``: the quantile at probability v with
    # complement q (and their logs), all accurate; the methods below are written in terms of it.

    @flat
    def _ppf(self, v):
        v = np.asarray(v, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            out = self._quantile_vq(v, 1.0 - v, np.log(v), np.log1p(-v))
        return np.where((v >= 0) & (v <= 1), out, np.nan)

    @flat
    def _isf(self, q):
        q = np.asarray(q, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            out = self._quantile_vq(1.0 - q, q, np.log1p(-q), np.log(q))
        return np.where((q >= 0) & (q <= 1), out, np.nan)

    @flat
    def _cdf(self, x):
        return np.exp(self._logcdf(x))

    @flat
    def _pdf(self, x):
        return np.exp(self._logpdf(x))

    def _rvs(self, size=None, random_state=None):
        v = random_state.uniform(size=size)
        return self._ppf(v)

    # moments by quadrature over the order statistic's own uniform variable ------------------
    def _quad_values(self):
        """Quantiles at the quadrature nodes and the range ``[lo, hi)`` where they are valid.

        Parents evaluated at tail probabilities near ``exp(-700)`` may return values that
        are infinite, NaN, of the wrong sign or saturated (scipy's ``t.ppf(1e-300)`` is
        ``+inf``). Starting from the median node, the range extends outwards while the
        quantiles are finite and non-decreasing (to a relative 1e-10, which allows rounding
        noise), so every node outside it is dropped. Whether the dropped tails matter is
        decided by :meth:`_quad_expect`.
        """
        if self._moment_cache is None:
            g = np.asarray(
                self._quantile_vq(
                    np.exp(_QUAD_LOGV), np.exp(_QUAD_LOG1MV), _QUAD_LOGV, _QUAD_LOG1MV
                ),
                dtype=float,
            )
            self._moment_cache = (g, *_valid_range(g))
        return self._moment_cache

    def _quad_expect(self, h):
        """``E[h(X)]`` by the trapezoidal rule in ``z = logit(v)``; NaN if it does not exist.

        The sum runs over the valid nodes (:meth:`_quad_values`). It is accepted only when
        the terms at both ends of that range are below 1e-15 of the sum of magnitudes, so
        that the neglected tails (whose weight falls geometrically beyond the ends) do not
        change the result: a moment that does not exist has terms that do not decay, and
        gives NaN.
        """
        g, lo, hi = self._quad_values()
        if hi - lo < 32:
            return np.nan
        with np.errstate(over="ignore", invalid="ignore"):
            terms = h(g[lo:hi]) * _QUAD_W[lo:hi]
        if not np.all(np.isfinite(terms)):
            return np.nan
        total = math.fsum(terms)
        scale = math.fsum(np.abs(terms))
        ends = max(abs(terms[:8]).max(), abs(terms[-8:]).max())
        if ends > 1e-15 * scale:
            return np.nan  # the moment does not exist, or its tail reaches past the range
        return total

    def _stats(self):
        mean = self._quad_expect(lambda g: g)
        if not math.isfinite(mean):
            return np.nan, np.nan, np.nan, np.nan
        m2 = self._quad_expect(lambda g: (g - mean) ** 2)
        m3 = self._quad_expect(lambda g: (g - mean) ** 3)
        m4 = self._quad_expect(lambda g: (g - mean) ** 4)
        skew = m3 / m2**1.5 if m2 > 0 else np.nan
        kurt = m4 / m2**2 - 3.0 if m2 > 0 else np.nan
        return mean, m2, skew, kurt

    def _munp(self, k):
        return self._quad_expect(lambda g: g**k)


class ExtremeFrozen(rv_continuous_frozen):
    """Frozen order-statistic distribution with direct (argument-check-free) methods."""

    def __init__(self, gen: ExtremeGen):
        super().__init__(gen)

    @property
    def parent(self):
        """The distribution of a single draw."""
        return self.dist._parent.dist

    def _call(self, name, x):
        out = getattr(self.dist, name)(np.asarray(x, dtype=float))
        return _scalar_out(np.asarray(out, dtype=float))

    def cdf(self, x):
        """Cumulative distribution function."""
        return self._call("_cdf", x)

    def sf(self, x):
        """Survival function, accurate in the upper tail."""
        return self._call("_sf", x)

    def logcdf(self, x):
        """Natural log of the cdf."""
        return self._call("_logcdf", x)

    def logsf(self, x):
        """Natural log of the survival function."""
        return self._call("_logsf", x)

    def pdf(self, x):
        """Probability density, in 1/(units of x)."""
        return self._call("_pdf", x)

    def logpdf(self, x):
        """Natural log of the density."""
        return self._call("_logpdf", x)

    def ppf(self, q):
        """Quantile function; NaN outside [0, 1]."""
        return self._call("_ppf", q)

    def isf(self, q):
        """Inverse survival function, accurate for small q; NaN outside [0, 1]."""
        return self._call("_isf", q)

    def median(self):
        """Median (same units as the parent)."""
        return float(self.ppf(0.5))

    def interval(self, confidence=None):
        """Central interval with the given probability content (upper end via ``isf``).

        Parameters
        ----------
        confidence : float
            Probability content in [0, 1], e.g. 0.9.

        Returns
        -------
        lower, upper : float
        """
        c = np.asarray(confidence, dtype=float)
        if c.ndim or not (0 <= float(c) <= 1):
            raise ValueError(f"confidence must be a scalar in [0, 1], got {confidence!r}")
        tail = (1.0 - float(c)) / 2.0
        return float(self.ppf(tail)), float(self.isf(tail))

    def support(self):
        """(lower, upper) end of the support."""
        return float(self.dist.a), float(self.dist.b)
