"""The figures of the study report: each function draws one matplotlib figure from analysis
results and returns it (the report's sections add it with its caption)."""

from __future__ import annotations

import math
import textwrap
from typing import Any

import numpy as np

from .allowable import area_words
from .analysis_settings import PRIMARY_SAMPLE, SAMPLE_LABELS
from .answer import case_label
from .report_document import fmt_cell
from .report_numbers import SAMPLE_ORDER, fitted

__all__ = ["bem_histograms_figure", "bem_maps_figure", "damage_curve_figure",
           "damage_reliability_figure", "differences_figure", "display_map", "histograms_figure",
           "integrity_figure", "lambda_figure", "maximum_figure", "pressure_maps_figure",
           "psd_like_figure", "surfaces_figure", "validation_figure"]


def pyplot():
    """:mod:`matplotlib.pyplot` on the Agg backend unless another one was chosen."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def display_map(a: np.ndarray, how: str, size: int = 512) -> np.ndarray:
    """A map reduced by blocks to at most ``size`` pixels per side for display (block mean, or
    block maximum so that no contact peak disappears)."""
    f = max(1, -(-max(a.shape) // size))
    if f == 1:
        return a
    n0, n1 = (a.shape[0] // f) * f, (a.shape[1] // f) * f
    blocks = a[:n0, :n1].reshape(n0 // f, f, n1 // f, f)
    return blocks.max(axis=(1, 3)) if how == "max" else blocks.mean(axis=(1, 3))


def sample_panels() -> tuple[Any, list[tuple[Any, str]]]:
    """A figure with one panel per sample, side by side.

    Returns
    -------
    fig : matplotlib.figure.Figure
    panels : list of (matplotlib.axes.Axes, str)
        The axes of the grid-point and of the contact-spot sample, with the sample.
    """
    fig, axes = pyplot().subplots(1, 2, figsize=(11, 3.8), squeeze=False, layout="constrained")
    return fig, [(axes[0, col], sample) for col, sample in enumerate(SAMPLE_ORDER)]


def _log_norm(positive: np.ndarray):
    """A logarithmic colour scale over the positive values, or None when they are one value."""
    from matplotlib.colors import LogNorm

    if positive.size and positive.min() < positive.max():
        return LogNorm(vmin=positive.min(), vmax=positive.max())
    return None


def _extent(settings) -> list[float]:
    """The image extent of one surface, [0, Lx, 0, Ly] in mm."""
    lx, ly = settings.size
    return [0.0, lx * 1e3, 0.0, ly * 1e3]


def _spacing_mm(settings) -> tuple[float, float]:
    """The grid spacing (dx, dy) of one surface in mm."""
    dx, dy = settings.spacing
    return dx * 1e3, dy * 1e3


def _zoom(a: np.ndarray, grid: int) -> tuple[slice, slice]:
    """The window of ``grid // 16`` points (at least 8) each side of the maximum of ``a``."""
    i0, j0 = np.unravel_index(np.argmax(a), a.shape)
    h = max(8, grid // 16)
    return slice(max(0, i0 - h), i0 + h), slice(max(0, j0 - h), j0 + h)


def _zoom_panel(fig, ax, sub, sl, spacing: tuple[float, float], norm, title: str,
                **title_kw) -> None:
    """One panel of a zoomed pressure map (MPa, masked where there is no contact); ``spacing``
    is (dx, dy) in mm."""
    dx, dy = spacing
    ext = [sl[0].start * dx, (sl[0].start + sub.shape[0]) * dx,
           sl[1].start * dy, (sl[1].start + sub.shape[1]) * dy]
    im = ax.imshow(sub.T, origin="lower", extent=ext, cmap="magma", norm=norm, interpolation="nearest")
    ax.set_facecolor("#dde")
    ax.set_title(title, **title_kw)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    fig.colorbar(im, ax=ax, label="pressure (MPa)")


def damage_curve_figure(settings, asettings, analysis: dict, suffix: str = ""):
    """Damage probability of one area against the hardness, per case: the contact-spot
    predictor with its band, and the observed fraction of surfaces above it."""
    cases = list(analysis.items())
    fig, axes = pyplot().subplots(1, len(cases), figsize=(4.2 * len(cases), 3.4), squeeze=False)
    for ax, ((ih, il), r) in zip(axes[0], cases, strict=True):
        c = r[PRIMARY_SAMPLE].damage_curve
        if c is None:
            ax.set_axis_off()
            continue
        x = c["hardness_mpa"] / 1e3
        ax.fill_between(x, c["low"], c["high"], alpha=0.3, label="90 % band")
        ax.plot(x, c["damage"], label="predicted")
        ax.step(x, c["observed"], where="post", color="k", lw=1, label="observed fraction")
        ax.axvline(asettings.hardness_mpa / 1e3, color="r", ls="--", lw=1, label="hardness")
        table = r[PRIMARY_SAMPLE].validation.table
        top = float(np.quantile(table["observed"], 0.95)) / 1e3 if table is not None else float(x.max())
        ax.set_xlim(float(x.min()), max(top * 1.15, asettings.hardness_mpa / 1e3 * 1.1))
        ax.set_xlabel("hardness Pd (GPa)")
        ax.set_ylabel("P(max > Pd), one area")
        ax.set_title(case_label(settings, ih, il) + suffix, fontsize=9)
        ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


#: Legend labels of the samples in the reliability figure.
_RELIABILITY_LABELS = {"spot": "contact spots", "asperity": "asperities", "grid": "grid (paper)"}


def damage_reliability_figure(settings, analysis: dict, suffix: str = ""):
    """Predicted against observed damage probability on held-out surfaces, per case, for
    both samples and the area factors 1, 2 and 4."""
    cases = list(analysis.items())
    fig, axes = pyplot().subplots(1, len(cases), figsize=(4.2 * len(cases), 3.6), squeeze=False)
    for ax, ((ih, il), r) in zip(axes[0], cases, strict=True):
        for sample, marker in (("spot", "o"), ("asperity", "^"), ("grid", "s")):
            if sample not in r:
                continue
            c = r[sample].validation.calibration
            if c is None or len(c) == 0:
                continue
            for k, color in ((1, "C0"), (2, "C1"), (4, "C2")):
                ck = c[c["area_factor"] == k]
                if not len(ck):
                    continue
                ax.errorbar(ck["predicted"], ck["observed"],
                            yerr=[np.maximum(ck["observed"] - ck["observed_low"], 0.0),
                                  np.maximum(ck["observed_high"] - ck["observed"], 0.0)],
                            fmt=marker, ms=4, color=color, mfc=color if sample == "spot" else "none",
                            label=f"{_RELIABILITY_LABELS[sample]}, k = {k}")
        ax.plot([0, 1], [0, 1], "k:", lw=1)
        ax.set_xlabel("predicted P(max > Pd)")
        ax.set_ylabel("observed fraction (Wilson 95 %)")
        ax.set_title(case_label(settings, ih, il) + suffix, fontsize=9)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=6)
    fig.tight_layout()
    return fig


