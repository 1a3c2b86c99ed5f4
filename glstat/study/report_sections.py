"""The sections of the study report that come first: the answer on the first screen, its
checks, the consistency with the paper, the main results, the settings, and the example
surfaces. Each function returns its section as :class:`~glstat.study.report_document.Blocks`."""

from __future__ import annotations

from ..formatting import fmt_number, fmt_probability
from .analysis_settings import PRIMARY_SAMPLE, SAMPLE_LABELS
from .answer import (
    area_damage_rows,
    area_scaling_sentence,
    case_label,
    case_name,
    check_rows,
    degenerate_scene,
    first_screen_rows,
    overlap_note,
    scene_choice_sentence,
    width_note,
)
from .report_document import Blocks, fmt_cell
from .report_figures import (
    allowable_figure,
    damage_curve_figure,
    damage_reliability_figure,
    pressure_maps_figure,
    surfaces_figure,
)
from .report_numbers import SAMPLE_ORDER, model_error_factors
from .report_scale import elastic_validity_note, scale_blocks, scale_paragraph, spike_note
from .report_surfaces import area_text, scene_sentence, surface_rows
from .report_text import (
    calibration_verdict,
    damage_sentence,
    fmt_interval,
    truncation_caption,
    truncation_paragraphs,
)
from .scales import scale_text
from .surface_table import resolution_note, scale_frame

__all__ = ["answer_section", "checks_section", "examples_section", "main_results_section",
           "paper_section", "settings_section"]


def _level(asettings) -> int:
    return round(100 * asettings.confidence_level)


