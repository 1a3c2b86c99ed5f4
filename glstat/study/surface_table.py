"""Per-surface results of a study and the answer against the scale.

* :func:`surfaces_frame` — ``surfaces.csv``: one row per surface or area with its scale, its
  roughness, its data quality (outlier points found and replaced) and each model's maximal
  pressure, plastic area and verdict under every criterion.
* :func:`criteria_frame` — per case, the fraction of areas damaged under each criterion with
  its exact (Clopper–Pearson) interval: what the surfaces show, without a fitted model.
* :func:`scale_frame` — per case and multiple of λs (the surfaces solved again with a coarser
  S-filter): the median maximal pressure, the median plastic area, and the fraction damaged
  under the study's criterion with its exact interval; :func:`resolution_note` says when the
  answer moves between the two finest scales by more than its interval.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from .criteria import CRITERIA, Criterion, exact_interval
from .scales import s_filter_um, spacing_um

__all__ = ["SURFACE_COLUMNS", "criteria_frame", "resolution_note", "scale_frame",
           "surfaces_frame"]

#: Columns of ``surfaces.csv``.
SURFACE_COLUMNS = ("name", "hurst", "pressure_mpa", "spacing_um", "bem_spacing_um", "s_filter_um",
                   "sq_um", "sdq",
                   "spikes", "spike_largest_um", "spikes_replaced", "max_on_spike",
                   "height_step_nm", "asperity_max_pressure_mpa", "bem_max_pressure_mpa",
                   "bem_max_von_mises_mpa", "plastic_area_um2", "plastic_area_cells",
                   "largest_plastic_zone_um2", "bem_converged", "damaged_surface",
                   "damaged_subsurface", "damaged_plastic_zone")


def _name(settings: Any, ih: int, i: int) -> str:
    if settings.measured:
        return settings.surface_name(i)
    return f"H = {settings.hurst[ih]:g}, surface {i + 1}"


def _verdicts(rec: dict | None, crit: Criterion) -> dict[str, Any]:
    """Whether an elastic record is damaged under each criterion (None where the figure is
    not computed)."""
    if rec is None:
        return dict.fromkeys(("damaged_surface", "damaged_subsurface", "damaged_plastic_zone"))
    zones = rec.get("plastic_zone_areas")
    vm = rec.get("max_von_mises")
    return {"damaged_surface": bool(float(rec["max_surface_pressure"]) >= crit.hardness),
            "damaged_subsurface": None if vm is None else bool(float(vm) >= crit.yield_stress),
            "damaged_plastic_zone": None if zones is None else
            bool(np.size(zones) and float(np.max(zones)) >= crit.min_plastic_area)}


def surfaces_frame(settings: Any, crit: Criterion, results: dict, bem_records: dict | None,
                   left_out: list | None = None, bem_grid: int | None = None):
    """``surfaces.csv``: one row per surface (or area) and load, as a pandas DataFrame.

    Columns: ``name`` (the file and area, or the case and surface number), ``hurst``,
    ``pressure_mpa`` (nominal), ``spacing_um`` (``bem_spacing_um``: the elastic BEM's, when it
    solves simulated surfaces on a grid of its own), ``s_filter_um`` (λs, NaN without an S-filter),
    ``sq_um`` and ``sdq`` (ISO 25178, at the study's scale; measured files), ``spikes`` (outlier
    points found in the file's area, :func:`contact.find_spikes`), ``spike_largest_um`` (the
    largest one's height above or below its neighbourhood), ``spikes_replaced`` (whether
    ``despike`` replaced them), ``max_on_spike`` (whether the elastic maximal pressure lies on
    or next to one), ``height_step_nm`` (the smallest step between stored heights),
    ``asperity_max_pressure_mpa``, ``bem_max_pressure_mpa`` (elastic, spots inside the patch),
    ``bem_max_von_mises_mpa`` (with the subsurface criterion), ``plastic_area_um2`` and
    ``plastic_area_cells`` (points at the hardness in the capped solution),
    ``largest_plastic_zone_um2``, ``bem_converged`` and ``damaged_surface``,
    ``damaged_subsurface``, ``damaged_plastic_zone`` (the elastic solutions under each
    criterion; empty where not computed).
    """
    import pandas as pd

    bem_records = bem_records or {}
    dropped = set(left_out or ())
    cell = (float(np.prod(settings.spacing)) if bem_grid is None
            else (settings.length / bem_grid) ** 2)
    rows = []
    for key in sorted(set(results) | set(bem_records) | dropped):
        ih, il, i = key
        r = results.get(key, {})
        b = bem_records.get(key)
        zones = None if b is None else b.get("plastic_zone_areas")
        plastic = math.nan if zones is None else float(np.sum(zones))
        vm = None if b is None else b.get("max_von_mises")
        rows.append({
            "name": _name(settings, ih, i), "hurst": settings.hurst[ih],
            "pressure_mpa": settings.pressures[il] / 1e6, "spacing_um": spacing_um(settings),
            "bem_spacing_um": spacing_um(settings, bem_grid),
            "s_filter_um": s_filter_um(settings),
            "sq_um": float(r.get("iso_Sq", math.nan)) * 1e6, "sdq": float(r.get("iso_Sdq", math.nan)),
            "spikes": int(r["spike_count"]) if "spike_count" in r else None,
            "spike_largest_um": float(r.get("spike_largest", math.nan)) * 1e6,
            "spikes_replaced": bool(settings.despike),
            "max_on_spike": None if b is None or "max_on_spike" not in b else bool(b["max_on_spike"]),
            "height_step_nm": float(r.get("height_step", math.nan)) * 1e9,
            "asperity_max_pressure_mpa": float(r.get("max_pressure", math.nan)) / 1e6,
            "bem_max_pressure_mpa": math.nan if b is None else float(b["max_surface_pressure"]) / 1e6,
            "bem_max_von_mises_mpa": math.nan if vm is None else float(vm) / 1e6,
            "plastic_area_um2": plastic * 1e12, "plastic_area_cells": plastic / cell,
            "largest_plastic_zone_um2": (math.nan if zones is None else
                                         float(np.max(zones, initial=0.0)) * 1e12),
            "bem_converged": None if not bem_records else key not in dropped,
            **_verdicts(b, crit)})
    return pd.DataFrame(rows, columns=list(SURFACE_COLUMNS))


def _cases(records: dict) -> dict[tuple[int, int], list[dict]]:
    cases: dict[tuple[int, int], list[dict]] = {}
    for (ih, il, _), rec in sorted(records.items()):
        cases.setdefault((ih, il), []).append(rec)
    return cases


def criteria_frame(settings: Any, crit: Criterion, bem_records: dict, confidence_level: float):
    """Per case and criterion, the elastic solutions' fraction of areas damaged with its exact
    interval (pandas DataFrame: ``hurst``, ``pressure_mpa``, ``criterion``, ``threshold``
    (words), ``damaged``, ``n_surfaces``, ``fraction``, ``low``, ``high``); a criterion whose
    figure was not computed is left out."""
    import pandas as pd

    rows = []
    for (ih, il), recs in _cases(bem_records).items():
        verdicts = [_verdicts(r, crit) for r in recs]
        for name in CRITERIA:
            hits = [v[f"damaged_{name.replace('-', '_')}"] for v in verdicts]
            if any(h is None for h in hits) or not hits:
                continue
            k, n = int(sum(hits)), len(hits)
            low, high = exact_interval(k, n, confidence_level)
            c = dataclasses.replace(crit, name=name)
            rows.append({"hurst": settings.hurst[ih], "pressure_mpa": settings.pressures[il] / 1e6,
                         "criterion": name, "threshold": c.threshold_text(), "damaged": k,
                         "n_surfaces": n, "fraction": k / n, "low": low, "high": high})
    return pd.DataFrame(rows, columns=["hurst", "pressure_mpa", "criterion", "threshold",
                                       "damaged", "n_surfaces", "fraction", "low", "high"])


def scale_frame(settings: Any, crit: Criterion, bem_records: dict, confidence_level: float):
    """The answer against the scale (pandas DataFrame, empty without an S-filter): per case and
    multiple of λs, ``s_filter_um``, ``max_pressure_mpa`` (median over the areas of the
    elastic maximal pressure of the spots inside the patch), ``max_von_mises_mpa`` (median, with
    the subsurface stress), ``plastic_area_um2`` and ``largest_plastic_zone_um2`` (medians),
    and ``damaged``, ``n_surfaces``, ``fraction``, ``low``, ``high``: the areas damaged under
    the study's criterion with the exact interval."""
    import pandas as pd

    rows = []
    for (ih, il), recs in _cases(bem_records).items():
        recs = [r for r in recs if "scale_factors" in r]
        if not recs:
            continue
        factors = np.asarray(recs[0]["scale_factors"])
        for j, k in enumerate(factors):
            ok = [r for r in recs if bool(np.asarray(r["scale_converged"])[j])]
            pmax = np.array([float(r["scale_max_pressure"][j]) for r in ok])
            vm = np.array([float(r["scale_max_von_mises"][j]) for r in ok])
            area = np.array([float(r["scale_plastic_area"][j]) for r in ok])
            zone = np.array([float(r["scale_largest_zone"][j]) for r in ok])
            value = {"surface": pmax, "subsurface": vm, "plastic-zone": zone}[crit.name]
            hits = int(np.count_nonzero(value >= crit.threshold))
            low, high = exact_interval(hits, len(ok), confidence_level)
            rows.append({"hurst": settings.hurst[ih], "pressure_mpa": settings.pressures[il] / 1e6,
                         "scale_factor": int(k), "s_filter_um": int(k) * s_filter_um(settings),
                         "max_pressure_mpa": float(np.median(pmax)) / 1e6 if ok else math.nan,
                         "max_von_mises_mpa": float(np.median(vm)) / 1e6 if ok else math.nan,
                         "plastic_area_um2": float(np.median(area)) * 1e12 if ok else math.nan,
                         "largest_plastic_zone_um2": float(np.median(zone)) * 1e12 if ok else math.nan,
                         "damaged": hits, "n_surfaces": len(ok),
                         "fraction": hits / len(ok) if ok else math.nan, "low": low, "high": high})
    return pd.DataFrame(rows)