def surfaces_figure(settings, examples: list):
    """The heights (µm) of the example surfaces, ``examples`` a list of ((ih, il), result)."""
    fig, axes = pyplot().subplots(1, len(examples), figsize=(4.6 * len(examples), 3.6),
                                  squeeze=False, layout="constrained")
    ext = _extent(settings)
    for ax, ((ih, il), r) in zip(axes[0], examples, strict=True):
        im = ax.imshow(display_map(np.asarray(r["heights"], dtype=float), "mean").T * 1e6,
                       origin="lower", extent=ext, cmap="viridis")
        ax.set_title(case_label(settings, ih, il))
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        fig.colorbar(im, ax=ax, label="height (µm)")
    return fig


def pressure_maps_figure(settings, examples: list):
    """The contact pressure of the example surfaces (log scale) and a zoom around the highest
    pressure, ``examples`` a list of ((ih, il), result)."""
    fig, axes = pyplot().subplots(2, len(examples), figsize=(4.6 * len(examples), 7.4),
                                  squeeze=False, layout="constrained")
    ext = _extent(settings)
    mm = _spacing_mm(settings)
    for col, ((ih, il), r) in enumerate(examples):
        p = r["pressure"].astype(float) / 1e6
        norm = _log_norm(p[p > 0])
        ax = axes[0, col]
        im = ax.imshow(np.ma.masked_less_equal(display_map(p, "max"), 0).T, origin="lower", extent=ext,
                       cmap="magma", norm=norm, interpolation="nearest")
        ax.set_facecolor("#dde")
        ax.set_title(f"{case_label(settings, ih, il)}: contact pressure")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        fig.colorbar(im, ax=ax, label="pressure (MPa)")
        sl = _zoom(p, settings.grid)
        _zoom_panel(fig, axes[1, col], np.ma.masked_less_equal(p, 0)[sl], sl, mm, norm,
                    "zoom on the highest pressure")
    return fig


