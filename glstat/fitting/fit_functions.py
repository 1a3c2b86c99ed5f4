"""Fitting a GLD: every root of the moment, percentile, L-moment and TL-moment equations, ML, MPS,
starship.

The public functions here check their input and return :class:`GLDFit` results; the fit of
a sample is :func:`glstat._fit_engine.sample_fit.fit_sample`, the candidate bookkeeping and
selection are in :mod:`glstat._fit_engine.candidates`, and the numerical work is in the compiled
kernels of :mod:`glstat._fit_engine.kernels` (shape equations and Newton solver) and
:mod:`glstat._fit_engine.likelihood` (data-based objectives).
"""

from __future__ import annotations

import warnings

import numpy as np

from _glstat_runtime.validation import check_sample_scale as _check_sample_scale
from _glstat_runtime.validation import check_trim as _check_trim
from _glstat_runtime.validation import real_values as _real_values

from .._fit_engine import kernels as K
from .._fit_engine import sample_statistics as S
from .._fit_engine.aliases import resolve_method as _resolve_method
from .._fit_engine.aliases import resolve_param as _check_param
from .._fit_engine.candidates import emit_issues as _emit
from .._fit_engine.equations import FAMILY as _FAM
from .._fit_engine.equations import KIND as _KIND
from .._fit_engine.equations import STAT_NAMES as _STAT_NAMES
from .._fit_engine.equations import check_u as _check_u
from .._fit_engine.equations import fit_from_stats
from .._fit_engine.equations import seed_table as _table
from .._fit_engine.sample_fit import fit_sample
from .._fit_engine.tl_kernels import pack_trim as _pack_trim
from ..errors import FitError, FitWarning
from .result import GLDFit, as_gldfit

__all__ = ["fit", "fit_batch", "fit_lmoments", "fit_moments", "fit_percentiles", "fit_tlmoments"]

# ---------------------------------------------------------------------------------------------
# public API: fits from summary statistics
# ---------------------------------------------------------------------------------------------
def fit_moments(mean: float, std: float, skew: float, kurt: float, param: str = "rs", *,
                fisher: bool = False) -> GLDFit:
    """GLD matching four moments: every root of the moment equations.

    Parameters
    ----------
    mean, std : float
        Mean and standard deviation (units of the data).
    skew : float
        Skewness alpha3 = mu3 / mu2^1.5 (dimensionless).
    kurt : float
        Kurtosis alpha4 = mu4 / mu2^2 (Pearson's, 3 for the normal), or the excess
        kurtosis when ``fisher=True`` (dimensionless).
    param : {"rs", "fkml"}
        Parameterisation. RS reaches moments only in regions 3 and 4.
    fisher : bool
        True when ``kurt`` is the excess kurtosis (``scipy.stats.kurtosis`` default).

    Returns
    -------
    GLDFit
        All roots in ``solutions``; the selected one is the valid root with the smallest
        max(|lambda3|, |lambda4|) (no data to compare with).

    Raises
    ------
    FitError
        When the moments are impossible (kurt <= 1 + skew^2) or no GLD of this
        parameterisation matches them; the message names the statistics and what can
        reach them.

    Examples
    --------
    >>> from glstat import GLD, fit_moments
    >>> f = fit_moments(0, 1, 0, 3)          # the normal
    >>> [round(v, 4) for v in f.lambdas]     # (lambda1, lambda2, lambda3, lambda4), R's order
    [0.0, 0.1975, 0.1349, 0.1349]
    >>> f.dist == GLD(*f.lambdas)            # the fitted GLD (gld_rs would take lambda3, lambda4 first)
    True
    >>> round(float(f.dist.ppf(0.975)), 3)  # the normal's own: 1.960
    1.968
    """
    param = _check_param(param)
    kurt = float(kurt) + (3.0 if fisher else 0.0)
    stats = (float(mean), float(std), float(skew), kurt)
    S.check_moment_stats(*stats)
    return as_gldfit(fit_from_stats("moments", param, stats, 0.1, None, None,
                                    dict(zip(_STAT_NAMES["moments"], stats, strict=True)), {}))


