"""Validity regions of the GLD parameterisations.

RS (Ramberg–Schmeiser) is valid in six regions of (lambda3, lambda4), each fixing the sign of
lambda2 (Karian & Dudewicz, *Handbook of Fitting Statistical Distributions with R*, 2011,
Theorem 1.3.23):

====== ======= ============ ============ ==============================================
region lambda2 lambda3      lambda4      extra condition
====== ======= ============ ============ ==============================================
1      < 0     <= -1        >= 1
2      < 0     >= 1         <= -1
3      > 0     >= 0         >= 0         not both 0
4      < 0     <= 0         <= 0         not both 0
5      < 0     (-1, 0)      > 1          (1-l3)^(1-l3) (l4-1)^(l4-1) / (l4-l3)^(l4-l3) < -l3/l4
6      < 0     > 1          (-1, 0)      the same with l3 and l4 exchanged
====== ======= ============ ============ ==============================================

FKML is valid for every finite (lambda3, lambda4) with lambda2 > 0.
"""

from __future__ import annotations

import numpy as np

from _glstat_runtime.validation import check_param

from .errors import InvalidParameterError

__all__ = ["check_lambdas", "fkml_valid", "rs_region", "rs_valid"]



def _region56_inequality(a, b):
    """Region 5 condition for a in (-1, 0), b > 1, evaluated in logs without cancellation.

    With c = 1 - a and d = b - 1 the condition c log c + d log d - (c + d) log(c + d) <
    log(-a) - log(b) reads

        g = -c log1p(d/c) - d log1p(c/d) - log(-a) + log1p(d) < 0,

    a sum of terms of the size of log(b): the form with the three x log x terms loses
    eps * b log b to cancellation (every digit once b exceeds ~1e13).
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        c = 1.0 - a
        d = b - 1.0
        # d log1p(c/d) -> c as d -> inf and -> 0 as d -> 0 (xlogy-like limit at d = 0)
        t = np.where(d > 0, d * np.log1p(c / np.where(d > 0, d, 1.0)), 0.0)
        g = -c * np.log1p(d / c) - t - np.log(-a) + np.log1p(d)
    return g < 0


def rs_region(lam3, lam4):
    """RS region number (1-6) of each (lambda3, lambda4); 0 where no region contains it.

    Parameters
    ----------
    lam3, lam4 : array_like
        Shape parameters lambda3 and lambda4 (broadcast together).

    Returns
    -------
    ndarray of int
    """
    a, b = np.broadcast_arrays(np.asarray(lam3, dtype=float), np.asarray(lam4, dtype=float))
    shape = a.shape
    a = a.ravel()
    b = b.ravel()
    out = np.zeros(a.shape, dtype=int)
    finite = np.isfinite(a) & np.isfinite(b)
    with np.errstate(invalid="ignore"):
        not_both_zero = ~((a == 0) & (b == 0))
        out[finite & (a >= 0) & (b >= 0) & not_both_zero] = 3
        out[finite & (a <= 0) & (b <= 0) & not_both_zero] = 4
        out[finite & (a <= -1) & (b >= 1)] = 1
        out[finite & (a >= 1) & (b <= -1)] = 2
        m5 = finite & (a > -1) & (a < 0) & (b > 1)
        m5[m5] = _region56_inequality(a[m5], b[m5])
        out[m5] = 5
        m6 = finite & (b > -1) & (b < 0) & (a > 1)
        m6[m6] = _region56_inequality(b[m6], a[m6])
        out[m6] = 6
    return out.reshape(shape)


def rs_valid(lam3, lam4):
    """True where (lambda3, lambda4) lies in an RS region."""
    return rs_region(lam3, lam4) > 0


def fkml_valid(lam3, lam4):
    """True where (lambda3, lambda4) are finite (every finite pair is a valid FKML GLD)."""
    a, b = np.broadcast_arrays(np.asarray(lam3, dtype=float), np.asarray(lam4, dtype=float))
    return np.isfinite(a) & np.isfinite(b)


def rs_lambda2_sign(lam3, lam4):
    """Sign lambda2 must have in the RS region of (lambda3, lambda4): +1 in region 3, else -1."""
    return np.where((np.asarray(lam3) >= 0) & (np.asarray(lam4) >= 0), 1.0, -1.0)


def _describe_rs_failure(l3: float, l4: float) -> str:
    if -1 < l3 < 0 and l4 > 1:
        return (
            f"(lambda3, lambda4) = ({l3:g}, {l4:g}) has -1 < lambda3 < 0 and lambda4 > 1 but fails "
            "the region 5 condition (1-l3)^(1-l3) (l4-1)^(l4-1) / (l4-l3)^(l4-l3) < -l3/l4, so Q(u) "
            "is not monotone"
        )
    if -1 < l4 < 0 and l3 > 1:
        return (
            f"(lambda3, lambda4) = ({l3:g}, {l4:g}) has -1 < lambda4 < 0 and lambda3 > 1 but fails "
            "the region 6 condition (1-l4)^(1-l4) (l3-1)^(l3-1) / (l3-l4)^(l3-l4) < -l4/l3, so Q(u) "
            "is not monotone"
        )
    if l3 == 0 and l4 == 0:
        return "lambda3 = lambda4 = 0 gives a constant quantile function (a degenerate distribution)"
    return (
        f"(lambda3, lambda4) = ({l3:g}, {l4:g}) lies in none of the six RS regions (lambda3 and "
        "lambda4 of opposite signs are valid only in regions 1, 2, 5 and 6: one of them <= -1 with "
        "the other >= 1, or one in (-1, 0) with the other > 1 and the region 5/6 condition)"
    )


def check_lambdas(l1, l2, l3, l4, param: str = "rs") -> int:
    """Validate GLD parameters in lambda notation.

    Parameters
    ----------
    l1, l2, l3, l4 : float
        Location, inverse scale and the two shape parameters.
    param : {"rs", "fkml"}
        Parameterisation.

    Returns
    -------
    int
        The RS region (1-6), or 0 for FKML.

    Raises
    ------
    InvalidParameterError
        Naming the violated condition; for RS also the region of (lambda3, lambda4) and the
        sign lambda2 needs there.
    """
    param = check_param(param)
    values = {"lambda1": l1, "lambda2": l2, "lambda3": l3, "lambda4": l4}
    for name, v in values.items():
        if np.ndim(v) != 0:
            raise InvalidParameterError(f"{name} must be a scalar, got an array of shape {np.shape(v)}")
        if not np.isfinite(v):
            raise InvalidParameterError(f"{name} must be finite, got {v!r}")
    l1, l2, l3, l4 = (float(v) for v in (l1, l2, l3, l4))
    if l2 == 0:
        raise InvalidParameterError("lambda2 must be non-zero (it is the inverse of the scale)")
    if param == "fkml":
        if l2 < 0:
            raise InvalidParameterError(
                f"FKML needs lambda2 > 0, got lambda2 = {l2:g}; use lambda2 = {-l2:g} "
                "(an FKML GLD with negative lambda2 is not a distribution)"
            )
        return 0
    region = int(rs_region(l3, l4))
    if region == 0:
        raise InvalidParameterError("invalid RS GLD: " + _describe_rs_failure(l3, l4))
    need = 1.0 if region == 3 else -1.0
    if np.sign(l2) != need:
        raise InvalidParameterError(
            f"invalid RS GLD: (lambda3, lambda4) = ({l3:g}, {l4:g}) lies in region {region}, where "
            f"lambda2 must be {'positive' if need > 0 else 'negative'}; got lambda2 = {l2:g}. "
            f"Did you mean lambda2 = {-l2:g}? (published tables often print |lambda2| for "
            "regions 1, 2, 4, 5 and 6)"
        )
    return region