def histograms_figure(settings, analysis: dict):
    """Pooled pressures and the fitted GLD density per case: grid-point pressures (top row)
    and contact-spot peaks (bottom row)."""
    from ..plot import plot_histogram

    nc = len(analysis)
    fig, axes = pyplot().subplots(2, nc, figsize=(4.2 * nc, 6.8), squeeze=False, layout="constrained")
    for col, ((ih, il), r) in enumerate(analysis.items()):
        for irow, sample in enumerate(SAMPLE_ORDER):
            sa = r[sample]
            ax = axes[irow, col]
            if sa.data.size:
                plot_histogram(sa.data, *([sa.boot.fit.dist] if sa.ok else []),
                               names=[f"GLD {sa.param.upper()}"] if sa.ok else None, ax=ax)
                ax.legend(fontsize=8)
            ax.set_title(f"{case_label(settings, ih, il)}\n{SAMPLE_LABELS[sample]}", fontsize=9)
            ax.set_xlabel("pressure (MPa)")
    return fig


def lambda_figure(settings, asettings, ih: int, il: int, sa):
    """Kernel densities of the bootstrapped λ1..λ4 of one grid-point sample."""
    from ..plot import plot_lambda_densities

    fig, axes = pyplot().subplots(2, 2, figsize=(8, 6.4), layout="constrained")
    plot_lambda_densities(sa.boot.lambdas, true=sa.boot.fit.lambdas, axes=axes,
                          true_label="full-sample fit")
    fig.suptitle(f"{case_label(settings, ih, il)}: {SAMPLE_LABELS['grid']}, "
                 f"B = {len(sa.boot.lambdas)} resamples")
    return fig


def maximum_figure(settings, asettings, records: list):
    """Density of the maximal pressure over one analysed area with its interval, one panel
    per sample; ``records`` from :func:`glstat.study.report_numbers.maximum_records`."""
    fig, panels = sample_panels()
    for ax, sample in panels:
        mine = [rec for rec in records if rec["sample"] == sample]
        observed = max((rec["observed_max"] for rec in mine), default=math.nan)
        for rec in mine:
            bm, lo, hi = rec["maximum"], rec["low"], rec["high"]
            span = hi - lo
            # the axis ends a little beyond the interval and the largest observed pressure,
            # not at the far tail of the fit
            end = min(bm.mixture.isf(1e-4), max(hi + 0.5 * span, 1.2 * rec["observed_max"]))
            xs = np.linspace(max(bm.mixture.ppf(1e-4), lo - span), end, 160)
            ax.plot(xs, bm.mixture.pdf(xs), label=case_label(settings, rec["ih"], rec["il"]))
            ax.axvspan(lo, hi, alpha=0.08)
        if math.isfinite(observed):
            ax.axvline(observed, color="0.4", ls="--", lw=1,
                       label=f"largest observed {observed:.4g} MPa (beyond: extrapolated)")
        ax.axvline(asettings.hardness_mpa, color="k", ls=":",
                   label=f"hardness {asettings.hardness_mpa:g} MPa")
        ax.set_xlabel("maximal pressure (MPa)")
        ax.set_ylabel("density (1/MPa)")
        ax.set_title(SAMPLE_LABELS[sample])
        ax.legend(fontsize=8)
    return fig


