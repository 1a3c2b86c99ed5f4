"""Distributions of the maximum and of the order statistics of n i.i.d. draws.

``maximum(dist, n)`` is the distribution of the largest of n independent draws from ``dist``:
cdf ``F(x)^n`` and quantile function ``Q(v^(1/n))``. ``order_statistic(dist, k, n)`` is the
distribution of the k-th smallest. Both return frozen ``scipy.stats`` distributions, so
``kstest``, ``probplot``, ``expect`` and other frozen-distribution code work with them.

Numerics (docs/gld.md). For n up to 1e12 and beyond, ``v^(1/n) = 1 - O(1/n)`` and ``F^n`` with
``F = 1 - O(1/n)`` lose every digit when formed directly. Here:

* ``log F`` is taken as ``log1p(-sf(x))`` where ``sf(x) < 1/2`` and as ``logcdf(x)`` elsewhere,
  so it is accurate to a few ulp in both tails;
* ``cdf = exp(n log F)``, ``sf = -expm1(n log F)``, ``pdf = exp(log n + (n - 1) log F + log f)``;
* the quantile at ``v`` uses ``t = log(v) / n``: ``Q(exp(t))`` when ``exp(t) <= 1/2``, and
  otherwise the parent's ``isf`` at ``-expm1(t) = 1 - v^(1/n)``, which never subtracts from 1;
* order statistics use the regularized incomplete beta function on whichever of ``F`` and
  ``1 - F`` is small (``I_F(k, n-k+1)`` and its reflection ``I_S(n-k+1, k)``), and invert it with
  ``betaincinv``/``betainccinv``.

Moments integrate the order statistic's own quantile function over its uniform variable
``v in (0, 1)`` after the substitution ``v = 1 / (1 + exp(-z))``:
``E[g(X)] = integral g(Q_X(v(z))) v (1 - v) dz`` over the real line. The integrand is smooth
and of unit width in ``z`` whatever n is (the concentration of ``Q(v^(1/n))`` near ``v = 1``
lives inside ``Q_X``, which is evaluated with the tail-accurate formulas above), so the
trapezoidal rule on ``z in [-700, 700]`` with step 1/4 converges geometrically and gives
double-precision moments for n = 1 as for n = 1e12. Nodes where the parent's quantile is not
finite or not monotone (scipy's ``t`` returns ``+inf`` for ``ppf(1e-300)``) are dropped by
shrinking the range outwards from the median; the result stands only if the terms at the
ends of the range that is kept are below 1e-15 of the total. A moment is NaN when it does
not exist, or when the tails are too heavy for the truncation (tail index above ~0.95 at
``|z| = 700``). The order statistics' quantiles invert the regularized incomplete beta with
``betaincinv`` and, in the deep tail where it returns NaN (p below ~1e-100 for small
parameters), with the leading term ``I_x(a, b) ~ x^a / (a B(a, b))`` refined by Newton's
method in ``log x``.
"""

from __future__ import annotations

import math
import numbers

import numpy as np
from scipy import special
from scipy.stats import rv_continuous

from ._compat import rv_continuous_frozen
from ._tails import SF_TINY as _TINY
from ._tails import TailAccess
from ._tails import log1mexp as _log1mexp

__all__ = [
    "MaximumCountDistribution",
    "MaximumDistribution",
    "OrderStatisticDistribution",
    "maximum",
    "order_statistic",
]


# nodes of the moment quadrature in z = logit(v)
_QUAD_H = 0.25
_QUAD_Z = np.arange(-2800, 2801) * _QUAD_H
_QUAD_LOGV = -np.logaddexp(0.0, -_QUAD_Z)
_QUAD_LOG1MV = -np.logaddexp(0.0, _QUAD_Z)
_QUAD_W = np.exp(_QUAD_LOGV + _QUAD_LOG1MV) * _QUAD_H


# ------------------------------------------------------------------------------------------
# parent distributions
# ------------------------------------------------------------------------------------------
def _flat(method):
    """Run ``method`` on a 1-D float copy of its argument and restore the argument's shape."""

    def wrapper(self, x):
        x = np.asarray(x, dtype=float)
        out = np.asarray(method(self, x.reshape(-1)), dtype=float)
        return out.reshape(x.shape)

    wrapper.__name__ = method.__name__
    wrapper.__doc__ = method.__doc__
    return wrapper


def _check_n(n, name="n", what="a number of draws") -> float:
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, (numbers.Real, np.ndarray)):
        raise TypeError(f"{name} must be a real number, got {type(n).__name__}")
    arr = np.asarray(n, dtype=float)
    if arr.ndim:
        raise ValueError(f"{name} must be a scalar, got an array of shape {arr.shape}")
    value = float(arr)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value}")
    if value < 1:
        raise ValueError(f"{name} must be >= 1 ({what}), got {value}")
    return value