def fit_percentiles(rho=None, param: str = "rs", *, quantiles=None, u: float = 0.1) -> GLDFit:
    """GLD matching the Karian–Dudewicz percentile statistics: every root.

    Parameters
    ----------
    rho : sequence of 4 float, optional
        (rho1, rho2, rho3, rho4): median, pi(1-u) - pi(u) (units of the data), the
        left-right tail-weight ratio (pi(.5) - pi(u)) / (pi(1-u) - pi(.5)) and the
        tail-weight factor (pi(.75) - pi(.25)) / rho2 (dimensionless).
    param : {"rs", "fkml"}
        Parameterisation.
    quantiles : sequence of 5 float, optional
        Instead of ``rho``: the quantiles pi(u), pi(1/4), pi(1/2), pi(3/4), pi(1-u).
    u : float
        Percentile probability, 0 < u < 1/4 (Karian & Dudewicz use 0.1).

    Returns
    -------
    GLDFit

    Raises
    ------
    FitError
        Tied or out-of-range statistics, or statistics no GLD of this type matches.
    """
    param = _check_param(param)
    u = _check_u(u)
    if (rho is None) == (quantiles is None):
        raise ValueError("give exactly one of rho=(rho1, rho2, rho3, rho4) or quantiles=(5 values)")
    stats: tuple[float, ...]
    if quantiles is not None:
        q = np.asarray(quantiles, dtype=float)
        if q.shape != (5,):
            raise ValueError("quantiles must hold pi(u), pi(.25), pi(.5), pi(.75), pi(1-u); "
                             f"got shape {q.shape}")
        if np.any(np.diff(q) <= 0):
            raise FitError(f"quantiles must be strictly increasing, got {q.tolist()} (tied quantiles)")
        stats = S.rho_from_quantiles(q)
    else:
        stats = tuple(float(v) for v in rho)
        if len(stats) != 4:
            raise ValueError(f"rho must hold 4 values, got {len(stats)}")
    S.check_rho(*stats)
    return as_gldfit(fit_from_stats("percentiles", param, stats, u, None, None,
                                    dict(zip(_STAT_NAMES["percentiles"], stats, strict=True)),
                                    {"u": u}))


def fit_lmoments(l1: float, l2: float, t3: float, t4: float, param: str = "rs") -> GLDFit:
    """GLD matching the first two L-moments and the L-moment ratios tau3, tau4: every root.

    Parameters
    ----------
    l1, l2 : float
        First two L-moments (units of the data).
    t3, t4 : float
        L-skewness and L-kurtosis (dimensionless).
    param : {"rs", "fkml"}
        Parameterisation.

    Returns
    -------
    GLDFit
    """
    param = _check_param(param)
    stats = (float(l1), float(l2), float(t3), float(t4))
    S.check_lmoment_stats(*stats)
    return as_gldfit(fit_from_stats("lmoments", param, stats, 0.1, None, None,
                                    dict(zip(_STAT_NAMES["lmoments"], stats, strict=True)), {}))


