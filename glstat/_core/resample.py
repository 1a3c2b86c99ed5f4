"""Compiled statistics of bootstrap resamples (the numerical core of :mod:`glstat.bootstrap`).

A resample of the sorted sample ``x`` (length n) is described by its multiplicities: ``c[i]``
copies of ``x[i]``, ``m = sum(c)`` values in all. Sorting is then free (the resample in
increasing order is ``x[0]`` repeated ``c[0]`` times, then ``x[1]`` ...), so every statistic
is one or two linear passes over ``x`` whatever the resample:

* moments: mean, standard deviation, skewness and Pearson kurtosis with divisor m, the
  central sums taken about the resample's own mean (two passes, no cancellation);
* percentiles: the sample quantiles at (u, 1/4, 1/2, 3/4, 1 - u) with the order statistic at
  (m + 1) p, linearly interpolated exactly as ``numpy.quantile(method="weibull")`` does, and
  the Karian–Dudewicz rho1..rho4 built from them;
* L-moments: the unbiased probability-weighted moments b0..b3 (Hosking 1990), with the
  rank of each copy known from the running count, giving l1, l2, tau3, tau4.

Entry points: :func:`stats_from_indices` (resamples given by index rows, as drawn by a numpy
Generator), :func:`stats_from_counts` (multiplicities given directly, e.g. a delete-group
jackknife) and :func:`stats_from_sorted` (each row an already sorted sample, as in a
parametric bootstrap). Rows whose statistic is undefined (zero spread, tied quantiles) are NaN.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

MOMENTS = 0
PERCENTILES = 1
LMOMENTS = 2

CODES = {"moments": MOMENTS, "percentiles": PERCENTILES, "lmoments": LMOMENTS}


@njit(cache=True, error_model="numpy")
def _finish_moments(s1, s2, s3, s4, m, loc, scale, out):
    """Moments from the power sums of ``(x - loc) / scale`` over m values."""
    a = s1 / m
    r2 = s2 / m
    r3 = s3 / m
    r4 = s4 / m
    a2 = a * a
    m2 = r2 - a2
    m3 = r3 - 3.0 * a * r2 + 2.0 * a2 * a
    m4 = r4 - 4.0 * a * r3 + 6.0 * a2 * r2 - 3.0 * a2 * a2
    out[0] = loc + scale * a
    if m2 > 1e-14 * r2 and m2 > 0.0:
        out[1] = scale * math.sqrt(m2)
        out[2] = m3 / m2**1.5
        out[3] = m4 / (m2 * m2)
    else:  # no spread left above the rounding of the power sums: a constant resample
        out[1] = math.nan
        out[2] = math.nan
        out[3] = math.nan


@njit(cache=True, error_model="numpy")
def _moments(x, c, m, loc, scale, out):
    s1 = 0.0
    s2 = 0.0
    s3 = 0.0
    s4 = 0.0
    inv = 1.0 / scale
    for i in range(x.size):
        d = (x[i] - loc) * inv
        d2 = d * d
        w = c[i] * d
        s1 += w
        s2 += w * d
        s3 += w * d2
        s4 += w * d * d2
    _finish_moments(s1, s2, s3, s4, m, loc, scale, out)


@njit(cache=True, error_model="numpy")
def _lerp(a, b, t):
    # numpy.quantile's interpolation (numpy/lib/_function_base_impl.py, _lerp)
    d = b - a
    if t >= 0.5:
        return b - d * (1.0 - t)
    return a + d * t


@njit(cache=True, error_model="numpy")
def _percentiles(x, c, m, u, out):
    probs = np.array([u, 0.25, 0.5, 0.75, 1.0 - u])
    ranks = np.empty(10, dtype=np.int64)
    gam = np.empty(5)
    for j in range(5):
        p = probs[j]
        v = m * p + p - 1.0  # 0-based virtual index of the (m + 1) p order statistic
        if v < 0.0:
            lo = 0
            hi = 0
            g = 0.0
        elif v >= m - 1:
            lo = m - 1
            hi = m - 1
            g = 0.0
        else:
            lo = int(v)  # v >= 0 here: truncation is the floor
            hi = lo + 1
            g = v - lo
        ranks[2 * j] = lo
        ranks[2 * j + 1] = hi
        gam[j] = g
    vals = np.empty(10)
    # one scan of the cumulative counts finds all ten ranks, taken in increasing order
    order = np.argsort(ranks)
    k = 0
    cum = 0
    for i in range(x.size):
        cum += c[i]
        while k < 10 and ranks[order[k]] < cum:
            vals[order[k]] = x[i]
            k += 1
        if k == 10:
            break
    # interpolate the deviations from the lower middle order statistic (exact under a common
    # offset such as 1e9): the rounding of interpolated values of the size of the offset
    # would otherwise enter every difference below
    ctr = vals[4]
    if not (math.isfinite(vals[0] - ctr) and math.isfinite(vals[9] - ctr)):
        ctr = 0.0
    q = np.empty(5)
    for j in range(5):
        q[j] = _lerp(vals[2 * j] - ctr, vals[2 * j + 1] - ctr, gam[j])
    r2 = q[4] - q[0]
    out[0] = q[2] + ctr
    out[1] = r2
    if q[4] > q[2] and r2 > 0.0:
        out[2] = (q[2] - q[0]) / (q[4] - q[2])
        out[3] = (q[3] - q[1]) / r2
    else:
        out[2] = math.nan
        out[3] = math.nan


@njit(cache=True, error_model="numpy")
def _lmoments(x, c, m, out):
    b0 = 0.0
    b1 = 0.0
    b2 = 0.0
    b3 = 0.0
    d1 = m - 1.0
    d2 = (m - 1.0) * (m - 2.0)
    d3 = (m - 1.0) * (m - 2.0) * (m - 3.0)
    pos = 0
    # deviations from a central data value: exact under a common offset (1e9 + N(0, 1)),
    # where sums of the raw data would lose the digits that l2, l3 and l4 are made of
    ctr = x[x.size // 2] if x.size > 0 else 0.0
    if x.size > 0 and not (math.isfinite(x[0] - ctr) and math.isfinite(x[x.size - 1] - ctr)):
        ctr = 0.0
    for i in range(x.size):
        w = c[i]
        if w == 0:
            continue
        # sums over the ranks pos .. pos + w - 1 of the rank weights
        w1 = 0.0
        w2 = 0.0
        w3 = 0.0
        for r in range(pos, pos + w):
            fr = float(r)
            w1 += fr
            w2 += fr * (fr - 1.0)
            w3 += fr * (fr - 1.0) * (fr - 2.0)
        xi = x[i] - ctr
        b0 += w * xi
        b1 += w1 * xi
        b2 += w2 * xi
        b3 += w3 * xi
        pos += w
    b0 /= m
    b1 /= m * d1
    b2 /= m * d2
    b3 /= m * d3
    l2 = 2.0 * b1 - b0
    l3 = 6.0 * b2 - 6.0 * b1 + b0
    l4 = 20.0 * b3 - 30.0 * b2 + 12.0 * b1 - b0
    out[0] = b0 + ctr
    out[1] = l2
    if l2 > 0.0:
        out[2] = l3 / l2
        out[3] = l4 / l2
    else:
        out[2] = math.nan
        out[3] = math.nan


@njit(cache=True, error_model="numpy")
def _extremes(x, c, ext):
    """Smallest and largest value of the resample with multiplicities ``c`` of sorted ``x``."""
    ext[0] = math.nan
    ext[1] = math.nan
    for i in range(x.size):
        if c[i] > 0:
            ext[0] = x[i]
            break
    for i in range(x.size - 1, -1, -1):
        if c[i] > 0:
            ext[1] = x[i]
            break


@njit(cache=True, error_model="numpy")
def _row(kind, x, c, m, u, loc, scale, out, ext):
    _extremes(x, c, ext)
    if kind == MOMENTS:
        _moments(x, c, m, loc, scale, out)
    elif kind == PERCENTILES:
        _percentiles(x, c, m, u, out)
    else:
        _lmoments(x, c, m, out)


def stats_from_indices(kind, x, idx, u, loc, scale, out, ext):
    """Statistics of the resamples ``x[idx[r]]`` of the sorted sample ``x``.

    Parameters
    ----------
    kind : int
        MOMENTS, PERCENTILES or LMOMENTS.
    x : ndarray, shape (n,)
        Sorted sample.
    idx : ndarray of int, shape (R, m)
        Indices into ``x``, one row per resample.
    u : float
        Percentile probability (PERCENTILES only).
    loc, scale : float
        Centre and spread of ``x`` (its mean and largest absolute deviation from it, scale >
        0, as from ``glstat._fit_engine.sample_statistics.location_spread``): the moments are accumulated as
        power sums of ``(x - loc) / scale`` (MOMENTS only), which then lie in [-1, 1] whatever
        the scale of the data, so they neither underflow nor overflow.
    out : ndarray, shape (R, 4)
        Receives the four statistics per resample.
    ext : ndarray, shape (R, 2)
        Receives the smallest and the largest value of each resample (a fit must have a
        support covering them).
    """
    # one compiled kernel per branch: a moments bootstrap does not compile the percentile
    # and L-moment code (nor the other way round)
    if kind == MOMENTS:
        _moments_from_indices(x, idx, float(loc), float(scale), out, ext)
    else:
        _counts_from_indices(int(kind), x, idx, float(u), float(loc), float(scale), out, ext)


@njit(cache=True, error_model="numpy")
def _moments_from_indices(x, idx, loc, scale, out, ext):
    """The MOMENTS branch of :func:`stats_from_indices`."""
    m = idx.shape[1]
    inv = 1.0 / scale
    z = np.empty(x.size)
    for i in range(x.size):
        z[i] = (x[i] - loc) * inv
    for r in range(idx.shape[0]):
        s1 = 0.0
        s2 = 0.0
        s3 = 0.0
        s4 = 0.0
        imin = x.size
        imax = -1
        for j in range(m):
            k = idx[r, j]
            imin = min(imin, k)
            imax = max(imax, k)
            d = z[k]
            d2 = d * d
            s1 += d
            s2 += d2
            s3 += d2 * d
            s4 += d2 * d2
        _finish_moments(s1, s2, s3, s4, m, loc, scale, out[r])
        ext[r, 0] = x[imin] if m > 0 else math.nan
        ext[r, 1] = x[imax] if m > 0 else math.nan


@njit(cache=True, error_model="numpy")
def _counts_from_indices(kind, x, idx, u, loc, scale, out, ext):
    """The PERCENTILES and LMOMENTS branches of :func:`stats_from_indices` (through counts)."""
    m = idx.shape[1]
    c = np.zeros(x.size, dtype=np.int32)
    for r in range(idx.shape[0]):
        c[:] = 0
        for j in range(m):
            c[idx[r, j]] += 1
        _row(kind, x, c, m, u, loc, scale, out[r], ext[r])


@njit(cache=True, error_model="numpy")
def stats_from_counts(kind, x, counts, u, loc, scale, out, ext):
    """Statistics of the resamples with multiplicities ``counts[r]`` (shape (R, n)).

    ``ext`` (R, 2) receives each resample's smallest and largest value.
    """
    for r in range(counts.shape[0]):
        m = 0
        for i in range(x.size):
            m += counts[r, i]
        _row(kind, x, counts[r], m, u, loc, scale, out[r], ext[r])


@njit(cache=True, error_model="numpy")
def stats_from_sorted(kind, samples, u, loc, scale, out, ext):
    """Statistics of each row of ``samples`` (shape (R, m)), every row sorted increasingly.

    ``ext`` (R, 2) receives each row's smallest and largest value.
    """
    m = samples.shape[1]
    c = np.ones(m, dtype=np.int32)
    for r in range(samples.shape[0]):
        _row(kind, samples[r], c, m, u, loc, scale, out[r], ext[r])


@njit(cache=True, error_model="numpy")
def stats_delete_groups(kind, x, group, n_groups, u, loc, scale, out, ext):
    """Delete-a-group jackknife: statistics of ``x`` without the points of each group.

    ``group[i]`` in [0, n_groups) is the group of ``x[i]``; ``out`` has shape (n_groups, 4).
    With one point per group this is the delete-one jackknife. ``ext`` (n_groups, 2)
    receives the smallest and largest value left in each jackknife sample.
    """
    c = np.ones(x.size, dtype=np.int32)
    sizes = np.zeros(n_groups, dtype=np.int64)
    for i in range(x.size):
        sizes[group[i]] += 1
    for g in range(n_groups):
        for i in range(x.size):
            c[i] = 0 if group[i] == g else 1
        _row(kind, x, c, x.size - sizes[g], u, loc, scale, out[g], ext[g])