def answer_section(settings, asettings, analysis: dict, info: dict) -> Blocks:
    """"The answer": warnings on the scene, the damage probability per case beside the
    observed fraction, the elastic model and the paper, the model error of the asperity
    model, and how the peak pressures were fitted."""
    out = Blocks()
    hard, lvl = asettings.hardness_mpa, _level(asettings)
    out.heading("The answer")
    bem = info.get("bem")
    crit = info.get("criterion") or asettings.criterion_of(settings)
    bem_on_all = bool(info.get("bem_analysis"))
    bem_grid = getattr(info.get("bem_settings"), "grid", None)
    out.paragraph(scale_paragraph(settings, crit, bem_on_all, bem_grid))
    resolution = resolution_note(settings, scale_frame(settings, crit, info.get("bem_records") or {},
                                                       asettings.confidence_level))
    if resolution:
        out.paragraph("⚠ " + resolution)
    validity = elastic_validity_note(settings, crit, info.get("bem_analysis"))
    if validity:
        out.paragraph("⚠ " + validity)
    odd: list[str] = getattr(settings, "implausible_values", list)()
    if odd:
        out.paragraph("⚠ Implausible values for their SI unit (a unit mix-up?): " + "; ".join(odd)
                      + ".")
    for warn in (degenerate_scene(analysis, settings), overlap_note(settings, analysis),
                 width_note(settings, analysis, info.get("bem_analysis"))):
        if warn:
            out.paragraph("⚠ " + warn)
    quality = spike_note(settings, info.get("results") or {}, info.get("bem_records"))
    if quality:
        out.paragraph(("⚠ " if "lies on or next to one in 0 " not in quality else "") + quality)
    rows, columns = first_screen_rows(settings, asettings, analysis, bem, info.get("bem_analysis"),
                                      crit)
    sub = (f" Under the subsurface criterion the elastic BEM's rows give the probability that the "
           f"von Mises stress beneath the surface exceeds Y = {crit.yield_stress / 1e6:.4g} MPa, "
           f"predicted in the same way from the largest von Mises stress beneath each contact spot."
           if crit.name == "subsurface" and bem_on_all else "")
    out.table(columns, rows,
              f"Probability that the contact pressure exceeds the hardness Pd = {hard:g} MPa "
              f"somewhere on one analysed area ({area_text(settings)}"
              + ("" if settings.measured else "; H is the Hurst exponent of the surfaces, not the "
                 "hardness")
              + f"; {scale_text(settings, short=True, bem_grid=bem_grid)}), "
              f"predicted from the peak pressures of the connected contact spots of each surface's "
              f"pressure map with their number per surface as a random count (docs/method.md §6; "
              f"the largest spot peak of a surface is its maximal pressure), with its {lvl} % "
              f"bootstrap interval (surfaces resampled){_tail_words(asettings)}. 'Check' tests "
              f"the prediction on held-out surfaces: the fraction damaged and the coverage of "
              f"the maximum's interval, each by an exact binomial test ('not checkable' when the "
              f"surfaces are too few to detect a miss of 20 percentage points). "
              + ("The elastic BEM solves every surface: it is the reference answer; the asperity "
                 "model is the paper's, shown with its own check." if info.get("bem_analysis") else
                 "The elastic BEM column is the same predictor on the elastic solution of the first "
                 "surfaces, without a check of its own (run --model both for the reference).")
              + sub)
    rows, columns = area_damage_rows(settings, asettings, analysis, info.get("bem_analysis"))
    if rows:
        out.table(columns, rows,
                  f"Growth with the area: the probability that the pressure exceeds {hard:g} MPa "
                  f"somewhere on an area of {_areas_text(asettings.damage_areas)} (contact-spot "
                  f"predictor; an area "
                  f"k times the analysed one holds k independent analysed areas, docs/method.md §7; "
                  f"the figure \"Integrity against area\" below draws the integrity, 1 − damage, "
                  f"against k)."
                  + (f" The elastic BEM's rows: the von Mises stress beneath the surface exceeding "
                     f"Y = {crit.yield_stress / 1e6:.4g} MPa." if sub else ""))
    scale_blocks(out, settings, asettings, crit, info.get("bem_records"))
    if info.get("allowable"):
        _allowable_block(out, settings, asettings, info["allowable"],
                         bool(info.get("allowable_searched")))
    if bem:
        ratios = [f"{case_name(settings, ih)}: mean pressure ×{mean:.2g}, maximal pressure ×{peak:.2g}"
                  for ih, _, mean, peak in model_error_factors(bem)]
        out.paragraph("Contact model error: on the same surfaces the elastic boundary-element "
                      "solution gives " + "; ".join(ratios) + " the asperity model's (c = "
                      f"{settings.cone_factor:g}). The asperity model neglects elastic interaction "
                      "and prescribes the pressure shape; the damage verdict depends on the model.")
    notes = [f"{case_name(settings, ih)}: {r[PRIMARY_SAMPLE].end_note}"
             for (ih, il), r in analysis.items() if r[PRIMARY_SAMPLE].end_note]
    if notes:
        out.paragraph("⚠ Fitted end point: " + "; ".join(notes) + ".")
    choices = [f"{case_name(settings, ih)}: {r[PRIMARY_SAMPLE].choice.reason}"
               for (ih, il), r in analysis.items() if r[PRIMARY_SAMPLE].choice is not None]
    if choices:
        out.paragraph("Fit of the peak pressures, chosen on an inner split of the surfaces (never on "
                      "the surfaces it is checked against): " + "; ".join(choices) + ".")
    return out


def _tail_words(asettings) -> str:
    """How the fitted GLDs end above their largest peaks, for the first screen's caption."""
    if asettings.tail is None:
        return "; the GLDs alone (--tail none), as the paper fitted them"
    return ("; every fitted GLD ends in a generalized Pareto tail on its sample's ⌈√N⌉ largest "
            "peaks and the interval is the calibrated one (the 3.5–96.5 % bootstrap percentiles, "
            "docs/method.md §6)")


