"""Goodness of fit: EDF statistics, binned chi-square, likelihood criteria, family comparison.

:func:`gof_report` tabulates, for one sample and any number of fitted GLDs or frozen scipy
distributions, the Kolmogorov–Smirnov, Anderson–Darling and Cramér–von Mises statistics, a
binned chi-square, the log-likelihood with AIC and BIC, and the worst quantile deviation.
When the parameters were estimated from the same sample the classical p-values do not apply;
they are then computed by parametric bootstrap (simulate from the fitted model, refit by the
same method, recompute the statistics). :func:`compare_families` fits several families and
ranks them by AIC. :func:`edf_statistics` is the numerical core. :func:`adjust_pvalues`
adjusts the p-values of several tests (e.g. one per Hurst exponent) for multiple testing with
``statsmodels.stats.multitest.multipletests`` (statsmodels is imported when it runs).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy import stats

from .fitting import GLDFit
from .fitting import fit as _gld_fit
from .fitting._eval import gld_evaluate
from .gld import GLD

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["DEFAULT_FAMILIES", "adjust_pvalues", "compare_families", "edf_statistics", "gof_report"]

DEFAULT_FAMILIES = ("gld_rs", "gld_fkml", "norm", "lognorm", "weibull_min", "gamma", "genextreme",
                    "gumbel_r")
"""Families compared by :func:`compare_families` by default."""

_NAN_POLICIES = ("raise", "omit", "propagate")
_QDEV_GRID = np.round(np.arange(1, 100) / 100.0, 2)
_KNOWN = "known parameters: KS exact, A², W² and chi² asymptotic"
_NOT_AVAILABLE = "not available (parameters estimated; set n_resamples)"
_PROPAGATED = "not available (data contain NaN; nan_policy='propagate')"
_LOG_HALF = math.log(0.5)


# ---------------------------------------------------------------------------------------------
# EDF statistics
# ---------------------------------------------------------------------------------------------
def _quiet(dist, what: str, x) -> np.ndarray:
    """``dist.<what>(x)`` as a float array, without warnings and without touching the
    process-wide warning filters (this runs in the bootstrap replicates, possibly in worker
    threads): a GLD is evaluated by the compiled kernels directly (points where the inversion
    of Q reached its limit keep the best estimate), other distributions under
    ``numpy.errstate`` (thread-local)."""
    if isinstance(dist, GLD) and what in ("cdf", "sf", "logcdf", "logsf", "pdf", "logpdf"):
        return gld_evaluate(dist.param, what, x, dist.lambdas)[0]
    with np.errstate(all="ignore"):
        return np.asarray(getattr(dist, what)(x), dtype=float)


def _pit(dist, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Probability integral transform of sorted ``x``: (u, log F, log(1 - F)).

    ``u`` is taken from log F below the median and from log(1 - F) above it, so that it
    carries the accuracy of whichever tail it lies in.
    """
    logf = _quiet(dist, "logcdf", x).reshape(x.shape)
    logs = _quiet(dist, "logsf", x).reshape(x.shape)
    with np.errstate(all="ignore"):
        u = np.where(logf <= _LOG_HALF, np.exp(logf), -np.expm1(logs))
    return u, logf, logs


def _edf_from_pit(u: np.ndarray, logf: np.ndarray, logs: np.ndarray) -> tuple[float, float, float]:
    n = u.size
    i = np.arange(1, n + 1, dtype=float)
    d = max(float(np.max(i / n - u)), float(np.max(u - (i - 1) / n)))
    with np.errstate(invalid="ignore"):
        terms = (2.0 * i - 1.0) * (logf + logs[::-1])
    if np.any(np.isnan(terms)):
        a2 = math.nan
    elif np.any(np.isneginf(terms)):
        a2 = math.inf
    else:
        a2 = -n - math.fsum(terms) / n
    w2 = 1.0 / (12.0 * n) + math.fsum(((2.0 * i - 1.0) / (2.0 * n) - u) ** 2)
    return d, a2, w2


