"""The regularized incomplete beta function in its deep lower tail, and its inverses finite
down to the smallest probabilities (the quantiles of the order statistics,
:func:`glstat.order_statistic`).

``scipy.special.betaincinv`` returns NaN (or 0) below p ~ 1e-100 for some (a, b); there the
inverse starts from the leading term ``I_x(a, b) ~ x^a / (a B(a, b))`` and is refined by
Newton's method in ``log x``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special

__all__ = ["betainccinv", "betaincinv", "log_betainc_small"]


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


