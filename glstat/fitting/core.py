"""Fitting a GLD: every root of the moment, percentile and L-moment equations, ML, MPS, starship.

The public functions here handle input checking, candidate bookkeeping and selection; the
numerical work is in the compiled kernels of :mod:`glstat.fitting._kernels` (shape equations
and Newton solver) and :mod:`glstat.fitting._likelihood` (data-based objectives).
"""

from __future__ import annotations

import logging
import math
import textwrap
import warnings
from dataclasses import dataclass, field
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .._core import _gld
from ..errors import FitError, FitWarning
from ..gld import GLD
from ..regions import rs_region
from . import _kernels as K
from . import _stats as S
from ._eval import gld_evaluate, gld_support, lambdas_valid

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["FitIssue", "GLDFit", "fit", "fit_batch", "fit_lmoments", "fit_moments", "fit_percentiles"]

logger = logging.getLogger(__name__)

METHODS = ("moments", "percentiles", "lmoments", "mle", "mps", "starship")
_KIND = {"moments": K.MOMENTS, "percentiles": K.PERCENTILES, "lmoments": K.LMOMENTS}
_FAM = {"rs": _gld.RS, "fkml": _gld.FKML}
_STAT_NAMES = {
    "moments": ("mean", "std", "skew", "kurt"),
    "percentiles": ("rho1", "rho2", "rho3", "rho4"),
    "lmoments": ("l1", "l2", "t3", "t4"),
}


# ---------------------------------------------------------------------------------------------
# result
# ---------------------------------------------------------------------------------------------
class FitIssue(NamedTuple):
    """A warning of a fit: what :func:`fit` warns, or with ``warn=False`` would have warned.

    Attributes
    ----------
    category : type
        The warning class (:class:`glstat.FitWarning`, :class:`glstat.ConvergenceWarning`).
    message : str
        The warning text, with the figures behind it.
    """

    category: type
    message: str


@dataclass(frozen=True)
class GLDFit:
    """Result of a GLD fit.

    The selected distribution is ``fit.dist``, a :class:`glstat.GLD` in the lambda (R)
    order; to rebuild it from ``lambdas`` write ``glstat.GLD(*fit.lambdas, param=fit.param)``.
    Do not pass ``lambdas`` to ``gld_rs``/``gld_fkml``: scipy's order is
    ``(lambda3, lambda4, loc=lambda1, scale=1/|lambda2|)``.

    Attributes
    ----------
    lambdas : tuple of float
        Selected (lambda1, lambda2, lambda3, lambda4), in the units of the data for lambda1
        and of 1/data for lambda2; NaN when ``nan_policy="propagate"`` met a NaN.
    param : str
        ``"rs"`` or ``"fkml"``.
    method : str
        Fitting method.
    n : int or None
        Number of data points used (None for a fit from summary statistics).
    statistics : dict
        The matched sample statistics (moments, rho, L-moments) or, for the data-based
        methods, the value of the objective at the optimum.
    options : dict
        Options the fit used (e.g. ``u`` for percentiles).
    issues : tuple of FitIssue
        The warnings of the fit (category and message): empty for a fit that covers the
        data with a Kolmogorov–Smirnov distance within the 1 % critical value and converged.
        :func:`fit` also emits them unless called with ``warn=False``.
    dist : GLD or None
        The selected frozen distribution (None for a NaN fit); built on first access.
    solutions : pandas.DataFrame
        Every root or candidate found: ``lambda1..lambda4``, ``region`` (RS), ``valid``,
        ``converged``, ``objective`` (residual of the equations or value of the objective),
        ``covers_data``, ``ks`` (Kolmogorov–Smirnov distance to the data), ``selected``;
        built on first access.
    """

    lambdas: tuple[float, float, float, float]
    param: str
    method: str
    n: int | None
    statistics: dict[str, float]
    options: dict[str, Any] = field(default_factory=dict)
    issues: tuple[FitIssue, ...] = ()
    _candidates: tuple[dict, ...] = field(default=(), repr=False, compare=False)

    @cached_property
    def dist(self) -> GLD | None:
        """The selected distribution, ``GLD(*lambdas, param=param)`` (None for a NaN fit)."""
        if not all(math.isfinite(v) for v in self.lambdas):
            return None
        return GLD(*self.lambdas, param=self.param)

    @cached_property
    def solutions(self) -> pd.DataFrame:
        """Every root or candidate as a table (see the class description)."""
        return _frame(self._candidates, self.param)

    @property
    def n_valid(self) -> int:
        """Number of valid roots or candidates (a distribution each), without building
        ``solutions``."""
        return sum(bool(r["valid"]) for r in self._candidates)

    @property
    def region(self) -> int | None:
        """RS region of the selected fit (None for FKML or a NaN fit)."""
        if self.param != "rs" or not all(math.isfinite(v) for v in self.lambdas):
            return None
        return int(rs_region(self.lambdas[2], self.lambdas[3]))

    def to_frame(self) -> pd.DataFrame:
        """Every candidate as a tidy table (a copy of ``solutions``)."""
        return self.solutions.copy()

    def summary(self) -> pd.DataFrame:
        """One-row table: method, parameterisation, n, selected lambdas, matched statistics.

        ``print(fit)`` shows the fit as a text block in the style of a statsmodels summary:
        method, parameterisation, n, the objective at the optimum (the log-likelihood for
        ``"mle"``), Kolmogorov–Smirnov distance, support, RS region, the lambdas, the
        matched statistics and the fit's warnings.
        """
        import pandas as pd

        row: dict[str, Any] = {"method": self.method, "param": self.param, "n": self.n}
        for i, v in enumerate(self.lambdas, start=1):
            row[f"lambda{i}"] = v
        row["region"] = self.region
        row["n_solutions"] = len(self._candidates)
        row.update(self.statistics)
        return pd.DataFrame([row])

    def __repr__(self) -> str:
        l1, l2, l3, l4 = self.lambdas
        return (f"GLDFit(method={self.method!r}, param={self.param!r}, lambdas=({l1:.6g}, {l2:.6g}, "
                f"{l3:.6g}, {l4:.6g}), n={self.n}, solutions={len(self._candidates)})")

    def __str__(self) -> str:
        return _summary_text(self)


