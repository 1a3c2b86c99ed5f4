"""The section "Asperity model vs elastic BEM" of the study report (``glstat study
--compare-bem``): the first surfaces of every case solved by both models, their per-surface
statistics, pressure distributions, fitted GLDs and damage probabilities."""

from __future__ import annotations

from .answer import case_label
from .report_document import Blocks, fmt_cell
from .report_figures import bem_histograms_figure, bem_maps_figure
from .report_numbers import comparison_rows, unconverged_solves

__all__ = ["bem_section"]

#: Per-surface quantities of the comparison shown without a ratio, with their labels.
_EXTRA = {"n_clusters": "contact spots per surface", "mean_peak_MPa": "mean spot peak pressure (MPa)",
          "border_load_fraction": "load share on the grid border"}


def _pm(stat: tuple[float, float | None]) -> str:
    """Mean ± standard deviation (just the mean for one value)."""
    mean, sd = stat
    return fmt_cell(mean) if sd is None else f"{fmt_cell(mean)} ± {fmt_cell(sd)}"


def _method(settings, asettings, bsettings) -> str:
    """The paragraph on how both models were solved and fitted."""
    k = bsettings.n_compare
    plural = "s" if k > 1 else ""
    return (
        f"The first {k} surface{plural} of every case, solved again at the same nominal "
        f"pressure by the asperity model (`contact.solve`, c = {settings.cone_factor:g}) and by the "
        f"elastic boundary-element method (`contact.solve_bem`, Polonsky–Keer, tolerance "
        f"{bsettings.tol:g}), which keeps the elastic interaction between all grid points and "
        f"prescribes no pressure shape. Boundary condition of the BEM: "
        + ("periodic" if bsettings.periodic else
           "isolated patch on an unloaded half-space (the Weierstrass frequencies γ^n/L, γ = "
           f"{settings.gamma:g}, are not integer multiples of 1/L, so the surfaces do not repeat "
           "on the grid; the asperity model sees an isolated patch too)")
        + f". The contact-spot peak pressures of each model (the highest pressure of every "
        f"8-connected contact spot inside the patch), pooled over the {k} surface{plural}, get "
        f"the study's GLD fit ({asettings.param.upper()} {asettings.method}, fallbacks as above) "
        f"with B = "
        f"{asettings.n_resamples} bootstrap resamples of whole surfaces, and the damage "
        f"probability at {asettings.hardness_mpa:g} MPa is 1 − E[F(Pd)^N] with N the number of "
        f"contact spots of a surface, a random count "
        f"({round(100 * asettings.confidence_level)} % bootstrap interval). "
        f"Ratios are asperity model / BEM (1: no error); ± is the "
        f"standard deviation over the surfaces, the range their minimum and maximum.")


def _quantity_table(out: Blocks, comparison, label: str, k: int) -> None:
    """The per-surface statistics of both models of one case, with their ratio."""
    from .model_comparison import QUANTITIES, QUANTITY_LABELS

    rows = []
    for rec in comparison_rows(comparison, (*QUANTITIES, *_EXTRA), QUANTITIES):
        q = rec["quantity"]
        if rec["ratio"] is None:
            ratio = span = "—"
        else:
            ratio = _pm(rec["ratio"])
            span = f"{fmt_cell(rec['ratio_min'])} – {fmt_cell(rec['ratio_max'])}"
        rows.append([QUANTITY_LABELS.get(q) or _EXTRA[q], _pm(rec["asperity"]), _pm(rec["bem"]),
                     ratio, span])
    out.table(["quantity", "asperity model", "elastic BEM", "ratio asperity / BEM", "ratio range"],
              rows, f"{label}: {k} surface{'s' if k > 1 else ''}, per-surface values "
              f"(mean ± standard deviation).")


def bem_section(settings, asettings, comps: dict, bsettings, maps: dict) -> Blocks:
    """"Asperity model vs elastic BEM".

    Parameters
    ----------
    settings : CampaignSettings
    asettings : AnalysisSettings
    comps : dict
        ``(ih, il) -> BEMComparison``.
    bsettings : BEMSettings
    maps : dict
        ``(ih, il) -> {model: pressure map of surface 0}`` (may be empty).

    Returns
    -------
    Blocks
    """
    from .both_models import MODEL_LABELS, MODELS
    from .comparison_text import findings

    hard, lvl = asettings.hardness_mpa, round(100 * asettings.confidence_level)
    k = bsettings.n_compare
    out = Blocks()
    out.heading("Asperity model vs elastic BEM")
    out.paragraph(_method(settings, asettings, bsettings))
    labels = {c: case_label(settings, *c) for c in comps}
    out.paragraph("**Findings.** " + findings({labels[c]: v for c, v in comps.items()}))
    unconverged = unconverged_solves(comps)
    if unconverged:
        out.paragraph(f"**Warning:** {unconverged} BEM solve(s) did not reach the tolerance "
                      f"{bsettings.tol:g} within {bsettings.max_iter} iterations; their rows use the "
                      f"last iterate.")
    for c, v in comps.items():
        _quantity_table(out, v, labels[c], k)
    out.figure("bem_histograms", bem_histograms_figure(comps, labels, hard),
               f"Contact-spot peak pressures of the asperity model (blue) and of the elastic BEM (red), "
               f"pooled over the {k} compared surface{'s' if k > 1 else ''} of each case (log bins, "
               f"densities per MPa), with each model's fitted GLD density (dashed).")
    rows = []
    for c, v in comps.items():
        for _, f in v.fit_frame().iterrows():
            rows.append([labels[c], MODEL_LABELS[f["model"]], f["n"], f["n_ref"], f["fit"],
                         f["lambda1"], f["lambda2"], f["lambda3"], f["lambda4"], f["damage"],
                         f["damage_low"], f["damage_high"]])
    out.table(["case", "model", "spot peaks pooled", "spots per surface", "fit", "λ1", "λ2", "λ3",
               "λ4", "damage probability", f"{lvl} % low", f"{lvl} % high"], rows,
              f"GLD of each model's contact-spot peak pressures (the highest pressure of every "
              f"8-connected contact spot inside the patch; MPa, λ1 in MPa, λ2 in 1/MPa) and the "
              f"damage probability 1 − E[F(Pd)^N] at Pd = {hard:g} MPa on one analysed area, N "
              f"the spots of a surface (surfaces resampled by the bootstrap).")
    notes = [f"{labels[c]}, {MODEL_LABELS[m]}: {v.fits[m].note}" for c, v in comps.items()
             for m in MODELS if v.fits[m].note]
    if notes:
        out.paragraph("Fit notes: " + " | ".join(notes))
    if maps:
        out.figure("bem_maps", bem_maps_figure(settings, [c for c in comps if c in maps], maps, labels),
                   "Surface 0 of every case: pressure of the asperity model (top) and of the elastic "
                   "BEM (bottom) around the BEM's highest pressure (common log colour scale per "
                   "case, grey: no contact).")
    return out
