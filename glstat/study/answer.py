"""The study's answer as tables (``summary.csv``, ``damage_calibration.csv``) and as the
report's first screen: per H, the damage probability at the hardness on one analysed area
with its interval and whether it passed its check, beside the paper's numbers and the elastic
model's (docs/study.md, "Reading the report")."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..formatting import fmt_mpa, fmt_probability
from .analysis_settings import PRIMARY_SAMPLE, SAMPLE_LABELS, SAMPLES

__all__ = ["calibration_frame", "degenerate_scene", "summary_frame"]


def case_name(settings, ih: int) -> str:
    """How the report names group ``ih``: "H = 0.5", or "measured" for measured files."""
    return "measured" if getattr(settings, "measured", False) else f"H = {settings.hurst[ih]:g}"


def case_label(settings, ih: int, il: int) -> str:
    """How the report names a case of group ``ih`` at load ``il``: "H = 0.5, 20 MPa"."""
    return f"{case_name(settings, ih)}, {settings.pressures[il] / 1e6:g} MPa"


#: Columns of ``summary.csv`` (one row per H × load × model × sample).
SUMMARY_COLUMNS = ("hurst", "pressure_mpa", "model", "sample", "mean_pressure_mpa",
                   "values_per_surface", "asperities_per_surface", "spots_per_surface",
                   "points_in_contact_per_surface", "fit", "damage", "damage_low", "damage_high",
                   "observed_damage", "held_out_damage", "held_out_surfaces", "damage_p_value",
                   "coverage", "coverage_low", "coverage_high", "coverage_p_value",
                   "detectable_miss", "bias_p_value", "theta", "damage_levels_inside", "check",
                   "passes_check", "upper_end_mpa", "n_surfaces", "plastic_area_fraction",
                   "plastic_area_fraction_low", "plastic_area_fraction_high", "plastic_check",
                   "spacing_um", "s_filter_um", "criterion", "threshold",
                   "observed_max_pressure_mpa")
#: The plastic area fraction's columns of ``summary.csv`` (the capped BEM; NaN otherwise).
PLASTIC_COLUMNS = ("plastic_area_fraction", "plastic_area_fraction_low",
                   "plastic_area_fraction_high")
#: Columns of ``damage_calibration.csv``.
CALIBRATION_COLUMNS = ("hurst", "pressure_mpa", "model", "sample", "hardness_mpa", "area_factor",
                       "predicted", "predicted_low", "predicted_high", "observed", "observed_low",
                       "observed_high", "n_surfaces",
                       "p_value", "spacing_um", "s_filter_um")
#: The paper's damage verdicts at 2050 MPa (its section 4), by H.
PAPER_VERDICTS = {0.0: "certain", 0.5: "≈ 1 %", 1.0: "impossible"}
#: The paper's mean contact pressures (Table 1), MPa, by H.
PAPER_MEAN_MPA = {0.0: 1724.0, 0.5: 1369.0, 1.0: 1108.0}


def _scalar(a) -> float:
    return float(np.ravel(a)[0])


def _samples(r: dict) -> list[str]:
    """The samples of one case's analysis, in table order (primary first)."""
    return [sample for sample in SAMPLES if sample in r]


def _model_cases(analysis: dict, bem_analysis: dict | None, bem_label: str,
                 asperity_label: str) -> list[tuple[tuple[int, int], dict, str]]:
    """``((ih, il), case analysis, label)`` in table order: per case the elastic BEM first (the
    reference) when it ran on every surface, then the asperity model; the asperity model alone,
    unlabelled, otherwise."""
    if not bem_analysis:
        return [(k, r, "") for k, r in analysis.items()]
    return [c for k, r in analysis.items() for c in
            ([(k, bem_analysis[k], bem_label)] if k in bem_analysis else [])
            + [(k, r, asperity_label)]]


def _check_numbers(v) -> dict:
    """The held-out check's columns of ``summary.csv`` (NaN where there is no check)."""
    d, c = v.damage_check, v.coverage_check
    misses = [x.detectable_miss for x in (d, c) if x is not None]
    return {"held_out_damage": math.nan if d is None else d.observed,
            "held_out_surfaces": 0 if d is None else d.n,
            "damage_p_value": math.nan if d is None else d.p_value,
            "coverage_p_value": math.nan if c is None else c.p_value,
            "detectable_miss": max(misses) if misses else math.nan,
            "check": v.verdict()}


