"""The resampling driver of :func:`glstat.bootstrap`: drawing the resamples and fitting them.

A nonparametric resample is ``x[g.integers(0, n, n)]`` of the sorted finite data ``x`` (or
the members of G groups drawn with replacement), a parametric one is n draws ``Q(U)`` from
the full-sample fit, generated directly in increasing order (normalised partial sums of
n + 1 exponential variables are distributed as the order statistics of n uniforms) and with
``Q(1 - U)`` taken through the upper-tail quantile wherever ``U > 1/2``; ``g`` is the
resample's own generator (:mod:`glstat.resampling._arguments`), so the resamples do not depend on
the fitting method, the batching or the executor.

The compiled methods (moments, percentiles, L-moments) get the statistics of all resamples
from one compiled pass (:mod:`glstat._core.resample`) and their lambdas from one call to
:func:`glstat.fit_batch`; the others call :func:`glstat.fit` per resample, in tasks of a few
resamples, optionally on a ``concurrent.futures.Executor``.
"""

from __future__ import annotations

import math
from concurrent.futures import Executor
from typing import NamedTuple

import numpy as np

from .._core import resample as _R
from .._fit_engine import sample_statistics as _S
from ..errors import FitError, InvalidParameterError
from ..fitting import GLDFit, fit, fit_batch
from ._arguments import COMPILED, Groups
from ._diagnostics import stat_failures
from ._lambda_rows import FAMILY, quantiles

__all__ = ["ResampleFits", "draw", "fit_resamples", "group_indices", "jackknife_lambdas",
           "resample_fit_task"]

# values per chunk of the compiled path (index rows of int32: 8 MB)
_CHUNK_VALUES = 2_000_000
# resamples per task of the per-resample path
_TASK_SIZE = 8
# largest number of delete-a-group jackknife samples (BCa acceleration)
_JACKKNIFE_GROUPS = {"compiled": 1000, "data": 100}
# the progress bar appears by default above this much work (values resampled x fits)
_PROGRESS_WORK = {"compiled": 3e8, "data": 2e5}


class ResampleFits(NamedTuple):
    """The fits of the B resamples.

    Attributes
    ----------
    lambdas : ndarray, shape (B, 4)
        lambda1..lambda4 of every resample; NaN where it has no fit.
    n_roots : ndarray of int, shape (B,)
        Number of valid roots or candidates.
    errors : list of str
        Per resample, why it was not fitted or its fit failed ("" otherwise).
    extremes : ndarray, shape (B, 2), or None
        Minimum and maximum of every resample (None when nothing was resampled).
    statistics : ndarray, shape (B, 4), or None
        The matched statistics (compiled methods only).
    n_cover : ndarray of int, shape (B,), or None
        Number of valid roots covering the resample (compiled methods only).
    """

    lambdas: np.ndarray
    n_roots: np.ndarray
    errors: list[str]
    extremes: np.ndarray | None = None
    statistics: np.ndarray | None = None
    n_cover: np.ndarray | None = None


def group_indices(groups: Groups, chosen: np.ndarray) -> np.ndarray:
    """Indices into the sorted sample of the members of the chosen groups, group after group."""
    members, offsets = groups.members, groups.offsets
    sizes = offsets[1:] - offsets[:-1]
    take = sizes[chosen]
    starts = offsets[:-1][chosen]
    shift = np.repeat(starts - np.concatenate(([0], np.cumsum(take)[:-1])), take)
    return members[np.arange(int(take.sum())) + shift]


def draw(x: np.ndarray, g: np.random.Generator, kind: str, lam, fam: int,
         groups: Groups | None = None) -> np.ndarray:
    """One resample with generator ``g`` (length n, or the members of G groups drawn with
    replacement); sorted for the parametric kind."""
    n = x.size
    if groups is not None:
        G = groups.sizes.size
        return x[group_indices(groups, g.integers(0, G, size=G, dtype=np.int64))]
    if kind == "nonparametric":
        return x[g.integers(0, n, size=n, dtype=np.int64)]
    e = g.standard_exponential(n + 1)
    total = math.fsum(e)
    v = np.cumsum(e[:-1]) / total
    q = np.cumsum(e[:0:-1])[::-1] / total
    return quantiles(np.asarray(lam, dtype=float)[None, :], fam, v[None, :], q[None, :])[0]


def resample_fit_task(x, seeds, kind, lam, param, method, options, groups=None):
    """Fits of the resamples with the given seeds (runs in the executor's workers): per
    resample ``(lambdas, n_valid, error, (min, max))``."""
    fam = FAMILY[param]
    out = []
    for s in seeds:
        sample = draw(x, np.random.default_rng(s), kind, lam, fam, groups)
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
    from _glstat_runtime.progress import progress_bar

    return progress_bar(total, desc, "resample")


