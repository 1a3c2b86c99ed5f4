"""The allowable load: the nominal pressure that keeps the damage probability below a target.

Every load solved gives, per case (H or measured group) and contact model, the damage
probability at the hardness on each area of :attr:`AnalysisSettings.damage_areas`, with its
bootstrap interval: a *probe* (:class:`Probe`). The probes of one case and area, sorted by the
load, are its damage curve. The allowable nominal pressure on an area is where that curve
reaches the target (:attr:`AnalysisSettings.target_damage`, 1 % by default):

* the curve is made monotone first (the damage cannot fall when the load rises on the same
  surfaces; :func:`monotone` pools adjacent probes that disagree, and the table flags where
  it had to, ``monotone = False``);
* the crossing is interpolated between the two probes that bracket the target in the logarithm
  of the load: linearly in the logit of the probability when both lie strictly between 0 and 1,
  linearly in the probability when one of them is exactly 0 or 1 (a logit of 0 has no value;
  the linear form puts the crossing nearer the lower, safer load when the curve is convex);
* its interval is where the ends of the probability's interval cross the target (the upper end
  at the lower allowable pressure); an end that does not cross between the probes is written
  "< a" or "> b" with the load it is beyond;
* nothing is extrapolated: a target below the damage at the lowest load or above it at the
  highest is reported as such.

With ``glstat study --allowable`` (:mod:`glstat.study.allowable_search`) the loads are not only
those of the campaign: the search solves new ones until the crossing is bracketed within 10 %,
then solves the load it found and keeps it only when the target lies inside the interval of
the damage predicted there (``status = "verified"``).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .analysis_settings import PRIMARY_SAMPLE

__all__ = ["ALLOWABLE_COLUMNS", "PROBE_COLUMNS", "Probe", "allowable_frame", "allowable_row",
           "allowable_text", "area_words", "campaign_probes", "crossing", "monotone",
           "probes_frame"]

#: Columns of ``allowable_load.csv``.
ALLOWABLE_COLUMNS = ("model", "hurst", "area_mm2", "target_damage", "allowable_pressure_mpa",
                     "allowable_low_mpa", "allowable_high_mpa", "interval_mpa", "status",
                     "bracket_mpa", "checks", "damage_at_allowable", "damage_low", "damage_high",
                     "monotone", "probes_mpa", "spacing_um", "s_filter_um", "criterion")

#: Columns of ``allowable_probes.csv``: one row per load solved, case and area.
PROBE_COLUMNS = ("model", "hurst", "area_mm2", "pressure_mpa", "role", "damage", "damage_low",
                 "damage_high", "monotone_damage", "check")

#: Roles of a probe: a load of the campaign, one stepping out to bracket the target, a
#: bisection in the logarithm of the load, and the verification of a load found.
ROLES = ("campaign", "bracket", "bisection", "verification")


@dataclass(frozen=True)
class Probe:
    """The damage probability predicted at one nominal pressure, for one case and area.

    Attributes
    ----------
    pressure : float
        Nominal pressure (Pa).
    estimate, low, high : float
        The damage probability and its interval (NaN without a prediction).
    check : str
        The held-out check's verdict at this load ("not checked" without one).
    role : str
        One of :data:`ROLES`.
    """

    pressure: float
    estimate: float
    low: float
    high: float
    check: str = "not checked"
    role: str = "campaign"

    @property
    def usable(self) -> bool:
        """Whether the probe has a finite prediction and interval."""
        return all(math.isfinite(v) for v in (self.estimate, self.low, self.high))

    def holds(self, target: float) -> bool:
        """Whether ``target`` lies inside the probe's interval."""
        return self.usable and self.low <= target <= self.high


def area_words(m2: float) -> str:
    """An area in the unit a reader uses: "25 mm²" below 1 cm², "10 cm²" from 1 cm² on (the
    area in m²)."""
    mm2 = round(m2 * 1e6, 9)  # 1e-4 m² is 99.99999999999999 mm² in binary
    return f"{mm2:g} mm²" if mm2 < 100 else f"{mm2 / 100:g} cm²"


