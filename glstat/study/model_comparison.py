"""The asperity model against the elastic BEM on a set of surfaces at one load: per-surface
tables, the GLD of each model's contact-spot peak pressures and the damage probability
predicted from each (:class:`BEMComparison`, :func:`compare_bem`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..prediction import MaximumPrediction
from .analysis_settings import AnalysisSettings, fit_order, predict_sample, sample_rng
from .both_models import MODELS, contact_record, interior, solve_both

__all__ = ["QUANTITIES", "QUANTITY_LABELS", "SHORT_LABELS", "BEMComparison", "compare_bem",
           "compare_records"]

#: Quantities compared surface by surface (column names of :attr:`BEMComparison.surfaces`).
QUANTITIES = ("contact_fraction", "mean_pressure_MPa", "max_pressure_MPa")
SHORT_LABELS = {"contact_fraction": "contact fraction", "mean_pressure_MPa": "mean contact pressure",
                "max_pressure_MPa": "maximal pressure"}
QUANTITY_LABELS = {"contact_fraction": "contact fraction 1 − α",
                   "mean_pressure_MPa": "mean contact pressure (MPa)",
                   "max_pressure_MPa": "maximal pressure (MPa)"}
#: Seed slot of the comparison's bootstraps (distinct from the study's slots 0–6).
SEED_SLOT = 20


@dataclass
class BEMComparison:
    """The asperity model against the elastic BEM on a set of surfaces at one load.

    Attributes
    ----------
    surfaces : pandas.DataFrame
        Tidy, one row per (surface, model): ``surface``, ``model`` (``"asperity"`` or
        ``"bem"``), ``contact_fraction``, ``mean_pressure_MPa`` (over the points in
        contact), ``max_pressure_MPa`` (the largest pressure of the spots inside the patch),
        ``n_contact``, ``n_clusters`` (connected contact spots inside the patch),
        ``n_border_spots`` (spots touching the patch border, left out of the peaks, the
        maximum and the fits, see :func:`contact_record`), ``mean_peak_MPa`` (mean of the
        inner spots' highest pressures),
        ``border_load_fraction`` (share of the load on the outermost grid rows and columns),
        ``force_error``, ``converged``, ``n_iterations``.
    fits : dict
        ``model -> glstat.prediction.MaximumPrediction``: the GLD of the peak pressure of
        every contact spot inside the patch (MPa; the spots of a surface are its random
        count) and the damage probability at the hardness with its bootstrap interval.
    hardness : float
        Pd in MPa.
    confidence_level : float
        Level of the damage intervals.
    """

    surfaces: Any
    fits: dict
    hardness: float
    confidence_level: float

    def to_frame(self) -> Any:
        """The per-surface table :attr:`surfaces`."""
        return self.surfaces

    def ratios(self) -> Any:
        """One row per surface: ``surface`` and, for every compared quantity, the ratio
        asperity / BEM (a pandas DataFrame; 1 means no error)."""
        wide = self.surfaces.pivot(index="surface", columns="model", values=list(QUANTITIES))
        out = {q: wide[(q, "asperity")] / wide[(q, "bem")] for q in QUANTITIES}
        import pandas as pd

        return pd.DataFrame(out).reset_index()

    def summary(self) -> Any:
        """One row per quantity: mean, standard deviation (across surfaces, ddof = 1), min and
        max of each model and of the ratio asperity / BEM (a pandas DataFrame)."""
        import pandas as pd

        r = self.ratios()
        rows = []
        for q in QUANTITIES:
            row: dict[str, str | float] = {"quantity": q}
            for m in MODELS:
                v = self.surfaces.loc[self.surfaces["model"] == m, q].to_numpy(dtype=float)
                v = v[np.isfinite(v)]  # a surface without a spot inside the patch has no maximum
                row[f"{m}_mean"] = float(np.mean(v)) if v.size else math.nan
                row[f"{m}_std"] = float(np.std(v, ddof=1)) if v.size > 1 else math.nan
            v = r[q].to_numpy(dtype=float)
            v = v[np.isfinite(v)]
            row.update(ratio_mean=float(np.mean(v)) if v.size else math.nan,
                       ratio_std=float(np.std(v, ddof=1)) if v.size > 1 else math.nan,
                       ratio_min=float(np.min(v)) if v.size else math.nan,
                       ratio_max=float(np.max(v)) if v.size else math.nan)
            rows.append(row)
        return pd.DataFrame(rows)

    def fit_frame(self) -> Any:
        """One row per model: ``model``, ``n`` (pooled points), ``n_ref``, ``fit``, ``lambda1``
        .. ``lambda4`` (λ1 in MPa, λ2 in 1/MPa), ``damage``, ``damage_low``,
        ``damage_high`` (at the hardness, one analysed area) and ``note``."""
        import pandas as pd

        rows = []
        for m in MODELS:
            f = self.fits[m]
            lam = f.boot.fit.lambdas if f.ok else (math.nan,) * 4
            d = f.damage
            spots = self.surfaces.loc[self.surfaces["model"] == m, "n_clusters"]
            rows.append({"model": m, "n": int(f.data.size),
                         "n_ref": max(float(spots.mean()), 1.0) if len(spots) else 1.0,
                         "fit": f"{f.param.upper()} {f.method}" if f.ok else "none",
                         **{f"lambda{j + 1}": float(lam[j]) for j in range(4)},
                         "damage": math.nan if d is None else float(d.estimate),
                         "damage_low": math.nan if d is None else float(d.low),
                         "damage_high": math.nan if d is None else float(d.high),
                         "note": f.note})
        return pd.DataFrame(rows)


def model_spots(record: Mapping[str, Any], model: str) -> dict[str, Any]:
    """The contact spots of one model's solution that the study analyses: for the elastic BEM
    those inside the patch (:func:`glstat.study.both_models.interior`: a spot cut by the
    patch's edge carries its singularity), for the asperity model every spot, as the answer's
    analysis of the campaign does (its pressure has no edge singularity), so that one page gives
    one asperity-model answer."""
    inner = interior(record)
    if model == "bem":
        return inner
    peaks = np.asarray(record["cluster_peaks"], dtype=float)
    return {**inner, "peaks": peaks, "n_spots": int(peaks.size),
            "max_pressure": float(peaks.max()) if peaks.size else 0.0}


def compare_records(entries: Sequence[tuple[Any, Mapping[str, Mapping[str, np.ndarray | np.generic]]]],
             a: AnalysisSettings,
             key: tuple[int, ...]) -> BEMComparison:
    """Tables, GLD fits and damage of both models from per-surface records."""
    import pandas as pd

    rows = []
    for label, rec in entries:
        for m in MODELS:
            r = rec[m]
            # like for like: the maxima of both models over the spots inside the patch
            inner = interior(r)
            spot_peaks = inner["peaks"]
            rows.append({"surface": label, "model": m,
                         "contact_fraction": float(r["contact_fraction"]),
                         "mean_pressure_MPa": float(r["mean_pressure"]) / 1e6,
                         # no spot inside the patch: no maximum to compare (NaN, not 0)
                         "max_pressure_MPa": (inner["max_pressure"] / 1e6 if inner["n_spots"]
                                              else math.nan),
                         "n_contact": int(r["n_contact"]), "n_clusters": inner["n_spots"],
                         "n_border_spots": inner["n_border_spots"],
                         "mean_peak_MPa": (float(spot_peaks.mean()) / 1e6 if spot_peaks.size
                                           else math.nan),
                         "border_load_fraction": float(r["border_load_fraction"]),
                         "force_error": float(r["force_error"]),
                         "converged": bool(r["converged"]), "n_iterations": int(r["n_iterations"])})
    surfaces = pd.DataFrame(rows)
    fits = {}
    for j, m in enumerate(MODELS):
        # the peak pressure of every contact spot, with the spots per surface as a random count:
        # the study's primary predictor applied to each model as the answer applies it
        peaks = [model_spots(rec[m], m)["peaks"] / 1e6 for _, rec in entries]
        data = np.concatenate(peaks)
        labels = np.repeat(np.arange(len(peaks)), [p.size for p in peaks])
        n_ref = max(float(np.mean([p.size for p in peaks])), 1.0)
        if data.size < 5:
            f = MaximumPrediction(data=data, param="", method="", boot=None, threshold=a.hardness_mpa,
                                  note=f"only {data.size} spot peaks on {len(entries)} surfaces; "
                                       "at least 5 are needed")
        else:
            # several surfaces: resample them, their spot counts the random count; one surface:
            # resample its spots, with its spot count as n
            several = len(peaks) >= 2
            f = predict_sample(data, a, sample_rng(a, *key, SEED_SLOT + j), fit_order(a),
                               groups=labels if several else None,
                               n=None if several else n_ref, threshold=a.hardness_mpa)
        fits[m] = f
    return BEMComparison(surfaces=surfaces, fits=fits, hardness=a.hardness_mpa,
                         confidence_level=a.confidence_level)


def compare_bem(
    surfaces: Any,
    nominal_pressure: float,
    E: float,
    nu: float,
    *,
    cone_factor: float = 0.2,
    counter_face: Sequence[float] | None = None,
    periodic: bool = False,
    tol: float = 1e-8,
    max_iter: int = 1000,
    analysis: AnalysisSettings | None = None,
    workers: int | None = None,
) -> BEMComparison:
    """Compare the asperity model with the elastic BEM on your own surfaces.

    Each surface is solved with :func:`contact.solve` and :func:`contact.solve_bem` at the same
    nominal pressure; the contact-spot peak pressures of each model, pooled over the surfaces, get a
    GLD by the study's method with a bootstrap, from which the damage probability at the
    hardness follows.

    Parameters
    ----------
    surfaces : contact.Surface or iterable of contact.Surface
        The rough surfaces (heights in metres), all analysed as samples of one topography.
    nominal_pressure : float
        Imposed nominal pressure in pascals, > 0.
    E : float
        Young's modulus of the rough body in pascals.
    nu : float
        Poisson ratio of the rough body.
    cone_factor : float, default 0.2
        ``c`` of the asperity model (:func:`contact.solve`).
    counter_face : (E2, nu2) or None
        Elastic constants of the flat (Pa, dimensionless); None for a rigid flat.
    periodic : bool, default False
        Boundary condition of the BEM: False for an isolated patch (right for measured
        topographies and Weierstrass surfaces, which do not repeat), True only for surfaces
        that are periodic on their grid (e.g. :func:`contact.self_affine`).
    tol, max_iter : float, int
        Tolerance and iteration limit of the BEM.
    analysis : AnalysisSettings, optional
        Hardness (MPa), bootstrap resamples, GLD parameterisation and method, confidence
        level and seed (default ``AnalysisSettings()``: 2050 MPa, B = 1000, RS by moments).
    workers : int, optional
        Threads of :mod:`scipy.fft` in the BEM.

    Returns
    -------
    BEMComparison
        ``surfaces`` (tidy per-surface table, surfaces numbered from 0), ``summary()``,
        ``ratios()``, ``fit_frame()`` (GLD and damage probability per model).

    Raises
    ------
    TypeError
        An element is not a :class:`contact.Surface`.
    ValueError
        No surface, or bad load, moduli or options (as raised by the solvers).
    """
    import contact

    if isinstance(surfaces, contact.Surface):
        surfaces = [surfaces]
    if not isinstance(surfaces, Iterable):
        raise TypeError(f"surfaces must be a contact.Surface or a sequence of them, got "
                        f"{type(surfaces).__name__}")
    surfaces = list(surfaces)
    if not surfaces:
        raise ValueError("surfaces is empty: give at least one contact.Surface")
    for j, s in enumerate(surfaces):
        if not isinstance(s, contact.Surface):
            raise TypeError(f"surfaces[{j}] must be a contact.Surface, got {type(s).__name__}; wrap "
                            f"a height array with contact.Surface(heights, dx)")
    a = analysis or AnalysisSettings()
    entries = []
    for j, s in enumerate(surfaces):
        asp, bem, _, _ = solve_both(s, nominal_pressure, E, nu, cone_factor, counter_face, periodic,
                                     tol, max_iter, workers, False)
        entries.append((j, {"asperity": contact_record(asp), "bem": contact_record(bem)}))
    return compare_records(entries, a, (0, 0))


