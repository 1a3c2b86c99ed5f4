"""Report text and sections describing the surfaces: simulated, measured, or simulated like a
measured template (computations live in :mod:`glstat.study.measured`). The sections return
their :class:`~glstat.study.report_document.Blocks`."""

from __future__ import annotations

import math
import os
from typing import Any

from ..formatting import fmt_number
from .campaign import MEASURED_PARAMETERS
from .report_document import Blocks
from .report_figures import psd_like_figure
from .topography import FORM_LABELS

__all__ = ["area_text", "grid_text", "like_section", "measured_section", "scene_sentence",
           "surface_rows"]

#: Units and scale of the ISO parameters in the measured table.
_ISO_DISPLAY = {"Sq": ("Sq (µm)", 1e6), "Ssk": ("Ssk", 1.0), "Sku": ("Sku", 1.0),
                "Sdq": ("Sdq", 1.0), "Sp": ("Sp (µm)", 1e6), "Sv": ("Sv (µm)", 1e6),
                "hurst": ("H (structure function)", 1.0)}


def area_text(settings) -> str:
    """The side lengths of one surface, ``"Lx mm × Ly mm"`` (three significant digits)."""
    lx, ly = settings.size
    return f"{lx * 1e3:.3g} mm × {ly * 1e3:.3g} mm"


def grid_text(settings) -> str:
    """The grid of one surface: ``"n² points"`` on a square grid, else ``"nx × ny points"``
    and the spacing along x and y when they differ."""
    (nx, ny), (dx, dy) = settings.shape, settings.spacing
    if settings.square:
        return f"{nx}² points"
    text = f"{nx} × {ny} points"
    if not math.isclose(dx, dy, rel_tol=1e-6):
        text += f" (spacing {dx * 1e6:.4g} µm along x, {dy * 1e6:.4g} µm along y)"
    return text


def _form(settings) -> str:
    return FORM_LABELS.get(settings.form, settings.form)


def scene_sentence(settings) -> str:
    """The first sentence of "Main results": what surfaces were pressed, and how."""
    model = (f"pressed by a rigid flat (asperity model, c = {settings.cone_factor:g}, E = "
             f"{settings.E / 1e9:g} GPa, ν = {settings.nu:g})")
    if settings.measured:
        return (f"{settings.n_surfaces} {measured_surfaces_text(settings)}, {grid_text(settings)} "
                f"on {area_text(settings)}, mean Rq = {settings.rq * 1e6:.3g} µm, {model}.")
    like = ""
    if settings.like:
        like = (f", statistically like the measured {os.path.basename(settings.topographies[0])} "
                f"(H, Rq, size and truncation from its spectrum; section \"Measured template and "
                f"simulated surfaces\")")
    return (f"{settings.n_surfaces} Weierstrass surfaces per Hurst exponent{like}, "
            f"{grid_text(settings)} on {area_text(settings)}, Rq = {settings.rq_text} µm"
            f"{' (one per H)' if isinstance(settings.rq, tuple) else ''}, {model}.")


def measured_surfaces_text(settings) -> str:
    """What the measured surfaces are, in words: "measured topographies (one surface per file,
    form removed: …)" or "areas of 1 measured scan (each cut into 4 × 3 areas, …)"."""
    files = len(settings.topographies)
    if settings.tiles is None:
        return f"measured topographies (one surface per file, form removed: {_form(settings)})"
    nx, ny = settings.tiles
    return (f"areas of {files} measured scan{'s' if files > 1 else ''} (each cut into {nx} × {ny} "
            f"areas of equal size, form removed from each area: {_form(settings)})")


def surface_rows(settings) -> list[list[Any]]:
    """The rows of the settings table that describe the surfaces."""
    rows: list[list[Any]] = []
    if settings.measured:
        rows += [["measured topographies", f"{len(settings.topographies)} files in "
                  f"{os.path.commonpath([os.path.dirname(p) for p in settings.topographies])}"],
                 ["form removed", f"{settings.form} ({_form(settings)})"],
                 *([["areas per file (along x × along y)",
                     "{} × {}".format(*settings.tiles)]] if settings.tiles else []),
                 *([["spacing given (--spacing, µm)", "{:.4g} × {:.4g}".format(
                     *(v * 1e6 for v in settings.file_spacing))]] if settings.file_spacing else []),
                 *([["length unit given (--unit)", settings.file_unit]] if settings.file_unit
                   else []),
                 ["Hurst exponent (median of the areas' structure-function estimates in [0, 1]; "
                  "a label only, 0.5 when no area has one: column H below)",
                  f"{settings.hurst[0]:.3g}"]]
    else:
        rows.append(["Hurst exponents H", ", ".join(f"{h:.4g}" for h in settings.hurst)])
        if settings.like:
            rows += [["measured template", settings.topographies[0]],
                     ["its SHA-256", settings.digests[0]],
                     ["form removed", f"{settings.form} ({_form(settings)})"]]
    rows += [["nominal pressures (MPa)", ", ".join(f"{p / 1e6:g}" for p in settings.pressures)],
             ["surfaces per (H, load)", settings.n_surfaces],
             ["grid", "{} × {}".format(*settings.shape)],
             ["size (mm)", "{:g} × {:g}".format(*(v * 1e3 for v in settings.size))],
             ["spacing (µm)", "{:.4g} × {:.4g}".format(*(v * 1e6 for v in settings.spacing))],
             ["Rq (µm)" + (" (mean over the files)" if settings.measured else
                           " per H" if isinstance(settings.rq, tuple) else ""), settings.rq_text]]
    if not settings.measured:
        n = len(settings.hurst)
        rows += [["γ", settings.gamma],
                 ["Weierstrass terms per axis (n_terms) per H",
                  ", ".join("Nyquist" if t is None else str(t) for t in settings.n_terms)],
                 [f"highest frequency γ^(N−1)/{'L' if settings.square else 'max(Lx, Ly)'} (1/mm) "
                  f"per H",
                  ", ".join(f"{settings.max_frequency(i) / 1e3:.3g}" for i in range(n))],
                 ["shortest wavelength (µm) per H",
                  ", ".join(f"{1e6 / settings.max_frequency(i):.3g}" for i in range(n))]]
    return rows


