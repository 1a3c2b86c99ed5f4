"""Statistics of a campaign (DESIGN §1 steps 3–9): GLD fits, bootstrap, maximal pressure,
damage and integrity, and the validation of the predicted maximum across surfaces."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import FitError
from .campaign import CampaignSettings

__all__ = ["AnalysisSettings", "SampleAnalysis", "Validation", "analyse", "wilson_interval"]

#: The two samples whose maximum is predicted: grid-point pressures (the paper's) and the
#: peak pressure 1.5 p_m of every asperity in contact (one value per asperity).
SAMPLES = {"grid": ("samples", "n_contact", "max_pressure"),
           "asperity": ("asperity_peak", "n_asperities", "asperity_max")}
SAMPLE_LABELS = {"grid": "grid-point pressures", "asperity": "per-asperity peak pressures"}
#: Fallback order when the requested fit has no solution for a sample.
FALLBACKS = (("rs", "moments"), ("fkml", "moments"), ("rs", "percentiles"), ("fkml", "lmoments"))


@dataclass(frozen=True)
class AnalysisSettings:
    """How a campaign's pressures are analysed.

    Attributes
    ----------
    hardness : float
        Hardness / first-yield pressure Pd in MPa.
    n_resamples : int
        Bootstrap resamples B.
    param, method : str
        GLD parameterisation and fitting method (the paper: ``"rs"``, ``"moments"``).
    confidence_level : float
        Level of the predicted intervals of the maximum and of the probabilities.
    test_level : float
        Level of the test on (predicted − observed) (0.95: reject at 5 %).
    area_factors : tuple of float
        Area factors k of the integrity-vs-area curve.
    integrity_level : float
        Integrity probability of the guaranteed pressure ``Q(p^(1/(k n)))``.
    seed : int
        Root of the bootstrap seeds.
    """

    hardness: float = 2050.0
    n_resamples: int = 1000
    param: str = "rs"
    method: str = "moments"
    confidence_level: float = 0.9
    test_level: float = 0.95
    area_factors: tuple[float, ...] = tuple(np.unique(np.round(np.logspace(0, 3, 31), 6)).tolist())
    integrity_level: float = 0.99
    seed: int = 2019

    def __post_init__(self) -> None:
        if not (math.isfinite(self.hardness) and self.hardness > 0):
            raise ValueError(f"hardness must be a positive pressure in MPa, got {self.hardness!r}")
        if int(self.n_resamples) != self.n_resamples or self.n_resamples < 10:
            raise ValueError(f"n_resamples (bootstrap B) must be an integer >= 10, got {self.n_resamples!r}")
        for name in ("confidence_level", "test_level", "integrity_level"):
            v = getattr(self, name)
            if not 0 < v < 1:
                raise ValueError(f"{name} must be in (0, 1), got {v!r}")
        if isinstance(self.seed, bool) or int(self.seed) != self.seed or self.seed < 0:
            raise ValueError(f"seed must be an integer >= 0, got {self.seed!r}")
        if not self.area_factors or any(not (math.isfinite(v) and v > 0) for v in self.area_factors):
            raise ValueError(f"area_factors must be positive finite numbers, got {self.area_factors!r}")


def wilson_interval(k: int, n: int, level: float = 0.95) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion k/n.

    Parameters
    ----------
    k, n : int
        Successes and trials (n >= 1).
    level : float
        Confidence level.

    Returns
    -------
    (low, high) : tuple of float
    """
    from scipy.stats import norm

    if n < 1:
        return math.nan, math.nan
    z = float(norm.isf((1 - level) / 2))
    p = k / n
    den = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return max(0.0, centre - half), min(1.0, centre + half)


