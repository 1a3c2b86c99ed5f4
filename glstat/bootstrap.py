"""Bootstrap of GLD fits: parameter uncertainty, confidence intervals, maximum and damage.

:func:`bootstrap` resamples the data (or draws from the fitted GLD), fits a GLD to every
resample and returns a :class:`BootstrapFit` (docs/method.md §5). On it:

* :meth:`BootstrapFit.confidence_interval` — percentile, basic and BCa intervals for the
  lambdas or for any quantity derived from a GLD (quantiles, moments, probabilities);
* :meth:`BootstrapFit.maximum` — the maximum of n draws for every bootstrap GLD and their
  pooled mixture (step 6);
* :meth:`BootstrapFit.integrity_probability` and :meth:`BootstrapFit.damage_probability` —
  probabilities with their bootstrap interval, vectorised over the area factor (steps 7–8).

Resamples
---------
Every resample r has its own generator, ``numpy.random.default_rng(child_r)`` with
``child_r`` the r-th child of one ``numpy.random.SeedSequence`` whose entropy is drawn from
``rng``; a nonparametric resample is ``x[g.integers(0, n, n)]`` of the sorted finite data
``x``, a parametric one is n draws ``Q(U)`` from the full-sample fit, generated directly in
increasing order (normalised partial sums of n + 1 exponential variables are distributed as
the order statistics of n uniforms) and with ``Q(1 - U)`` taken through the upper-tail
quantile wherever ``U > 1/2``. The resamples therefore do not depend on the fitting method,
the batching or the executor.

Fitting
-------
For ``"moments"``, ``"percentiles"`` and ``"lmoments"`` the statistics of all resamples are
computed in one compiled pass (:mod:`glstat._core.resample`) and turned into lambdas by one
call to :func:`glstat.fit_batch`, which applies the rule of the full-sample fit: of the
valid roots whose support covers the resample's range (its minimum and maximum come from
the same compiled pass), the one closest to the full-sample fit's shapes (lambda3, lambda4).
A resample with valid roots of which none covers its data fails with the reason "no root
whose support covers the resample" - unless the full-sample fit does not cover the data
either (percentile and L-moment fits of long-tailed data), in which case the nearest root
is kept and a warning counts the resample fits that do not cover their data. ``"mle"``,
``"mps"`` and ``"starship"`` call
:func:`glstat.fit` per resample, optionally through a ``concurrent.futures.Executor``.
A resample without a fit is kept, with NaN lambdas and its reason in
:attr:`BootstrapFit.failed`, and a warning states the count.
"""

from __future__ import annotations

import logging
import math
import warnings
from collections.abc import Callable
from concurrent.futures import Executor
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy import special

from ._core import resample as _R
from ._lambda_rows import FAMILY, frozen_batch, log_tails, max_quantiles, max_raw_moments, quantiles
from ._validate import check_level, check_n_resamples
from .bootstrap_maximum import BootstrapMaximum, BootstrapProbability, MaximumMixture
from .counts import ObservedCounts, RowCounts, as_count
from .damage import damage_probability as _damage
from .damage import integrity_probability as _integrity
from .errors import FitError, InvalidParameterError
from .extremes import maximum as _maximum
from .fitting import GLDFit, fit, fit_batch
from .fitting import _stats as _S
from .gld import GLD
from .regions import rs_region

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = [
    "BootstrapFit",
    "BootstrapInterval",
    "BootstrapMaximum",
    "BootstrapProbability",
    "BootstrapWarning",
    "MaximumMixture",
    "bootstrap",
]

logger = logging.getLogger(__name__)

KINDS = ("nonparametric", "parametric")
METHODS = ("moments", "percentiles", "lmoments", "mle", "mps", "starship")
COMPILED = ("moments", "percentiles", "lmoments")
CI_METHODS = ("percentile", "basic", "bca")
_LAMBDA_NAMES = ("lambda1", "lambda2", "lambda3", "lambda4")
_STAT_NAMES = {
    "moments": ("mean", "std", "skew", "kurt"),
    "percentiles": ("rho1", "rho2", "rho3", "rho4"),
    "lmoments": ("l1", "l2", "t3", "t4"),
}
# values per chunk of the compiled path (index rows of int32: 8 MB)
_CHUNK_VALUES = 2_000_000
# resamples per task of the per-resample path
_TASK_SIZE = 8
# largest number of delete-a-group jackknife samples (BCa acceleration)
_JACKKNIFE_GROUPS = {"compiled": 1000, "data": 100}
# the progress bar appears by default above this much work (values resampled x fits)
_PROGRESS_WORK = {"compiled": 3e8, "data": 2e5}
# a resample jumped to another root branch when its lambda3 or lambda4 lies farther from the
# full-sample fit's than this many robust standard deviations (1.4826 MAD) of the resamples'
_JUMP_SPREADS = 12.0
_MAD_SCALE = 1.482602218505602


class BootstrapWarning(RuntimeWarning):
    """Some resamples had no fit, their lambdas lie on several branches, or no interval exists."""


# ---------------------------------------------------------------------------------------------
# resample generation
# ---------------------------------------------------------------------------------------------
def _group_indices(groups, chosen: np.ndarray) -> np.ndarray:
    """Indices into the sorted sample of the members of the chosen groups, group after group."""
    members, offsets = groups
    sizes = offsets[1:] - offsets[:-1]
    take = sizes[chosen]
    starts = offsets[:-1][chosen]
    shift = np.repeat(starts - np.concatenate(([0], np.cumsum(take)[:-1])), take)
    return members[np.arange(int(take.sum())) + shift]