_TEXT_WIDTH = 78
# (label, sign) of the objective of the data-based methods in the text summary
_OBJECTIVE_TEXT = {"neg_loglik": ("Log-likelihood", -1.0), "neg_mean_log_spacing": ("Mean log spacing", -1.0),
                   "anderson_darling": ("Anderson-Darling A2", 1.0)}


def _summary_text(f: GLDFit) -> str:
    """The fit as a statsmodels-style text block (``print(fit)``)."""

    def num(v) -> str:
        return "n/a" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.6g}"

    sel = next((r for r in f._candidates if r["selected"]), None)
    ok = f.dist is not None
    if ok:
        lo, hi = gld_support(f.param, f.lambdas)
        support = f"[{lo:.6g}, {hi:.6g}]"
    else:
        support = "n/a"
    covers = None if sel is None else sel["covers_data"]
    left = [("Method:", f.method), ("Parameterisation:", f.param.upper()),
            ("No. observations:", "n/a" if f.n is None else str(f.n))]
    right = [("RS region:", "n/a" if f.region is None else str(f.region)),
             ("KS distance:", num(None if sel is None else sel["ks"])),
             ("Covers the data:", "n/a" if covers is None else ("yes" if covers else "no"))]
    for key, (label, sign) in _OBJECTIVE_TEXT.items():
        if key in f.statistics:
            left.append((f"{label}:", num(sign * f.statistics[key])))
    right.append(("Candidates (valid):", f"{len(f._candidates)} ({f.n_valid})"))
    while len(left) < len(right):
        left.append(("", ""))
    while len(right) < len(left):
        right.append(("", ""))
    half = _TEXT_WIDTH // 2
    rule, thin = "=" * _TEXT_WIDTH, "-" * _TEXT_WIDTH
    lines = ["GLD fit results".center(_TEXT_WIDTH).rstrip(), rule]
    for (a, b), (c, d) in zip(left, right, strict=True):
        lines.append(f"{a:<20}{b:>{half - 22}}  " + f"  {c:<20}{d:>{half - 22}}".rstrip())
    lines.append(f"{'Support:':<20}{support:>{_TEXT_WIDTH - 20}}")
    lines += [rule, f"{'':<12}{'value':>16}", thin]
    for i, v in enumerate(f.lambdas, start=1):
        lines.append(f"{f'lambda{i}':<12}{num(v):>16}")
    lines.append(rule)
    matched = [k for k in f.statistics if k not in _OBJECTIVE_TEXT]
    if matched:
        lines.append(textwrap.fill("Matched statistics: " + ", ".join(f"{k} = {num(f.statistics[k])}"
                                                                       for k in matched),
                                   _TEXT_WIDTH, subsequent_indent="    "))
    if f.options:
        lines.append(textwrap.fill("Options: " + ", ".join(f"{k}={v!r}" for k, v in f.options.items()),
                                   _TEXT_WIDTH, subsequent_indent="    "))
    if not ok:
        lines.append("No fit: the lambdas are NaN (nan_policy='propagate' met a non-finite value).")
    notes = ["lambda1 in data units, lambda2 in 1/(data unit), lambda3 and lambda4 dimensionless, "
             "in R's order: glstat.GLD(*fit.lambdas, param=fit.param) is the distribution.",
             "Standard errors are not part of a fit; glstat.bootstrap(data, ...).summary() gives "
             "bootstrap standard errors and intervals."]
    notes += [f"{issue.category.__name__}: {issue.message}" for issue in f.issues]
    lines.append("")
    lines.append("Notes:")
    lines += [textwrap.fill(f"[{k}] {note}", _TEXT_WIDTH, subsequent_indent="    ", break_long_words=False,
                            break_on_hyphens=False) for k, note in enumerate(notes, start=1)]
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------------------------
def _check_param(param: str) -> str:
    p = str(param).lower()
    if p not in _FAM:
        raise ValueError(f"param must be 'rs' or 'fkml', got {param!r}")
    return p


