"""The maximum over an area across the bootstrap fits: per-resample draws, medians and means,
their pooled mixture, and the bootstrap probabilities of integrity and damage (the results of
:meth:`glstat.BootstrapFit.maximum`, :meth:`~glstat.BootstrapFit.damage_probability` and
:meth:`~glstat.BootstrapFit.integrity_probability`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy import optimize, special
from scipy.stats import rv_continuous

from _glstat_runtime.reprs import short_values
from _glstat_runtime.validation import check_level

from ..distributions.gld import GLD
from ..extremes.counts import RowCounts, TabulatedCount
from ..extremes.order_statistics import MaximumCountDistribution, MaximumDistribution, maximum
from ..extremes.tails import log1mexp
from ._lambda_rows import (
    FAMILY,
    count_max_moments,
    log_tails,
    max_quantiles,
    max_raw_moments,
    quantiles,
    support,
)

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["BootstrapMaximum", "BootstrapProbability", "MaximumMixture", "interval_level",
           "reach_compatible_tails", "resample_count_maximum", "resample_maximum", "resample_probability",
           "row_distributions"]


class MaximumMixture(rv_continuous):
    """Pooled distribution of the maximum of n draws over the bootstrap GLDs.

    An equal-weight mixture of the B distributions of the maximum,
    ``F_mix(x) = (1/B) sum_b F_b(x)^n``, as a shape-free ``scipy.stats.rv_continuous``:
    ``cdf``, ``sf``, ``logcdf``, ``logsf`` and ``pdf`` average the components (in log space,
    with ``F_b^n = exp(n log F_b)`` and ``log F_b = log1p(-S_b)`` in the upper tail);
    ``ppf``/``isf`` solve ``log F_mix = log p`` (or ``log S_mix = log q``) by Brent's method
    inside the bracket [min_b, max_b] of the component quantiles, so the tails keep their
    relative accuracy; ``rvs`` picks a component uniformly, then draws from it; the mean and
    variance average the components' moments (quadrature, see :mod:`glstat.extremes`).

    Parameters
    ----------
    lambdas : array_like, shape (B, 4)
        lambda1..lambda4 of the component GLDs.
    param : {"rs", "fkml"}
        Parameterisation.
    n : float
        Number of draws (>= 1).
    counts : glstat.extremes.counts.RowCounts, optional
        A random number of draws per component, given at least one (then ``n`` is unused):
        component b is ``E_b[F_b(x)^N]``.
    tails : array_like, shape (B, 4), optional
        A generalized Pareto tail per component (``u, q, xi, sigma``,
        :mod:`glstat.extremes.spliced_tail`): component b is then its GLD below ``u`` and the
        Pareto tail above.
    """

    def __init__(self, lambdas=None, param="rs", n=1.0, counts=None, tails=None, **kwargs):
        lam = np.array(lambdas, dtype=float, ndmin=2)
        if lam.ndim != 2 or lam.shape[1] != 4 or lam.shape[0] < 1:
            raise ValueError(f"lambdas must have shape (B, 4), got {np.shape(lambdas)}")
        self._lam = lam
        self._param = param
        self._n = float(n)
        self._counts = counts
        if counts is not None and counts.rows != lam.shape[0]:
            raise ValueError(f"counts has {counts.rows} rows for {lam.shape[0]} components")
        self._tails = None if tails is None else np.array(tails, dtype=float, ndmin=2)
        if self._tails is not None and self._tails.shape != (lam.shape[0], 4):
            raise ValueError(f"tails must have shape ({lam.shape[0]}, 4), got {np.shape(tails)}")
        self._family = FAMILY[param]
        lo, hi = support(lam, self._family, self._tails)
        kwargs.setdefault("a", float(np.min(lo)))
        kwargs.setdefault("b", float(np.max(hi)))
        kwargs.setdefault("name", "maximum_mixture")
        super().__init__(**kwargs)

    def _updated_ctor_param(self):
        dct = super()._updated_ctor_param()
        dct.update(lambdas=self._lam, param=self._param, n=self._n, counts=self._counts,
                   tails=self._tails)
        return dct

    @property
    def n_components(self) -> int:
        """Number of mixed distributions B."""
        return self._lam.shape[0]

    def _component_logs(self, x):
        x = np.asarray(x, dtype=float).ravel()
        logf, logs, logp = log_tails(self._lam, self._family, x, self._tails)
        c = self._counts
        if c is not None:
            y = c.log_pgf(logf)
            with np.errstate(divide="ignore"):
                ls = np.log(c.one_minus_pgf(logf))
            deep = logs < math.log(1e-290)
            ls = np.where(deep, np.log(c.mean)[:, None] + logs, ls)
            return y, ls, c.log_dpgf(logf) + logp
        n = self._n
        y = n * logf  # log of the component cdf of the maximum
        ls = log1mexp(y)
        deep = logs < math.log(1e-290)
        ls = np.where(deep, math.log(n) + logs, ls)
        lp = math.log(n) + (n - 1.0) * logf + logp if n != 1 else logp
        return y, ls, lp

    def _mix(self, comp, shape):
        with np.errstate(divide="ignore"):
            out = special.logsumexp(comp, axis=0) - math.log(comp.shape[0])
        return out.reshape(shape)

    def _logcdf(self, x):
        return self._mix(self._component_logs(x)[0], np.shape(x))

    def _logsf(self, x):
        return self._mix(self._component_logs(x)[1], np.shape(x))

    def _logpdf(self, x):
        return self._mix(self._component_logs(x)[2], np.shape(x))

    def _cdf(self, x):
        return np.exp(self._logcdf(x))

    def _sf(self, x):
        return np.exp(self._logsf(x))

    def _pdf(self, x):
        return np.exp(self._logpdf(x))

    def _solve(self, logp, upper):
        """x with log F_mix(x) = logp (log S_mix(x) = logp when ``upper``)."""
        if upper:
            logv = log1mexp(np.array([logp]))
        else:
            logv = np.array([logp])
        ns = [self._n] if self._counts is None else [self._counts.values.min(),
                                                      self._counts.values.max()]
        comp = []
        for n in ns:  # F^nmax <= E[F^N] <= F^nmin: the quantiles of nmin and nmax bracket
            t = logv / n
            comp.append(quantiles(self._lam, self._family, np.exp(t)[None, :],
                                  (-np.expm1(t))[None, :], self._tails)[:, 0])
        comp = np.concatenate(comp)
        lo, hi = float(np.min(comp)), float(np.max(comp))
        if not lo < hi:
            return lo

        def h(x):
            y, ls, _ = self._component_logs(np.array([x]))
            val = self._mix(ls if upper else y, (1,))[0]
            return (logp - val) if upper else (val - logp)

        hlo, hhi = h(lo), h(hi)
        if hlo >= 0:
            return lo
        if hhi <= 0:
            return hi
        return optimize.brentq(h, lo, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=400)

    def _ppf(self, q):
        q = np.asarray(q, dtype=float)
        out = np.empty(q.shape)
        for i, v in np.ndenumerate(q):
            if v <= 0.5:
                out[i] = self._solve(math.log(v), False) if v > 0 else self.a
            else:
                out[i] = self._solve(math.log1p(-v), True) if v < 1 else self.b
        return out

    def _isf(self, q):
        q = np.asarray(q, dtype=float)
        out = np.empty(q.shape)
        for i, s in np.ndenumerate(q):
            if s <= 0.5:
                out[i] = self._solve(math.log(s), True) if s > 0 else self.b
            else:
                out[i] = self._solve(math.log1p(-s), False) if s < 1 else self.a
        return out

    def _rvs(self, size=None, random_state=None):
        size = () if size is None else size
        # uniform() exists on both numpy.random.Generator and RandomState
        pick = np.asarray(random_state.uniform(size=size)) * self.n_components
        comp = np.minimum(pick.astype(np.int64), self.n_components - 1)
        v = random_state.uniform(size=size)
        flat_c = np.ravel(comp)
        n = self._n
        if self._counts is not None:
            n = self._counts.take(flat_c).sample(random_state)
        t = np.log(np.ravel(v)) / n
        tails = None if self._tails is None else self._tails[flat_c]
        out = quantiles(self._lam[flat_c], self._family, np.exp(t)[:, None], (-np.expm1(t))[:, None],
                        tails)
        return out[:, 0].reshape(np.shape(comp))

    def _munp(self, k):
        if k > 2 or int(k) != k:
            return super()._munp(k)
        if self._counts is not None:
            return float(np.mean(count_max_moments(self._lam, self._family, self._counts, int(k),
                                                   self._tails)))
        return float(np.mean(max_raw_moments(self._lam, self._family, self._n, int(k),
                                             self._tails)))

    def _stats(self):
        m1 = self._munp(1)
        m2 = self._munp(2)
        return m1, m2 - m1 * m1, None, None


@dataclass(frozen=True)
class BootstrapMaximum:
    """The maximum of n draws across the bootstrap GLDs (result of :meth:`BootstrapFit.maximum`).

    Attributes
    ----------
    n : float
        Number of draws (the mean count given at least one draw, with a random count).
    draws : ndarray, shape (B_ok,)
        One random maximum of n draws per bootstrap GLD (the paper's "one value per
        bootstrap GLD"), units of the data.
    medians : ndarray, shape (B_ok,)
        Median of each bootstrap GLD's maximum, ``Q_b(0.5^(1/n))``.
    means : ndarray, shape (B_ok,)
        Mean of each bootstrap GLD's maximum (NaN where it does not exist).
    confidence_level : float
        Default coverage of :meth:`interval`, :meth:`median_interval` and :meth:`mixture_interval`.
    mixture : MaximumMixture
        The pooled distribution (1/B) sum_b F_b(x)^n: the density of the maximal value
        combining parameter uncertainty and the randomness of the maximum itself.
    full : MaximumDistribution
        Maximum of n draws from the full-sample fit.
    count : CountDistribution or None
        The random count (None for a fixed n); each bootstrap GLD then has its own count
        given N >= 1 (its resample's group sizes with ``groups``).
    calibrated : bool
        Whether the intervals read the calibrated percentile pair of a nominal level
        (:func:`interval_level`; the bootstrap of a GLD with a Pareto tail).
    """

    n: float
    draws: np.ndarray
    medians: np.ndarray
    confidence_level: float
    mixture: MaximumMixture
    full: MaximumDistribution
    _lam: np.ndarray = field(repr=False, compare=False, default=None)  # type: ignore[arg-type]
    _param: str = field(repr=False, compare=False, default="rs")
    _means: np.ndarray | None = field(repr=False, compare=False, default=None)
    _counts: RowCounts | None = field(repr=False, compare=False, default=None)
    count: Any = None
    _tails: np.ndarray | None = field(repr=False, compare=False, default=None)
    calibrated: bool = False

    def __repr__(self) -> str:
        """One line: the number of draws, of bootstrap GLDs, the median and the interval of
        the maximum (never the draws)."""
        count = "" if self.count is None else f", count={self.count!r}"
        if self.draws.size:
            lo, hi = self.interval()
            centre = (f", median={short_values(self.median)}, interval=({short_values(lo)}, "
                      f"{short_values(hi)})")
        else:
            centre = ""
        return (f"BootstrapMaximum(n={self.n:g}{count}, n_draws={self.draws.size}{centre}, "
                f"confidence_level={self.confidence_level:g}, calibrated={self.calibrated})")

    @property
    def means(self) -> np.ndarray:
        """Mean of each bootstrap GLD's maximum (NaN where it does not exist); with a random
        count, the count-weighted means of the fixed-n maxima (computed when first asked)."""
        if self._means is None:
            fam = FAMILY[self._param]
            means = (max_raw_moments(self._lam, fam, self.n, 1, self._tails) if self._counts is None
                     else count_max_moments(self._lam, fam, self._counts, 1, self._tails))
            object.__setattr__(self, "_means", means)
            return means
        return self._means

    @property
    def mean(self) -> float:
        """Mean of the per-GLD draws (units of the data); it follows the heaviest of the
        bootstrap tails, :attr:`median` is the stable centre."""
        return float(np.mean(self.draws))

    @property
    def median(self) -> float:
        """Median of the per-GLD draws (units of the data)."""
        return float(np.median(self.draws))

    def _level(self, confidence_level):
        """The level of the percentile pair read for the nominal ``confidence_level``."""
        level = self.confidence_level if confidence_level is None else check_level(confidence_level)
        return interval_level(level, self.calibrated)

    def interval(self, confidence_level: float | None = None) -> tuple[float, float]:
        """Equal-tailed interval of the per-GLD draws (units of the data).

        Parameters
        ----------
        confidence_level : float, optional
            Coverage of the interval; default :attr:`confidence_level`.
        """
        a = 1.0 - self._level(confidence_level)
        lo, hi = np.quantile(self.draws, [a / 2, 1 - a / 2])
        return float(lo), float(hi)

    def median_interval(self, confidence_level: float | None = None) -> tuple[float, float]:
        """Percentile interval of the per-GLD medians: the parameter uncertainty of the median.

        Parameters
        ----------
        confidence_level : float, optional
            Coverage of the interval; default :attr:`confidence_level`.
        """
        a = 1.0 - self._level(confidence_level)
        lo, hi = np.quantile(self.medians, [a / 2, 1 - a / 2])
        return float(lo), float(hi)

    def mixture_interval(self, confidence_level: float | None = None) -> tuple[float, float]:
        """Equal-tailed interval of :attr:`mixture` (the limit of :meth:`interval` for many draws).

        Parameters
        ----------
        confidence_level : float, optional
            Coverage of the interval; default :attr:`confidence_level`.
        """
        a = 1.0 - self._level(confidence_level)
        return float(self.mixture.ppf(a / 2)), float(self.mixture.isf(a / 2))

    def components(self) -> list[MaximumDistribution]:
        """``glstat.maximum(dist, n)`` of every bootstrap distribution (with its own count, if
        random)."""
        dists = row_distributions(self._lam, self._param, self._tails)
        if self._counts is None:
            return [maximum(d, self.n) for d in dists]
        c = self._counts
        return [maximum(d, count=TabulatedCount(c.values, c.weights[b]))
                for b, d in enumerate(dists)]

    def to_frame(self) -> pd.DataFrame:
        """One row per bootstrap GLD: draw, median and mean of its maximum."""
        import pandas as pd

        return pd.DataFrame({"draw": self.draws, "median": self.medians, "mean": self.means})

    def summary(self) -> pd.DataFrame:
        """Mean and interval of the draws, the mixture and the medians (one row each)."""
        import pandas as pd

        lo, hi = self.interval()
        mlo, mhi = self.mixture_interval()
        dlo, dhi = self.median_interval()
        return pd.DataFrame(
            [{"quantity": "draws", "center": self.mean, "low": lo, "high": hi},
             {"quantity": "mixture", "center": float(self.mixture.median()), "low": mlo, "high": mhi},
             {"quantity": "medians", "center": float(np.median(self.medians)), "low": dlo, "high": dhi},
             {"quantity": "full_fit", "center": float(self.full.median()),
              "low": float(self.full.ppf((1 - self.confidence_level) / 2)),
              "high": float(self.full.isf((1 - self.confidence_level) / 2))}]
        ).assign(n=self.n, confidence_level=self.confidence_level)


@dataclass(frozen=True)
class BootstrapProbability:
    """Integrity or damage probability with its bootstrap interval.

    Attributes
    ----------
    what : str
        ``"integrity"`` or ``"damage"``.
    threshold, n : float
        Pressure level (units of the data) and number of points (the mean count with a
        random count).
    area_factor : ndarray
        Area factors k (dimensionless).
    estimate : ndarray
        Probability from the full-sample fit, shape of ``area_factor``.
    low, high : ndarray
        Percentile interval over the bootstrap fits.
    values : ndarray
        Per-resample probabilities, shape (B_ok, *area_factor.shape).
    confidence_level : float
        Nominal coverage of the interval.
    count : CountDistribution or None
        The random count of the full-sample estimate (None for a fixed n).
    interval_level : float or None
        Level of the percentile pair ``low``, ``high`` when it is not ``confidence_level``
        (the calibrated widening of :func:`interval_level`).
    tail_bound : ndarray or None
        With a bounded full-sample Pareto tail and a threshold above its start: the largest
        damage (smallest integrity) under the tails compatible with the data at the
        interval's level (:meth:`glstat.BootstrapFit.with_pareto_tail`), which ``high``
        (``low`` for the integrity) reaches when the bootstrap percentile does not; shape of
        ``estimate``. None otherwise.
    """

    what: str
    threshold: float
    n: float
    area_factor: np.ndarray
    estimate: np.ndarray
    low: np.ndarray
    high: np.ndarray
    values: np.ndarray
    confidence_level: float
    count: Any = None
    interval_level: float | None = None
    tail_bound: np.ndarray | None = None

    def __repr__(self) -> str:
        """One line: what, where, the estimate and the interval per area factor (a long array
        as its size and range) and the number of bootstrap values, never the values."""
        count = "" if self.count is None else f", count={self.count!r}"
        level = "" if self.interval_level is None else f", interval_level={self.interval_level:g}"
        return (f"BootstrapProbability(what={self.what!r}, threshold={self.threshold:g}, "
                f"n={self.n:g}{count}, area_factor={short_values(self.area_factor)}, "
                f"estimate={short_values(self.estimate)}, low={short_values(self.low)}, "
                f"high={short_values(self.high)}, confidence_level={self.confidence_level:g}"
                f"{level}, n_values={len(self.values)})")

    @property
    def bounded_by_tails(self) -> np.ndarray:
        """Per area factor: whether the end of the interval on the side of the danger
        (``high`` for the damage, ``low`` for the integrity) comes from the compatible tails
        (:attr:`tail_bound`) rather than from the bootstrap percentile."""
        shape = np.shape(self.estimate)
        if self.tail_bound is None:
            return np.zeros(shape, dtype=bool)
        side = self.high if self.what == "damage" else self.low
        pct = self.percentile_end
        return np.broadcast_to(np.asarray(side != pct), shape)

    @property
    def percentile_end(self) -> np.ndarray:
        """The bootstrap percentile on the side of the danger (the damage's upper, the
        integrity's lower one), before the compatible tails (:attr:`tail_bound`) widen it."""
        a = 1.0 - (self.interval_level if self.interval_level is not None
                   else self.confidence_level)
        q = a / 2 if self.what == "integrity" else 1 - a / 2
        return np.quantile(self.values, q, axis=0)

    def to_frame(self) -> pd.DataFrame:
        """One row per area factor: estimate, low, high."""
        import pandas as pd

        k = np.broadcast_to(self.area_factor, np.shape(self.estimate))
        return pd.DataFrame({"area_factor": np.ravel(k), "estimate": np.ravel(self.estimate),
                             "low": np.ravel(self.low), "high": np.ravel(self.high)})


# ---------------------------------------------------------------------------------------------
# the results from the lambdas of the successful resamples
# ---------------------------------------------------------------------------------------------
#: The calibrated interval of nominal level c reads the percentile pair of level
#: ``1 - WIDENING (1 - c)`` (chosen by measurement, :func:`interval_level`).
WIDENING = 0.7


def interval_level(level: float, calibrated: bool) -> float:
    """The level of the bootstrap percentile pair read as the interval of nominal ``level``.

    Uncalibrated, ``level`` itself. Calibrated (the default of a GLD with a Pareto tail), the
    pair of 0.7 times the nominal miss rate, ``1 - 0.7 (1 - level)`` (:data:`WIDENING`): the
    3.5 % and 96.5 % percentiles for a nominal 90 % interval. Of the readings 0.90, 0.93 and
    0.95 measured on six parents (docs/benchmarks.md "calibration"), 0.93 is the one whose
    mean coverage is nearest the nominal 90 % (damage 90 %, maximum 91 %) with every parent
    at 85 % or more (89–94 %); 0.90 covers 87 % (85–92 %), 0.95 covers 92 % (91–95 %).
    """
    return 1.0 - WIDENING * (1.0 - level) if calibrated else level


def row_distributions(lam: np.ndarray, param: str, tails: np.ndarray | None = None) -> list:
    """A GLD per row of ``lam`` (a :class:`glstat.ParetoTailGLD` per row with ``tails``)."""
    dists = [GLD(l1, l2, l3, l4, param=param) for l1, l2, l3, l4 in lam]
    if tails is None:
        return dists
    from ..extremes.spliced_tail import ParetoTailGLD

    return [ParetoTailGLD(d, *t) for d, t in zip(dists, tails, strict=True)]


def resample_maximum(lam: np.ndarray, param: str, full: MaximumDistribution, level: float,
                     g: np.random.Generator, tails: np.ndarray | None = None) -> BootstrapMaximum:
    """The maximum of ``full.n`` draws for every row of ``lam`` (shape (B_ok, 4); with its
    Pareto tail, a row of ``tails``): one random draw each from ``g``, the medians, the means
    and the pooled mixture."""
    fam = FAMILY[param]
    n = full.n
    v = g.random(lam.shape[0])
    draws = max_quantiles(lam, fam, n, np.log(v)[:, None], tails)[:, 0]
    medians = max_quantiles(lam, fam, n, np.array([[math.log(0.5)]]), tails)[:, 0]
    return BootstrapMaximum(n=n, draws=draws, medians=medians, confidence_level=level,
                            mixture=MaximumMixture(lam, param, n, tails=tails), full=full,
                            _lam=lam, _param=param, _tails=tails, calibrated=tails is not None)


def resample_count_maximum(lam: np.ndarray, param: str, full: MaximumCountDistribution, count,
                           cond: RowCounts, level: float, g: np.random.Generator,
                           tails: np.ndarray | None = None) -> BootstrapMaximum:
    """The maximum of a random number of draws for every row of ``lam``: ``count`` is the
    count of the full-sample maximum ``full``, row b of ``cond`` the count of row b given at
    least one draw. One count and one maximum drawn from ``g`` per row, the medians and the
    pooled mixture."""
    fam = FAMILY[param]
    counts = cond.sample(g)
    v = g.random(lam.shape[0])
    draws = max_quantiles(lam, fam, counts[:, None], np.log(v)[:, None], tails)[:, 0]
    lf = cond.log_f_for(math.log(0.5))
    with np.errstate(invalid="ignore"):
        medians = quantiles(lam, fam, np.exp(lf)[:, None], (-np.expm1(lf))[:, None], tails)[:, 0]
    return BootstrapMaximum(n=float(count.mean), draws=draws, medians=medians,
                            confidence_level=level,
                            mixture=MaximumMixture(lam, param, 1.0, counts=cond, tails=tails),
                            full=full, _lam=lam, _param=param, _counts=cond, count=count,
                            _tails=tails, calibrated=tails is not None)


def reach_compatible_tails(prob: BootstrapProbability, logf: np.ndarray,
                           count=None) -> BootstrapProbability:
    """``prob`` with the end of its interval on the side of the danger reaching the
    probabilities of the full-sample model under the compatible tails.

    Parameters
    ----------
    prob : BootstrapProbability
        The bootstrap probability (at one threshold).
    logf : ndarray, shape (J,)
        ``log F(threshold)`` of the full-sample model under each of the J tails compatible
        with the data (:meth:`glstat.BootstrapFit.with_pareto_tail`).
    count : CountDistribution, optional
        The random count of the full-sample estimate (None: ``prob.n`` draws).

    Returns
    -------
    BootstrapProbability
        ``high`` (damage) or ``low`` (integrity) widened where the compatible tails go
        further, and :attr:`BootstrapProbability.tail_bound` set.
    """
    k = np.asarray(prob.area_factor, dtype=float)
    lf = np.asarray(logf, dtype=float).reshape((-1,) + (1,) * k.ndim)
    if count is None:
        y = lf * k * prob.n
        vals = np.exp(y) if prob.what == "integrity" else -np.expm1(y)
    elif prob.what == "integrity":
        vals = np.exp(count.log_integrity(lf, k))
    else:
        vals = count.damage(lf, k)
    if prob.what == "damage":
        bound = np.max(vals, axis=0)
        return replace(prob, high=np.maximum(prob.high, bound), tail_bound=bound)
    bound = np.min(vals, axis=0)
    return replace(prob, low=np.minimum(prob.low, bound), tail_bound=bound)


def resample_probability(lam: np.ndarray, param: str, what: str, threshold: float, n, k: np.ndarray,
                         estimate: np.ndarray, level: float, count=None,
                         rows: RowCounts | None = None, tails: np.ndarray | None = None
                         ) -> BootstrapProbability:
    """The probability of integrity (``what="integrity"``) or damage at ``threshold`` for every
    row of ``lam`` and its percentile interval.

    The number of points is ``n``, or the random ``count`` (full sample) with ``rows`` (its
    distribution per row of ``lam``); ``k`` holds the area factors and ``estimate`` the
    full-sample probabilities; ``tails`` the rows' Pareto tails (then the interval is the
    calibrated percentile pair, :func:`interval_level`).
    """
    logf = log_tails(lam, FAMILY[param], np.array([threshold]), tails)[0][:, 0]
    logf = logf.reshape((-1,) + (1,) * k.ndim)  # one row per resample
    if rows is None:
        y = (logf * k) * float(n)  # k n log F
        vals = np.exp(y) if what == "integrity" else -np.expm1(y)
    elif what == "integrity":
        vals = np.exp(k * rows.log_pgf(logf))
    else:
        vals = rows.damage(logf, k)
    pair = interval_level(level, tails is not None)
    alpha = 1.0 - pair
    q = np.quantile(vals, [alpha / 2, 1 - alpha / 2], axis=0)
    return BootstrapProbability(what=what, threshold=threshold,
                                n=float(n) if count is None else float(count.mean),
                                area_factor=k, estimate=estimate, low=q[0], high=q[1], values=vals,
                                confidence_level=level, count=count,
                                interval_level=None if pair == level else pair)
