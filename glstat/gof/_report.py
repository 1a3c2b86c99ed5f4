"""The goodness-of-fit table of one sample against several models (:func:`gof_report`).

Each row holds a model's statistics, its likelihood criteria, its worst quantile deviation,
and p-values either classical (parameters known) or by parametric bootstrap (parameters
estimated).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy import stats

from ._statistics import ad_asymptotic_sf, check_bins, evaluate_quietly, model_statistics, pit
from .inputs import Model, as_dist, assessed_models, check_gof_resamples, prepare_sample

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["empty_row", "gof_report", "report_table"]

_QDEV_GRID = np.round(np.arange(1, 100) / 100.0, 2)
_KNOWN = "known parameters: KS exact, A², W² and chi² asymptotic"
_NOT_AVAILABLE = "not available (parameters estimated; set n_resamples)"
_PROPAGATED = "not available (data contain NaN; nan_policy='propagate')"


def _qdev(dist, x: np.ndarray) -> tuple[float, float, float]:
    n = x.size
    q25, q75 = np.quantile(x, [0.25, 0.75], method="weibull")
    iqr = float(q75 - q25)
    grid = _QDEV_GRID[(_QDEV_GRID >= 1.0 / (n + 1)) & (_QDEV_GRID <= n / (n + 1.0))]
    if grid.size == 0 or not iqr > 0:
        return math.nan, math.nan, iqr
    emp = np.quantile(x, grid, method="weibull")
    mod = evaluate_quietly(dist, "ppf", grid)
    dev = np.abs(emp - mod) / iqr
    j = int(np.nanargmax(dev)) if np.any(np.isfinite(dev)) else 0
    return float(dev[j]), float(grid[j]), iqr


def _loglik(dist, x: np.ndarray) -> float:
    lp = evaluate_quietly(dist, "logpdf", x)
    if np.any(np.isnan(lp)):
        return math.nan
    return float(math.fsum(lp)) if np.all(np.isfinite(lp)) else float(np.sum(lp))


def _classical_pvalues(s: dict, n: int, u_dist, x) -> dict[str, float]:
    out = {"ks_pvalue": float(stats.kstwo.sf(s["ks"], n)), "ad_pvalue": ad_asymptotic_sf(s["ad"])}
    u, _, _ = pit(u_dist, x)
    if np.all((u >= 0) & (u <= 1)):
        out["cvm_pvalue"] = float(stats.cramervonmises(u, "uniform").pvalue)
    else:
        out["cvm_pvalue"] = math.nan
    cells = s["chi2_bins"]
    out["chi2_pvalue"] = float(stats.chi2.sf(s["chi2"], cells - 1)) if cells >= 2 else math.nan
    return out


_STATS = ("ks", "ad", "cvm", "chi2")


def _bootstrap_pvalues(model: Model, observed: dict, n: int, bins, n_resamples: int,
                       rng: np.random.Generator) -> tuple[dict[str, float], int, str]:
    exceed = dict.fromkeys(_STATS, 0)
    valid = dict.fromkeys(_STATS, 0)
    failed = 0
    last_error = ""
    refit = model.refit
    if refit is None:
        raise TypeError(f"{model.name}: an estimated model needs a refit function for the "
                        "bootstrap p-values")
    for _ in range(n_resamples):
        sim = np.sort(np.asarray(model.dist.rvs(size=n, random_state=rng), dtype=float))
        try:
            # no warning filters here: the default refits do not warn, and this loop may run
            # in a worker thread, where changing the process-wide filters is not safe
            dist_b = as_dist(refit(sim))
            s = model_statistics(dist_b, sim, bins)
        except Exception as exc:  # a refit that fails is counted and reported, never hidden
            failed += 1
            last_error = f"{type(exc).__name__}: {exc}"
            continue
        for key in _STATS:
            if not math.isnan(s[key]) and not math.isnan(observed[key]):
                valid[key] += 1
                exceed[key] += s[key] >= observed[key]
    pv = {f"{key}_pvalue": (exceed[key] + 1.0) / (valid[key] + 1.0) if valid[key] else math.nan
          for key in _STATS}
    return pv, failed, last_error


def _outside_note(dist, x: np.ndarray) -> str:
    """Why A² is infinite: how many of the sorted values ``x`` lie outside the model's support
    (``F = 0`` or ``1 - F = 0`` there), with the support when the model has one."""
    _, logf, logs = pit(dist, x)
    below, above = int(np.sum(np.isneginf(logf))), int(np.sum(np.isneginf(logs)))
    where = []
    if below:
        where.append(f"{below} below")
    if above:
        where.append(f"{above} above")
    support = ""
    if callable(getattr(dist, "support", None)):
        with np.errstate(all="ignore"):
            lo, hi = (float(v) for v in dist.support())
        support = f" [{lo:.6g}, {hi:.6g}]"
    return (f"A² is infinite: {below + above} of the {x.size} values lie outside the model's "
            f"support{support} ({' and '.join(where) or 'at its ends'}), where it has no "
            "probability, so the A² p-value is 0")


def empty_row(model: Model, n: int, why: str) -> dict[str, Any]:
    """A table row without statistics: the model's name, family, method and k, NaN elsewhere.

    Parameters
    ----------
    model : Model
        The row's model.
    n : int
        The number of points.
    why : str
        Why there are no statistics (the ``pvalue_method`` entry).

    Returns
    -------
    dict
        Column name -> value.
    """
    row = {"name": model.name, "family": model.family, "method": model.method, "k": model.k, "n": n}
    for key in ("loglik", "aic", "bic", "ks", "ks_pvalue", "ad", "ad_pvalue", "cvm", "cvm_pvalue",
                "chi2", "chi2_bins", "chi2_dof", "chi2_pvalue", "max_qdev_iqr", "max_qdev_prob"):
        row[key] = math.nan
    row.update({"pvalue_method": why, "n_resamples": 0, "n_failed_refits": 0})
    return row


_COLUMNS = ["name", "family", "method", "k", "n", "loglik", "aic", "bic", "ks", "ks_pvalue", "ad",
            "ad_pvalue", "cvm", "cvm_pvalue", "chi2", "chi2_bins", "chi2_dof", "chi2_pvalue",
            "max_qdev_iqr", "max_qdev_prob", "pvalue_method", "n_resamples", "n_failed_refits"]


def report_table(x: np.ndarray | None, n_total: int, models: list[Model], n_resamples: int, rng, bins):
    """The goodness-of-fit table of a prepared sample (the work of :func:`gof_report`).

    Parameters
    ----------
    x : ndarray or None
        The sorted finite sample (None: every row NaN, for ``nan_policy="propagate"``).
    n_total : int
        The number of data points as given (the ``n`` of the NaN rows).
    models : list of Model
        The rows.
    n_resamples : int
        Parametric-bootstrap replicates for the estimated models (0: none).
    rng : numpy.random.Generator
        Random source of the bootstrap.
    bins : "auto", int or ndarray
        The chi-square cells, as returned by :func:`glstat.gof._statistics.check_bins`.

    Returns
    -------
    pandas.DataFrame
        The columns of :func:`gof_report`.

    Warns
    -----
    RuntimeWarning
        When bootstrap refits failed (counted and named in the table as well).
    """
    import pandas as pd

    rows = []
    for model in models:
        if x is None:
            rows.append(empty_row(model, n_total, _PROPAGATED))
            continue
        n = x.size
        s = model_statistics(model.dist, x, bins)
        ll = _loglik(model.dist, x)
        qdev, qprob, _ = _qdev(model.dist, x)
        row: dict[str, Any] = {"name": model.name, "family": model.family, "method": model.method,
                               "k": model.k, "n": n, "loglik": ll,
                               "aic": 2.0 * model.k - 2.0 * ll, "bic": model.k * math.log(n) - 2.0 * ll}
        row.update(s)
        cells = s["chi2_bins"]
        row["chi2_dof"] = (cells - 1 - model.k) if cells >= 2 else math.nan
        row["max_qdev_iqr"] = qdev
        row["max_qdev_prob"] = qprob
        failed = 0
        if not model.estimated:
            row.update(_classical_pvalues(s, n, model.dist, x))
            how = _KNOWN
        elif n_resamples > 0:
            pv, failed, err = _bootstrap_pvalues(model, s, n, bins, n_resamples, rng)
            row.update(pv)
            how = f"parametric bootstrap (B={n_resamples})"
            if failed:
                how += f"; {failed} refit(s) failed, last: {err}"
                level = "most" if failed > n_resamples / 2 else "some"
                warnings.warn(f"{model.name}: {failed} of {n_resamples} bootstrap refits failed ({level}); "
                              f"p-values use the {n_resamples - failed} that succeeded. Last error: {err}",
                              RuntimeWarning, stacklevel=3)
        else:
            row.update(dict.fromkeys(("ks_pvalue", "ad_pvalue", "cvm_pvalue", "chi2_pvalue"), math.nan))
            how = _NOT_AVAILABLE
        if s["ad"] == math.inf:  # a value the model cannot produce: rejected, whatever B says
            row["ad_pvalue"] = 0.0
            how += "; " + _outside_note(model.dist, x)
        row["pvalue_method"] = how
        row["n_resamples"] = n_resamples if (model.estimated and n_resamples > 0) else 0
        row["n_failed_refits"] = failed
        rows.append(row)
    frame = pd.DataFrame(rows, columns=_COLUMNS)
    frame["chi2_bins"] = frame["chi2_bins"].astype("Int64")
    frame["chi2_dof"] = frame["chi2_dof"].astype("Int64")
    return frame


def gof_report(data, *fits_or_dists, names: Sequence[str] | None = None, n_resamples: int = 0,
               rng=None, bins: str | int | Sequence[float] = "auto", nan_policy: str = "raise",
               estimated: bool | Sequence[bool | None] | None = None,
               refit: Callable | Sequence[Callable | None] | None = None,
               n_params: int | Sequence[int | None] | None = None) -> pd.DataFrame:
    """Goodness-of-fit table of one sample against fitted GLDs or scipy distributions.

    Parameters
    ----------
    data : array_like
        The sample (any shape; flattened, never modified), in the units of the distributions.
    *fits_or_dists : GLDFit, GLD or frozen continuous scipy.stats distribution
        The models to assess. A :class:`glstat.GLDFit` counts as estimated from ``data``
        (4 parameters) and is refitted with :func:`glstat.fit` with the same ``param``,
        ``method`` and options (``warn=False``: replicates warn nothing); a frozen
        distribution counts as known unless ``estimated`` or ``refit`` says otherwise. A
        known GLD is ``fit.dist`` or ``glstat.GLD(l1, l2, l3, l4, param=...)``, lambdas in
        R's order (``gld_rs``/``gld_fkml`` take scipy's: lambda3, lambda4, loc, scale).
    names : sequence of str, optional
        Row names; default from the family and method. Repeated names get ``" #2"``, ...
    n_resamples : int, optional
        Parametric-bootstrap replicates B for the p-values of estimated models (0: none;
        otherwise >= 2). Default 0.
    rng : numpy.random.Generator, int or None, optional
        Random source of the bootstrap (``numpy.random.default_rng(rng)``).
    bins : "auto", int or sequence of float, optional
        Cells of the chi-square. ``"auto"``: ``min(ceil(2 n^(2/5)), n // 5)`` cells
        equiprobable under each model (expected count >= 5); an integer: that many
        equiprobable cells; a sequence: increasing cut points c1 < ... < cm in the units of
        the data, cells (-inf, c1], (c1, c2], ..., (cm, inf).
    nan_policy : {"raise", "omit", "propagate"}, optional
        Non-finite data: raise ``ValueError``, drop them, or return rows of NaN statistics.
    estimated : bool or sequence of (bool or None), optional
        Whether each model's parameters were estimated from ``data``. Default: True for a
        GLDFit and for a frozen distribution given a ``refit``, False otherwise.
    refit : callable or sequence of (callable or None), optional
        For estimated frozen distributions: ``refit(sample) -> frozen distribution or
        GLDFit`` fitting a sample the way the model was fitted. It is called as it is, in
        the thread running ``gof_report``, and its warnings are not filtered: call
        ``glstat.fit(..., warn=False)`` in it rather than ``warnings.catch_warnings()``. Default for a frozen
        distribution: ``dist.dist(*dist.dist.fit(sample))`` (scipy's maximum likelihood of
        every shape, loc and scale).
    n_params : int or sequence of (int or None), optional
        Number k of parameters estimated from ``data`` (for AIC, BIC and the chi-square dof).
        Default: 4 for a GLDFit, shapes + loc + scale for an estimated frozen distribution,
        0 for a known one.

    Returns
    -------
    pandas.DataFrame
        One row per model, columns:

        * ``name``, ``family`` (``"gld_rs"``, ``"gld_fkml"`` or the scipy name), ``method``
          (fit method, ``"estimated"`` or ``"given"``), ``k``, ``n`` (points used);
        * ``loglik`` (natural log, data in their units), ``aic`` = 2k − 2 loglik,
          ``bic`` = k ln n − 2 loglik; ``-inf``/``inf`` when a point is outside the support;
        * ``ks`` (Kolmogorov–Smirnov D), ``ad`` (Anderson–Darling A²), ``cvm``
          (Cramér–von Mises W²), all dimensionless, see :func:`edf_statistics`;
        * ``chi2`` (Pearson), ``chi2_bins`` (cells), ``chi2_dof`` = cells − 1 − k;
        * ``max_qdev_iqr``: the largest |empirical − model quantile| over the probabilities
          0.01, 0.02, ..., 0.99 that lie within [1/(n+1), n/(n+1)], divided by the sample
          interquartile range (empirical quantiles at (n+1)p), and ``max_qdev_prob``, the
          probability where it occurs;
        * ``ks_pvalue``, ``ad_pvalue``, ``cvm_pvalue``, ``chi2_pvalue`` and
          ``pvalue_method``, which says how they were obtained: for known parameters the
          exact KS distribution (``scipy.stats.kstwo``), the limiting A² distribution
          (Marsaglia & Marsaglia 2004), scipy's W² distribution and chi² with cells − 1
          dof; for estimated parameters ``"parametric bootstrap (B=...)"`` with
          p = (1 + #{T* >= T}) / (1 + B_ok), or ``"not available ..."`` when
          ``n_resamples=0`` (the classical p-values would be too large). An infinite A² (a
          value outside the model's support, where the model has no probability) has the
          p-value 0 however it was obtained, and ``pvalue_method`` then says how many values
          lie outside the support (replicates of the fitting method may also have infinite
          statistics, which would make a bootstrap p-value of ties, not evidence of fit);
        * ``n_resamples`` and ``n_failed_refits`` (failed bootstrap refits are counted,
          named in ``pvalue_method`` and warned about, never silently dropped).

    Raises
    ------
    TypeError
        Non-numeric data, or a model of an unsupported type.
    ValueError
        Empty or constant data, fewer than 2 finite points, NaN with ``nan_policy="raise"``,
        no models, bad ``bins``, ``n_resamples`` of 1 or negative, or per-model sequences of
        the wrong length.

    Notes
    -----
    A bootstrap replicate draws n points from the fitted model, refits them and recomputes
    every statistic against the refitted model (with ``"auto"`` or integer ``bins`` the
    cells are equiprobable under the refitted model). This reproduces the effect of
    estimating the parameters, which makes the EDF statistics smaller than for a model
    fixed in advance.

    Examples
    --------
    >>> import numpy as np, glstat
    >>> x = np.random.default_rng(1).gamma(5.0, 3.0, size=300)
    >>> tab = glstat.gof_report(x, glstat.fit(x, "rs", "moments"), n_resamples=19, rng=2)
    >>> list(tab[["name", "pvalue_method"]].iloc[0])
    ['GLD-RS (moments)', 'parametric bootstrap (B=19)']
    """
    if not fits_or_dists:
        raise ValueError("give at least one GLDFit, GLD or frozen scipy distribution to assess")
    b = check_gof_resamples(n_resamples)
    bins = check_bins(bins)
    models = assessed_models(fits_or_dists, names, estimated, refit, n_params)
    x, _ = prepare_sample(data, nan_policy)
    n_total = int(np.size(data))
    return report_table(x, n_total, models, b, np.random.default_rng(rng), bins)
