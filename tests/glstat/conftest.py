"""Shared parameter sets for the GLD distribution tests.

Every case is ``(id, lam3, lam4, loc, scale)`` for ``glstat.gld_rs`` / ``glstat.gld_fkml``
(``loc`` = lambda1, ``scale`` = 1/|lambda2|). The RS cases cover all six regions of
Karian & Dudewicz, including the region edges that are themselves valid (lambda3 = 0 or
lambda4 = 0 in regions 3/4, lambda3 = -1 with lambda4 = 1 in region 1, ...). The FKML cases
span shapes from -3 to 5 with exact zeros and tiny (1e-12) values.

Literature values used as cases (docs/method.md §14):
N(0, 1) by RS moments (0, 0.197451, 0.134912, 0.134912); Uniform(0, 1) RS (0.5, 2, 1, 1);
Gamma(5, scale 3) RS moments (10.7621, 0.014452, 0.0251988, 0.093884);
N(0, 1) by FKML moments (0, 1.46355, 0.134912, 0.134912).
"""

from __future__ import annotations

import numpy as np
import pytest

import glstat

# (id, lam3, lam4, loc, scale, region)
RS_CASES = [
    ("r1", -1.5, 1.5, 0.0, 1.0, 1),
    ("r1-edge", -1.0, 1.0, 2.0, 0.5, 1),
    ("r1-wide", -3.0, 2.0, 0.0, 1.0, 1),
    ("r2", 1.5, -1.5, 0.0, 1.0, 2),
    ("r2-edge", 1.0, -1.0, -1.0, 3.0, 2),
    ("r2-wide", 2.0, -3.0, 0.0, 1.0, 2),
    ("r3-normal", 0.134912, 0.134912, 0.0, 1.0 / 0.197451, 3),
    ("r3-uniform", 1.0, 1.0, 0.5, 0.5, 3),
    ("r3-gamma", 0.0251988, 0.093884, 10.7621, 1.0 / 0.014452, 3),
    ("r3-l3zero", 0.0, 0.5, 0.0, 1.0, 3),
    ("r3-l4zero", 2.0, 0.0, 1.0, 2.0, 3),
    ("r3-steep", 5.0, 0.2, 0.0, 1.0, 3),
    ("r4", -0.1, -0.2, 0.0, 1.0, 4),
    ("r4-l3zero", 0.0, -0.3, 0.0, 1.0, 4),
    ("r4-l4zero", -0.15, 0.0, 1.0, 0.25, 4),
    ("r4-mid", -0.4, -0.3, 0.0, 1.0, 4),
    ("r4-heavy", -1.5, -2.0, 0.0, 1.0, 4),
    ("r5", -0.5, 2.0, 0.0, 1.0, 5),
    ("r5-near", -0.7, 1.5, 0.0, 1.0, 5),
    ("r5-long", -0.3, 5.0, 3.0, 2.0, 5),
    ("r6", 2.0, -0.5, 0.0, 1.0, 6),
    ("r6-near", 1.5, -0.7, 0.0, 1.0, 6),
]

# (id, lam3, lam4, loc, scale)
FKML_CASES = [
    ("logistic", 0.0, 0.0, 0.0, 1.0),
    ("normal", 0.134912, 0.134912, 0.0, 1.0 / 1.46355),
    ("tiny", 1e-12, 1e-12, 0.0, 1.0),
    ("tiny-mixed", -1e-12, 1e-12, 1.0, 2.0),
    ("zero-tiny", 0.0, -1e-12, 0.0, 1.0),
    ("zero-one", 0.0, 1.0, 0.0, 1.0),
    ("one-zero", 1.0, 0.0, -2.0, 0.5),
    ("neg3-pos5", -3.0, 5.0, 0.0, 1.0),
    ("pos5-neg3", 5.0, -3.0, 0.0, 1.0),
    ("pos5", 5.0, 5.0, 0.0, 1.0),
    ("neg3", -3.0, -3.0, 0.0, 1.0),
    ("cauchy-like", -1.0, -1.0, 0.0, 1.0),
    ("skew", -0.5, 2.0, 1.0, 3.0),
    ("mild", 0.25, -0.2, 0.0, 1.0),
]


def _rs_param(case):
    cid, a, b, loc, scale, _region = case
    return pytest.param(glstat.gld_rs, a, b, loc, scale, id=f"rs-{cid}")


def _fkml_param(case):
    cid, a, b, loc, scale = case
    return pytest.param(glstat.gld_fkml, a, b, loc, scale, id=f"fkml-{cid}")


