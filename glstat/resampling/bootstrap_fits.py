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
import warnings
from concurrent.futures import Executor

import numpy as np

from .._fit_engine import sample_statistics as _S
from ..fitting import GLDFit, fit
from ._arguments import (
    COMPILED,
    Arguments,
    check_arguments,
    draw_entropy,
    group_choices,
    resample_seeds,
)
from ._diagnostics import (
    BootstrapWarning,
    branch_note,
    branches,
    failed_frame,
    failure_reasons,
    warn_failures,
    warn_uncovered,
)
from ._driver import ResampleFits, fit_resamples
from ._result import BootstrapFit
from ._tables import lambdas_frame, statistics_frame

__all__ = ["bootstrap"]

logger = logging.getLogger("glstat.bootstrap")  # the name of the public function


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
    args = check_arguments(data, param, method, n_resamples, confidence_level, kind, nan_policy,
                           groups)
    method = args.method  # glstat's name of an R or scipy alias
    x, _ = _S.prepare_data(data, nan_policy)
    entropy = draw_entropy(rng)
    if x is None:  # nan_policy="propagate" met a non-finite value
        return _propagated(data, args, kind, method, options, entropy)
    full = fit(x, args.param, method, **options)
    seeds = resample_seeds(entropy, args.n_resamples)
    logger.debug("bootstrap: %d %s resamples of %d values (groups: %s), %s %s fits, %s",
                 args.n_resamples, kind, x.size,
                 "no" if args.groups is None else args.groups.sizes.size, args.param, method,
                 "compiled batch" if method in COMPILED else f"executor {executor!r}")
    fits = fit_resamples(x, seeds, full, kind, method, args.param, args.groups, executor, progress,
                         options)
    grouping = None
    if args.groups is not None:
        grouping = (args.groups.sizes, group_choices(seeds, args.groups.sizes.size), args.groups)
    return _result(full, fits, args, kind, method, options, x, entropy, grouping)


def _propagated(data, args: Arguments, kind, method, options, entropy) -> BootstrapFit:
    """The bootstrap of data with non-finite values under ``nan_policy="propagate"``: the NaN
    fit of the full sample and B failed resamples, without a warning."""
    full = fit(data, args.param, method, nan_policy="propagate", **options)
    B = args.n_resamples
    reasons = ["data contain non-finite values (nan_policy='propagate')"] * B
    fits = ResampleFits(np.full((B, 4), np.nan), np.zeros(B, dtype=np.int64), reasons)
    return _result(full, fits, args, kind, method, options, None, entropy, None, warn=False)


def _result(full: GLDFit, fits: ResampleFits, args: Arguments, kind, method, options, x, entropy,
            grouping, *, warn: bool = True) -> BootstrapFit:
    """The :class:`BootstrapFit` of the resample fits: their tables, and the warnings about
    fits without cover, failed resamples and several branches (``warn``)."""
    B, param, lam = args.n_resamples, args.param, fits.lambdas
    reasons = failure_reasons(fits.errors, lam, fits.n_roots, fits.statistics, fits.extremes,
                              method, param)
    if warn and fits.n_cover is not None:
        warn_uncovered(lam, fits.n_cover, method, param, stacklevel=3)
    region, jump = branches(lam, full.lambdas[2:], param)
    failed = failed_frame(lam, reasons)
    if warn:
        warn_failures(failed, B, method, param, stacklevel=3)
    ok = np.all(np.isfinite(lam), axis=1)
    logger.info("bootstrap %s %s: %d of %d resamples fitted", param, method, int(ok.sum()), B)
    note = branch_note(region[ok], jump[ok], param, full.region)
    if warn and note:
        warnings.warn(f"bootstrap lambdas on several branches: {note}", BootstrapWarning, stacklevel=3)
    return BootstrapFit(fit=full, lambdas=lambdas_frame(lam, fits.n_roots, region, jump),
                        statistics=statistics_frame(fits, method), failed=failed, n_resamples=B,
                        confidence_level=args.confidence_level, kind=kind, method=method, param=param,
                        options=dict(full.options) if full.options else dict(options), _data=x,
                        _entropy=entropy, _grouping=grouping)