@lru_cache(maxsize=32)
def _table(kind: int, fam: int, u: float) -> tuple[np.ndarray, ...]:
    """Seed tables of the statistics of ``kind`` (computed once).

    Returns the shape grid, the two statistics on it, and the lambda -> 0 limit table of
    :func:`glstat.fitting._kernels.build_limit_table`.
    """
    logger.debug("building the %s seed table of the %s statistics (u=%g)",
                 "RS" if fam == _gld.RS else "FKML", {k: m for m, k in _KIND.items()}.get(kind), u)
    nodes = K.grid_nodes(kind)
    t1 = np.empty((nodes.size, nodes.size))
    t2 = np.empty_like(t1)
    K.build_table(kind, fam, u, nodes, t1, t2)
    lim = np.empty((K.NPHI, 4))
    K.build_limit_table(kind, fam, u, lim)
    for arr in (nodes, t1, t2, lim):
        arr.setflags(write=False)
    return nodes, t1, t2, lim


def _check_u(u: float) -> float:
    u = float(u)
    if not 0.0 < u < 0.25:
        raise ValueError(f"u must be in (0, 0.25) so that u < 1/4 < 3/4 < 1 - u, got {u!r}")
    return u


def ks_distance(dist, x: np.ndarray) -> float:
    """Kolmogorov–Smirnov distance between a GLD and the sorted sample ``x``.

    ``dist`` is a :class:`glstat.GLD` or ``(param, lambdas)``. Never warns (safe in worker
    threads): points where the inversion of Q reached its limit enter with its best estimate.
    """
    param, lams = (dist.param, dist.lambdas) if isinstance(dist, GLD) else dist
    f, _ = gld_evaluate(param, "cdf", x, lams)
    n = x.size
    i = np.arange(1, n + 1)
    return float(max(np.max(i / n - f), np.max(f - (i - 1) / n)))


def covers(dist, x: np.ndarray) -> bool:
    """True when the support of the GLD ``dist`` (or ``(param, lambdas)``) contains every
    point of the sorted sample ``x``."""
    param, lams = (dist.param, dist.lambdas) if isinstance(dist, GLD) else dist
    lo, hi = gld_support(param, lams)
    return bool(lo <= x[0] and hi >= x[-1])


def _candidate(lams, param, converged, objective, x) -> dict:
    """One candidate: its lambdas, validity, and with data its cover and KS distance."""
    lams = tuple(float(v) for v in lams)
    row = {"lambdas": lams, "valid": lambdas_valid(param, lams), "converged": bool(converged),
           "objective": float(objective), "covers_data": None, "ks": math.nan, "selected": False}
    if x is not None and row["valid"]:
        row["covers_data"] = covers((param, lams), x)
        row["ks"] = ks_distance((param, lams), x)
    return row


