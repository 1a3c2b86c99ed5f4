"""Many surfaces like one measurement: fit the spectrum, simulate, compare.

    python examples/surfaces_like_measurement.py [scan.x3p] [--n 100] [--seed 1] [--plot FILE]

Without a file argument a demonstration scan is made first and written to X3P in a
temporary directory: a 256 x 256 window (0.5 mm square) of a larger self-affine surface
with H = 0.75, a roll-off at 80 µm wavelength and a slight tilt, so that it is neither
periodic nor levelled, as a measurement would be. The scan is read back, its Rq, Hurst
exponent and self-affine range are fitted from its radially averaged power spectral density,
``--n`` statistically equivalent self-affine surfaces (and a few Weierstrass surfaces) are
simulated on the same grid, and their ISO 25178 parameters are set against the measured
ones. ``--plot FILE`` saves the measured and simulated spectra.
"""

from __future__ import annotations

import argparse
import math
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

import contact

ROWS = ["Sq", "Sa", "Ssk", "Sku", "Sz", "Sdq", "Sdr", "Spd", "Spc", "hurst", "psd_hurst"]


def demo_scan(path: Path) -> None:
    """Write a tilted, non-periodic 256 x 256 self-affine scan (0.5 mm, Sq ≈ 1 µm) to X3P."""
    side = 1e-3  # the larger surface the scan is cut from, m
    rolloff = 2 * math.pi / 80e-6  # rad/m
    big = contact.self_affine((512, 512), side, 0.75, rq=1e-6, rng=25178, rolloff=rolloff)
    window = big.heights[100:356, 40:296]
    x = np.arange(256) * big.dx
    tilt = 3e-3 * x[:, None] - 1e-3 * x[None, :]
    contact.Surface(window + tilt, big.dx).write(path)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("path", nargs="?", help="an .x3p file (default: a generated scan)")
    parser.add_argument("--n", type=int, default=100, help="number of simulated surfaces")
    parser.add_argument("--seed", type=int, default=1, help="seed of the simulated surfaces")
    parser.add_argument("--plot", help="save the spectra to this image file")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(args.path) if args.path else Path(tmp) / "demo.x3p"
        if not args.path:
            demo_scan(path)
            print(f"wrote a demonstration scan to {path.name}")
        measured = contact.read(path)
    print(measured)

    fit = contact.fit_spectrum(measured)
    print(
        f"fitted spectrum: Rq = {fit.rq * 1e6:.4g} µm, H = {fit.hurst:.3f} ± {fit.hurst_se:.3f} "
        f"(D = {fit.fractal_dimension:.3f}), R² = {fit.r2:.4f} over {fit.n_bins} rings"
    )
    print(
        f"  fitted from q = {fit.q_fit_min:.4g} to {fit.q_fit_max:.4g} rad/m; "
        f"roll-off q_r = {fit.q_r:.4g} rad/m (wavelength {2 * math.pi / fit.q_r * 1e6:.3g} µm, "
        f"{'detected' if fit.rolloff_detected else 'the grid limit'}), "
        f"cut-off q_s = {fit.q_s:.4g} rad/m "
        f"({'detected' if fit.cutoff_detected else 'Nyquist'})"
    )

    start = time.perf_counter()
    simulated = contact.self_affine_like(measured, args.n, rng=args.seed)
    weierstrass = contact.weierstrass_like(measured, 10, rng=args.seed)
    print(f"simulated {len(simulated)} self-affine and {len(weierstrass)} Weierstrass "
          f"surfaces in {time.perf_counter() - start:.2f} s")

    table = contact.compare_surfaces(measured, simulated)
    table_w = contact.compare_surfaces(measured, weierstrass)
    out = table.loc[ROWS, ["measured", "simulated_mean", "simulated_std", "z"]]
    out = out.rename(columns={"simulated_mean": "self-affine mean", "simulated_std": "sd"})
    out["Weierstrass mean"] = table_w.loc[ROWS, "simulated_mean"]
    out["unit"] = table.loc[ROWS, "unit"]
    with pd.option_context("display.float_format", "{:.4g}".format):
        print(out.to_string())

    psd = contact.psd_comparison(measured, simulated)
    inside = (psd["q"] >= fit.q_fit_min) & (psd["q"] <= fit.q_fit_max)
    ratio = (psd["measured"] / psd["simulated_mean"])[inside]
    print(f"measured / simulated mean PSD over the fitted rings: "
          f"{ratio.min():.2f} to {ratio.max():.2f}")
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        ax = contact.plot_psd_comparison(measured, simulated)
        ax.figure.savefig(args.plot, dpi=120, bbox_inches="tight")
        print(f"saved {args.plot}")


if __name__ == "__main__":
    main()