def _draw(x: np.ndarray, g: np.random.Generator, kind: str, lam, fam: int, groups=None) -> np.ndarray:
    """One resample with generator ``g`` (length n, or the members of G groups drawn with
    replacement); sorted for the parametric kind."""
    n = x.size
    if groups is not None:
        G = groups[1].size - 1
        return x[_group_indices(groups, g.integers(0, G, size=G, dtype=np.int64))]
    if kind == "nonparametric":
        return x[g.integers(0, n, size=n, dtype=np.int64)]
    e = g.standard_exponential(n + 1)
    total = math.fsum(e)
    v = np.cumsum(e[:-1]) / total
    q = np.cumsum(e[:0:-1])[::-1] / total
    return quantiles(np.asarray(lam, dtype=float)[None, :], fam, v[None, :], q[None, :])[0]


def _fit_task(x, seeds, kind, lam, param, method, options, groups=None):
    """Fits of the resamples with the given seeds (runs in the executor's workers)."""
    fam = FAMILY[param]
    out = []
    for s in seeds:
        sample = _draw(x, np.random.default_rng(s), kind, lam, fam, groups)
        ext = (float(np.min(sample)), float(np.max(sample)))
        try:
            # warn=False: no warning from a worker, and no change to the process-wide filters
            f = fit(sample, param, method, warn=False, **options)
            out.append((f.lambdas, f.n_valid, "", ext))
        except (FitError, InvalidParameterError, FloatingPointError, ValueError,
                ZeroDivisionError) as exc:
            out.append(((math.nan,) * 4, 0, f"fit error ({type(exc).__name__}): {exc}", ext))
    return out


def _progress_bar(total, enabled, desc):
    if not enabled:
        return None
    from tqdm.auto import tqdm

    return tqdm(total=total, desc=desc, unit="resample")


def _stat_failures(method: str, st: np.ndarray) -> list[str]:
    """Reason per row why statistics cannot be fitted ("" when they can)."""
    _, b, c, d = st.T
    with np.errstate(invalid="ignore"):
        if method == "moments":
            ok = (b > 0) & (d > 1.0 + c * c)
        elif method == "percentiles":
            ok = (b > 0) & (c > 0) & (d > 0) & (d < 1)
        else:
            ok = (b > 0) & (np.abs(c) < 1) & (d >= (5 * c * c - 1) / 4) & (d < 1)
    ok &= np.all(np.isfinite(st), axis=1)
    reasons = [""] * st.shape[0]
    check = {"moments": _S.check_moment_stats, "percentiles": _S.check_rho,
             "lmoments": _S.check_lmoment_stats}[method]
    for r in np.flatnonzero(~ok):
        row = st[r]
        if not np.all(np.isfinite(row)):
            reasons[r] = "statistics undefined: constant resample or tied quantiles"
            continue
        try:
            check(*row)
        except FitError as exc:
            reasons[r] = f"statistics out of range: {exc}"
    return reasons


def _covers_data(full: GLDFit) -> bool:
    """True when the selected full-sample fit covers the data (or there are no data)."""
    sol = full.solutions
    if sol is None or len(sol) == 0 or "selected" not in sol:
        return True
    sel = sol[sol["selected"]]
    if len(sel) == 0:
        return True
    cov = sel["covers_data"].iloc[0]
    return cov is None or bool(cov)


def _branches(lam: np.ndarray, ref, param: str) -> tuple[np.ndarray, np.ndarray]:
    """RS region and branch jump of every row of ``lam`` (shape (B, 4), NaN rows = failed).

    Returns
    -------
    region : ndarray of int, shape (B,)
        RS region (1-6) of (lambda3, lambda4); 0 for a failed row and for FKML.
    jump : ndarray of bool, shape (B,)
        True where lambda3 or lambda4 lies more than ``_JUMP_SPREADS`` robust standard
        deviations (1.4826 times the median absolute deviation over the successful rows;
        their standard deviation when that is 0) from ``ref``, the full-sample shapes.
    """
    B = lam.shape[0]
    ok = np.all(np.isfinite(lam), axis=1)
    region = np.zeros(B, dtype=np.int64)
    if param == "rs" and ok.any():
        region[ok] = rs_region(lam[ok, 2], lam[ok, 3])
    jump = np.zeros(B, dtype=bool)
    ref = np.asarray(ref, dtype=float)
    if ok.sum() >= 2 and np.all(np.isfinite(ref)):
        sh = lam[ok, 2:]
        spread = _MAD_SCALE * np.median(np.abs(sh - np.median(sh, axis=0)), axis=0)
        spread = np.where(spread > 0, spread, np.std(sh, axis=0))
        dev = np.abs(sh - ref)
        with np.errstate(divide="ignore", invalid="ignore"):
            z = np.where(dev > 0, dev / spread, 0.0)
        jump[ok] = np.max(z, axis=1) > _JUMP_SPREADS
    return region, jump