def _analysis_rows(settings, analysis: dict, model: str) -> list[dict]:
    rows = []
    for (ih, il), r in analysis.items():
        s = r["summary"]
        for sample in _samples(r):
            sa = r[sample]
            v = sa.validation
            d = sa.damage
            hits, m = v.damage_hits()
            rows.append({
                "hurst": settings.hurst[ih], "pressure_mpa": settings.pressures[il] / 1e6,
                "model": model, "sample": sample, "mean_pressure_mpa": s["mean_pressure"],
                "values_per_surface": float(sa.counts.mean()) if sa.counts.size else math.nan,
                "asperities_per_surface": s["n_asperities"] if model == "asperity" else math.nan,
                "spots_per_surface": s.get("n_spots", math.nan),
                "points_in_contact_per_surface": s["n_contact"],
                "fit": f"{sa.param.upper()} {sa.method}" if sa.ok else "none",
                "damage": math.nan if d is None else _scalar(d.estimate),
                "damage_low": math.nan if d is None else _scalar(d.low),
                "damage_high": math.nan if d is None else _scalar(d.high),
                "observed_damage": s.get("observed_damage", math.nan),
                "coverage": v.coverage, "coverage_low": v.coverage_interval[0],
                "coverage_high": v.coverage_interval[1], "bias_p_value": v.t_pvalue,
                "theta": v.theta, "damage_levels_inside": f"{hits} of {m}" if m else "",
                **_check_numbers(v),
                "passes_check": v.passes() if sa.ok else False,
                "upper_end_mpa": sa.upper_end, "n_surfaces": s["n_surfaces"],
                **{k: s.get(k, math.nan) for k in PLASTIC_COLUMNS},
                "plastic_check": s.get("plastic_check", ""),
                "observed_max_pressure_mpa": s.get("observed_max_pressure", math.nan)})
    return rows


def summary_frame(settings, analysis: dict, bem: dict | None = None, bem_analysis: dict | None = None,
                  criterion=None, bem_records: dict | None = None, confidence_level: float = 0.9,
                  bem_grid: int | None = None):
    """``summary.csv``: one row per H × load × model × sample (pandas DataFrame).

    Columns (pressures in MPa, probabilities as fractions): ``hurst``, ``pressure_mpa`` (nominal),
    ``model`` ("asperity", or "bem" for the elastic BEM), ``sample`` ("spot" for the peaks of
    the connected contact spots, the answer; "asperity" for per-asperity peaks; "grid" for
    grid-point pressures), ``mean_pressure_mpa`` (mean contact pressure per surface),
    ``values_per_surface`` (the sample's mean count per surface: spots, asperities or points),
    ``asperities_per_surface``, ``spots_per_surface``, ``points_in_contact_per_surface``,
    ``fit`` (GLD used), ``damage``, ``damage_low``, ``damage_high`` (P(max > hardness) on one
    analysed area with its bootstrap interval), ``observed_damage`` (fraction of the surfaces
    whose maximum exceeds the hardness), ``held_out_damage`` and ``held_out_surfaces`` (the
    same on the held-out surfaces of the check), ``damage_p_value`` (exact binomial test of the
    held-out damage against the predicted interval of the damage, 1 inside it), ``coverage``,
    ``coverage_low``, ``coverage_high`` (held-out coverage of the predicted interval of the
    maximum and its Wilson interval), ``coverage_p_value`` (one-sided exact binomial test
    against the interval's level: small when it covers too rarely),
    ``detectable_miss`` (the smallest miss beyond the prediction either test detects with 80 %
    power),
    ``bias_p_value`` (centring t-test), ``theta`` (extremal index), ``damage_levels_inside``
    (hardness levels at which the predicted damage lies inside the observed interval, "k of
    m"), ``check`` ("passed", "failed", "not checkable" or "not checked"), ``passes_check``,
    ``upper_end_mpa`` (upper end of the fitted GLD), ``n_surfaces``; for the elastic BEM with
    a hardness, ``plastic_area_fraction`` (mean over the surfaces of the fraction of the
    analysed area at the hardness in the capped solution), ``plastic_area_fraction_low`` and
    ``_high`` (the interval of one area's fraction from a GLD over the surfaces) and
    ``plastic_check`` (its check on held-out surfaces). NaN where a quantity does
    not apply (the elastic model compared on a few surfaces has no held-out check unless the
    whole study ran on it too: ``bem_analysis``, with the same columns as the asperity model).
    """
    import pandas as pd

    rows = _analysis_rows(settings, analysis, "asperity")
    if bem_analysis:
        rows += _analysis_rows(settings, bem_analysis, "bem")
    for ih, il in analysis:
        if bem and (ih, il) in bem and not bem_analysis:
            c = bem[(ih, il)]
            f = c.fits["bem"]
            surf = c.surfaces[c.surfaces["model"] == "bem"]
            d = f.damage
            rows.append({
                "hurst": settings.hurst[ih], "pressure_mpa": settings.pressures[il] / 1e6,
                "model": "bem", "sample": "spot",
                "mean_pressure_mpa": float(surf["mean_pressure_MPa"].mean()),
                "values_per_surface": float(surf["n_clusters"].mean()),
                "asperities_per_surface": math.nan,
                "spots_per_surface": float(surf["n_clusters"].mean()),
                "points_in_contact_per_surface": float(surf["n_contact"].mean()),
                "fit": f"{f.param.upper()} {f.method}" if f.ok else "none",
                "damage": math.nan if d is None else _scalar(d.estimate),
                "damage_low": math.nan if d is None else _scalar(d.low),
                "damage_high": math.nan if d is None else _scalar(d.high),
                "observed_damage": float(np.mean(surf["max_pressure_MPa"] > c.hardness)),
                "coverage": math.nan, "coverage_low": math.nan, "coverage_high": math.nan,
                "bias_p_value": math.nan, "theta": math.nan, "damage_levels_inside": "",
                "held_out_damage": math.nan, "held_out_surfaces": 0, "damage_p_value": math.nan,
                "coverage_p_value": math.nan, "detectable_miss": math.nan,
                "check": "not checked", "passes_check": False, "upper_end_mpa": math.nan,
                "n_surfaces": len(surf)})
    if criterion is not None and criterion.name == "plastic-zone" and bem_records:
        rows += _plastic_zone_rows(settings, criterion, bem_records, confidence_level)
    _scale_columns(rows, settings, criterion, bool(bem_analysis), bem_grid)
    return pd.DataFrame(rows, columns=list(SUMMARY_COLUMNS))