def fit_tlmoments(l1: float, l2: float, t3: float, t4: float, param: str = "rs", *,
                  trim: tuple[int, int] = (1, 1)) -> GLDFit:
    """GLD matching the first two TL-moments and the TL-moment ratios tau3, tau4 with trimming
    ``trim``: every root.

    Parameters
    ----------
    l1, l2 : float
        TL-location and TL-scale, the first two trimmed L-moments (units of the data).
    t3, t4 : float
        TL-skewness l3 / l2 and TL-kurtosis l4 / l2 (dimensionless).
    param : {"rs", "fkml"}
        Parameterisation.
    trim : (int, int)
        Trimming (t1, t2): the numbers of values trimmed from the lower and the upper end of
        the conceptual sample (Elamir & Seheult 2003; R gld's ``t1``, ``t2``). (0, 0) gives
        the L-moments.

    Returns
    -------
    GLDFit
        All roots in ``solutions``; the selected one is the valid root with the smallest
        max(|lambda3|, |lambda4|) (no data to compare with). ``options["trim"]`` holds the
        trimming.

    Raises
    ------
    FitError
        Non-finite statistics, l2 <= 0, or statistics no GLD of this parameterisation
        matches (the message says what would).
    TypeError, ValueError
        ``trim`` is not a pair of non-negative integers.

    Examples
    --------
    >>> from glstat.fitting import fit_tlmoments
    >>> f = fit_tlmoments(0.0, 0.36768, 0.0, 0.044549, param="fkml")  # those of FKML (0, 1, 0.3, 0.3)
    >>> [round(v, 4) for v in f.lambdas]
    [0.0, 1.0, 0.3, 0.3]
    >>> len(f.solutions)                 # a second root with lambda3 = lambda4 = 3.2
    2
    """
    param = _check_param(param)
    t1, t2 = _check_trim(trim)
    stats = (float(l1), float(l2), float(t3), float(t4))
    S.check_tlmoment_stats(*stats)
    return as_gldfit(fit_from_stats("tlmoments", param, stats, _pack_trim(t1, t2), None, None,
                                    dict(zip(_STAT_NAMES["tlmoments"], stats, strict=True)),
                                    {"trim": (t1, t2)}))


def fit_batch(stats, method: str = "moments", param: str = "rs", *, u: float = 0.1,
              ref=None, extremes=None, require_cover: bool = True,
              return_cover: bool = False, trim: tuple[int, int] = (1, 1)) -> tuple[np.ndarray, ...]:
    """Fits for many rows of statistics in one compiled call (the bootstrap core).

    Parameters
    ----------
    stats : array_like, shape (B, 4)
        One row per resample: (mean, std, skew, kurt) for ``"moments"`` (Pearson kurtosis),
        (rho1, rho2, rho3, rho4) for ``"percentiles"``, (l1, l2, t3, t4) for ``"lmoments"``,
        (tl1, tl2, tt3, tt4) for ``"tlmoments"``.
    method : {"moments", "percentiles", "lmoments", "tlmoments"}
    param : {"rs", "fkml"}
    u : float
        Percentile probability.
    ref : (float, float), optional
        Reference shapes (lambda3, lambda4), typically those of the full-sample fit: of
        several roots the one closest to ``ref`` is kept. Default: the shapes of the
        normal-like root (0.1349, 0.1349).
    extremes : array_like, shape (B, 2), optional
        Each row's data minimum and maximum. Roots whose support covers [min, max] come
        first (the rule of the full-sample fit: valid, covering, then nearest to ``ref``).
        A NaN row of ``extremes`` sets no constraint.
    require_cover : bool
        With ``extremes``: a row without a covering root gets NaN lambdas (although its
        ``n_roots`` may be positive) when True, the nearest valid root when False.
    return_cover : bool
        Also return the number of covering roots per row.
    trim : (int, int)
        Trimming (t1, t2) of ``"tlmoments"``.

    Returns
    -------
    lambdas : ndarray, shape (B, 4)
        lambda1..lambda4 per row; NaN where no valid (covering, if required) root exists.
    n_roots : ndarray of int, shape (B,)
        Number of valid roots per row (0 = no fit), covering or not.
    n_cover : ndarray of int, shape (B,)
        Only with ``return_cover``: number of valid roots covering the row's extremes
        (equal to ``n_roots`` without ``extremes``).
    """
    param = _check_param(param)
    method = _resolve_method(method)
    if method not in _KIND:
        raise ValueError(f"fit_batch supports {tuple(_KIND)}, got {method!r}")
    u = _check_u(u)
    kind = _KIND[method]
    if kind == K.TLMOMENTS:
        u = _pack_trim(*_check_trim(trim))
    st = np.array(stats, dtype=float, copy=True, ndmin=2)
    if st.ndim != 2 or st.shape[1] != 4:
        raise ValueError(f"stats must have shape (B, 4), got {np.shape(stats)}")
    if extremes is None:
        ext = np.full((st.shape[0], 2), np.nan)
    else:
        ext = np.array(extremes, dtype=float, copy=True, ndmin=2)
        if ext.shape != (st.shape[0], 2):
            raise ValueError(f"extremes must have shape ({st.shape[0]}, 2), got {np.shape(extremes)}")
    with np.errstate(invalid="ignore", divide="ignore"):
        if kind == K.MOMENTS:
            st[:, 3] = np.log(st[:, 3] - st[:, 2] ** 2 - 1.0)
        elif kind == K.PERCENTILES:
            st[:, 2] = np.log(st[:, 2])
    st[~np.isfinite(st)] = np.nan
    nodes, t1, t2, lim = _table(kind, _FAM[param], u)
    r = np.array([0.134912, 0.134912] if ref is None else ref, dtype=float)
    out = np.empty((st.shape[0], 4))
    status = np.zeros(st.shape[0], dtype=np.int64)
    ncover = np.zeros(st.shape[0], dtype=np.int64)
    K.fit_many(kind, _FAM[param], st, u, nodes, t1, t2, lim, r, ext, bool(require_cover), out, status,
               ncover)
    if return_cover:
        return out, status, ncover
    return out, status