def _select(rows: list[dict], have_data: bool, by_objective: bool = False) -> int:
    """Index of the selected candidate (the documented rule), -1 when none qualifies.

    Valid and converged first; with data, a support that covers the data; then the smallest
    KS distance (data) or objective (``by_objective``); without data, the root with the
    least extreme shapes, the smallest max(|lambda3|, |lambda4|).
    """
    best = -1
    best_key: tuple = ()
    key: tuple[float, ...]
    for i, r in enumerate(rows):
        if not (r["valid"] and r["converged"]):
            continue
        if have_data:
            key = (0 if r["covers_data"] else 1,
                   r["objective"] if by_objective else r["ks"], r["objective"])
        else:
            key = (max(abs(r["lambdas"][2]), abs(r["lambdas"][3])), r["objective"])
        if best < 0 or key < best_key:
            best, best_key = i, key
    return best


_COLUMNS = ["lambda1", "lambda2", "lambda3", "lambda4", "region", "valid", "converged", "objective",
            "covers_data", "ks", "selected"]


def _frame(rows, param: str):
    import pandas as pd

    lam = np.array([r["lambdas"] for r in rows], dtype=float).reshape(-1, 4)
    if param == "rs" and len(rows):
        region = np.asarray(rs_region(lam[:, 2], lam[:, 3]), dtype=int)
    else:
        region = np.zeros(len(rows), dtype=int)
    data: dict[str, np.ndarray | list[Any]] = {f"lambda{i + 1}": lam[:, i] for i in range(4)}
    data["region"] = region
    for c in _COLUMNS[5:]:
        data[c] = [r[c] for r in rows]
    return pd.DataFrame(data, columns=_COLUMNS)


def _make_fit(rows, sel, param, method, n, statistics, options, issues=()) -> GLDFit:
    if sel >= 0:
        rows[sel]["selected"] = True
        lams = rows[sel]["lambdas"]
    else:
        lams = (math.nan,) * 4
    l1, l2, l3, l4 = (float(v) for v in lams)
    return GLDFit(lambdas=(l1, l2, l3, l4), param=param, method=method, n=n,
                  statistics=statistics, options=options, issues=tuple(issues),
                  _candidates=tuple(rows))


def _nan_fit(param, method, n, options) -> GLDFit:
    return GLDFit(lambdas=(math.nan,) * 4, param=param, method=method, n=n, statistics={},
                  options=options)


def _emit(issues, stacklevel: int) -> None:
    """Warn every issue (in the calling thread)."""
    for issue in issues:
        warnings.warn(issue.message, issue.category, stacklevel=stacklevel + 1)


def _roots(method: str, param: str, stats, u: float) -> list[tuple]:
    """Every root of the shape equations: list of (lambdas, converged, residual)."""
    kind = _KIND[method]
    fam = _FAM[param]
    loc, scale, s1, s2 = S.shape_targets(kind, stats)
    nodes, t1, t2, lim = _table(kind, fam, u)
    out = np.empty((K.MAXROOTS, K.NCOL))
    nr = K.solve_shape(kind, fam, s1, s2, u, nodes, t1, t2, lim, out)
    res = []
    for k in range(nr):
        a, b = out[k, K.R_A], out[k, K.R_B]
        conv = bool(out[k, K.R_CONV]) and bool(K.shape_valid(fam, a, b))
        if conv or K.shape_valid(fam, a, b):
            l1, l2 = K.location_scale(kind, fam, a, b, loc, scale, u)
        else:
            l1, l2 = math.nan, math.nan
        res.append(((l1, l2, a, b), conv, out[k, K.R_RES]))
    return res


