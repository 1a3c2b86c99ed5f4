"""Statistics of a campaign (docs/method.md §5–§9): GLD fits, bootstrap, maximal pressure,
damage and integrity, and their validation across held-out surfaces.

Three samples are analysed per (H, load) (two for the elastic BEM, which has no asperities):

* ``"spot"`` (primary): the peak pressure of every connected contact spot of the pressure map,
  with the number of spots per surface as a random count N. The largest spot peak of a surface
  is its maximal pressure, so the prediction and the observation speak of the same event
  whatever the contact model and wherever asperity patches overlap. The maximum over one
  analysed area is ``E[F(x)^N]``; the bootstrap resamples whole surfaces (their peaks and their
  count together). The fit (parameterisation and method) is chosen inside the fitting data only,
  by an inner split (:func:`choose_fit`).
* ``"asperity"``: the peak pressure 1.5 p_m of every asperity in contact, with the number of
  asperities in contact as N (the per-asperity option; blind to overlapping patches).
* ``"grid"`` (the paper's): the non-zero grid-point pressures with n = grid points in contact,
  fitted by the paper's RS moments.

Every prediction is checked on surfaces the fit did not see (two folds: even and odd surfaces),
always against each held-out surface's maximal pressure: the damage probability ``P(max > Pd)``
at the hardness against the fraction of held-out surfaces damaged, and the number of maxima
inside their predicted interval against its level, each by an exact binomial test that says
"not checkable" when the surfaces are too few to detect a miss (:mod:`glstat.gof.binomial_check`); the
damage at other hardness levels and on groups of k = 2, 4 surfaces (the area scaling) is
tabulated beside them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..prediction import MaximumPrediction, collect_warnings
from .analysis_settings import (
    GROUPED_SAMPLES,
    MODEL_NAMES,
    MODEL_SAMPLES,
    MODEL_SLOTS,
    MORE_SURFACES,
    PRIMARY_SAMPLE,
    SAMPLE_LABELS,
    SEED_SLOTS,
    AnalysisSettings,
    fit_order,
    overlap_sets_maximum,
    pool,
    predict_sample,
    sample_rng,
    surface_values,
)
from .answer import case_label
from .campaign_settings import CampaignSettings
from .fit_choice import FitChoice, choose_fit
from .plasticity import plastic_summary
from .validation import Validation, hardness_levels, validate_sample

__all__ = ["SampleAnalysis", "analyse", "analyse_sample"]


@dataclass
class SampleAnalysis:
    """Analysis of one sample (grid or asperity) for one (H, load).

    Attributes
    ----------
    sample : str
        ``"spot"``, ``"asperity"`` or ``"grid"``.
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
    area_damage : pandas.DataFrame or None
        Damage probability at the hardness on the areas of ``AnalysisSettings.damage_areas`` (the
        primary sample only):
        ``area_mm2``, ``area_factor`` (over the analysed area), ``estimate``, ``low``,
        ``high``.
    upper_end : float
        Upper end of the fitted GLD's support (MPa; inf when unbounded).
    end_note : str
        A plain warning when the hardness lies beyond or near that end point.
    damage_curve : pandas.DataFrame or None
        Damage probability on one area against hardness, with its interval.
    validation : Validation
    """

    sample: str
    data: np.ndarray
    n_ref: float
    counts: np.ndarray = field(default_factory=lambda: np.empty(0))
    choice: FitChoice | None = None
    note: str = ""
    prediction: MaximumPrediction | None = None
    integrity: Any = None
    guaranteed: dict = field(default_factory=dict)
    area_damage: Any = None
    upper_end: float = math.nan
    end_note: str = ""
    damage_curve: Any = None
    validation: Validation = field(default_factory=Validation)

    @property
    def ok(self) -> bool:
        """Whether a GLD was fitted."""
        return self.boot is not None

    @property
    def kind(self) -> str:
        """Deprecated name of :attr:`sample`."""
        import warnings

        warnings.warn("SampleAnalysis.kind is deprecated: use SampleAnalysis.sample",
                      DeprecationWarning, stacklevel=2)
        return self.sample

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


#: Areas (mm²) on which the damage probability is reported: 1 mm², 1 cm², 10 cm².


def analyse_sample(results: dict, keys: list, sample: str, a: AnalysisSettings,
                   ih: int, il: int, area_m2: float | None = None,
                   advice: str = MORE_SURFACES) -> SampleAnalysis:
    """Fit, bootstrap, maximum, damage, integrity and validation of one sample.

    Parameters
    ----------
    results : dict
        Surface results keyed by (ih, il, i) (:func:`glstat.study.load_results`).
    keys : list of (int, int, int)
        The surfaces of this (H, load).
    sample : {"spot", "asperity", "grid"}
    a : AnalysisSettings
    ih, il : int
        Indices of the Hurst exponent and load (seeds).
    area_m2 : float, optional
        The analysed area in m², for the damage on ``a.damage_areas``.
    advice : str
        What to do when the surfaces are too few, in options the study's mode accepts
        (:meth:`CampaignSettings.more_surfaces_advice`).
    """


    per = [surface_values(results[k], sample) for k in keys]
    data, labels, counts = pool(per)
    sa = SampleAnalysis(sample=sample, data=data, n_ref=max(float(counts.mean()) if per else 0.0, 1.0),
                        counts=counts)
    if data.size < 5:
        sa.note = (f"only {data.size} values pooled over {len(keys)} surfaces; at least 5 are "
                   f"needed: {advice}")
        return sa
    grouped = sample in GROUPED_SAMPLES
    if grouped and len(keys) < 2:
        sa.note = (f"one surface: the interval resamples whole surfaces, so it needs at least "
                   f"two; {advice}")
        return sa
    param = method = order = None
    if grouped:
        sa.choice = choose_fit(per, tail=a.tail)
        param, method, order = sa.choice.param, sa.choice.method, sa.choice.order()
    full_slot, _, _, maximum_slot = SEED_SLOTS[sample]
    sa.prediction = predict_sample(
        data, a, sample_rng(a, ih, il, full_slot),
        fit_order(a, param, method, order), groups=labels if grouped else None,
        n=None if grouped else sa.n_ref,
        threshold=a.hardness_mpa, maximum=True, maximum_rng=sample_rng(a, ih, il, maximum_slot),
        sample=sample)
    bf, p, m = sa.prediction.boot, sa.prediction.param, sa.prediction.method
    sa.note = sa.prediction.note
    if bf is None:
        return sa
    # the warnings of what is derived from the bootstrap (an inversion at its iteration limit)
    # join the prediction's notes, as those of the fit do: recorded, never printed
    _, caught = collect_warnings(_derived_quantities, sa, per, a, ih, il, p, m, area_m2,
                                 sample, grouped, advice)
    if caught:
        import dataclasses

        new = tuple(dict.fromkeys(c for c in caught if c not in sa.prediction.notes))
        sa.prediction = dataclasses.replace(sa.prediction, notes=sa.prediction.notes + new)
    return sa


def _derived_quantities(sa: SampleAnalysis, per: list, a: AnalysisSettings, ih: int, il: int,
                        p: str, m: str, area_m2: float | None, sample: str, grouped: bool,
                        advice: str) -> None:
    """Integrity, guaranteed pressures, the damage on the areas, the damage curve and the
    held-out validation of a sample whose prediction has a bootstrap (set on ``sa``)."""
    import pandas as pd

    import glstat

    if sa.prediction is None or sa.prediction.boot is None:
        raise ValueError("a sample without a bootstrap has no derived quantities")
    bf = sa.prediction.boot
    count_kw = sa.prediction.count_kwargs()
    sa.integrity = bf.integrity_probability(a.hardness_mpa, area_factor=np.asarray(a.area_factors),
                                            **count_kw)
    full_kw = {"count": bf.counts} if grouped else {"n": sa.n_ref}
    dist = sa.prediction.dist
    for k in (1.0, 10.0, 100.0, 1000.0):
        sa.guaranteed[k] = float(glstat.guaranteed_threshold(
            dist, probability=a.integrity_level, area_factor=k, **full_kw))
    if area_m2 and sample == PRIMARY_SAMPLE:  # the answer's growth with the area
        factors = np.array(a.damage_areas) / area_m2
        d = bf.damage_probability(a.hardness_mpa, area_factor=factors, **count_kw)
        sa.area_damage = pd.DataFrame({"area_mm2": np.array(a.damage_areas) * 1e6,
                                       "area_factor": factors,
                                       "estimate": np.ravel(d.estimate), "low": np.ravel(d.low),
                                       "high": np.ravel(d.high)})
    sa.upper_end = float(dist.support()[1])
    sa.end_note = _end_note(sa, a.hardness_mpa)
    maxima = np.array([q[2] for q in per])
    levels = hardness_levels(maxima, a.hardness_mpa, a.n_levels)
    curve = []
    for lv in np.unique(np.concatenate([levels, np.linspace(maxima.min(), maxima.max(), 25)])):
        d = bf.damage_probability(float(lv), **count_kw)
        curve.append({"hardness_mpa": float(lv), "damage": float(np.ravel(d.estimate)[0]),
                      "low": float(np.ravel(d.low)[0]), "high": float(np.ravel(d.high)[0]),
                      "observed": float(np.mean(maxima > lv))})
    sa.damage_curve = pd.DataFrame(curve)
    sa.validation = validate_sample(per, sample, a, ih, il, p, m, levels, advice=advice)


def analyse(results: dict, settings: CampaignSettings, a: AnalysisSettings, progress=None,
            model: str = "asperity", samples: tuple[str, ...] | None = None) -> dict:
    """Analyse every (H, load) of a campaign, every sample of its model.

    ``progress``, when given, is called with a one-line description before each case and
    sample (the command prints it). ``model`` names the contact model of ``results``
    ("asperity", or "bem" for :func:`glstat.study.bem.elastic_results`, which has no per-asperity
    sample); the surfaces missing from ``results`` (e.g.
    elastic solves that did not converge) are left out. Each model has its own seeds.
    ``samples`` narrows the samples analysed (default: every sample of the model).

    Returns
    -------
    dict
        ``(ih, il) -> {"spot": SampleAnalysis, "asperity": SampleAnalysis, "grid": SampleAnalysis,
        "summary": dict}`` (no ``"asperity"`` for the BEM)
        where the summary holds the per-surface means of mean pressure (MPa), 1 − α, points
        and asperities in contact and the maximal pressure (MPa), and
        ``observed_max_pressure`` (MPa, the median of the surfaces' maximal surface pressures).
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
                "n_spots": float(np.mean([r["n_spots"] for r in rs])),
                "max_pressure": float(np.mean([r["max_pressure"] for r in rs])) / 1e6,
                "observed_max_pressure": float(np.median(
                    [r.get("max_surface_pressure", r["max_pressure"]) for r in rs])) / 1e6,
                "observed_damage": float(np.mean([float(r["max_pressure"]) / 1e6 > a.hardness_mpa
                                                  for r in rs])),
                "overlap_fraction": float(np.mean([overlap_sets_maximum(r) for r in rs])),
                "force_error": float(np.max(np.abs([r["force_error"] for r in rs]))),
                "n_in_jump": int(sum(int(r.get("in_jump", 0)) for r in rs)),
                "max_force_jump": float(max(float(r.get("force_jump", 0.0)) for r in rs)),
                "n_surfaces": len(rs),
                "n_left_out": settings.n_surfaces - len(rs),
            }
            plastic = [r["plastic_area_fraction"] for r in rs if "plastic_area_fraction" in r]
            if plastic:  # the capped BEM: how much of the area yields
                summary.update(plastic_summary(plastic, a.confidence_level))
                summary["plastic_load_fraction"] = float(np.mean(
                    [r["plastic_load_fraction"] for r in rs if "plastic_load_fraction" in r]))
                # the mean plastic area of one analysed area in µm² and in grid cells (of the
                # grid the capped solution was computed on)
                lx, ly = settings.size
                summary["plastic_area_um2"] = float(np.mean(plastic)) * lx * ly * 1e12
                summary["plastic_area_cells"] = float(np.mean(
                    [r["plastic_area_fraction"] * r.get("n_points", np.prod(settings.shape))
                     for r in rs if "plastic_area_fraction" in r]))
            slot = MODEL_SLOTS[model]
            case: dict[str, SampleAnalysis | dict[str, float]] = {}
            for sample in (MODEL_SAMPLES[model] if samples is None else samples):
                if progress is not None:
                    progress(f"analysis ({MODEL_NAMES[model]}): {case_label(settings, ih, il)}, "
                             f"{SAMPLE_LABELS[sample]}")
                case[sample] = analyse_sample(results, keys, sample, a, ih + slot, il,
                                              area_m2=settings.size[0] * settings.size[1],
                                              advice=settings.more_surfaces_advice())
            case["summary"] = summary
            out[(ih, il)] = case
    return out