# ---------------------------------------------------------------------------------------------
# public API: fit to data
# ---------------------------------------------------------------------------------------------
def fit(data, param: str = "rs", method: str = "moments", nan_policy: str = "raise", *,
        warn: bool = True, **options) -> GLDFit:
    """Fit a GLD to data.

    Parameters
    ----------
    data : array_like or scipy.stats.CensoredData
        Sample (any shape; flattened, never modified; a table of several columns or rows is
        fitted as one sample with a :class:`FitWarning`). Units: those of the data. Censored
        data are fitted by ``method="mle"`` only: the likelihood sums logpdf over the exact
        values, logcdf over the left-censored, logsf over the right-censored and
        log(F(high) - F(low)) over the intervals (Nelder–Mead from the uncensored ML fit;
        options ``maxiter``, ``starts``; no KS distance or poor-fit warning, which
        censoring makes meaningless). ``statistics`` then also counts each kind of value.
    param : {"rs", "fkml"}
        Parameterisation; R's spelling ``"fmkl"`` is accepted (any case).
    method : {"moments", "percentiles", "lmoments", "tlmoments", "mle", "mps", "starship"}
        R's names are accepted in any case: ``"ML"`` (``"mle"``), ``"MPS"``/``"MSP"``,
        ``"SM"`` (``"starship"``), ``"Lmom"``/``"LM"`` (``"lmoments"``), ``"TL"``
        (``"tlmoments"``), ``"Mom"`` and scipy's ``"MM"`` (``"moments"``); R's ``"TM"``,
        ``"DLA"`` raise ``ValueError`` naming the closest glstat method (docs/fitting.md).
        ``"moments"``: match mean, variance, skewness, kurtosis (divisor n). ``"percentiles"``:
        Karian–Dudewicz rho statistics at ``u`` (option, default 0.1; sample quantile at
        (n+1)p). ``"lmoments"``: unbiased sample L-moments. ``"tlmoments"``: unbiased
        sample trimmed L-moments (Elamir & Seheult 2003) with trimming ``trim`` (option,
        default (1, 1); R's ``t1``, ``t2``, whose default in R is (0, 0)). ``"mle"``: maximum likelihood;
        ``"mps"``: maximum product of spacings; ``"starship"``: minimum Anderson–Darling
        statistic of the probability integral transform. The last three start from the
        percentile and L-moment fits and from generic shapes, are refined by a compiled
        BFGS with analytic gradients and keep the support covering the data.
    nan_policy : {"raise", "omit", "propagate"}
        Non-finite values (NaN, inf): raise ``ValueError``, drop them, or return a NaN fit.
    warn : bool
        Emit the fit's issues (poor fit, optimiser limit) as warnings (default). With
        ``False`` nothing is warned and the issues are only returned in ``GLDFit.issues``:
        use it in worker threads and loops, which should not touch the process-wide warning
        filters, and warn once with the aggregated issues in the calling thread.
    **options
        ``u`` (percentiles); ``trim`` (tlmoments); for the data-based methods ``starts`` (number of distinct
        starting points refined, default 2), ``maxiter`` (iterations per start; default 500
        for BFGS, 2000 for Nelder–Mead), ``optimizer`` (``"bfgs"``, default, or
        ``"nelder-mead"``) and ``start``, a guess (lambda1, lambda2, lambda3, lambda4) used
        as one more starting point: refined after the usual starts unless its shapes lie
        within their basins, so the result is never worse than without it.

    Returns
    -------
    GLDFit
        Selection rule: valid lambdas; support covering the data; then, for the equation
        methods, the smallest Kolmogorov–Smirnov distance among the roots, and for the
        data-based methods the best objective among the refined candidates: the highest
        likelihood (``"mle"``), the largest mean log spacing (``"mps"``), the smallest
        Anderson–Darling statistic (``"starship"``). Every root or candidate stays in
        ``solutions``. The selected distribution is ``fit.dist`` (a :class:`glstat.GLD`,
        lambdas in R's order); ``gld_rs``/``gld_fkml`` take ``(lambda3, lambda4, loc=lambda1,
        scale=1/|lambda2|)`` instead.

    Warns
    -----
    FitWarning
        The selected fit's support does not cover the data, or its Kolmogorov–Smirnov
        distance exceeds the asymptotic 1 % critical value 1.63/sqrt(n). The message names
        both and what to try instead; for the data-based methods also a candidate with a
        smaller KS distance, and a value repeated so often that no continuous distribution
        fits it (e.g. the zeros of contact pressures).
    ConvergenceWarning
        A data-based fit whose optimiser stopped at ``maxiter``.

    Raises
    ------
    FitError
        Fewer than 5 finite points, constant data, tied quantiles, or statistics out of
        reach (the message says which method or parameterisation reaches them).
    ValueError
        Unknown ``method``, ``param``, ``nan_policy`` or option, non-finite data with
        ``nan_policy="raise"``, or data beyond the range the fits compute with: a magnitude
        above 1e300 (powers overflow) or only subnormal values (below 2.2e-308); the message
        says how to rescale the data and the lambdas.
    TypeError
        Data that are not real numbers (complex, dates, booleans, text, also in object
        arrays and pandas Series of text, ``None``, ``pandas.NA``).

    Examples
    --------
    >>> import numpy as np, glstat
    >>> x = np.random.default_rng(1).gamma(5.0, 3.0, size=2000)
    >>> f = glstat.fit(x, "fkml", "mle")
    >>> d = f.dist                      # the fitted GLD, same as glstat.GLD(*f.lambdas, param="fkml")
    >>> round(float(d.ppf(0.99)), 1)    # the gamma's own 99 % quantile is 34.8
    35.5
    >>> f.issues                        # nothing to warn about
    ()
    """
    _check_values(data)
    f = as_gldfit(fit_sample(data, param, method, nan_policy, **options))
    if warn:
        _warn_if_table(data)
        _emit(f.issues, stacklevel=2)
    return f


def _check_values(data) -> None:
    """Refuse, before any work, data that are not real numbers (the messages of
    :func:`_glstat_runtime.validation.real_values`) or whose finite values lie beyond the
    range the fits compute with (:func:`_glstat_runtime.validation.check_sample_scale`)."""
    from scipy.stats import CensoredData

    if isinstance(data, CensoredData):
        return
    values, keep = _real_values(data)
    finite = np.isfinite(values)
    _check_sample_scale(values[finite if keep is None else finite & keep])


def _warn_if_table(data) -> None:
    """Say so when ``data`` has more than one axis longer than 1 (a table of columns is more
    likely several quantities than one sample)."""
    from scipy.stats import CensoredData

    if isinstance(data, CensoredData):
        return
    shape = np.shape(data)
    if sum(n > 1 for n in shape) > 1:
        warnings.warn(f"data of shape {shape} were fitted as one sample of {int(np.prod(shape))} "
                      "values; pass one column (data[:, j]) if the columns are different "
                      "quantities, or data.ravel() to fit them as one sample without this warning",
                      FitWarning, stacklevel=3)