def _compiled_statistics(x, seeds, kind, lam, fam, method, u, loc, scale, bar, groups=None):
    """Statistics (B, 4) and extremes (B, 2: min, max) of the resamples, compiled."""
    code = _R.CODES[method]
    n = x.size
    B = len(seeds)
    st = np.empty((B, 4))
    ext = np.empty((B, 2))
    if groups is not None:  # resamples of groups have their own lengths: one call each
        G = groups.sizes.size
        for r, seed in enumerate(seeds):
            chosen = np.random.default_rng(seed).integers(0, G, size=G, dtype=np.int64)
            idx = group_indices(groups, chosen)[None, :]
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
                samples[j] = draw(x, np.random.default_rng(seed), kind, lam, fam)
            _R.stats_from_sorted(code, samples, u, loc, scale, st[s:s + len(chunk)],
                                 ext[s:s + len(chunk)])
        if bar is not None:
            bar.update(len(chunk))
    return st, ext


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


def _compiled_fits(x, seeds, full: GLDFit, kind, method, param, groups, bar) -> ResampleFits:
    """The compiled path: one pass for the statistics, one call of fit_batch for the lambdas.

    Of the valid roots of a resample the one covering its range and closest to the full-sample
    shapes is kept, the rule of the full-sample fit; when the full-sample fit itself does not
    cover the data, a resample without a covering root keeps its nearest root.
    """
    B = len(seeds)
    u = float(full.options.get("u", 0.1))
    mean, std = _S.location_spread(x)
    st, ext = _compiled_statistics(x, seeds, kind, full.lambdas, FAMILY[param], method, u, mean,
                                   std, bar, groups)
    errors = stat_failures(method, st)
    ok = np.array([r == "" for r in errors])
    lam = np.full((B, 4), np.nan)
    nroots = np.zeros(B, dtype=np.int64)
    ncover = np.zeros(B, dtype=np.int64)
    if ok.any():
        lam[ok], nroots[ok], ncover[ok] = fit_batch(
            st[ok], method, param, u=u, ref=full.lambdas[2:], extremes=ext[ok],
            require_cover=_covers_data(full), return_cover=True)
    return ResampleFits(lam, nroots, errors, ext, st, ncover)


def _per_resample_fits(x, seeds, full: GLDFit, kind, method, param, groups, bar,
                       executor: Executor | None, options) -> ResampleFits:
    """The per-resample path: :func:`glstat.fit` on every resample, in tasks of a few."""
    tasks = [seeds[s:s + _TASK_SIZE] for s in range(0, len(seeds), _TASK_SIZE)]
    args = (kind, full.lambdas, param, method, dict(options), groups)
    results = []
    if executor is None:
        for t in tasks:
            results.extend(resample_fit_task(x, t, *args))
            if bar is not None:
                bar.update(len(t))
    else:
        futures = [executor.submit(resample_fit_task, x, t, *args) for t in tasks]
        for fut, t in zip(futures, tasks, strict=True):
            results.extend(fut.result())
            if bar is not None:
                bar.update(len(t))
    return ResampleFits(np.array([r[0] for r in results], dtype=float),
                        np.array([r[1] for r in results], dtype=np.int64),
                        [r[2] for r in results],
                        np.array([r[3] for r in results], dtype=float))


def fit_resamples(x: np.ndarray, seeds, full: GLDFit, kind: str, method: str, param: str,
                  groups: Groups | None, executor: Executor | None, progress: bool | None,
                  options: dict) -> ResampleFits:
    """Draw and fit the resamples with the given seeds (a tqdm bar shows the progress when
    ``progress`` says so; by default only for long runs)."""
    compiled = method in COMPILED
    if progress is None:
        progress = len(seeds) * x.size > _PROGRESS_WORK["compiled" if compiled else "data"]
    bar = _progress_bar(len(seeds), bool(progress), f"bootstrap {method}")
    try:
        if compiled:
            return _compiled_fits(x, seeds, full, kind, method, param, groups, bar)
        return _per_resample_fits(x, seeds, full, kind, method, param, groups, bar, executor,
                                  options)
    finally:
        if bar is not None:
            bar.close()


def jackknife_lambdas(x: np.ndarray, method: str, param: str, options: dict, ref,
                      seed: np.random.SeedSequence) -> np.ndarray:
    """Lambdas of the delete-a-group jackknife samples of the data (the failed ones left out).

    Delete-one for n up to 1000 (compiled methods) or 100 (the others); otherwise the data
    are split at random (generator seeded by ``seed``) into that many groups. ``ref`` is the
    full-sample fit's (lambda1, ..., lambda4).
    """
    n = x.size
    compiled = method in COMPILED
    groups = min(n, _JACKKNIFE_GROUPS["compiled" if compiled else "data"])
    group = np.empty(n, dtype=np.int64)
    perm = np.random.default_rng(seed).permutation(n)
    group[perm] = np.arange(n) % groups
    lam = np.full((groups, 4), np.nan)
    if compiled:
        st = np.empty((groups, 4))
        ext = np.empty((groups, 2))
        mean, std = _S.location_spread(x)
        u = float(options.get("u", 0.1))
        _R.stats_delete_groups(_R.CODES[method], x, group, groups, u, mean, std, st, ext)
        ok = np.array([r == "" for r in stat_failures(method, st)])
        if ok.any():
            lam[ok], _ = fit_batch(st[ok], method, param, u=u, ref=ref[2:], extremes=ext[ok])
    else:
        for g in range(groups):
            try:
                lam[g] = fit(x[group != g], param, method, warn=False, **options).lambdas
            except (FitError, InvalidParameterError, FloatingPointError, ValueError):
                pass
    return lam[np.all(np.isfinite(lam), axis=1)]