def _end_text(value: float, status: str, loads_mpa: Sequence[float] | np.ndarray) -> str:
    """One end of the allowable load's interval: its value, or the load it lies beyond."""
    if math.isfinite(value):
        return f"{value:.3g}"
    if status == "below the lowest load" and len(loads_mpa):
        return f"< {min(loads_mpa):.3g}"
    if status == "above the highest load" and len(loads_mpa):
        return f"> {max(loads_mpa):.3g}"
    return "—"


def allowable_text(row, pressures, interval: bool = True) -> str:
    """One row of :func:`allowable_frame` as text: "7.3 MPa [2.97, > 10]" when found,
    "< 5 MPa (below the lowest load)" or "> 20 MPa (above the highest load)" otherwise
    (``pressures`` in Pa, the loads solved). Whether a load found was verified is the row's
    ``status``, given with the damage predicted there (``damage_at_allowable``)."""
    status = row["status"]
    loads = [p / 1e6 for p in pressures]
    if status in ("interpolated", "verified", "not verified", "undetermined"):
        spread = ""
        if interval:
            spread = row.get("interval_mpa") or ""
            spread = f" {spread}" if spread else (
                f" [{_end_text(row['allowable_low_mpa'], '', loads)}, "
                f"{_end_text(row['allowable_high_mpa'], '', loads)}]")
        return f"{row['allowable_pressure_mpa']:.3g} MPa{spread}"
    if status == "below the lowest load":
        return f"< {min(loads):.3g} MPa ({status})"
    if status == "above the highest load":
        return f"> {max(loads):.3g} MPa ({status})"
    return f"— ({status})"


def monotone(values: Sequence[float]) -> np.ndarray:
    """The non-decreasing sequence closest to ``values`` in least squares (pool adjacent
    violators).

    Examples
    --------
    >>> from glstat.study.allowable import monotone
    >>> monotone([0.0, 0.04, 0.02, 0.3]).tolist()
    [0.0, 0.03, 0.03, 0.3]
    """
    blocks: list[list[float]] = []  # [mean, weight]
    for v in np.asarray(values, dtype=float):
        blocks.append([float(v), 1.0])
        while len(blocks) > 1 and blocks[-2][0] > blocks[-1][0]:
            (m1, w1), (m2, w2) = blocks[-2], blocks.pop()
            blocks[-1] = [(m1 * w1 + m2 * w2) / (w1 + w2), w1 + w2]
    return np.concatenate([np.full(int(w), m) for m, w in blocks]) if blocks else np.zeros(0)


def _logit(p: float) -> float:
    return math.log(p) - math.log1p(-p)


def crossing(pressures, damage, target: float) -> tuple[float, str, int]:
    """The pressure at which a non-decreasing damage curve reaches ``target``.

    Parameters
    ----------
    pressures : array_like
        Nominal pressures, increasing (any unit; the result is in the same).
    damage : array_like
        Damage probability at each pressure, non-decreasing (:func:`monotone`).
    target : float
        The damage probability sought, in (0, 1).

    Returns
    -------
    pressure : float
        The crossing between the first two pressures that bracket the target, interpolated in
        the logarithm of the pressure: linearly in the logit of the damage when both lie in
        (0, 1), linearly in the damage when one is exactly 0 or 1; NaN when no pair brackets it.
    status : str
        ``"interpolated"``, ``"below the lowest load"`` (the damage exceeds the target at every
        load), ``"above the highest load"`` (it stays at or below it at every load) or ``"no
        estimate"`` (NaN damage, or a curve that falls).
    index : int
        The lower bracketing load's index (-1 when not interpolated).

    Examples
    --------
    >>> from glstat.study.allowable import crossing
    >>> p, status, _ = crossing([10, 20, 40], [0.001, 0.01, 0.2], 0.01)
    >>> round(p, 6), status
    (20.0, 'interpolated')
    >>> p, status, _ = crossing([10, 20], [0.0, 1.0], 0.01)   # from exactly 0 to exactly 1
    >>> round(p, 4), status
    (10.0696, 'interpolated')
    """
    p = np.asarray(pressures, dtype=float)
    d = np.asarray(damage, dtype=float)
    if d.size == 0 or not np.all(np.isfinite(d)) or np.any(np.diff(d) < 0):
        return math.nan, "no estimate", -1
    if d[0] > target:
        return math.nan, "below the lowest load", -1
    if d[-1] <= target:
        return math.nan, "above the highest load", -1
    k = int(np.nonzero(d > target)[0][0]) - 1  # d[k] <= target < d[k + 1]
    d0, d1 = float(d[k]), float(d[k + 1])
    if 0.0 < d0 and d1 < 1.0:
        w = (_logit(target) - _logit(d0)) / (_logit(d1) - _logit(d0))
    else:
        w = (target - d0) / (d1 - d0)
    w = min(max(w, 0.0), 1.0)
    return float(math.exp(math.log(p[k]) + w * (math.log(p[k + 1]) - math.log(p[k])))), \
        "interpolated", k