def _scale_columns(rows: list[dict], settings, criterion, bem_on_all: bool,
                   bem_grid: int | None = None) -> None:
    """Add the scale (spacing, λs) and the criterion of each row of ``summary.csv``: the asperity
    model and the elastic rows answer under the surface criterion, but for the subsurface
    criterion of the elastic model run on every surface."""
    from .criteria import Criterion
    from .scales import s_filter_um, spacing_um

    crit = criterion or Criterion()
    surface = Criterion("surface", crit.hardness)
    for row in rows:
        if row.get("criterion") == "plastic-zone":
            own = crit
        elif row["model"] == "bem" and bem_on_all and crit.name == "subsurface":
            own = crit
        else:
            own = surface
        row.update(spacing_um=spacing_um(settings, bem_grid if row["model"] == "bem" else None),
                   s_filter_um=s_filter_um(settings), criterion=own.name,
                   threshold=own.threshold_text())
    for row in rows:
        row.setdefault("observed_max_pressure_mpa", math.nan)


def _plastic_zone_rows(settings, criterion, bem_records: dict, level: float) -> list[dict]:
    """The plastic-zone criterion's rows of ``summary.csv`` (elastic BEM, sample "areas")."""
    from .surface_table import criteria_frame

    frame = criteria_frame(settings, criterion, bem_records, level)
    rows = []
    for _, r in frame[frame["criterion"] == "plastic-zone"].iterrows():
        rows.append({"hurst": r["hurst"], "pressure_mpa": r["pressure_mpa"], "model": "bem",
                     "sample": "areas", "damage": r["fraction"], "damage_low": r["low"],
                     "damage_high": r["high"], "observed_damage": r["fraction"],
                     "n_surfaces": int(r["n_surfaces"]), "fit": "none (exact binomial)",
                     "held_out_surfaces": 0,
                     "check": "not checked", "passes_check": False,
                     "criterion": "plastic-zone", "threshold": r["threshold"]})
    return rows


