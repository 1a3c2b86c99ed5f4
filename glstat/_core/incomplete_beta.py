"""The regularized incomplete beta function in its deep lower tail, and its inverses finite
down to the smallest probabilities (the quantiles of the order statistics,
:func:`glstat.order_statistic`).

``scipy.special.betaincinv`` returns NaN (or 0) below p ~ 1e-100 for some (a, b); there the
inverse starts from the leading term ``I_x(a, b) ~ x^a / (a B(a, b))`` and is refined by
Newton's method in ``log x``.

For any rank r and any number of trials n (1e12 and beyond), :func:`binomial_tails` gives
both binomial tails ``P(Bin(n, p) < r)`` and ``P(Bin(n, p) >= r) = I_p(r, n - r + 1)`` to a
few ulp plus the conditioning of ``n log q``,
and :func:`binomial_tail_inv` inverts either one. ``scipy.special.betainc`` and ``betaincc``
lose up to 1e-8 relative there when ``b = n - r + 1`` is large (1e6 and beyond, near the
median of the binomial). For ``r <= SMALL_RANK`` the lower tail is the finite sum
``q^n sum_(j<r) C(n, j) (p/q)^j`` with ``log q`` given by the caller (``log1p(-p)`` or the
parent's ``logsf``), whose terms are all positive; the upper tail is ``1 - lower`` where the
lower tail is at most 1/2, the series of its own terms where ``n p <= (r + 1) / 8`` (ratio
of successive terms at most 1/8), and ``scipy.special.betainc``, accurate where the upper
tail is below 1/2, in between. Larger ranks (with ``n - r + 1 >= r``) use one binomial
term in Loader's saddle-point form times an integral of order one
(:mod:`glstat._core.binomial_tail`), to the same accuracy.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from scipy import special

from .binomial_tail import binomial_tails_any_rank

__all__ = [
    "SMALL_RANK",
    "BinomialTails",
    "betainccinv",
    "betaincinv",
    "binomial_tail_inv",
    "binomial_tail_rank_one",
    "binomial_tails",
    "log_betainc_small",
]


def log_betainc_small(a, b, x):
    """log I_x(a, b) for small x, from ``x^a (1-x)^b 2F1(a+b, 1; a+1; x) / (a B(a, b))``.

    The hypergeometric factor is summed as its power series ``sum_j c_j x^j`` with
    ``c_(j+1) / c_j = (a+b+j) / (a+1+j)``; where that series converges slowly
    (``x (a+b) / (a+1) > 1/2``) the log of ``scipy.special.betainc`` is used instead.
    """
    x = np.asarray(x, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        term = np.ones_like(x)
        series = np.ones_like(x)
        for j in range(60):
            term = term * x * ((a + b + j) / (a + 1.0 + j))
            series = series + term
        out = (
            a * np.log(x) + b * np.log1p(-x) - math.log(a) - special.betaln(a, b)
            + np.log(series)
        )
        slow = x * (a + b) / (a + 1.0) > 0.5
        if slow.any():
            out[slow] = np.log(special.betainc(a, b, x[slow]))
    return out


def _betaincinv_tail(a, b, logp):
    """x with ``I_x(a, b) = exp(logp)`` in the deep lower tail (``exp(logp)`` tiny).

    Starts from the leading term ``I_x ~ x^a / (a B(a, b))``, i.e.
    ``x0 = exp((log p + log a + B(a, b)) / a)`` with ``B = betaln``, and refines it by Newton's
    method on ``log I_x(a, b) - log p`` in ``y = log x``, whose derivative is
    ``x f(x) / I_x = x^a (1-x)^(b-1) / (B(a, b) I_x)``.
    """
    logp = np.asarray(logp, dtype=float)
    lbeta = special.betaln(a, b)
    y0 = np.minimum((logp + math.log(a) + lbeta) / a, 0.0)
    y = y0
    with np.errstate(over="ignore", under="ignore", invalid="ignore", divide="ignore"):
        for _ in range(8):
            x = np.exp(y)
            logi = log_betainc_small(a, b, x)
            slope = np.exp(a * y + (b - 1.0) * np.log1p(-x) - lbeta - logi)
            step = (logi - logp) / slope
            y = np.minimum(y - step, 0.0)
        # where x underflows (or Newton has nothing to work on) the leading term stands
        y = np.where(np.isfinite(y), y, y0)
        return np.exp(y)


def betaincinv(a, b, p, logp):
    """x with ``I_x(a, b) = p`` (``logp = log p``), finite down to the smallest p.

    ``scipy.special.betaincinv`` returns NaN (or 0) below p ~ 1e-100 for some (a, b); there
    the deep-tail inverse :func:`_betaincinv_tail` is used.
    """
    p, logp = np.broadcast_arrays(np.asarray(p, dtype=float), np.asarray(logp, dtype=float))
    with np.errstate(invalid="ignore"):
        x = np.asarray(special.betaincinv(a, b, p), dtype=float)
    bad = (p > 0) & (p < 1e-20) & (~np.isfinite(x) | (x <= 0))
    bad |= np.isnan(x) & ~np.isnan(p) & (p > 0) & (p <= 0.5)
    if bad.any():
        x = np.array(x, copy=True)
        x[bad] = _betaincinv_tail(a, b, logp[bad])
    return x


def betainccinv(a, b, q, logq):
    """x with ``1 - I_x(a, b) = q`` (``logq = log q``), finite down to the smallest q."""
    q, logq = np.broadcast_arrays(np.asarray(q, dtype=float), np.asarray(logq, dtype=float))
    with np.errstate(invalid="ignore"):
        x = np.asarray(special.betainccinv(a, b, q), dtype=float)
    bad = (q > 0) & (q <= 0.5) & (~np.isfinite(x) | (x >= 1))
    if bad.any():
        x = np.array(x, copy=True)
        x[bad] = 1.0 - betaincinv(b, a, q[bad], logq[bad])
    return x




# ------------------------------------------------------------------------------------------
# binomial tails for a small rank
# ------------------------------------------------------------------------------------------
#: largest rank r for which :func:`binomial_tails` sums the r terms of the lower tail
SMALL_RANK = 32

# below this a product may be subnormal: its log is summed instead
_UP_TINY = 1e-280


class BinomialTails(NamedTuple):
    """Both binomial tails at p and their logarithms (see :func:`binomial_tails`)."""

    low: np.ndarray  #: P(Bin(n, p) < r)
    up: np.ndarray  #: P(Bin(n, p) >= r) = I_p(r, n - r + 1)
    loglow: np.ndarray
    logup: np.ndarray
    dloglow: np.ndarray | None  #: d log(low) / dw with w = log(p / q) (None when not asked)
    dlogup: np.ndarray | None  #: d log(up) / dw


def _lower_sum(r, n, p, q, logp, logq):
    """``log U`` and ``log u_(r-1)`` for ``U = sum_(j<r) u_j``, ``u_j = C(n, j) (p/q)^j``.

    The terms are formed by the exact ratios ``u_(j+1) / u_j = (n - j) / (j + 1) * p / q``
    (``j + 1`` roundings each); where the sum overflows (p near 1) it is redone in
    logarithms.
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ratio = p / q
        u = np.ones_like(p)
        total = np.ones_like(p)
        for j in range(r - 1):
            u = u * ((n - j) / (j + 1.0)) * ratio
            total = total + u
        log_total = np.log(total)
        log_last = np.log(u)
        big = ~np.isfinite(total) & np.isfinite(logp) & np.isfinite(logq)
        if big.any():
            step = logp[big] - logq[big]
            acc = np.zeros_like(step)
            logs = [acc]
            for j in range(r - 1):
                acc = acc + (math.log((n - j) / (j + 1.0)) + step)
                logs.append(acc)
            stacked = np.stack(logs)
            top = stacked.max(axis=0)
            log_total[big] = top + np.log(np.exp(stacked - top).sum(axis=0))
            log_last[big] = acc
    return log_total, log_last