def validation_figure(settings, asettings, analysis: dict, sample: str):
    """Observed maximal pressure of every held-out surface against its predicted interval,
    one panel per case (the reason in words where the sample was not checked)."""
    lvl = round(100 * asettings.confidence_level)
    nc = len(analysis)
    fig, axes = pyplot().subplots(1, nc, figsize=(4.2 * nc, 3.6), squeeze=False, layout="constrained")
    for col, ((ih, il), r) in enumerate(analysis.items()):
        v = r[sample].validation
        ax = axes[0, col]
        ax.set_title(f"{case_label(settings, ih, il)}", fontsize=9)
        if v.table is None:
            ax.text(0.5, 0.5, textwrap.fill((v.error or r[sample].note or "no fit")[:200], 40),
                    ha="center", va="center", fontsize=7, transform=ax.transAxes)
            continue
        t = v.table
        cov = t["covered"].to_numpy()
        # the interval as a segment: the point prediction need not lie inside a bootstrap
        # interval of the maximum (e.g. when the interval is of the mixture's quantiles)
        ax.vlines(t["surface"], t["low"], t["high"], color="0.6", lw=1,
                  label=f"predicted {lvl} % interval")
        ax.plot(t["surface"][cov], t["observed"][cov], "o", ms=3, color="tab:blue",
                label="observed, inside")
        ax.plot(t["surface"][~cov], t["observed"][~cov], "x", ms=4, color="tab:red",
                label="observed, outside")
        ax.set_xlabel("surface")
        ax.set_ylabel("maximal pressure (MPa)")
        ax.text(0.02, 0.97, f"coverage {100 * v.coverage:.0f} % [{100 * v.coverage_interval[0]:.0f}, "
                f"{100 * v.coverage_interval[1]:.0f}]", transform=ax.transAxes, va="top", fontsize=8)
        ax.legend(fontsize=7, loc="lower right")
    fig.suptitle(SAMPLE_LABELS[sample])
    return fig


def differences_figure(settings, analysis: dict, sample: str):
    """Histogram of (predicted − observed) maximal pressure of the held-out surfaces, one
    panel per case (empty where the sample was not checked)."""
    nc = len(analysis)
    fig, axes = pyplot().subplots(1, nc, figsize=(4.2 * nc, 3.2), squeeze=False, layout="constrained")
    for col, ((ih, il), r) in enumerate(analysis.items()):
        v = r[sample].validation
        if v.table is None:
            continue
        ax = axes[0, col]
        ax.hist((v.table["predicted"] - v.table["observed"]).to_numpy(), bins="auto", color="tab:gray")
        ax.axvline(0, color="k", ls=":")
        ax.set_xlabel("predicted − observed (MPa)")
        ax.set_title(f"{case_label(settings, ih, il)}: t-test p = {fmt_cell(v.t_pvalue)}", fontsize=9)
    fig.suptitle(SAMPLE_LABELS[sample])
    return fig


def integrity_figure(settings, asettings, analysis: dict):
    """Integrity probability against the area factor with its band, one panel per sample."""
    fig, panels = sample_panels()
    for ax, sample in panels:
        for ih, il, sa in fitted(analysis, sample):
            it = sa.integrity
            line, = ax.semilogx(it.area_factor, it.estimate, label=case_label(settings, ih, il))
            ax.fill_between(it.area_factor, it.low, it.high, color=line.get_color(), alpha=0.15)
        ax.set_xlabel("area factor k (area / analysed area)")
        ax.set_ylabel(f"integrity probability at {asettings.hardness_mpa:g} MPa")
        ax.set_ylim(-0.02, 1.02)
        ax.set_title(SAMPLE_LABELS[sample])
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
    return fig


