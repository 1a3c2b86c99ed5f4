"""Sentences of the study report written from the run's numbers: the damage probabilities and
their verdict, the calibration verdict of a predicted maximum, and the Weierstrass truncation
with the stored reference measurement."""

from __future__ import annotations

import math

from ..formatting import fmt_probability
from .analysis_settings import SAMPLE_LABELS
from .answer import case_label
from .report_document import fmt_cell
from .report_numbers import SAMPLE_ORDER, damage_verdict, truncation_summary
from .report_surfaces import area_text, grid_text

__all__ = ["PAPER_PRESSURES", "calibration_verdict", "damage_sentence", "fmt_interval",
           "truncation_caption", "truncation_matches", "truncation_paragraphs"]

#: Mean contact pressures reported by Bigerelle et al. (2019), in MPa.
PAPER_PRESSURES = (1100.0, 1700.0)


def fmt_interval(d) -> str:
    """``estimate [low, high]`` of a bootstrap probability in percent, or "—" for None."""
    if d is None:
        return "—"
    return (f"{fmt_probability(float(d.estimate))} [{fmt_probability(float(d.low))}, "
            f"{fmt_probability(float(d.high))}]")


def damage_sentence(settings, analysis: dict, hardness: float, level: int) -> str:
    """The damage probabilities of this run in words, computed from the analysis.

    Parameters
    ----------
    settings : CampaignSettings
        Campaign settings (for the case labels).
    analysis : dict
        Output of :func:`glstat.study.analysis.analyse`: per case, ``"grid"`` and
        ``"spot"`` sample analyses whose ``damage`` is a bootstrap probability or None.
    hardness : float
        Hardness in MPa.
    level : int
        Interval level in percent.

    Returns
    -------
    str
        One paragraph: the estimate and interval per case and sample, and a verdict only when
        it holds for every case: "certain" when every estimate and lower bound is 1 to four
        digits (>= 0.99995), "negligible" when every upper bound is below 5e-5 (and no verdict
        when a case has no estimate; :func:`glstat.study.report_numbers.damage_verdict`).
    """
    parts = [f"{case_label(settings, ih, il)}: "
             + ", ".join(f"{fmt_interval(r[sample].damage)} ({SAMPLE_LABELS[sample]})"
                         for sample in SAMPLE_ORDER)
             for (ih, il), r in analysis.items()]
    text = (f"Damage probability at the hardness {hardness:g} MPa on one analysed area (estimate "
            f"[{level} % bootstrap interval]): " + "; ".join(parts) + ".")
    verdict = damage_verdict(analysis)
    if verdict == "certain":
        text += f" Damage at {hardness:g} MPa is certain (1 to four digits) in every case."
    elif verdict == "negligible":
        text += f" Damage at {hardness:g} MPa is negligible (below 5e-5) in every case."
    return text


def truncation_matches(settings, reference: dict | None) -> bool:
    """True when the run has the grid, size and Rq of the stored truncation measurement."""
    if not reference:
        return False
    return (settings.square and int(settings.grid) == int(reference["grid"])
            and math.isclose(settings.length, reference["length"], rel_tol=1e-9)
            and not isinstance(settings.rq, tuple)
            and math.isclose(settings.rq, reference["rq"], rel_tol=1e-9))


def reference_label(reference: dict) -> str:
    """The settings of the stored truncation measurement in words."""
    return (f"{reference['grid']}², {reference['length'] * 1e3:g} × {reference['length'] * 1e3:g} "
            f"mm², Rq = {reference['rq'] * 1e6:g} µm, {reference['pressure'] / 1e6:g} MPa, "
            f"{reference['n_surfaces']} surfaces per row, seed {reference['seed']}")


def truncation_caption(settings, reference: dict | None) -> str:
    """Caption of the stored truncation table: what it is, its settings, whether they apply."""
    if not reference:
        return "Stored reference measurement (glstat.study.TRUNCATION_TABLE); means over surfaces."
    text = ("Stored reference measurement (glstat.study.TRUNCATION_TABLE, from "
            f"glstat.study.truncation_table() on {reference_label(reference)}), not computed in "
            "this run; means over surfaces.")
    if not truncation_matches(settings, reference):
        text += (f" This run's settings ({grid_text(settings)}, {area_text(settings)}, Rq = "
                 f"{settings.rq_text} µm) differ, so the table does not describe it.")
    return text


