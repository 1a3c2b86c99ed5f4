"""Statistics of a campaign (docs/method.md §5–§9): GLD fits, bootstrap, maximal pressure,
damage and integrity, and their validation across held-out surfaces.

Two samples are analysed per (H, load):

* ``"asperity"`` (primary): the peak pressure 1.5 p_m of every asperity in contact, with the
  number of asperities in contact per surface as a random count N. The maximum over one
  analysed area is ``E[F(x)^N]``; the bootstrap resamples whole surfaces (their peaks and their
  count together). The fit (parameterisation and method) is chosen inside the fitting data only,
  by an inner split (:func:`choose_fit`).
* ``"grid"`` (the paper's): the non-zero grid-point pressures with n = grid points in contact,
  fitted by the paper's RS moments.

Every prediction is checked on surfaces the fit did not see (two folds: even and odd surfaces):
the maximum of each held-out surface against its predicted interval (coverage, centring test),
and the damage probability ``P(max > Pd)`` at several hardness levels against the observed
fraction of held-out surfaces (and of groups of k = 2, 4 surfaces for the area scaling).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import FitError
from ..prediction import MaximumPrediction
from .campaign import CampaignSettings

__all__ = [
    "AnalysisSettings",
    "FitChoice",
    "SampleAnalysis",
    "Validation",
    "analyse",
    "choose_fit",
    "wilson_interval",
]

#: The two samples whose maximum is predicted: grid-point pressures (the paper's) and the
#: peak pressure 1.5 p_m of every asperity in contact (one value per asperity).
SAMPLES = {"grid": ("samples", "n_contact", "max_pressure"),
           "asperity": ("asperity_peak", "n_asperities", "asperity_max")}
SAMPLE_LABELS = {"grid": "grid-point pressures (the paper's)",
                 "asperity": "per-asperity peak pressures"}
#: Contact models whose solutions the analysis reads, with their seed slot and name.
MODEL_SLOTS = {"asperity": 0, "bem": 1000}
MODEL_NAMES = {"asperity": "asperity model", "bem": "elastic BEM"}
#: Fits tried for the primary sample, in order of preference on ties.
CANDIDATES = (("rs", "moments"), ("fkml", "moments"), ("rs", "lmoments"), ("fkml", "lmoments"),
              ("fkml", "mle"))
#: Fallback order when the requested fit has no solution for a sample.
FALLBACKS = (("rs", "moments"), ("fkml", "moments"), ("rs", "percentiles"), ("fkml", "lmoments"))
#: Bootstrap resamples of a maximum-likelihood fit (each resample is an optimisation).
MLE_RESAMPLES = 100
#: Area factors checked by grouping held-out surfaces.
AREA_CHECKS = (2, 4)
#: A result "passes its check" when its predicted damage lies inside the observed Wilson
#: interval at this fraction of the hardness levels (with the coverage and bias criteria).
PASS_FRACTION = 0.8


@dataclass(frozen=True)
class AnalysisSettings:
    """How a campaign's pressures are analysed.

    Attributes
    ----------
    hardness : float
        Hardness / first-yield pressure Pd in MPa.
    n_resamples : int
        Bootstrap resamples B of the primary (per-asperity) sample.
    grid_resamples : int
        Bootstrap resamples of the secondary grid-point sample (a million values per fold:
        its intervals are narrow and not the answer, so fewer resamples suffice).
    param, method : str
        GLD of the grid-point sample (the paper: ``"rs"``, ``"moments"``).
    confidence_level : float
        Level of the predicted intervals of the maximum and of the probabilities.
    test_level : float
        Level of the test on (predicted − observed) (0.95: reject at 5 %).
    area_factors : tuple of float
        Area factors k of the integrity-vs-area curve.
    integrity_level : float
        Integrity probability of the guaranteed pressure.
    seed : int
        Root of the bootstrap seeds.
    n_levels : int
        Hardness levels of the damage check (spanning the observed per-surface maxima).
    """

    hardness: float = 2050.0
    n_resamples: int = 1000
    grid_resamples: int = 50
    param: str = "rs"
    method: str = "moments"
    confidence_level: float = 0.9
    test_level: float = 0.95
    area_factors: tuple[float, ...] = tuple(np.unique(np.round(np.logspace(0, 3, 31), 6)).tolist())
    integrity_level: float = 0.99
    seed: int = 2019
    n_levels: int = 7

    def __post_init__(self) -> None:
        if not (isinstance(self.hardness, int | float) and math.isfinite(self.hardness)
                and self.hardness > 0):
            raise ValueError(f"hardness must be a positive finite pressure in MPa, got {self.hardness!r}")
        for name in ("n_resamples", "grid_resamples"):
            v = getattr(self, name)
            if int(v) != v or v < 10:
                raise ValueError(f"{name} (bootstrap B) must be an integer >= 10, got {v!r}")
        for name in ("confidence_level", "test_level", "integrity_level"):
            v = getattr(self, name)
            if not 0 < v < 1:
                raise ValueError(f"{name} must be in (0, 1), got {v!r}")
        if isinstance(self.seed, bool) or int(self.seed) != self.seed or self.seed < 0:
            raise ValueError(f"seed must be an integer >= 0, got {self.seed!r}")
        if not self.area_factors or any(not (math.isfinite(v) and v > 0) for v in self.area_factors):
            raise ValueError(f"area_factors must be positive finite numbers, got {self.area_factors!r}")
        if int(self.n_levels) != self.n_levels or self.n_levels < 5:
            raise ValueError(f"n_levels must be an integer >= 5, got {self.n_levels!r}")


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

    def damage_hits(self) -> tuple[int, int]:
        """(levels whose prediction lies inside the observed interval, levels) on one area."""
        c = self.calibration
        if c is None or len(c) == 0:
            return 0, 0
        one = c[c["area_factor"] == 1]
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


@dataclass(frozen=True)
class FitChoice:
    """The fit chosen for a sample by an inner split of its fitting surfaces.

    Attributes
    ----------
    param, method : str
        The chosen parameterisation and method.
    scores : dict
        ``"PARAM method" -> mean log predictive density`` of the held-out half's per-surface
        maxima inside the fit's support, best candidate first.
    reason : str
        The choice and why, in words.
    """

    param: str
    method: str
    scores: dict
    reason: str

    def order(self) -> list[tuple[str, str]]:
        """The candidates from best to worst, then the fallbacks: the fits to try."""
        ranked = [tuple(k.lower().split(" ", 1)) for k in self.scores]
        first = [(self.param, self.method)]
        rest = [f for f in ranked + list(FALLBACKS) if f != first[0]]
        return first + list(dict.fromkeys(rest))


@dataclass
class SampleAnalysis:
    """Analysis of one sample (grid or asperity) for one (H, load).

    Attributes
    ----------
    kind : str
        ``"grid"`` or ``"asperity"``.
    data : ndarray
        The pooled sample (MPa).
    n_ref : float
        Mean count per surface (points or asperities in contact).
    counts : ndarray
        The count of every surface.
    choice : FitChoice or None
        How the fit was chosen (the per-asperity sample).
    note : str
        Why a fallback was used, or why nothing could be fitted.
    prediction : glstat.prediction.MaximumPrediction or None
        Fit, bootstrap, maximal pressure over one analysed area and damage probability at
        the hardness on one analysed area (its ``param``, ``method``, ``boot``,
        ``maximum`` and ``damage`` are also attributes of this analysis).
    integrity : glstat.BootstrapProbability or None
        Integrity probability against the area factors.
    guaranteed : dict
        Area factor -> pressure (MPa) that the area stays below with ``integrity_level``.
    upper_end : float
        Upper end of the fitted GLD's support (MPa; inf when unbounded).
    end_note : str
        A plain warning when the hardness lies beyond or near that end point.
    damage_curve : pandas.DataFrame or None
        Damage probability on one area against hardness, with its interval.
    validation : Validation
    """

    kind: str
    data: np.ndarray
    n_ref: float
    counts: np.ndarray = field(default_factory=lambda: np.empty(0))
    choice: FitChoice | None = None
    note: str = ""
    prediction: MaximumPrediction | None = None
    integrity: Any = None
    guaranteed: dict = field(default_factory=dict)
    upper_end: float = math.nan
    end_note: str = ""
    damage_curve: Any = None
    validation: Validation = field(default_factory=Validation)

    @property
    def ok(self) -> bool:
        """Whether a GLD was fitted."""
        return self.boot is not None

    @property
    def param(self) -> str:
        """Parameterisation of the fit used ("" without one)."""
        return "" if self.prediction is None else self.prediction.param

    @property
    def method(self) -> str:
        """Method of the fit used ("" without one)."""
        return "" if self.prediction is None else self.prediction.method

    @property
    def boot(self) -> Any:
        """The bootstrap (glstat.BootstrapFit) or None."""
        return None if self.prediction is None else self.prediction.boot

    @property
    def maximum(self) -> Any:
        """Maximal pressure over one analysed area (glstat.BootstrapMaximum) or None."""
        return None if self.prediction is None else self.prediction.maximum

    @property
    def damage(self) -> Any:
        """Damage probability at the hardness, one analysed area
        (glstat.BootstrapProbability) or None."""
        return None if self.prediction is None else self.prediction.damage


# -- samples of the surfaces -------------------------------------------------------------------
def surface_values(res: dict, kind: str) -> tuple[np.ndarray, int, float]:
    """(values in MPa, count, observed maximum in MPa) of one surface's result."""
    if kind == "grid":
        return res["samples"] / 1e6, int(res["n_contact"]), float(res["max_pressure"]) / 1e6
    peaks = res["asperity_peak"] / 1e6
    return peaks, int(peaks.size), float(peaks.max()) if peaks.size else 0.0


