"""Sample statistics matched by the fits and their conversion to the solver coordinates."""

from __future__ import annotations

import math

import numpy as np

from _glstat_runtime.validation import real_values

from ..errors import FitError
from . import kernels as K

MIN_N = 5
_NAN_POLICIES = ("raise", "omit", "propagate")


def prepare_data(data, nan_policy: str = "raise") -> tuple[np.ndarray | None, int]:
    """Sorted finite copy of ``data`` (never the caller's array), or None for ``propagate``.

    Parameters
    ----------
    data : array_like
        Real numbers (integers or floats; a pandas Series or array of a numeric dtype, whose
        missing values count as NaN). The masked entries of a :class:`numpy.ma.MaskedArray`
        are missing values and are always left out (they are counted with the non-finite
        values removed).
    nan_policy : {"raise", "omit", "propagate"}
        What to do with NaN and infinite values.

    Returns
    -------
    x : ndarray or None
        The sorted sample (None when ``nan_policy="propagate"`` meets a non-finite value).
    nbad : int
        Number of masked and non-finite values removed.

    Raises
    ------
    TypeError
        Complex numbers, dates or times, booleans, strings, or objects that are not real
        numbers (``None``, ``pandas.NA``, ...).
    ValueError
        Non-finite values with ``nan_policy="raise"``, or an unknown ``nan_policy``.
    FitError
        Fewer than ``MIN_N`` values, or all equal.
    """
    if nan_policy not in _NAN_POLICIES:
        raise ValueError(f"nan_policy must be one of {_NAN_POLICIES}, got {nan_policy!r}")
    x, keep = real_values(data)
    nmasked = 0
    if keep is not None:
        nmasked = int(keep.size - keep.sum())
        x = x[keep]
    bad = ~np.isfinite(x)
    nbad = int(bad.sum())
    if nbad:
        if nan_policy == "raise":
            raise ValueError(
                f"data contain {nbad} non-finite value(s) (NaN or inf) out of {x.size}; remove them "
                "or pass nan_policy='omit' (drop them) or 'propagate' (return a NaN fit)"
            )
        if nan_policy == "propagate":
            return None, nbad
        x = x[~bad]
    if x.size < MIN_N:
        raise FitError(
            f"a GLD fit needs at least {MIN_N} finite data points, got {x.size}"
            + (f" ({nbad} non-finite value(s) omitted)" if nbad else "")
            + (f" ({nmasked} masked value(s) left out)" if nmasked else "")
        )
    x.sort()
    if x[0] == x[-1]:
        raise FitError(f"the {x.size} data points are all equal to {x[0]!r}: a constant sample has no "
                       "GLD fit (zero variance)")
    return x, nbad + nmasked


