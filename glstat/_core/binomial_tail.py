"""Binomial tails ``P(Bin(n, p) >= r)`` and ``P(Bin(n, p) < r)`` for any rank r (numba kernels).

Both tails are ``I_p(r, n - r + 1)`` and its complement. The smaller of the two is written as
one binomial term times an integral of order one,

* ``P(X >= r) = r b(r) K(r - 1, n - r, p / q)`` and
* ``P(X < r) = (n - r + 1) b(r - 1) K(n - r, r - 1, q / p)``,

with ``b(j) = C(n, j) p^j q^(n-j)`` and ``K(alpha, beta, t) = int_0^1 (1 - u)^alpha
(1 + t u)^beta du`` (the substitution ``x = p (1 - u)`` in the incomplete beta integral).
The tail whose integrand decreases from ``u = 0`` is the one taken (``(r - 1) - (n - 1) p``
decides); the other is one minus it, which is then at least about 1/2.

* The term ``b(j)`` is Loader's saddle-point form ``exp(-bd0(j, n p) - bd0(n - j, n q)
  + stirlerr terms) sqrt(n / (2 pi j (n - j)))`` with the deviance
  ``bd0(j, M) = j log(j / M) + M - j`` formed from ``j - n p``, which is computed from the
  exact product ``n p`` (two-product) so that the deviation of the rank from the mean keeps
  its relative accuracy even where both are 1e12.
* The integrand is ``exp(psi(u))`` with ``psi(u) = alpha log1pmx(-u) + beta log1pmx(t u)
  - c u``, ``log1pmx(x) = log(1 + x) - x`` by its series where small and ``c = alpha - beta t``
  again from the exact product: no term of size ``alpha u`` (up to 1e6 near the centre at
  n = 1e12) is ever formed and cancelled. psi is concave with ``psi(0) = 0``; the integral
  runs to the point U where ``psi(U)`` is between -40 and -48 (found by Newton's method from
  the right, which converges monotonically on a concave function) and is summed by
  Gauss-Legendre on 12 equal panels of 16 nodes; the part beyond U is below ``e^-40`` of the
  whole (concavity).

The cost is about 200 logarithms per point whatever n and r are. The error is a few ulp
plus ``|log tail|`` ulp from the exponential, beyond the conditioning of the tail with respect
to p itself (``|r - n p|`` times the relative error of p).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .double_double import two_prod

__all__ = ["binomial_tails_any_rank"]

_LOG_2PI = math.log(2.0 * math.pi)
_LEVEL = 40.0  # the integral runs to psi(U) ~ -_LEVEL
_PANELS = 12
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)


@njit(cache=True, error_model="numpy")
def _stirlerr(m):
    """log(m!) - ((m + 1/2) log m - m + log(2 pi) / 2), for m >= 16 (asymptotic series)."""
    z = 1.0 / (m * m)
    return (
        1.0 / 12.0 - z * (1.0 / 360.0 - z * (1.0 / 1260.0 - z * (1.0 / 1680.0 - z / 1188.0)))
    ) / m


@njit(cache=True, error_model="numpy")
def _log1pmx(x):
    """log(1 + x) - x, to a few ulp for every x > -1 (series in v = x / (2 + x) where
    |x| < 1/2)."""
    if abs(x) >= 0.5:
        return math.log1p(x) - x
    v = x / (2.0 + x)
    v2 = v * v
    term = v2
    s = 0.0
    k = 3.0
    while True:
        add = term / k
        s += add
        if add < 1e-18 * s or term == 0.0:
            break
        term *= v2
        k += 2.0
    # log1p(x) = 2 (v + v^3/3 + ...), and x - 2 v = v x
    return 2.0 * v * s - v * x


@njit(cache=True, error_model="numpy")
def _deviation(k, n, p, q):
    """(k - n p, n p, n q), the first to full relative accuracy, from the exact product of n
    and the smaller of p, q."""
    if p <= q:
        hi, lo = two_prod(n, p)
        return (k - hi) - lo, hi + lo, (n - hi) - lo
    hi, lo = two_prod(n, q)
    return ((k - n) + hi) + lo, (n - hi) - lo, hi + lo


@njit(cache=True, error_model="numpy")
def _bd0(k, d, m, logm):
    """k log(k / M) + M - k with d = k - M accurate, M and log M given."""
    if m > 0.0 and math.isfinite(d / m):
        e = d / m
        if e <= 1.0:
            return m * (_log1pmx(e) + e * math.log1p(e))
        return k * math.log1p(e) - d
    return k * (math.log(k) - logm) - d


@njit(cache=True, error_model="numpy")
def _log_term(j, n, d, m, mf, logp, logq):
    """log of C(n, j) p^j q^(n-j), with d = j - n p accurate, m = n p and mf = n q (Loader's
    saddle-point form)."""
    logn = math.log(n)
    return (
        _stirlerr(n) - _stirlerr(j) - _stirlerr(n - j)
        - _bd0(j, d, m, logn + logp) - _bd0(n - j, -d, mf, logn + logq)
        + 0.5 * (logn - _LOG_2PI - math.log(j) - math.log(n - j))
    )


@njit(cache=True, error_model="numpy")
def _psi(u, alpha, beta, t, c):
    return alpha * _log1pmx(-u) + beta * _log1pmx(t * u) - c * u


@njit(cache=True, error_model="numpy")
def _integral(alpha, beta, t, c):
    """int_0^1 (1 - u)^alpha (1 + t u)^beta du with c = alpha - beta t >= 0 given accurately."""
    # a point beyond the level: psi(u) <= -c u and psi(u) <= -alpha u^2 / 2
    u = math.sqrt(2.0 * _LEVEL / alpha)
    if c > 0.0:
        u = min(u, _LEVEL / c)
    u = min(u, 0.5)
    while _psi(u, alpha, beta, t, c) > -_LEVEL:
        u = 0.5 * (1.0 + u)
    # Newton from the right: monotone on the concave psi
    for _ in range(60):
        val = _psi(u, alpha, beta, t, c)
        if val >= -1.2 * _LEVEL:
            break
        slope = -alpha / (1.0 - u) + beta * t / (1.0 + t * u)
        u -= (val + _LEVEL) / slope
    h = u / _PANELS
    total = 0.0
    for i in range(_PANELS):
        mid = (i + 0.5) * h
        part = 0.0
        for g in range(_GL_X.size):
            part += _GL_W[g] * math.exp(_psi(mid + 0.5 * h * _GL_X[g], alpha, beta, t, c))
        total += part
    return 0.5 * h * total


@njit(cache=True, error_model="numpy")
def _tails(r, n, p, q, logp, logq, out):
    """out[:] = (low, up, loglow, logup, dloglow, dlogup) at one p (see the module docstring)."""
    if not (p >= 0.0 and q >= 0.0):
        for i in range(6):
            out[i] = np.nan
        return
    if p == 0.0:
        out[0], out[1], out[2], out[3], out[4], out[5] = 1.0, 0.0, 0.0, -np.inf, 0.0, np.inf
        return
    if q == 0.0:
        out[0], out[1], out[2], out[3], out[4], out[5] = 0.0, 1.0, -np.inf, 0.0, -np.inf, 0.0
        return
    # (r - 1) - (n - 1) p decides which tail has the decreasing integrand
    d1 = _deviation(r - 1.0, n - 1.0, p, q)[0]
    if d1 >= 0.0:
        # upper tail: r b(r) K(r - 1, n - r, p / q), c = d1 / q
        d, m, mf = _deviation(r, n, p, q)
        kk = _integral(r - 1.0, n - r, p / q, d1 / q)
        small = math.log(r) + _log_term(r, n, d, m, mf, logp, logq) + math.log(kk)
        big = math.log1p(-math.exp(small))
        out[0], out[1], out[2], out[3] = -math.expm1(small), math.exp(small), big, small
        # d log(up)/dw = q / K, d log(low)/dw = -(up / low) q / K   (w = log(p / q))
        out[5] = q / kk
        out[4] = -math.exp(small - big) * q / kk
    else:
        # lower tail: (n - r + 1) b(r - 1) K(n - r, r - 1, q / p), c = -d1 / p
        d, m, mf = _deviation(r - 1.0, n, p, q)
        kk = _integral(n - r, r - 1.0, q / p, -d1 / p)
        small = math.log(n - r + 1.0) + _log_term(r - 1.0, n, d, m, mf, logp, logq) + math.log(kk)
        big = math.log1p(-math.exp(small))
        out[0], out[1], out[2], out[3] = math.exp(small), -math.expm1(small), small, big
        out[4] = -p / kk
        out[5] = math.exp(small - big) * p / kk


@njit(cache=True, error_model="numpy")
def _tails_array(r, n, p, q, logp, logq):
    out = np.empty((6, p.size))
    row = np.empty(6)
    for i in range(p.size):
        _tails(r, n, p[i], q[i], logp[i], logq[i], row)
        for j in range(6):
            out[j, i] = row[j]
    return out


def binomial_tails_any_rank(r: int, n: float, p, q, logp, logq):
    """Both binomial tails of Bin(n, p) at the rank r, for any ``1 < r <= n``.

    Parameters
    ----------
    r : int
        Rank, ``2 <= r <= n`` (the kernel needs ``r - 1 >= 16`` and ``n - r + 1 >= 16`` for its
        Stirling series; smaller ranks are served by the finite sums of
        :mod:`glstat._core.incomplete_beta`).
    n : float
        Number of trials, a whole number up to about 1e15.
    p, q : array_like
        Success probability and its complement, each to full relative accuracy.
    logp, logq : array_like
        Their logarithms, each accurate.

    Returns
    -------
    ndarray, shape (6,) + shape of p
        ``P(Bin(n, p) < r)``, ``P(Bin(n, p) >= r)``, their logs (finite where the values
        underflow), and the derivatives of the logs with respect to ``w = log(p / q)``.
    """
    shape = np.broadcast(p, q, logp, logq).shape
    p, q, logp, logq = (
        np.ascontiguousarray(a, dtype=float).ravel() for a in np.broadcast_arrays(p, q, logp, logq)
    )
    return _tails_array(float(r), float(n), p, q, logp, logq).reshape((6, *shape))
