"""The study report: one self-contained HTML file (figures embedded) and the same content as
Markdown with PNG files."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .analysis import SAMPLE_LABELS
from .answer import case_label
from .report_document import Report, fmt_cell
from .report_text import (
    PAPER_PRESSURES,
    calibration_verdict,
    damage_sentence,
    truncation_caption,
    truncation_matches,
    truncation_paragraphs,
)

__all__ = ["PAPER_PRESSURES", "Report", "build_report", "calibration_verdict", "damage_sentence",
           "truncation_caption", "truncation_matches", "truncation_paragraphs"]


def _display(a: np.ndarray, how: str, size: int = 512) -> np.ndarray:
    """A map reduced by blocks to at most ``size`` pixels per side for display (block mean, or
    block maximum so that no contact peak disappears)."""
    f = max(1, -(-max(a.shape) // size))
    if f == 1:
        return a
    n0, n1 = (a.shape[0] // f) * f, (a.shape[1] // f) * f
    blocks = a[:n0, :n1].reshape(n0 // f, f, n1 // f, f)
    return blocks.max(axis=(1, 3)) if how == "max" else blocks.mean(axis=(1, 3))


def _kind_panels(plt) -> tuple[Any, list[tuple[Any, str]]]:
    """A figure with one panel per sample kind, side by side.

    Parameters
    ----------
    plt : module
        :mod:`matplotlib.pyplot`.

    Returns
    -------
    fig : matplotlib.figure.Figure
    panels : list of (matplotlib.axes.Axes, str)
        The axes of the grid-point and of the per-asperity sample, with the kind.
    """
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), squeeze=False, layout="constrained")
    return fig, [(axes[0, col], kind) for col, kind in enumerate(("grid", "asperity"))]


def _fitted(analysis: dict, kind: str):
    """The cases whose sample of one kind got a GLD.

    Parameters
    ----------
    analysis : dict
        ``(ih, il) -> {kind: SampleAnalysis, ...}``.
    kind : str
        ``"grid"`` or ``"asperity"``.

    Yields
    ------
    ih, il : int
        The case.
    sa : SampleAnalysis
        Its analysis of that sample, with ``sa.ok``.
    """
    for (ih, il), r in analysis.items():
        sa = r[kind]
        if sa.ok:
            yield ih, il, sa


def _answer_figures(rep: Report, settings, asettings, analysis: dict, model: str = "") -> None:
    """Damage probability against hardness (with its band and the observed fraction) and the
    reliability of the predicted damage probabilities, per H."""
    suffix = f" ({model})" if model else ""
    tag = "_bem" if model else ""
    import matplotlib.pyplot as plt

    cases = list(analysis.items())
    fig, axes = plt.subplots(1, len(cases), figsize=(4.2 * len(cases), 3.4), squeeze=False)
    for ax, ((ih, il), r) in zip(axes[0], cases, strict=True):
        c = r["asperity"].damage_curve
        if c is None:
            ax.set_axis_off()
            continue
        x = c["hardness_mpa"] / 1e3
        ax.fill_between(x, c["low"], c["high"], alpha=0.3, label="90 % band")
        ax.plot(x, c["damage"], label="predicted")
        ax.step(x, c["observed"], where="post", color="k", lw=1, label="observed fraction")
        ax.axvline(asettings.hardness / 1e3, color="r", ls="--", lw=1, label="hardness")
        top = float(np.quantile(r["asperity"].validation.table["observed"], 0.95)) / 1e3 \
            if r["asperity"].validation.table is not None else float(x.max())
        ax.set_xlim(float(x.min()), max(top * 1.15, asettings.hardness / 1e3 * 1.1))
        ax.set_xlabel("hardness Pd (GPa)")
        ax.set_ylabel("P(max > Pd), one area")
        ax.set_title(case_label(settings, ih, il) + suffix, fontsize=9)
        ax.legend(fontsize=7)
    fig.tight_layout()
    rep.figure("damage_curve" + tag, fig, "Damage probability on one analysed area against the "
               "hardness, with its bootstrap band (per-asperity predictor), and the fraction of "
               "surfaces whose maximal pressure exceeds it" + suffix + ".")
    fig, axes = plt.subplots(1, len(cases), figsize=(4.2 * len(cases), 3.6), squeeze=False)
    for ax, ((ih, il), r) in zip(axes[0], cases, strict=True):
        for kind, marker in (("asperity", "o"), ("grid", "s")):
            c = r[kind].validation.calibration
            if c is None or len(c) == 0:
                continue
            for k, color in ((1, "C0"), (2, "C1"), (4, "C2")):
                ck = c[c["area_factor"] == k]
                if not len(ck):
                    continue
                ax.errorbar(ck["predicted"], ck["observed"],
                            yerr=[np.maximum(ck["observed"] - ck["observed_low"], 0.0),
                                  np.maximum(ck["observed_high"] - ck["observed"], 0.0)],
                            fmt=marker, ms=4, color=color, mfc="none" if kind == "grid" else color,
                            label=f"{'grid (paper)' if kind == 'grid' else 'asperity'}, k = {k}")
        ax.plot([0, 1], [0, 1], "k:", lw=1)
        ax.set_xlabel("predicted P(max > Pd)")
        ax.set_ylabel("observed fraction (Wilson 95 %)")
        ax.set_title(case_label(settings, ih, il) + suffix, fontsize=9)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=6)
    fig.tight_layout()
    rep.figure("damage_reliability" + tag, fig, "Reliability of the damage probability: predicted (fit on "
               "the other fold) against observed on held-out surfaces, at several hardness levels, "
               "for one area (k = 1) and groups of k = 2 and 4 surfaces (the area scaling). Filled: "
               "per-asperity predictor; open squares: the paper's grid-point predictor.")


def build_report(settings, asettings, results: dict, analysis: dict, info: dict) -> Report:
    """Assemble the study report.

    Parameters
    ----------
    settings : CampaignSettings
    asettings : AnalysisSettings
    results : dict
        Surface results (example surfaces with their maps).
    analysis : dict
        Output of :func:`glstat.study.analysis.analyse`.
    info : dict
        ``versions`` (dict), ``timings`` (dict of seconds), ``truncation`` (rows of the
        stored truncation table or None), ``truncation_reference`` (its settings: ``grid``,
        ``length``, ``rq``, ``pressure``, ``n_surfaces``, ``seed``), ``command`` (str),
        ``workers`` (str).
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    from ..plot import plot_histogram, plot_lambda_densities

    combos = list(analysis)
    nc = len(combos)
    hard = asettings.hardness
    lvl = round(100 * asettings.confidence_level)
    rep = Report("Mechanical integrity of rough surfaces in contact — study report")

    # ---- the answer -------------------------------------------------------------------------
    from .answer import case_name, check_rows, degenerate_scene, first_screen_rows, overlap_note
    from .report_surfaces import like_section, measured_section, scene_sentence, surface_rows

    rep.heading("The answer")
    bem = info.get("bem")
    for warn in (degenerate_scene(analysis), overlap_note(settings, analysis)):
        if warn:
            rep.paragraph("⚠ " + warn)
    bem_an = info.get("bem_analysis")
    arows, acols = first_screen_rows(settings, asettings, analysis, bem, bem_an)
    rep.table(acols, arows,
              f"Probability that the contact pressure exceeds the hardness {hard:g} MPa somewhere on "
              f"one analysed area ({settings.length * 1e3:g} × {settings.length * 1e3:g} mm²), "
              f"predicted from the peak pressures of the asperities in contact with their number "
              f"per surface as a random count (docs/method.md §6), with its {lvl} % bootstrap "
              f"interval (surfaces resampled). 'Check' is the prediction tested on held-out "
              f"surfaces (coverage of the maximum, centring, and the damage probability at "
              f"{asettings.n_levels}+ hardness levels). The elastic BEM column is the same "
              f"predictor on the elastic solution of the first surfaces (per contact spot).")
    if bem:
        ratios = []
        for (ih, _), c in bem.items():
            r = c.summary().set_index("quantity")["ratio_mean"]
            ratios.append(f"{case_name(settings, ih)}: mean pressure ×{1 / r['mean_pressure_MPa']:.2g}, "
                          f"maximal pressure ×{1 / r['max_pressure_MPa']:.2g}")
        rep.paragraph("Contact model error: on the same surfaces the elastic boundary-element "
                      "solution gives " + "; ".join(ratios) + " the asperity model's (c = "
                      f"{settings.cone_factor:g}). The asperity model neglects elastic interaction "
                      "and prescribes the pressure shape; the damage verdict depends on the model.")
    notes = [f"{case_name(settings, ih)}: {r['asperity'].end_note}" for (ih, il), r in analysis.items()
             if r["asperity"].end_note]
    if notes:
        rep.paragraph("⚠ Fitted end point: " + "; ".join(notes) + ".")
    choices = [f"{case_name(settings, ih)}: {r['asperity'].choice.reason}"
               for (ih, il), r in analysis.items() if r["asperity"].choice is not None]
    if choices:
        rep.paragraph("Fit of the peak pressures, chosen on an inner split of the surfaces (never on "
                      "the surfaces it is checked against): " + "; ".join(choices) + ".")
    crows, ccols = check_rows(settings, asettings, analysis, bem_an)
    rep.table(ccols, crows,
              "Checks on held-out surfaces (fit on one fold, predict the other): coverage of the "
              "predicted interval of each surface's maximum, the t-test of (predicted − observed) "
              "maxima, the hardness levels at which the predicted damage probability lies inside "
              "the observed Wilson interval, and the extremal index θ (effective over nominal number "
              "of draws). A prediction passes when the coverage interval contains the level, the "
              "test does not reject at 5 % and ≥ 80 % of the levels are inside. The Holm column "
              "adjusts the centring p-values for testing every case (one family per model and "
              "sample; statsmodels' multipletests): it answers whether any case is off-centre, "
              "while each case's check uses its own p.")
    _answer_figures(rep, settings, asettings, analysis)
    left = info.get("bem_left_out") or []
    if left:
        rep.paragraph("⚠ Elastic BEM solves that did not converge within the iteration limit are "
                      "left out of its analysis (never used): " + "; ".join(
                          f"{case_label(settings, ih, il)} surface {i}" for ih, il, i in left) + ".")
    if bem_an:
        _answer_figures(rep, settings, asettings, bem_an, model="elastic BEM")
    paper = info.get("paper_findings")
    if paper:
        rep.heading("Consistency with the paper")
        rep.paragraph("Computed from the paper's Table 1 by this run (docs/method.md §11):")
        for line in paper:
            rep.paragraph("• " + line)

    # ---- summary ---------------------------------------------------------------------------
    rep.heading("Main results")
    rep.paragraph(
        scene_sentence(settings) + f" Per-asperity peaks: the GLD chosen per H "
        f"(above), B = {asettings.n_resamples} bootstrap resamples of whole surfaces; grid-point "
        f"pressures: {asettings.param.upper()} by {asettings.method} (the paper's), B = "
        f"{asettings.grid_resamples}; hardness {hard:g} MPa, {lvl} % intervals. Pressures in MPa.")
    rows = []
    for (ih, il), r in analysis.items():
        s = r["summary"]
        row = [case_label(settings, ih, il), s["mean_pressure"], s["contact_fraction"], s["n_contact"],
               s["n_asperities"], s["max_pressure"]]
        for kind in ("grid", "asperity"):
            d = r[kind].damage
            row.append("—" if d is None else
                       f"{fmt_cell(float(d.estimate))} [{fmt_cell(float(d.low))}, {fmt_cell(float(d.high))}]")
            v = r[kind].validation
            row.append("—" if v.table is None else
                       f"{100 * v.coverage:.0f} % [{100 * v.coverage_interval[0]:.0f}, "
                       f"{100 * v.coverage_interval[1]:.0f}]")
        rows.append(row)
    rep.table(["case", "mean contact pressure", "1 − α", "points in contact / surface",
               "asperities / surface", "max pressure / surface",
               "damage P (grid)", f"coverage of {lvl} % interval (grid)",
               "damage P (asperity)", f"coverage of {lvl} % interval (asperity)"], rows,
              f"Per-surface means; damage probability at {hard:g} MPa on one analysed area with its "
              f"{lvl} % bootstrap interval; coverage with its Wilson 95 % interval.")
    rep.paragraph(damage_sentence(settings, analysis, hard, lvl))
    jumps = [(case_label(settings, ih, il), r["summary"]) for (ih, il), r in analysis.items()
             if r["summary"].get("n_in_jump", 0)]
    if jumps:
        rep.paragraph(
            "Load control: the asperity model's force jumps where a summit starts to touch or a "
            "patch boundary passes a dip, so a requested load can fall inside a jump, where no "
            "state of the model carries it exactly; such surfaces keep the nearest physical "
            "state (docs/contact.md). " + "; ".join(
                f"{lab}: {s['n_in_jump']} of {s['n_surfaces']} surfaces, largest jump "
                f"{100 * s['max_force_jump']:.2g} % of the load, largest |force error| "
                f"{100 * s['force_error']:.2g} %" for lab, s in jumps) + ".")
    calib = []
    for (ih, il), r in analysis.items():
        for kind in ("grid", "asperity"):
            v = r[kind].validation
            if v.table is not None:
                calib.append(f"{case_label(settings, ih, il)}, {SAMPLE_LABELS[kind]}: "
                             + calibration_verdict(v, asettings.confidence_level))
    if calib:
        rep.paragraph("Calibration of the predicted maximum (calibrated = coverage consistent with "
                      "the nominal level, i.e. the level inside the Wilson interval, and the "
                      "centring t-test at the test level not rejecting; docs/method.md §9): "
                      + "; ".join(calib) + ".")

    # ---- the surfaces, when measured -----------------------------------------------------------
    if settings.measured:
        measured_section(rep, settings, results)
    if info.get("like") is not None:
        like_section(rep, settings, info["like"], plt)

    # ---- settings ---------------------------------------------------------------------------
    rep.heading("Settings, versions and timings")
    srows = [*surface_rows(settings),
             ["E (GPa), ν, cone factor c",
              f"{settings.E / 1e9:g}, {settings.nu:g}, {settings.cone_factor:g}"],
             ["seed", settings.seed], ["hardness Pd (MPa)", hard],
             ["GLD fit", f"{asettings.param.upper()} by {asettings.method}"],
             ["bootstrap resamples B", asettings.n_resamples],
             ["interval level", asettings.confidence_level],
             ["test level", asettings.test_level],
             ["guaranteed-pressure integrity level", asettings.integrity_level]]
    if info.get("bem_settings") is not None:
        b = info["bem_settings"]
        srows.append(["BEM comparison: surfaces per case K, boundary, tolerance, iteration limit",
                      f"{b.n_compare}, {'periodic' if b.periodic else 'isolated patch'}, {b.tol:g}, "
                      f"{b.max_iter}"])
    rep.table(["setting", "value"], [[a, fmt_cell(b)] for a, b in srows])
    for text in ([] if settings.measured else truncation_paragraphs(settings, info)):
        rep.paragraph(text)
    if info.get("truncation") and not settings.measured:
        rep.table(["H", "n_terms", "highest frequency (1/mm)", "mean pressure (GPa)", "1 − α",
                   "asperities in contact"], info["truncation"],
                  truncation_caption(settings, info.get("truncation_reference")))
    rep.table(["package", "version"], [[k, v] for k, v in info.get("versions", {}).items()])
    rep.table(["stage", "seconds"], [[k, v] for k, v in info.get("timings", {}).items()],
              f"Workers: {info.get('workers', '?')}. Command: `{info.get('command', '')}`")

    # ---- example surfaces and pressure maps ----------------------------------------------------
    stored = [(c, results.get((c[0], c[1], 0))) for c in combos]
    ex = [(c, r) for c, r in stored if r is not None and "heights" in r]
    if ex:
        rep.heading("Example surfaces")
        fig, axes = plt.subplots(1, len(ex), figsize=(4.6 * len(ex), 3.6), squeeze=False,
                                 layout="constrained")
        ext = [0, settings.length * 1e3, 0, settings.length * 1e3]
        for ax, ((ih, il), r) in zip(axes[0], ex, strict=True):
            im = ax.imshow(_display(np.asarray(r["heights"], dtype=float), "mean").T * 1e6,
                           origin="lower", extent=ext, cmap="viridis")
            ax.set_title(case_label(settings, ih, il))
            ax.set_xlabel("x (mm)")
            ax.set_ylabel("y (mm)")
            fig.colorbar(im, ax=ax, label="height (µm)")
        rep.figure("surfaces", fig, "Example surface (surface 0) of every case: heights in µm.")
        rep.heading("Pressure maps")
        fig, axes = plt.subplots(2, len(ex), figsize=(4.6 * len(ex), 7.4), squeeze=False,
                                 layout="constrained")
        dx = settings.length / settings.grid * 1e3
        for col, ((ih, il), r) in enumerate(ex):
            p = r["pressure"].astype(float) / 1e6
            pos = p[p > 0]
            norm = LogNorm(vmin=pos.min(), vmax=pos.max()) if pos.size and pos.min() < pos.max() else None
            pm = np.ma.masked_less_equal(p, 0)
            ax = axes[0, col]
            im = ax.imshow(np.ma.masked_less_equal(_display(p, "max"), 0).T, origin="lower", extent=ext,
                           cmap="magma", norm=norm, interpolation="nearest")
            ax.set_facecolor("#dde")
            ax.set_title(f"{case_label(settings, ih, il)}: contact pressure")
            ax.set_xlabel("x (mm)")
            ax.set_ylabel("y (mm)")
            fig.colorbar(im, ax=ax, label="pressure (MPa)")
            i0, j0 = np.unravel_index(np.argmax(p), p.shape)
            h = max(8, settings.grid // 16)
            sl = (slice(max(0, i0 - h), i0 + h), slice(max(0, j0 - h), j0 + h))
            ax = axes[1, col]
            sub = pm[sl]
            e2 = [sl[0].start * dx, (sl[0].start + sub.shape[0]) * dx,
                  sl[1].start * dx, (sl[1].start + sub.shape[1]) * dx]
            im = ax.imshow(sub.T, origin="lower", extent=e2, cmap="magma", norm=norm,
                           interpolation="nearest")
            ax.set_facecolor("#dde")
            ax.set_title("zoom on the highest pressure")
            ax.set_xlabel("x (mm)")
            ax.set_ylabel("y (mm)")
            fig.colorbar(im, ax=ax, label="pressure (MPa)")
        rep.figure("pressure_maps", fig, "Contact-pressure maps of the example surfaces (log colour "
                   "scale, grey: no contact) and a zoom around the highest pressure.")

    # ---- moments and lambdas ------------------------------------------------------------------
    from scipy import stats

    rep.heading("Moments and fitted GLD")
    rows = []
    for (ih, il), r in analysis.items():
        for kind in ("grid", "asperity"):
            sa = r[kind]
            x = sa.data
            m = [x.size, np.mean(x), np.std(x), stats.skew(x), stats.kurtosis(x, fisher=False)] \
                if x.size > 2 else [x.size] + [math.nan] * 4
            lam = sa.boot.fit.lambdas if sa.ok else (math.nan,) * 4
            fitname = f"{sa.param.upper()} {sa.method}" if sa.ok else "none"
            rows.append([case_label(settings, ih, il), SAMPLE_LABELS[kind], *m, fitname, *lam])
    rep.table(["case", "sample", "n", "mean", "std", "skewness α3", "kurtosis α4", "fit",
               "λ1", "λ2", "λ3", "λ4"], rows,
              "Pooled samples of all surfaces (MPa); λ1 in MPa, λ2 in 1/MPa.")
    notes = [f"{case_label(settings, ih, il)}, {SAMPLE_LABELS[k]}: {r[k].note}"
             for (ih, il), r in analysis.items() for k in ("grid", "asperity") if r[k].note]
    if notes:
        rep.paragraph("Fit notes: " + " | ".join(notes))

    rep.heading("Histograms with the fitted GLD densities")
    fig, axes = plt.subplots(2, nc, figsize=(4.2 * nc, 6.8), squeeze=False, layout="constrained")
    for col, ((ih, il), r) in enumerate(analysis.items()):
        for irow, kind in enumerate(("grid", "asperity")):
            sa = r[kind]
            ax = axes[irow, col]
            if sa.data.size:
                plot_histogram(sa.data, *([sa.boot.fit.dist] if sa.ok else []),
                               names=[f"GLD {sa.param.upper()}"] if sa.ok else None, ax=ax)
                ax.legend(fontsize=8)
            ax.set_title(f"{case_label(settings, ih, il)}\n{SAMPLE_LABELS[kind]}", fontsize=9)
            ax.set_xlabel("pressure (MPa)")
    rep.figure("histograms", fig, "Pooled pressures and the fitted GLD density: grid-point pressures "
               "(top) and per-asperity peak pressures (bottom).")

    rep.heading("Bootstrap densities of the λ parameters")
    for ih, il, sa in _fitted(analysis, "grid"):
        fig = plot_lambda_densities(sa.boot.lambdas, true=sa.boot.fit.lambdas)
        fig.suptitle(f"{case_label(settings, ih, il)}: {SAMPLE_LABELS['grid']}, B = {asettings.n_resamples}")
        rep.figure(f"lambdas_{ih}_{il}", fig, f"Kernel densities of the bootstrapped λ1..λ4 "
                   f"({case_label(settings, ih, il)}, grid-point pressures); dashed: full-sample fit.")

    # ---- maximum --------------------------------------------------------------------------------
    rep.heading("Maximal pressure over the analysed area")
    rep.paragraph(
        "For each bootstrap GLD the maximum of n draws has cdf F_b(x)^n; the density shown is the "
        "pooled mixture (1/B) Σ_b F_b(x)^n. n is the mean number of grid points in contact per "
        "surface (grid sample) or of asperities in contact per surface (asperity sample): the "
        "α δ(p) part of PR(p) carries no pressure, so the maximum over all N grid points is the "
        "maximum over the (1 − α) N points in contact.")
    fig, panels = _kind_panels(plt)
    rows = []
    for ax, kind in panels:
        for ih, il, sa in _fitted(analysis, kind):
            bm = sa.maximum
            lo, hi = bm.mixture_interval()
            span = hi - lo
            xs = np.linspace(max(bm.mixture.ppf(1e-4), lo - span), bm.mixture.isf(1e-4), 120)
            ax.plot(xs, bm.mixture.pdf(xs), label=case_label(settings, ih, il))
            ax.axvspan(lo, hi, alpha=0.08)
            rows.append([case_label(settings, ih, il), SAMPLE_LABELS[kind], sa.n_ref, bm.mean, lo, hi])
        ax.axvline(hard, color="k", ls=":", label=f"hardness {hard:g} MPa")
        ax.set_xlabel("maximal pressure (MPa)")
        ax.set_ylabel("density (1/MPa)")
        ax.set_title(SAMPLE_LABELS[kind])
        ax.legend(fontsize=8)
    rep.figure("maximum_density", fig, f"Density of the maximal pressure over one analysed area, "
               f"per H, with its {lvl} % interval (shaded).")
    rep.table(["case", "sample", "n", "mean maximum", f"{lvl} % low", f"{lvl} % high"], rows,
              "Maximal pressure (MPa) over one analysed area.")

    # ---- validation ---------------------------------------------------------------------------
    rep.heading("Validation across surfaces")
    rep.paragraph(
        f"Two-fold cross-validation: the surfaces are split into even and odd indices; a GLD "
        f"bootstrap fitted on one half predicts, for every surface of the other half, the "
        f"distribution of its maximal pressure given its own n (points or asperities in contact): "
        f"one random maximum per bootstrap GLD, whose mean is the prediction and whose "
        f"equal-tailed {lvl} % range is the predicted interval. Coverage = fraction of surfaces "
        f"whose observed maximum lies in its interval, with its Wilson 95 % binomial interval. "
        f"Test: one-sample two-sided t-test of the null hypothesis 'the mean of (predicted − "
        f"observed) is 0' at the {100 * (1 - asettings.test_level):g} % level (Wilcoxon "
        f"signed-rank p-value for reference).")
    vrows = []
    for kind in ("grid", "asperity"):
        figv, axv = plt.subplots(1, nc, figsize=(4.2 * nc, 3.6), squeeze=False, layout="constrained")
        figh, axh = plt.subplots(1, nc, figsize=(4.2 * nc, 3.2), squeeze=False, layout="constrained")
        for col, ((ih, il), r) in enumerate(analysis.items()):
            v = r[kind].validation
            ax = axv[0, col]
            ax.set_title(f"{case_label(settings, ih, il)}", fontsize=9)
            if v.table is None:
                import textwrap

                ax.text(0.5, 0.5, textwrap.fill((v.error or r[kind].note or "no fit")[:200], 40),
                        ha="center", va="center", fontsize=7, transform=ax.transAxes)
                vrows.append([case_label(settings, ih, il), SAMPLE_LABELS[kind], 0, "—", "—", "—",
                              "—", "—", v.error or r[kind].note])
                continue
            t = v.table
            cov = t["covered"].to_numpy()
            ax.errorbar(t["surface"], t["predicted"],
                        yerr=[t["predicted"] - t["low"], t["high"] - t["predicted"]],
                        fmt="none", ecolor="0.6", lw=1, label=f"predicted {lvl} % interval")
            ax.plot(t["surface"][cov], t["observed"][cov], "o", ms=3, color="tab:blue",
                    label="observed, inside")
            ax.plot(t["surface"][~cov], t["observed"][~cov], "x", ms=4, color="tab:red",
                    label="observed, outside")
            ax.set_xlabel("surface")
            ax.set_ylabel("maximal pressure (MPa)")
            ax.text(0.02, 0.97, f"coverage {100 * v.coverage:.0f} % [{100 * v.coverage_interval[0]:.0f}, "
                    f"{100 * v.coverage_interval[1]:.0f}]", transform=ax.transAxes, va="top", fontsize=8)
            ax.legend(fontsize=7, loc="lower right")
            d = (t["predicted"] - t["observed"]).to_numpy()
            ax = axh[0, col]
            ax.hist(d, bins="auto", color="tab:gray")
            ax.axvline(0, color="k", ls=":")
            ax.set_xlabel("predicted − observed (MPa)")
            ax.set_title(f"{case_label(settings, ih, il)}: t-test p = {fmt_cell(v.t_pvalue)}", fontsize=9)
            vrows.append([case_label(settings, ih, il), SAMPLE_LABELS[kind], len(t),
                          f"{100 * v.coverage:.1f} %",
                          f"[{100 * v.coverage_interval[0]:.1f}, {100 * v.coverage_interval[1]:.1f}] %",
                          float(np.mean(d)), v.t_pvalue, v.w_pvalue,
                          "rejected" if v.reject else "not rejected"])
        figv.suptitle(SAMPLE_LABELS[kind])
        rep.figure(f"validation_{kind}", figv, f"Observed maximal pressure of every surface against "
                   f"its predicted {lvl} % interval ({SAMPLE_LABELS[kind]}).")
        figh.suptitle(SAMPLE_LABELS[kind])
        rep.figure(f"differences_{kind}", figh, f"Histogram of (predicted − observed) maximal pressure "
                   f"({SAMPLE_LABELS[kind]}).")
    rep.table(["case", "sample", "surfaces", "coverage", "Wilson 95 %", "mean (pred. − obs.)",
               "t-test p", "Wilcoxon p", f"H0 at {100 * (1 - asettings.test_level):g} %"], vrows,
              f"Coverage of the predicted {lvl} % interval of the maximal pressure.")

    # ---- damage and integrity -------------------------------------------------------------------
    rep.heading("Damage probability at the hardness")
    rows = []
    for (ih, il), r in analysis.items():
        for kind in ("grid", "asperity"):
            d = r[kind].damage
            if d is None:
                rows.append([case_label(settings, ih, il), SAMPLE_LABELS[kind], r[kind].n_ref, "—", "—", "—"])
            else:
                rows.append([case_label(settings, ih, il), SAMPLE_LABELS[kind], r[kind].n_ref,
                             float(d.estimate), float(d.low), float(d.high)])
    rep.table(["case", "sample", "n", "damage probability", f"{lvl} % low", f"{lvl} % high"], rows,
              f"1 − F(Pd)^n at Pd = {hard:g} MPa on one analysed area "
              f"({settings.length * 1e3:g} × {settings.length * 1e3:g} mm²).")

    rep.heading("Integrity against area")
    fig, panels = _kind_panels(plt)
    grows = []
    for ax, kind in panels:
        for ih, il, sa in _fitted(analysis, kind):
            it = sa.integrity
            line, = ax.semilogx(it.area_factor, it.estimate, label=case_label(settings, ih, il))
            ax.fill_between(it.area_factor, it.low, it.high, color=line.get_color(), alpha=0.15)
            grows.append([case_label(settings, ih, il), SAMPLE_LABELS[kind],
                          *[sa.guaranteed[k] for k in (1.0, 10.0, 100.0, 1000.0)]])
        ax.set_xlabel("area factor k (area / analysed area)")
        ax.set_ylabel(f"integrity probability at {hard:g} MPa")
        ax.set_ylim(-0.02, 1.02)
        ax.set_title(SAMPLE_LABELS[kind])
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
    rep.figure("integrity_vs_area", fig, f"Integrity probability F(Pd)^(k n) against the area factor "
               f"k, with the {lvl} % bootstrap band.")
    rep.table(["case", "sample", "k = 1", "k = 10", "k = 100", "k = 1000"], grows,
              f"Guaranteed pressure Q(p^(1/(k n))) (MPa): all points of an area k times the analysed "
              f"one stay below it with probability p = {asettings.integrity_level:g}.")
    if info.get("bem"):
        _bem_section(rep, settings, asettings, info["bem"], info["bem_settings"],
                     info.get("bem_maps") or {})
    return rep


def _pm(v) -> str:
    """Mean ± standard deviation of a column (just the mean for one value)."""
    v = np.asarray(v, dtype=float)
    if v.size > 1:
        return f"{fmt_cell(float(v.mean()))} ± {fmt_cell(float(v.std(ddof=1)))}"
    return fmt_cell(float(v.mean()))


def _bem_section(rep: Report, settings, asettings, comps: dict, bsettings, maps: dict) -> None:
    """The section "Asperity model vs elastic BEM" (``glstat study --compare-bem``)."""
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    from .bem import MODEL_LABELS, MODELS, QUANTITIES, QUANTITY_LABELS, findings

    hard = asettings.hardness
    lvl = round(100 * asettings.confidence_level)
    k = bsettings.n_compare
    rep.heading("Asperity model vs elastic BEM")
    rep.paragraph(
        f"The first {k} surface{'s' if k > 1 else ''} of every case, solved again at the same nominal "
        f"pressure by the asperity model (`contact.solve`, c = {settings.cone_factor:g}) and by the "
        f"elastic boundary-element method (`contact.solve_bem`, Polonsky–Keer, tolerance "
        f"{bsettings.tol:g}), which keeps the elastic interaction between all grid points and "
        f"prescribes no pressure shape. Boundary condition of the BEM: "
        + ("periodic" if bsettings.periodic else
           "isolated patch on an unloaded half-space (the Weierstrass frequencies γ^n/L, γ = "
           f"{settings.gamma:g}, are not integer multiples of 1/L, so the surfaces do not repeat "
           "on the grid; the asperity model sees an isolated patch too)")
        + f". The grid-point pressures of each model, pooled over the {k} surface"
        f"{'s' if k > 1 else ''}, get the study's "
        f"GLD fit ({asettings.param.upper()} {asettings.method}, fallbacks as above) with B = "
        f"{asettings.n_resamples} bootstrap resamples, and the damage probability at {hard:g} MPa is "
        f"1 − F(Pd)^n with n = that model's mean number of points in contact per surface "
        f"({lvl} % bootstrap interval). Ratios are asperity model / BEM (1: no error); ± is the "
        f"standard deviation over the surfaces, the range their minimum and maximum.")
    labels = {c: case_label(settings, *c) for c in comps}
    rep.paragraph("**Findings.** " + findings({labels[c]: v for c, v in comps.items()}))
    unconverged = sum(int((~v.surfaces.loc[v.surfaces["model"] == "bem", "converged"]).sum())
                      for v in comps.values())
    if unconverged:
        rep.paragraph(f"**Warning:** {unconverged} BEM solve(s) did not reach the tolerance "
                      f"{bsettings.tol:g} within {bsettings.max_iter} iterations; their rows use the "
                      f"last iterate.")
    extra = {"n_clusters": "contact spots per surface", "mean_peak_MPa": "mean spot peak pressure (MPa)",
             "border_load_fraction": "load share on the grid border"}
    for c, v in comps.items():
        s = v.surfaces
        r = v.ratios()
        rows = []
        for q in (*QUANTITIES, *extra):
            a = s.loc[s["model"] == "asperity", q].to_numpy(dtype=float)
            b = s.loc[s["model"] == "bem", q].to_numpy(dtype=float)
            if q in QUANTITIES:
                rq = r[q].to_numpy(dtype=float)
                ratio, span = _pm(rq), f"{fmt_cell(float(rq.min()))} – {fmt_cell(float(rq.max()))}"
            else:
                ratio = span = "—"
            rows.append([QUANTITY_LABELS.get(q) or extra[q], _pm(a), _pm(b), ratio, span])
        rep.table(["quantity", "asperity model", "elastic BEM", "ratio asperity / BEM", "ratio range"],
                  rows, f"{labels[c]}: {k} surface{'s' if k > 1 else ''}, per-surface values "
                  f"(mean ± standard deviation).")
    # histograms of both models with their GLD densities, one panel per case
    nc = len(comps)
    fig, axes = plt.subplots(1, nc, figsize=(4.6 * nc, 3.8), squeeze=False, layout="constrained")
    colours = {"asperity": "tab:blue", "bem": "tab:red"}
    for ax, (c, v) in zip(axes[0], comps.items(), strict=True):
        data = [v.fits[m].data for m in MODELS]
        allx = np.concatenate(data)
        if allx.size == 0:
            ax.set_title(labels[c])
            continue
        lo, hi = float(allx.min()), float(allx.max())
        bins = np.geomspace(lo, hi * (1 + 1e-9), 40) if hi > lo > 0 else 10
        heights = []
        for m, x in zip(MODELS, data, strict=True):
            if x.size:
                hv, _, _ = ax.hist(x, bins=bins, density=True, histtype="step", lw=1.5, color=colours[m],
                                   label=f"{MODEL_LABELS[m]} (n = {x.size})")
                heights.append(np.asarray(hv)[np.asarray(hv) > 0])
            f = v.fits[m]
            if f.ok:
                xs = np.geomspace(lo, hi, 400) if hi > lo > 0 else np.linspace(lo, hi + 1, 400)
                with np.errstate(all="ignore"):
                    ys = np.asarray(f.boot.fit.dist.pdf(xs), dtype=float)
                ax.plot(xs, ys, color=colours[m], ls="--", lw=1,
                        label=f"GLD {f.param.upper()} {f.method}")
        ax.axvline(hard, color="k", ls=":", label=f"hardness {hard:g} MPa")
        ax.set_xscale("log")
        ax.set_yscale("log")
        hv = np.concatenate(heights) if heights else np.empty(0)
        if hv.size:  # the GLD densities vanish at bounded supports: keep the histograms in view
            ax.set_ylim(hv.min() / 5, hv.max() * 5)
        ax.set_xlabel("grid-point pressure (MPa)")
        ax.set_ylabel("density (1/MPa)")
        ax.set_title(labels[c], fontsize=9)
        ax.legend(fontsize=7)
    rep.figure("bem_histograms", fig, f"Grid-point pressures of the asperity model (blue) and of the "
               f"elastic BEM (red), pooled over the {k} compared surface{'s' if k > 1 else ''} of each "
               f"case (log bins, densities per MPa), with each model's fitted GLD density (dashed).")
    rows = []
    for c, v in comps.items():
        for _, f in v.fit_frame().iterrows():
            rows.append([labels[c], MODEL_LABELS[f["model"]], f["n"], f["n_ref"], f["fit"],
                         f["lambda1"], f["lambda2"], f["lambda3"], f["lambda4"], f["damage"],
                         f["damage_low"], f["damage_high"]])
    rep.table(["case", "model", "n pooled", "n per surface", "fit", "λ1", "λ2", "λ3", "λ4",
               "damage probability", f"{lvl} % low", f"{lvl} % high"], rows,
              f"GLD of each model's grid-point pressures (MPa; λ1 in MPa, λ2 in 1/MPa) and the damage "
              f"probability 1 − F(Pd)^n at Pd = {hard:g} MPa on one analysed area.")
    notes = [f"{labels[c]}, {MODEL_LABELS[m]}: {v.fits[m].note}" for c, v in comps.items()
             for m in MODELS if v.fits[m].note]
    if notes:
        rep.paragraph("Fit notes: " + " | ".join(notes))
    if maps:
        cases = [c for c in comps if c in maps]
        fig, axes = plt.subplots(2, len(cases), figsize=(4.6 * len(cases), 7.4), squeeze=False,
                                 layout="constrained")
        dx = settings.length / settings.grid * 1e3
        for col, c in enumerate(cases):
            mp = {m: maps[c][m] / 1e6 for m in MODELS}
            pos = np.concatenate([x[x > 0] for x in mp.values()])
            norm = LogNorm(vmin=pos.min(), vmax=pos.max()) if pos.size and pos.min() < pos.max() else None
            i0, j0 = np.unravel_index(np.argmax(mp["bem"]), mp["bem"].shape)
            h = max(8, settings.grid // 16)
            sl = (slice(max(0, i0 - h), i0 + h), slice(max(0, j0 - h), j0 + h))
            for row, m in enumerate(MODELS):
                sub = np.ma.masked_less_equal(mp[m][sl], 0)
                ext = [sl[0].start * dx, (sl[0].start + sub.shape[0]) * dx,
                       sl[1].start * dx, (sl[1].start + sub.shape[1]) * dx]
                ax = axes[row, col]
                im = ax.imshow(sub.T, origin="lower", extent=ext, cmap="magma", norm=norm,
                               interpolation="nearest")
                ax.set_facecolor("#dde")
                ax.set_title(f"{labels[c]}: {MODEL_LABELS[m]}", fontsize=9)
                ax.set_xlabel("x (mm)")
                ax.set_ylabel("y (mm)")
                fig.colorbar(im, ax=ax, label="pressure (MPa)")
        rep.figure("bem_maps", fig, "Surface 0 of every case: pressure of the asperity model (top) and "
                   "of the elastic BEM (bottom) around the BEM's highest pressure (common log colour "
                   "scale per case, grey: no contact).")
