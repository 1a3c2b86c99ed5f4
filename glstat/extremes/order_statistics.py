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
* an order statistic counts the draws on the near side of x: with ``r = min(k, n-k+1)``,
  ``p`` the parent's probability on that side (F for ``k <= n-k+1``, S otherwise) and ``q``
  its complement, cdf and sf are the binomial tails ``P(Bin(n, p) < r)`` and
  ``P(Bin(n, p) >= r)`` (:func:`glstat._core.incomplete_beta.binomial_tails`): for
  ``r <= 32`` the finite sum ``q^n sum_(j<r) C(n, j) (p/q)^j`` with ``log q`` from
  ``log1p(-p)`` or the parent's ``logsf``/``logcdf`` (the other tail one minus it, its own
  series or ``scipy.special.betainc`` where that is below 1/2); for larger ranks one binomial
  term in Loader's saddle-point form times an integral of order one
  (:mod:`glstat._core.binomial_tail`). The quantile solves for (p, q) by Newton's method from
  ``betaincinv``'s estimate. cdf, sf and their logs stay at about 1e-13 relative, beyond the
  parent's conditioning, for every rank and n up to 1e12 (docs/gld.md), where
  ``scipy.special.betainc`` alone loses up to 1e-8.

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

from _glstat_runtime.validation import draws_or_count

from .._core.incomplete_beta import (
    betainccinv,
    betaincinv,
    binomial_tail_inv,
    binomial_tail_rank_one,
    binomial_tails,
)
from ._rv_extreme import ExtremeFrozen, ExtremeGen, flat
from .tails import SF_TINY as _TINY
from .tails import TailAccess
from .tails import log1mexp as _log1mexp

__all__ = [
    "MaximumCountDistribution",
    "MaximumDistribution",
    "OrderStatisticDistribution",
    "maximum",
    "order_statistic",
]


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


# ------------------------------------------------------------------------------------------
# maximum
# ------------------------------------------------------------------------------------------
class _MaximumGen(ExtremeGen):
    """Maximum of n i.i.d. draws; ``order = n`` (real, >= 1)."""

    @flat
    def _logcdf(self, x):
        _, logf, _, _ = self._parent.tail(x)
        return self._order * logf

    @flat
    def _cdf(self, x):
        f, logf, _, _ = self._parent.tail(x)
        return f if self._order == 1 else np.exp(self._order * logf)

    @flat
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

    @flat
    def _logsf(self, x):
        n = self._order
        _, logf, s, logs = self._parent.tail(x)
        out = _log1mexp(n * logf)
        deep = s < _TINY
        out[deep] = math.log(n) + logs[deep]
        return out

    @flat
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


class MaximumDistribution(ExtremeFrozen):
    """Frozen distribution of the maximum of n i.i.d. draws (see :func:`maximum`)."""

    @property
    def n(self) -> float:
        """Number of draws."""
        return self.dist._order

    def __repr__(self) -> str:
        return f"maximum({self.parent!r}, n={self.n:g})"


class _MaximumCountGen(ExtremeGen):
    """Maximum of a random number N >= 1 of i.i.d. draws; ``order`` is the count given N >= 1
    (a table of values n_j and probabilities w_j)."""

    @flat
    def _logcdf(self, x):
        _, logf, _, _ = self._parent.tail(x)
        return self._order.log_pgf(logf)

    @flat
    def _cdf(self, x):
        return np.exp(self._logcdf(x))

    @flat
    def _sf(self, x):
        _, logf, s, logs = self._parent.tail(x)
        out = np.asarray(self._order.one_minus_pgf(logf), dtype=float)
        deep = s < _TINY
        out[deep] = np.exp(math.log(self._order.mean) + logs[deep])
        return out

    @flat
    def _logsf(self, x):
        _, logf, s, logs = self._parent.tail(x)
        with np.errstate(divide="ignore"):
            out = np.log(np.asarray(self._order.one_minus_pgf(logf), dtype=float))
        deep = s < _TINY
        out[deep] = math.log(self._order.mean) + logs[deep]
        return out

    @flat
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
        ``dist`` is not a continuous distribution (or an unfrozen one with shapes); both
        ``n`` and ``count`` given, or neither.

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
    draws_or_count(n, count)
    if count is not None:
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
# the tail of Bin(n, p) that each function is, with p the parent's probability on the near
# side: X_(k) <= x  <=>  at least k draws <= x (p = F), and X_(k) > x  <=>  at least n - k + 1
# draws > x (p = S)
_FIELD = {
    True: {"cdf": "up", "sf": "low", "logcdf": "logup", "logsf": "loglow"},
    False: {"cdf": "low", "sf": "up", "logcdf": "loglow", "logsf": "logup"},
}