#: A surface's maximal pressure above its largest asperity peak by more than this fraction is
#: set by overlapping asperity patches (their pressures add up).
OVERLAP_MARGIN = 0.01


def _overlap_sets_maximum(res: dict) -> bool:
    """Whether a surface's maximal grid pressure exceeds every asperity's own peak (the
    patches of neighbouring asperities overlap there and their pressures add up)."""
    peaks = np.asarray(res.get("asperity_peak", ()), dtype=float)
    return bool(peaks.size and float(res["max_pressure"]) > (1 + OVERLAP_MARGIN) * peaks.max())


def _pool(per: list) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(pooled values, group label per value, count per surface) of per-surface values."""
    data = np.concatenate([p[0] for p in per]) if per else np.empty(0)
    counts = np.array([p[1] for p in per], dtype=np.int64)
    labels = np.repeat(np.arange(len(per)), [p[0].size for p in per])
    return data, labels, counts


def sample_rng(a: AnalysisSettings, *key: int) -> np.random.Generator:
    """The generator of one analysis step: ``SeedSequence(a.seed, spawn_key=(10000, *key))``."""
    return np.random.default_rng(np.random.SeedSequence(a.seed, spawn_key=(10_000, *key)))


def fit_order(a: AnalysisSettings, param: str | None = None, method: str | None = None,
              order: list[tuple[str, str]] | None = None) -> list[tuple[str, str]]:
    """The fits to try: ``order`` when given; else the requested fit (default the settings'),
    followed by FALLBACKS unless the fit was forced."""
    if order is not None:
        return order
    first = (param or a.param, method or a.method)
    return [first] + ([] if param is not None else [f for f in FALLBACKS if f != first])


def predict_sample(x: np.ndarray, a: AnalysisSettings, rng, fits: list[tuple[str, str]], *,
                   groups=None, n: float | None = None, n_resamples: int | None = None,
                   threshold: float | None = None, maximum: bool = False, maximum_rng=None):
    """:func:`glstat.predict_maximum` with the settings' resamples and level: the first of
    ``fits`` that has a solution, likelihood fits on at most MLE_RESAMPLES resamples."""
    from ..prediction import predict_maximum

    return predict_maximum(x, fits, n=n, groups=groups, threshold=threshold,
                           n_resamples=n_resamples or a.n_resamples,
                           likelihood_resamples=MLE_RESAMPLES,
                           confidence_level=a.confidence_level, rng=rng, maximum=maximum,
                           maximum_rng=maximum_rng)


# -- the choice of fit ---------------------------------------------------------------------------
def _max_log_score(dist, maxima: np.ndarray, counts: np.ndarray) -> tuple[int, float]:
    """(maxima outside the support, mean log density of the others under ``F^(n_i)``):
    ``log n + (n - 1) log F(M) + log f(M)``."""
    lo, hi = dist.support()
    inside = (maxima >= lo) & (maxima <= hi)
    n = np.maximum(counts.astype(float), 1.0)[inside]
    m = maxima[inside]
    if not m.size:
        return int(maxima.size), -math.inf
    with np.errstate(all="ignore"):
        v = np.log(n) + (n - 1.0) * np.asarray(dist.logcdf(m)) + np.asarray(dist.logpdf(m))
    ok = np.isfinite(v)
    return int(maxima.size - ok.sum()), (float(np.mean(v[ok])) if ok.any() else -math.inf)


def choose_fit(per: list, candidates=CANDIDATES) -> FitChoice:
    """Choose the GLD fit of a sample by an inner split of its surfaces.

    The surfaces are split into two halves (alternately); every candidate is fitted to one half
    and scored on the other by its per-surface maxima (the quantity the study predicts): first
    the number of maxima outside the fit's support (fewer is better), then the mean log density
    of the others under ``F(x)^(n_i)`` (higher is better); then the halves swap and the two
    scores add up. Earlier candidates win ties. Only the surfaces passed in are used, so a
    choice made on a fitting fold never sees the fold it is checked against.

    Parameters
    ----------
    per : list of (values, count, maximum)
        Per surface: its values (MPa), its count and its observed maximum (MPa).
    candidates : sequence of (param, method)

    Returns
    -------
    FitChoice
    """
    import glstat

    from ..prediction import collect_warnings

    halves = [per[0::2], per[1::2]]
    scores, outside = {}, {}
    for p, m in candidates:
        s, out = [], 0
        for h in (0, 1):
            train, test = halves[h], halves[1 - h]
            x = np.concatenate([t[0] for t in train]) if train else np.empty(0)
            if x.size < 5 or not test:
                continue
            try:
                f, _ = collect_warnings(glstat.fit, x, p, m)
            except (FitError, ValueError):
                out += len(test)
                s.append(-math.inf)
                continue
            o, v = _max_log_score(f.dist, np.array([t[2] for t in test]),
                                  np.array([t[1] for t in test]))
            out += o
            s.append(v)
        name = f"{p.upper()} {m}"
        scores[name] = float(np.mean(s)) if s else -math.inf
        outside[name] = out if s else len(per)
    names = list(scores)
    best = min(names, key=lambda k: (outside[k], -scores[k], names.index(k)))
    p, m = best.split(" ", 1)
    ranked = sorted(names, key=lambda k: (outside[k], -scores[k], names.index(k)))
    runner = next((k for k in ranked if k != best), None)
    why = (f"{best} predicts the held-out half's maxima best (mean log density "
           f"{scores[best]:.3g}" + (f" against {scores[runner]:.3g} for {runner})" if runner else ")"))
    if outside[best]:
        why += (f"; {outside[best]} held-out maxima lie beyond its support (fewest of the "
                f"candidates)")
    return FitChoice(p.lower(), m, {k: scores[k] for k in ranked}, why)


# -- predictions and checks ------------------------------------------------------------------------
def hardness_levels(maxima: np.ndarray, hardness: float, n_levels: int) -> np.ndarray:
    """Hardness levels spanning the observed per-surface maxima (quantiles 5 %–95 %) and the
    hardness itself, in MPa (rounded to 3 significant digits)."""
    q = np.quantile(maxima, np.linspace(0.05, 0.95, n_levels))
    levels = np.unique(np.concatenate([[hardness], q]))
    return np.unique(np.array([float(f"{v:.3g}") for v in levels]))


def _validate(per: list, kind: str, a: AnalysisSettings, ih: int, il: int, param: str, method: str,
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
        x, labels, counts = _pool([per[i] for i in train])
        if x.size < 5:
            return Validation(error=f"only {x.size} values in a fitting fold (at least 5 needed)")
        p, m, order = param, method, None
        if kind == "asperity":
            ch = choose_fit([per[i] for i in train])
            p, m, order = ch.param, ch.method, ch.order()
        grouped = kind == "asperity"
        pred = predict_sample(x, a, sample_rng(a, ih, il, 1 if kind == "grid" else 2, f),
                              fit_order(a, p, m, order), groups=labels if grouped else None,
                              n=None if grouped else max(float(counts.mean()), 1.0),
                              n_resamples=a.grid_resamples if kind == "grid" else None)
        bf = pred.boot
        if bf is None:
            return Validation(error=f"no {p.upper()} {m} fit of a fitting fold: {pred.note}")
        count_kw = pred.count_kwargs()
        tested = [i for i in test if per[i][1] >= 1]
        if tested:
            ns = np.array([per[i][1] for i in tested], dtype=float)
            obs = np.array([per[i][2] for i in tested])
            v = sample_rng(a, ih, il, 3 if kind == "grid" else 4, f).random((bf.n_successful, len(tested)))
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


def _end_note(sa: SampleAnalysis, hardness: float) -> str:
    end = sa.upper_end
    if not math.isfinite(end):
        return ""
    if hardness >= end:
        return (f"the hardness {hardness:.4g} MPa lies beyond the fitted GLD's upper end point "
                f"{end:.4g} MPa: its damage probability is 0 by construction of the fit, not "
                f"because the data say so")
    if hardness >= 0.9 * end:
        return (f"the hardness {hardness:.4g} MPa lies within 10 % of the fitted GLD's upper end "
                f"point {end:.4g} MPa: the damage probability depends on where the fit ends")
    return ""


def analyse_sample(results: dict, keys: list, kind: str, a: AnalysisSettings,
                   ih: int, il: int) -> SampleAnalysis:
    """Fit, bootstrap, maximum, damage, integrity and validation of one sample.

    Parameters
    ----------
    results : dict
        Surface results keyed by (ih, il, i) (:func:`glstat.study.load_results`).
    keys : list of (int, int, int)
        The surfaces of this (H, load).
    kind : {"grid", "asperity"}
    a : AnalysisSettings
    ih, il : int
        Indices of the Hurst exponent and load (seeds).
    """
    import pandas as pd

    import glstat

    per = [surface_values(results[k], kind) for k in keys]
    data, labels, counts = _pool(per)
    sa = SampleAnalysis(kind=kind, data=data, n_ref=max(float(counts.mean()) if per else 0.0, 1.0),
                        counts=counts)
    if data.size < 5:
        sa.note = f"only {data.size} values pooled over {len(keys)} surfaces; at least 5 are needed"
        return sa
    grouped = kind == "asperity"
    param = method = order = None
    if grouped:
        sa.choice = choose_fit(per)
        param, method, order = sa.choice.param, sa.choice.method, sa.choice.order()
    sa.prediction = predict_sample(
        data, a, sample_rng(a, ih, il, 0 if kind == "grid" else 5),
        fit_order(a, param, method, order), groups=labels if grouped else None,
        n=None if grouped else sa.n_ref,
        n_resamples=a.grid_resamples if kind == "grid" else None, threshold=a.hardness,
        maximum=True, maximum_rng=sample_rng(a, ih, il, 6))
    bf, p, m = sa.prediction.boot, sa.prediction.param, sa.prediction.method
    sa.note = sa.prediction.note
    if bf is None:
        return sa
    count_kw = sa.prediction.count_kwargs()
    sa.integrity = bf.integrity_probability(a.hardness, area_factor=np.asarray(a.area_factors),
                                            **count_kw)
    full_kw = {"count": bf.counts} if grouped else {"n": sa.n_ref}
    dist = sa.prediction.dist
    for k in (1.0, 10.0, 100.0, 1000.0):
        sa.guaranteed[k] = float(glstat.guaranteed_threshold(
            dist, probability=a.integrity_level, area_factor=k, **full_kw))
    sa.upper_end = float(dist.support()[1])
    sa.end_note = _end_note(sa, a.hardness)
    maxima = np.array([q[2] for q in per])
    levels = hardness_levels(maxima, a.hardness, a.n_levels)
    curve = []
    for lv in np.unique(np.concatenate([levels, np.linspace(maxima.min(), maxima.max(), 25)])):
        d = bf.damage_probability(float(lv), **count_kw)
        curve.append({"hardness_mpa": float(lv), "damage": float(np.ravel(d.estimate)[0]),
                      "low": float(np.ravel(d.low)[0]), "high": float(np.ravel(d.high)[0]),
                      "observed": float(np.mean(maxima > lv))})
    sa.damage_curve = pd.DataFrame(curve)
    sa.validation = _validate(per, kind, a, ih, il, p, m, levels)
    return sa


def analyse(results: dict, settings: CampaignSettings, a: AnalysisSettings, progress=None,
            model: str = "asperity") -> dict:
    """Analyse every (H, load) of a campaign, both samples.

    ``progress``, when given, is called with a one-line description before each case and
    sample (the command prints it). ``model`` names the contact model of ``results``
    ("asperity", or "bem" for :func:`glstat.study.bem.elastic_results`, whose per-asperity
    sample is the peak of every contact spot); the surfaces missing from ``results`` (e.g.
    elastic solves that did not converge) are left out. Each model has its own seeds.

    Returns
    -------
    dict
        ``(ih, il) -> {"grid": SampleAnalysis, "asperity": SampleAnalysis, "summary": dict}``
        where the summary holds the per-surface means of mean pressure (MPa), 1 − α, points
        and asperities in contact and the maximal pressure (MPa).
    """
    out = {}
    for ih in range(len(settings.hurst)):
        for il in range(len(settings.pressures)):
            keys = [(ih, il, i) for i in range(settings.n_surfaces) if (ih, il, i) in results]
            rs = [results[k] for k in keys]
            if not rs:
                continue
            summary = {
                "mean_pressure": float(np.mean([r["mean_pressure"] for r in rs])) / 1e6,
                "contact_fraction": float(np.mean([1 - r["alpha"] for r in rs])),
                "n_contact": float(np.mean([r["n_contact"] for r in rs])),
                "n_asperities": float(np.mean([r["n_asperities"] for r in rs])),
                "max_pressure": float(np.mean([r["max_pressure"] for r in rs])) / 1e6,
                "observed_damage": float(np.mean([float(r["max_pressure"]) / 1e6 > a.hardness
                                                  for r in rs])),
                "overlap_fraction": float(np.mean([_overlap_sets_maximum(r) for r in rs])),
                "force_error": float(np.max(np.abs([r["force_error"] for r in rs]))),
                "n_in_jump": int(sum(int(r.get("in_jump", 0)) for r in rs)),
                "max_force_jump": float(max(float(r.get("force_jump", 0.0)) for r in rs)),
                "n_surfaces": len(rs),
                "n_left_out": settings.n_surfaces - len(rs),
            }
            slot = MODEL_SLOTS[model]
            case: dict[str, SampleAnalysis | dict[str, float]] = {}
            for kind in SAMPLES:
                if progress is not None:
                    progress(f"analysis ({MODEL_NAMES[model]}): H = {settings.hurst[ih]:g}, "
                             f"{settings.pressures[il] / 1e6:g} MPa, {SAMPLE_LABELS[kind]}")
                case[kind] = analyse_sample(results, keys, kind, a, ih + slot, il)
            case["summary"] = summary
            out[(ih, il)] = case
    return out