def _bem_histogram_panel(ax, comparison, hardness: float, title: str) -> None:
    """Contact-spot peak pressures of both models of one comparison on log axes, with their
    GLDs."""
    from .both_models import MODEL_LABELS, MODELS

    colours = {"asperity": "tab:blue", "bem": "tab:red"}
    data = [comparison.fits[m].data for m in MODELS]
    allx = np.concatenate(data)
    if allx.size == 0:
        ax.set_title(title)
        return
    lo, hi = float(allx.min()), float(allx.max())
    bins = np.geomspace(lo, hi * (1 + 1e-9), 40) if hi > lo > 0 else 10
    heights = []
    for m, x in zip(MODELS, data, strict=True):
        if x.size:
            hv, _, _ = ax.hist(x, bins=bins, density=True, histtype="step", lw=1.5, color=colours[m],
                               label=f"{MODEL_LABELS[m]} (n = {x.size})")
            heights.append(np.asarray(hv)[np.asarray(hv) > 0])
        f = comparison.fits[m]
        if f.ok:
            xs = np.geomspace(lo, hi, 400) if hi > lo > 0 else np.linspace(lo, hi + 1, 400)
            with np.errstate(all="ignore"):
                ys = np.asarray(f.boot.fit.dist.pdf(xs), dtype=float)
            ax.plot(xs, ys, color=colours[m], ls="--", lw=1, label=f"GLD {f.param.upper()} {f.method}")
    ax.axvline(hardness, color="k", ls=":", label=f"hardness {hardness:g} MPa")
    ax.set_xscale("log")
    ax.set_yscale("log")
    hv = np.concatenate(heights) if heights else np.empty(0)
    if hv.size:  # the GLD densities vanish at bounded supports: keep the histograms in view
        ax.set_ylim(hv.min() / 5, hv.max() * 5)
    ax.set_xlabel("contact-spot peak pressure (MPa)")
    ax.set_ylabel("density (1/MPa)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)


def bem_histograms_figure(comparisons: dict, labels: dict, hardness: float):
    """Contact-spot peak pressures of the asperity model and of the elastic BEM with their
    fitted GLD densities, one panel per case (``labels``: case -> title)."""
    nc = len(comparisons)
    fig, axes = pyplot().subplots(1, nc, figsize=(4.6 * nc, 3.8), squeeze=False, layout="constrained")
    for ax, (c, v) in zip(axes[0], comparisons.items(), strict=True):
        _bem_histogram_panel(ax, v, hardness, labels[c])
    return fig


def bem_maps_figure(settings, cases: list, maps: dict, labels: dict):
    """Surface 0 of every case: pressure of the asperity model (top) and of the elastic BEM
    (bottom) around the BEM's highest pressure, on a common log scale per case."""
    from .both_models import MODEL_LABELS, MODELS

    fig, axes = pyplot().subplots(2, len(cases), figsize=(4.6 * len(cases), 7.4), squeeze=False,
                                  layout="constrained")
    mm = _spacing_mm(settings)
    for col, c in enumerate(cases):
        mp = {m: maps[c][m] / 1e6 for m in MODELS}
        norm = _log_norm(np.concatenate([x[x > 0] for x in mp.values()]))
        sl = _zoom(mp["bem"], settings.grid)
        for row, m in enumerate(MODELS):
            _zoom_panel(fig, axes[row, col], np.ma.masked_less_equal(mp[m][sl], 0), sl, mm, norm,
                        f"{labels[c]}: {MODEL_LABELS[m]}", fontsize=9)
    return fig


def psd_like_figure(like: dict):
    """Radially averaged PSD of the measured template against the simulated surfaces."""
    import contact

    fig, ax = pyplot().subplots(figsize=(6.4, 4.2), layout="constrained")
    contact.plot_psd_comparison(like["measured"], like["simulated"], ax=ax)
    return fig


def allowable_figure(settings, asettings, curves: dict, model: str):
    """Damage probability at the hardness against the nominal pressure, one panel per area of
    ``asettings.damage_areas``, one line per case through its probes
    (:class:`glstat.study.allowable.Probe`, ``curves`` as ``(ih, area_m2) -> [Probe]``) with its
    interval band, a marker per role, and the target."""
    plt = pyplot()
    areas = asettings.damage_areas
    marks = {"campaign": "o", "bracket": "^", "bisection": "D", "verification": "*"}
    fig, axes = plt.subplots(1, len(areas), figsize=(3.4 * len(areas), 3.2), squeeze=False)
    for ia, (ax, area) in enumerate(zip(axes[0], areas, strict=True)):
        for (ih, a), probes in sorted(curves.items()):
            if abs(a / area - 1) > 1e-9:
                continue
            q = sorted((p for p in probes if p.usable), key=lambda p: p.pressure)
            if not q:
                continue
            loads = np.array([p.pressure / 1e6 for p in q])
            name = "measured" if settings.measured else f"H = {settings.hurst[ih]:g}"
            (line,) = ax.plot(loads, [p.estimate for p in q], lw=1, label=name)
            ax.fill_between(loads, [p.low for p in q], [p.high for p in q],
                            color=line.get_color(), alpha=0.2, lw=0)
            for role, m in marks.items():
                sel = [p for p in q if p.role == role]
                if sel:
                    ax.plot([p.pressure / 1e6 for p in sel], [p.estimate for p in sel], m,
                            color=line.get_color(), ms=9 if m == "*" else 5, ls="none")
        ax.axhline(asettings.target_damage, color="C3", ls="--", lw=1,
                   label=f"target {100 * asettings.target_damage:g} %")
        ax.set_title(area_words(area), fontsize=9)
        ax.set_xlabel("nominal pressure (MPa)")
        ax.set_xscale("log")
        ax.set_ylim(-0.02, 1.02)
        if ia == 0:
            ax.set_ylabel(f"P(max > {asettings.hardness_mpa:g} MPa) ({model})")
            ax.legend(fontsize=7)
    fig.tight_layout()
    return fig
