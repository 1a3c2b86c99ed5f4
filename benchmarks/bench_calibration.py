"""Coverage of the 90 % intervals of the maximum and the damage probability, by simulation.

Run: ``python benchmarks/bench_calibration.py`` (the default grid: 23 min on one core of a
shared 2-core machine), ``--quick`` (n = 1000, m = 1e3: under 2 min), ``--reps R``,
``--slow-reps R``, ``--out PATH`` (CSV, default ``benchmarks/results/calibration.csv``);
``--help`` lists the rest. Results: docs/benchmarks.md, section "calibration".

For every parent distribution (:data:`PARENTS`: five unimodal ones, a GLD control, a normal
mixture with a second bump at the top and a Fréchet of tail index 3), sample size n and number
m of draws of the maximum, the data are drawn R times from the parent (seeded numpy
Generators, the same data for every method) and every method predicts, with its
nonparametric bootstrap:

* the damage probability ``P(max of m > t) = 1 - F(t)^m`` at thresholds t taken from the
  parent's exact upper quantiles, ``t = isf(1 - (1 - d)^(1/m))``, so that the true damage is d;
  the 90 % percentile interval of the per-resample damage covers the truth or misses it above
  (the interval is too low: the danger is underestimated) or below;
* the maximum of m draws: the equal-tailed interval of one random maximum per resample
  (:meth:`glstat.BootstrapMaximum.interval`) against a fresh draw of the true maximum, and the
  interval of the per-resample medians against the true median.

Methods (:data:`METHODS`): ``default`` is :func:`glstat.predict_maximum` with its defaults (an
RS moment GLD with a generalized Pareto tail on the ceil(sqrt(n)) largest values of every
resample, the calibrated 3.5 / 96.5 % percentiles as its 90 % interval); ``rs_moments`` is the
same without the tail (``tail=None``: the GLD alone, the paper's method and the baseline),
``fkml_lmoments`` and ``fkml_mle`` the GLD alone with other fits; the tail models
are implemented here: ``tail_gld`` (a GLD fitted by L-moments to the top of the sample, used as
the conditional tail), ``pot_gpd_mle``, ``pot_gpd_zs`` and ``pot_gpd_zs_sqrt`` (generalized
Pareto peaks over threshold, fitted by scipy's maximum likelihood or by the Zhang-Stephens
estimator, above the 0.9 sample quantile or to the sqrt(n) largest values). Every damage row
of the CSV also holds the coverage of the wider 95 % and 98 % percentile intervals of the same
resamples (a crude calibration by widening), and the shares of its intervals that are a
confident 0 % (``zero_interval``), at least 0.9 wide (``undetermined``) or wider than 0.5
(``wide``). The library's methods are scored on the library's own interval (for a bounded
Pareto tail its upper end reaches the tails compatible with the data). "Slow" methods (one
optimisation per resample) run on the first ``--slow-reps`` data sets only. Times are per
call: fit, bootstrap and every maximum and damage probability (one core; numba compiled and
cached beforehand).
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np
import scipy.stats as st

import glstat
from glstat import FitError, fit_batch, gld_fkml, predict_maximum

LEVEL = 0.9  #: nominal coverage of the intervals
WIDE_LEVELS = (0.93, 0.95, 0.98)  #: widened percentile intervals of the same resamples (calibration)
DAMAGES = (0.01, 0.1, 0.5, 0.9)  #: true damage probabilities
OUT = Path(__file__).resolve().parent / "results" / "calibration.csv"


# ---------------------------------------------------------------------------------------------
# parents
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Parent:
    """A parent distribution of the data.

    Attributes
    ----------
    name : str
        Short name (CSV and tables).
    label : str
        Description.
    dist : Any
        Frozen distribution with ``rvs`` and an accurate ``isf`` (scipy.stats or glstat.GLD).
    """

    name: str
    label: str
    dist: Any


class NormalMixture:
    """A mixture of normal distributions with the ``rvs`` and accurate ``isf`` of a parent.

    Parameters
    ----------
    weights : sequence of float
        Component probabilities (summing to 1).
    locs, scales : sequence of float
        Component means and standard deviations (units of the data).
    """

    def __init__(self, weights: Sequence[float], locs: Sequence[float], scales: Sequence[float]):
        self.weights = np.asarray(weights, dtype=float)
        self.locs = np.asarray(locs, dtype=float)
        self.scales = np.asarray(scales, dtype=float)

    def logsf(self, x: np.ndarray) -> np.ndarray:
        """log P(X > x), accurate far in the upper tail (log-sum-exp of the components).

        Parameters
        ----------
        x : array_like
            Points (units of the data).

        Returns
        -------
        ndarray
            Shape of ``x``.
        """
        from scipy.special import logsumexp

        x = np.asarray(x, dtype=float)[..., None]
        return logsumexp(st.norm.logsf(x, self.locs, self.scales), b=self.weights, axis=-1)

    def isf(self, p: np.ndarray) -> np.ndarray:
        """The x with ``P(X > x) = p``, by Brent's method on :meth:`logsf` (to 1e-13).

        Parameters
        ----------
        p : array_like
            Upper-tail probabilities in (0, 1).

        Returns
        -------
        ndarray
            Shape of ``p`` (units of the data).
        """
        from scipy.optimize import brentq

        lo = float(np.min(self.locs - 40 * self.scales))
        hi = float(np.max(self.locs + 40 * self.scales))

        def one(pp: float) -> float:
            return brentq(lambda x: float(self.logsf(x)) - math.log(pp), lo, hi, xtol=1e-13)

        return np.vectorize(one, otypes=[float])(np.asarray(p, dtype=float))

    def rvs(self, size: int, random_state: np.random.Generator) -> np.ndarray:
        """``size`` draws: a component picked by its weight, then a normal draw from it.

        Parameters
        ----------
        size : int
            Number of values.
        random_state : numpy.random.Generator
            Source of the draws.

        Returns
        -------
        ndarray, shape (size,)
        """
        c = np.searchsorted(np.cumsum(self.weights), random_state.random(size), side="right")
        c = np.minimum(c, self.weights.size - 1)
        return random_state.normal(self.locs[c], self.scales[c])


PARENTS = (
    Parent("lognormal", "lognormal σ 0.5", st.lognorm(0.5)),
    Parent("weibull", "Weibull k 2", st.weibull_min(2.0)),
    Parent("gamma", "gamma k 3", st.gamma(3.0)),
    Parent("normal", "normal", st.norm()),
    Parent("student_t", "Student-t ν 5, location 5", st.t(5.0, loc=5.0)),
    # lambda3 = lambda4: the same distribution in both parameterisations (RS and FKML fits
    # are both well specified); power tails of index 0.1, moments up to order 9
    Parent("gld", "GLD FKML(0, 1, -0.1, -0.1) = RS(0, -0.1, -0.1, -0.1) (control)",
           glstat.GLD(0.0, 1.0, -0.1, -0.1, param="fkml")),
    # appended: the seeds of the parents above are unchanged (a parent's index seeds its data)
    Parent("two_bump", "0.9 N(0, 1) + 0.1 N(3, 0.5): a second bump at the top of the sample",
           NormalMixture((0.9, 0.1), (0.0, 3.0), (1.0, 0.5))),
    # tail index 3: moments up to order 2 only, the RS moment fit of many samples has no root
    Parent("frechet", "Fréchet, tail index 3", st.invweibull(3.0)),
)


def true_thresholds(dist: Any, ms: np.ndarray, damages: Sequence[float]) -> np.ndarray:
    """Thresholds t with ``1 - F(t)^m = d`` for every m (rows) and d (columns).

    Parameters
    ----------
    dist : Any
        The parent (frozen, with ``isf``).
    ms : ndarray, shape (M,)
        Numbers of draws of the maximum.
    damages : sequence of float
        True damage probabilities d in (0, 1).

    Returns
    -------
    ndarray, shape (M, D)
        ``isf(1 - (1 - d)^(1/m))``, the tail probability formed as ``-expm1(log1p(-d) / m)``.
    """
    d = np.asarray(damages, dtype=float)
    return dist.isf(-np.expm1(np.log1p(-d)[None, :] / ms[:, None]))


# ---------------------------------------------------------------------------------------------
# what a method returns
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Prediction:
    """The bootstrap of one method on one sample.

    Attributes
    ----------
    damage : ndarray, shape (B_ok, M, D)
        Damage probability of every successful resample at every (m, threshold).
    draws : ndarray, shape (B_ok, M)
        One random maximum of m draws per resample (units of the data).
    medians : ndarray, shape (B_ok, M)
        Median of the maximum of m draws per resample.
    n_resamples : int
        Resamples drawn (B), successful or not.
    interval : tuple of two ndarrays, shape (M, D), optional
        The damage interval the library reports itself (for a bounded Pareto tail it also
        reaches the tails compatible with the data), scored for a method that reads the
        library's level ``interval_level``; otherwise the percentile interval of ``damage``
        at the method's level is scored.
    interval_level : float, optional
        The percentile level of ``interval``.
    """

    damage: np.ndarray
    draws: np.ndarray
    medians: np.ndarray
    n_resamples: int
    interval: tuple[np.ndarray, np.ndarray] | None = None
    interval_level: float | None = None


MethodFunc = Callable[[np.ndarray, np.ndarray, np.ndarray, np.random.Generator], Prediction | None]


@dataclass(frozen=True)
class Method:
    """A prediction method compared by the benchmark.

    Attributes
    ----------
    name : str
        Short name (CSV and tables).
    label : str
        Description.
    func : callable
        ``func(x, ms, thresholds, rng) -> Prediction or None`` (None: no fit).
    n_resamples : int
        Bootstrap resamples B.
    slow : bool
        Whether it optimises per resample (then it runs on ``--slow-reps`` data sets only).
    interval_level : float
        The level of the percentile pair the method reports as its 90 % interval (0.93 for
        the library's default, which reads the calibrated 3.5 % and 96.5 % percentiles).
    """

    name: str
    label: str
    func: MethodFunc
    n_resamples: int
    slow: bool = False
    interval_level: float = LEVEL


# ---------------------------------------------------------------------------------------------
# a, b: glstat.predict_maximum
# ---------------------------------------------------------------------------------------------
def predict_glstat(x: np.ndarray, ms: np.ndarray, thresholds: np.ndarray, rng: np.random.Generator,
                   *, fits: tuple[tuple[str, str], ...], n_resamples: int,
                   likelihood_resamples: int | None = None, tail: str | None = None
                   ) -> Prediction | None:
    """:func:`glstat.predict_maximum` with ``fits``; its bootstrap at every (m, threshold).

    The first m and threshold are those of the call; the others come from the same
    :class:`glstat.BootstrapFit`: ``damage_probability``, and ``maximum_quantiles`` for one
    random maximum and the median per resample (what ``maximum`` draws from the same
    generator, without the means and the mixture, which are not scored).

    Parameters
    ----------
    x : ndarray
        The sample.
    ms : ndarray, shape (M,)
        Numbers of draws of the maximum.
    thresholds : ndarray, shape (M, D)
        Thresholds of the damage probability, one row per m.
    rng : numpy.random.Generator
        Source of the bootstrap and of the random maxima.
    fits : tuple of (param, method)
        As for :func:`glstat.predict_maximum`.
    n_resamples : int
        Bootstrap resamples B.
    likelihood_resamples : int, optional
        At most this many resamples for the likelihood fits.
    tail : {"pareto", None}
        As for :func:`glstat.predict_maximum` (None: the GLDs alone).

    Returns
    -------
    Prediction or None
        None when no fit has a solution (or fewer than two resamples have one).
    """
    p = predict_maximum(x, fits, n=float(ms[0]), threshold=float(thresholds[0, 0]),
                        n_resamples=n_resamples, likelihood_resamples=likelihood_resamples,
                        rng=rng, maximum_rng=rng, tail=tail)
    if not p.ok or p.maximum is None or p.damage is None:
        return None
    boot = p.boot
    draws, medians = [p.maximum.draws], [p.maximum.medians]
    for m in ms[1:]:  # BootstrapFit.maximum's draws and medians, without its means and mixture
        b_ok = p.maximum.draws.size
        v = np.column_stack([rng.random(b_ok), np.full(b_ok, 0.5)])
        qm = boot.maximum_quantiles(float(m), v)
        draws.append(qm[:, 0])
        medians.append(qm[:, 1])
    try:
        probs = [[p.damage if (i, j) == (0, 0) else boot.damage_probability(float(t), n=float(m))
                  for j, t in enumerate(row)]
                 for i, (m, row) in enumerate(zip(ms, thresholds, strict=True))]
    except FitError:
        return None
    damage = np.stack([np.stack([b.values for b in row], axis=-1) for row in probs], axis=1)
    interval = tuple(np.array([[float(getattr(b, end)) for b in row] for row in probs])
                     for end in ("low", "high"))
    # the library's interval: the percentiles of the same values, the damage's upper end
    # widened to the compatible tails of a bounded tail
    level = LEVEL if tail is None else glstat.resampling.maxima.interval_level(LEVEL, True)
    lo, hi = np.quantile(damage[:, 0, 0], [(1 - level) / 2, (1 + level) / 2])
    if not (np.isclose(lo, p.damage.low, rtol=1e-12, atol=1e-15)
            and (np.isclose(hi, p.damage.high, rtol=1e-12, atol=1e-15)
                 or (p.damage.tail_bound is not None and p.damage.high >= hi))):
        raise AssertionError("damage interval differs from predict_maximum's")
    if not np.allclose(p.maximum.interval(), np.quantile(draws[0], [(1 - level) / 2,
                                                                    (1 + level) / 2])):
        raise AssertionError("maximum interval differs from predict_maximum's")
    return Prediction(damage=damage, draws=np.column_stack(draws), medians=np.column_stack(medians),
                      n_resamples=n_resamples, interval=interval, interval_level=level)


# ---------------------------------------------------------------------------------------------
# c, d: tail models (a parametric upper tail above the empirical body)
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class TailRows:
    """One tail model per resample: ``S(x) = q S_tail(x)`` above ``u``, empirical below.

    Attributes
    ----------
    rows : ndarray, shape (B, n)
        The sorted resamples.
    u : ndarray, shape (B,)
        Tail threshold of every resample: its (k+1)-th largest value.
    q : float
        k / n, the probability mass of the tail.
    log_sf : callable
        ``log_sf(x)``, x of shape (B, T): log S_tail of every resample's tail at x.
    isf : callable
        ``isf(p)``, p of shape (B, T): the tail quantiles with ``S_tail = p``.
    """

    rows: np.ndarray
    u: np.ndarray
    q: float
    log_sf: Callable[[np.ndarray], np.ndarray]
    isf: Callable[[np.ndarray], np.ndarray]

    def survival(self, x: np.ndarray) -> np.ndarray:
        """S(x) of every resample at the points x.

        Parameters
        ----------
        x : ndarray, shape (B, T)
            Points (units of the data).

        Returns
        -------
        ndarray, shape (B, T)
            The tail model above ``u``, the empirical survival function at or below it.
        """
        s = self.q * np.exp(self.log_sf(x))
        below = x <= self.u[:, None]
        if below.any():
            n = self.rows.shape[1]
            for b in np.flatnonzero(below.any(axis=1)):
                cols = below[b]
                s[b, cols] = (n - np.searchsorted(self.rows[b], x[b, cols], side="right")) / n
        return s

    def quantile_sf(self, s: np.ndarray) -> np.ndarray:
        """The value x with ``S(x) = s`` for every resample.

        Parameters
        ----------
        s : ndarray, shape (B, T)
            Survival probabilities in (0, 1).

        Returns
        -------
        ndarray, shape (B, T)
            The tail quantile where ``s < q``, else the empirical quantile of the resample.
        """
        out = self.isf(np.minimum(s, self.q) / self.q)
        body = s >= self.q
        if body.any():
            n = self.rows.shape[1]
            idx = np.clip(np.ceil(n * (1.0 - s)).astype(int) - 1, 0, n - 1)
            b = np.broadcast_to(np.arange(s.shape[0])[:, None], s.shape)
            out[body] = self.rows[b[body], idx[body]]
        return out


def tail_prediction(model: TailRows, ms: np.ndarray, thresholds: np.ndarray,
                    rng: np.random.Generator) -> Prediction:
    """Damage, random maxima and medians of the maximum for every resample of a tail model.

    Parameters
    ----------
    model : TailRows
        The per-resample tail models (rows with failed fits already removed).
    ms : ndarray, shape (M,)
        Numbers of draws of the maximum.
    thresholds : ndarray, shape (M, D)
        Thresholds of the damage probability, one row per m.
    rng : numpy.random.Generator
        Source of the random maxima.

    Returns
    -------
    Prediction
        ``n_resamples`` is the number of rows of the model (set by the caller).
    """
    b = model.u.size
    m_count, d_count = thresholds.shape
    s = model.survival(np.broadcast_to(thresholds.ravel(), (b, thresholds.size)).copy())
    s = s.reshape(b, m_count, d_count)
    damage = -np.expm1(ms[None, :, None] * np.log1p(-s))
    logv = np.log(rng.random((b, m_count)))
    draws = model.quantile_sf(-np.expm1(logv / ms[None, :]))
    medians = model.quantile_sf(np.broadcast_to(-np.expm1(math.log(0.5) / ms), (b, m_count)).copy())
    return Prediction(damage=damage, draws=draws, medians=medians, n_resamples=b)


def sorted_resamples(x: np.ndarray, n_resamples: int, rng: np.random.Generator) -> np.ndarray:
    """Nonparametric bootstrap resamples of x, each sorted.

    Parameters
    ----------
    x : ndarray, shape (n,)
        The sample.
    n_resamples : int
        B.
    rng : numpy.random.Generator
        Source of the resample indices.

    Returns
    -------
    ndarray, shape (B, n)
    """
    return np.sort(x[rng.integers(0, x.size, (n_resamples, x.size))], axis=1)


def tail_size(n: int, q: float | None, k_min: int, k_sqrt: float | None = None) -> int:
    """Number k of tail values: ``ceil(q n)`` or ``ceil(k_sqrt sqrt(n))``, in [k_min, n - 1].

    Parameters
    ----------
    n : int
        Sample size.
    q : float or None
        Nominal tail fraction (used when ``k_sqrt`` is None).
    k_min : int
        Smallest tail size.
    k_sqrt : float, optional
        k proportional to the square root of n instead (a rule of thumb of peaks over
        threshold: the bias of the tail approximation shrinks as k / n does).

    Returns
    -------
    int
    """
    k = math.ceil(k_sqrt * math.sqrt(n)) if k_sqrt is not None else math.ceil(float(q) * n)
    return int(min(n - 1, max(k_min, k)))


def sample_lmoments(rows: np.ndarray) -> np.ndarray:
    """Unbiased sample L-moments (l1, l2, t3, t4) of every sorted row.

    Parameters
    ----------
    rows : ndarray, shape (B, k)
        Sorted samples (k >= 4).

    Returns
    -------
    ndarray, shape (B, 4)
        Mean, L-scale, L-skewness and L-kurtosis (the statistics of
        :func:`glstat.fit_batch` with ``method="lmoments"``).
    """
    k = rows.shape[1]
    i = np.arange(k, dtype=float)
    b0 = rows.mean(axis=1)
    b1 = (rows * (i / (k - 1))).mean(axis=1)
    b2 = (rows * (i * (i - 1) / ((k - 1) * (k - 2)))).mean(axis=1)
    b3 = (rows * (i * (i - 1) * (i - 2) / ((k - 1) * (k - 2) * (k - 3)))).mean(axis=1)
    l2 = 2 * b1 - b0
    l3 = 6 * b2 - 6 * b1 + b0
    l4 = 20 * b3 - 30 * b2 + 12 * b1 - b0
    return np.column_stack([b0, l2, l3 / l2, l4 / l2])


def predict_tail_gld(x: np.ndarray, ms: np.ndarray, thresholds: np.ndarray, rng: np.random.Generator,
                     *, q: float = 0.2, k_min: int = 50, n_resamples: int = 200) -> Prediction | None:
    """Tail-weighted GLD: an FKML L-moment fit to the top k values as the conditional tail.

    In every resample the k largest values (k from :func:`tail_size`) are fitted by an FKML
    GLD G (L-moments, :func:`glstat.fit_batch`; of several roots the one covering the k values
    and nearest to the full sample's tail fit; when none covers, the nearest). Above the
    resample's (k+1)-th largest value u, ``F(x) = 1 - (k/n) (1 - G(x))``; at or below u the
    empirical distribution.

    Parameters
    ----------
    x : ndarray
        The sample.
    ms : ndarray, shape (M,)
        Numbers of draws of the maximum.
    thresholds : ndarray, shape (M, D)
        Thresholds of the damage probability, one row per m.
    rng : numpy.random.Generator
        Source of the resamples and of the random maxima.
    q : float
        Nominal tail fraction.
    k_min : int
        Smallest number of tail values.
    n_resamples : int
        Bootstrap resamples B.

    Returns
    -------
    Prediction or None
        None when fewer than two resamples have a fit.
    """
    n = x.size
    k = tail_size(n, q, k_min)
    try:
        ref = glstat.fit(np.sort(x)[n - k:], param="fkml", method="lmoments", warn=False).lambdas[2:]
    except (FitError, ValueError):
        ref = None
    rows = sorted_resamples(x, n_resamples, rng)
    top = rows[:, n - k:]
    lam, _ = fit_batch(sample_lmoments(top), method="lmoments", param="fkml", ref=ref,
                       extremes=np.column_stack([top[:, 0], top[:, -1]]), require_cover=False)
    ok = np.all(np.isfinite(lam), axis=1)
    if ok.sum() < 2:
        return None
    lam = lam[ok]
    dist = gld_fkml(lam[:, 2:3], lam[:, 3:4], loc=lam[:, 0:1], scale=1.0 / np.abs(lam[:, 1:2]))
    model = TailRows(rows=rows[ok], u=rows[ok, n - k - 1], q=k / n, log_sf=dist.logsf, isf=dist.isf)
    return tail_prediction(model, ms, thresholds, rng)


def gpd_zhang_stephens(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Generalized Pareto shape and scale of every row by Zhang and Stephens (2009): the
    library's estimator (:func:`glstat.extremes.peaks_over_threshold.fit_gpd`), vectorised over the rows.

    Parameters
    ----------
    y : ndarray, shape (B, k)
        Exceedances (>= 0), every row sorted.

    Returns
    -------
    xi, sigma : ndarray, shape (B,)
        Shape (> 0: power tail) and scale.
    """
    from glstat.extremes.peaks_over_threshold import fit_gpd

    return fit_gpd(y)


def gpd_scipy_mle(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Generalized Pareto shape and scale of every row by ``scipy.stats.genpareto.fit``.

    Parameters
    ----------
    y : ndarray, shape (B, k)
        Exceedances (>= 0), one sample per row.

    Returns
    -------
    xi, sigma : ndarray, shape (B,)
        Maximum likelihood shape and scale (location fixed at 0); NaN where the fit fails.
    """
    xi = np.full(y.shape[0], np.nan)
    sigma = np.full(y.shape[0], np.nan)
    for b, row in enumerate(y):
        try:
            c, _, s = st.genpareto.fit(row, floc=0.0)
        except (ValueError, RuntimeError, FloatingPointError):
            continue
        xi[b], sigma[b] = c, s
    return xi, sigma


def predict_pot(x: np.ndarray, ms: np.ndarray, thresholds: np.ndarray, rng: np.random.Generator,
                *, estimator: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
                q: float | None = 0.1, k_min: int = 30, k_sqrt: float | None = None,
                n_resamples: int = 200) -> Prediction | None:
    """Peaks over threshold: a generalized Pareto tail above the (k+1)-th largest value.

    In every resample u is the (k+1)-th largest value and the k exceedances ``y = x - u`` are
    fitted by a GPD (shape xi, scale sigma); ``F(x) = 1 - (k/n) S_GPD(x - u)`` above u, the
    empirical distribution at or below it. The bootstrap resamples the whole sample, so u and
    the exceedances vary with it.

    Parameters
    ----------
    x : ndarray
        The sample.
    ms : ndarray, shape (M,)
        Numbers of draws of the maximum.
    thresholds : ndarray, shape (M, D)
        Thresholds of the damage probability, one row per m.
    rng : numpy.random.Generator
        Source of the resamples and of the random maxima.
    estimator : callable
        ``estimator(y) -> (xi, sigma)`` for sorted rows of exceedances
        (:func:`gpd_zhang_stephens`, :func:`gpd_scipy_mle`).
    q : float or None
        Nominal tail fraction (exceedances over the 1 - q sample quantile).
    k_min : int
        Smallest number of exceedances.
    k_sqrt : float, optional
        ``k = ceil(k_sqrt sqrt(n))`` exceedances instead of ``q n`` (:func:`tail_size`).
    n_resamples : int
        Bootstrap resamples B.

    Returns
    -------
    Prediction or None
        None when fewer than two resamples have a fit.
    """
    n = x.size
    k = tail_size(n, q, k_min, k_sqrt)
    rows = sorted_resamples(x, n_resamples, rng)
    u = rows[:, n - k - 1]
    xi, sigma = estimator(rows[:, n - k:] - u[:, None])
    ok = np.isfinite(xi) & np.isfinite(sigma) & (sigma > 0)
    if ok.sum() < 2:
        return None
    u_ok = u[ok]
    c = xi[ok, None]
    s = sigma[ok, None]

    def log_sf(z: np.ndarray) -> np.ndarray:
        return st.genpareto.logsf(z - u_ok[:, None], c, scale=s)

    def isf(p: np.ndarray) -> np.ndarray:
        return u_ok[:, None] + st.genpareto.isf(p, c, scale=s)

    model = TailRows(rows=rows[ok], u=u_ok, q=k / n, log_sf=log_sf, isf=isf)
    return tail_prediction(model, ms, thresholds, rng)


B_FAST = 200  #: resamples of the methods without a per-resample optimisation
B_GPD_MLE = 100  #: resamples of the scipy GPD fit (about 7 ms per fit)
B_LIKELIHOOD = 30  #: resamples of the GLD maximum likelihood fit (0.01-0.1 s per fit)

#: Every method; the index in this tuple seeds its bootstrap (stable when some are left out).
METHODS = (
    Method("rs_moments", "a. predict_maximum(tail=None): the GLD alone, RS, method of moments",
           partial(predict_glstat, fits=(("rs", "moments"),), n_resamples=B_FAST), B_FAST),
    Method("fkml_lmoments", "b. predict_maximum, FKML L-moments",
           partial(predict_glstat, fits=(("fkml", "lmoments"),), n_resamples=B_FAST), B_FAST),
    Method("fkml_mle", "b. predict_maximum, FKML maximum likelihood",
           partial(predict_glstat, fits=(("fkml", "mle"),), n_resamples=B_FAST,
                   likelihood_resamples=B_LIKELIHOOD), B_LIKELIHOOD, slow=True),
    Method("tail_gld", "c. FKML L-moment GLD on the top 20 % (>= 50 values) as the tail",
           partial(predict_tail_gld, q=0.2, k_min=50, n_resamples=B_FAST), B_FAST),
    Method("pot_gpd_mle", "d. GPD above the 0.9 quantile (>= 30 exceedances), scipy ML",
           partial(predict_pot, estimator=gpd_scipy_mle, q=0.1, k_min=30, n_resamples=B_GPD_MLE),
           B_GPD_MLE, slow=True),
    Method("pot_gpd_zs", "d. GPD above the 0.9 quantile (>= 30 exceedances), Zhang-Stephens",
           partial(predict_pot, estimator=gpd_zhang_stephens, q=0.1, k_min=30, n_resamples=B_FAST),
           B_FAST),
    # chosen in a pilot run with another seed (k = 0.05 n, 2 sqrt(n), sqrt(n); tail GLD on the
    # top 10, 20, 30 %): the fewest exceedances gave the best coverage
    Method("pot_gpd_zs_sqrt", "d. GPD on the ceil(sqrt(n)) largest values (>= 20), Zhang-Stephens",
           partial(predict_pot, estimator=gpd_zhang_stephens, q=None, k_min=20, k_sqrt=1.0,
                   n_resamples=B_FAST), B_FAST),
    # appended last, so that the seeds of the methods above are unchanged
    Method("default", "e. predict_maximum defaults: RS moments GLD with a Pareto tail on the "
           "ceil(sqrt(n)) largest values, the calibrated 3.5 / 96.5 % percentiles",
           partial(predict_glstat, fits=(("rs", "moments"),), n_resamples=B_FAST, tail="pareto"),
           B_FAST, interval_level=glstat.resampling.maxima.interval_level(LEVEL, True)),
    Method("default_plain", "e'. the same model read at the plain 5 / 95 % percentiles",
           partial(predict_glstat, fits=(("rs", "moments"),), n_resamples=B_FAST, tail="pareto"),
           B_FAST),
)


# ---------------------------------------------------------------------------------------------
# scoring
# ---------------------------------------------------------------------------------------------
def percentile_interval(values: np.ndarray, level: float) -> tuple[np.ndarray, np.ndarray]:
    """Equal-tailed percentile interval over the first axis.

    Parameters
    ----------
    values : ndarray, shape (B, ...)
        Per-resample values.
    level : float
        Coverage in (0, 1).

    Returns
    -------
    low, high : ndarray
        Shape ``values.shape[1:]``.
    """
    a = 1.0 - level
    lo, hi = np.quantile(values, [a / 2, 1 - a / 2], axis=0)
    return lo, hi


@dataclass
class Tally:
    """The intervals of one method in one (parent, n) cell, over the repetitions.

    Attributes
    ----------
    shape : tuple of int
        (M, D): numbers of draws and damage levels.
    damage : dict of float to (list, list)
        For the level 0.9 and every level of :data:`WIDE_LEVELS`: the damage intervals
        (low and high, shape (M, D) per repetition; NaN: no fit).
    max_lo, max_hi, med_lo, med_hi : list of ndarray
        90 % intervals of the random maximum and of the median of the maximum, shape (M,).
    true_max : list of ndarray
        The fresh true maxima, shape (M,).
    seconds : list of float
        Run time of every call (fit, bootstrap, maxima and damages).
    """

    shape: tuple[int, int]
    damage: dict[float, tuple[list[np.ndarray], list[np.ndarray]]] = field(
        default_factory=lambda: {lv: ([], []) for lv in (LEVEL, *WIDE_LEVELS)})
    max_lo: list[np.ndarray] = field(default_factory=list)
    max_hi: list[np.ndarray] = field(default_factory=list)
    med_lo: list[np.ndarray] = field(default_factory=list)
    med_hi: list[np.ndarray] = field(default_factory=list)
    true_max: list[np.ndarray] = field(default_factory=list)
    seconds: list[float] = field(default_factory=list)

    def add(self, pred: Prediction | None, true_max: np.ndarray, seconds: float,
            level: float = LEVEL) -> None:
        """Record one repetition.

        Parameters
        ----------
        pred : Prediction or None
            The method's bootstrap (None: no fit, counted as a miss).
        true_max : ndarray, shape (M,)
            A fresh draw of the true maximum for every m.
        seconds : float
            Run time of the call.
        level : float
            The level of the percentile pair the method reports (:attr:`Method.interval_level`).
        """
        nan_m = np.full(self.shape[0], np.nan)
        for lv, (lo, hi) in self.damage.items():
            if pred is None:
                a, b = (np.full(self.shape, np.nan),) * 2
            elif (pred.interval is not None and lv == level
                  and math.isclose(level, float(pred.interval_level or math.nan))):
                a, b = pred.interval
            else:
                a, b = percentile_interval(pred.damage, lv)
            lo.append(a)
            hi.append(b)
        mlo, mhi = (nan_m, nan_m) if pred is None else percentile_interval(pred.draws, level)
        dlo, dhi = (nan_m, nan_m) if pred is None else percentile_interval(pred.medians, level)
        for lst, val in ((self.max_lo, mlo), (self.max_hi, mhi), (self.med_lo, dlo),
                         (self.med_hi, dhi), (self.true_max, true_max)):
            lst.append(np.asarray(val, dtype=float))
        self.seconds.append(seconds)


def score(lo: np.ndarray, hi: np.ndarray, truth: np.ndarray) -> dict[str, np.ndarray]:
    """Coverage, misses above and below, failures and mean width over the repetitions (axis 0).

    Parameters
    ----------
    lo, hi : ndarray, shape (R, ...)
        Intervals (NaN where the method had no fit).
    truth : ndarray
        True values, broadcast against ``lo``.

    Returns
    -------
    dict
        ``coverage``, ``miss_above`` (truth above the interval), ``miss_below``, ``failed``
        (shares of R) and ``mean_width`` (over the repetitions with a fit).
    """
    failed = np.isnan(lo) | np.isnan(hi)
    with np.errstate(invalid="ignore"):
        above = ~failed & (truth > hi)
        below = ~failed & (truth < lo)
        width = np.where(failed, np.nan, hi - lo)
    covered = ~failed & ~above & ~below
    mean_width = (np.nanmean(width, axis=0) if (~failed).any()
                  else np.full(lo.shape[1:], np.nan))
    return {"coverage": covered.mean(axis=0), "miss_above": above.mean(axis=0),
            "miss_below": below.mean(axis=0), "failed": failed.mean(axis=0),
            "mean_width": mean_width}


def interval_shares(lo: np.ndarray, hi: np.ndarray) -> dict[str, np.ndarray]:
    """How often a damage interval says nothing, or says 0 for certain.

    Parameters
    ----------
    lo, hi : ndarray, shape (R, ...)
        Intervals (NaN where the method had no fit).

    Returns
    -------
    dict
        Shares of R: ``zero_interval`` (the upper end is at most 1e-12: a confident 0 %, a
        miss whenever the true damage is not 0), ``undetermined`` (at least 0.9 wide:
        :data:`glstat.prediction.UNDETERMINED_WIDTH`) and ``wide`` (wider than 0.5, where the
        library estimates the data that would narrow it).
    """
    with np.errstate(invalid="ignore"):
        return {"zero_interval": (hi <= 1e-12).mean(axis=0),
                "undetermined": (hi - lo >= 0.9).mean(axis=0),
                "wide": (hi - lo > 0.5).mean(axis=0)}


def tally_rows(tally: Tally, parent: Parent, n: int, ms: np.ndarray, damages: Sequence[float],
               true_median: np.ndarray, method: Method) -> list[dict[str, Any]]:
    """CSV rows of one method in one (parent, n) cell.

    Parameters
    ----------
    tally : Tally
        The recorded repetitions.
    parent : Parent
        The parent.
    n : int
        Sample size.
    ms : ndarray, shape (M,)
        Numbers of draws.
    damages : sequence of float
        True damage probabilities.
    true_median : ndarray, shape (M,)
        True median of the maximum of m draws.
    method : Method
        The method.

    Returns
    -------
    list of dict
        One row per (m, d) for the damage, then two per m for the maximum (``max_draw``: the
        interval of the random maxima against a fresh true maximum; ``max_median``: the
        interval of the medians against the true median).
    """
    reps = len(tally.seconds)
    base = {"parent": parent.name, "n": n, "method": method.name, "reps": reps,
            "n_resamples": method.n_resamples, "seconds": float(np.mean(tally.seconds))}
    d = np.asarray(damages, dtype=float)
    sc = {lv: score(np.array(lo), np.array(hi), d[None, None, :])
          for lv, (lo, hi) in tally.damage.items()}
    shares = interval_shares(*(np.array(v) for v in tally.damage[method.interval_level]))
    wide_nan = {k: math.nan for lv in WIDE_LEVELS for k in (f"coverage_{lv * 100:.0f}",
                                                            f"mean_width_{lv * 100:.0f}")}
    wide_nan.update(dict.fromkeys(shares, math.nan))
    out = []
    for i, m in enumerate(ms):
        for j, dj in enumerate(d):
            wide = {}
            for lv in WIDE_LEVELS:
                wide[f"coverage_{lv * 100:.0f}"] = float(sc[lv]["coverage"][i, j])
                wide[f"mean_width_{lv * 100:.0f}"] = float(sc[lv]["mean_width"][i, j])
            wide.update({key: float(val[i, j]) for key, val in shares.items()})
            out.append({**base, "m": float(m), "quantity": "damage", "true_value": float(dj),
                        **{key: float(val[i, j])
                           for key, val in sc[method.interval_level].items()}, **wide})
    draw = score(np.array(tally.max_lo), np.array(tally.max_hi), np.array(tally.true_max))
    med = score(np.array(tally.med_lo), np.array(tally.med_hi), true_median[None, :])
    for i, m in enumerate(ms):
        for quantity, res, truth in (("max_draw", draw, math.nan),
                                     ("max_median", med, true_median[i])):
            out.append({**base, "m": float(m), "quantity": quantity, "true_value": float(truth),
                        **{key: float(val[i]) for key, val in res.items()}, **wide_nan})
    return out


# ---------------------------------------------------------------------------------------------
# the run
# ---------------------------------------------------------------------------------------------
def run(parents: Sequence[Parent], ns: Sequence[int], ms: np.ndarray, damages: Sequence[float],
        methods: Sequence[Method], reps: int, slow_reps: int, seed: int,
        log: Callable[[str], None]) -> list[dict[str, Any]]:
    """Simulate every (parent, n) cell and score every method.

    Data set r of parent p and size n comes from ``SeedSequence([seed, p, n, r])`` (the same for
    every method and every m); the bootstrap of method j on it from
    ``SeedSequence([seed, p, n, r, 1000 + j])`` with j the method's index in :data:`METHODS`.

    Parameters
    ----------
    parents : sequence of Parent
        Parents.
    ns : sequence of int
        Sample sizes.
    ms : ndarray, shape (M,)
        Numbers of draws of the maximum.
    damages : sequence of float
        True damage probabilities.
    methods : sequence of Method
        Methods.
    reps : int
        Repetitions R per cell.
    slow_reps : int
        Repetitions of the slow methods (the first ones of the R).
    seed : int
        Root seed.
    log : callable
        Progress messages.

    Returns
    -------
    list of dict
        The CSV rows.
    """
    rows: list[dict[str, Any]] = []
    # one untimed call per method first: compiled kernels loaded, caches warm
    x0 = np.random.default_rng(seed).standard_normal(200)
    t0_grid = true_thresholds(st.norm(), ms, damages)
    for mt in methods:
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            mt.func(x0, ms, t0_grid, np.random.default_rng(seed))
    for parent in parents:
        p_idx = PARENTS.index(parent)
        thresholds = true_thresholds(parent.dist, ms, damages)
        true_median = parent.dist.isf(-np.expm1(math.log(0.5) / ms))
        for n in ns:
            t_cell = time.perf_counter()
            tallies = {mt.name: Tally(shape=thresholds.shape) for mt in methods}
            for r in range(reps):
                g_data, g_truth = (np.random.default_rng(s) for s in
                                   np.random.SeedSequence([seed, p_idx, n, r]).spawn(2))
                x = np.asarray(parent.dist.rvs(size=n, random_state=g_data), dtype=float)
                true_max = parent.dist.isf(-np.expm1(np.log(g_truth.random(ms.size)) / ms))
                for mt in methods:
                    if mt.slow and r >= slow_reps:
                        continue
                    g = np.random.default_rng(
                        np.random.SeedSequence([seed, p_idx, n, r, 1000 + METHODS.index(mt)]))
                    t0 = time.perf_counter()
                    # in the main thread only: the fits' warnings are expected and not shown
                    with warnings.catch_warnings(), np.errstate(all="ignore"):
                        warnings.simplefilter("ignore")
                        pred = mt.func(x, ms, thresholds, g)
                    tallies[mt.name].add(pred, true_max, time.perf_counter() - t0,
                                         mt.interval_level)
            for mt in methods:
                rows += tally_rows(tallies[mt.name], parent, n, ms, damages, true_median, mt)
            log(f"{parent.name:10s} n={n:<5d} {time.perf_counter() - t_cell:7.1f} s")
    return rows


# ---------------------------------------------------------------------------------------------
# tables
# ---------------------------------------------------------------------------------------------
def fmt_pct(v: float) -> str:
    """A share as a percentage ("—" for NaN).

    Parameters
    ----------
    v : float
        Share in [0, 1].

    Returns
    -------
    str
    """
    return "—" if not np.isfinite(v) else f"{100 * v:.0f}"


def above_share(row: dict[str, Any]) -> float:
    """Share of the misses (failures excluded) that lie above the interval.

    Parameters
    ----------
    row : dict
        A CSV row.

    Returns
    -------
    float
        NaN without misses.
    """
    miss = row["miss_above"] + row["miss_below"]
    return row["miss_above"] / miss if miss > 0 else math.nan


def print_full_table(rows: list[dict[str, Any]]) -> None:
    """Every damage cell and every maximum cell, one line each.

    Parameters
    ----------
    rows : list of dict
        The CSV rows.
    """
    print("\nDamage probability, 90 % interval: coverage (%), misses above (% of misses), "
          "failed fits (%), mean width, coverage of the 95 % and 98 % intervals (%), s per call")
    print(f"{'parent':10s} {'n':>5s} {'m':>7s} {'d':>5s} {'method':16s} {'R':>4s} {'cover':>5s} "
          f"{'above':>5s} {'fail':>4s} {'width':>7s} {'c95':>4s} {'c98':>4s} {'s':>7s}")
    for r in rows:
        if r["quantity"] != "damage":
            continue
        print(f"{r['parent']:10s} {r['n']:5d} {r['m']:7.0e} {r['true_value']:5.2f} {r['method']:16s} "
              f"{r['reps']:4d} {fmt_pct(r['coverage']):>5s} {fmt_pct(above_share(r)):>5s} "
              f"{fmt_pct(r['failed']):>4s} {r['mean_width']:7.3f} {fmt_pct(r['coverage_95']):>4s} "
              f"{fmt_pct(r['coverage_98']):>4s} {r['seconds']:7.3f}")
    print("\nMaximum of m draws, 90 % intervals: random draws vs a fresh true maximum, medians vs "
          "the true median: coverage (%), misses above (% of misses)")
    print(f"{'parent':10s} {'n':>5s} {'m':>7s} {'method':16s} {'R':>4s} {'draw':>5s} {'above':>5s} "
          f"{'median':>6s} {'above':>5s}")
    by_key = {(r["parent"], r["n"], r["m"], r["method"], r["quantity"]): r for r in rows}
    for r in rows:
        if r["quantity"] != "max_draw":
            continue
        med = by_key[(r["parent"], r["n"], r["m"], r["method"], "max_median")]
        print(f"{r['parent']:10s} {r['n']:5d} {r['m']:7.0e} {r['method']:16s} {r['reps']:4d} "
              f"{fmt_pct(r['coverage']):>5s} {fmt_pct(above_share(r)):>5s} "
              f"{fmt_pct(med['coverage']):>6s} {fmt_pct(above_share(med)):>5s}")


def print_summary(rows: list[dict[str, Any]], methods: Sequence[Method], title: str,
                  keep: Callable[[dict[str, Any]], bool], column: str = "coverage") -> None:
    """Markdown table: mean damage coverage per parent x method with the worst cell.

    Parameters
    ----------
    rows : list of dict
        The CSV rows.
    methods : sequence of Method
        Methods (columns).
    title : str
        Heading line.
    keep : callable
        Selects the damage rows aggregated.
    column : str
        The coverage shown: ``"coverage"`` (90 % interval, with the share of the misses above
        it), ``"coverage_95"`` or ``"coverage_98"`` (the widened intervals).
    """
    sel = [r for r in rows if r["quantity"] == "damage" and keep(r)]
    if not sel:
        return
    parents = list(dict.fromkeys(r["parent"] for r in sel))
    names = [mt.name for mt in methods]
    print(f"\n{title}\n")
    print("| parent | " + " | ".join(names) + " |")
    print("|---" * (len(names) + 1) + "|")
    for p in [*parents, "all parents"]:
        cells = []
        for name in names:
            rs = [r for r in sel if r["method"] == name and (p == "all parents" or r["parent"] == p)]
            if not rs:
                cells.append("—")
                continue
            cov = np.array([r[column] for r in rs])
            w = np.array([r["reps"] for r in rs])
            worst = min(rs, key=lambda r: r[column])
            up = ""
            if column == "coverage":
                above = np.sum([r["miss_above"] * r["reps"] for r in rs])
                miss = np.sum([(r["miss_above"] + r["miss_below"]) * r["reps"] for r in rs])
                up = f", {100 * above / miss:.0f} % of misses above" if miss > 0 else ""
            cells.append(f"{fmt_pct(float(np.average(cov, weights=w)))} "
                         f"(min {fmt_pct(worst[column])}{up})")
        print(f"| {p} | " + " | ".join(cells) + " |")
    print("\nWorst cell of each method (parent, n, m, d: coverage %; of the 90 % interval: "
          "misses above %, failed fits %):")
    for name in names:
        rs = [r for r in sel if r["method"] == name]
        if rs:
            w = min(rs, key=lambda r: r[column])
            extra = (f", above {fmt_pct(w['miss_above'])} %, failed {fmt_pct(w['failed'])} %"
                     if column == "coverage" else "")
            print(f"  {name:16s} {w['parent']}, n={w['n']}, m={w['m']:.0e}, d={w['true_value']}: "
                  f"{fmt_pct(w[column])} %{extra} (R = {w['reps']})")
    per_parent = {name: [np.average([r[column] for r in sel if r["method"] == name and
                                     r["parent"] == p],
                                    weights=[r["reps"] for r in sel if r["method"] == name and
                                             r["parent"] == p])
                         for p in parents if any(r["method"] == name and r["parent"] == p
                                                 for r in sel)]
                  for name in names}
    ok = [name for name in names if per_parent[name] and min(per_parent[name]) >= 0.85]
    print(f"Mean coverage >= 85 % for every parent: {', '.join(ok) if ok else 'none'}")


def print_times(rows: list[dict[str, Any]], methods: Sequence[Method]) -> None:
    """Markdown table: seconds per call (fit, bootstrap, maxima, damages) per method and n.

    Parameters
    ----------
    rows : list of dict
        The CSV rows.
    methods : sequence of Method
        Methods (rows of the table).
    """
    ns = sorted({r["n"] for r in rows})
    print("\nSeconds per call (fit + bootstrap + every maximum and damage), mean over parents\n")
    print("| method | B | " + " | ".join(f"n = {n}" for n in ns) + " |")
    print("|---" * (len(ns) + 2) + "|")
    for mt in methods:
        cells = []
        for n in ns:
            s = {r["parent"]: r["seconds"] for r in rows
                 if r["method"] == mt.name and r["n"] == n and r["quantity"] == "damage"}
            cells.append(f"{np.mean(list(s.values())):.3f}" if s else "—")
        print(f"| {mt.name} | {mt.n_resamples} | " + " | ".join(cells) + " |")


def write_csv(rows: list[dict[str, Any]], path: Path) -> None:
    """Write the rows as CSV (the folder is created).

    Parameters
    ----------
    rows : list of dict
        The rows (same keys).
    path : Path
        Output file.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def parse_args(argv: Sequence[str] | None = None) -> argparse.Namespace:
    """Command-line options.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default ``sys.argv[1:]``).

    Returns
    -------
    argparse.Namespace
    """
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true",
                    help="n = 1000, m = 1e3, R = 30, slow R = 10 (under 2 minutes)")
    ap.add_argument("--reps", type=int, default=None, help="repetitions R per cell (default 100)")
    ap.add_argument("--slow-reps", type=int, default=None,
                    help="repetitions of the slow methods (default 30; at most R)")
    ap.add_argument("--n", type=int, nargs="+", default=None, help="sample sizes (200 1000 5000)")
    ap.add_argument("--m", type=float, nargs="+", default=None,
                    help="draws of the maximum (1e2 1e3 1e4 1e6)")
    ap.add_argument("--parents", nargs="+", choices=[p.name for p in PARENTS], default=None)
    ap.add_argument("--methods", nargs="+", choices=[m.name for m in METHODS], default=None)
    ap.add_argument("--seed", type=int, default=20240607, help="root seed")
    ap.add_argument("--out", type=Path, default=OUT, help=f"CSV output (default {OUT})")
    ap.add_argument("--brief", action="store_true", help="summaries only, not every cell")
    return ap.parse_args(argv)


def main(argv: Sequence[str] | None = None) -> None:
    """Run the benchmark, print the tables and write the CSV.

    Parameters
    ----------
    argv : sequence of str, optional
        Command-line arguments.
    """
    args = parse_args(argv)
    reps = args.reps if args.reps is not None else (30 if args.quick else 100)
    slow = args.slow_reps if args.slow_reps is not None else (10 if args.quick else 30)
    slow = min(slow, reps)
    ns = args.n or ([1000] if args.quick else [200, 1000, 5000])
    ms = np.array(args.m or ([1e3] if args.quick else [1e2, 1e3, 1e4, 1e6]), dtype=float)
    parents = [p for p in PARENTS if args.parents is None or p.name in args.parents]
    methods = [m for m in METHODS if args.methods is None or m.name in args.methods]
    print(f"glstat {glstat.__version__}; parents {[p.name for p in parents]}; n {ns}; "
          f"m {ms.tolist()}; d {list(DAMAGES)}; R {reps} (slow methods {slow}); seed {args.seed}")
    for mt in methods:
        print(f"  {mt.name:16s} B = {mt.n_resamples:4d}{' (slow)' if mt.slow else ''}: {mt.label}")
    t0 = time.perf_counter()
    rows = run(parents, ns, ms, DAMAGES, methods, reps, slow, args.seed,
               log=lambda s: print(f"  [{time.perf_counter() - t0:7.0f} s] {s}", file=sys.stderr,
                                   flush=True))
    elapsed = time.perf_counter() - t0
    write_csv(rows, args.out)
    if not args.brief:
        print_full_table(rows)
    print_summary(rows, methods, "Damage coverage (%) of the 90 % interval, every n, m and d "
                  "(mean over the cells, weighted by R; min = worst cell)", lambda r: True)
    if 1000 in ns and 1e3 in ms:
        print_summary(rows, methods, "Damage coverage (%) of the 90 % interval, n = 1000, m = 1e3 "
                      "(mean over the four d)", lambda r: r["n"] == 1000 and r["m"] == 1e3)
    for lv in WIDE_LEVELS:
        print_summary(rows, methods, f"Damage coverage (%) of the widened {lv * 100:.0f} % percentile "
                      "interval (the same resamples), every n, m and d", lambda r: True,
                      column=f"coverage_{lv * 100:.0f}")
    print_times(rows, methods)
    print(f"\n{len(rows)} rows written to {args.out}; total {elapsed:.0f} s")


if __name__ == "__main__":
    main()
