"""The result of :func:`glstat.bootstrap`: :class:`BootstrapFit`, the GLD fits of the
resamples, with their intervals, the maximum of n draws and the probabilities of integrity
and damage across them."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from _glstat_runtime.validation import check_level, draws_or_count

from ..errors import FitError
from ..extremes.counts import ObservedCounts, RowCounts, as_count
from ..extremes.damage import damage_probability as _damage
from ..extremes.damage import integrity_probability as _integrity
from ..extremes.order_statistics import maximum as _maximum
from ..fitting import GLDFit
from ._arguments import stream_seed
from ._diagnostics import BootstrapWarning, branch_note
from ._driver import jackknife_lambdas
from ._intervals import (
    LAMBDA_NAMES,
    BootstrapInterval,
    ConfidenceIntervalAccess,
    check_ci_method,
    finite_rows,
    make_interval,
    statistic_values,
)
from ._lambda_rows import FAMILY, frozen_batch, max_quantiles
from ._tables import summary_frame
from .maxima import (
    BootstrapMaximum,
    BootstrapProbability,
    interval_level,
    reach_compatible_tails,
    resample_count_maximum,
    resample_maximum,
    resample_probability,
    row_distributions,
)

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["BootstrapFit"]


@dataclass(frozen=True)
class BootstrapFit:
    """GLD fits of bootstrap resamples (result of :func:`bootstrap`).

    Attributes
    ----------
    fit : GLDFit
        Fit of the full sample (the point estimate).
    lambdas : pandas.DataFrame
        One row per resample (index ``resample``): ``lambda1..lambda4`` (NaN for a failed
        resample); ``n_roots``, the number of valid roots or candidates found; ``region``,
        the RS region (1-6) of the fit (0 for a failed resample and for FKML, which has no
        regions); ``branch_jump``, True when the fit's lambda3 or lambda4 lies more than 12
        robust standard deviations (1.4826 times the median absolute deviation of the
        successful resamples' values) from the full-sample fit's: a root of another branch.
        Resamples in several regions or on several branches make the percentile intervals
        of the lambdas meaningless (see :attr:`branch_note`).
    statistics : pandas.DataFrame or None
        Per resample: the matched statistics (moments, rho or L-moments; not for the
        data-based methods), the resample's ``min`` and ``max`` and, for the compiled
        methods, ``covers`` (whether a root covering them exists). The support of every
        fit covers its resample's range unless the full-sample fit does not cover the data
        either (then a warning gives the count). None only for ``nan_policy="propagate"``
        with non-finite data.
    failed : pandas.DataFrame
        The resamples without a fit: ``resample``, ``reason`` (``"statistics undefined"``,
        ``"statistics out of range"``, ``"no root"``, ``"no root whose support covers the
        resample"``, ``"fit error (...)"``) and ``detail`` (the full message).
    n_resamples : int
        Number of resamples B.
    confidence_level : float
        Default nominal coverage of the intervals.
    kind : str
        ``"nonparametric"`` or ``"parametric"``.
    method, param : str
        Fitting method and parameterisation.
    options : dict
        Fitting options (e.g. ``u``).
    """

    fit: GLDFit
    lambdas: pd.DataFrame
    statistics: pd.DataFrame | None
    failed: pd.DataFrame
    n_resamples: int
    confidence_level: float
    kind: str
    method: str
    param: str
    options: dict[str, Any] = field(default_factory=dict)
    _data: np.ndarray | None = field(default=None, repr=False, compare=False)
    _entropy: tuple[int, ...] = field(default=(), repr=False, compare=False)
    _cache: dict = field(default_factory=dict, repr=False, compare=False)
    _grouping: tuple | None = field(default=None, repr=False, compare=False)
    _tails: np.ndarray | None = field(default=None, repr=False, compare=False)
    _full_tail: np.ndarray | None = field(default=None, repr=False, compare=False)
    _profile: np.ndarray | None = field(default=None, repr=False, compare=False)

    @property
    def tail(self) -> pd.DataFrame | None:
        """The generalized Pareto tails (:meth:`with_pareto_tail`), else None.

        One row per resample (index ``resample``, NaN where the resample has no fit) and a
        first row ``"full"`` for the full sample: ``u`` (start of the tail, units of the data),
        ``q`` (its probability, k / N), ``xi`` (shape) and ``sigma`` (scale, units of the
        data).
        """
        if self._tails is None or self._full_tail is None:
            return None
        import pandas as pd

        rows = np.vstack([self._full_tail[None, :], self._tails])
        index = pd.Index(["full", *range(self.n_resamples)], name="resample")
        return pd.DataFrame(rows, index=index, columns=["u", "q", "xi", "sigma"])

    @property
    def tail_size(self) -> int | None:
        """k, the number of largest values each Pareto tail is fitted to (None without tails)."""
        return self.options.get("tail_size") if self._tails is not None else None

    @property
    def n_groups(self) -> int | None:
        """The number of groups G of a bootstrap with ``groups`` (None without)."""
        return None if self._grouping is None else int(np.size(self._grouping[0]))

    @property
    def counts(self) -> ObservedCounts | None:
        """The number of values per group (a bootstrap with ``groups``), else None."""
        return None if self._grouping is None else ObservedCounts(self._grouping[0])

    def resampled_counts(self) -> RowCounts:
        """Per successful resample, the numbers of values of its drawn groups (with ``groups``)."""
        if self._grouping is None:
            raise TypeError("the bootstrap has no groups: give n or count")
        sizes, choices = self._grouping[:2]
        return RowCounts.from_choices(sizes, choices[self._ok()])

    def _ok(self) -> np.ndarray:
        """Which resamples have a fit (and, with tails, a tail fit): shape (B,)."""
        lam = self.lambdas[list(LAMBDA_NAMES)].to_numpy(dtype=float)
        ok = np.all(np.isfinite(lam), axis=1)
        if self._tails is not None:
            ok &= np.all(np.isfinite(self._tails), axis=1)
        return ok

    def _tail_rows(self) -> np.ndarray | None:
        """The Pareto tails of the resamples of :meth:`_lam` (None without tails)."""
        return None if self._tails is None else self._tails[self._ok()]

    def _full_dist(self):
        """The full-sample model: the GLD fit, with its Pareto tail when there is one."""
        if self._full_tail is None:
            return self.fit.dist
        from ..extremes.spliced_tail import ParetoTailGLD

        u, q, xi, sigma = (float(v) for v in self._full_tail)
        return ParetoTailGLD(self.fit.dist, u=u, q=q, xi=xi, sigma=sigma, tail_size=self.tail_size)

    def with_pareto_tail(self, tail_size: str | float | int = "sqrt") -> BootstrapFit:
        """The same bootstrap with a generalized Pareto tail on every fit.

        Each resample's (and the full sample's) GLD is kept below ``u``, the (k+1)-th largest
        of its values, and a generalized Pareto tail fitted to its k largest values
        (Zhang–Stephens) replaces it above (:class:`glstat.ParetoTailGLD`, docs/method.md
        §6). :meth:`maximum`, :meth:`damage_probability` and :meth:`integrity_probability`
        then use these spliced models, as do :meth:`dists` and the damage functions given the
        bootstrap, and their intervals read the calibrated percentile pair (the 3.5 % and
        96.5 % percentiles for a nominal 90 %, :func:`glstat.resampling.maxima.interval_level`).
        The lambdas, their intervals and :meth:`batch` stay those of the GLD fits.

        When the full sample's tail is bounded (shape xi < 0), the bootstrap understates how
        far its end may lie (every resample repeats the largest values): the interval of a
        probability at a threshold above ``u`` then also reaches the probability under the
        tails that a likelihood-ratio test of the full sample's exceedances keeps at the
        interval's level (the profile likelihood of the end point, over the regular shapes
        xi >= -1/2: :func:`glstat.extremes.peaks_over_threshold.tail_profile`), so it is not
        [0, 0] when the data are compatible with a tail reaching the threshold.

        Parameters
        ----------
        tail_size : "sqrt", float or int
            k: ``ceil(sqrt(N))`` (at least 20; the default, the best calibrated in
            docs/benchmarks.md "calibration"), a fraction of N, or a count. With a rule (not
            a count), fewer (at least 10) when the largest values form a bump of their own
            rather than a tail (their fitted shape is below -1/2:
            :func:`glstat.extremes.peaks_over_threshold.checked_tail_size`). With groups, k
            is set from the full sample and each resample's tail probability is k over its
            own size.

        Returns
        -------
        BootstrapFit

        Raises
        ------
        ValueError
            Without the data (``nan_policy="propagate"``), with fewer than 21 values for the
            default ``tail_size``, or when the full sample's tail cannot be fitted.

        Examples
        --------
        >>> import numpy as np, glstat
        >>> x = np.random.default_rng(0).gamma(4.0, 250.0, 1000)   # pressures, MPa
        >>> bt = glstat.bootstrap(x, n_resamples=100, rng=1).with_pareto_tail()
        >>> bt.tail_size, bt.tail.shape
        (32, (101, 4))
        """
        from ..extremes.peaks_over_threshold import tail_profile, tail_size_for
        from ..extremes.spliced_tail import pareto_tail_rows
        from ._arguments import resample_seeds
        from ._driver import draw

        x = self._data
        if x is None:
            raise ValueError("the bootstrap holds no data (nan_policy='propagate'): no tail")
        k = tail_size_for(x, tail_size)
        full = pareto_tail_rows(x[None, x.size - k - 1:], x.size, k)[0]
        if not np.all(np.isfinite(full)):
            raise ValueError("the generalized Pareto fit of the sample's tail failed (its "
                             "largest values are all equal?): use another tail_size")
        groups = None if self._grouping is None else self._grouping[2]
        seeds = resample_seeds(self._entropy, self.n_resamples)
        tops = np.empty((self.n_resamples, k + 1))
        sizes = np.empty(self.n_resamples)
        fam = FAMILY[self.param]
        for r, seed in enumerate(seeds):
            sample = draw(x, np.random.default_rng(seed), self.kind, self.fit.lambdas, fam, groups)
            sizes[r] = sample.size
            if sample.size <= k:
                tops[r] = np.nan
                continue
            tops[r] = np.sort(np.partition(sample, sample.size - k - 1)[sample.size - k - 1:])
        tails = np.full((self.n_resamples, 4), np.nan)
        good = np.all(np.isfinite(tops), axis=1)
        if good.any():
            tails[good] = pareto_tail_rows(tops[good], sizes[good], k)
        options = dict(self.options, tail_size=k)
        return replace(self, options=options, _tails=tails, _full_tail=full, _cache={},
                       failed=self._tail_failures(tails, sizes, k),
                       _profile=tail_profile(x[x.size - k:] - x[x.size - k - 1]))

    def _tail_failures(self, tails: np.ndarray, sizes: np.ndarray, k: int) -> pd.DataFrame:
        """:attr:`failed` with the resamples whose GLD was fitted but whose tail was not."""
        import pandas as pd

        lam = self.lambdas[list(LAMBDA_NAMES)].to_numpy(dtype=float)
        bad = np.flatnonzero(np.all(np.isfinite(lam), axis=1) & ~np.all(np.isfinite(tails), axis=1))
        if bad.size == 0:
            return self.failed
        detail = [f"no Pareto tail: the resample has {int(sizes[r])} values, at most k = {k}"
                  if sizes[r] <= k else
                  f"no Pareto tail: the generalized Pareto fit of the resample's {k} largest "
                  "values failed (they are all equal to the next one?)" for r in bad]
        extra = pd.DataFrame({"resample": bad.astype(np.int64), "reason": "no Pareto tail",
                              "detail": detail})
        out = pd.concat([self.failed, extra], ignore_index=True)
        return out.sort_values("resample", kind="stable").reset_index(drop=True)


    def _draw_counts(self, n, count):
        """(n, None, None) for a fixed n, or (None, full-sample count, RowCounts per resample)."""
        draws_or_count(n, count)
        if count is not None:
            c = as_count(count)
            return None, c, RowCounts.common(c, self._lam().shape[0])
        if n is not None:
            return n, None, None
        if self._grouping is None:
            raise TypeError("n (the number of points of the analysed area) or count (a random "
                            "number of them) is required; a bootstrap with groups defaults to "
                            "its groups' sizes")
        return None, self.counts, self.resampled_counts()

    # -- basic views ----------------------------------------------------------------------
    @property
    def n_failed(self) -> int:
        """Number of resamples without a fit."""
        return len(self.failed)

    @property
    def n_successful(self) -> int:
        """Number of resamples with a fit."""
        return self.n_resamples - self.n_failed

    @property
    def _fam(self) -> int:
        return FAMILY[self.param]

    def _lam(self) -> np.ndarray:
        """Lambdas of the successful resamples, shape (n_successful, 4)."""
        if "lam" not in self._cache:
            lam = self.lambdas[list(LAMBDA_NAMES)].to_numpy(dtype=float)
            self._cache["lam"] = np.ascontiguousarray(lam[self._ok()])
        return self._cache["lam"]

    def _seed(self, key: int) -> np.random.SeedSequence:
        return stream_seed(self._entropy, self.n_resamples, key)

    def _level(self, confidence_level) -> float:
        return self.confidence_level if confidence_level is None else check_level(confidence_level)

    def dists(self) -> list:
        """The model of every successful resample, in resample order: its GLD, or with
        :meth:`with_pareto_tail` its :class:`glstat.ParetoTailGLD`."""
        if "dists" not in self._cache:
            self._cache["dists"] = row_distributions(self._lam(), self.param, self._tail_rows())
        return list(self._cache["dists"])

    def __glstat_distributions__(self) -> list:
        """The bootstrap distributions, for :mod:`glstat.extremes.damage` and :mod:`glstat.extremes`."""
        return self.dists()

    def batch(self):
        """All successful bootstrap GLDs as one frozen scipy distribution with array parameters.

        Returns
        -------
        frozen ``gld_rs`` or ``gld_fkml``
            Parameters of shape (n_successful, 1): ``batch().ppf([0.5, 0.9])`` has shape
            (n_successful, 2).
        """
        return frozen_batch(self._lam(), self.param)

    def _regions(self) -> np.ndarray:
        """RS region of every successful resample (0 for FKML)."""
        return self.lambdas["region"].to_numpy()[self._ok()]

    @property
    def branch_note(self) -> str:
        """Why the percentile intervals of the lambdas are not meaningful; "" when they are.

        Non-empty when the successful resample fits fall in more than one RS region (lambda2
        changes sign and lambda3, lambda4 cross 0: e.g. near-logistic data, whose moment fits
        have lambda3, lambda4 near 0) or when some jumped to another root branch
        (``lambdas["branch_jump"]``). The distributions may then be nearly identical while
        their lambdas are not comparable; intervals of quantiles, moments or probabilities
        (:meth:`confidence_interval` with ``statistic``) are unaffected.
        """
        if "note" not in self._cache:
            lam = self.lambdas[list(LAMBDA_NAMES)].to_numpy(dtype=float)
            ok = np.all(np.isfinite(lam), axis=1)
            self._cache["note"] = branch_note(self.lambdas["region"].to_numpy()[ok],
                                              self.lambdas["branch_jump"].to_numpy()[ok],
                                              self.param, self.fit.region)
        return self._cache["note"]

    def standard_error(self) -> pd.Series:
        """Bootstrap standard errors of lambda1..lambda4 (divisor B - 1, successful resamples).

        Warns
        -----
        BootstrapWarning
            When :attr:`branch_note` is not empty (the note is also in the Series'
            ``attrs["note"]``); :meth:`summary` then gives the standard errors per region.
        """
        import pandas as pd

        se = pd.Series(np.std(self._lam(), axis=0, ddof=1), index=list(LAMBDA_NAMES),
                       name="standard_error")
        se.attrs["note"] = self.branch_note
        if self.branch_note:
            warnings.warn(f"standard errors of the lambdas: {self.branch_note}", BootstrapWarning,
                          stacklevel=2)
        return se

    # -- statistics of the resamples --------------------------------------------------------
    def _jackknife_lambdas(self) -> np.ndarray:
        """Lambdas of the delete-a-group jackknife samples of the data (cached)."""
        if "jack" not in self._cache:
            if self._data is None:
                raise ValueError("BCa needs the data, which this BootstrapFit does not hold")
            self._cache["jack"] = jackknife_lambdas(self._data, self.method, self.param,
                                                    self.options, self.fit.lambdas, self._seed(0))
        return self._cache["jack"]

    @property
    def confidence_interval(self) -> ConfidenceIntervalAccess:
        """Bootstrap confidence intervals: call it, or read it as scipy's attribute.

        ``bf.confidence_interval(method="percentile", confidence_level=None, statistic=None,
        *, vectorized=False, names=None)`` returns a :class:`BootstrapInterval` (see
        :meth:`ConfidenceIntervalAccess.__call__`). Read as an attribute, as
        ``scipy.stats.bootstrap(...).confidence_interval`` is, it is the default interval
        (percentile, :attr:`confidence_level`, of the lambdas): ``.low``, ``.high`` (arrays
        of shape (4,)), ``low, high = bf.confidence_interval`` and ``.standard_error``.
        """
        return ConfidenceIntervalAccess(self)

    @property
    def bootstrap_distribution(self) -> np.ndarray:
        """The resampled lambdas in scipy's layout: shape (4, n_successful).

        Row i holds lambda(i+1) of every resample with a fit, in resample order (the
        successful rows of :attr:`lambdas`, transposed), as
        ``scipy.stats.bootstrap(...).bootstrap_distribution`` holds a vector statistic with
        its resamples along the last axis. Failed resamples are left out (they are the NaN
        rows of :attr:`lambdas`), so the last axis is shorter than :attr:`n_resamples` when
        some failed. A read-only view.
        """
        out = self._lam().T
        out.flags.writeable = False
        return out

    def _confidence_interval(
        self,
        method: str = "percentile",
        confidence_level: float | None = None,
        statistic: Callable[[Any], Any] | None = None,
        *,
        vectorized: bool = False,
        names: tuple[str, ...] | None = None,
        stacklevel: int = 2,
    ) -> BootstrapInterval:
        """The interval of :class:`ConfidenceIntervalAccess` (its call documents the
        arguments); warnings point to the frame ``stacklevel`` levels up from this one."""
        note = self.branch_note if statistic is None else ""
        if note:
            warnings.warn(f"interval of the lambdas: {note}", BootstrapWarning, stacklevel=stacklevel)
        return self._interval(method, confidence_level, statistic, vectorized, names, self._lam(), note,
                              stacklevel + 1)

    def _interval(self, method, confidence_level, statistic, vectorized, names, lam, note,
                  stacklevel: int = 2):
        m = check_ci_method(method)
        level = self._level(confidence_level)
        if lam.shape[0] < 2:
            raise FitError(f"only {lam.shape[0]} of {self.n_resamples} resamples have a fit: no "
                           "bootstrap interval")
        theta = finite_rows(statistic_values(statistic, vectorized, lam, self.param),
                            stacklevel=stacklevel)
        full = np.array([self.fit.lambdas], dtype=float)
        est = statistic_values(statistic, vectorized, full, self.param)[0]
        jack = None
        if m == "bca":
            jack = statistic_values(statistic, vectorized, self._jackknife_lambdas(), self.param)
            jack = jack[np.all(np.isfinite(jack), axis=1)]
        return make_interval(m, level, theta, est, jack, statistic is not None, names, note)

    # -- maximum and damage -----------------------------------------------------------------
    def maximum_quantiles(self, n, v) -> np.ndarray:
        """Quantiles ``Q_b(v^(1/n))`` of the maximum of n draws for every bootstrap model b
        (its GLD, with its Pareto tail when the bootstrap has them).

        Parameters
        ----------
        n : array_like
            Numbers of draws (>= 1), broadcast against the columns of ``v``.
        v : array_like, shape (n_successful, m)
            Probabilities, one row per successful resample (e.g. uniform draws: one random
            maximum of n draws per bootstrap GLD).

        Returns
        -------
        ndarray, shape (n_successful, m)
            In the units of the data; ``1 - v^(1/n)`` is formed as ``-expm1(log(v) / n)``.
        """
        with np.errstate(divide="ignore"):
            logv = np.log(np.asarray(v, dtype=float))
        return max_quantiles(self._lam(), self._fam, np.asarray(n, dtype=float), logv,
                             self._tail_rows())

    @property
    def calibrated(self) -> bool:
        """Whether the intervals of the maximum and the probabilities read the calibrated
        percentile pair (a bootstrap with Pareto tails, :meth:`with_pareto_tail`)."""
        return self._tails is not None

    def percentile_level(self, confidence_level: float | None = None) -> float:
        """The level of the percentile pair read as the interval of nominal
        ``confidence_level`` (default :attr:`confidence_level`): the level itself, or with
        Pareto tails ``1 - 0.7 (1 - level)`` (:func:`glstat.resampling.maxima.interval_level`).
        """
        return interval_level(self._level(confidence_level), self.calibrated)

    def maximum(self, n: float | None = None, confidence_level: float | None = None, *, rng=None,
                count=None) -> BootstrapMaximum:
        """The maximum of n draws for every bootstrap GLD (docs/method.md §6).

        Parameters
        ----------
        n : float, optional
            Number of draws (grid points), >= 1.
        confidence_level : float, optional
            Coverage of the intervals; default :attr:`confidence_level`.
        rng : int, numpy.random.Generator or None
            Source of the one random maximum drawn per bootstrap GLD. Default: a stream
            derived from the bootstrap's own seed, so the draws are reproducible.
        count : glstat.PoissonCount, glstat.ObservedCounts or frozen scipy.stats discrete, optional
            A random number of draws instead of ``n`` (see :func:`glstat.maximum`). Without
            ``n`` and ``count``, a bootstrap with ``groups`` uses each resample's own group
            sizes, so the interval carries the uncertainty of the count too.

        Returns
        -------
        BootstrapMaximum
        """
        n, cfull, rows = self._draw_counts(n, count)
        if rows is not None:
            return self._count_maximum(cfull, rows, confidence_level, rng)
        full = _maximum(self._full_dist(), n)
        level = self._level(confidence_level)
        lam = self._enough_fits()
        g = np.random.default_rng(self._seed(1) if rng is None else rng)
        return resample_maximum(lam, self.param, full, level, g, self._tail_rows())

    def _count_maximum(self, cfull, rows, confidence_level, rng) -> BootstrapMaximum:
        full = _maximum(self._full_dist(), count=cfull)
        level = self._level(confidence_level)
        lam = self._enough_fits()
        g = np.random.default_rng(self._seed(1) if rng is None else rng)
        return resample_count_maximum(lam, self.param, full, cfull, rows.conditional(), level, g,
                                      self._tail_rows())

    def _enough_fits(self) -> np.ndarray:
        """The lambdas of the successful resamples; FitError with fewer than two."""
        lam = self._lam()
        if lam.shape[0] < 2:
            raise FitError(f"only {lam.shape[0]} resamples have a fit")
        return lam

    def integrity_probability(self, threshold, n=None, area_factor=1.0,
                              confidence_level: float | None = None, *, count=None
                              ) -> BootstrapProbability:
        """Integrity probability F(threshold)^(k n) with its bootstrap percentile interval.

        Parameters
        ----------
        threshold : float
            Pressure level (units of the data); outside the support of a fit, that fit gives
            the limiting probabilities (integrity 0 below, 1 above).
        n : float, optional
            Number of points of the analysed area (>= 1).
        area_factor : array_like
            k, ratio of the area of interest to the analysed one (> 0); vectorised.
        confidence_level : float, optional
            Default :attr:`confidence_level`.
        count : glstat.PoissonCount, glstat.ObservedCounts or frozen scipy.stats discrete, optional
            A random number of points instead of ``n`` (``E[F^N]^k``, see
            :func:`glstat.integrity_probability`). Without ``n`` and ``count``, a bootstrap
            with ``groups`` uses each resample's own group sizes.

        Returns
        -------
        BootstrapProbability
            ``estimate`` from the full-sample fit, ``low``/``high`` the percentile interval,
            ``values`` the per-resample probabilities (shape (n_successful, *area_factor.shape)).
        """
        return self._probability(_integrity, "integrity", threshold, n, area_factor, confidence_level,
                                 count)

    def damage_probability(self, threshold, n=None, area_factor=1.0,
                           confidence_level: float | None = None, *, count=None
                           ) -> BootstrapProbability:
        """Damage probability 1 - F(threshold)^(k n) with its bootstrap percentile interval.

        Parameters and returns as for :meth:`integrity_probability`.
        """
        return self._probability(_damage, "damage", threshold, n, area_factor, confidence_level,
                                 count)

    def _probability(self, func, what, threshold, n, area_factor, confidence_level, count=None):
        level = self._level(confidence_level)
        k = np.asarray(area_factor, dtype=float)
        t = float(threshold)
        n, cfull, rows = self._draw_counts(n, count)
        # the full-sample value and the argument checks come from glstat.extremes.damage itself
        est = np.asarray(func(self._full_dist(), t, n, k, count=cfull, outside_support="limit"),
                         dtype=float)
        out = resample_probability(self._lam(), self.param, what, t, n, k, est, level, cfull, rows,
                                   self._tail_rows())
        logf = self._compatible_logf(t, interval_level(level, True))
        return out if logf is None else reach_compatible_tails(out, logf, cfull)

    def _compatible_logf(self, threshold: float, level: float) -> np.ndarray | None:
        """log F(threshold) of the full-sample model under every tail compatible with the
        exceedances at ``level`` (:meth:`with_pareto_tail`), or None: without tails, for an
        unbounded full-sample tail or a threshold at or below its start ``u``."""
        if self._full_tail is None or self._profile is None or self._profile.size == 0:
            return None
        from ..extremes.peaks_over_threshold import compatible_tails, log_gpd_sf
        from ..extremes.tails import log1mexp

        u, q, xi, _ = (float(v) for v in self._full_tail)
        if not (xi < 0 and threshold > u):
            return None
        alt = compatible_tails(self._profile, level)
        if alt.shape[0] == 0:
            return None
        log_s = math.log(q) + log_gpd_sf(np.asarray(threshold - u), alt[:, 0], alt[:, 1])
        return log1mexp(log_s)

    # -- tables -------------------------------------------------------------------------------
    def to_frame(self) -> pd.DataFrame:
        """The lambdas of every resample with their statistics (one row per resample)."""
        df = self.lambdas.copy()
        if self.statistics is not None:
            df = df.join(self.statistics)
        return df

    def summary(self) -> pd.DataFrame:
        """Full-sample estimate, bootstrap mean, standard error and percentile interval per lambda.

        Returns
        -------
        pandas.DataFrame
            Index ``quantity``. Rows ``lambda1..lambda4`` over all successful resamples
            (``region`` ``"all"``), with ``note`` = :attr:`branch_note`; when the resample
            fits fall in several RS regions, four more rows per region holding at least two
            of them, ``"lambda1 [region 4]"`` ..., over that region's resamples only
            (``estimate`` is the full-sample value when the full-sample fit lies in that
            region, NaN otherwise). Columns: ``estimate``, ``bootstrap_mean``, ``low``,
            ``high``, ``standard_error``, ``note``, ``region``, ``n_used``, ``method``,
            ``kind``, ``n_resamples``, ``n_failed``.
        """
        def interval(lam, note):
            return self._interval("percentile", None, None, False, None, lam, note)

        out = summary_frame(self._lam(), self._regions(), self.param, self.fit.region, interval,
                            self.branch_note)
        out["method"] = self.method
        out["kind"] = self.kind
        out["n_resamples"] = self.n_resamples
        out["n_failed"] = self.n_failed
        return out

    def __repr__(self) -> str:
        return (f"BootstrapFit(method={self.method!r}, param={self.param!r}, kind={self.kind!r}, "
                f"n_resamples={self.n_resamples}, n_failed={self.n_failed}, fit={self.fit!r})")