def _reach_message(method: str, param: str, stats, u: float) -> str:
    names = _STAT_NAMES[method]
    desc = ", ".join(f"{nm}={float(v):.6g}" for nm, v in zip(names[2:], stats[2:], strict=True))
    other = "fkml" if param == "rs" else "rs"
    alt = []
    try:
        if any(c for _, c, _ in _roots(method, other, stats, u)):
            alt.append(f"param='{other}' with method='{method}' reaches them")
    except (FloatingPointError, ValueError, ZeroDivisionError):
        pass
    hint = {
        "moments": "method='percentiles' or 'lmoments' (which need no 3rd or 4th moment) or a "
                   "data-based method ('mle', 'mps', 'starship')",
        "percentiles": "method='lmoments' or a data-based method ('mle', 'mps', 'starship')",
        "lmoments": "method='percentiles' or a data-based method ('mle', 'mps', 'starship')",
    }[method]
    where = ""
    if method == "moments" and param == "rs":
        where = " (RS has a 4th moment only in regions 3 and 4)"
    msg = (f"no {param.upper()} GLD matches the {method} statistics {desc}{where}. ")
    if alt:
        msg += alt[0] + "; "
    return msg + "other options: " + hint


# asymptotic 1 % critical value of the Kolmogorov–Smirnov distance times sqrt(n)
_KS_CRIT_1PCT = math.sqrt(-0.5 * math.log(0.005))
_DATA_METHODS = ("mle", "mps", "starship")
_CRITERION = {"mle": "highest likelihood", "mps": "largest mean log spacing",
              "starship": "smallest Anderson–Darling statistic"}


def _largest_atom(x: np.ndarray) -> tuple[float, int]:
    """The most repeated value of the sorted sample ``x`` and its count."""
    edges = np.flatnonzero(np.diff(x)) + 1
    starts = np.concatenate(([0], edges))
    counts = np.diff(np.concatenate((starts, [x.size])))
    j = int(np.argmax(counts))
    return float(x[starts[j]]), int(counts[j])


def _poor_fit_issue(rows, param: str, method: str, x: np.ndarray) -> FitIssue | None:
    """The ``FitWarning`` issue of a fit of the data ``x`` whose selected candidate does not
    cover them or whose KS distance exceeds the asymptotic 1 % critical value (None when it
    fits). The message gives the figures: KS distance and critical value, cover, for the
    data-based methods the candidate with the smallest KS distance when it is another one,
    and a value repeated so often that no continuous distribution can fit it."""
    sel = next((r for r in rows if r["selected"]), None)
    if sel is None:
        return None
    n = x.size
    ks = float(sel["ks"])
    crit = _KS_CRIT_1PCT / math.sqrt(n)
    covered = bool(sel["covers_data"])
    if covered and not ks > crit:
        return None
    _, _, l3, l4 = sel["lambdas"]
    other = "fkml" if param == "rs" else "rs"
    msg = (f"{method} fit ({param.upper()}, lambda3={l3:.4g}, lambda4={l4:.4g}) describes the data "
           f"poorly: KS distance {ks:.3g} (1 % critical value {crit:.3g}), support "
           f"{'covers' if covered else 'does not cover'} the data")
    if method in _DATA_METHODS:
        alt = [r for r in rows if r is not sel and r["valid"] and r["covers_data"] and r["ks"] < 0.9 * ks]
        if alt:
            best = min(alt, key=lambda r: r["ks"])
            name = {"mle": "log-likelihood", "mps": "mean log spacing", "starship": "A²"}[method]
            sign = 1.0 if method == "starship" else -1.0
            msg += (f"; it has the {_CRITERION[method]} of the {len(rows)} candidates ({name} "
                    f"{sign * sel['objective']:.6g}), another candidate (lambda3="
                    f"{best['lambdas'][2]:.4g}, lambda4={best['lambdas'][3]:.4g}) has KS "
                    f"{best['ks']:.3g} at {name} {sign * best['objective']:.6g}")
    value, count = _largest_atom(x)
    if count > 1 and count / (2.0 * n) > crit:
        msg += (f"; {count} of the {n} data ({100.0 * count / n:.3g} %) equal {value:.6g}: no "
                f"continuous distribution fits such an atom (its KS distance is at least "
                f"{count / (2.0 * n):.3g}), so fit the other values and the share of {value:.6g} "
                "separately")
    elif method in _DATA_METHODS:
        others = " or ".join(f"'{m}'" for m in _DATA_METHODS if m != method)
        msg += (f"; try param='{other}', method={others}, or an equation method ('percentiles', "
                "'lmoments')")
    else:
        others = " or ".join(f"'{m}'" for m in ("percentiles", "lmoments") if m != method)
        msg += (f"; try param='{other}', method={others}, or a data-based method ('mle', 'mps', "
                "'starship')")
    return FitIssue(FitWarning, msg)


