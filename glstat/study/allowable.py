"""The allowable load: the nominal pressure that keeps the damage probability below a target.

A campaign of several nominal pressures (``glstat study --pressure P1 P2 …``) gives, per case
(H or measured group) and contact model, the damage probability at the hardness on each area
of :attr:`AnalysisSettings.damage_areas` at every pressure, with its bootstrap interval. The
allowable nominal pressure on an area is where that curve crosses the target
(:attr:`AnalysisSettings.target_damage`, 1 % by default): found between the two loads that
bracket it, linearly in the logit of the damage probability against the pressure. Its interval
comes from the interval's ends: the upper end of the damage crosses the target at the lower
allowable pressure, the lower end at the higher. Nothing is extrapolated: a target below the
damage at the lowest load or above it at the highest is reported as such ("below P1",
"above Pn"), and a crossing between loads whose held-out checks did not both pass says so.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .analysis_settings import PRIMARY_SAMPLE

__all__ = ["ALLOWABLE_COLUMNS", "allowable_frame", "allowable_text", "area_words", "crossing"]

#: Columns of ``allowable_load.csv``.
ALLOWABLE_COLUMNS = ("model", "hurst", "area_mm2", "target_damage", "allowable_pressure_mpa",
                     "allowable_low_mpa", "allowable_high_mpa", "status", "bracket_mpa",
                     "checks", "spacing_um", "s_filter_um", "criterion")


def area_words(m2: float) -> str:
    """An area in the unit a reader uses: "25 mm²" below 1 cm², "10 cm²" from 1 cm² on (the
    area in m²)."""
    mm2 = round(m2 * 1e6, 9)  # 1e-4 m² is 99.99999999999999 mm² in binary
    return f"{mm2:g} mm²" if mm2 < 100 else f"{mm2 / 100:g} cm²"


def allowable_text(row, pressures, interval: bool = True) -> str:
    """One row of :func:`allowable_frame` as text: "7.3 MPa [2.97, —]" when interpolated,
    "< 5 MPa (below the lowest load)" or "> 20 MPa (above the highest load)" otherwise
    (``pressures`` in Pa, the loads run)."""
    def mpa(v: float) -> str:
        return "—" if v != v else f"{v:.3g}"

    status = row["status"]
    if status == "interpolated":
        spread = (f" [{mpa(row['allowable_low_mpa'])}, {mpa(row['allowable_high_mpa'])}]"
                  if interval else "")
        return f"{row['allowable_pressure_mpa']:.3g} MPa{spread}"
    if status == "below the lowest load":
        return f"< {min(pressures) / 1e6:g} MPa ({status})"
    if status == "above the highest load":
        return f"> {max(pressures) / 1e6:g} MPa ({status})"
    return f"— ({status})"


def _logit(p: np.ndarray) -> np.ndarray:
    q = np.clip(np.asarray(p, dtype=float), 1e-12, 1 - 1e-12)
    return np.log(q) - np.log1p(-q)


def crossing(pressures, damage, target: float) -> tuple[float, str, int]:
    """The pressure at which an increasing damage curve reaches ``target``.

    Parameters
    ----------
    pressures : array_like
        Nominal pressures, increasing.
    damage : array_like
        Damage probability at each pressure.
    target : float
        The damage probability sought, in (0, 1).

    Returns
    -------
    pressure : float
        Linear interpolation of the logit of the damage against the pressure between the
        first two loads that bracket the target; NaN when none does.
    status : str
        ``"interpolated"``, ``"below the lowest load"`` (the damage exceeds the target at every
        load), ``"above the highest load"`` (it stays below at every load) or ``"no
        estimate"`` (NaN damage).
    index : int
        The lower bracketing load's index (-1 when not interpolated).

    Examples
    --------
    >>> from glstat.study.allowable import crossing
    >>> p, status, _ = crossing([10, 20, 40], [0.001, 0.01, 0.2], 0.01)
    >>> round(p, 6), status
    (20.0, 'interpolated')
    """
    p = np.asarray(pressures, dtype=float)
    d = np.asarray(damage, dtype=float)
    if d.size == 0 or not np.all(np.isfinite(d)):
        return math.nan, "no estimate", -1
    if d[0] > target:
        return math.nan, "below the lowest load", -1
    for k in range(d.size - 1):
        if d[k] <= target <= d[k + 1] and d[k + 1] > d[k]:
            y0, y1, yt = _logit(np.array([d[k], d[k + 1], target]))
            if not y1 > y0:
                return float(p[k]), "interpolated", k
            w = float(np.clip((yt - y0) / (y1 - y0), 0.0, 1.0))
            return float(p[k] + w * (p[k + 1] - p[k])), "interpolated", k
    if d[-1] <= target:
        return math.nan, "above the highest load", -1
    return math.nan, "no estimate", -1  # not increasing: the curve crosses back


def allowable_frame(settings, asettings, analyses: dict[str, dict],
                    bem_grid: int | None = None) -> Any:
    """``allowable_load.csv``: the allowable nominal pressure per model, case and area.

    Parameters
    ----------
    settings : CampaignSettings
        The campaign (its ``pressures`` in Pa, two or more for a crossing).
    asettings : AnalysisSettings
        Its ``damage_areas`` (m²) and ``target_damage``.
    analyses : dict
        ``model -> analysis`` (:func:`glstat.study.analysis.analyse`): "bem" and/or
        "asperity".

    Returns
    -------
    pandas.DataFrame
        One row per model × H × area: ``allowable_pressure_mpa`` (where the damage estimate
        crosses the target), ``allowable_low_mpa`` and ``allowable_high_mpa`` (where the upper
        and the lower end of its interval cross it; NaN when they do not between the loads),
        ``status`` (:func:`crossing`), ``bracket_mpa`` (the two loads it lies between) and
        ``checks`` (the held-out checks at those loads), ``spacing_um``, ``s_filter_um`` and
        ``criterion`` (the scale and the damage criterion the load holds at).
    """
    import pandas as pd

    from .scales import s_filter_um, spacing_um

    order = np.argsort(settings.pressures)
    loads = np.asarray(settings.pressures, dtype=float)[order] / 1e6
    rows = []
    for model, analysis in analyses.items():
        if not analysis:
            continue
        for ih in sorted({ih for ih, _ in analysis}):
            found = [analysis.get((ih, int(il))) for il in order]
            cases = [c for c in found if c is not None and c[PRIMARY_SAMPLE].area_damage is not None]
            if len(cases) < len(found):
                continue
            tables = [c[PRIMARY_SAMPLE].area_damage for c in cases]
            verdicts = [c[PRIMARY_SAMPLE].validation.verdict() if c[PRIMARY_SAMPLE].ok
                        else "not checked" for c in cases]
            for ia, area in enumerate(tables[0]["area_mm2"]):
                est, low, high = (np.array([t.iloc[ia][col] for t in tables], dtype=float)
                                  for col in ("estimate", "low", "high"))
                target = asettings.target_damage
                p, status, k = crossing(loads, est, target)
                p_low, _, _ = crossing(loads, high, target)
                p_high, _, _ = crossing(loads, low, target)
                bracket = checks = ""
                if k >= 0:
                    bracket = f"{loads[k]:g}–{loads[k + 1]:g}"
                    checks = f"{verdicts[k]}, {verdicts[k + 1]}"
                rows.append({"model": model, "hurst": settings.hurst[ih], "area_mm2": float(area),
                             "target_damage": target, "allowable_pressure_mpa": p,
                             "allowable_low_mpa": p_low, "allowable_high_mpa": p_high,
                             "status": status, "bracket_mpa": bracket, "checks": checks,
                             "spacing_um": spacing_um(settings,
                                                      bem_grid if model == "bem" else None),
                             "s_filter_um": s_filter_um(settings),
                             "criterion": (asettings.criterion if model == "bem"
                                           and asettings.criterion == "subsurface" else "surface")})
    return pd.DataFrame(rows, columns=list(ALLOWABLE_COLUMNS))
