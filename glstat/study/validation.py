"""Predictions checked on surfaces the fit did not see: two folds (even and odd surfaces), the
maximum of each held-out surface against its predicted interval, and the damage probability at
several hardness levels and area factors against the observed fraction of surfaces."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .analysis_settings import (
    AREA_CHECKS,
    PASS_FRACTION,
    AnalysisSettings,
    fit_order,
    pool,
    predict_sample,
    sample_rng,
)
from .fit_choice import choose_fit

__all__ = ["Validation", "hardness_levels", "validate_sample", "wilson_interval"]


def wilson_interval(k: int, n: int, level: float = 0.95) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion k/n (statsmodels' ``proportion_confint``).

    Parameters
    ----------
    k, n : int
        Successes and trials.
    level : float
        Confidence level.

    Returns
    -------
    (low, high) : tuple of float
        NaN for n < 1.
    """
    if n < 1:
        return math.nan, math.nan
    from statsmodels.stats.proportion import proportion_confint

    lo, hi = proportion_confint(int(k), int(n), alpha=1 - level, method="wilson")
    return max(0.0, float(lo)), min(1.0, float(hi))


@dataclass
class Validation:
    """Observed maximum of every held-out surface against its predicted interval.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per surface: ``surface``, ``fold``, ``n`` (points or asperities), ``observed``,
        ``predicted`` (mean of the predicted maximum), ``low``, ``high`` (predicted interval),
        ``covered``; pressures in MPa. The prediction for surface i is one random maximum
        of ``n_i`` draws per bootstrap GLD of the other fold.
    coverage : float
        Fraction of surfaces whose observed maximum lies in the predicted interval.
    coverage_interval : (float, float)
        Wilson 95 % interval of the coverage.
    t_statistic, t_pvalue : float
        One-sample t-test of mean(predicted − observed) = 0 (two-sided).
    w_pvalue : float
        Wilcoxon signed-rank test, for reference.
    reject : bool
        Whether the t-test rejects at the test level.
    theta : float
        Extremal index: the effective number of independent draws over the nominal n,
        ``m / sum_i n_i (-log F(M_i))`` (1 when the n values behave as independent draws).
    calibration : pandas.DataFrame
        Predicted against observed damage probability per hardness level and area factor
        (columns of ``damage_calibration.csv``).
    error : str
        Why the validation could not be done ("" when it was).
    """

    table: Any = None
    coverage: float = math.nan
    coverage_interval: tuple[float, float] = (math.nan, math.nan)
    t_statistic: float = math.nan
    t_pvalue: float = math.nan
    w_pvalue: float = math.nan
    reject: bool = False
    theta: float = math.nan
    calibration: Any = None
    error: str = ""

    def damage_hits(self, area_factor: float = 1) -> tuple[int, int]:
        """(levels whose prediction lies inside the observed interval, levels) for an area of
        ``area_factor`` analysed areas (groups of that many held-out surfaces; default one)."""
        c = self.calibration
        if c is None or len(c) == 0:
            return 0, 0
        one = c[c["area_factor"] == area_factor]
        inside = (one["predicted"] >= one["observed_low"]) & (one["predicted"] <= one["observed_high"])
        return int(inside.sum()), len(one)

    def passes(self, level: float) -> bool:
        """Whether the result passes its check: the coverage's Wilson interval contains the
        nominal level, the centring test does not reject, and the predicted damage lies inside
        the observed interval at >= 80 % of the hardness levels."""
        if self.error or self.table is None:
            return False
        hits, m = self.damage_hits()
        lo, hi = self.coverage_interval
        return bool(lo <= level <= hi and not self.reject and m and hits >= PASS_FRACTION * m)


def hardness_levels(maxima: np.ndarray, hardness: float, n_levels: int) -> np.ndarray:
    """Hardness levels spanning the observed per-surface maxima (quantiles 5 %–95 %) and the
    hardness itself, in MPa (rounded to 3 significant digits)."""
    q = np.quantile(maxima, np.linspace(0.05, 0.95, n_levels))
    levels = np.unique(np.concatenate([[hardness], q]))
    return np.unique(np.array([float(f"{v:.3g}") for v in levels]))


