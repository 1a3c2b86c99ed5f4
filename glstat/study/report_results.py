"""The sections of the study report on the asperity model's results in detail: the fitted
GLDs, the maximal pressure, the validation across surfaces, and the damage probability with
the integrity against area. Each function returns its section as
:class:`~glstat.study.report_document.Blocks`."""

from __future__ import annotations

import math

import numpy as np

from ..formatting import fmt_probability
from .analysis_settings import SAMPLE_LABELS
from .answer import case_label
from .report_document import Blocks
from .report_figures import (
    differences_figure,
    histograms_figure,
    integrity_figure,
    lambda_figure,
    maximum_figure,
    validation_figure,
)
from .report_numbers import (
    SAMPLE_ORDER,
    damage_records,
    fitted,
    guaranteed_records,
    maximum_records,
    sample_moments,
    validation_records,
)
from .report_surfaces import area_text

__all__ = ["damage_section", "fit_section", "maximum_section", "validation_section"]


def fit_section(settings, asettings, analysis: dict) -> Blocks:
    """"Moments and fitted GLD", the histograms with the fitted densities and the bootstrap
    densities of the λ parameters of the grid-point samples."""
    out = Blocks()
    out.heading("Moments and fitted GLD")
    rows = []
    for (ih, il), r in analysis.items():
        for sample in SAMPLE_ORDER:
            sa = r[sample]
            lam = sa.boot.fit.lambdas if sa.ok else (math.nan,) * 4
            fitname = f"{sa.param.upper()} {sa.method}" if sa.ok else "none"
            rows.append([case_label(settings, ih, il), SAMPLE_LABELS[sample], *sample_moments(sa.data),
                         fitname, *lam])
    out.table(["case", "sample", "n", "mean", "std", "skewness α3", "kurtosis α4", "fit",
               "λ1", "λ2", "λ3", "λ4"], rows,
              "Pooled samples of all surfaces (MPa); λ1 in MPa, λ2 in 1/MPa.")
    notes = [f"{case_label(settings, ih, il)}, {SAMPLE_LABELS[k]}: {r[k].note}"
             for (ih, il), r in analysis.items() for k in SAMPLE_ORDER if r[k].note]
    if notes:
        out.paragraph("Fit notes: " + " | ".join(notes))

    out.heading("Histograms with the fitted GLD densities")
    out.figure("histograms", histograms_figure(settings, analysis),
               "Pooled pressures and the fitted GLD density: grid-point pressures (top) and "
               "per-asperity peak pressures (bottom).")

    out.heading("Bootstrap densities of the λ parameters")
    for ih, il, sa in fitted(analysis, "grid"):
        out.figure(f"lambdas_{ih}_{il}", lambda_figure(settings, asettings, ih, il, sa),
                   f"Kernel densities of the bootstrapped λ1..λ4 ({case_label(settings, ih, il)}, "
                   f"grid-point pressures); dashed: full-sample fit.")
    return out


def maximum_section(settings, asettings, analysis: dict) -> Blocks:
    """"Maximal pressure over the analysed area": its density per case and sample, and its
    mean and interval."""
    lvl = round(100 * asettings.confidence_level)
    out = Blocks()
    out.heading("Maximal pressure over the analysed area")
    out.paragraph(
        "For each bootstrap GLD the maximum of n draws has cdf F_b(x)^n; the density shown is the "
        "pooled mixture (1/B) Σ_b F_b(x)^n. n is the mean number of grid points in contact per "
        "surface (grid sample) or of asperities in contact per surface (asperity sample): the "
        "α δ(p) part of PR(p) carries no pressure, so the maximum over all N grid points is the "
        "maximum over the (1 − α) N points in contact.")
    records = maximum_records(analysis)
    out.figure("maximum_density", maximum_figure(settings, asettings, records),
               f"Density of the maximal pressure over one analysed area, per H, with its {lvl} % "
               f"interval (shaded).")
    out.table(["case", "sample", "n", "median maximum", f"{lvl} % low", f"{lvl} % high"],
              [[case_label(settings, m["ih"], m["il"]), SAMPLE_LABELS[m["sample"]], m["n"], m["median"],
                m["low"], m["high"]] for m in records],
              "Maximal pressure (MPa) over one analysed area.")
    return out


def _validation_row(settings, rec: dict) -> list:
    """One row of the validation table."""
    head = [case_label(settings, rec["ih"], rec["il"]), SAMPLE_LABELS[rec["sample"]]]
    v = rec["validation"]
    if "reason" in rec:
        return [*head, 0, "—", "—", "—", "—", "—", rec["reason"]]
    return [*head, rec["surfaces"], f"{100 * v.coverage:.1f} %",
            f"[{100 * v.coverage_interval[0]:.1f}, {100 * v.coverage_interval[1]:.1f}] %",
            rec["mean_difference"], v.t_pvalue, v.w_pvalue,
            "rejected" if v.reject else "not rejected"]


