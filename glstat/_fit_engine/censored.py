"""Maximum likelihood of censored data (:class:`scipy.stats.CensoredData`) for :func:`glstat.fit`.

The log-likelihood sums ``logpdf`` over the exact observations, ``logcdf`` over the
left-censored ones (the value lies below the bound), ``logsf`` over the right-censored ones
(above the bound) and ``log(F(high) - F(low))`` over the intervals, all from the GLD's
tail-accurate kernels. It starts from the uncensored ML fit of all values (bounds and interval
midpoints taken as observations, scipy's ``_uncensor``) and is maximised by Nelder–Mead in
theta = (lambda1, log scale, lambda3, lambda4) of the data scaled by median and interquartile
range.
"""

from __future__ import annotations

import math

import numpy as np

from .._core.quantile_function import FKML, RS
from ..errors import ConvergenceWarning, FitError
from . import kernels as K
from . import likelihood as L
from .candidates import FitIssue, FitRecord, candidate, make_record, select_candidate
from .data_fits import fit_data_objective, std_theta, to_lambdas
from .evaluate import gld_evaluate

__all__ = ["CensoredParts", "censored_parts", "fit_censored", "is_censored"]

_ALLOWED = {"maxiter", "starts"}


def is_censored(data) -> bool:
    """True for a :class:`scipy.stats.CensoredData`."""
    from scipy.stats import CensoredData

    return isinstance(data, CensoredData)


class CensoredParts:
    """The four kinds of values of a :class:`scipy.stats.CensoredData` as float arrays."""

    def __init__(self, data):
        self.exact = np.sort(np.asarray(data._uncensored, dtype=float))
        self.left = np.asarray(data._left, dtype=float)
        self.right = np.asarray(data._right, dtype=float)
        self.interval = np.asarray(data._interval, dtype=float).reshape(-1, 2)
        self.all = np.sort(np.asarray(data._uncensor(), dtype=float))

    @property
    def n(self) -> int:
        return self.exact.size + self.left.size + self.right.size + self.interval.shape[0]

    @property
    def n_censored(self) -> int:
        return self.n - self.exact.size

    def scaled(self, med: float, iqr: float) -> CensoredParts:
        out = object.__new__(CensoredParts)
        for name in ("exact", "left", "right", "interval", "all"):
            setattr(out, name, (getattr(self, name) - med) / iqr)
        return out


def censored_parts(data) -> CensoredParts:
    """The parts of censored data (checked: at least 5 values, and finite where exact)."""
    parts = CensoredParts(data)
    if parts.n < 5:
        raise FitError(f"a GLD fit needs at least 5 values, got {parts.n} (censored ones included)")
    return parts


def loglik(param: str, lams, parts: CensoredParts) -> float:
    """Censored log-likelihood of the GLD ``(param, lambdas)`` (-inf where it is not defined)."""
    return _weighted_loglik(param, lams, parts, 1, 1, 1)


def _weighted_loglik(param: str, lams, parts: CensoredParts, w_left, w_right, w_interval) -> float:
    """:func:`loglik` with a weight (a multiplicity) per left, right and interval bound."""
    def ev(what, x):
        # never warns: a point where the inversion of Q hit its limit enters with its best estimate
        return gld_evaluate(param, what, x, lams)[0]

    total = 0.0
    if parts.exact.size:
        total += float(np.sum(ev("logpdf", parts.exact)))
    if parts.left.size:
        total += float(np.sum(w_left * ev("logcdf", parts.left)))
    if parts.right.size:
        total += float(np.sum(w_right * ev("logsf", parts.right)))
    if parts.interval.shape[0]:
        lo, hi = parts.interval[:, 0], parts.interval[:, 1]
        # the difference of the smaller tail probabilities: sf in the upper half, cdf below
        upper = np.asarray(ev("cdf", lo)) > 0.5
        with np.errstate(divide="ignore", invalid="ignore"):
            mass = np.where(upper, ev("sf", lo) - ev("sf", hi), ev("cdf", hi) - ev("cdf", lo))
            total += float(np.sum(w_interval * np.log(mass)))
    return total if math.isfinite(total) else -math.inf