ALL_CASES = [_rs_param(c) for c in RS_CASES] + [_fkml_param(c) for c in FKML_CASES]
"""pytest params ``(dist, lam3, lam4, loc, scale)`` over both parameterisations."""

CASE_NAMES = "dist, lam3, lam4, loc, scale"


def has_moment(lam3: float, lam4: float, k: int) -> bool:
    """True when the k-th moment exists (docs/method.md §14: min(lam3, lam4) > -1/k)."""
    return min(lam3, lam4) * k > -1.0


def quantile_grid(n_tail: int = 6) -> np.ndarray:
    """Probabilities from 1e-(n_tail*2) to 1 - 1e-(n_tail*2) with a dense middle part."""
    tails = 10.0 ** -np.arange(2 * n_tail, 1, -2)
    mid = np.linspace(0.02, 0.98, 25)
    return np.concatenate([tails, mid, 1.0 - tails[::-1]])


def rs_lambda2_sign(lam3: float, lam4: float) -> float:
    """Sign of lambda2 in the RS region of (lam3, lam4): + in region 3, - elsewhere (docs/method.md §4)."""
    return 1.0 if (lam3 >= 0 and lam4 >= 0) else -1.0


def gld_of(dist, lam3, lam4, loc, scale) -> glstat.GLD:
    """The same distribution built in lambda notation through ``glstat.GLD``."""
    if dist is glstat.gld_rs:
        return glstat.GLD(loc, rs_lambda2_sign(lam3, lam4) / scale, lam3, lam4, param="rs")
    return glstat.GLD(loc, 1.0 / scale, lam3, lam4, param="fkml")


def q_terms(dist, lam3: float, lam4: float, u: float):
    """Reference standardized Q(u) and the magnitudes of its two terms, by mpmath (40 digits).

    Straight from the definitions in docs/method.md §14:
    RS   Q(u) = s (u^l3 - (1-u)^l4), s = sign of lambda2 in the region;
    FKML Q(u) = (u^l3 - 1)/l3 - ((1-u)^l4 - 1)/l4, with log limits at 0.
    The term magnitudes bound the rounding error of any evaluation of the difference.
    """
    import mpmath

    with mpmath.workdps(40):
        u = mpmath.mpf(float(u))
        v = 1 - u
        a = mpmath.mpf(float(lam3))
        b = mpmath.mpf(float(lam4))

        def power(x, e):
            if e == 0:
                return mpmath.mpf(1)
            if x == 0:
                return mpmath.inf if e < 0 else mpmath.mpf(0)
            return x**e

        def boxcox(x, e):
            if e == 0:
                return mpmath.log(x) if x > 0 else -mpmath.inf
            if x == 0:
                return -mpmath.inf if e < 0 else -1 / e
            return mpmath.expm1(e * mpmath.log(x)) / e

        if dist is glstat.gld_rs:
            s = rs_lambda2_sign(lam3, lam4)
            t1, t2 = power(u, a), power(v, b)
            q = s * (t1 - t2)
        else:
            t1, t2 = boxcox(u, a), boxcox(v, b)
            q = t1 - t2
        return float(q), float(abs(t1)), float(abs(t2))


def qprime(dist, lam3: float, lam4: float, u: float) -> float:
    """Reference standardized Q'(u) by mpmath from the closed forms of docs/method.md §14."""
    import mpmath

    with mpmath.workdps(40):
        u = mpmath.mpf(float(u))
        v = 1 - u
        a = mpmath.mpf(float(lam3))
        b = mpmath.mpf(float(lam4))
        if dist is glstat.gld_rs:
            s = rs_lambda2_sign(lam3, lam4)
            ta = a * u ** (a - 1) if a != 0 else 0
            tb = b * v ** (b - 1) if b != 0 else 0
            return float(s * (ta + tb))
        return float(u ** (a - 1) + v ** (b - 1))


def qsecond(dist, lam3: float, lam4: float, u: float) -> float:
    """Reference standardized Q''(u) (mpmath), used to bound how x-rounding moves the pdf."""
    import mpmath

    with mpmath.workdps(40):
        u = mpmath.mpf(float(u))
        v = 1 - u
        a = mpmath.mpf(float(lam3))
        b = mpmath.mpf(float(lam4))
        if dist is glstat.gld_rs:
            s = rs_lambda2_sign(lam3, lam4)
            ta = a * (a - 1) * u ** (a - 2) if a not in (0, 1) else 0
            tb = b * (b - 1) * v ** (b - 2) if b not in (0, 1) else 0
            return float(s * (ta - tb))
        ta = (a - 1) * u ** (a - 2) if a != 1 else 0
        tb = (b - 1) * v ** (b - 2) if b != 1 else 0
        return float(ta - tb)