def _allowable_block(out: Blocks, settings, asettings, curves: dict, searched: bool) -> None:
    """The allowable nominal pressure (table) and the damage against the nominal pressure
    with every load solved (figure), the elastic BEM's when it ran on every surface."""
    from .allowable import allowable_frame, allowable_text, area_words

    key = "bem" if "bem" in curves else "asperity"
    model = "elastic BEM" if key == "bem" else "asperity model"
    frame = allowable_frame(settings, asettings, {key: curves[key]})
    target = fmt_probability(asettings.target_damage)
    lvl = round(100 * asettings.confidence_level)
    rows = []
    for _, r in frame.iterrows():
        loads = [float(v) * 1e6 for v in r["probes_mpa"].split()] or list(settings.pressures)
        at = ("—" if r["damage_at_allowable"] != r["damage_at_allowable"] else
              f"{fmt_probability(r['damage_at_allowable'])} [{fmt_probability(r['damage_low'])}, "
              f"{fmt_probability(r['damage_high'])}] ({r['status']})")
        rows.append([("measured" if settings.measured else f"H = {r['hurst']:g}"),
                     area_words(r["area_mm2"] * 1e-6), allowable_text(r, loads), at,
                     r["bracket_mpa"] or "—", r["checks"] or "—"])
    how = (f"found by solving further loads (bisection in the logarithm of the load to 10 %), "
           f"then verified: the load found was solved and its predicted damage, with its {lvl} % "
           f"interval, is in the fourth column ('verified' when the interval holds the target)"
           if searched else
           "interpolated between the two loads run that bracket it; run --allowable to find "
           "and verify it with further loads")
    out.table(["case", "area", f"allowable nominal pressure for damage ≤ {target} [{lvl} % interval]",
               "damage predicted at that load", "between the loads (MPa)",
               "held-out checks at those loads"], rows,
              f"The allowable load ({model}): the nominal pressure at which the probability that "
              f"the pressure exceeds {asettings.hardness_mpa:g} MPa somewhere on the area reaches "
              f"{target}, {how}. The crossing is read on the damage made monotone in the load, "
              f"in the logit of the probability (linearly in the probability next to an exact 0 "
              f"or 1); its interval where the ends of the probability's interval cross the "
              f"target, '< a' or '> b' beyond the loads solved. Nothing is extrapolated. "
              f"allowable_load.csv holds the table, allowable_probes.csv every load solved.")
    falls = [f"{'measured' if settings.measured else f'H = {r.hurst:g}'}, "
             f"{area_words(r.area_mm2 * 1e-6)}" for r in frame.itertuples() if not r.monotone]
    if falls:
        out.paragraph("⚠ The predicted damage falls where the load rises (" + "; ".join(falls)
                      + "): the tails fitted at neighbouring loads disagree more than their "
                        "intervals. The allowable load reads the monotone curve through them "
                        "(the falling loads pooled); allowable_probes.csv holds both.")
    out.figure("allowable_load", allowable_figure(settings, asettings, curves[key], model),
               f"Damage probability on each area against the nominal pressure ({model}), with its "
               f"{lvl} % interval, every load solved (○ the campaign's, △ bracketing, ◇ "
               f"bisection, ★ verification) and the target {target}.")


def _areas_text(areas) -> str:
    """Areas in m² in words: "1 mm², 1 cm² or 10 cm²"."""
    from .allowable import area_words

    words = [area_words(a) for a in areas]
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " or " + words[-1]


def _answer_figures(out: Blocks, settings, asettings, analysis: dict, model: str = "") -> None:
    """Damage probability against hardness (with its band and the observed fraction) and the
    reliability of the predicted damage probabilities, per case."""
    suffix = f" ({model})" if model else ""
    tag = "_bem" if model else ""
    out.figure("damage_curve" + tag, damage_curve_figure(settings, asettings, analysis, suffix),
               "Damage probability on one analysed area against the hardness, with its bootstrap "
               "band (contact-spot predictor), and the fraction of surfaces whose maximal pressure "
               "exceeds it" + suffix + ".")
    out.figure("damage_reliability" + tag, damage_reliability_figure(settings, analysis, suffix),
               "Reliability of the damage probability: predicted (fit on the other fold) against "
               "observed on held-out surfaces, at several hardness levels, for one area (k = 1) and "
               "groups of k = 2 and 4 surfaces (the area scaling). Filled circles: the contact-spot "
               "predictor (the answer); open triangles: the per-asperity predictor; open squares: the "
               "paper's grid-point predictor.")