def calibration_frame(settings, analysis: dict, bem_analysis: dict | None = None,
                      bem_grid: int | None = None):
    """``damage_calibration.csv``: predicted against observed damage probabilities.

    One row per H × load × model × sample × hardness level × area factor: ``hardness_mpa``,
    ``area_factor`` (1: one analysed area; 2 and 4: groups of held-out surfaces),
    ``predicted`` (P(max > hardness) from the fit of the other fold, averaged over the two
    folds), ``observed`` (fraction of held-out surfaces or groups whose maximum exceeds it),
    ``observed_low``/``observed_high`` (Wilson 95 % interval), ``n_surfaces`` (surfaces or
    groups), ``p_value`` (exact binomial test of the observed count against the predicted
    interval, 1 when the observed fraction lies in it),
    ``spacing_um`` and ``s_filter_um`` (the scale: grid spacing and S-filter, NaN without one).
    """
    import pandas as pd

    frames = []
    models = [("asperity", analysis)] + ([("bem", bem_analysis)] if bem_analysis else [])
    for model, an in models:
        for (ih, il), r in an.items():
            for sample in _samples(r):
                c = r[sample].validation.calibration
                if c is None or len(c) == 0:
                    continue
                c = c.copy()
                c.insert(0, "sample", sample)
                c.insert(0, "model", model)
                c.insert(0, "pressure_mpa", settings.pressures[il] / 1e6)
                c.insert(0, "hurst", settings.hurst[ih])
                frames.append(c)
    if not frames:
        return pd.DataFrame(columns=list(CALIBRATION_COLUMNS))
    from .scales import s_filter_um, spacing_um

    out = pd.concat(frames, ignore_index=True)
    out["spacing_um"] = np.where(out["model"] == "bem", spacing_um(settings, bem_grid),
                                 spacing_um(settings))
    out["s_filter_um"] = s_filter_um(settings)
    return out[list(CALIBRATION_COLUMNS)]


def degenerate_scene(analysis: dict, settings=None) -> str:
    """A plain warning when the scene cannot answer the question ("" otherwise): fewer than
    3 contact spots per surface on average, or a damage probability of 0 or 1 for every H.
    The advice names options of the study's mode (``settings``: measured or simulated)."""
    msgs = []
    few = [r["summary"].get("n_spots", r["summary"]["n_asperities"]) for r in analysis.values()]
    if few and min(few) < 3:
        msgs.append(f"only {min(few):.2g} contact spots per surface on average for at least one "
                    "H: one or two spots carry the load, the pressure statistics describe those "
                    "few contacts and the maximum is barely random")
    dmg = [r[PRIMARY_SAMPLE].damage for r in analysis.values()
           if r[PRIMARY_SAMPLE].damage is not None]
    vals = [_scalar(d.estimate) for d in dmg]
    if vals and (all(v >= 1 - 1e-12 for v in vals) or all(v <= 1e-12 for v in vals)):
        msgs.append("the damage probability is " + ("1" if vals[0] >= 0.5 else "0") + " for every H: "
                    "the hardness does not discriminate between the surfaces at this scene")
    if not msgs:
        return ""
    if settings is not None and getattr(settings, "measured", False):
        return ("Degenerate scene: " + "; ".join(msgs) + ". The measured surfaces fix the "
                "roughness: choose another nominal pressure (--pressure) or check the hardness "
                "(--hardness).")
    return ("Degenerate scene: " + "; ".join(msgs) + ". Place the scene at the paper's pressure "
            "level with --rq or --target-pressure (docs/method.md §10).")


def overlap_note(settings, analysis: dict, threshold: float = 0.1) -> str:
    """A warning when, on more than ``threshold`` of the surfaces of a case, the maximal
    pressure is where asperity patches overlap ("" otherwise): the per-asperity predictor
    describes each asperity's own peak, not these sums."""
    cases = [(case_name(settings, ih), r["summary"].get("overlap_fraction", 0.0))
             for (ih, _), r in analysis.items()]
    many = [(name, f) for name, f in cases if f > threshold]
    if not many:
        return ""
    return ("Overlapping asperities: on " + ", ".join(f"{100 * f:.0f} % of the surfaces ({name})"
                                                      for name, f in many)
            + " the maximal pressure lies where the pressure patches of neighbouring asperities "
              "overlap and add up, above every asperity's own peak. The answer's contact-spot "
              "peaks include these sums; the per-asperity option (in the checks below) does not "
              "and understates the damage probability there.")