def measured_section(settings, results: dict) -> Blocks:
    """"Measured topographies": one row per file with its ISO 25178 parameters and its contact."""
    rep = Blocks()
    rep.heading("Measured topographies")
    unit = "area" if settings.tiles else "file"
    cut = ("" if settings.tiles is None else
           f"Each file is cut into {settings.tiles[0]} × {settings.tiles[1]} areas of equal size "
           f"(along x × along y; points left over at the far end of an axis are not used). ")
    rep.paragraph(
        cut + f"Each {unit} is one surface; its form ({_form(settings)}, fitted on the measured "
        f"points{' of the area, as for a separate scan' if settings.tiles else ''}) was removed "
        f"before the contact solve, lengths and heights come from "
        f"the file in metres and the analysed area is one {unit}'s ({grid_text(settings)} on "
        f"{area_text(settings)}). Points missing in a file carry no load and are no part of the "
        f"nominal area: the nominal pressure is the load over the measured area (measured points "
        f"× dx × dy, in the table). ISO 25178-2 parameters "
        f"about the mean of the levelled heights; the Hurst exponent from the structure function "
        f"(— when the fit is outside [0, 1]). A file's SHA-256 is checked before it is used, so a "
        f"changed file is never mixed with results of the old one.")
    cols = [unit, *[_ISO_DISPLAY[k][0] for k in MEASURED_PARAMETERS], "missing points",
            "measured area (mm²)",
            *[f"{p / 1e6:g} MPa: mean / max pressure (MPa), asperities" for p in settings.pressures]]
    rows = []
    for i in range(settings.n_surfaces):
        first = next((results[k] for k in results if k[0] == 0 and k[2] == i), None)
        if first is None:
            continue
        row = [settings.surface_name(i)]
        row += [fmt_number(float(first.get(f"iso_{k}", math.nan)), ".3g", _ISO_DISPLAY[k][1])
                for k in MEASURED_PARAMETERS]
        missing = float(first.get("masked_fraction", 0.0))
        row.append(f"{100 * missing:.2g} %")
        row.append(f"{(1.0 - missing) * math.prod(settings.size) * 1e6:.4g}")
        for il in range(len(settings.pressures)):
            r = results.get((0, il, i))
            row.append("—" if r is None else
                       f"{fmt_number(float(r['mean_pressure']), '.4g', 1e-6)} / "
                       f"{fmt_number(float(r['max_pressure']), '.4g', 1e-6)}, {int(r['n_asperities'])}")
        rows.append(row)
    rep.table(cols, rows, f"One row per measured {unit}.")
    for text in measured_scope_notes(settings):
        rep.paragraph(text)
    return rep


def measured_scope_notes(settings) -> list[str]:
    """What the measured surfaces can and cannot tell, as report paragraphs: how many surfaces
    the held-out checks need, and, for areas cut from few scans, what such areas describe."""
    from ..gof.binomial_check import outcomes_needed

    notes = []
    n = settings.n_surfaces
    low, high = outcomes_needed(0.1), outcomes_needed(0.5)
    what = "areas" if settings.tiles else "files"
    if n < high:
        notes.append(
            f"⚠ {n} {what}: a held-out check can pass only when it would detect a miss of 20 "
            f"percentage points with 80 % power, which takes about {low} surfaces at a predicted "
            f"10 % or 90 % and {high} at 50 %; with fewer a check says \"not checkable\" (the "
            f"table of checks names the smallest miss it could detect). "
            + settings.more_surfaces_advice()[0].upper() + settings.more_surfaces_advice()[1:]
            + ".")
    files = len(settings.topographies)
    if settings.tiles is not None and files < 5:
        notes.append(
            f"The {n} areas come from {files} scan{'s' if files > 1 else ''}: neighbouring areas "
            f"of one place on one part, measured by one instrument. They tell how the damage "
            f"probability of one {area_text(settings)} area varies within that place, and how it "
            f"grows with the area there; they cannot tell how it varies between parts, places "
            f"or instruments — that needs scans of several places (more files). Neighbouring "
            f"areas also share their longest wavelengths, so they are not fully independent and "
            f"the intervals are somewhat too narrow when the scan's spectrum has power at "
            f"wavelengths near the area's size.")
    return notes


