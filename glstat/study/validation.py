"""Predictions checked on surfaces the fit did not see: two folds (even and odd surfaces), the
maximum of each held-out surface against its predicted interval, and the damage probability at
several hardness levels and area factors against the observed fraction of surfaces.

The verdict's two checks fail only when the held-out surfaces disagree with the prediction:
the damage at the hardness when the number of damaged surfaces lies significantly outside the
predicted interval of the damage probability, the coverage of the maximum's interval when it
falls significantly short of the interval's level (an interval that covers more often is
reported as conservative)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..formatting import fmt_probability
from .analysis_settings import (
    AREA_CHECKS,
    CHECK_MAX_MISS,
    CHECK_POWER,
    CHECK_SIGNIFICANCE,
    GROUPED_SAMPLES,
    MORE_SURFACES,
    SEED_SLOTS,
    AnalysisSettings,
    fit_order,
    pool,
    predict_sample,
    sample_rng,
)
from .fit_choice import choose_fit

__all__ = ["Validation", "hardness_levels", "held_out_check", "validate_sample", "wilson_interval"]


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
        (columns of ``damage_calibration.csv``, with ``predicted_low`` and
        ``predicted_high``, the predicted interval, and ``p_value``, the exact binomial
        test of the observed count against that interval).
    damage_check : glstat.BinomialCheck or None
        The predicted damage probability at the hardness on one area, with its interval,
        against the fraction of held-out surfaces whose maximal pressure exceeds it: failed
        only when the count lies significantly outside the interval (exact binomial tests).
    coverage_check : glstat.BinomialCheck or None
        The number of held-out maxima inside their predicted interval against the interval's
        level, one-sided: failed only when they are significantly fewer (exact binomial
        test); significantly more make it :attr:`~glstat.BinomialCheck.conservative`.
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
    damage_check: Any = None
    coverage_check: Any = None
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

    def verdict(self) -> str:
        """The held-out check: ``"failed"`` when the number of damaged held-out surfaces lies
        significantly outside the predicted interval of the damage probability at the
        hardness, or the maximum's interval covers significantly less often than its level
        (exact binomial tests at 5 %); ``"not checkable"`` when neither is rejected but the
        held-out surfaces are too few to detect a miss of 20 percentage points beyond the
        prediction with 80 % power (or the damage interval leaves no room for one);
        ``"passed"`` otherwise; ``"not checked"`` without a validation."""
        checks = [c for c in (self.damage_check, self.coverage_check) if c is not None]
        if self.error or self.table is None or len(checks) < 2:
            return "not checked"
        if any(c.verdict == "failed" for c in checks):
            return "failed"
        if any(c.verdict == "not checkable" for c in checks):
            return "not checkable"
        return "passed"

    def passes(self, level: float | None = None) -> bool:
        """Whether the result passes its check (:meth:`verdict` is ``"passed"``); ``level``
        is accepted for compatibility (the coverage check uses the interval's own level)."""
        return self.verdict() == "passed"

    def short_text(self) -> str:
        """The verdict in a few words, for a table cell: what failed, or how many held-out
        surfaces a check would need."""
        v = self.verdict()
        d, c = self.damage_check, self.coverage_check
        if v == "not checked":
            return f"not checked ({self.error})" if self.error else "not checked"
        if v == "failed":
            parts = []
            if d is not None and d.verdict == "failed":
                parts.append(f"{d.hits} of {d.n} held-out surfaces damaged, "
                             f"{fmt_probability(d.predicted)} [{fmt_probability(d.low)}, "
                             f"{fmt_probability(d.high)}] predicted (p = {d.p_value:.2g})")
            if c is not None and c.verdict == "failed":
                parts.append(f"{c.hits} of {c.n} held-out maxima inside the "
                             f"{fmt_probability(c.predicted)} interval (one-sided p = "
                             f"{c.p_value:.2g})")
            return "failed: " + "; ".join(parts)
        miss = max(x.detectable_miss for x in (d, c))
        if v == "not checkable":
            if d.verdict == "not checkable" and d.too_wide_to_check:
                return (f"not checkable: the predicted damage interval [{fmt_probability(d.low)}, "
                        f"{fmt_probability(d.high)}] is too wide to be checked")
            if not math.isfinite(miss):
                return (f"not checkable with {d.n} held-out surfaces: no miss, however large, "
                        f"would show")
            return (f"not checkable with {d.n} held-out surfaces: misses under "
                    f"{_pp(miss)} go undetected")
        wide = (f"; the interval of the maximum is conservative ({c.hits} of {c.n} inside)"
                if c.conservative else "")
        return f"passed ({d.hits} of {d.n} damaged; a miss of {_pp(miss)} would show{wide})"

    def verdict_text(self) -> str:
        """The verdict with the reason, in one line (for the report and the command)."""
        v = self.verdict()
        if v == "not checked":
            return f"not checked ({self.error})" if self.error else "not checked"
        parts = []
        if self.damage_check is not None:
            parts.append("damage " + self.damage_check.text())
        if self.coverage_check is not None:
            parts.append("coverage of the maximum " + self.coverage_check.text())
        return f"{v} — " + "; ".join(parts)


def _pp(d: float) -> str:
    return "any size" if not math.isfinite(d) else f"{100 * d:.2g} percentage points"


def held_out_check(predicted: float, hits: int, n: int, *, interval=None,
                   alternative: str = "two-sided"):
    """:func:`glstat.binomial_check` at the study's level, power and largest undetected miss.

    Parameters
    ----------
    predicted : float
        The predicted probability (clipped to [0, 1]).
    hits, n : int
        Held-out surfaces (or groups) with the event, and held-out surfaces.
    interval : (float, float), optional
        The predicted interval of the probability: the check then fails only when ``hits``
        lies significantly outside it. It is widened to hold ``predicted`` should it leave
        it out, and clipped to [0, 1].
    alternative : {"two-sided", "less", "greater"}
        As in :func:`glstat.binomial_check`; ``"less"`` for the coverage of an interval
        against its level (only a shortfall fails).

    Returns
    -------
    glstat.BinomialCheck
    """
    from ..gof.binomial_check import binomial_check

    p = _clip(predicted)
    if interval is not None:
        low, high = (_clip(v) for v in interval)
        interval = (p if math.isnan(low) else min(low, p), p if math.isnan(high) else max(high, p))
    return binomial_check(p, int(hits), int(n), interval=interval, alternative=alternative,
                          significance=CHECK_SIGNIFICANCE, power=CHECK_POWER,
                          max_miss=CHECK_MAX_MISS)


def _clip(p: float) -> float:
    """A probability clipped to [0, 1] (NaN stays NaN)."""
    p = float(p)
    return p if math.isnan(p) else min(max(p, 0.0), 1.0)


def hardness_levels(maxima: np.ndarray, hardness: float, n_levels: int) -> np.ndarray:
    """Hardness levels spanning the observed per-surface maxima (quantiles 5 %–95 %, rounded
    to 3 significant digits) and the hardness itself (exact), in MPa."""
    q = np.quantile(maxima, np.linspace(0.05, 0.95, n_levels))
    return np.unique(np.concatenate([[float(hardness)], [float(f"{v:.3g}") for v in q]]))


def validate_sample(per: list, sample: str, a: AnalysisSettings, ih: int, il: int, param: str, method: str,
              levels: np.ndarray, advice: str = MORE_SURFACES) -> Validation:
    """Two-fold validation: fits on the even surfaces predict the odd ones and vice versa.

    ``advice`` says what to do when the surfaces are too few, in options the study's mode
    accepts."""
    import pandas as pd
    from scipy import stats

    folds = [list(range(0, len(per), 2)), list(range(1, len(per), 2))]
    rows, cal, theta_terms = [], [], []
    for f in (0, 1):
        train, test = folds[1 - f], folds[f]
        if not train or not test:
            return Validation(error=f"needs at least two surfaces (one per fold): {advice}")
        if sample in GROUPED_SAMPLES and len(train) < 2:
            return Validation(error=f"needs at least four surfaces: each half predicts the other, "
                                    f"and an interval resamples whole surfaces, at least two per "
                                    f"half; {advice}")
        x, labels, counts = pool([per[i] for i in train])
        if x.size < 5:
            return Validation(error=f"only {x.size} values in a fitting fold (at least 5 needed): "
                                    f"{advice}")
        p, m, order = param, method, None
        grouped = sample in GROUPED_SAMPLES
        if grouped:
            ch = choose_fit([per[i] for i in train], tail=a.tail)
            p, m, order = ch.param, ch.method, ch.order()
        _, fold_slot, maxima_slot, _ = SEED_SLOTS[sample]
        pred = predict_sample(x, a, sample_rng(a, ih, il, fold_slot, f),
                              fit_order(a, p, m, order), groups=labels if grouped else None,
                              n=None if grouped else max(float(counts.mean()), 1.0),
                              sample=sample)
        bf = pred.boot
        if bf is None:
            return Validation(error=f"no {p.upper()} {m} fit of a fitting fold: {pred.note}")
        count_kw = pred.count_kwargs()
        tested = [i for i in test if per[i][1] >= 1]
        if tested:
            ns = np.array([per[i][1] for i in tested], dtype=float)
            obs = np.array([per[i][2] for i in tested])
            v = sample_rng(a, ih, il, maxima_slot, f).random((bf.n_successful, len(tested)))
            draws = bf.maximum_quantiles(ns[None, :], v)
            alpha = 1 - bf.percentile_level(a.confidence_level)
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
                            "predicted_low": float(np.ravel(d.low)[0]),
                            "predicted_high": float(np.ravel(d.high)[0]),
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
        # pool the folds: predictions and interval ends weighted by the surfaces they predict
        pooled = ["predicted", "predicted_low", "predicted_high"]
        for col in pooled:
            c["w_" + col] = c[col] * c["n_surfaces"]
        g = c.groupby(["hardness_mpa", "area_factor"], as_index=False)[
            ["w_" + col for col in pooled] + ["hits", "n_surfaces"]].sum()
        for col in pooled:
            g[col] = g["w_" + col] / g["n_surfaces"]
        g["observed"] = g["hits"] / g["n_surfaces"]
        ci = [wilson_interval(h, n) for h, n in zip(g["hits"], g["n_surfaces"], strict=True)]
        g["observed_low"] = [c_[0] for c_ in ci]
        g["observed_high"] = [c_[1] for c_ in ci]
        checks = [held_out_check(pr, h, n, interval=(lo, hi)) for pr, lo, hi, h, n in
                  zip(g["predicted"], g["predicted_low"], g["predicted_high"], g["hits"],
                      g["n_surfaces"], strict=True)]
        g["p_value"] = [c_.p_value for c_ in checks]
        at = np.flatnonzero(np.isclose(g["hardness_mpa"], a.hardness_mpa, rtol=1e-12)
                            & (g["area_factor"] == 1))
        if at.size:
            val.damage_check = checks[int(at[0])]
        val.calibration = g[["hardness_mpa", "area_factor", "predicted", "predicted_low",
                             "predicted_high", "observed", "observed_low", "observed_high",
                             "n_surfaces", "p_value"]]
    val.coverage_check = held_out_check(a.confidence_level, k_cov, mcount, alternative="less")
    return val