def checks_section(settings, asettings, analysis: dict, info: dict) -> Blocks:
    """The checks of the answer on held-out surfaces: their table, the damage curves and
    their reliability per model, and the elastic solves left out."""
    out = Blocks()
    bem_an = info.get("bem_analysis")
    rows, columns = check_rows(settings, asettings, analysis, bem_an)
    out.table(columns, rows,
              "Checks on held-out surfaces (fit on one fold, predict the other), each against the "
              "surface's maximal pressure, the event the damage probability is about. Damage: the "
              "number of held-out surfaces whose maximum exceeds the hardness against the predicted "
              "probability; coverage: the number of held-out maxima inside their predicted interval "
              "against the interval's level. Each is an exact binomial test at 5 % (p below 0.05: "
              "the prediction and the observation disagree, 'failed'). A test that does not reject "
              "proves little when the surfaces are few: the check counts only when a miss of 20 "
              "percentage points or more would be detected with 80 % probability; otherwise it "
              "says 'not checkable' and the column before the centring test gives the smallest "
              "miss it could detect. The centring test (t-test of predicted − observed maxima) and "
              "the extremal index θ (effective over nominal number of draws; 1 for independent "
              "draws) are shown for reference.")
    scaling = area_scaling_sentence(settings, analysis)
    if scaling:
        out.paragraph(scaling)
    _answer_figures(out, settings, asettings, analysis)
    left = info.get("bem_left_out") or []
    if left:
        out.paragraph("⚠ Elastic BEM solves that did not converge within the iteration limit are "
                      "left out of its analysis (never used): " + "; ".join(
                          f"{case_label(settings, ih, il)} surface {i}" for ih, il, i in left) + ".")
    if bem_an:
        _answer_figures(out, settings, asettings, bem_an, model="elastic BEM")
    return out


def paper_section(info: dict, settings=None, analysis: dict | None = None) -> Blocks:
    """"Consistency with the paper": the findings computed from the paper's Table 1 and, for
    a simulated scene, why its Rq is not the printed one (empty when the run has no findings)."""
    out = Blocks()
    paper = info.get("paper_findings")
    if paper:
        out.heading("Consistency with the paper")
        out.paragraph("Computed from the paper's Table 1 by this run (docs/method.md §11):")
        for line in paper:
            out.paragraph("• " + line)
        scene = scene_choice_sentence(settings, analysis) if settings is not None else ""
        if scene:
            out.paragraph("• " + scene)
    return out


def _coverage(v) -> str:
    """Coverage of the predicted interval with its Wilson interval, in percent ("—" unchecked)."""
    if v.table is None:
        return "—"
    return (f"{100 * v.coverage:.0f} % [{100 * v.coverage_interval[0]:.0f}, "
            f"{100 * v.coverage_interval[1]:.0f}]")


def main_results_section(settings, asettings, analysis: dict) -> Blocks:
    """"Main results": the scene, one row per case with its contact, damage probabilities and
    coverages, the damage verdict, load-control jumps and the calibration of the maximum."""
    out = Blocks()
    hard, lvl = asettings.hardness_mpa, _level(asettings)
    out.heading("Main results")
    out.paragraph(
        scene_sentence(settings) + f" Per-asperity peaks: the GLD chosen per H "
        f"(above), B = {asettings.n_resamples} bootstrap resamples of whole surfaces; grid-point "
        f"pressures: {asettings.param.upper()} by {asettings.method} (the paper's), B = "
        f"{asettings.grid_resamples}; hardness {hard:g} MPa, {lvl} % intervals. Pressures in MPa.")
    rows = []
    for (ih, il), r in analysis.items():
        s = r["summary"]
        row = [case_label(settings, ih, il), s["mean_pressure"], s["contact_fraction"],
               fmt_number(s["n_contact"], ",.0f"), s["n_asperities"], s["max_pressure"]]
        for sample in SAMPLE_ORDER:
            row += [fmt_interval(r[sample].damage), _coverage(r[sample].validation)]
        rows.append(row)
    out.table(["case", "mean contact pressure", "1 − α", "points in contact / surface",
               "asperities / surface", "max pressure / surface",
               "damage P (grid)", f"coverage of {lvl} % interval (grid)",
               "damage P (asperity)", f"coverage of {lvl} % interval (asperity)"], rows,
              f"Per-surface means; damage probability at {hard:g} MPa on one analysed area with its "
              f"{lvl} % bootstrap interval; coverage with its Wilson 95 % interval.")
    out.paragraph(damage_sentence(settings, analysis, hard, lvl))
    jumps = [(case_label(settings, ih, il), r["summary"]) for (ih, il), r in analysis.items()
             if r["summary"].get("n_in_jump", 0)]
    if jumps:
        out.paragraph(
            "Load control: the asperity model's force jumps where a summit starts to touch or a "
            "patch boundary passes a dip, so a requested load can fall inside a jump, where no "
            "state of the model carries it exactly; such surfaces keep the nearest physical "
            "state (docs/contact.md). " + "; ".join(
                f"{lab}: {s['n_in_jump']} of {s['n_surfaces']} surfaces, largest jump "
                f"{100 * s['max_force_jump']:.2g} % of the load, largest |force error| "
                f"{100 * s['force_error']:.2g} %" for lab, s in jumps) + ".")
    calib = [f"{case_label(settings, ih, il)}, {SAMPLE_LABELS[sample]}: "
             + calibration_verdict(r[sample].validation, asettings.confidence_level)
             for (ih, il), r in analysis.items() for sample in SAMPLE_ORDER
             if r[sample].validation.table is not None]
    if calib:
        out.paragraph("Calibration of the predicted maximum (calibrated = coverage consistent with "
                      "the nominal level, i.e. the level inside the Wilson interval, and the "
                      "centring t-test at the test level not rejecting; docs/method.md §9): "
                      + "; ".join(calib) + ".")
    return out