def validate_sample(per: list, sample: str, a: AnalysisSettings, ih: int, il: int, param: str, method: str,
              levels: np.ndarray) -> Validation:
    """Two-fold validation: fits on the even surfaces predict the odd ones and vice versa."""
    import pandas as pd
    from scipy import stats

    folds = [list(range(0, len(per), 2)), list(range(1, len(per), 2))]
    rows, cal, theta_terms = [], [], []
    for f in (0, 1):
        train, test = folds[1 - f], folds[f]
        if not train or not test:
            return Validation(error="needs at least two surfaces (one per fold)")
        x, labels, counts = pool([per[i] for i in train])
        if x.size < 5:
            return Validation(error=f"only {x.size} values in a fitting fold (at least 5 needed)")
        p, m, order = param, method, None
        if sample == "asperity":
            ch = choose_fit([per[i] for i in train])
            p, m, order = ch.param, ch.method, ch.order()
        grouped = sample == "asperity"
        pred = predict_sample(x, a, sample_rng(a, ih, il, 1 if sample == "grid" else 2, f),
                              fit_order(a, p, m, order), groups=labels if grouped else None,
                              n=None if grouped else max(float(counts.mean()), 1.0),
                              n_resamples=a.grid_resamples if sample == "grid" else None)
        bf = pred.boot
        if bf is None:
            return Validation(error=f"no {p.upper()} {m} fit of a fitting fold: {pred.note}")
        count_kw = pred.count_kwargs()
        tested = [i for i in test if per[i][1] >= 1]
        if tested:
            ns = np.array([per[i][1] for i in tested], dtype=float)
            obs = np.array([per[i][2] for i in tested])
            v = sample_rng(a, ih, il, 3 if sample == "grid" else 4, f).random((bf.n_successful, len(tested)))
            draws = bf.maximum_quantiles(ns[None, :], v)
            alpha = 1 - a.confidence_level
            lo, hi = np.nanquantile(draws, [alpha / 2, 1 - alpha / 2], axis=0)
            pred = np.nanmean(draws, axis=0)
            for j, i in enumerate(tested):
                rows.append({"surface": i, "fold": f, "n": int(ns[j]), "observed": obs[j],
                             "predicted": pred[j], "low": lo[j], "high": hi[j],
                             "covered": bool(lo[j] <= obs[j] <= hi[j])})
            theta_terms.extend(ns * -np.asarray(bf.fit.dist.logcdf(obs), dtype=float))
        # damage on one area and on k areas (groups of k held-out surfaces)
        maxima = np.array([per[i][2] for i in test])
        for k in (1, *AREA_CHECKS):
            groups = len(test) // k
            if groups < 2:
                continue
            gmax = maxima[: groups * k].reshape(groups, k).max(axis=1)
            for lv in levels:
                d = bf.damage_probability(lv, area_factor=float(k), **count_kw)
                cal.append({"fold": f, "hardness_mpa": float(lv), "area_factor": k,
                            "predicted": float(np.ravel(d.estimate)[0]),
                            "hits": int(np.sum(gmax > lv)), "n_surfaces": int(groups)})
    if not rows:
        return Validation(error="no held-out surface has a contact")
    table = pd.DataFrame(rows).sort_values("surface", ignore_index=True)
    k_cov, mcount = int(table["covered"].sum()), len(table)
    diff = (table["predicted"] - table["observed"]).to_numpy()
    val = Validation(table=table, coverage=k_cov / mcount,
                     coverage_interval=wilson_interval(k_cov, mcount))
    if mcount >= 3 and np.ptp(diff) > 0:
        t = stats.ttest_1samp(diff, 0.0)
        val.t_statistic, val.t_pvalue = float(t.statistic), float(t.pvalue)
        val.w_pvalue = float(stats.wilcoxon(diff).pvalue)
        val.reject = bool(val.t_pvalue < 1 - a.test_level)
    terms = np.asarray(theta_terms)
    if terms.size and np.all(np.isfinite(terms)) and terms.sum() > 0:
        val.theta = float(terms.size / terms.sum())
    if cal:
        c = pd.DataFrame(cal)
        # pool the folds: predictions weighted by the surfaces they predict
        c["wpred"] = c["predicted"] * c["n_surfaces"]
        g = c.groupby(["hardness_mpa", "area_factor"], as_index=False)[["wpred", "hits",
                                                                         "n_surfaces"]].sum()
        g["predicted"] = g["wpred"] / g["n_surfaces"]
        g["observed"] = g["hits"] / g["n_surfaces"]
        ci = [wilson_interval(h, n) for h, n in zip(g["hits"], g["n_surfaces"], strict=True)]
        g["observed_low"] = [c_[0] for c_ in ci]
        g["observed_high"] = [c_[1] for c_ in ci]
        val.calibration = g.drop(columns=["wpred", "hits"])[
            ["hardness_mpa", "area_factor", "predicted", "observed", "observed_low", "observed_high",
             "n_surfaces"]]
    return val