def _fit_from_stats(method, param, stats, u, x, n, statistics, options) -> GLDFit:
    roots = _roots(method, param, stats, u)
    rows = [_candidate(lams, param, conv, res, x) for lams, conv, res in roots]
    sel = _select(rows, x is not None)
    if sel < 0:
        raise FitError(_reach_message(method, param, stats, u))
    return _make_fit(rows, sel, param, method, n, statistics, options)


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
    return _fit_from_stats("moments", param, stats, 0.1, None, None,
                           dict(zip(_STAT_NAMES["moments"], stats, strict=True)), {})


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
    return _fit_from_stats("percentiles", param, stats, u, None, None,
                           dict(zip(_STAT_NAMES["percentiles"], stats, strict=True)), {"u": u})


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
    return _fit_from_stats("lmoments", param, stats, 0.1, None, None,
                           dict(zip(_STAT_NAMES["lmoments"], stats, strict=True)), {})


def fit_batch(stats, method: str = "moments", param: str = "rs", *, u: float = 0.1,
              ref=None, extremes=None, require_cover: bool = True,
              return_cover: bool = False) -> tuple[np.ndarray, ...]:
    """Fits for many rows of statistics in one compiled call (the bootstrap core).

    Parameters
    ----------
    stats : array_like, shape (B, 4)
        One row per resample: (mean, std, skew, kurt) for ``"moments"`` (Pearson kurtosis),
        (rho1, rho2, rho3, rho4) for ``"percentiles"``, (l1, l2, t3, t4) for ``"lmoments"``.
    method : {"moments", "percentiles", "lmoments"}
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
    if method not in _KIND:
        raise ValueError(f"fit_batch supports {tuple(_KIND)}, got {method!r}")
    u = _check_u(u)
    kind = _KIND[method]
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
    data : array_like
        Sample (any shape; flattened, never modified). Units: those of the data.
    param : {"rs", "fkml"}
        Parameterisation.
    method : {"moments", "percentiles", "lmoments", "mle", "mps", "starship"}
        ``"moments"``: match mean, variance, skewness, kurtosis (divisor n). ``"percentiles"``:
        Karian–Dudewicz rho statistics at ``u`` (option, default 0.1; sample quantile at
        (n+1)p). ``"lmoments"``: unbiased sample L-moments. ``"mle"``: maximum likelihood;
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
        ``u`` (percentiles); for the data-based methods ``starts`` (number of distinct
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
        Unknown ``method``, ``param``, ``nan_policy`` or option, or non-finite data with
        ``nan_policy="raise"``.

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
    param = _check_param(param)
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    allowed = {"u"} if method == "percentiles" else set()
    if method in _DATA_METHODS:
        allowed = {"maxiter", "starts", "optimizer", "start"}
    unknown = set(options) - allowed
    if unknown:
        raise ValueError(f"unknown option(s) {sorted(unknown)} for method {method!r}; "
                         f"allowed: {sorted(allowed) or 'none'}")
    x, _ = S.prepare_data(data, nan_policy)
    if x is None:
        return _nan_fit(param, method, None, dict(options))
    n = x.size
    if method in _DATA_METHODS:
        from ._data import fit_data_objective

        f = fit_data_objective(x, param, method, **options)
    else:
        u = 0.1
        if method == "moments":
            stats = S.sample_moments(x)
        elif method == "percentiles":
            u = _check_u(options.get("u", 0.1))
            stats = S.sample_rho(x, u)
            S.check_rho(*stats)
        else:
            stats = S.sample_lmoments(x)
            S.check_lmoment_stats(*stats)
        f = _fit_from_stats(method, param, stats, u, x, n,
                            dict(zip(_STAT_NAMES[method], stats, strict=True)),
                            {"u": u} if method == "percentiles" else {})
    logger.debug("fit %s %s of n=%d: %d candidate(s), %d valid; selected lambdas %s", param, method, n,
                 len(f._candidates), f.n_valid, f.lambdas)
    issue = _poor_fit_issue(f._candidates, param, method, x)
    if issue is not None:
        object.__setattr__(f, "issues", (issue, *f.issues))
    if warn:
        _emit(f.issues, stacklevel=2)
    return f
