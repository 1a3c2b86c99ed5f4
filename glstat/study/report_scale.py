"""What the first screen says about the scale and the meaning of the answer: the length scale
(grid spacing, S-filter) and the damage criterion every number holds at, the elastic
solution's validity, the outlier points of measured files, the fraction of areas damaged
under each criterion, and the answer against the scale (table, figure and the
resolution-dominated warning)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..formatting import fmt_probability
from .answer import case_name
from .criteria import CRITERION_LABELS
from .report_document import Blocks
from .scales import scale_text
from .surface_table import criteria_frame, scale_frame

__all__ = ["elastic_validity_note", "scale_blocks", "scale_figure", "scale_paragraph",
           "spike_note"]


def scale_paragraph(settings: Any, crit: Any, bem_on_all: bool, bem_grid: int | None = None) -> str:
    """The sentence that opens the answer: at what scale and under which criterion it holds."""
    text = (f"Every number below holds at this length scale: "
            f"{scale_text(settings, bem_grid=bem_grid)}. "
            f"Damage criterion: {crit.text()} — {CRITERION_LABELS[crit.name]}")
    if crit.name != "surface":
        text += (" (elastic BEM; the asperity model answers under the surface criterion, "
                 f"hardness {crit.hardness / 1e6:.4g} MPa)" if bem_on_all else
                 " (the elastic BEM's fraction of areas below; the predicted probabilities are "
                 "under the surface criterion)")
    return text + "."


def elastic_validity_note(settings: Any, crit: Any, bem_analysis: dict | None) -> str:
    """A warning when the elastic mean contact pressure of a case exceeds the hardness ("" when
    none does): the elastic solution is then far outside its validity."""
    if not bem_analysis:
        return ""
    over = [(case_name(settings, ih) + (f", {settings.pressures[il] / 1e6:g} MPa"
                                        if len(settings.pressures) > 1 else ""),
             r["summary"]["mean_pressure"], r["summary"].get("plastic_load_fraction", math.nan))
            for (ih, il), r in bem_analysis.items()
            if r["summary"]["mean_pressure"] > crit.hardness / 1e6]
    if not over:
        return ""
    parts = [f"{name}: {mean:.4g} MPa" + (f", {100 * load:.3g} % of the load carried "
                                           f"plastically" if math.isfinite(load) else "")
             for name, mean, load in over]
    return ("The elastic solution is far outside its validity: its mean contact pressure exceeds "
            f"the hardness {crit.hardness / 1e6:.4g} MPa (" + "; ".join(parts) + "). Read the "
            "plastic columns (the solution capped at the hardness) and the plastic-zone "
            "criterion; the elastic damage probability only says that the hardness is reached.")


def spike_note(settings: Any, results: dict, bem_records: dict | None) -> str:
    """Outlier points of measured files in words ("" for simulated surfaces or when none is
    found); quantised heights too."""
    if not settings.measured:
        return ""
    keys = [k for k in results if "spike_count" in results[k]]
    if not keys:
        return ""
    counts = np.array([int(results[k]["spike_count"]) for k in keys])
    on = [k for k, r in (bem_records or {}).items() if bool(r.get("max_on_spike", False))]
    steps = [float(results[k]["steps_per_sq"]) for k in keys if "steps_per_sq" in results[k]]
    parts = []
    if counts.sum():
        largest = max(float(results[k]["spike_largest"]) for k in keys)
        parts.append(
            f"outlier points (one or a few pixels standing out from their neighbourhood) in "
            f"{np.count_nonzero(counts)} of {len(keys)} areas, {int(counts.sum())} points in all, "
            f"the largest {largest * 1e9:.4g} nm from its neighbourhood; "
            + ("they were replaced by the local median of their neighbours (--despike) before "
               "the S-filter" if settings.despike else
               f"the elastic maximal pressure lies on or next to one in {len(on)} of "
               f"{len(bem_records or {})} areas; --despike replaces them"))
    if steps and min(steps) < 20:
        parts.append(f"heights stored in few distinct steps (Sq is {min(steps):.3g} steps in the "
                     f"coarsest area): the heights are quantised")
    if not parts:
        return ""
    return "Data quality: " + "; ".join(parts) + " (surfaces.csv lists every area)."


def _criteria_rows(frame, level: int) -> tuple[list[list[str]], list[str]]:
    rows = []
    for _, r in frame.iterrows():
        rows.append([r["case"], r["criterion"], r["threshold"],
                     f"{int(r['damaged'])} of {int(r['n_surfaces'])} = "
                     f"{fmt_probability(r['fraction'])} [{fmt_probability(r['low'])}, "
                     f"{fmt_probability(r['high'])}]"])
    return rows, ["case", "criterion", "threshold",
                  f"areas damaged (elastic BEM) [{level} % exact interval]"]


def _case_column(settings: Any, frame):
    frame = frame.copy()
    frame.insert(0, "case", [("measured" if settings.measured else f"H = {h:g}")
                             + (f", {p:g} MPa" if len(settings.pressures) > 1 else "")
                             for h, p in zip(frame["hurst"], frame["pressure_mpa"], strict=True)])
    return frame


def scale_blocks(out: Blocks, settings: Any, asettings: Any, crit: Any,
                 bem_records: dict | None) -> None:
    """Add the criteria table and the answer against the scale (table and figure) to ``out``."""
    if not bem_records:
        return
    level = asettings.confidence_level
    lvl = round(100 * level)
    frame = _case_column(settings, criteria_frame(settings, crit, bem_records, level))
    if len(frame):
        rows, columns = _criteria_rows(frame, lvl)
        out.table(columns, rows,
                  f"What the areas show, without a fitted model: the fraction of the analysed areas "
                  f"({settings.size[0] * 1e3:.3g} mm × {settings.size[1] * 1e3:.3g} mm) whose elastic "
                  f"solution is damaged under each criterion, at {scale_text(settings, short=True)}, "
                  f"with its exact (Clopper–Pearson) {lvl} % interval. 'plastic-zone' reads the "
                  f"solution capped at the hardness; its zones are 8-connected points at the "
                  f"hardness (surfaces.csv gives every area's plastic area in µm² and in grid cells).")
    scales = scale_frame(settings, crit, bem_records, level)
    if not len(scales):
        return
    scales = _case_column(settings, scales)
    rows = []
    for _, r in scales.iterrows():
        vm = r["max_von_mises_mpa"]
        rows.append([r["case"], f"{r['s_filter_um']:.3g} µm" + (" (the answer's)" if r["scale_factor"] == 1
                                                                 else ""),
                     f"{r['max_pressure_mpa']:.4g} MPa",
                     "—" if not math.isfinite(vm) else f"{vm:.4g} MPa",
                     f"{r['plastic_area_um2']:.3g} µm²", f"{r['largest_plastic_zone_um2']:.3g} µm²",
                     f"{int(r['damaged'])} of {int(r['n_surfaces'])} = {fmt_probability(r['fraction'])} "
                     f"[{fmt_probability(r['low'])}, {fmt_probability(r['high'])}]"])
    out.table(["case", "S-filter λs", "maximal pressure (median)", "von Mises maximum (median)",
               "plastic area (median)", "largest plastic zone (median)",
               f"areas damaged, {crit.name} criterion [{lvl} % exact interval]"], rows,
              f"The answer against the scale: the same areas solved again after an S-filter of 2 "
              f"and 4 times λs (grid spacing {max(settings.spacing) * 1e6:.3g} µm throughout). An "
              f"answer that holds for the surface changes little between the two finest scales; "
              f"one that moves by more than its interval is decided by features near the filter's "
              f"scale (scales.csv).")
    out.figure("scale", scale_figure(scales, crit),
               "Maximal elastic surface pressure (and, with the subsurface stress, the largest von "
               "Mises stress beneath it), plastic area and fraction of areas damaged against the "
               "S-filter's nesting index λs (medians over the areas; the fraction with its exact "
               "interval).")


def scale_figure(frame, crit: Any):
    """Maximal pressure (and von Mises stress), plastic area and damaged fraction against λs,
    one line per case, on the λs of the study's solves."""
    from matplotlib.ticker import FixedLocator, NullLocator

    from .report_figures import pyplot

    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.4), layout="constrained")
    for case, g in frame.groupby("case", sort=False):
        g = g.sort_values("s_filter_um")
        lam = g["s_filter_um"].to_numpy(dtype=float)
        line = axes[0].plot(lam, g["max_pressure_mpa"], "o-", label=f"{case}: surface pressure")[0]
        vm = g["max_von_mises_mpa"].to_numpy(dtype=float)
        if np.isfinite(vm).any():
            axes[0].plot(lam, vm, "s--", color=line.get_color(), label=f"{case}: von Mises")
        axes[1].plot(lam, g["plastic_area_um2"], "o-", label=case)
        frac = g["fraction"].to_numpy(dtype=float)
        err = np.vstack([frac - g["low"].to_numpy(dtype=float), g["high"].to_numpy(dtype=float) - frac])
        axes[2].errorbar(lam, 100 * frac, yerr=100 * err, fmt="o-", capsize=3, label=case)
    axes[0].axhline(crit.hardness / 1e6, color="0.4", ls="--", lw=1, label="hardness")
    if crit.name == "subsurface":
        axes[0].axhline(crit.yield_stress / 1e6, color="0.6", ls=":", lw=1, label="yield stress")
    axes[0].set_ylabel("largest elastic stress (MPa)")
    axes[1].set_ylabel("plastic area per area (µm²)")
    axes[1].set_ylim(bottom=0)
    axes[2].set_ylabel(f"areas damaged, {crit.name} (%)")
    axes[2].set_ylim(-2, 102)
    ticks = sorted(set(frame["s_filter_um"].round(6)))
    for ax in axes:
        ax.set_xscale("log")
        ax.xaxis.set_major_locator(FixedLocator(ticks))
        ax.xaxis.set_minor_locator(NullLocator())
        ax.set_xticklabels([f"{t:g}" for t in ticks])
        ax.set_xlabel("S-filter λs (µm)")
    axes[0].legend(fontsize=7)
    return fig