def _branch_note(region: np.ndarray, jump: np.ndarray, param: str, full_region) -> str:
    """Why percentile intervals of the lambdas are not meaningful ("" when they are).

    ``region`` and ``jump`` cover the successful resamples only.
    """
    parts = []
    if param == "rs":
        regs, counts = np.unique(region, return_counts=True)
        if regs.size > 1:
            per = ", ".join(f"region {r}: {c}" for r, c in zip(regs, counts, strict=True))
            parts.append(f"the resample fits fall in {regs.size} RS regions ({per}; full-sample fit: "
                         f"region {full_region})")
    nj = int(np.sum(jump))
    if nj:
        parts.append(f"{nj} of {jump.size} resample fits jumped to another root branch (lambda3 or "
                     f"lambda4 more than {_JUMP_SPREADS:g} robust standard deviations, 1.4826 MAD of the "
                     "resamples, from the full-sample fit's)")
    if not parts:
        return ""
    per_region = " (summary() also gives them per region)" if len(parts) > 1 or not nj else ""
    return ("; ".join(parts) + ". Percentile intervals, standard errors and means of the lambdas mix "
            f"different parameterisations of similar distributions and are not meaningful{per_region}; "
            "intervals of quantiles, moments or probabilities, confidence_interval(statistic=...), do "
            "not depend on the parameterisation")