def allowable_row(probes: Iterable[Probe], target: float) -> dict[str, Any]:
    """The allowable load of one damage curve: where the monotone curve of the usable
    ``probes`` reaches ``target``, its interval, and, when the curve holds a probe of role
    "verification" (the last one: the load a search found and solved), that load and what
    is predicted there.

    Returns
    -------
    dict
        ``allowable_pressure_mpa``, ``allowable_low_mpa``, ``allowable_high_mpa``,
        ``interval_mpa`` (text, "[< 5, 9.1]"), ``status`` ("interpolated"; with a
        verification probe "verified" when the target lies inside its interval, "undetermined"
        when it does only because that interval covers most of [0, 1]
        (:func:`glstat.prediction.undetermined`), "not verified" otherwise; or
        :func:`crossing`'s other statuses), ``bracket_mpa``, ``checks``,
        ``damage_at_allowable``, ``damage_low``, ``damage_high`` (NaN without such a probe),
        ``monotone`` (whether the curve needed no pooling) and ``probes_mpa``.
    """
    curve = sorted((q for q in probes if q.usable), key=lambda q: q.pressure)
    loads = np.array([q.pressure / 1e6 for q in curve])
    est, low, high = (monotone([getattr(q, f) for q in curve]) for f in ("estimate", "low", "high"))
    p, status, k = crossing(loads, est, target)
    p_low, s_low, _ = crossing(loads, high, target)
    p_high, s_high, _ = crossing(loads, low, target)
    row: dict[str, Any] = {
        "allowable_pressure_mpa": p, "allowable_low_mpa": p_low, "allowable_high_mpa": p_high,
        "interval_mpa": "", "status": status, "bracket_mpa": "", "checks": "",
        "damage_at_allowable": math.nan, "damage_low": math.nan, "damage_high": math.nan,
        "monotone": bool(np.array_equal(est, [q.estimate for q in curve])),
        "probes_mpa": " ".join(f"{v:.4g}" for v in loads)}
    if k < 0:
        return row
    row["interval_mpa"] = (f"[{_end_text(p_low, s_low, loads)}, "
                           f"{_end_text(p_high, s_high, loads)}]")
    row["bracket_mpa"] = f"{loads[k]:.4g}–{loads[k + 1]:.4g}"
    row["checks"] = f"{curve[k].check}, {curve[k + 1].check}"
    checked = [q for q in probes if q.role == "verification" and q.usable]
    if checked:  # the last load the search solved to verify its answer
        q = checked[-1]
        from ..prediction import undetermined

        status = ("not verified" if not q.holds(target) else
                  "undetermined" if undetermined(q.low, q.high) else "verified")
        row.update(damage_at_allowable=q.estimate, damage_low=q.low, damage_high=q.high,
                   allowable_pressure_mpa=q.pressure / 1e6, status=status)
    return row


