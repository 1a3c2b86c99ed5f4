"""Data-based GLD fits: maximum likelihood, maximum product of spacings, starship.

All three need the probability integral transform u_i = F(x_i) of the sample for every trial
parameter. The compiled kernel inverts Q for the sorted sample in logit coordinates
w = log(u / (1 - u)) by a bracketed Newton iteration warm-started from the previous trial's
w (an optimiser moves the parameters a little at a time, so two or three steps suffice).
Parameters whose support does not cover the data are rejected (objective +inf): the fits stay
feasible.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from numba import njit
from scipy.optimize import minimize

from .._core._gld import FKML, RS, log_qprime_lower, q_lower, qprime_lower, rs_sign
from ..errors import ConvergenceWarning, FitError
from . import _kernels as K

MLE = 0
MPS = 1
STARSHIP = 2
_KIND = {"mle": MLE, "mps": MPS, "starship": STARSHIP}


@njit(cache=True)
def _logsig(w):
    """log(1 / (1 + exp(-w))) without overflow."""
    if w > 0.0:
        return -math.log1p(math.exp(-w))
    return w - math.log1p(math.exp(w))


@njit(cache=True)
def _q_w(fam, a, b, w):
    """Standardized Q and dQ/dw at u = 1 / (1 + exp(-w))."""
    t = _logsig(w)
    l1 = _logsig(-w)
    if w <= 0.0:
        q = q_lower(fam, a, b, t, l1)
        qp = qprime_lower(fam, a, b, t, l1)
    else:
        q = -q_lower(fam, b, a, l1, t)
        qp = qprime_lower(fam, b, a, l1, t)
    return q, qp * math.exp(t + l1)


@njit(cache=True)
def _logqp_w(fam, a, b, w):
    """log Q'(u) at u = 1 / (1 + exp(-w)) (minus the log density of the standardized GLD)."""
    t = _logsig(w)
    l1 = _logsig(-w)
    if w <= 0.0:
        return log_qprime_lower(fam, a, b, t, l1)
    return log_qprime_lower(fam, b, a, l1, t)


@njit(cache=True)
def pit_logit(fam, a, b, y, w):
    """Solve Q(u_i) = y_i for sorted standardized ``y``; ``w`` (logit u) is the warm start
    and receives the solution. Returns False when a point lies outside the support or an
    iteration fails."""
    n = y.shape[0]
    lo_end = q_lower(fam, a, b, -math.inf, 0.0)
    hi_end = -q_lower(fam, b, a, -math.inf, 0.0)
    if not (y[0] > lo_end and y[n - 1] < hi_end):
        return False
    for i in range(n):
        wi = w[i]
        lo = -740.0
        hi = 740.0
        if i > 0 and w[i - 1] > lo:
            lo = w[i - 1] - 1e-9 * (1.0 + abs(w[i - 1]))
        ok = False
        for _ in range(200):
            q, dq = _q_w(fam, a, b, wi)
            r = q - y[i]
            if abs(r) <= 4e-16 * (abs(q) + abs(y[i])):
                ok = True
                break
            if r > 0.0:
                hi = wi
            elif r < 0.0:
                lo = wi
            else:
                ok = True
                break
            wn = wi - r / dq if dq > 0.0 else math.nan
            if not (wn > lo and wn < hi):
                wn = 0.5 * (lo + hi)
            if abs(wn - wi) <= 1e-11 * (1.0 + abs(wi)):
                wi = wn
                ok = True
                break
            wi = wn
        if not ok:
            return False
        w[i] = wi
    return True


@njit(cache=True)
def objective(kind, fam, a, b, l1, scale, x, w):
    """Objective of ``kind`` (to minimise) for the sorted sample ``x``; +inf when infeasible.

    MLE: negative log-likelihood. MPS: minus the sum of the log spacings F(x_(i)) -
    F(x_(i-1)) (ties use the log density, Cheng & Amin 1983). STARSHIP: the
    Anderson–Darling statistic of u_i = F(x_i) against the uniform.
    """
    if not K.shape_valid(fam, a, b) or not (scale > 0.0):
        return math.inf
    n = x.shape[0]
    y = (x - l1) / scale
    if not pit_logit(fam, a, b, y, w):
        return math.inf
    total = 0.0
    if kind == MLE:
        for i in range(n):
            total += _logqp_w(fam, a, b, w[i])
        return total + n * math.log(scale)
    if kind == MPS:
        prev_u = 0.0
        for i in range(n + 1):
            if i < n:
                wi = w[i]
                ui = math.exp(_logsig(wi))
                if i > 0 and wi > 0.0 and w[i - 1] > 0.0:
                    # both in the upper half: difference of the survival probabilities
                    d = math.exp(_logsig(-w[i - 1])) - math.exp(_logsig(-wi))
                else:
                    d = ui - prev_u
                prev_u = ui
            else:
                d = math.exp(_logsig(-w[n - 1]))
            if d > 0.0:
                total -= math.log(d)
            else:
                total += _logqp_w(fam, a, b, w[i - 1]) + math.log(scale)
        return total / (n + 1)
    for i in range(n):
        total += (2.0 * i + 1.0) * (_logsig(w[i]) + _logsig(-w[n - 1 - i]))
    return -n - total / n


