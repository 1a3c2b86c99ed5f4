"""Settings of a campaign's analysis, its seeds, and the per-surface samples it reads.

The two samples and the fits tried for them are named here; :func:`predict_sample` runs the
library's pipeline (:func:`glstat.predict_maximum`) with these settings.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from .criteria import CRITERIA, Criterion

__all__ = ["GROUPED_SAMPLES", "MODEL_SAMPLES", "MORE_SURFACES", "PRIMARY_SAMPLE", "SEED_SLOTS",
           "AnalysisSettings",
           "fit_order", "overlap_sets_maximum", "pool", "predict_sample",
           "sample_rng", "surface_values"]

#: The samples whose maximum is predicted: the peak pressure of every connected contact spot
#: of the pressure map (the primary sample: the largest spot peak of a surface is its maximal
#: pressure, whatever the contact model), the peak pressure 1.5 p_m of every asperity in
#: contact (one value per asperity: the per-asperity option, blind to overlapping patches) and
#: the grid-point pressures (the paper's).
SAMPLES = {"spot": ("spot_peak", "n_spots", "max_pressure"),
           "asperity": ("asperity_peak", "n_asperities", "max_pressure"),
           "grid": ("samples", "n_contact", "max_pressure")}
SAMPLE_LABELS = {"spot": "contact-spot peak pressures",
                 "asperity": "per-asperity peak pressures",
                 "grid": "grid-point pressures (the paper's)"}
#: The sample of the answer.
PRIMARY_SAMPLE = "spot"
#: Samples with one value per spot or asperity: the bootstrap resamples whole surfaces and
#: the number of values of a surface is the random count of the maximum.
GROUPED_SAMPLES = ("spot", "asperity")
#: Seed slots of each sample: (full-sample fit, fold fits, fold maxima, maximum).
SEED_SLOTS = {"grid": (0, 1, 3, 6), "asperity": (5, 2, 4, 6), "spot": (7, 8, 9, 10)}
#: Contact models whose solutions the analysis reads, with their seed slot and name.
MODEL_SLOTS = {"asperity": 0, "bem": 1000}
#: The samples analysed for each model (the elastic BEM has no asperities: its spots are the
#: per-spot sample).
MODEL_SAMPLES = {"asperity": ("spot", "asperity", "grid"), "bem": ("spot", "grid")}
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
#: The held-out checks (exact binomial tests of the damage at the hardness and of the coverage
#: of the maximum's interval): their level, the power with which a miss must be detected, and
#: the largest miss (in probability) that may go undetected for a check to count.
CHECK_SIGNIFICANCE = 0.05
CHECK_POWER = 0.8
CHECK_MAX_MISS = 0.2


#: What to do about too few surfaces or values when the caller does not say (simulated
#: surfaces; :meth:`CampaignSettings.more_surfaces_advice` words it for every mode).
MORE_SURFACES = "analyse more or larger surfaces (--surfaces, --size)"


#: A hardness below this (Pa) is a value in MPa, the unit of earlier releases: no material's
#: hardness is below 100 kPa.
MPA_FORM_BELOW = 1e5


@dataclass(frozen=True)
class AnalysisSettings:
    """How a campaign's pressures are analysed.

    Attributes
    ----------
    hardness : float
        Hardness / first-yield pressure Pd in Pa (SI, as every setting; the study's tables and
        report give it in MPa, :attr:`hardness_mpa`). A value below 100 kPa is read as MPa,
        the unit of earlier releases, with a :class:`DeprecationWarning`.
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
    damage_areas : tuple of float
        Areas in m² on which the damage probability at the hardness is given (the growth with
        the area, and the allowable load): 1 mm², 1 cm² and 10 cm² by default.
    target_damage : float
        Damage probability the allowable nominal pressure must not exceed on each of
        ``damage_areas`` (campaigns of several loads; :mod:`glstat.study.allowable`).
    tail : {"pareto", None}
        The model of the upper tail (:func:`glstat.predict_maximum`) of the spot and
        per-asperity samples: ``"pareto"`` (default), every GLD with a generalized Pareto tail
        on the ceil(sqrt(N)) largest values of its sample and the calibrated intervals; None,
        the GLDs alone. The grid-point sample, the paper's predictor, always uses the GLD
        alone, as the paper did.
    criterion : {"surface", "subsurface", "plastic-zone"}
        What damages a surface (:mod:`glstat.study.criteria`): the elastic surface pressure
        reaching the hardness (the paper's, default), the von Mises stress beneath the surface
        reaching ``yield_stress``, or a connected plastic zone of the capped solution of at
        least ``min_plastic_area``. The asperity model answers under the surface criterion.
    yield_stress : float or None
        Yield stress Y in Pa of the subsurface criterion; None: hardness / 2.8 (Tabor).
    min_plastic_area : float or None
        Smallest plastic zone in m² of the plastic-zone criterion; None: a disc of diameter λs
        (the S-filter's nesting index), or of three grid spacings without an S-filter.
    """

    hardness: float = 2050e6
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
    damage_areas: tuple[float, ...] = (1e-6, 1e-4, 1e-3)
    target_damage: float = 0.01
    tail: str | None = "pareto"
    criterion: str = "surface"
    yield_stress: float | None = None
    min_plastic_area: float | None = None

    def criterion_of(self, settings) -> Criterion:
        """The damage criterion with its thresholds resolved against the campaign ``settings``
        (the default minimum plastic area depends on λs or the grid spacing)."""
        from .criteria import TABOR_FACTOR

        area = self.min_plastic_area
        if area is None:
            lam = settings.s_filter if settings.s_filter is not None else 3 * max(settings.spacing)
            area = math.pi * lam ** 2 / 4
        return Criterion(self.criterion, self.hardness,
                         self.hardness / TABOR_FACTOR if self.yield_stress is None
                         else self.yield_stress, area, self.yield_stress is not None,
                         self.min_plastic_area is not None,
                         "λs" if settings.s_filter is not None else "3 grid spacings")

    @property
    def hardness_mpa(self) -> float:
        """The hardness in MPa, the unit of the study's tables and report."""
        return self.hardness / 1e6

    def __post_init__(self) -> None:
        from _glstat_runtime.validation import check_level, positive_finite

        hardness = positive_finite(self.hardness, "hardness", "pressure in Pa")
        if hardness < MPA_FORM_BELOW:
            warnings.warn(f"AnalysisSettings.hardness is in Pa; {hardness:g} was read as {hardness:g} "
                          f"MPa, the unit of earlier releases: give hardness={hardness:g}e6",
                          DeprecationWarning, stacklevel=3)
            hardness *= 1e6
        object.__setattr__(self, "hardness", float(hardness))
        for name in ("n_resamples", "grid_resamples"):
            v = getattr(self, name)
            if int(v) != v or v < 10:
                raise ValueError(f"{name} (bootstrap B) must be an integer >= 10, got {v!r}")
        for name in ("confidence_level", "test_level", "integrity_level"):
            check_level(getattr(self, name), name)
        if isinstance(self.seed, bool) or int(self.seed) != self.seed or self.seed < 0:
            raise ValueError(f"seed must be an integer >= 0, got {self.seed!r}")
        if not self.area_factors or any(not (math.isfinite(v) and v > 0) for v in self.area_factors):
            raise ValueError(f"area_factors must be positive finite numbers, got {self.area_factors!r}")
        if int(self.n_levels) != self.n_levels or self.n_levels < 5:
            raise ValueError(f"n_levels must be an integer >= 5, got {self.n_levels!r}")
        areas = tuple(positive_finite(v, "damage_areas", "area in square metres")
                      for v in np.atleast_1d(self.damage_areas))
        if not areas:
            raise ValueError("damage_areas must hold one or more areas in m²")
        object.__setattr__(self, "damage_areas", tuple(sorted(set(areas))))
        if not (0.0 < self.target_damage < 1.0):
            raise ValueError(f"target_damage must be a probability in (0, 1), got "
                             f"{self.target_damage!r}")
        if self.tail not in ("pareto", None):
            raise ValueError(f"tail must be 'pareto' or None, got {self.tail!r}")
        if self.criterion not in CRITERIA:
            raise ValueError(f"criterion must be one of {', '.join(map(repr, CRITERIA))}, got "
                             f"{self.criterion!r}")
        if self.yield_stress is not None:
            y = positive_finite(self.yield_stress, "yield_stress", "yield stress in Pa")
            if y >= self.hardness:
                raise ValueError(f"yield stress {y / 1e6:g} MPa is not below the hardness "
                                 f"{self.hardness / 1e6:g} MPa: for metals H ≈ 2.8 Y (Tabor); give "
                                 f"a yield stress below the hardness, or leave it out for H / 2.8")
            object.__setattr__(self, "yield_stress", float(y))
        if self.min_plastic_area is not None:
            object.__setattr__(self, "min_plastic_area", positive_finite(
                self.min_plastic_area, "min_plastic_area", "area in square metres"))



# -- samples of the surfaces -------------------------------------------------------------------
def surface_values(res: dict, sample: str) -> tuple[np.ndarray, int, float]:
    """(values in MPa, count, observed maximum in MPa) of one surface's result.

    The observed maximum is the surface's maximal pressure for every sample: the event the
    damage probability is about. For the spot sample it is the largest spot peak; for the
    per-asperity sample it can lie above every asperity's own peak where patches overlap."""
    if sample == "grid":
        return res["samples"] / 1e6, int(res["n_contact"]), float(res["max_pressure"]) / 1e6
    if sample not in GROUPED_SAMPLES:
        raise ValueError(f"unknown sample {sample!r}; expected one of {tuple(SAMPLES)}")
    if SAMPLES[sample][0] not in res:
        raise KeyError(f"the stored result has no {SAMPLES[sample][0]!r} (written by an earlier "
                       "version): rerun the campaign with --force")
    peaks = np.asarray(res[SAMPLES[sample][0]], dtype=float) / 1e6
    return peaks, int(peaks.size), float(res["max_pressure"]) / 1e6


#: A surface's maximal pressure above its largest asperity peak by more than this fraction is
#: set by overlapping asperity patches (their pressures add up).
OVERLAP_MARGIN = 0.01


def overlap_sets_maximum(res: dict) -> bool:
    """Whether a surface's maximal grid pressure exceeds every asperity's own peak (the
    patches of neighbouring asperities overlap there and their pressures add up)."""
    peaks = np.asarray(res.get("asperity_peak", ()), dtype=float)
    return bool(peaks.size and float(res["max_pressure"]) > (1 + OVERLAP_MARGIN) * peaks.max())


def pool(per: list) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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
                   threshold: float | None = None, maximum: bool = False, maximum_rng=None,
                   sample: str = PRIMARY_SAMPLE):
    """:func:`glstat.predict_maximum` with the settings' resamples, level and tail: the first
    of ``fits`` that has a solution, likelihood fits on at most MLE_RESAMPLES resamples. The
    grid-point ``sample`` is the paper's predictor, reproduced as the paper made it: the GLD
    alone, on the settings' ``grid_resamples``."""
    grid = sample == "grid"
    from ..prediction import predict_maximum

    return predict_maximum(x, fits, n=n, groups=groups, threshold=threshold,
                           n_resamples=a.grid_resamples if grid else (n_resamples or a.n_resamples),
                           likelihood_resamples=MLE_RESAMPLES,
                           confidence_level=a.confidence_level, rng=rng, maximum=maximum,
                           maximum_rng=maximum_rng, tail=None if grid else a.tail)