def edf_statistics(data, dist) -> tuple[float, float, float]:
    """Kolmogorov–Smirnov, Anderson–Darling and Cramér–von Mises statistics of a sample.

    Parameters
    ----------
    data : array_like
        Finite sample (any shape; flattened), in the units of ``dist``.
    dist : frozen continuous distribution
        Anything with ``logcdf`` and ``logsf`` (a :class:`glstat.GLD`, a frozen
        ``scipy.stats`` distribution).

    Returns
    -------
    ks, ad, cvm : float
        Dimensionless. With ``u_i = F(x_(i))`` for the sorted sample:
        ``ks = max_i max(i/n - u_i, u_i - (i-1)/n)``;
        ``ad = A² = -n - (1/n) Σ (2i-1) [ln F(x_(i)) + ln(1 - F(x_(n+1-i)))]``;
        ``cvm = W² = 1/(12n) + Σ (u_i - (2i-1)/(2n))²``.
        ``A²`` uses ``logcdf`` and ``logsf``, so it stays finite when tail probabilities
        underflow; it is ``inf`` only when a point lies outside the support.

    Raises
    ------
    ValueError
        Empty or non-finite data.
    TypeError
        Non-numeric data.
    """
    x = _as_float(data)
    if x.size == 0:
        raise ValueError("data are empty: the EDF statistics need at least one point")
    if not np.all(np.isfinite(x)):
        raise ValueError("data contain non-finite values (NaN or inf)")
    x = np.sort(x)
    return _edf_from_pit(*_pit(dist, x))


