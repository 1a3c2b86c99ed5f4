"""How much of the area yields: the plastic area fraction of the elastic-perfectly-plastic BEM
over the surfaces of a case, its GLD, a 90 % interval and its check on held-out surfaces.

Each surface's capped solve (:func:`contact.solve_bem` with ``hardness=H``) gives one
fraction: the points at the hardness over the analysed area. Over the surfaces of a case these
fractions are a sample of the surface-to-surface scatter; a GLD fitted to them gives the
interval in which the fraction of one area lies with the interval's probability, and the
interval is checked as the study checks the maximum: fitted on one half of the surfaces, it
must hold the fractions of the other half at its level (an exact binomial test,
:func:`glstat.binomial_check`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .analysis_settings import CHECK_MAX_MISS, CHECK_POWER, CHECK_SIGNIFICANCE

__all__ = ["plastic_interval", "plastic_summary"]

#: GLD fits tried in turn for the fractions (FKML by L-moments exists for every sample whose
#: L-moment ratios a GLD reaches; RS by moments otherwise).
FITS = (("fkml", "lmoments"), ("rs", "moments"), ("fkml", "mle"))


def plastic_interval(fractions: np.ndarray, level: float) -> tuple[float, float, str]:
    """The central ``level`` interval of a GLD fitted to plastic area fractions, clipped to
    [0, 1], and the fit's name ("" when every value is equal: the interval is that value;
    "empirical quantiles" when no GLD could be fitted; "none" without values: NaN)."""
    import warnings

    import glstat

    x = np.asarray(fractions, dtype=float)
    if x.size and np.ptp(x) == 0:
        return float(x[0]), float(x[0]), ""
    alpha = (1.0 - level) / 2
    for param, method in FITS:
        try:
            with warnings.catch_warnings(record=True):  # a fit's warnings are not the caller's
                fit = glstat.fit(x, param, method)
                if not fit.ok:
                    continue
                low, high = fit.dist.ppf([alpha, 1.0 - alpha])
        except (ValueError, RuntimeError, ArithmeticError):
            continue
        if math.isfinite(low) and math.isfinite(high):
            return float(np.clip(low, 0.0, 1.0)), float(np.clip(high, 0.0, 1.0)), \
                f"{param.upper()} {method}"
    if x.size:  # no GLD fits (e.g. mostly zeros): the sample's own quantiles
        low, high = np.quantile(x, [alpha, 1.0 - alpha])
        return float(low), float(high), "empirical quantiles"
    return math.nan, math.nan, "none"


def plastic_summary(fractions, level: float = 0.9) -> dict[str, Any]:
    """The plastic area fraction of a case: mean, GLD interval and its held-out check.

    Parameters
    ----------
    fractions : array_like
        One plastic area fraction per surface (points at the hardness over the analysed area).
    level : float
        Level of the interval.

    Returns
    -------
    dict
        ``plastic_area_fraction`` (mean), ``plastic_area_fraction_low`` and ``_high`` (the
        interval of one area's fraction, from the GLD fitted to all surfaces),
        ``plastic_fit`` (the GLD), ``plastic_held_out`` (held-out fractions inside the interval
        fitted on the other half, "k of m"), ``plastic_p_value`` and ``plastic_check``
        ("passed", "failed", "not checkable", or "not checked" with fewer than 4 surfaces).
    """
    from ..gof.binomial_check import binomial_check

    x = np.asarray(fractions, dtype=float)
    low, high, fit = plastic_interval(x, level)
    out = {"plastic_area_fraction": float(x.mean()) if x.size else math.nan,
           "plastic_area_fraction_low": low, "plastic_area_fraction_high": high,
           "plastic_fit": fit, "plastic_held_out": "", "plastic_p_value": math.nan,
           "plastic_check": "not checked"}
    if x.size < 4:
        return out
    hits = 0
    for train, test in ((x[0::2], x[1::2]), (x[1::2], x[0::2])):
        lo, hi, _ = plastic_interval(train, level)
        hits += int(np.count_nonzero((test >= lo) & (test <= hi)))
    check = binomial_check(level, hits, x.size, significance=CHECK_SIGNIFICANCE,
                           power=CHECK_POWER, max_miss=CHECK_MAX_MISS, alternative="less")
    out.update(plastic_held_out=f"{hits} of {x.size}", plastic_p_value=check.p_value,
               plastic_check=check.verdict)
    return out