def width_note(settings, analysis: dict, bem_analysis: dict | None = None) -> str:
    """What would narrow the answer's damage interval on one analysed area to ±10 percentage
    points when it is wider than half of [0, 1] ("" otherwise): how many surfaces at least
    (:meth:`glstat.prediction.MaximumPrediction.data_for_width`, a low estimate) or what
    smaller area, per case of the answer's model (the elastic BEM's when it ran on every
    surface)."""
    from ..prediction import WIDE
    from .allowable import area_words

    model, an = ("elastic BEM", bem_analysis) if bem_analysis else ("asperity model", analysis)
    parts = []
    area = settings.size[0] * settings.size[1]
    for (ih, il), case in sorted(an.items()):
        sa = case[PRIMARY_SAMPLE]
        d = None if not sa.ok else sa.prediction.damage
        if d is None or not float(np.ravel(d.high)[0]) - float(np.ravel(d.low)[0]) > WIDE:
            continue  # a narrow interval: no search for a smaller area
        t = sa.prediction.data_for_width()
        r = t.iloc[0]
        load = (f", {settings.pressures[il] / 1e6:g} MPa" if len(settings.pressures) > 1 else "")
        text = (f"{case_name(settings, ih)}{load}: [{fmt_probability(r['low'])}, "
                f"{fmt_probability(r['high'])}] from {int(r['size'])} surfaces; at least about "
                f"{math.ceil(r['needed'])} surfaces")
        if r["smaller_area_factor"] == r["smaller_area_factor"]:
            smaller = float(f"{area * r['smaller_area_factor']:.2g}")
            text += (f", or an area of {area_words(smaller)} "
                     f"([{fmt_probability(r['smaller_low'])}, "
                     f"{fmt_probability(r['smaller_high'])}] from these surfaces)")
        parts.append(text)
    if not parts:
        return ""
    return (f"The damage interval on one area spans more than half of [0, 1] ({model}): "
            + "; ".join(parts) + " would narrow it to ±10 percentage points (the number of "
            "surfaces is a low estimate: the interval shrinks more slowly than 1/√N).")


def first_screen_rows(settings, asettings, analysis: dict, bem: dict | None,
                      bem_analysis: dict | None = None, criterion=None
                      ) -> tuple[list[list[Any]], list[str]]:
    """Rows of the report's first table, one per (H, load) and model: with the elastic BEM on
    every surface (``bem_analysis``) its row, the reference answer, comes first and the
    asperity model (the paper's) follows; otherwise the asperity model with the BEM's damage
    probability on the compared surfaces beside it. The paper's columns only for the
    simulated Weierstrass scene."""
    lvl = round(100 * asettings.confidence_level)
    simulated = not getattr(settings, "topographies", ())
    rows = []
    plastic = any("plastic_area_fraction" in r["summary"] for r in (bem_analysis or {}).values())
    elastic = ", elastic BEM (reference)"
    if criterion is not None and criterion.name == "subsurface":
        elastic += f", von Mises ≥ Y = {criterion.yield_stress / 1e6:.4g} MPa beneath the surface"
    cases = _model_cases(analysis, bem_analysis, elastic,
                         f", asperity model (c = {settings.cone_factor:g}, the paper's)")
    for (ih, il), r, label in cases:
        h = settings.hurst[ih]
        sa = r[PRIMARY_SAMPLE]
        d = sa.damage
        v = sa.validation
        if d is None:
            answer = f"no fit ({sa.note[:80]})"
        else:
            answer = (f"{fmt_probability(_scalar(d.estimate))} [{fmt_probability(_scalar(d.low))}, "
                      f"{fmt_probability(_scalar(d.high))}]")
            if sa.end_note:
                answer += " ⚠ near or beyond the fit's end point (below)"
        check = v.short_text() if sa.ok else "—"
        # without the BEM on every surface, its damage on the compared surfaces beside it
        elastic = "—"
        if not bem_analysis and bem and (ih, il) in bem and bem[(ih, il)].fits["bem"].damage is not None:
            elastic = fmt_probability(_scalar(bem[(ih, il)].fits["bem"].damage.estimate))
        row = [
            case_name(settings, ih) + (f", {settings.pressures[il] / 1e6:g} MPa"
                                       if len(settings.pressures) > 1 else "") + label,
            answer, check, fmt_probability(r["summary"].get("observed_damage", math.nan)),
            *([] if bem_analysis else [elastic]), fmt_mpa(r["summary"]["mean_pressure"]),
            *([plastic_text(r["summary"])] if plastic else []),
        ]
        if simulated:
            row += [PAPER_VERDICTS.get(h, "—") if abs(asettings.hardness_mpa - 2050) < 1e-9 else "—",
                    fmt_mpa(PAPER_MEAN_MPA.get(h, math.nan)) if h in PAPER_MEAN_MPA else "—"]
        rows.append(row)
    columns = ["case", f"damage probability at {asettings.hardness_mpa:g} MPa, one area "
                       f"[{lvl} % interval]", "check on held-out surfaces",
               "observed fraction of surfaces damaged",
               *([] if bem_analysis else ["elastic BEM (first surfaces)"]), "mean contact pressure",
               *([f"plastic area at {asettings.hardness_mpa:g} MPa, one area [{lvl} % interval]; "
                  f"share of the load"] if plastic else [])]
    return rows, columns + (["paper: damage", "paper: mean pressure"] if simulated else [])