def _scalar_out(out):
    return out[()] if out.ndim == 0 else out


def _log_betainc_small(a, b, x):
    """log I_x(a, b) for small x, from ``x^a (1-x)^b 2F1(a+b, 1; a+1; x) / (a B(a, b))``.

    The hypergeometric factor is summed as its power series ``sum_j c_j x^j`` with
    ``c_(j+1) / c_j = (a+b+j) / (a+1+j)``; where that series converges slowly
    (``x (a+b) / (a+1) > 1/2``) the log of ``scipy.special.betainc`` is used instead.
    """
    x = np.asarray(x, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        term = np.ones_like(x)
        series = np.ones_like(x)
        for j in range(60):
            term = term * x * ((a + b + j) / (a + 1.0 + j))
            series = series + term
        out = (
            a * np.log(x) + b * np.log1p(-x) - math.log(a) - special.betaln(a, b)
            + np.log(series)
        )
        slow = x * (a + b) / (a + 1.0) > 0.5
        if slow.any():
            out[slow] = np.log(special.betainc(a, b, x[slow]))
    return out


def _betaincinv_tail(a, b, logp):
    """x with ``I_x(a, b) = exp(logp)`` in the deep lower tail (``exp(logp)`` tiny).

    Starts from the leading term ``I_x ~ x^a / (a B(a, b))``, i.e.
    ``x0 = exp((log p + log a + B(a, b)) / a)`` with ``B = betaln``, and refines it by Newton's
    method on ``log I_x(a, b) - log p`` in ``y = log x``, whose derivative is
    ``x f(x) / I_x = x^a (1-x)^(b-1) / (B(a, b) I_x)``.
    """
    logp = np.asarray(logp, dtype=float)
    lbeta = special.betaln(a, b)
    y0 = np.minimum((logp + math.log(a) + lbeta) / a, 0.0)
    y = y0
    with np.errstate(over="ignore", under="ignore", invalid="ignore", divide="ignore"):
        for _ in range(8):
            x = np.exp(y)
            logi = _log_betainc_small(a, b, x)
            slope = np.exp(a * y + (b - 1.0) * np.log1p(-x) - lbeta - logi)
            step = (logi - logp) / slope
            y = np.minimum(y - step, 0.0)
        # where x underflows (or Newton has nothing to work on) the leading term stands
        y = np.where(np.isfinite(y), y, y0)
        return np.exp(y)


def _betaincinv(a, b, p, logp):
    """x with ``I_x(a, b) = p`` (``logp = log p``), finite down to the smallest p.

    ``scipy.special.betaincinv`` returns NaN (or 0) below p ~ 1e-100 for some (a, b); there
    the deep-tail inverse :func:`_betaincinv_tail` is used.
    """
    p, logp = np.broadcast_arrays(np.asarray(p, dtype=float), np.asarray(logp, dtype=float))
    with np.errstate(invalid="ignore"):
        x = np.asarray(special.betaincinv(a, b, p), dtype=float)
    bad = (p > 0) & (p < 1e-20) & (~np.isfinite(x) | (x <= 0))
    bad |= np.isnan(x) & ~np.isnan(p) & (p > 0) & (p <= 0.5)
    if bad.any():
        x = np.array(x, copy=True)
        x[bad] = _betaincinv_tail(a, b, logp[bad])
    return x


def _betainccinv(a, b, q, logq):
    """x with ``1 - I_x(a, b) = q`` (``logq = log q``), finite down to the smallest q."""
    q, logq = np.broadcast_arrays(np.asarray(q, dtype=float), np.asarray(logq, dtype=float))
    with np.errstate(invalid="ignore"):
        x = np.asarray(special.betainccinv(a, b, q), dtype=float)
    bad = (q > 0) & (q <= 0.5) & (~np.isfinite(x) | (x >= 1))
    if bad.any():
        x = np.array(x, copy=True)
        x[bad] = 1.0 - _betaincinv(b, a, q[bad], logq[bad])
    return x


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


# ------------------------------------------------------------------------------------------
# common generator and frozen machinery
# ------------------------------------------------------------------------------------------
class _ExtremeGen(rv_continuous):
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

    @_flat
    def _ppf(self, v):
        v = np.asarray(v, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            out = self._quantile_vq(v, 1.0 - v, np.log(v), np.log1p(-v))
        return np.where((v >= 0) & (v <= 1), out, np.nan)

    @_flat
    def _isf(self, q):
        q = np.asarray(q, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            out = self._quantile_vq(1.0 - q, q, np.log1p(-q), np.log(q))
        return np.where((q >= 0) & (q <= 1), out, np.nan)

    @_flat
    def _cdf(self, x):
        return np.exp(self._logcdf(x))

    @_flat
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


class _ExtremeFrozen(rv_continuous_frozen):
    """Frozen order-statistic distribution with direct (argument-check-free) methods."""

    def __init__(self, gen: _ExtremeGen):
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


# ------------------------------------------------------------------------------------------
# maximum
# ------------------------------------------------------------------------------------------
class _MaximumGen(_ExtremeGen):
    """Maximum of n i.i.d. draws; ``order = n`` (real, >= 1)."""

    @_flat
    def _logcdf(self, x):
        _, logf, _, _ = self._parent.tail(x)
        return self._order * logf

    @_flat
    def _cdf(self, x):
        f, logf, _, _ = self._parent.tail(x)
        return f if self._order == 1 else np.exp(self._order * logf)

    @_flat
    def _sf(self, x):
        n = self._order
        _, logf, s, logs = self._parent.tail(x)
        if n == 1:
            return s
        with np.errstate(invalid="ignore"):
            out = -np.expm1(n * logf)
        deep = s < _TINY
        out[deep] = np.exp(math.log(n) + logs[deep])
        return out

    @_flat
    def _logsf(self, x):
        n = self._order
        _, logf, s, logs = self._parent.tail(x)
        out = _log1mexp(n * logf)
        deep = s < _TINY
        out[deep] = math.log(n) + logs[deep]
        return out

    @_flat
    def _logpdf(self, x):
        n = self._order
        _, logf, _, _ = self._parent.tail(x)
        lp = self._parent.logpdf(x)
        body = 0.0 if n == 1 else (n - 1.0) * logf
        return math.log(n) + body + lp

    def _quantile_vq(self, v, q, logv, logq):
        n = self._order
        if n == 1:
            return self._parent.quantile(v, q)
        t = np.asarray(logv, dtype=float) / n
        return self._parent.quantile(np.exp(t), -np.expm1(t))


class MaximumDistribution(_ExtremeFrozen):
    """Frozen distribution of the maximum of n i.i.d. draws (see :func:`maximum`)."""

    @property
    def n(self) -> float:
        """Number of draws."""
        return self.dist._order

    def __repr__(self) -> str:
        return f"maximum({self.parent!r}, n={self.n:g})"


class _MaximumCountGen(_ExtremeGen):
    """Maximum of a random number N >= 1 of i.i.d. draws; ``order`` is the count given N >= 1
    (a table of values n_j and probabilities w_j)."""

    @_flat
    def _logcdf(self, x):
        _, logf, _, _ = self._parent.tail(x)
        return self._order.log_pgf(logf)

    @_flat
    def _cdf(self, x):
        return np.exp(self._logcdf(x))

    @_flat
    def _sf(self, x):
        _, logf, s, logs = self._parent.tail(x)
        out = np.asarray(self._order.one_minus_pgf(logf), dtype=float)
        deep = s < _TINY
        out[deep] = np.exp(math.log(self._order.mean) + logs[deep])
        return out

    @_flat
    def _logsf(self, x):
        _, logf, s, logs = self._parent.tail(x)
        with np.errstate(divide="ignore"):
            out = np.log(np.asarray(self._order.one_minus_pgf(logf), dtype=float))
        deep = s < _TINY
        out[deep] = math.log(self._order.mean) + logs[deep]
        return out

    @_flat
    def _logpdf(self, x):
        # d/dx E[F^N] = E[N F^(N-1)] f
        _, logf, _, _ = self._parent.tail(x)
        return self._order.log_dpgf(logf) + self._parent.logpdf(x)

    def _quantile_vq(self, v, q, logv, logq):
        logv = np.asarray(logv, dtype=float)
        logf = self._order.log_f_for(logv)
        with np.errstate(invalid="ignore"):
            return self._parent.quantile(np.exp(logf), -np.expm1(logf))

    def _rvs(self, size=None, random_state=None):
        n = self._order.sample(size, random_state).astype(float)
        t = np.log(random_state.uniform(size=size)) / n
        return self._parent.quantile(np.exp(t), -np.expm1(t))

    def _components(self):
        return [(float(w), _MaximumGen(self._parent, float(n), name="maximum"))
                for n, w in zip(self._order.values, self._order.weights, strict=True)]

    def _munp(self, k):
        return math.fsum(w * g._munp(k) for w, g in self._components())

    def _stats(self):
        m1, m2, m3, m4 = (self._munp(k) for k in (1, 2, 3, 4))
        if not math.isfinite(m1):
            return np.nan, np.nan, np.nan, np.nan
        var = m2 - m1 * m1
        if not (math.isfinite(var) and var > 0):
            return m1, var, np.nan, np.nan
        c3 = m3 - 3 * m1 * m2 + 2 * m1**3
        c4 = m4 - 4 * m1 * m3 + 6 * m1 * m1 * m2 - 3 * m1**4
        return m1, var, c3 / var**1.5, c4 / var**2 - 3.0


class MaximumCountDistribution(MaximumDistribution):
    """Frozen distribution of the maximum of a random number of draws, given at least one
    (see :func:`maximum` with ``count=``)."""

    @property
    def n(self) -> None:  # type: ignore[override]  # no fixed number of draws
        """None: the number of draws is random (see :attr:`count`)."""
        return None

    @property
    def count(self):
        """The count distribution given (N unconditioned)."""
        return self._count

    @property
    def p_none(self) -> float:
        """P(N = 0): the probability that nothing is drawn (no contact on the area)."""
        return float(self._count.p_zero)

    def __repr__(self) -> str:
        return f"maximum({self.parent!r}, count={self._count!r})"


def maximum(dist, n: float | None = None, *, count=None) -> MaximumDistribution:
    """Distribution of the maximum of n independent draws from ``dist``.

    Parameters
    ----------
    dist : frozen continuous distribution
        The distribution of one draw: a ``glstat.GLD``, a frozen ``gld_rs``/``gld_fkml``
        (both use the compiled GLD kernels), any frozen ``scipy.stats`` continuous
        distribution, or an object with ``logcdf``, ``logsf``, ``isf`` (and ``ppf``,
        ``logpdf``, ``support``) methods. Values are in the units of ``dist``.
    n : float, optional
        Number of draws, real and >= 1 (for a surface: the number of grid points, possibly
        times an area factor). Tested up to 1e12; larger values keep the same formulas.
    count : glstat.PoissonCount, glstat.ObservedCounts or frozen scipy.stats discrete, optional
        A random number N of draws instead of ``n`` (e.g. the asperities in contact on an
        area, docs/method.md §6): cdf ``E[F(x)^N | N >= 1]``. The maximum exists only when
        something is drawn, so the distribution is that given N >= 1; ``p_none`` holds
        ``P(N = 0)``, which :func:`glstat.damage_probability` counts as no damage
        (``F^0 = 1``). Give ``n`` or ``count``, not both.

    Returns
    -------
    MaximumDistribution
        (a :class:`MaximumCountDistribution` with ``count``, whose moments are the
        probability-weighted moments of the fixed-n maxima)
        A frozen ``scipy.stats`` distribution (an ``rv_continuous_frozen``) with cdf
        ``F(x)^n``, pdf ``n F^(n-1) f``, quantile ``Q(v^(1/n))``, and the usual ``sf``,
        ``logcdf``, ``logsf``, ``isf``, ``rvs`` (by the quantile of uniforms, never by
        drawing n values), ``mean``, ``var``, ``std``, ``median``, ``interval``,
        ``support``.

    Raises
    ------
    ValueError
        n < 1, non-finite or not a scalar.
    TypeError
        ``dist`` is not a continuous distribution (or an unfrozen one with shapes).

    Notes
    -----
    See the module docstring for the formulas; cdf and sf are both accurate to about
    ``(1 + |log cdf|)`` ulp (resp. a few ulp), deep into either tail, when the parent's
    ``sf``, ``logcdf`` and ``isf`` are.

    Examples
    --------
    >>> import glstat
    >>> g = glstat.GLD(0, 0.197451, 0.134912, 0.134912)
    >>> m = glstat.maximum(g, 1e6)
    >>> round(float(m.median()), 3)
    4.317
    """
    parent = TailAccess(dist)
    if count is not None:
        if n is not None:
            raise TypeError("give either n (a fixed number of draws) or count (a random one), not both")
        from .counts import as_count

        c = as_count(count)
        if c.p_zero >= 1.0:
            raise ValueError("count is 0 with probability 1: there is no maximum")
        out = MaximumCountDistribution(_MaximumCountGen(parent, c.conditional(), name="maximum"))
        out._count = c
        return out
    if n is None:
        raise TypeError("maximum() needs n (a number of draws) or count (a random number of draws)")
    n = _check_n(n)
    return MaximumDistribution(_MaximumGen(parent, n, name="maximum"))


# ------------------------------------------------------------------------------------------
# order statistics
# ------------------------------------------------------------------------------------------
class _OrderStatisticGen(_ExtremeGen):
    """k-th smallest of n i.i.d. draws; ``order = (k, n)``."""

    def _km(self):
        k, n = self._order
        return k, n - k + 1.0

    def _both(self, x):
        k, m = self._km()
        f, _, s, _ = self._parent.tail(x)
        lower = s >= 0.5
        with np.errstate(invalid="ignore"):
            cdf = np.where(lower, special.betainc(k, m, f), special.betaincc(m, k, s))
            sf = np.where(lower, special.betaincc(k, m, f), special.betainc(m, k, s))
        return cdf, sf

    @_flat
    def _cdf(self, x):
        return self._both(x)[0]

    @_flat
    def _sf(self, x):
        return self._both(x)[1]

    @_flat
    def _logcdf(self, x):
        with np.errstate(divide="ignore"):
            return np.log(self._both(x)[0])

    @_flat
    def _logsf(self, x):
        with np.errstate(divide="ignore"):
            return np.log(self._both(x)[1])

    @_flat
    def _logpdf(self, x):
        k, m = self._km()
        _, logf, _, logs = self._parent.tail(x)
        lp = self._parent.logpdf(x)
        a = 0.0 if k == 1 else (k - 1.0) * logf
        b = 0.0 if m == 1 else (m - 1.0) * logs
        return a + b + lp - special.betaln(k, m)

    def _quantile_vq(self, v, q, logv, logq):
        k, m = self._km()
        v, q, logv, logq = np.broadcast_arrays(
            np.asarray(v, float), np.asarray(q, float), np.asarray(logv, float),
            np.asarray(logq, float),
        )
        # u = F at the quantile, s = 1 - u; each from the better-conditioned inverse
        u = np.full(v.shape, np.nan)
        s = np.full(v.shape, np.nan)
        low = v <= 0.5
        u[low] = _betaincinv(k, m, v[low], logv[low])
        u[~low] = _betainccinv(k, m, q[~low], logq[~low])
        high = q <= 0.5
        s[high] = _betaincinv(m, k, q[high], logq[high])
        s[~high] = _betainccinv(m, k, v[~high], logv[~high])
        return self._parent.quantile(u, s)


class OrderStatisticDistribution(_ExtremeFrozen):
    """Frozen distribution of the k-th smallest of n i.i.d. draws (see :func:`order_statistic`)."""

    @property
    def k(self) -> int:
        """Rank (1 = minimum, n = maximum)."""
        return int(self.dist._order[0])

    @property
    def n(self) -> int:
        """Number of draws."""
        return int(self.dist._order[1])

    def __repr__(self) -> str:
        return f"order_statistic({self.parent!r}, k={self.k}, n={self.n})"


def _check_integer(value, name, what) -> float:
    v = _check_n(value, name, what)
    if v != math.floor(v):
        raise ValueError(f"{name} must be a whole number, got {v}")
    return v


def order_statistic(dist, k: int, n: int) -> OrderStatisticDistribution:
    """Distribution of the k-th smallest of n independent draws from ``dist``.

    Parameters
    ----------
    dist : frozen continuous distribution
        The distribution of one draw (as for :func:`maximum`).
    k : int
        Rank, 1 <= k <= n (1 is the minimum, n the maximum).
    n : int
        Number of draws, >= 1 (whole numbers given as floats, e.g. 1e9, are accepted).

    Returns
    -------
    OrderStatisticDistribution
        Frozen ``scipy.stats`` distribution. cdf ``I_F(k, n-k+1)`` (regularized incomplete
        beta; evaluated as ``1 - I_S(n-k+1, k)`` with ``S = 1 - F`` taken from the parent's
        ``sf`` in the upper half), pdf ``F^(k-1) S^(n-k) f / B(k, n-k+1)`` in logs, quantile
        ``Q(I^-1(v))`` with ``betaincinv``/``betainccinv``, and moments by quadrature of the
        quantile function (module docstring). Values in the units of ``dist``.

    Raises
    ------
    ValueError
        k or n not whole, non-finite, < 1, or k > n.
    TypeError
        ``dist`` is not a continuous distribution.
    """
    parent = TailAccess(dist)
    draws = _check_integer(n, "n", "a number of draws")
    rank = _check_integer(k, "k", "a rank, 1 for the minimum")
    if rank > draws:
        raise ValueError(f"k must be between 1 and n = {draws:g}, got k = {rank:g}")
    return OrderStatisticDistribution(_OrderStatisticGen(parent, (rank, draws), name="order_statistic"))