def _centre(x: np.ndarray) -> tuple[float, np.ndarray]:
    """A data value ``c`` near the middle of ``x`` and the deviations ``y = x - c``.

    For data under a large common offset (1e9 + N(0, 1)) the subtraction of a data value of
    the same magnitude is exact, so every statistic accumulated from ``y`` is what the
    shifted data would give; the mean of ``x`` itself would carry an absolute rounding error
    of eps * |offset| into every central moment.
    """
    c = float(np.partition(x, x.size // 2)[x.size // 2]) if x.size else 0.0
    y = x - c
    if not np.all(np.isfinite(y)):
        # the differences overflowed (data spanning the whole double range): no shift
        return 0.0, np.asarray(x, dtype=float)
    return c, y


def _mean(y: np.ndarray) -> float:
    """Mean of ``y`` with one correction pass (the mean of the residuals), overflow-safe."""
    m = float(np.mean(y))
    if not math.isfinite(m):
        # the sum overflowed: take the mean of the data scaled by their largest magnitude
        big = float(np.max(np.abs(y)))
        m = big * float(np.mean(y / big))
    return m + float(np.mean(y - m))


def sample_moments(x: np.ndarray) -> tuple[float, float, float, float]:
    """Mean, standard deviation, skewness and (Pearson) kurtosis, all with divisor n.

    The data are first centred on one of their own values (exact for data under a common
    offset, see `_centre`), the mean of the deviations is taken with a correction pass, and
    the deviations from it are divided by their largest magnitude before the powers are
    taken, so that neither ``d**4`` underflows (data of order 1e-80 and below) nor overflows
    (data of order 1e77 and above): the results scale exactly with the data, and a common
    offset does not enter the shape statistics.
    """
    c, y = _centre(x)
    my = _mean(y)
    m = c + my
    d = y - my
    spread = float(np.max(np.abs(d)))
    if not (spread > 0.0 and math.isfinite(spread)):
        raise FitError("the data have zero variance: no GLD matches them")
    d = d / spread
    m2 = float(np.mean(d * d))
    m3 = float(np.mean(d**3))
    m4 = float(np.mean(d**4))
    if not m2 > 0.0:
        raise FitError("the data have zero variance: no GLD matches them")
    skew = m3 / m2**1.5
    kurt = m4 / (m2 * m2)
    # Pearson's inequality kurt >= 1 + skew^2 holds for every sample, with equality exactly for
    # two-valued data; rounding can push it a few ulps either way
    if kurt - 1.0 - skew * skew <= 64 * 2.2e-16 * kurt:
        raise FitError(
            f"kurtosis {kurt:.6g} equals 1 + skew^2 = {1.0 + skew * skew:.6g} (Pearson's bound, "
            f"reached only by two-valued data): {distinct_note(x)}"
        )
    return m, spread * math.sqrt(m2), skew, kurt


def location_spread(x: np.ndarray) -> tuple[float, float]:
    """Mean of ``x`` and the largest distance of a value from it (> 0 unless x is constant).

    The centre and scale about which the compiled resample statistics take their power sums
    (:mod:`glstat._core.resample`): dividing by the largest deviation rather than by the
    standard deviation keeps every power in [0, 1], whatever the scale of the data, and never
    divides by a standard deviation that underflowed to zero.
    """
    c, y = _centre(x)
    my = _mean(y)
    spread = float(np.max(np.abs(y - my)))
    return c + my, spread if spread > 0.0 else 1.0


def distinct_note(x: np.ndarray) -> str:
    """What to do about data with ties / too few distinct values (for error messages)."""
    k = int(np.unique(x).size)
    return (f"the {x.size} data points take only {k} distinct value(s) (ties); a continuous GLD "
            "cannot describe them. Use data with more resolution or, if the ties come from "
            "rounding, spread each value over its rounding interval (e.g. add uniform noise of "
            "half the rounding step) before fitting")


def sample_quantiles(x: np.ndarray, u: float) -> np.ndarray:
    """Sample quantiles at (u, 1/4, 1/2, 3/4, 1-u), order statistic at (n+1)p (interpolated)."""
    return np.quantile(x, [u, 0.25, 0.5, 0.75, 1.0 - u], method="weibull")


def sample_rho(x: np.ndarray, u: float) -> tuple[float, float, float, float]:
    """Karian–Dudewicz rho1..rho4 of ``x``, with the quantiles interpolated as deviations from
    a central data value, so that a common offset (1e9 + N(0, 1)) leaves rho2..rho4 exact;
    equal to ``rho_from_quantiles(sample_quantiles(x, u))`` up to that rounding."""
    c, y = _centre(np.asarray(x, dtype=float))
    r1, r2, r3, r4 = rho_from_quantiles(sample_quantiles(y, u))
    return c + r1, r2, r3, r4


def rho_from_quantiles(q) -> tuple[float, float, float, float]:
    """Karian–Dudewicz rho1..rho4 from the quantiles at (u, 1/4, 1/2, 3/4, 1-u)."""
    qu, q25, q50, q75, q1u = (float(v) for v in q)
    r2 = q1u - qu
    return q50, r2, (q50 - qu) / (q1u - q50) if q1u != q50 else math.inf, (q75 - q25) / r2 if r2 else math.nan


def sample_lmoments(x: np.ndarray) -> tuple[float, float, float, float]:
    """Unbiased sample L-moments l1, l2 and ratios t3, t4 (Hosking 1990) of sorted ``x``.

    The probability-weighted moments are accumulated from the deviations from a central data
    value (exact under a common offset); l2, l3 and l4 do not depend on the shift, which is
    added back to l1 only.
    """
    n = x.size
    c, x = _centre(x)
    i = np.arange(n, dtype=float)
    b0 = x.mean()
    b1 = np.sum(i / (n - 1) * x) / n
    b2 = np.sum(i * (i - 1) / ((n - 1) * (n - 2)) * x) / n
    b3 = np.sum(i * (i - 1) * (i - 2) / ((n - 1) * (n - 2) * (n - 3)) * x) / n
    l2 = 2 * b1 - b0
    l3 = 6 * b2 - 6 * b1 + b0
    l4 = 20 * b3 - 30 * b2 + 12 * b1 - b0
    if l2 == 0.0:  # all values equal: no L-moment ratios (NaN, without numpy's 0/0 warning)
        return c + float(b0), 0.0, math.nan, math.nan
    return c + float(b0), float(l2), float(l3 / l2), float(l4 / l2)


def _order_weights(n: int, p: int, q: int) -> np.ndarray:
    """C(i-1, p) C(n-i, q) / C(n, p+q+1) for i = 1..n: the probability that the (p+1)-th of
    p+q+1 values drawn without replacement from n ranks is rank i.

    Built as a product of ratios each at most 1 (no large binomial coefficients), exact to a
    few ulps for any n.
    """
    i = np.arange(1, n + 1, dtype=float)
    w = np.full(n, float(math.comb(p + q + 1, p) * (q + 1)))
    for j in range(p):
        w *= (i - 1.0 - j) / (n - j)
    for j in range(q):
        w *= (n - i - j) / (n - p - j)
    return w / (n - p - q)


def sample_tlmoments(x: np.ndarray, t1: int = 1, t2: int = 1) -> tuple[float, float, float, float]:
    """Unbiased sample TL-moments l1, l2 and ratios t3 = l3/l2, t4 = l4/l2 of sorted ``x``
    with trimming (t1, t2) (Elamir & Seheult 2003).

    The r-th sample TL-moment is the average, over all subsamples of r + t1 + t2 of the n
    values, of (1/r) sum_k (-1)^k C(r-1, k) times the (r + t1 - k)-th smallest value of the
    subsample; here it is the weighted sum of the order statistics with the weights
    (1/r) sum_k (-1)^k C(r-1, k) C(i-1, r+t1-1-k) C(n-i, t2+k) / C(n, r+t1+t2). With
    t1 = t2 = 0 these are the sample L-moments of :func:`sample_lmoments`. The sums are taken
    over the deviations from a central data value (exact under a common offset), added back
    to l1 only.

    Raises
    ------
    FitError
        Fewer than 4 + t1 + t2 values.
    """
    n = x.size
    need = 4 + t1 + t2
    if n < need:
        raise FitError(f"TL-moments with trim=({t1}, {t2}) need at least 4 + t1 + t2 = {need} data "
                       f"points, got {n}; trim less or use method='lmoments'")
    c, y = _centre(x)
    lam = []
    for r in range(1, 5):
        w = np.zeros(n)
        for k in range(r):
            w += (-1) ** k * math.comb(r - 1, k) * _order_weights(n, r + t1 - 1 - k, t2 + k)
        lam.append(float(np.dot(w, y)) / r)
    l1, l2, l3, l4 = lam
    return c + l1, l2, l3 / l2 if l2 else math.nan, l4 / l2 if l2 else math.nan


def check_moment_stats(mean, std, skew, kurt) -> None:
    """Reject statistics no distribution has."""
    for name, v in (("mean", mean), ("std", std), ("skew", skew), ("kurt", kurt)):
        if not np.isfinite(v):
            raise FitError(f"{name} must be finite, got {v!r}")
    if std <= 0:
        raise FitError(f"std must be positive, got {std!r}")
    if kurt <= 1.0 + skew * skew:
        raise FitError(
            f"kurtosis {kurt:g} <= 1 + skew^2 = {1 + skew * skew:g}: no distribution has these moments "
            "(Pearson's inequality); check that kurt is Pearson's kurtosis (3 for the normal), not the "
            "excess kurtosis (pass fisher=True for excess kurtosis)"
        )


def check_rho(r1, r2, r3, r4) -> None:
    """Reject percentile statistics no continuous distribution has."""
    for name, v in (("rho1", r1), ("rho2", r2), ("rho3", r3), ("rho4", r4)):
        if not np.isfinite(v):
            raise FitError(f"{name} must be finite, got {v!r} (tied quantiles?)")
    if r2 <= 0 or r3 <= 0 or not (0 < r4 < 1):
        raise FitError(
            f"percentile statistics out of range: need rho2 > 0, rho3 > 0 and 0 < rho4 < 1, got "
            f"rho2={r2:g}, rho3={r3:g}, rho4={r4:g} (tied sample quantiles: too few distinct values)"
        )


def check_lmoment_stats(l1, l2, t3, t4) -> None:
    """Reject L-moment statistics no distribution has (Hosking's bounds)."""
    for name, v in (("l1", l1), ("l2", l2), ("t3", t3), ("t4", t4)):
        if not np.isfinite(v):
            raise FitError(f"{name} must be finite, got {v!r}")
    if l2 <= 0 or abs(t3) >= 1 or t4 < (5 * t3 * t3 - 1) / 4 or t4 >= 1:
        raise FitError(
            f"L-moments out of range: need l2 > 0, |t3| < 1 and (5 t3^2 - 1)/4 <= t4 < 1, got l2={l2:g}, "
            f"t3={t3:g}, t4={t4:g}"
        )


def check_tlmoment_stats(l1, l2, t3, t4) -> None:
    """Reject TL-moment statistics no distribution has (finite, positive TL-scale l2)."""
    for name, v in (("tl1", l1), ("tl2", l2), ("tt3", t3), ("tt4", t4)):
        if not np.isfinite(v):
            raise FitError(f"{name} must be finite, got {v!r}")
    if l2 <= 0:
        raise FitError(f"the TL-scale tl2 must be positive, got {l2:g} (ties: too few distinct "
                       "values between the trimmed ends)")


def shape_targets(kind: int, stats) -> tuple[float, float, float, float]:
    """(loc_stat, scale_stat, s1, s2) in the solver coordinates of ``kind``."""
    a, b, c, d = (float(v) for v in stats)
    if kind == K.MOMENTS:
        return a, b, c, math.log(d - c * c - 1.0)
    if kind == K.PERCENTILES:
        return a, b, math.log(c), d
    return a, b, c, d