# ---------------------------------------------------------------------------------------------
# binned chi-square
# ---------------------------------------------------------------------------------------------
def _n_cells(n: int, bins) -> int:
    """Number of cells for ``bins`` = "auto" or an integer (equiprobable under the model)."""
    if isinstance(bins, str):
        if bins != "auto":
            raise ValueError(f"bins must be 'auto', an integer or a sequence of cut points, got {bins!r}")
        # Moore's 2 n^(2/5) equiprobable cells, at most n/5 so that every expected count is >= 5
        return int(min(math.ceil(2.0 * n**0.4), n // 5))
    m = int(bins)
    if m != bins or m < 2:
        raise ValueError(f"an integer bins must be >= 2, got {bins!r}")
    return m


def _check_bins(bins):
    if isinstance(bins, str):
        _n_cells(10, bins)
        return bins
    if np.ndim(bins) == 0:
        _n_cells(10, bins)
        return int(bins)
    cuts = np.asarray(bins, dtype=float).ravel()
    if cuts.size < 1 or not np.all(np.isfinite(cuts)) or np.any(np.diff(cuts) <= 0):
        raise ValueError("bins as a sequence must be finite, strictly increasing cut points (at least one)")
    return cuts


def _chi2(dist, x: np.ndarray, bins) -> tuple[float, int]:
    """Pearson chi-square of sorted ``x`` and the number of cells (0 when too few points)."""
    n = x.size
    if isinstance(bins, np.ndarray):
        cuts = bins
        cdf = _quiet(dist, "cdf", cuts)
        sf = _quiet(dist, "sf", cuts)
        # cell probabilities from the cdf below the median and the sf above it
        p = np.empty(cuts.size + 1)
        p[0] = cdf[0]
        p[-1] = sf[-1]
        p[1:-1] = np.where(cdf[1:] <= 0.5, cdf[1:] - cdf[:-1], sf[:-1] - sf[1:])
        expected = n * p
    else:
        m = _n_cells(n, bins)
        if m < 2:
            return math.nan, 0
        cuts = _quiet(dist, "ppf", np.arange(1, m) / m)
        expected = np.full(m, n / m)
    observed = np.diff(np.concatenate(([0], np.searchsorted(x, cuts, side="right"), [n])))
    with np.errstate(divide="ignore", invalid="ignore"):
        contrib = np.where(observed == expected, 0.0, (observed - expected) ** 2 / expected)
    return float(np.sum(contrib)), int(expected.size)


# ---------------------------------------------------------------------------------------------
# A² asymptotic distribution (parameters known)
# ---------------------------------------------------------------------------------------------
def _ad_asymptotic_sf(a2: float) -> float:
    """Upper-tail probability of the limiting Anderson–Darling distribution (case 0).

    The approximation of the limiting distribution function by Marsaglia & Marsaglia,
    *Evaluating the Anderson–Darling distribution*, J. Stat. Softw. 9(2), 2004 (absolute
    error below about 2e-6).
    """
    z = float(a2)
    if not math.isfinite(z):
        return 0.0 if z > 0 else math.nan
    if z <= 0:
        return 1.0
    if z < 2.0:
        poly = 2.00012 + (0.247105 - (0.0649821 - (0.0347962 - (0.011672 - 0.00168691 * z) * z) * z) * z) * z
        return float(min(1.0, max(0.0, 1.0 - math.exp(-1.2337141 / z) / math.sqrt(z) * poly)))
    poly = 1.0776 - (2.30695 - (0.43424 - (0.082433 - (0.008056 - 0.0003146 * z) * z) * z) * z) * z
    return float(-math.expm1(-math.exp(poly)))


# ---------------------------------------------------------------------------------------------
# models
# ---------------------------------------------------------------------------------------------
@dataclass
class _Model:
    name: str
    family: str
    method: str
    dist: Any
    k: int
    estimated: bool
    refit: Callable[[np.ndarray], Any] | None


def _is_frozen_continuous(obj) -> bool:
    return (isinstance(getattr(obj, "dist", None), stats.rv_continuous)
            and all(hasattr(obj, a) for a in ("logcdf", "logsf", "logpdf", "ppf", "rvs")))


def _family_name(dist) -> str:
    if isinstance(dist, GLD):
        return f"gld_{dist.param}"
    return str(getattr(dist.dist, "name", type(dist.dist).__name__))


def _gld_refit(param: str, method: str, options: dict) -> Callable[[np.ndarray], Any]:
    def refit(sample: np.ndarray):
        # a poor or unconverged refit is part of the null distribution: nothing to warn
        return _gld_fit(sample, param=param, method=method, warn=False, **options).dist

    return refit


def _scipy_refit(gen) -> Callable[[np.ndarray], Any]:
    def refit(sample: np.ndarray):
        with np.errstate(all="ignore"):
            return gen(*gen.fit(sample))

    return refit


def _as_dist(obj):
    """A refit result (GLDFit or frozen distribution) as a frozen distribution."""
    if isinstance(obj, GLDFit):
        if obj.dist is None:
            raise ValueError("the refit returned a NaN fit")
        return obj.dist
    if not _is_frozen_continuous(obj):
        raise TypeError(f"refit must return a GLDFit or a frozen continuous distribution, got "
                        f"{type(obj).__name__}")
    return obj


def _per_fit(value, m: int, what: str) -> list:
    if value is None or isinstance(value, (bool, int, np.integer, str)) or callable(value):
        return [value] * m
    seq = list(value)
    if len(seq) != m:
        raise ValueError(f"{what} has {len(seq)} entries for {m} fits or distributions")
    return seq


def _models(objs, names, estimated, refit, n_params) -> list[_Model]:
    m = len(objs)
    names = [None] * m if names is None else _per_fit(names, m, "names")
    est = _per_fit(estimated, m, "estimated")
    ref = _per_fit(refit, m, "refit")
    kk = _per_fit(n_params, m, "n_params")
    out = []
    for j, obj in enumerate(objs):
        if isinstance(obj, GLDFit):
            if obj.dist is None:
                raise ValueError(f"fit {j} is a NaN fit (no distribution): it cannot be assessed")
            e = True if est[j] is None else bool(est[j])
            k = 4 if kk[j] is None else int(kk[j])
            r = ref[j] if ref[j] is not None else _gld_refit(obj.param, obj.method, dict(obj.options))
            name = names[j] or f"GLD-{obj.param.upper()} ({obj.method})"
            out.append(_Model(name, f"gld_{obj.param}", obj.method, obj.dist, k if e else 0, e, r))
        elif _is_frozen_continuous(obj):
            e = (ref[j] is not None) if est[j] is None else bool(est[j])
            family = _family_name(obj)
            k = obj.dist.numargs + 2 if kk[j] is None else int(kk[j])
            r = ref[j] if ref[j] is not None else _scipy_refit(obj.dist)
            name = names[j] or (f"GLD-{obj.param.upper()}" if isinstance(obj, GLD) else family)
            out.append(_Model(name, family, "estimated" if e else "given", obj, k if e else 0, e, r))
        else:
            raise TypeError(f"argument {j + 1} after data must be a GLDFit, a GLD or a frozen continuous "
                            f"scipy.stats distribution, got {type(obj).__name__}")
        if out[-1].k < 0:
            raise ValueError(f"n_params must be >= 0, got {out[-1].k}")
        if e and not callable(out[-1].refit):
            raise TypeError(f"refit for fit {j} must be callable, got {type(out[-1].refit).__name__}")
    # unique names, so that the column can serve as an index
    seen: dict[str, int] = {}
    for mod in out:
        c = seen.get(mod.name, 0)
        seen[mod.name] = c + 1
        if c:
            mod.name = f"{mod.name} #{c + 1}"
    return out


# ---------------------------------------------------------------------------------------------
# data checks
# ---------------------------------------------------------------------------------------------
def _as_float(data) -> np.ndarray:
    arr = np.asarray(data)
    if arr.dtype.kind not in "biuf":
        if arr.dtype.kind == "O":
            try:
                return arr.astype(float).ravel()
            except (TypeError, ValueError):
                pass
        raise TypeError(f"data must be numeric (real numbers), got an array of dtype {arr.dtype}")
    return arr.astype(float).ravel()


def _prepare(data, nan_policy: str) -> tuple[np.ndarray | None, int]:
    if nan_policy not in _NAN_POLICIES:
        raise ValueError(f"nan_policy must be one of {_NAN_POLICIES}, got {nan_policy!r}")
    x = _as_float(data)
    if x.size == 0:
        raise ValueError("data are empty")
    bad = ~np.isfinite(x)
    nbad = int(bad.sum())
    if nbad:
        if nan_policy == "raise":
            raise ValueError(f"data contain {nbad} non-finite value(s) (NaN or inf) out of {x.size}; "
                             "pass nan_policy='omit' to drop them or 'propagate' for a NaN table")
        if nan_policy == "propagate":
            return None, nbad
        x = x[~bad]
    if x.size < 2:
        raise ValueError(f"goodness of fit needs at least 2 finite data points, got {x.size}")
    x = np.sort(x)
    if x[0] == x[-1]:
        raise ValueError(f"the {x.size} data points are all equal to {x[0]!r}")
    return x, nbad


# ---------------------------------------------------------------------------------------------
# report
# ---------------------------------------------------------------------------------------------
def _statistics(dist, x: np.ndarray, bins) -> dict[str, float]:
    u, logf, logs = _pit(dist, x)
    d, a2, w2 = _edf_from_pit(u, logf, logs)
    chi2, cells = _chi2(dist, x, bins)
    return {"ks": d, "ad": a2, "cvm": w2, "chi2": chi2, "chi2_bins": cells}


def _qdev(dist, x: np.ndarray) -> tuple[float, float, float]:
    n = x.size
    q25, q75 = np.quantile(x, [0.25, 0.75], method="weibull")
    iqr = float(q75 - q25)
    grid = _QDEV_GRID[(_QDEV_GRID >= 1.0 / (n + 1)) & (_QDEV_GRID <= n / (n + 1.0))]
    if grid.size == 0 or not iqr > 0:
        return math.nan, math.nan, iqr
    emp = np.quantile(x, grid, method="weibull")
    mod = _quiet(dist, "ppf", grid)
    dev = np.abs(emp - mod) / iqr
    j = int(np.nanargmax(dev)) if np.any(np.isfinite(dev)) else 0
    return float(dev[j]), float(grid[j]), iqr


def _loglik(dist, x: np.ndarray) -> float:
    lp = _quiet(dist, "logpdf", x)
    if np.any(np.isnan(lp)):
        return math.nan
    return float(math.fsum(lp)) if np.all(np.isfinite(lp)) else float(np.sum(lp))


def _classical_pvalues(s: dict, n: int, u_dist, x) -> dict[str, float]:
    out = {"ks_pvalue": float(stats.kstwo.sf(s["ks"], n)), "ad_pvalue": _ad_asymptotic_sf(s["ad"])}
    u, _, _ = _pit(u_dist, x)
    if np.all((u >= 0) & (u <= 1)):
        out["cvm_pvalue"] = float(stats.cramervonmises(u, "uniform").pvalue)
    else:
        out["cvm_pvalue"] = math.nan
    cells = s["chi2_bins"]
    out["chi2_pvalue"] = float(stats.chi2.sf(s["chi2"], cells - 1)) if cells >= 2 else math.nan
    return out


_STATS = ("ks", "ad", "cvm", "chi2")


def _bootstrap_pvalues(model: _Model, observed: dict, n: int, bins, n_resamples: int,
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
            dist_b = _as_dist(refit(sim))
            s = _statistics(dist_b, sim, bins)
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


def _empty_row(model: _Model, n: int, why: str) -> dict[str, Any]:
    row = {"name": model.name, "family": model.family, "method": model.method, "k": model.k, "n": n}
    for key in ("loglik", "aic", "bic", "ks", "ks_pvalue", "ad", "ad_pvalue", "cvm", "cvm_pvalue",
                "chi2", "chi2_bins", "chi2_dof", "chi2_pvalue", "max_qdev_iqr", "max_qdev_prob"):
        row[key] = math.nan
    row.update({"pvalue_method": why, "n_resamples": 0, "n_failed_refits": 0})
    return row


_COLUMNS = ["name", "family", "method", "k", "n", "loglik", "aic", "bic", "ks", "ks_pvalue", "ad",
            "ad_pvalue", "cvm", "cvm_pvalue", "chi2", "chi2_bins", "chi2_dof", "chi2_pvalue",
            "max_qdev_iqr", "max_qdev_prob", "pvalue_method", "n_resamples", "n_failed_refits"]


def _report(x: np.ndarray | None, n_total: int, models: list[_Model], n_resamples: int, rng, bins):
    import pandas as pd

    rows = []
    for model in models:
        if x is None:
            rows.append(_empty_row(model, n_total, _PROPAGATED))
            continue
        n = x.size
        s = _statistics(model.dist, x, bins)
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
        row["pvalue_method"] = how
        row["n_resamples"] = n_resamples if (model.estimated and n_resamples > 0) else 0
        row["n_failed_refits"] = failed
        rows.append(row)
    frame = pd.DataFrame(rows, columns=_COLUMNS)
    frame["chi2_bins"] = frame["chi2_bins"].astype("Int64")
    frame["chi2_dof"] = frame["chi2_dof"].astype("Int64")
    return frame


def _check_n_resamples(n_resamples) -> int:
    if isinstance(n_resamples, bool) or int(n_resamples) != n_resamples:
        raise TypeError(f"n_resamples must be an integer, got {n_resamples!r}")
    b = int(n_resamples)
    if b != 0 and b < 2:
        raise ValueError(f"n_resamples must be 0 (no bootstrap) or >= 2, got {b}")
    return b


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
          ``n_resamples=0`` (the classical p-values would be too large);
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
    b = _check_n_resamples(n_resamples)
    bins = _check_bins(bins)
    models = _models(fits_or_dists, names, estimated, refit, n_params)
    x, _ = _prepare(data, nan_policy)
    n_total = int(np.size(data))
    return _report(x, n_total, models, b, np.random.default_rng(rng), bins)


# ---------------------------------------------------------------------------------------------
# family comparison
# ---------------------------------------------------------------------------------------------
_POSITIVE_FAMILIES = ("lognorm", "weibull_min", "gamma")


def _gev_lmoment_start(x: np.ndarray) -> tuple[float, float, float] | None:
    """GEV (c, loc, scale) from the sample L-moments, scipy's sign of c.

    Hosking, Wallis & Wood (1985) approximation of the shape,
    c = 7.8590 z + 2.9554 z², z = 2 / (3 + t3) − ln 2 / ln 3, then the scale and location
    from l2 and l1 in closed form.
    """
    n = x.size
    if n < 3:
        return None
    i = np.arange(n, dtype=float)
    b0 = float(np.mean(x))
    b1 = float(np.sum(i * x) / (n * (n - 1)))
    b2 = float(np.sum(i * (i - 1) * x) / (n * (n - 1) * (n - 2)))
    l2 = 2 * b1 - b0
    if not l2 > 0:
        return None
    t3 = (6 * b2 - 6 * b1 + b0) / l2
    z = 2.0 / (3.0 + t3) - math.log(2.0) / math.log(3.0)
    c = 7.8590 * z + 2.9554 * z * z
    if abs(c) < 1e-6:
        scale = l2 / math.log(2.0)
        return 0.0, b0 - 0.5772156649015329 * scale, scale
    g = math.gamma(1.0 + c)
    scale = l2 * c / (g * (1.0 - 2.0 ** (-c)))
    return c, b0 - scale * (1.0 - g) / c, scale


def _starts(name: str, x: np.ndarray, loc_fixed: bool) -> list[tuple | None]:
    """Starting values for scipy's maximum likelihood (None: scipy's own start)."""
    starts: list[tuple | None] = [None]
    if name == "genextreme":
        st = _gev_lmoment_start(x)
        if st is not None:
            starts.append(st)
        loc, scale = stats.gumbel_r.fit(x)
        starts.append((0.0, loc, scale))
    elif name == "weibull_min" and loc_fixed:
        # the log of a Weibull variable is Gumbel-distributed: shape ~ pi / (sqrt 6 sd(log x))
        sd = float(np.std(np.log(x)))
        if sd > 0:
            starts.append((math.pi / math.sqrt(6.0) / sd,))
    return starts


def _mle(gen, x: np.ndarray, starts: list[tuple | None], fixed: dict[str, float]):
    """scipy maximum likelihood from each start; the fit with the largest log-likelihood."""
    best, best_ll, errors = None, -math.inf, []
    for start in starts:
        try:
            with np.errstate(all="ignore"):
                if start is None:
                    par = gen.fit(x, **fixed)
                elif len(start) == gen.numargs:
                    par = gen.fit(x, *start, **fixed)
                else:
                    shapes, (loc, scale) = start[: gen.numargs], start[gen.numargs:]
                    kw = {"loc": loc, "scale": scale} if not fixed else {"scale": scale}
                    par = gen.fit(x, *shapes, **kw, **fixed)
                if not np.all(np.isfinite(par)):
                    raise ValueError(f"non-finite parameters {par}")
                d = gen(*par)
                ll = float(np.sum(d.logpdf(x)))
        except Exception as exc:
            errors.append(f"{type(exc).__name__}: {exc}")
            continue
        if best is None or ll > best_ll:
            best, best_ll = d, ll
    if best is None:
        raise ValueError(f"{gen.name} maximum likelihood failed from every start: {'; '.join(errors)}")
    return best


def _fit_family(name: str, x: np.ndarray, gld_method: str) -> _Model:
    """Fit one family to sorted ``x``; raises on failure."""
    if name in ("gld_rs", "gld_fkml"):
        param = name[4:]
        res = _gld_fit(x, param=param, method=gld_method, warn=False)
        return _Model(f"GLD-{param.upper()} ({gld_method})", name, gld_method, res.dist, 4, True,
                      _gld_refit(param, gld_method, dict(res.options)))
    gen = getattr(stats, name, None)
    if not isinstance(gen, stats.rv_continuous):
        raise ValueError(f"{name!r} is neither 'gld_rs', 'gld_fkml' nor a continuous scipy.stats "
                         "distribution")
    fixed: dict[str, float] = {}
    if name in _POSITIVE_FAMILIES and x[0] > 0:
        fixed["floc"] = 0.0
    k = gen.numargs + 2 - len(fixed)

    def refit(sample: np.ndarray):
        if name == "lognorm" and fixed:
            # closed-form maximum likelihood of the two-parameter lognormal
            if np.any(sample <= 0):
                raise ValueError("lognormal with loc=0 needs positive data")
            ls = np.log(sample)
            return gen(float(np.std(ls)), 0.0, float(np.exp(np.mean(ls))))
        return _mle(gen, sample, _starts(name, sample, bool(fixed)), fixed)

    dist = refit(x)
    method = "mle (loc = 0 fixed)" if fixed else "mle"
    return _Model(name, name, method, dist, k, True, refit)


def compare_families(data, families: Sequence[str] = DEFAULT_FAMILIES, gld_method: str = "moments",
                     n_resamples: int = 0, rng=None, bins: str | int | Sequence[float] = "auto",
                     nan_policy: str = "raise") -> pd.DataFrame:
    """Fit several families to one sample and rank them by AIC.

    Parameters
    ----------
    data : array_like
        The sample (any shape; flattened), in its units.
    families : sequence of str, optional
        ``"gld_rs"`` and ``"gld_fkml"`` (fitted by :func:`glstat.fit` with ``gld_method``)
        and names of continuous ``scipy.stats`` distributions (fitted by maximum likelihood,
        ``scipy.stats.<name>.fit``). For ``lognorm``, ``weibull_min`` and ``gamma`` on
        positive data the location is fixed at 0 (the usual two-parameter families); on
        data with values <= 0 it is estimated. Default: :data:`DEFAULT_FAMILIES`.
    gld_method : str, optional
        :func:`glstat.fit` method for the GLDs. Default ``"moments"`` (the paper's choice);
        ``"mle"`` makes the AIC comparison a comparison of maximised likelihoods.
    n_resamples, rng, bins, nan_policy
        As in :func:`gof_report`; the bootstrap refits each family the same way.

    Returns
    -------
    pandas.DataFrame
        The :func:`gof_report` columns plus ``aic_rank`` (1 = smallest AIC), ``delta_aic``
        (AIC − smallest AIC), ``ranked_by`` (``"AIC"``) and ``error`` (the message of a
        family that could not be fitted, whose row has NaN statistics and is ranked last),
        sorted by ``aic_rank``.

    Raises
    ------
    TypeError, ValueError
        Bad data, as in :func:`gof_report`; an empty ``families``.

    Notes
    -----
    AIC = 2k − 2 ln L compares likelihoods at the fitted parameters. For families fitted by
    maximum likelihood that is the classical criterion; a GLD fitted by moments has a lower
    likelihood than its maximum-likelihood fit, so its AIC is a conservative one.
    """
    import pandas as pd

    fams = [families] if isinstance(families, str) else list(families)
    if not fams:
        raise ValueError("families is empty")
    b = _check_n_resamples(n_resamples)
    bins = _check_bins(bins)
    x, _ = _prepare(data, nan_policy)
    n_total = int(np.size(data))
    models, errors = [], {}
    for name in fams:
        if x is None:
            models.append(_Model(str(name), str(name), "", None, 0, True, None))
            continue
        try:
            models.append(_fit_family(str(name), x, gld_method))
        except Exception as exc:  # one family failing must not stop the comparison
            errors[str(name)] = f"{type(exc).__name__}: {exc}"
    ok = [m for m in models if m.dist is not None] if x is not None else []
    frame = _report(x, n_total, ok if x is not None else models, b, np.random.default_rng(rng), bins)
    fail_rows = []
    for name, msg in errors.items():
        row = _empty_row(_Model(name, name, "", None, 0, True, None), x.size if x is not None else n_total,
                         "not available (fit failed)")
        row["k"] = pd.NA
        row["error"] = msg
        fail_rows.append(row)
    frame["error"] = ""
    if fail_rows:
        frame = pd.concat([frame, pd.DataFrame(fail_rows)], ignore_index=True)
    frame["k"] = frame["k"].astype("Int64")
    frame["chi2_bins"] = frame["chi2_bins"].astype("Int64")
    frame["chi2_dof"] = frame["chi2_dof"].astype("Int64")
    aic = frame["aic"].astype(float)
    frame["aic_rank"] = aic.rank(method="min", na_option="keep").astype("Int64")
    frame["delta_aic"] = aic - aic.min() if aic.notna().any() else math.nan
    frame["ranked_by"] = "AIC"
    frame = frame.sort_values(["aic_rank", "name"], na_position="last", kind="stable").reset_index(drop=True)
    return frame


# ---------------------------------------------------------------------------------------------
# multiple testing
# ---------------------------------------------------------------------------------------------
def _adjusted(p: np.ndarray, method: str, alpha: float) -> np.ndarray:
    """``multipletests`` adjustment of the 1-d ``p`` over its non-NaN entries (NaN stays NaN)."""
    from statsmodels.stats.multitest import multipletests

    out = np.full(p.shape, math.nan)
    ok = ~np.isnan(p)
    if ok.any():
        out[ok] = multipletests(p[ok], alpha=alpha, method=method)[1]
    return out


def _pvalue_array(values, what: str) -> np.ndarray:
    """``values`` (array_like or pandas column, missing values as NaN) as a flat float array of
    p-values; raises unless every non-NaN entry lies in [0, 1]."""
    if hasattr(values, "to_numpy"):
        try:
            values = values.to_numpy(dtype=float, na_value=math.nan)
        except (TypeError, ValueError):
            raise TypeError(f"{what} must be numeric p-values, got dtype {values.dtype}") from None
    try:
        p = _as_float(values)
    except TypeError:
        raise TypeError(f"{what} must be numeric p-values, got {type(values).__name__} of "
                        f"dtype {np.asarray(values).dtype}") from None
    bad = ~np.isnan(p) & ~((p >= 0) & (p <= 1))
    if bad.any():
        raise ValueError(f"{what} must be p-values in [0, 1] (or NaN), got {p[bad][:3].tolist()}")
    return p


def adjust_pvalues(pvalues, method: str = "holm", *, alpha: float = 0.05, columns=None, by=None):
    """P-values adjusted for multiple testing across a family of tests.

    The study runs one goodness-of-fit test per surface parameter (e.g. per Hurst exponent
    H); the chance that at least one of m true models is rejected at level α then grows
    towards 1 − (1 − α)^m. The adjusted p-values, compared with α, keep that family-wise
    error rate (or, for the ``fdr_*`` methods, the false discovery rate) at α. The work is
    done by ``statsmodels.stats.multitest.multipletests``.

    Parameters
    ----------
    pvalues : array_like, pandas.Series or pandas.DataFrame
        The p-values (in [0, 1]; NaN for tests without a p-value). An array (any shape) or a
        Series is one family; in a DataFrame (e.g. :func:`glstat.gof_report` or
        :func:`glstat.compare_families` tables of several samples, concatenated) each
        column in ``columns`` is its own family, or each group of rows of it with ``by``.
    method : str, optional
        A method name of ``multipletests``: ``"holm"`` (default; Holm's step-down
        Bonferroni, valid under any dependence between the tests), ``"bonferroni"``,
        ``"sidak"``, ``"holm-sidak"``, ``"simes-hochberg"``, ``"hommel"``, ``"fdr_bh"``
        (Benjamini–Hochberg), ``"fdr_by"`` (Benjamini–Yekutieli), ``"fdr_tsbh"``,
        ``"fdr_tsbky"`` or any alias statsmodels accepts.
    alpha : float, optional
        Family-wise error rate or false discovery rate, in (0, 1); default 0.05. It changes
        the adjusted p-values only for the two-stage methods ``"fdr_tsbh"`` and
        ``"fdr_tsbky"``.
    columns : str or sequence of str, optional
        DataFrame only: the p-value columns to adjust. Default: every column whose name
        ends in ``"_pvalue"`` (``ks_pvalue``, ``ad_pvalue``, ``cvm_pvalue``, ``chi2_pvalue``
        in the goodness-of-fit tables).
    by : str or sequence of str, optional
        DataFrame only: columns whose values split the rows into separate families (e.g.
        ``by="name"`` for a table with one row per model and sample: each model's tests
        across the samples form one family). Default: all rows form one family.

    Returns
    -------
    ndarray, pandas.Series or pandas.DataFrame
        For an array, the adjusted p-values with its shape; for a Series, a Series with its
        index and name. For a DataFrame, a copy with a column ``<column>_adj`` after each
        adjusted column and a column ``pvalue_adjustment`` holding ``method``; the input is
        not modified. NaN p-values stay NaN and do not count in the family size m.

    Raises
    ------
    ValueError
        A value outside [0, 1], an unknown ``method``, ``alpha`` outside (0, 1), or a
        DataFrame without the requested (or any ``*_pvalue``) column.
    TypeError
        Non-numeric p-values, or ``columns``/``by`` given with an array.

    Notes
    -----
    Holm (1979): with p₍₁₎ ≤ … ≤ p₍ₘ₎ the sorted p-values, the adjusted value of p₍ᵢ₎ is
    max over j ≤ i of min(1, (m − j + 1) p₍ⱼ₎). Testing each adjusted p-value at α
    rejects exactly the hypotheses Holm's step-down procedure rejects.

    Examples
    --------
    >>> from glstat.gof import adjust_pvalues
    >>> adjust_pvalues([0.01, 0.04, 0.03, 0.005]).round(3).tolist()
    [0.03, 0.06, 0.06, 0.02]
    """
    from statsmodels.stats.multitest import multipletests

    alpha = float(alpha)
    if not 0.0 < alpha < 1.0:
        raise ValueError(f"alpha must be in (0, 1), got {alpha!r}")
    try:
        multipletests(np.array([0.5]), alpha=alpha, method=method)
    except ValueError:
        raise ValueError(f"method {method!r} is not a statsmodels multipletests method; use e.g. "
                         "'holm', 'bonferroni', 'holm-sidak', 'hommel', 'fdr_bh' or 'fdr_by'") from None
    if type(pvalues).__module__.startswith("pandas"):
        import pandas as pd

        if isinstance(pvalues, pd.DataFrame):
            return _adjust_frame(pvalues, method, alpha, columns, by)
        if isinstance(pvalues, pd.Series) and columns is None and by is None:
            p = _pvalue_array(pvalues, "pvalues")
            return pd.Series(_adjusted(p, method, alpha), index=pvalues.index, name=pvalues.name)
    if columns is not None or by is not None:
        raise TypeError("columns and by apply to a DataFrame only")
    shape = np.shape(pvalues)
    return _adjusted(_pvalue_array(pvalues, "pvalues"), method, alpha).reshape(shape)


def _adjust_frame(frame, method: str, alpha: float, columns, by):
    if columns is None:
        cols = [c for c in frame.columns if isinstance(c, str) and c.endswith("_pvalue")]
        if not cols:
            raise ValueError("the table has no '*_pvalue' column; name the p-value columns with columns=")
    else:
        cols = [columns] if isinstance(columns, str) else list(columns)
        missing = [c for c in cols if c not in frame.columns]
        if missing:
            raise ValueError(f"the table lacks column(s) {missing}")
    keys = [] if by is None else ([by] if isinstance(by, str) else list(by))
    missing = [c for c in keys if c not in frame.columns]
    if missing:
        raise ValueError(f"the table lacks the by column(s) {missing}")
    if keys:
        families = list(frame.groupby(keys, sort=False, dropna=False).indices.values())
    else:
        families = [np.arange(len(frame))]
    out = frame.copy()
    for col in cols:
        p = _pvalue_array(frame[col], f"column {col!r}")
        adj = np.full(p.shape, math.nan)
        for rows in families:
            adj[rows] = _adjusted(p[rows], method, alpha)
        name = f"{col}_adj"
        if name in out.columns:
            out[name] = adj
        else:
            out.insert(out.columns.get_loc(col) + 1, name, adj)
    out["pvalue_adjustment"] = method
    return out