def settings_section(settings, asettings, info: dict) -> Blocks:
    """"Settings, versions and timings": the surfaces and the method, the Weierstrass
    truncation (simulated surfaces), package versions and the time of each stage."""
    out = Blocks()
    out.heading("Settings, versions and timings")
    rows = [*surface_rows(settings),
            ["E (GPa), ν, cone factor c",
             f"{settings.E / 1e9:g}, {settings.nu:g}, {settings.cone_factor:g}"],
            ["seed", settings.seed], ["hardness Pd (MPa)", asettings.hardness_mpa],
            ["GLD fit", f"{asettings.param.upper()} by {asettings.method}"],
            ["bootstrap resamples B", asettings.n_resamples],
            ["interval level", asettings.confidence_level],
            ["test level", asettings.test_level],
            ["guaranteed-pressure integrity level", asettings.integrity_level]]
    if info.get("bem_settings") is not None:
        b = info["bem_settings"]
        rows.append(["BEM comparison: surfaces per case K, boundary, tolerance, iteration limit",
                     f"{b.n_compare}, {'periodic' if b.periodic else 'isolated patch'}, {b.tol:g}, "
                     f"{b.max_iter}"])
    out.table(["setting", "value"], [[a, fmt_cell(b)] for a, b in rows])
    for text in ([] if settings.measured else truncation_paragraphs(settings, info)):
        out.paragraph(text)
    if info.get("truncation") and not settings.measured:
        out.table(["H", "n_terms", "highest frequency (1/mm)", "mean pressure (GPa)", "1 − α",
                   "asperities in contact"], info["truncation"],
                  truncation_caption(settings, info.get("truncation_reference")))
    out.table(["package", "version"], [[k, v] for k, v in info.get("versions", {}).items()])
    out.table(["stage", "seconds"], [[k, v] for k, v in info.get("timings", {}).items()],
              f"Workers: {info.get('workers', '?')}. Command: `{info.get('command', '')}`")
    return out


def examples_section(settings, analysis: dict, results: dict) -> Blocks:
    """"Example surfaces" and "Pressure maps" of surface 0 of every case whose maps were
    loaded (empty when none was)."""
    out = Blocks()
    stored = [(c, results.get((c[0], c[1], 0))) for c in analysis]
    ex = [(c, r) for c, r in stored if r is not None and "heights" in r]
    if not ex:
        return out
    out.heading("Example surfaces")
    out.figure("surfaces", surfaces_figure(settings, ex),
               "Example surface (surface 0) of every case: heights in µm.")
    out.heading("Pressure maps")
    out.figure("pressure_maps", pressure_maps_figure(settings, ex),
               "Contact-pressure maps of the example surfaces (log colour scale, grey: no contact) "
               "and a zoom around the highest pressure.")
    return out