@dataclass
class Validation:
    """Observed maximum of every surface against its predicted interval.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per surface: ``surface``, ``fold``, ``n`` (points or asperities), ``observed``,
        ``predicted`` (mean of the predicted maximum), ``low``, ``high`` (predicted interval),
        ``covered``; pressures in MPa. The prediction for surface i is one random maximum
        of ``n_i`` draws per bootstrap GLD of the other fold: ``predicted`` is their mean,
        ``low``/``high`` their equal-tailed quantiles at the confidence level.
    coverage : float
        Fraction of surfaces whose observed maximum lies in the predicted interval.
    coverage_interval : (float, float)
        Wilson 95 % interval of the coverage.
    t_statistic, t_pvalue : float
        One-sample t-test of mean(predicted − observed) = 0 (two-sided).
    w_pvalue : float
        Wilcoxon signed-rank test (symmetry of the differences about 0), for reference.
    reject : bool
        Whether the t-test rejects at the test level.
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
    error: str = ""


@dataclass
class SampleAnalysis:
    """Analysis of one sample kind (grid or asperity) for one (H, load).

    Attributes
    ----------
    kind : str
        ``"grid"`` or ``"asperity"``.
    data : ndarray
        The pooled sample (MPa).
    n_ref : float
        Points (or asperities) of the analysed area: the mean count per surface.
    param, method : str
        The fit actually used (a fallback when the requested one has no solution).
    note : str
        Why a fallback was used, or why nothing could be fitted.
    boot : glstat.BootstrapFit or None
    maximum : glstat.BootstrapMaximum or None
        Maximal pressure over one analysed area.
    damage : glstat.BootstrapProbability or None
        Damage probability at the hardness, one analysed area.
    integrity : glstat.BootstrapProbability or None
        Integrity probability against the area factors.
    guaranteed : dict
        Area factor -> pressure (MPa) that all points stay below with ``integrity_level``.
    validation : Validation
    """

    kind: str
    data: np.ndarray
    n_ref: float
    param: str = ""
    method: str = ""
    note: str = ""
    boot: Any = None
    maximum: Any = None
    damage: Any = None
    integrity: Any = None
    guaranteed: dict = field(default_factory=dict)
    validation: Validation = field(default_factory=Validation)

    @property
    def ok(self) -> bool:
        """Whether a GLD was fitted."""
        return self.boot is not None


def _seed(a: AnalysisSettings, *key: int) -> np.random.Generator:
    return np.random.default_rng(np.random.SeedSequence(a.seed, spawn_key=(10_000, *key)))


def _bootstrap(x: np.ndarray, a: AnalysisSettings, rng, param=None, method=None):
    """Bootstrap with the requested fit, falling back along FALLBACKS; returns (bf, param, method, note)."""
    from .. import bootstrap

    order = [(param or a.param, method or a.method)] + [f for f in FALLBACKS
                                                          if f != (param or a.param, method or a.method)]
    if param is not None:
        order = order[:1]
    notes = []
    state = rng.bit_generator.state
    for p, m in order:
        rng.bit_generator.state = state
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                bf = bootstrap(x, param=p, method=m, n_resamples=a.n_resamples,
                               confidence_level=a.confidence_level, rng=rng, progress=False)
            note = "" if not notes else "; ".join(notes) + f"; used {p.upper()} {m}"
            return bf, p, m, note
        except (FitError, ValueError) as exc:
            notes.append(f"{p.upper()} {m}: {str(exc).split('. ')[0].splitlines()[0][:120]}")
    return None, "", "", "; ".join(notes)


def _surface_values(res: dict, kind: str) -> tuple[np.ndarray, int, float]:
    if kind == "grid":
        return res["samples"] / 1e6, int(res["n_contact"]), float(res["max_pressure"]) / 1e6
    peaks = res["asperity_peak"] / 1e6
    return peaks, int(peaks.size), float(peaks.max()) if peaks.size else math.nan


def _validate(results: dict, keys: list, kind: str, a: AnalysisSettings, ih: int, il: int,
              param: str, method: str) -> Validation:
    """Two-fold cross-validation: a GLD fitted on the even surfaces predicts the odd ones and
    vice versa, so no surface's maximum is predicted from a fit that saw it."""
    import pandas as pd
    from scipy import stats

    folds = [keys[0::2], keys[1::2]]
    rows = []
    for f in (0, 1):
        train, test = folds[1 - f], folds[f]
        if not train or not test:
            return Validation(error="needs at least two surfaces (one per fold)")
        x = np.concatenate([_surface_values(results[k], kind)[0] for k in train])
        if x.size < 5:
            return Validation(error=f"only {x.size} values in a training fold (at least 5 needed)")
        bf, _, _, note = _bootstrap(x, a, _seed(a, ih, il, 1 if kind == "grid" else 2, f), param, method)
        if bf is None:
            return Validation(error=f"no {param.upper()} {method} fit of a training fold: {note}")
        # One random maximum of n_i draws per bootstrap GLD (the paper's construction):
        # M_b = Q_b(v^(1/n)) = isf_b(1 - v^(1/n)), with 1 - v^(1/n) = -expm1(ln v / n).
        test = [k for k in test if _surface_values(results[k], kind)[1] >= 1]
        if not test:
            continue
        ns = np.array([_surface_values(results[k], kind)[1] for k in test], dtype=float)
        obs = np.array([_surface_values(results[k], kind)[2] for k in test])
        v = _seed(a, ih, il, 3 if kind == "grid" else 4, f).random((bf.n_successful, len(test)))
        with np.errstate(all="ignore"):
            draws = bf.batch().isf(-np.expm1(np.log(v) / ns[None, :]))
        alpha = 1 - a.confidence_level
        lo, hi = np.nanquantile(draws, [alpha / 2, 1 - alpha / 2], axis=0)
        pred = np.nanmean(draws, axis=0)
        for j, k in enumerate(test):
            rows.append({"surface": k[2], "fold": f, "n": int(ns[j]), "observed": obs[j],
                         "predicted": pred[j], "low": lo[j], "high": hi[j],
                         "covered": bool(lo[j] <= obs[j] <= hi[j])})
    table = pd.DataFrame(rows).sort_values("surface", ignore_index=True)
    k_cov, m = int(table["covered"].sum()), len(table)
    diff = (table["predicted"] - table["observed"]).to_numpy()
    v = Validation(table=table, coverage=k_cov / m, coverage_interval=wilson_interval(k_cov, m))
    if m >= 3 and np.ptp(diff) > 0:
        t = stats.ttest_1samp(diff, 0.0)
        v.t_statistic, v.t_pvalue = float(t.statistic), float(t.pvalue)
        v.w_pvalue = float(stats.wilcoxon(diff).pvalue)
        v.reject = bool(v.t_pvalue < 1 - a.test_level)
    return v