def truncation_paragraphs(settings, info: dict) -> list[str]:
    """The paragraphs on the Weierstrass truncation of this run.

    The first states the run's truncation (terms per H, or none). The second quotes the
    stored reference measurement (``info["truncation"]``, rows (H, n_terms, highest
    frequency, mean pressure in GPa, 1 − α, asperities); settings in
    ``info["truncation_reference"]``) and is given only when this run has the reference's
    grid, size and Rq; every number in it comes from the stored rows.

    Parameters
    ----------
    settings : CampaignSettings
        Campaign settings of the run.
    info : dict
        Report information (see :func:`glstat.study.report.build_report`).

    Returns
    -------
    list of str
        One or two paragraphs.
    """
    rows = info.get("truncation")
    reference = info.get("truncation_reference")
    cut = [(h, n) for h, n in zip(settings.hurst, settings.n_terms, strict=True) if n is not None]
    if cut:
        kept = ", ".join(f"{n} (H = {h:g})" for h, n in cut)
        general = ("**Truncation of the Weierstrass series.** The series is truncated to "
                   f"{kept} terms per axis instead of carrying every frequency up to the grid's "
                   "Nyquist limit (docs/method.md §2; the `--n-terms` setting above).")
    else:
        general = ("**Truncation of the Weierstrass series.** None: the surfaces carry every "
                   "frequency up to the grid's Nyquist limit (docs/method.md §2).")
    if not rows or reference is None or not truncation_matches(settings, reference):
        return [general]
    summary = truncation_summary(rows)
    span = ", ".join(f"~{fmt_cell(float(r[3]))} GPa (H = {h:g}, {int(r[1])} terms)"
                     for h, r in sorted(summary.finest.items()))
    lo, hi = (p / 1e3 for p in PAPER_PRESSURES)
    reach = ("no truncation in it reaches" if summary.lowest > hi else "some truncations reach")
    return [
        general,
        "Without truncation the surfaces carry every frequency up to the grid's Nyquist limit. "
        f"In the stored reference measurement on these settings ({reference_label(reference)}) "
        "the asperity model's "
        f"mean contact pressure with the most terms is {span}; Bigerelle et al. (2019) report "
        f"{lo:g}–{hi:g} GPa, and {reach} that range (the fewest terms, {int(summary.coarsest[1])}, "
        f"give ~{fmt_cell(float(summary.coarsest[3]))} GPa). docs/study.md discusses the choice of "
        "truncation."
    ]


def calibration_verdict(validation, level: float) -> str:
    """Whether the predicted maximum of one sample is calibrated, in words.

    Parameters
    ----------
    validation : object
        Validation of the sample with ``coverage_interval`` (Wilson interval of the coverage,
        fractions) and ``reject`` (True when the centring t-test rejects "mean of (predicted −
        observed) is 0").
    level : float
        Nominal level of the predicted intervals, e.g. 0.9.

    Returns
    -------
    str
        "calibrated (…)" only when the coverage is consistent with ``level`` (the level lies
        in the Wilson interval) and the centring test does not reject; otherwise the failed
        check(s), e.g. "coverage consistent with 90 %, but biased (centring test rejects)";
        a coverage above the level is called conservative.
    """
    lvl = f"{100 * level:g} %"
    lo, hi = validation.coverage_interval
    cov_ok = bool(lo <= level <= hi)
    biased = bool(validation.reject)
    if cov_ok and not biased:
        return (f"calibrated (coverage consistent with {lvl}, mean (predicted − observed) "
                "compatible with 0)")
    if cov_ok:
        return (f"not calibrated: coverage consistent with {lvl}, but biased (centring test "
                "rejects)")
    # above the level: conservative, which the held-out check does not count as a failure
    cov = (f"coverage above {lvl}, conservative" if lo > level
           else f"coverage incompatible with {lvl}")
    if not biased:
        return f"not calibrated: {cov} (mean (predicted − observed) compatible with 0)"
    return f"not calibrated: {cov} and biased (centring test rejects)"
