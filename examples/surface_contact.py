"""Fractal surfaces pressed by a rigid flat: the contact-pressure samples for glstat.

Generates one 2-D Weierstrass surface per Hurst exponent at the scene of the study
(``glstat study``): 1 mm², 1024 x 1024 points, 6 terms per axis with gamma = 1.5 and
Rq = 1.6 µm, the roughness at which the asperity model gives the mean contact pressures of
Bigerelle et al. (2019), 1.1-1.7 GPa (docs/method.md §10; the 50 µm the paper prints gives
slopes 30 times larger and pressures of 19-32 GPa: ``--rq 50``). It presses a rigid plane
onto each surface until it carries 20 MPa (E = 210 GPa, nu = 0.3, c = 0.2) and prints the
roughness, the force balance and the contact-pressure statistics. With ``--plot FILE`` it
also saves the height and pressure maps.

    python examples/surface_contact.py [--n 1024] [--rq 1.6] [--plot maps.png]
"""

from __future__ import annotations

import argparse

import pandas as pd

import contact


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1024, help="grid points per side")
    parser.add_argument("--rq", type=float, default=1.6, help="RMS roughness in µm")
    parser.add_argument("--plot", help="save height and pressure maps to this image file")
    args = parser.parse_args()

    rows, results = {}, {}
    for hurst in (1.0, 0.5, 0.0):
        surface = contact.weierstrass((args.n, args.n), 1e-3, hurst, gamma=1.5, rq=args.rq * 1e-6,
                                      rng=2019, n_terms=6)
        result = contact.solve(surface, nominal_pressure=20e6, E=210e9, nu=0.3)
        summary = result.summary()
        rough = surface.roughness()
        rows[f"H = {hurst}"] = {
            "Sq (µm)": rough["Sq"] * 1e6,
            "Sdq": rough["Sdq"],
            "H estimated": rough["hurst"],
            "summits": rough["Spd"] * surface.area,
            "asperities in contact": summary["n_asperities"],
            "1 - alpha": summary["contact_fraction"],
            "mean p (GPa)": summary["mean_pressure"] / 1e9,
            "max p (GPa)": summary["max_pressure"] / 1e9,
            "force error": summary["force_error"],
        }
        results[hurst] = (surface, result)
    with pd.option_context("display.float_format", "{:.4g}".format, "display.width", 120):
        print(pd.DataFrame(rows))
        surface, result = results[0.5]
        print("\nAsperities in contact for H = 0.5 (SI units):")
        print(result.asperities.sort_values("F", ascending=False).head(10))
    print(f"\n{result.samples.size} pressure samples for the GLD fit (H = 0.5).")

    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(2, 3, figsize=(13, 8), constrained_layout=True)
        for col, (hurst, (surface, result)) in enumerate(results.items()):
            surface.plot(ax=axes[0, col])
            axes[0, col].set_title(f"H = {hurst}")
            result.plot(ax=axes[1, col], dx=surface.dx)
        fig.savefig(args.plot, dpi=120)
        print(f"maps saved to {args.plot}")


if __name__ == "__main__":
    main()