def like_section(settings, like: dict) -> Blocks:
    """"Measured template and simulated surfaces": spectrum fit, ISO parameters and PSDs side by
    side, and the contact of the template against the simulated surfaces."""
    rep = Blocks()
    p = like["parameters"]
    fit = p.fit
    rep.heading("Measured template and simulated surfaces")
    rep.paragraph(
        f"The surfaces of this study are Weierstrass series statistically like the measured "
        f"{os.path.basename(settings.topographies[0])} (form removed: {settings.form}). Its "
        f"radially averaged PSD gives H = {fit.hurst:.3g} ± {fit.hurst_se:.2g} (R² = {fit.r2:.3g} "
        f"over {fit.n_bins} rings, {fit.q_fit_min:.3g}–{fit.q_fit_max:.3g} rad/m"
        + (f"; used H = {p.hurst:.3g}, the nearest end of [0, 1]" if p.hurst != fit.hurst else "")
        + f"), Rq = {p.rq * 1e6:.4g} µm about its plane, and "
        + (f"a short-wavelength cut-off at {fit.q_s:.3g} rad/m" if fit.cutoff_detected
           else "no short-wavelength cut-off (the series runs to the Nyquist wavevector)")
        + (f"; its roll-off below {fit.q_r:.3g} rad/m cannot be reproduced by the series"
           if fit.rolloff_detected else "")
        + f". The series has {p.n_terms[0]} terms per axis (γ = {p.gamma:g}) on the measured grid "
          f"and spacing ({grid_text(settings)} on {area_text(settings)}).")
    if like.get("resampled"):
        rep.paragraph(f"Spacing: {like['resampled']}. The simulated surfaces have that one spacing.")
    filled = getattr(fit, "filled_fraction", 0.0)
    if filled > 0:
        rep.paragraph(f"Missing points: {100 * filled:.2g} % of the template's points were not "
                      f"measured; they were filled by harmonic interpolation (each the mean of its "
                      f"neighbours) for the spectrum fit only.")
    iso = like["iso"]
    n_sim = len(like["simulated"])
    rows = [[name, fmt_number(r["measured"], ".4g", 1e6 if r["unit"] == "m" else 1.0),
             fmt_number(r["simulated_mean"], ".4g", 1e6 if r["unit"] == "m" else 1.0),
             fmt_number(r["simulated_std"], ".2g", 1e6 if r["unit"] == "m" else 1.0),
             fmt_number(r["z"], ".2g", 1.0), "µm" if r["unit"] == "m" else r["unit"]]
            for name, r in iso.iterrows()]
    rep.table(["parameter", "measured", "simulated mean", "simulated sd", "z", "unit"], rows,
              f"ISO 25178-2 parameters (about the least-squares plane) of the measured template and "
              f"of the first {n_sim} simulated surfaces; z = (measured − simulated mean) / "
              f"simulated sd.")
    rep.figure("psd_like", psd_like_figure(like),
               "Radially averaged power spectral density of the measured template, the mean and "
               f"95 % band of {n_sim} simulated surfaces, and the power law fitted to the template.")
    prow = []
    for _, r in like["pressure"].iterrows():
        scale, spec = ((1e-6, ".4g") if "pressure" in r["quantity"] else (1.0, ".3g"))
        low, high = (fmt_number(r[q], spec, scale) for q in ("simulated_q05", "simulated_q95"))
        prow.append([f"{r['pressure_mpa']:g} MPa", r["quantity"], fmt_number(r["measured"], spec, scale),
                     fmt_number(r["simulated_mean"], spec, scale), f"{low} – {high}"])
    rep.table(["load", "quantity", "measured template", "simulated mean", "simulated 5–95 %"], prow,
              "The asperity model on the measured template and on the simulated surfaces "
              "(pressures in MPa). A template value outside the simulated range means the "
              "simulated surfaces do not reproduce its contact.")
    outside = [r["quantity"] for _, r in like["pressure"].iterrows()
               if r["measured"] == r["measured"]
               and not (r["simulated_q05"] <= r["measured"] <= r["simulated_q95"])]
    if like["pressure"]["measured"].isna().all():
        rep.paragraph("The template has no summit (no point strictly higher than its 8 "
                      "neighbours away from the border) once its form is removed, so the asperity "
                      "model cannot load it: its column is empty.")
    if outside:
        rep.paragraph("⚠ Outside the simulated 5–95 % range: " + ", ".join(sorted(set(outside)))
                      + ". The damage probability above describes the simulated surfaces; compare "
                        "with a study of measured topographies (--topographies).")
    return rep