def validation_section(settings, asettings, analysis: dict) -> Blocks:
    """"Validation across surfaces": the two-fold check of the predicted maximum, its figures
    per sample and its table."""
    lvl = round(100 * asettings.confidence_level)
    test = f"{100 * (1 - asettings.test_level):g} %"
    out = Blocks()
    out.heading("Validation across surfaces")
    out.paragraph(
        f"Two-fold cross-validation: the surfaces are split into even and odd indices; a GLD "
        f"bootstrap fitted on one half predicts, for every surface of the other half, the "
        f"distribution of its maximal pressure given its own n (points or asperities in contact): "
        f"one random maximum per bootstrap GLD, whose mean is the prediction and whose "
        f"equal-tailed {lvl} % range is the predicted interval. Coverage = fraction of surfaces "
        f"whose observed maximum lies in its interval, with its Wilson 95 % binomial interval. "
        f"Test: one-sample two-sided t-test of the null hypothesis 'the mean of (predicted − "
        f"observed) is 0' at the {test} level (Wilcoxon signed-rank p-value for reference).")
    for sample in SAMPLE_ORDER:
        out.figure(f"validation_{sample}", validation_figure(settings, asettings, analysis, sample),
                   f"Observed maximal pressure of every surface against its predicted {lvl} % "
                   f"interval ({SAMPLE_LABELS[sample]}).")
        out.figure(f"differences_{sample}", differences_figure(settings, analysis, sample),
                   f"Histogram of (predicted − observed) maximal pressure ({SAMPLE_LABELS[sample]}).")
    out.table(["case", "sample", "surfaces", "coverage", "Wilson 95 %", "mean (pred. − obs.)",
               "t-test p", "Wilcoxon p", f"H0 at {test}"],
              [_validation_row(settings, rec) for rec in validation_records(analysis)],
              f"Coverage of the predicted {lvl} % interval of the maximal pressure.")
    return out


def _guaranteed_cell(value: float, observed_max: float, e_star: float) -> str:
    """A guaranteed pressure (MPa) marked * beyond the largest observed pressure; above the
    contact modulus E* (MPa) only "> E*" and †, not a number no contact can reach."""
    if np.isnan(value) or value == -np.inf:
        return "—"
    if value > e_star:
        return "> E*†"
    mark = "*" if value > observed_max else ""
    return f"{value:.4g}{mark}"


def damage_section(settings, asettings, analysis: dict) -> Blocks:
    """"Damage probability at the hardness" per case and sample, and "Integrity against
    area" with the guaranteed pressures."""
    hard, lvl = asettings.hardness_mpa, round(100 * asettings.confidence_level)
    out = Blocks()
    out.heading("Damage probability at the hardness")
    rows = [[case_label(settings, ih, il), SAMPLE_LABELS[sample], n,
             *(("—",) * 3 if d is None else (fmt_probability(float(v)) for v in d))]
            for ih, il, sample, n, d in damage_records(analysis)]
    out.table(["case", "sample", "n", "damage probability", f"{lvl} % low", f"{lvl} % high"], rows,
              f"1 − F(Pd)^n at Pd = {hard:g} MPa on one analysed area "
              f"({area_text(settings)}).")

    out.heading("Integrity against area")
    out.figure("integrity_vs_area", integrity_figure(settings, asettings, analysis),
               f"Integrity probability F(Pd)^(k n) against the area factor k, with the {lvl} % "
               f"bootstrap band.")
    e_star = settings.E / (1 - settings.nu ** 2) / 1e6
    out.table(["case", "sample", "k = 1", "k = 10", "k = 100", "k = 1000"],
              [[case_label(settings, ih, il), SAMPLE_LABELS[sample],
                *(_guaranteed_cell(v, float(np.max(analysis[(ih, il)][sample].data)), e_star)
                  for v in g)]
               for ih, il, sample, g in guaranteed_records(analysis)],
              f"Guaranteed pressure Q(p^(1/(k n))) (MPa): all points of an area k times the analysed "
              f"one stay below it with probability p = {asettings.integrity_level:g}. "
              f"* beyond the largest pressure observed in the sample (an extrapolation of the "
              f"fitted tail); † above the contact modulus E* = {e_star / 1e3:.0f} GPa, where no "
              f"elastic contact pressure can be trusted (the material would have yielded long "
              f"before): the fitted tail gives no pressure there, only 'far above the "
              f"hardness'.")
    return out