def _compiled_statistics(x, seeds, kind, lam, fam, method, u, loc, scale, bar, groups=None):
    """Statistics (B, 4) and extremes (B, 2: min, max) of the resamples, compiled."""
    code = _R.CODES[method]
    n = x.size
    B = len(seeds)
    st = np.empty((B, 4))
    ext = np.empty((B, 2))
    if groups is not None:  # resamples of groups have their own lengths: one call each
        G = groups[1].size - 1
        for r, seed in enumerate(seeds):
            chosen = np.random.default_rng(seed).integers(0, G, size=G, dtype=np.int64)
            idx = _group_indices(groups, chosen)[None, :]
            _R.stats_from_indices(code, x, idx, u, loc, scale, st[r:r + 1], ext[r:r + 1])
            if bar is not None:
                bar.update(1)
        return st, ext
    rows = max(1, min(B, _CHUNK_VALUES // n))
    dtype = np.int32 if n < 2**31 else np.int64
    for s in range(0, B, rows):
        chunk = seeds[s:s + rows]
        if kind == "nonparametric":
            idx = np.empty((len(chunk), n), dtype=dtype)
            for j, seed in enumerate(chunk):
                idx[j] = np.random.default_rng(seed).integers(0, n, size=n, dtype=np.int64)
            _R.stats_from_indices(code, x, idx, u, loc, scale, st[s:s + len(chunk)],
                                  ext[s:s + len(chunk)])
        else:
            samples = np.empty((len(chunk), n))
            for j, seed in enumerate(chunk):
                samples[j] = _draw(x, np.random.default_rng(seed), kind, lam, fam)
            _R.stats_from_sorted(code, samples, u, loc, scale, st[s:s + len(chunk)],
                                 ext[s:s + len(chunk)])
        if bar is not None:
            bar.update(len(chunk))
    return st, ext


# ---------------------------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class BootstrapInterval:
    """Bootstrap confidence interval of one or several quantities.

    Attributes
    ----------
    estimate : ndarray
        Value on the full-sample fit.
    low, high : ndarray
        Interval bounds (units of the quantity), same shape as ``estimate``.
    standard_error : ndarray
        Standard deviation of the bootstrap values (divisor B - 1).
    names : tuple of str
        Name of each entry.
    method : str
        ``"percentile"``, ``"basic"`` or ``"BCa"``.
    confidence_level : float
        Nominal coverage.
    n_used : int
        Number of bootstrap values the interval rests on.
    note : str
        Why the interval is not meaningful, or "" (for the lambdas: resample fits in several
        RS regions or on several root branches, see :attr:`BootstrapFit.branch_note`).
    """

    estimate: np.ndarray
    low: np.ndarray
    high: np.ndarray
    standard_error: np.ndarray
    names: tuple[str, ...]
    method: str
    confidence_level: float
    n_used: int
    note: str = ""

    def to_frame(self) -> pd.DataFrame:
        """One row per quantity: estimate, low, high, standard_error, note."""
        import pandas as pd

        return pd.DataFrame(
            {"estimate": np.ravel(self.estimate), "low": np.ravel(self.low),
             "high": np.ravel(self.high), "standard_error": np.ravel(self.standard_error),
             "note": self.note},
            index=pd.Index(self.names, name="quantity"),
        )


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

    @property
    def counts(self) -> ObservedCounts | None:
        """The number of values per group (a bootstrap with ``groups``), else None."""
        return None if self._grouping is None else ObservedCounts(self._grouping[0])

    def resampled_counts(self) -> RowCounts:
        """Per successful resample, the numbers of values of its drawn groups (with ``groups``)."""
        if self._grouping is None:
            raise TypeError("the bootstrap has no groups: give n or count")
        lam = self.lambdas[list(_LAMBDA_NAMES)].to_numpy(dtype=float)
        ok = np.all(np.isfinite(lam), axis=1)
        sizes, choices = self._grouping
        return RowCounts.from_choices(sizes, choices[ok])

    def _draw_counts(self, n, count):
        """(n, None, None) for a fixed n, or (None, full-sample count, RowCounts per resample)."""
        if n is not None and count is not None:
            raise TypeError("give either n (a fixed number of draws) or count (a random one), not both")
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
            lam = self.lambdas[list(_LAMBDA_NAMES)].to_numpy(dtype=float)
            self._cache["lam"] = np.ascontiguousarray(lam[np.all(np.isfinite(lam), axis=1)])
        return self._cache["lam"]

    def _seed(self, key: int) -> np.random.SeedSequence:
        return np.random.SeedSequence(list(self._entropy), spawn_key=(self.n_resamples + key,))

    def dists(self) -> list[GLD]:
        """The GLD of every successful resample, in resample order."""
        if "dists" not in self._cache:
            self._cache["dists"] = [GLD(l1, l2, l3, l4, param=self.param)
                                    for l1, l2, l3, l4 in self._lam()]
        return list(self._cache["dists"])

    def __glstat_distributions__(self) -> list[GLD]:
        """The bootstrap distributions, for :mod:`glstat.damage` and :mod:`glstat.extremes`."""
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
        lam = self.lambdas[list(_LAMBDA_NAMES)].to_numpy(dtype=float)
        return self.lambdas["region"].to_numpy()[np.all(np.isfinite(lam), axis=1)]

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
            lam = self.lambdas[list(_LAMBDA_NAMES)].to_numpy(dtype=float)
            ok = np.all(np.isfinite(lam), axis=1)
            self._cache["note"] = _branch_note(self.lambdas["region"].to_numpy()[ok],
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

        se = pd.Series(np.std(self._lam(), axis=0, ddof=1), index=list(_LAMBDA_NAMES),
                       name="standard_error")
        se.attrs["note"] = self.branch_note
        if self.branch_note:
            warnings.warn(f"standard errors of the lambdas: {self.branch_note}", BootstrapWarning,
                          stacklevel=2)
        return se

    # -- statistics of the resamples --------------------------------------------------------
    def _values(self, statistic, vectorized, lam) -> np.ndarray:
        """statistic on every row of ``lam``: array (k, p)."""
        if statistic is None:
            return np.array(lam, dtype=float)
        if vectorized:
            res = np.asarray(statistic(frozen_batch(lam, self.param)), dtype=float)
            return res.reshape(lam.shape[0], -1)
        rows: list[np.ndarray | None] = []
        for l1, l2, l3, l4 in lam:
            try:
                d = GLD(l1, l2, l3, l4, param=self.param)
            except InvalidParameterError:
                rows.append(None)
                continue
            rows.append(np.atleast_1d(np.asarray(statistic(d), dtype=float)).ravel())
        width = max((r.size for r in rows if r is not None), default=1)
        return np.array([np.full(width, np.nan) if r is None else r for r in rows]).reshape(-1, width)

    def _estimate(self, statistic, vectorized) -> np.ndarray:
        lam = np.array([self.fit.lambdas], dtype=float)
        return self._values(statistic, vectorized, lam)[0]

    def _jackknife_lambdas(self) -> np.ndarray:
        """Lambdas of the delete-a-group jackknife samples of the data (cached)."""
        if "jack" in self._cache:
            return self._cache["jack"]
        x = self._data
        if x is None:
            raise ValueError("BCa needs the data, which this BootstrapFit does not hold")
        n = x.size
        compiled = self.method in COMPILED
        groups = min(n, _JACKKNIFE_GROUPS["compiled" if compiled else "data"])
        group = np.empty(n, dtype=np.int64)
        perm = np.random.default_rng(self._seed(0)).permutation(n)
        group[perm] = np.arange(n) % groups
        if compiled:
            st = np.empty((groups, 4))
            ext = np.empty((groups, 2))
            mean, std = _S.location_spread(x)
            _R.stats_delete_groups(_R.CODES[self.method], x, group, groups,
                                   float(self.options.get("u", 0.1)), mean, std, st, ext)
            ok = np.array([r == "" for r in _stat_failures(self.method, st)])
            lam = np.full((groups, 4), np.nan)
            if ok.any():
                lam[ok], _ = fit_batch(st[ok], self.method, self.param,
                                       u=float(self.options.get("u", 0.1)),
                                       ref=self.fit.lambdas[2:], extremes=ext[ok])
        else:
            lam = np.full((groups, 4), np.nan)
            for g in range(groups):
                try:
                    lam[g] = fit(x[group != g], self.param, self.method, warn=False,
                                 **self.options).lambdas
                except (FitError, InvalidParameterError, FloatingPointError, ValueError):
                    pass
        lam = lam[np.all(np.isfinite(lam), axis=1)]
        self._cache["jack"] = lam
        return lam

    def confidence_interval(
        self,
        method: str = "percentile",
        confidence_level: float | None = None,
        statistic: Callable[[Any], Any] | None = None,
        *,
        vectorized: bool = False,
        names: tuple[str, ...] | None = None,
    ) -> BootstrapInterval:
        """Bootstrap confidence interval of the lambdas or of a quantity derived from a GLD.

        Parameters
        ----------
        method : {"percentile", "basic", "BCa"}
            ``"percentile"``: quantiles alpha/2 and 1 - alpha/2 of the bootstrap values.
            ``"basic"``: those quantiles reflected about the full-sample estimate.
            ``"BCa"``: bias-corrected and accelerated (Efron 1987): the bias correction
            z0 = Phi^-1(fraction of bootstrap values below the estimate, ties counted half),
            the acceleration a = sum(d^3) / (6 (sum d^2)^(3/2)) from the jackknife
            differences d (delete-one for n <= 1000 (compiled methods) or 100 (ML, MPS,
            starship), otherwise delete-a-group over a random partition into that many
            groups), and the quantiles Phi(z0 + (z0 + z) / (1 - a (z0 + z))) at
            z = Phi^-1(alpha/2), Phi^-1(1 - alpha/2).
        confidence_level : float, optional
            Nominal coverage in (0, 1); default :attr:`confidence_level`.
        statistic : callable, optional
            Function of a :class:`glstat.GLD` returning a number or a 1-D array (e.g.
            ``lambda d: d.ppf(0.9)``, ``lambda d: d.mean()``, ``lambda d: d.sf(2050.0)``).
            Default: the lambdas themselves.
        vectorized : bool
            When True, ``statistic`` is called once with all distributions as one frozen
            scipy distribution whose parameters have shape (k, 1) (see :meth:`batch`) and
            must return shape (k,) or (k, p). Much faster than one call per GLD.
        names : tuple of str, optional
            Names of the entries of the statistic (default ``"statistic"`` or
            ``"statistic[i]"``).

        Returns
        -------
        BootstrapInterval
            ``estimate``, ``low``, ``high``, ``standard_error`` (arrays; a float-like 0-d
            array for a scalar statistic) over the successful resamples.

        Raises
        ------
        ValueError
            Unknown method or confidence_level outside (0, 1).

        Warns
        -----
        BootstrapWarning
            For the lambdas (no ``statistic``) when :attr:`branch_note` is not empty: the
            resample fits lie in several RS regions or on several root branches. The note is
            also the interval's ``note``.
        """
        note = self.branch_note if statistic is None else ""
        if note:
            warnings.warn(f"interval of the lambdas: {note}", BootstrapWarning, stacklevel=2)
        return self._interval(method, confidence_level, statistic, vectorized, names, self._lam(), note)

    def _interval(self, method, confidence_level, statistic, vectorized, names, lam, note):
        m = str(method).lower()
        if m not in CI_METHODS:
            raise ValueError(f"method must be 'percentile', 'basic' or 'BCa', got {method!r}")
        level = self.confidence_level if confidence_level is None else check_level(confidence_level)
        if lam.shape[0] < 2:
            raise FitError(f"only {lam.shape[0]} of {self.n_resamples} resamples have a fit: no "
                           "bootstrap interval")
        theta = self._values(statistic, vectorized, lam)
        est = self._estimate(statistic, vectorized)
        finite = np.all(np.isfinite(theta), axis=1)
        if not finite.all():
            warnings.warn(f"the statistic is not finite on {int((~finite).sum())} of {theta.shape[0]} "
                          "bootstrap fits; the interval uses the others", BootstrapWarning, stacklevel=2)
            theta = theta[finite]
        alpha = 1.0 - level
        probs = np.array([alpha / 2, 1.0 - alpha / 2])
        if m == "bca":
            jack = self._values(statistic, vectorized, self._jackknife_lambdas())
            jack = jack[np.all(np.isfinite(jack), axis=1)]
            lo, hi = _bca(theta, est, jack, probs)
        else:
            q = np.quantile(theta, probs, axis=0)
            lo, hi = q[0], q[1]
            if m == "basic":
                lo, hi = 2.0 * est - hi, 2.0 * est - lo
        se = np.std(theta, axis=0, ddof=1)
        if statistic is None:
            nm = _LAMBDA_NAMES
        elif names is not None:
            nm = tuple(names)
        else:
            nm = ("statistic",) if est.size == 1 else tuple(f"statistic[{i}]" for i in range(est.size))
        scalar = statistic is not None and est.size == 1
        shape = () if scalar else est.shape
        return BootstrapInterval(
            estimate=est.reshape(shape), low=np.asarray(lo).reshape(shape),
            high=np.asarray(hi).reshape(shape), standard_error=se.reshape(shape), names=nm,
            method={"bca": "BCa"}.get(m, m), confidence_level=level, n_used=theta.shape[0],
            note=note,
        )

    # -- maximum and damage -----------------------------------------------------------------
    def maximum_quantiles(self, n, v) -> np.ndarray:
        """Quantiles ``Q_b(v^(1/n))`` of the maximum of n draws for every bootstrap GLD b.

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
        return max_quantiles(self._lam(), self._fam, np.asarray(n, dtype=float), logv)

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
        full = _maximum(self.fit.dist, n)
        level = self.confidence_level if confidence_level is None else check_level(confidence_level)
        lam = self._lam()
        if lam.shape[0] < 2:
            raise FitError(f"only {lam.shape[0]} resamples have a fit")
        n = full.n
        g = np.random.default_rng(self._seed(1) if rng is None else rng)
        v = g.random(lam.shape[0])
        draws = max_quantiles(lam, self._fam, n, np.log(v)[:, None])[:, 0]
        medians = max_quantiles(lam, self._fam, n, np.array([[math.log(0.5)]]))[:, 0]
        means = max_raw_moments(lam, self._fam, n, 1)
        return BootstrapMaximum(n=n, draws=draws, medians=medians, confidence_level=level,
                                mixture=MaximumMixture(lam, self.param, n), full=full,
                                _lam=lam, _param=self.param, _means=means)

    def _count_maximum(self, cfull, rows, confidence_level, rng) -> BootstrapMaximum:
        full = _maximum(self.fit.dist, count=cfull)
        level = self.confidence_level if confidence_level is None else check_level(confidence_level)
        lam = self._lam()
        if lam.shape[0] < 2:
            raise FitError(f"only {lam.shape[0]} resamples have a fit")
        cond = rows.conditional()
        g = np.random.default_rng(self._seed(1) if rng is None else rng)
        counts = cond.sample(g)
        v = g.random(lam.shape[0])
        draws = max_quantiles(lam, self._fam, counts[:, None], np.log(v)[:, None])[:, 0]
        lf = cond.log_f_for(math.log(0.5))
        with np.errstate(invalid="ignore"):
            medians = quantiles(lam, self._fam, np.exp(lf)[:, None], (-np.expm1(lf))[:, None])[:, 0]
        return BootstrapMaximum(n=float(cfull.mean), draws=draws, medians=medians,
                                confidence_level=level,
                                mixture=MaximumMixture(lam, self.param, 1.0, counts=cond), full=full,
                                _lam=lam, _param=self.param, _counts=cond, count=cfull)

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
        level = self.confidence_level if confidence_level is None else check_level(confidence_level)
        k = np.asarray(area_factor, dtype=float)
        t = float(threshold)
        n, cfull, rows = self._draw_counts(n, count)
        # the full-sample value and the argument checks come from glstat.damage itself
        est = np.asarray(func(self.fit.dist, t, n, k, count=cfull, outside_support="limit"),
                         dtype=float)
        lam = self._lam()
        logf = log_tails(lam, self._fam, np.array([t]))[0][:, 0]
        logf = logf.reshape((-1,) + (1,) * k.ndim)  # one row per resample
        if rows is None:
            y = (logf * k) * float(n)  # k n log F
            vals = np.exp(y) if what == "integrity" else -np.expm1(y)
        elif what == "integrity":
            vals = np.exp(k * rows.log_pgf(logf))
        else:
            vals = rows.damage(logf, k)
        alpha = 1.0 - level
        q = np.quantile(vals, [alpha / 2, 1 - alpha / 2], axis=0)
        return BootstrapProbability(what=what, threshold=t,
                                    n=float(n) if cfull is None else float(cfull.mean),
                                    area_factor=k, estimate=est, low=q[0], high=q[1], values=vals,
                                    confidence_level=level, count=cfull)

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
        import pandas as pd

        lam = self._lam()
        note = self.branch_note
        ci = self._interval("percentile", None, None, False, None, lam, note).to_frame()
        ci.insert(1, "bootstrap_mean", np.mean(lam, axis=0))
        ci["region"] = "all"
        ci["n_used"] = lam.shape[0]
        frames = [ci]
        reg = self._regions()
        if self.param == "rs" and np.unique(reg).size > 1:
            for r in np.unique(reg):
                sub = lam[reg == r]
                if sub.shape[0] < 2:
                    continue
                part = self._interval("percentile", None, None, False, None, sub,
                                      f"resample fits in RS region {r} only").to_frame()
                if self.fit.region != r:
                    part["estimate"] = np.nan
                part.insert(1, "bootstrap_mean", np.mean(sub, axis=0))
                part["region"] = int(r)
                part["n_used"] = sub.shape[0]
                part.index = pd.Index([f"{q} [region {r}]" for q in _LAMBDA_NAMES], name="quantity")
                frames.append(part)
        out = pd.concat(frames) if len(frames) > 1 else ci
        out["method"] = self.method
        out["kind"] = self.kind
        out["n_resamples"] = self.n_resamples
        out["n_failed"] = self.n_failed
        return out

    def __repr__(self) -> str:
        return (f"BootstrapFit(method={self.method!r}, param={self.param!r}, kind={self.kind!r}, "
                f"n_resamples={self.n_resamples}, n_failed={self.n_failed}, fit={self.fit!r})")

def _bca(theta, est, jack, probs):
    """BCa bounds for every column of theta (k, p), estimate est (p,), jackknife jack (g, p)."""
    p = theta.shape[1]
    lo = np.full(p, np.nan)
    hi = np.full(p, np.nan)
    for j in range(p):
        t = theta[:, j]
        frac = (np.sum(t < est[j]) + 0.5 * np.sum(t == est[j])) / t.size
        z0 = special.ndtri(frac)
        d = np.mean(jack[:, j]) - jack[:, j]
        den = 6.0 * np.sum(d * d) ** 1.5
        a = np.sum(d**3) / den if den > 0 else 0.0
        if not np.isfinite(z0):
            warnings.warn("BCa: the full-sample estimate lies outside all bootstrap values; the "
                          "interval is NaN", BootstrapWarning, stacklevel=3)
            continue
        z = special.ndtri(probs)
        adj = special.ndtr(z0 + (z0 + z) / (1.0 - a * (z0 + z)))
        lo[j], hi[j] = np.quantile(t, adj)
    return lo, hi

# ---------------------------------------------------------------------------------------------
# public entry point
# ---------------------------------------------------------------------------------------------
def bootstrap(
    data,
    param: str = "rs",
    method: str = "moments",
    n_resamples: int = 1000,
    confidence_level: float = 0.9,
    kind: str = "nonparametric",
    rng: int | np.random.Generator | None = None,
    executor: Executor | None = None,
    nan_policy: str = "raise",
    progress: bool | None = None,
    groups=None,
    **options,
) -> BootstrapFit:
    """Fit a GLD to bootstrap resamples of the data (docs/method.md §5).

    Parameters
    ----------
    data : array_like
        Sample (flattened; units of the data, e.g. MPa).
    param : {"rs", "fkml"}
        Parameterisation.
    method : {"moments", "percentiles", "lmoments", "mle", "mps", "starship"}
        Fitting method, as for :func:`glstat.fit`. The first three run through the compiled
        statistics pass and :func:`glstat.fit_batch`; the others fit every resample.
    n_resamples : int
        Number of resamples B (>= 2).
    confidence_level : float
        Default coverage of the intervals, in (0, 1).
    kind : {"nonparametric", "parametric"}
        Resample the data with replacement, or draw n values from the full-sample fit.
    rng : int, numpy.random.Generator or None
        Seed or generator; the same seed gives identical results.
    executor : concurrent.futures.Executor, optional
        Runs the per-resample fits of ``"mle"``, ``"mps"`` and ``"starship"`` (e.g. a
        ``ProcessPoolExecutor`` or ``distributed.Client(...).get_executor()``); results are
        identical whatever the executor. Not used by the compiled methods.
    nan_policy : {"raise", "omit", "propagate"}
        Non-finite data: raise, drop them, or return a bootstrap whose resamples all failed.
    progress : bool, optional
        Show a tqdm progress bar; default: only for long runs.
    groups : array_like, optional
        A label per data value (e.g. the surface each asperity peak comes from). Resamples
        then draw whole groups with replacement (G of them, a cluster bootstrap), so the
        intervals include the variation between groups and the number of values per group:
        :attr:`BootstrapFit.counts` holds the group sizes and the probabilities and maxima
        use each resample's own sizes as the random count (docs/method.md §6). Only with
        ``kind="nonparametric"``; non-finite values are dropped with their labels under
        ``nan_policy="omit"``.
    **options
        Fitting options (``u`` for percentiles; ``maxiter``, ``starts`` for data methods).

    Returns
    -------
    BootstrapFit

    Raises
    ------
    ValueError
        n_resamples < 2, confidence_level outside (0, 1), unknown kind, method, param,
        nan_policy or option, or non-finite data with ``nan_policy="raise"``.
    FitError
        Too few or constant data, no fit of the full sample, or no resample with a fit.

    Warns
    -----
    BootstrapWarning
        When some resamples have no fit (the count and the commonest reasons).

    Examples
    --------
    >>> import numpy as np, glstat
    >>> x = np.random.default_rng(0).gamma(5.0, 3.0, 2000)
    >>> bf = glstat.bootstrap(x, n_resamples=200, rng=1)
    >>> ci = bf.confidence_interval(statistic=lambda d: d.ppf(0.9))
    >>> bool(ci.low < np.quantile(x, 0.9) < ci.high)
    True
    """
    import pandas as pd

    B = check_n_resamples(n_resamples)
    level = check_level(confidence_level)
    if kind not in KINDS:
        raise ValueError(f"kind must be 'nonparametric' or 'parametric', got {kind!r}")
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    param = str(param).lower()
    if param not in FAMILY:
        raise ValueError(f"param must be 'rs' or 'fkml', got {param!r}")
    grouping = None
    if groups is not None:
        if kind != "nonparametric":
            raise ValueError("groups resample whole groups of the data: use kind='nonparametric'")
        if nan_policy == "propagate":
            raise ValueError("groups need finite data: use nan_policy='raise' or 'omit'")
        grouping = _grouping(data, groups)
    x, _ = _S.prepare_data(data, nan_policy)
    entropy = tuple(int(v) for v in np.random.default_rng(rng).integers(0, 2**63, size=4))
    if x is None:  # nan_policy="propagate" met a non-finite value
        full = fit(data, param, method, nan_policy="propagate", **options)
        lam = np.full((B, 4), np.nan)
        nroots = np.zeros(B, dtype=np.int64)
        reasons = ["data contain non-finite values (nan_policy='propagate')"] * B
        return _result(full, lam, nroots, None, reasons, B, level, kind, method, param, options,
                       None, entropy, warn=False)
    full = fit(x, param, method, **options)
    seeds = [np.random.SeedSequence(list(entropy), spawn_key=(r,)) for r in range(B)]
    fam = FAMILY[param]
    n = x.size
    compiled = method in COMPILED
    if progress is None:
        progress = B * n > _PROGRESS_WORK["compiled" if compiled else "data"]
    logger.debug("bootstrap: %d %s resamples of %d values (groups: %s), %s %s fits, %s", B, kind, n,
                 "no" if grouping is None else grouping[2].size, param, method,
                 "compiled batch" if compiled else f"executor {executor!r}")
    bar = _progress_bar(B, bool(progress), f"bootstrap {method}")
    try:
        if compiled:
            u = float(full.options.get("u", 0.1))
            mean, std = _S.location_spread(x)
            st, ext = _compiled_statistics(x, seeds, kind, full.lambdas, fam, method, u, mean, std,
                                           bar, None if grouping is None else grouping[:2])
            reasons = _stat_failures(method, st)
            ok = np.array([r == "" for r in reasons])
            lam = np.full((B, 4), np.nan)
            nroots = np.zeros(B, dtype=np.int64)
            ncover = np.zeros(B, dtype=np.int64)
            # the rule of the full-sample fit: a root covering the data first; when the
            # full-sample fit itself covers the data, a resample without a covering root fails
            require = _covers_data(full)
            if ok.any():
                lam[ok], nroots[ok], ncover[ok] = fit_batch(
                    st[ok], method, param, u=u, ref=full.lambdas[2:], extremes=ext[ok],
                    require_cover=require, return_cover=True)
            for r in np.flatnonzero(ok):
                if nroots[r] == 0:
                    reasons[r] = (f"no root: no {param.upper()} GLD matches the {method} statistics "
                                  + ", ".join(f"{a}={b:.6g}" for a, b in
                                              zip(_STAT_NAMES[method], st[r], strict=True)))
                elif not np.all(np.isfinite(lam[r])):
                    reasons[r] = (f"no root whose support covers the resample: {nroots[r]} valid "
                                  f"{param.upper()} root(s), none covering its range "
                                  f"[{ext[r, 0]:.6g}, {ext[r, 1]:.6g}]")
            stats_df = pd.DataFrame(st, columns=list(_STAT_NAMES[method]))
            stats_df["min"] = ext[:, 0]
            stats_df["max"] = ext[:, 1]
            stats_df["covers"] = ncover > 0
            stats_df.index.name = "resample"
            fitted = np.all(np.isfinite(lam), axis=1)
            uncovered = int(np.sum(fitted & (ncover == 0)))
            if uncovered:
                warnings.warn(
                    f"{uncovered} of {B} resample fits ({method}, {param}) have a support that does "
                    "not cover their resample, as the full-sample fit does not cover the data "
                    "(statistics['covers'] says which); their maxima and tail probabilities are "
                    "unreliable: a method matching the tails (moments, 'mle') covers the data",
                    BootstrapWarning, stacklevel=2)
        else:
            tasks = [seeds[s:s + _TASK_SIZE] for s in range(0, B, _TASK_SIZE)]
            args = (kind, full.lambdas, param, method, dict(options),
                    None if grouping is None else grouping[:2])
            results = []
            if executor is None:
                for t in tasks:
                    results.extend(_fit_task(x, t, *args))
                    if bar is not None:
                        bar.update(len(t))
            else:
                futures = [executor.submit(_fit_task, x, t, *args) for t in tasks]
                for fut, t in zip(futures, tasks, strict=True):
                    results.extend(fut.result())
                    if bar is not None:
                        bar.update(len(t))
            lam = np.array([r[0] for r in results], dtype=float)
            nroots = np.array([r[1] for r in results], dtype=np.int64)
            reasons = [r[2] for r in results]
            stats_df = pd.DataFrame([r[3] for r in results], columns=["min", "max"])
            stats_df.index.name = "resample"
    finally:
        if bar is not None:
            bar.close()
    if grouping is not None:
        G = grouping[2].size
        choices = np.stack([np.random.default_rng(sd).integers(0, G, size=G, dtype=np.int64)
                            for sd in seeds])
        grouping = (grouping[2], choices)
    return _result(full, lam, nroots, stats_df, reasons, B, level, kind, method, param, options, x,
                   entropy, warn=True, grouping=grouping)


def _grouping(data, groups):
    """(members, offsets, sizes) of the groups over the sorted finite data."""
    values = np.asarray(data, dtype=float).ravel()
    labels = np.asarray(groups).ravel()
    if labels.size != values.size:
        raise ValueError(f"groups must give one label per data value: {labels.size} labels for "
                         f"{values.size} values")
    keep = np.isfinite(values)
    values, labels = values[keep], labels[keep]
    order = np.argsort(values, kind="stable")
    _, inverse = np.unique(labels[order], return_inverse=True)
    sizes = np.bincount(inverse)
    if sizes.size < 2:
        raise ValueError("groups: at least two groups are needed to resample them")
    members = np.argsort(inverse, kind="stable")
    offsets = np.concatenate(([0], np.cumsum(sizes)))
    return members, offsets, sizes


def _result(full, lam, nroots, stats_df, reasons, B, level, kind, method, param, options, x, entropy,
            *, warn, grouping=None):
    import pandas as pd

    frame = pd.DataFrame(lam, columns=list(_LAMBDA_NAMES))
    frame["n_roots"] = nroots
    region, jump = _branches(lam, full.lambdas[2:], param)
    frame["region"] = region
    frame["branch_jump"] = jump
    frame.index.name = "resample"
    bad = [r for r in range(B) if not np.all(np.isfinite(lam[r]))]
    detail = [reasons[r] or "no fit: invalid lambdas" for r in bad]
    failed = pd.DataFrame({"resample": np.array(bad, dtype=np.int64),
                           "reason": [d.split(":", 1)[0] for d in detail], "detail": detail})
    if warn and bad:
        common = failed.groupby("reason", sort=False)["detail"].agg(["size", "first"])
        common = common.sort_values("size", ascending=False).head(3)
        why = "; ".join(f"{row['size']} x {reason} (e.g. {row['first'][:200]})"
                        for reason, row in common.iterrows())
        if len(bad) == B:
            raise FitError(f"all {B} bootstrap resamples failed to fit ({method}, {param}): {why}")
        loud = "MOST " if 2 * len(bad) > B else ""
        warnings.warn(f"{loud}bootstrap fits failed: {len(bad)} of {B} resamples have no {method} fit "
                      f"(listed in .failed; intervals use the other {B - len(bad)}). Reasons: {why}",
                      BootstrapWarning, stacklevel=3)
    ok = np.all(np.isfinite(lam), axis=1)
    logger.info("bootstrap %s %s: %d of %d resamples fitted", param, method, int(ok.sum()), B)
    note = _branch_note(region[ok], jump[ok], param, full.region)
    if warn and note:
        warnings.warn(f"bootstrap lambdas on several branches: {note}", BootstrapWarning, stacklevel=3)
    return BootstrapFit(fit=full, lambdas=frame, statistics=stats_df, failed=failed, n_resamples=B,
                        confidence_level=level, kind=kind, method=method, param=param,
                        options=dict(full.options) if full.options else dict(options), _data=x,
                        _entropy=entropy, _grouping=grouping)