def _amount(v: float) -> str:
    """A positive amount for a reader: whole numbers from 100 on ("9310"), three significant
    digits below ("2.76")."""
    return f"{v:.0f}" if v >= 100 else f"{v:.3g}"


def plastic_text(summary: dict) -> str:
    """The plastic area fraction of a case as the first screen shows it: "0.85 % [0.76 %,
    0.91 %] (mean 8500 µm², 1250 grid cells); 87 % of the load; interval check passed" ("—"
    without a capped solution)."""
    if "plastic_area_fraction" not in summary:
        return "—"
    size = ""
    if "plastic_area_um2" in summary:
        size = (f" (mean {_amount(summary['plastic_area_um2'])} µm², "
                f"{_amount(summary['plastic_area_cells'])} grid cells)")
    return (f"{fmt_probability(summary['plastic_area_fraction'])} "
            f"[{fmt_probability(summary['plastic_area_fraction_low'])}, "
            f"{fmt_probability(summary['plastic_area_fraction_high'])}]{size}; "
            f"{fmt_probability(summary.get('plastic_load_fraction', math.nan))} of the load; "
            f"interval check {summary.get('plastic_check', 'not checked')}")


#: The rms height printed in the paper, m.
PAPER_RQ = 50e-6


def scene_choice_sentence(settings, analysis: dict | None) -> str:
    """Why a simulated scene's Rq is not the paper's printed 50 µm, from this run's mean
    pressures next to Table 1's ("" for measured surfaces or when no H of Table 1 was run)."""
    if getattr(settings, "topographies", ()) or getattr(settings, "measured", False) or not analysis:
        return ""
    pairs = [(settings.hurst[ih], r["summary"]["mean_pressure"]) for (ih, il), r in analysis.items()
             if settings.hurst[ih] in PAPER_MEAN_MPA and len(settings.pressures) == 1]
    if not pairs:
        return ""
    ratio = PAPER_RQ / settings.rq_geometric_mean
    ours = " / ".join(f"{m:.0f}" for _, m in pairs)
    theirs = " / ".join(f"{PAPER_MEAN_MPA[h]:.0f}" for h, _ in pairs)
    hs = " / ".join(f"{h:g}" for h, _ in pairs)
    text = (f"The scene: this run's Rq = {settings.rq_text} µm gives mean contact pressures "
            f"{ours} MPa for H = {hs}, against Table 1's {theirs} MPa. ")
    if abs(ratio - 1) < 1e-9:
        return text + ("This is the paper's printed Rq; docs/method.md §10 explains why the "
                       "printed value does not reproduce the printed pressures.")
    return text + (
        f"The paper prints Rq = 50 µm, which at the same spectrum makes every slope "
        f"{ratio:.3g} times {'steeper' if ratio > 1 else 'shallower'}; the pressures of Table 1 "
        f"need slopes of a few percent (above), so the printed Rq and the printed pressures "
        f"cannot both hold, and the study places its scene at the pressures (docs/method.md §10; "
        f"`--rq 50` runs the printed value, `--target-pressure` or "
        f"glstat.study.rq_for_pressure another level).")


def _readable(p: float) -> str:
    """A probability in percent for a reader: "< 0.001 %" below 1e-5, "> 99.999 %" above
    1 − 1e-5."""
    if 0 <= p < 1e-5:
        return "< 0.001 %"
    if 1 - 1e-5 < p < 1:
        return "> 99.999 %"
    return fmt_probability(p)