#: Relative change of the median maximal pressure between the two finest scales beyond which
#: the answer is called resolution-dominated even when the damaged fractions' intervals overlap.
PRESSURE_MOVE = 0.25


def resolution_note(settings: Any, frame) -> str:
    """A warning when the answer moves between the two finest scales by more than its interval
    ("" otherwise): the fraction damaged at 2λs lies outside the exact interval at λs, or the
    median maximal pressure changes by more than :data:`PRESSURE_MOVE`."""
    if frame is None or len(frame) == 0:
        return ""
    parts = []
    for (h, p), g in frame.groupby(["hurst", "pressure_mpa"], sort=False):
        g = g.sort_values("scale_factor")
        if len(g) < 2:
            continue
        a, b = g.iloc[0], g.iloc[1]
        moved = not (a["low"] <= b["fraction"] <= a["high"])
        ratio = b["max_pressure_mpa"] / a["max_pressure_mpa"] if a["max_pressure_mpa"] > 0 else 1.0
        if moved or abs(ratio - 1) > PRESSURE_MOVE:
            case = "measured" if settings.measured else f"H = {h:g}"
            if len(settings.pressures) > 1:
                case += f", {p:g} MPa"
            parts.append(f"{case}: {100 * a['fraction']:.3g} % of the areas damaged at λs = "
                         f"{a['s_filter_um']:.3g} µm [{100 * a['low']:.3g}, {100 * a['high']:.3g}], "
                         f"{100 * b['fraction']:.3g} % at {b['s_filter_um']:.3g} µm; median maximal "
                         f"pressure {a['max_pressure_mpa']:.4g} → {b['max_pressure_mpa']:.4g} MPa")
    if not parts:
        return ""
    return ("The answer is resolution-dominated: it moves by more than its interval when the "
            "S-filter is doubled (" + "; ".join(parts) + "). It describes the surface at the "
            "stated λs only; features near that scale decide it.")