class _OrderStatisticGen(ExtremeGen):
    """k-th smallest of n i.i.d. draws; ``order = (k, n)``."""

    def _km(self):
        k, n = self._order
        return k, n - k + 1.0

    def _rank(self):
        """(r, near): the rank from the nearer end, and whether that is the lower end."""
        k, m = self._km()
        return (int(k), True) if k <= m else (int(m), False)

    def _logs(self, x):
        """(F, log F, S, log S) at x with both logs accurate: the parent's ``tail`` forms
        ``log S`` as ``log(S)`` where S is near 1, which loses ``|log S|`` relative; there it
        is ``log1p(-F)``."""
        f, logf, s, logs = self._parent.tail(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            logs = np.where(s >= 0.5, np.log1p(-f), logs)
        return f, logf, s, logs

    def _small(self, x, which):
        """cdf, sf, logcdf or logsf (``which``) by the binomial tails at the rank from the
        nearer end; at the rank 1 only the parent's far-side tail is evaluated."""
        r, near = self._rank()
        n = self._order[1]
        field = _FIELD[near][which]
        if r == 1:  # P(Bin(n, p) < 1) = q^n
            q, logq = self._parent.upper(x) if near else self._parent.lower(x)
            return binomial_tail_rank_one(n, q, logq, field)
        f, logf, s, logs = self._logs(x)
        if near:
            t = binomial_tails(r, n, f, s, logf, logs, derivatives=False)
        else:
            t = binomial_tails(r, n, s, f, logs, logf, derivatives=False)
        return getattr(t, field)

    @flat
    def _cdf(self, x):
        return self._small(x, "cdf")

    @flat
    def _sf(self, x):
        return self._small(x, "sf")

    @flat
    def _logcdf(self, x):
        return self._small(x, "logcdf")

    @flat
    def _logsf(self, x):
        return self._small(x, "logsf")

    @flat
    def _logpdf(self, x):
        k, m = self._km()
        if k == 1:  # the minimum: only log S enters
            logf = None
            _, logs = self._parent.upper(x)
        elif m == 1:  # the maximum: only log F
            _, logf = self._parent.lower(x)
            logs = None
        else:
            _, logf, _, logs = self._logs(x)
        lp = self._parent.logpdf(x)
        a = 0.0 if k == 1 else (k - 1.0) * logf
        b = 0.0 if m == 1 else (m - 1.0) * logs
        return a + b + lp - special.betaln(k, m)

    def _quantile_small(self, v, q, logv, logq):
        """Quantile: (p, 1 - p) from :func:`binomial_tail_inv` at the rank from the nearer end.

        With ``near`` the tail ``P(Bin(n, p) < r)`` is the sf (p = F), otherwise the cdf
        (p = S); the smaller of the two targets is solved for, from the estimate of
        ``betaincinv``/``betainccinv``.
        """
        r, near = self._rank()
        n = self._order[1]
        m = n - r + 1.0
        t_low, t_up = (q, v) if near else (v, q)
        log_low, log_up = (logq, logv) if near else (logv, logq)
        lower = t_low <= 0.5
        p0 = np.full(v.shape, np.nan)
        with np.errstate(invalid="ignore", divide="ignore"):
            p0[lower] = betainccinv(r, m, t_low[lower], log_low[lower])
            p0[~lower] = betaincinv(r, m, t_up[~lower], log_up[~lower])
        p, pc = binomial_tail_inv(r, n, np.where(lower, log_low, log_up), lower, p0)
        return self._parent.quantile(p, pc) if near else self._parent.quantile(pc, p)

    def _quantile_vq(self, v, q, logv, logq):
        v, q, logv, logq = np.broadcast_arrays(
            np.asarray(v, float), np.asarray(q, float), np.asarray(logv, float),
            np.asarray(logq, float),
        )
        return self._quantile_small(v, q, logv, logq)


class OrderStatisticDistribution(ExtremeFrozen):
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
        beta, as the binomial tail ``P(Bin(n, F) >= k)`` or its mirror on ``S = 1 - F`` taken
        from the parent's ``sf``), pdf ``F^(k-1) S^(n-k) f / B(k, n-k+1)`` in logs, quantile
        ``Q(I^-1(v))`` by Newton's method on the binomial tail, and moments by quadrature of
        the quantile function (module docstring). Values in the units of ``dist``.

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