def _std_params(lams, param, med, iqr):
    """(lambda1, log scale, a, b) of the GLD for the standardized data (x - med) / iqr."""
    l1, l2, a, b = lams
    return np.array([(l1 - med) / iqr, math.log(1.0 / (abs(l2) * iqr)), a, b])


def _to_lambdas(theta, param, med, iqr):
    l1s, lsc, a, b = (float(v) for v in theta)
    scale = math.exp(lsc) * iqr
    s = float(rs_sign(a, b)) if param == "rs" else 1.0
    return (med + iqr * l1s, s / scale, a, b)


def _cover(lams, param, x):
    """``lams`` with the scale widened about the median until the support covers ``x``."""
    from ..gld import GLD
    from .core import covers

    l1, l2, a, b = lams
    med = float(GLD(*lams, param=param).median())
    for _ in range(200):
        if covers(GLD(l1, l2, a, b, param=param), x):
            return (l1, l2, a, b)
        l2 *= 1.0 / 1.1
        l1 = med - (med - l1) * 1.1
    return None


def fit_data_objective(x: np.ndarray, param: str, method: str, maxiter: int = 2000, starts: int = 1):
    """ML, MPS or starship fit of sorted, checked data ``x`` (see :func:`glstat.fit`).

    Starts: every valid root of the percentile and L-moment equations (scale widened about
    the median where the support misses data points); the ``starts`` best by objective are
    refined by Nelder–Mead in (lambda1, log scale, lambda3, lambda4) on the data scaled by
    median and interquartile range; infeasible parameters have objective +inf.
    """
    from ._stats import check_lmoment_stats, rho_from_quantiles, sample_lmoments, sample_quantiles
    from .core import _candidate, _make_fit, _roots, _select

    if int(starts) < 1 or int(maxiter) < 1:
        raise ValueError(f"starts and maxiter must be positive integers, got {starts!r}, {maxiter!r}")
    kind = _KIND[method]
    fam = RS if param == "rs" else FKML
    med = float(np.median(x))
    q25, q75 = np.quantile(x, [0.25, 0.75])
    iqr = float(q75 - q25) or float(x[-1] - x[0])
    z = (x - med) / iqr
    n = x.size
    w0 = np.log((np.arange(n) + 0.5) / (n - np.arange(n) - 0.5))

    start_lams = []
    stats_list = [("percentiles", rho_from_quantiles(sample_quantiles(x, 0.1)))]
    lm = sample_lmoments(x)
    try:
        check_lmoment_stats(*lm)
        stats_list.append(("lmoments", lm))
    except FitError:
        pass
    for meth, st in stats_list:
        try:
            for lams, conv, _ in _roots(meth, param, st, 0.1):
                if conv:
                    c = _cover(lams, param, x)
                    if c is not None:
                        start_lams.append(c)
        except (FitError, ValueError, ZeroDivisionError):
            continue
    if not start_lams:
        raise FitError(f"no {param.upper()} starting point for {method!r}: neither the percentile nor "
                       "the L-moment equations have a valid root for these data; try param='fkml'")

    def f(theta, w):
        l1s, lsc, a, b = theta
        return objective(kind, fam, a, b, l1s, math.exp(lsc), z, w)

    scored = []
    for lams in start_lams:
        th = _std_params(lams, param, med, iqr)
        w = w0.copy()
        scored.append((f(th, w), th, w))
    scored.sort(key=lambda t: t[0])
    # objective differences that matter: 1e-6 in log-likelihood units (per point for MPS, AD)
    ftol = 1e-6 if kind == MLE else 1e-6 / n
    rows = []
    success = []
    for val0, th0, w in scored[: int(starts)]:
        if not math.isfinite(val0):
            continue
        res = minimize(f, th0, args=(w,), method="Nelder-Mead",
                       options={"maxiter": int(maxiter), "xatol": 1e-6, "fatol": ftol})
        lams = _to_lambdas(res.x, param, med, iqr)
        obj = float(res.fun) + (n * math.log(iqr) if kind == MLE else 0.0)
        rows.append(_candidate(lams, param, math.isfinite(obj), obj, x))
        success.append(bool(res.success))
    sel = _select(rows, True, by_objective=True)
    if sel < 0:
        raise FitError(f"the {method} optimisation found no valid {param.upper()} GLD covering the data")
    if not success[sel]:
        warnings.warn(f"{method} fit: Nelder-Mead reached maxiter={maxiter}; the result is the best "
                      "point found", ConvergenceWarning, stacklevel=3)
    name = {"mle": "neg_loglik", "mps": "neg_mean_log_spacing", "starship": "anderson_darling"}[method]
    return _make_fit(rows, sel, param, method, n, {name: rows[sel]["objective"]},
                     {"maxiter": int(maxiter), "starts": int(starts)})