def _upper_series(r, n, p, q, logp, logq):
    """P(Bin(n, p) >= r) and its log from the series of its terms, for ``n p <= (r + 1) / 8``.

    ``C(n, r) p^r q^(n-r) sum_i prod_(j=r)^(r+i-1) rho_j`` with
    ``rho_j = (n - j) / (j + 1) * p / q <= 1/8``, so 20 terms reach double precision. The
    leading factor ``C(n, r) p^r`` is the product of the r factors ``(n - j) / (j + 1) * p``
    (r roundings); where it underflows it is summed in logarithms, which serves the log.
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        ratio = p / q
        term = np.ones_like(p)
        series = np.ones_like(p)
        for j in range(r, r + 20):
            term = term * ((n - j) / (j + 1.0)) * ratio
            series = series + term
        lead = np.ones_like(p)
        for j in range(r):
            lead = lead * ((n - j) / (j + 1.0)) * p
        up = lead * np.exp((n - r) * logq) * series
        logup = np.log(up)
        tiny = ~(lead >= _UP_TINY) & np.isfinite(logp)
        if tiny.any():
            logc = math.fsum(math.log((n - j) / (j + 1.0)) for j in range(r))
            logup[tiny] = (
                logc + r * logp[tiny] + (n - r) * logq[tiny] + np.log(series[tiny])
            )
            up[tiny] = np.exp(logup[tiny])
    return up, logup


def binomial_tails(r: int, n: float, p, q, logp, logq, derivatives: bool = True) -> BinomialTails:
    """Both tails of the binomial distribution Bin(n, p) at the rank r, in both tails.

    Parameters
    ----------
    r : int
        Rank, ``1 <= r <= n``. Ranks above ``SMALL_RANK`` (which need ``n - r + 1 >= r``) are
        computed by :func:`glstat._core.binomial_tail.binomial_tails_any_rank`.
    n : float
        Number of trials (a whole number, as large as 1e15).
    p, q : array_like
        Success probability and its complement ``1 - p``, each to full relative accuracy
        (q is not formed from p).
    logp, logq : array_like
        Their logarithms, each accurate (``log1p(-q)``, ``log1p(-p)`` where the argument is
        near 1).
    derivatives : bool, optional
        Whether to form ``dloglow`` and ``dlogup`` (None otherwise; the tails are the same).

    Returns
    -------
    BinomialTails
        ``low = P(Bin(n, p) < r)`` (= ``1 - I_p(r, n - r + 1)``), ``up = P(Bin(n, p) >= r)``
        (= ``I_p(r, n - r + 1)``), their logarithms (finite where the values underflow), and
        their derivatives with respect to ``w = log(p / q)`` (for :func:`binomial_tail_inv`).

    Notes
    -----
    The error is a few ulp plus the conditioning ``|n log q|`` times the relative error of
    ``log q`` (``n p`` for small p): the binomial tail itself amplifies the error of q that
    much.
    """
    p, q, logp, logq = (np.asarray(a, dtype=float) for a in np.broadcast_arrays(p, q, logp, logq))
    if r > SMALL_RANK:
        return BinomialTails(*binomial_tails_any_rank(r, n, p, q, logp, logq))
    log_total, log_last = _lower_sum(r, n, p, q, logp, logq)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        nlogq = n * logq
        loglow = np.where(q > 0, nlogq + log_total, -np.inf)
        low = np.exp(loglow)
        up = -np.expm1(loglow)
        body = low > 0.5
        logup = np.where(body, np.log(up), np.log1p(-low))
        if r > 1 and body.any():
            series = body & (n * p <= (r + 1.0) / 8.0)
            if series.any():
                up[series], logup[series] = _upper_series(
                    r, n, p[series], q[series], logp[series], logq[series]
                )
            body &= ~series
            up[body] = special.betainc(r, n - r + 1.0, p[body])
            logup[body] = np.log(up[body])
            # log(low) = log1p(-up): the sum form cancels where up is small
            body = low > 0.5
            loglow[body] = np.log1p(-up[body])
        if not derivatives:
            return BinomialTails(low, up, loglow, logup, None, None)
        # d log(low)/dw = -(n - r + 1) p u_(r-1) / U; d log(up)/dw = (n - r + 1) p t_(r-1) / up
        lead = math.log(n - r + 1.0) + logp + log_last
        dloglow = -np.exp(lead - log_total)
        dlogup = np.exp(lead + nlogq - logup)
    return BinomialTails(low, up, loglow, logup, dloglow, dlogup)


def binomial_tail_rank_one(n: float, q, logq, which: str):
    """One tail of Bin(n, p) at the rank 1, from q = 1 - p alone.

    Parameters
    ----------
    n : float
        Number of trials.
    q, logq : array_like
        ``1 - p`` and its logarithm, accurate.
    which : {"low", "up", "loglow", "logup"}
        The field of :func:`binomial_tails` (``r = 1``) to return: ``low = q^n``,
        ``up = 1 - q^n`` or their logarithms.

    Returns
    -------
    ndarray
        The same values as ``getattr(binomial_tails(1, n, p, q, logp, logq), which)``, with
        only the operations that field needs.
    """
    q, logq = (np.asarray(a, dtype=float) for a in np.broadcast_arrays(q, logq))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        loglow = np.where(q > 0, n * logq + 0.0, -np.inf)
        if which == "loglow":
            return loglow
        if which == "up":
            return -np.expm1(loglow)
        low = np.exp(loglow)
        if which == "low":
            return low
        if which != "logup":
            raise ValueError(f"which must be low, up, loglow or logup, got {which!r}")
        return np.where(low > 0.5, np.log(-np.expm1(loglow)), np.log1p(-low))


def _log_pair(p, q):
    """(log p, log q), each from the smaller of p and q."""
    with np.errstate(divide="ignore", invalid="ignore"):
        logp = np.where(p < 0.5, np.log(p), np.log1p(-q))
        logq = np.where(q < 0.5, np.log(q), np.log1p(-p))
    return logp, logq


def binomial_tail_inv(r: int, n: float, log_target, lower, p0):
    """p (and q = 1 - p) where a binomial tail of Bin(n, p) at rank r equals a target.

    Parameters
    ----------
    r : int
        Rank, ``1 <= r <= n`` (above ``SMALL_RANK`` with ``n - r + 1 >= r``).
    n : float
        Number of trials.
    log_target : array_like
        Log of the target probability (use the smaller of the two complementary targets).
    lower : array_like of bool
        True: solve ``P(Bin(n, p) < r) = target``; False: ``P(Bin(n, p) >= r) = target``.
    p0 : array_like
        Starting values in (0, 1) (e.g. from ``scipy.special.betaincinv``); non-finite or
        out-of-range starts are replaced by ``r / n``.

    Returns
    -------
    p, q : ndarray
        The root and its complement, each to full relative accuracy.

    Notes
    -----
    Newton's method on the log of the tail in ``w = log(p / q)``, with the iterate kept as the
    pair (p, q): a step ``dw`` maps it to ``(p, q e^-dw) / (p + q e^-dw)``, which keeps both
    to a few ulp (a double w would lose ``|w|`` ulp in the smaller of them). Steps are
    limited to 5 in w and the iteration stops after a step below 1e-10 (the next would be
    below 1e-20) or after 60 steps.
    """
    log_target = np.asarray(log_target, dtype=float)
    lower = np.broadcast_to(np.asarray(lower, dtype=bool), log_target.shape)
    p = np.array(np.broadcast_to(np.asarray(p0, dtype=float), log_target.shape), dtype=float)
    bad = ~((p > 0) & (p < 1))
    p[bad] = min(r / n, 0.5)
    q = 1.0 - p
    # a zero target: p = 1 for the lower tail, p = 0 for the upper one
    zero = log_target == -np.inf
    p[zero & lower], q[zero & lower] = 1.0, 0.0
    p[zero & ~lower], q[zero & ~lower] = 0.0, 1.0
    active = np.flatnonzero(np.isfinite(log_target) & (log_target <= 0))
    p[np.isnan(log_target) | (log_target > 0)] = np.nan
    for _ in range(60):
        if active.size == 0:
            break
        pa, qa = p[active], q[active]
        t = binomial_tails(r, n, pa, qa, *_log_pair(pa, qa))
        low = lower[active]
        g = np.where(low, t.loglow, t.logup) - log_target[active]
        if t.dloglow is None or t.dlogup is None:  # asked for above (derivatives=True)
            raise AssertionError("binomial_tails returned no derivatives")
        slope = np.where(low, t.dloglow, t.dlogup)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            dw = np.clip(-g / slope, -5.0, 5.0)
            e = np.exp(-dw)
            d = pa + qa * e
            p[active], q[active] = pa / d, qa * e / d
        active = active[np.abs(dw) > 1e-10]
    return p, q