def fit_censored(data, param: str, method: str, **options) -> FitRecord:
    """ML fit of :class:`scipy.stats.CensoredData` (see :func:`glstat.fit`)."""
    if method != "mle":
        raise ValueError(f"scipy.stats.CensoredData is fitted by method='mle' only (the censored "
                         f"likelihood), got method={method!r}; for {method!r} pass the exact values "
                         "(an array), or use method='mle'")
    unknown = set(options) - _ALLOWED
    if unknown:
        raise ValueError(f"unknown option(s) {sorted(unknown)} for censored data; allowed: "
                         f"{sorted(_ALLOWED)}")
    maxiter = int(options.get("maxiter", 4000))
    starts = int(options.get("starts", 2))
    parts = censored_parts(data)
    x = parts.all
    if not np.all(np.isfinite(parts.exact)):
        raise ValueError("the exact values of the censored data must be finite")
    fam = RS if param == "rs" else FKML
    med = float(np.median(x[np.isfinite(x)]))
    q25, q75 = np.quantile(x[np.isfinite(x)], [0.25, 0.75])
    iqr = float(q75 - q25) or float(np.ptp(x[np.isfinite(x)])) or 1.0
    z = parts.scaled(med, iqr)
    # uncensored ML of all values (bounds and midpoints as observations): the starts
    first = fit_data_objective(x[np.isfinite(x)], param, "mle", starts=starts)
    seeds = [r["lambdas"] for r in first._candidates if r["valid"]]

    # censored bounds enter once per distinct value, with their multiplicity
    left, n_left = np.unique(z.left, return_counts=True)
    right, n_right = np.unique(z.right, return_counts=True)
    ivl, n_ivl = (np.unique(z.interval, axis=0, return_counts=True) if z.interval.shape[0]
                  else (z.interval, np.zeros(0, dtype=np.int64)))
    bounds = CensoredParts.__new__(CensoredParts)
    bounds.exact, bounds.left, bounds.right, bounds.interval = z.exact[:0], left, right, ivl
    w = np.log((np.arange(z.exact.size) + 0.5) / (z.exact.size - np.arange(z.exact.size) - 0.5))

    def objective(theta):
        l1s, lsc, a, b = (float(v) for v in theta)
        if not (math.isfinite(lsc) and abs(lsc) < 700.0 and K.shape_valid(fam, a, b)):
            return math.inf
        # exact values: the compiled ML objective, warm-started at the last point's PIT
        val = L.objective(L.MLE, fam, a, b, l1s, math.exp(lsc), z.exact, w) if z.exact.size else 0.0
        if not math.isfinite(val):
            return math.inf
        if bounds.left.size or bounds.right.size or bounds.interval.shape[0]:
            val -= _weighted_loglik(param, to_lambdas(theta, param, 0.0, 1.0), bounds, n_left, n_right,
                                    n_ivl)
        return val if math.isfinite(val) else math.inf

    from scipy.optimize import minimize

    rows = []
    flags = []
    shift = parts.exact.size * math.log(iqr)  # density Jacobian of the scaling
    for lams in seeds:
        th = std_theta(lams, med, iqr)
        if not math.isfinite(objective(th)):
            continue
        ok = False
        for _ in range(2):  # a restart from the optimum rebuilds a collapsed simplex
            res = minimize(objective, th, method="Nelder-Mead",
                           options={"maxiter": maxiter, "xatol": 1e-9, "fatol": 1e-10})
            th, ok = np.asarray(res.x, dtype=float), bool(res.success)
        val = float(res.fun) + shift
        lam = to_lambdas(th, param, med, iqr)
        row = candidate(lam, param, math.isfinite(val), val, None)
        row["covers_data"] = bool(math.isfinite(val))
        rows.append(row)
        flags.append(ok)
    sel = select_candidate(rows, True, by_objective=True)
    if sel < 0:
        raise FitError(f"the censored mle found no valid {param.upper()} GLD whose support holds the "
                       "data; try the other parameterisation")
    issues = []
    if not flags[sel]:
        issues.append(FitIssue(ConvergenceWarning, f"censored mle fit: Nelder-Mead reached "
                               f"maxiter={maxiter}; the result is the best point found"))
    stats = {"neg_loglik": rows[sel]["objective"], "n_exact": float(parts.exact.size),
             "n_left_censored": float(parts.left.size), "n_right_censored": float(parts.right.size),
             "n_interval_censored": float(parts.interval.shape[0])}
    return make_record(rows, sel, param, method, parts.n, stats,
                       {"maxiter": maxiter, "starts": starts, "optimizer": "nelder-mead"}, issues)
