"""The whole method on measured topographies, and on surfaces simulated like one of them.

    python examples/study_measured.py [FOLDER_OF_SCANS] [--out DIR]

The same as ``glstat study --topographies FOLDER`` and ``glstat study --like FILE``, from the
Python API and at a size that runs in about a minute. Without a folder, twelve demonstration
scans are written first (X3P, 128 × 96 points on 0.25 × 0.1875 mm², Sq ≈ 0.25 µm, a tilt and
a curvature and, on all but the first, a few missing points, as an optical profilometer leaves
them).

1. Measured: every file is one surface; its form, a least-squares polynomial of degree 2, is
   removed; the campaign checks that all files share grid and spacing and records each file's
   SHA-256, so a changed file is never mixed with results of the old one.
2. Like: the first file is the template; its spectrum gives H, Rq and the truncation of the
   Weierstrass surfaces that are simulated and analysed instead, and the report sets the
   template and the simulated surfaces side by side (ISO 25178 parameters, PSDs, contact).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import contact
from glstat.study import AnalysisSettings, run_study
from glstat.study.measured import find_topographies, like_settings, measured_settings


def demo_scans(folder: Path, n: int = 12) -> None:
    """Write ``n`` rectangular self-affine scans with a tilt and a curvature (radius 50 mm along
    x) as X3P files; all but the first have 0.2 % missing points (the template of the "like"
    study must be fully measured)."""
    rng = np.random.default_rng(25178)
    for i in range(n):
        base = contact.self_affine((128, 96), (0.25e-3, 0.1875e-3), 0.75, rq=0.25e-6, rng=rng)
        x = np.arange(128)[:, None] * base.dx
        y = np.arange(96)[None, :] * base.dy
        form = 2e-2 * x - 1e-2 * y + x**2 / (2 * 50e-3)
        mask = (rng.random(base.shape) < 0.002) if i else None
        contact.Surface(base.heights + form, base.dx, base.dy, mask=mask).write(
            folder / f"scan_{i:02d}.x3p")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?", help="folder of measured topographies")
    parser.add_argument("--out", default="study-measured", help="output folder")
    args = parser.parse_args()
    folder = Path(args.folder) if args.folder else Path(args.out) / "scans"
    if not args.folder and not any(folder.glob("*.x3p")):
        folder.mkdir(parents=True, exist_ok=True)
        demo_scans(folder)  # written once: a rerun resumes on the same files
    analysis = AnalysisSettings(n_resamples=50, grid_resamples=20)

    settings = measured_settings(folder, form="poly2", pressures=(20e6,))
    (nx, ny), (lx, ly) = settings.shape, settings.size
    print(f"{settings.n_surfaces} measured files, {nx} × {ny} points on {lx * 1e3:g} mm × "
          f"{ly * 1e3:g} mm, mean Rq {settings.rq * 1e6:.3g} µm about the quadratic form")
    res = run_study(settings, analysis, Path(args.out) / "measured", workers=1,
                    progress=False, compare_bem=0)
    row = res.summary().query("sample == 'asperity'").iloc[0]
    print(f"measured: damage probability at {analysis.hardness_mpa:g} MPa on one scan "
          f"{row['damage']:.3g} [{row['damage_low']:.3g}, {row['damage_high']:.3g}], "
          f"observed on {row['observed_damage']:.0%} of {row['n_surfaces']} scans")
    print(f"report: {res.report_html}")

    template = find_topographies(folder)[0]
    like, params = like_settings(template, 12, form="poly2", pressures=(20e6,))
    print(f"like {template.name}: H = {params.fit.hurst:.3g} ± {params.fit.hurst_se:.2g} "
          f"(R² {params.fit.r2:.3f}), Rq {params.rq * 1e6:.3g} µm, {params.n_terms[0]} terms")
    res = run_study(like, analysis, Path(args.out) / "like", workers=1, progress=False,
                    compare_bem=0)
    row = res.summary().query("sample == 'asperity'").iloc[0]
    print(f"simulated like it: damage probability {row['damage']:.3g} "
          f"[{row['damage_low']:.3g}, {row['damage_high']:.3g}]")
    print(f"report: {res.report_html}")


if __name__ == "__main__":
    main()
