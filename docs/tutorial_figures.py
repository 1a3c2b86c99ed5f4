"""Draw the figures of docs/tutorial.md into docs/img/ (tutorial_*.png).

Run: ``python docs/tutorial_figures.py`` (about half a minute). The campaign, the fit and the
bootstrap are the tutorial's code blocks, with the same settings and seeds, so the figures show
the numbers printed on the page.
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import contact
import glstat
import glstat.plot

OUT = Path(__file__).resolve().parent / "img"
HARDNESS = 2050.0  # MPa
DPI = 80


def campaign():
    """The tutorial's campaign: 30 surfaces, asperity model at 20 MPa, peaks in MPa."""
    peaks, surface_of, first = [], [], None
    for i in range(30):
        surface = contact.weierstrass((512, 512), 1e-3, hurst=0.5, rq=1.6e-6, rng=i, n_terms=6)
        result = contact.solve(surface, 20e6, E=210e9, nu=0.3)
        p = 1.5 * result.asperities["p_m"].to_numpy() / 1e6
        peaks.append(p)
        surface_of.append(np.full(p.size, i))
        if first is None:
            first = (surface, result)
    return peaks, surface_of, first


def save(fig, name):
    path = OUT / name
    fig.savefig(path, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {path.relative_to(OUT.parent.parent)} ({path.stat().st_size // 1024} KB)")


def main() -> int:
    t0 = time.perf_counter()
    OUT.mkdir(exist_ok=True)
    peaks, surface_of, (surface, result) = campaign()
    pooled = np.concatenate(peaks)
    groups = np.concatenate(surface_of)
    counts = np.array([p.size for p in peaks])
    maxima = np.array([p.max() for p in peaks])

    # 1. the surface
    fig, ax = plt.subplots(figsize=(5.2, 4.2))
    surface.plot(ax=ax, unit="µm")
    ax.set_title("Weierstrass surface, H = 0.5, Rq = 1.6 µm, 1 mm²")
    save(fig, "tutorial_surface.png")

    # 2. its contact: pressure map with the asperities in contact circled
    fig, ax = plt.subplots(figsize=(5.2, 4.2))
    result.plot(ax=ax, unit="GPa", dx=1e-3 / 512)
    ast = result.asperities
    ax.set_title(f"contact at 20 MPa: {len(ast)} asperities in contact")
    save(fig, "tutorial_contact.png")

    # 3. the peaks and their number per surface
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.4))
    a1.hist(pooled, bins=30, color="0.6", edgecolor="k", linewidth=0.4)
    a1.set_xlabel("peak pressure 1.5 p_m of an asperity (MPa)")
    a1.set_ylabel("asperities")
    a1.set_title(f"{pooled.size} peaks on {counts.size} surfaces")
    vals, freq = np.unique(counts, return_counts=True)
    a2.bar(vals, freq, color="0.6", edgecolor="k", linewidth=0.4)
    a2.set_xlabel("asperities in contact per surface, N")
    a2.set_ylabel("surfaces")
    a2.set_title(f"mean N = {counts.mean():.2f}")
    fig.tight_layout()
    save(fig, "tutorial_peaks.png")

    # 4. the fit
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", glstat.FitWarning)
        fit = glstat.fit(pooled, param="fkml", method="lmoments")
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    glstat.plot.plot_histogram(pooled, fit, names=["FKML, L-moments"], ax=ax)
    ax.set_xlabel("peak pressure (MPa)")
    ax.set_title("per-asperity peaks and the fitted GLD")
    save(fig, "tutorial_fit.png")

    # 5. bootstrap by whole surfaces: the lambdas
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", glstat.BootstrapWarning)
        boot = glstat.bootstrap(pooled, groups=groups, method="lmoments", param="fkml",
                                n_resamples=1000, rng=2)
    lambdas = boot.to_frame()[["lambda1", "lambda2", "lambda3", "lambda4"]].to_numpy()
    fig = glstat.plot.plot_lambda_densities(lambdas)
    fig.set_size_inches(8, 5.4)
    fig.suptitle("bootstrap by whole surfaces: λ1..λ4 of the resample fits")
    fig.tight_layout()
    save(fig, "tutorial_bootstrap.png")

    # 6. the maximum on one area against the observed maxima
    mx = boot.maximum()
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    glstat.plot.plot_maximum_density(mx.mixture, ax=ax)
    ax.hist(maxima, bins=10, density=True, color="0.8", edgecolor="k", linewidth=0.4,
            label="observed maxima (30 surfaces)", zorder=0)
    ax.axvline(HARDNESS, color="C3", linestyle="--", label="hardness 2050 MPa")
    ax.set_xlim(1000, 8000)
    ax.set_xlabel("maximal pressure on 1 mm² (MPa)")
    ax.legend(fontsize=8)
    save(fig, "tutorial_maximum.png")

    # 7. damage probability against the hardness, with its interval
    levels = np.linspace(1500, 3500, 41)
    rows = [boot.damage_probability(x).to_frame().iloc[0] for x in levels]
    frame = {c: np.array([r[c] for r in rows]) for c in ("estimate", "low", "high")}
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    ax.fill_between(levels, frame["low"], frame["high"], color="C0", alpha=0.25, label="90 % interval")
    ax.plot(levels, frame["estimate"], color="C0", label="estimate")
    observed = [(maxima > x).mean() for x in levels]
    ax.step(levels, observed, where="post", color="k", linewidth=0.8, label="observed fraction")
    ax.axvline(HARDNESS, color="C3", linestyle="--", label="hardness 2050 MPa")
    ax.set_xlabel("hardness Pd (MPa)")
    ax.set_ylabel("P(max > Pd) on 1 mm²")
    ax.legend(fontsize=8)
    save(fig, "tutorial_damage.png")

    # 8. area scaling: an area k mm² holds k independent 1 mm² areas
    k = np.geomspace(1, 100, 30)
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    for j, level in enumerate((HARDNESS, 3000.0, 4000.0)):
        frame = boot.damage_probability(level, area_factor=k).to_frame()
        ax.fill_between(k, frame["low"], frame["high"], color=f"C{j}", alpha=0.2)
        ax.plot(k, frame["estimate"], color=f"C{j}", label=f"Pd = {level:.0f} MPa")
    ax.set_xscale("log")
    ax.set_xlabel("area (mm²)")
    ax.set_ylabel("P(max > Pd), 90 % interval")
    ax.legend(fontsize=8)
    save(fig, "tutorial_area.png")

    print(f"done in {time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
