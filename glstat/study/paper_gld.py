"""The RS GLDs behind Table 1 of the paper: the moments of any λ's (:func:`lambda_moments`, also
for a row that is not a valid GLD), the mirror image about the mean (:func:`mirror_lambdas`),
how printed λ's that are not a valid GLD are read (:func:`as_distribution`), and the damage
``1 − F(Pd)^n`` at the hardness with the range of n that reproduces a claim of the paper.

Pressures in MPa, as printed in the paper.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from .paper_table import CLAIM_RANGES

if TYPE_CHECKING:  # pragma: no cover
    from ..distributions.gld import GLD

__all__ = [
    "as_distribution",
    "claim_n_range",
    "damage_at",
    "gld_support",
    "lambda_moments",
    "mirror_lambdas",
    "other_readings",
    "valid_gld",
]

_NAN = float("nan")


def lambda_moments(l1: float, l2: float, l3: float, l4: float) -> tuple[float, float, float, float]:
    """Mean, standard deviation, skewness and kurtosis of ``Q(U)``, U uniform on (0, 1).

    ``Q(u) = λ1 + (u^λ3 − (1 − u)^λ4) / λ2`` (RS). ``Q(U)`` is a random variable for any λ's,
    whether or not ``Q`` is increasing (a valid quantile function), so this also gives the
    moments of a printed row that is not a valid GLD. Computed from the raw moments of
    ``Z = U^λ3 − (1 − U)^λ4``, ``E Z^k = Σ_j C(k, j) (−1)^j B(λ3 (k − j) + 1, λ4 j + 1)``, in
    50-digit arithmetic (mpmath), so the differences of beta functions do not cancel.

    Parameters
    ----------
    l1, l2, l3, l4 : float
        λ1 (units of x), λ2 (1 / units of x), λ3, λ4; the 4th moment needs
        ``min(λ3, λ4) > −1/4``.

    Returns
    -------
    (mean, sd, skewness, kurtosis)
        In the units of λ1 (mean, sd); skewness and Pearson's kurtosis dimensionless. NaN
        where a moment does not exist.

    Examples
    --------
    >>> from glstat.study.paper import lambda_moments
    >>> [round(v, 3) for v in lambda_moments(0, 0.197451, 0.134912, 0.134912)]  # ~ N(0, 1)
    [0.0, 1.0, 0.0, 3.0]
    """
    import mpmath as mp

    if not (l2 != 0 and all(math.isfinite(v) for v in (l1, l2, l3, l4))):
        return (_NAN,) * 4
    if min(l3, l4) <= -0.25:
        return (_NAN,) * 4
    with mp.workdps(50):
        a, b = mp.mpf(l3), mp.mpf(l4)
        ez = []
        for k in range(1, 5):
            ez.append(mp.fsum(mp.binomial(k, j) * (-1) ** j * mp.beta(a * (k - j) + 1, b * j + 1)
                              for j in range(k + 1)))
        m1, m2, m3, m4 = ez
        v = m2 - m1 ** 2
        mu3 = m3 - 3 * m1 * m2 + 2 * m1 ** 3
        mu4 = m4 - 4 * m1 * m3 + 6 * m1 ** 2 * m2 - 3 * m1 ** 4
        mean = mp.mpf(l1) + m1 / mp.mpf(l2)
        sd = mp.sqrt(v) / abs(mp.mpf(l2))
        skew = mu3 / v ** mp.mpf(1.5) * (1 if l2 > 0 else -1)
        kurt = mu4 / v ** 2
        return (float(mean), float(sd), float(skew), float(kurt))


def mirror_lambdas(lambdas: Sequence[float], mean: float) -> tuple[float, float, float, float]:
    """λ's of the mirror image ``2 α1 − X`` of the RS GLD X about its mean α1.

    ``2 α1 − Q(1 − u) = (2 α1 − λ1) + (u^λ4 − (1 − u)^λ3) / λ2``: the mirror has
    ``(2 α1 − λ1, λ2, λ4, λ3)`` — the same mean, standard deviation and kurtosis and the
    opposite skewness.

    Parameters
    ----------
    lambdas : (λ1, λ2, λ3, λ4)
        RS λ's (λ1 in the units of x, λ2 in 1 / units).
    mean : float
        α1, the mean of X (units of x).

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> from glstat.study.paper import mirror_lambdas
    >>> mirror_lambdas((1000.0, 0.002, 0.1, 0.3), 1070.0)
    (1140.0, 0.002, 0.3, 0.1)
    """
    l1, l2, l3, l4 = (float(v) for v in lambdas)
    return (2.0 * float(mean) - l1, l2, l4, l3)


def other_readings(l1: float, l2: float, l3: float,
                   l4: float) -> list[tuple[str, tuple[float, float, float, float]]]:
    """The readings of printed RS λ's other than as printed, in order of preference: the sign
    of λ2 changed (tables often print |λ2| where the region needs λ2 < 0), and the random
    variable ``Q(U)`` for a decreasing ``Q``, whose quantile function is ``Q(1 − u)``, the RS
    GLD ``(λ1, −λ2, λ4, λ3)``; each as (its name, its λ's)."""
    return [("λ2 sign changed", (l1, -l2, l3, l4)), ("Q(U), decreasing Q", (l1, -l2, l4, l3))]


def valid_gld(lambdas: tuple[float, float, float, float]) -> GLD | None:
    """The RS GLD of ``lambdas``, or None when they are not a valid one."""
    from ..distributions.gld import GLD
    from ..errors import InvalidParameterError

    try:
        return GLD(*lambdas)
    except InvalidParameterError:
        return None


def as_distribution(l1: float, l2: float, l3: float, l4: float):
    """The distribution printed RS λ's stand for, and how they were read.

    Readings, in this order, the first valid one wins: the λ's as printed; with the sign of
    λ2 changed (tables often print |λ2| where the region needs λ2 < 0, as the
    :class:`glstat.InvalidParameterError` message says); the random variable ``Q(U)`` for a
    decreasing ``Q`` (e.g. λ2 > 0 with λ3, λ4 < 0), whose quantile function is ``Q(1 − u)``, the
    RS GLD ``(λ1, −λ2, λ4, λ3)``.

    Parameters
    ----------
    l1, l2, l3, l4 : float
        RS λ's as printed.

    Returns
    -------
    (GLD or None, str, str)
        The distribution, the reading (``"as printed"``, ``"λ2 sign changed"``,
        ``"Q(U), decreasing Q"``, or ``""`` when none is valid) and the
        :class:`glstat.InvalidParameterError` text of the λ's as printed (``""`` when valid).

    Examples
    --------
    >>> from glstat.study.paper import as_distribution
    >>> g, reading, err = as_distribution(1700.0, 0.002, -0.1, -0.05)
    >>> reading, g.lambdas
    ('λ2 sign changed', (1700.0, -0.002, -0.1, -0.05))
    """
    from ..distributions.gld import GLD
    from ..errors import InvalidParameterError

    try:
        return GLD(l1, l2, l3, l4), "as printed", ""
    except InvalidParameterError as exc:
        err = str(exc)
    for reading, lam in other_readings(l1, l2, l3, l4):
        g = valid_gld(lam)
        if g is not None:
            return g, reading, err
    return None, "", err


def gld_support(g) -> tuple[float, float]:
    """The end points of the support of the GLD ``g``, as floats."""
    lo, hi = g.support()
    return float(lo), float(hi)


def damage_at(g, hardness: float, n: float) -> float:
    """``1 − F(hardness)^n`` of the GLD ``g`` (0 or 1 beyond the ends of its support)."""
    from ..extremes.damage import damage_probability

    return float(damage_probability(g, hardness, n, outside_support="limit"))


def claim_n_range(g, hardness: float, claim: str) -> tuple[float, float]:
    """[n_low, n_high] (n >= 1) over which 1 − F(Pd)^n lies in CLAIM_RANGES[claim]; (nan, nan)
    when no n >= 1 does."""
    lo_p, hi_p = CLAIM_RANGES[claim]
    lo_s, hi_s = gld_support(g)
    if hardness >= hi_s:
        log_f = 0.0
    elif hardness <= lo_s:
        log_f = -math.inf
    else:
        log_f = float(g.logcdf(hardness))
    if log_f == 0.0:  # never damaged
        return (1.0, math.inf) if lo_p == 0.0 else (_NAN, _NAN)
    if log_f == -math.inf:  # always damaged
        return (1.0, math.inf) if hi_p >= 1.0 else (_NAN, _NAN)
    # D(n) = 1 - exp(n log F) increases with n: lo_p <= D <= hi_p  <=>  n in [n_lo, n_hi]
    n_lo = math.log1p(-lo_p) / log_f if lo_p > 0 else 0.0
    n_hi = math.log1p(-hi_p) / log_f if hi_p < 1 else math.inf
    n_lo = max(n_lo, 1.0)
    return (n_lo, n_hi) if n_hi >= n_lo else (_NAN, _NAN)