def area_damage_rows(settings, asettings, analysis: dict, bem_analysis: dict | None = None
                     ) -> tuple[list[list[str]], list[str]]:
    """Growth with the area for the first screen: per case (and model, the elastic BEM first
    when it ran on every surface), the damage probability at the hardness on 1 mm², 1 cm² and
    10 cm² (contact-spot predictor, with its interval); no rows when no case has one."""
    rows = []
    for (ih, il), r, label in _model_cases(analysis, bem_analysis, ", elastic BEM",
                                           ", asperity model"):
        table = r[PRIMARY_SAMPLE].area_damage
        if table is None:
            continue
        row = [case_name(settings, ih) + (f", {settings.pressures[il] / 1e6:g} MPa"
                                          if len(settings.pressures) > 1 else "") + label]
        for _, t in table.iterrows():
            row.append(f"{_readable(t['estimate'])} [{_readable(t['low'])}, {_readable(t['high'])}]")
        rows.append(row)
    lvl = round(100 * asettings.confidence_level)
    from .allowable import area_words

    columns = ["case", *(f"damage on {area_words(a)} [{lvl} % interval]"
                         for a in asettings.damage_areas)]
    return rows, columns


def area_scaling_sentence(settings, analysis: dict) -> str:
    """The area scaling's check in words: per case, at how many hardness levels the predicted
    damage probability of k analysed areas (contact-spot predictor) lies inside the observed
    interval of groups of k held-out surfaces, for every k checked besides 1 ("" when none)."""
    from .analysis_settings import AREA_CHECKS

    parts = []
    for (ih, il), r in analysis.items():
        v = r[PRIMARY_SAMPLE].validation
        counts = [(k, *v.damage_hits(k)) for k in AREA_CHECKS]
        counts = [(k, hits, m) for k, hits, m in counts if m]
        if counts:
            parts.append(f"{case_label(settings, ih, il)}: " + ", ".join(
                f"k = {k}: {hits} of {m}" for k, hits, m in counts))
    if not parts:
        return ""
    return ("Area scaling (docs/method.md §7), checked by grouping k held-out surfaces: hardness "
            "levels at which the predicted damage probability of k areas (contact-spot "
            "predictor) lies inside the observed Wilson interval — " + "; ".join(parts)
            + ". These are not part of the pass rule, which is for one area: read the "
            "integrity of larger areas with them.")


def check_rows(settings, asettings, analysis: dict, bem_analysis: dict | None = None
               ) -> tuple[list[list[Any]], list[str]]:
    """Rows of the table of checks on held-out surfaces: one per (H, load, model, sample)."""
    lvl = round(100 * asettings.confidence_level)
    rows = []
    for (ih, il), r, label in _model_cases(analysis, bem_analysis, ", elastic BEM",
                                           ", asperity model"):
        for sample in _samples(r):
            v = r[sample].validation
            case = case_name(settings, ih) + (
                f", {settings.pressures[il] / 1e6:g} MPa" if len(settings.pressures) > 1 else "") + label
            if v.table is None or v.damage_check is None:
                rows.append([case, SAMPLE_LABELS[sample], "—", "—", "—", "—", "—",
                             f"not checked: {v.error or r[sample].note}"])
                continue
            d, c = v.damage_check, v.coverage_check
            miss = max(d.detectable_miss, c.detectable_miss)
            wide = "; conservative" if c.conservative else ""
            rows.append([case, SAMPLE_LABELS[sample],
                         f"{d.hits} of {d.n} vs {fmt_probability(d.predicted)} "
                         f"[{fmt_probability(d.low)}, {fmt_probability(d.high)}] (p = {d.p_value:.2g})",
                         f"{c.hits} of {c.n} = {100 * v.coverage:.0f} % (p = {c.p_value:.2g}{wide})",
                         "—" if not math.isfinite(miss) else f"{100 * miss:.2g} points",
                         f"{v.t_pvalue:.2g}", f"{v.theta:.2g}" if math.isfinite(v.theta) else "—",
                         v.verdict()])
    return rows, ["case", "sample", f"damaged held-out surfaces vs predicted at "
                                    f"{asettings.hardness_mpa:g} MPa [{lvl} % interval] (exact "
                                    "binomial p against the interval)",
                  f"held-out maxima inside the {lvl} % interval (one-sided exact binomial p)",
                  "smallest miss detected (80 % power)", "centring test p", "extremal index θ",
                  "check"]