def analyse_sample(results: dict, keys: list, kind: str, a: AnalysisSettings,
                   ih: int, il: int) -> SampleAnalysis:
    """Fit, bootstrap, maximum, damage, integrity and validation for one sample kind.

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
    import glstat

    per = [_surface_values(results[k], kind) for k in keys]
    data = np.concatenate([p[0] for p in per]) if per else np.empty(0)
    n_ref = float(np.mean([p[1] for p in per])) if per else 0.0
    sa = SampleAnalysis(kind=kind, data=data, n_ref=max(n_ref, 1.0))
    if data.size < 5:
        sa.note = f"only {data.size} values pooled over {len(keys)} surfaces; at least 5 are needed"
        return sa
    bf, p, m, note = _bootstrap(data, a, _seed(a, ih, il, 0 if kind == "grid" else 5))
    sa.param, sa.method, sa.note = p, m, note
    if bf is None:
        return sa
    sa.boot = bf
    sa.maximum = bf.maximum(sa.n_ref, rng=_seed(a, ih, il, 6))
    sa.damage = bf.damage_probability(a.hardness, sa.n_ref)
    sa.integrity = bf.integrity_probability(a.hardness, sa.n_ref, np.asarray(a.area_factors))
    for k in (1.0, 10.0, 100.0, 1000.0):
        sa.guaranteed[k] = float(glstat.guaranteed_threshold(bf.fit.dist, sa.n_ref, a.integrity_level, k))
    sa.validation = _validate(results, keys, kind, a, ih, il, p, m)
    return sa


def analyse(results: dict, settings: CampaignSettings, a: AnalysisSettings) -> dict:
    """Analyse every (H, load) of a campaign, both samples.

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
            keys = [(ih, il, i) for i in range(settings.n_surfaces)]
            rs = [results[k] for k in keys]
            summary = {
                "mean_pressure": float(np.mean([r["mean_pressure"] for r in rs])) / 1e6,
                "contact_fraction": float(np.mean([1 - r["alpha"] for r in rs])),
                "n_contact": float(np.mean([r["n_contact"] for r in rs])),
                "n_asperities": float(np.mean([r["n_asperities"] for r in rs])),
                "max_pressure": float(np.mean([r["max_pressure"] for r in rs])) / 1e6,
                "force_error": float(np.max(np.abs([r["force_error"] for r in rs]))),
                "n_in_jump": int(sum(int(r.get("in_jump", 0)) for r in rs)),
                "max_force_jump": float(max(float(r.get("force_jump", 0.0)) for r in rs)),
                "n_surfaces": len(rs),
            }
            out[(ih, il)] = {kind: analyse_sample(results, keys, kind, a, ih, il) for kind in SAMPLES}
            out[(ih, il)]["summary"] = summary
    return out