def campaign_probes(settings, analysis: dict, role: str = "campaign",
                    ) -> dict[tuple[int, float], list[Probe]]:
    """The probes of an analysed campaign: ``(ih, area_m2) -> [Probe per load]`` from the
    primary sample's damage on every area (:func:`glstat.study.analysis.analyse`); a load
    without a prediction gives a probe of NaN damage."""
    out: dict[tuple[int, float], list[Probe]] = {}
    for (ih, il), case in sorted(analysis.items()):
        sa = case[PRIMARY_SAMPLE]
        check = sa.validation.verdict() if sa.ok and sa.validation is not None else "not checked"
        table = sa.area_damage
        for ia, area in enumerate(_areas(table, analysis)):
            r = None if table is None else table.iloc[ia]
            out.setdefault((ih, area), []).append(Probe(
                float(settings.pressures[il]),
                math.nan if r is None else float(r["estimate"]),
                math.nan if r is None else float(r["low"]),
                math.nan if r is None else float(r["high"]), check, role))
    return out


def _areas(table, analysis: dict) -> list[float]:
    """The areas (m²) of a damage table, or of any case's when ``table`` is None."""
    for t in [table] + [c[PRIMARY_SAMPLE].area_damage for c in analysis.values()]:
        if t is not None:
            return [round(float(a) * 1e-6, 15) for a in t["area_mm2"]]
    return []


def allowable_frame(settings, asettings, curves: dict[str, dict[tuple[int, float], list[Probe]]],
                    bem_grid: int | None = None) -> Any:
    """``allowable_load.csv``: the allowable nominal pressure per model, case and area.

    Parameters
    ----------
    settings : CampaignSettings
        The campaign (its Hurst exponents, scale and criterion).
    asettings : AnalysisSettings
        Its ``target_damage``.
    curves : dict
        ``model -> {(ih, area_m2): [Probe]}`` (:func:`campaign_probes`, with the search's
        probes added by :mod:`glstat.study.allowable_search`).
    bem_grid : int, optional
        Points per side of the elastic BEM's own grid, for ``spacing_um``.

    Returns
    -------
    pandas.DataFrame
        One row per model × case × area, the columns :data:`ALLOWABLE_COLUMNS`
        (:func:`allowable_row`), with ``spacing_um``, ``s_filter_um`` and ``criterion`` (the
        scale and the damage criterion the load holds at).
    """
    import pandas as pd

    from .scales import s_filter_um, spacing_um

    rows = []
    for model, by_case in curves.items():
        for (ih, area), probes in sorted(by_case.items()):
            row = {"model": model, "hurst": settings.hurst[ih], "area_mm2": area * 1e6,
                   "target_damage": asettings.target_damage}
            row.update(allowable_row(probes, asettings.target_damage))
            row.update(spacing_um=spacing_um(settings, bem_grid if model == "bem" else None),
                       s_filter_um=s_filter_um(settings),
                       criterion=(asettings.criterion if model == "bem"
                                  and asettings.criterion == "subsurface" else "surface"))
            rows.append(row)
    return pd.DataFrame(rows, columns=list(ALLOWABLE_COLUMNS))


def probes_frame(settings, curves: dict[str, dict[tuple[int, float], list[Probe]]]) -> Any:
    """``allowable_probes.csv``: every load solved, per model, case and area, with its damage,
    the monotone curve through the probes and the held-out check (:data:`PROBE_COLUMNS`)."""
    import pandas as pd

    rows = []
    for model, by_case in curves.items():
        for (ih, area), probes in sorted(by_case.items()):
            ordered = sorted(probes, key=lambda q: q.pressure)
            usable = [q for q in ordered if q.usable]
            fitted = dict(zip((id(q) for q in usable), monotone([q.estimate for q in usable]),
                              strict=True))
            for q in ordered:
                rows.append({"model": model, "hurst": settings.hurst[ih], "area_mm2": area * 1e6,
                             "pressure_mpa": q.pressure / 1e6, "role": q.role,
                             "damage": q.estimate, "damage_low": q.low, "damage_high": q.high,
                             "monotone_damage": fitted.get(id(q), math.nan), "check": q.check})
    return pd.DataFrame(rows, columns=list(PROBE_COLUMNS))
