"""Fractal surfaces pressed by a rigid flat: the contact-pressure samples for glstat.

Generates one 2-D Weierstrass surface per Hurst exponent at the scene of the study
(``glstat study``): 1 mm², 1024 x 1024 points, 6 terms per axis with gamma = 1.5 and
Rq = 1.6 µm, the roughness at which the asperity model gives mean contact pressures at the
level of Bigerelle et al. (2019), Table 1: 1108 / 1369 / 1724 MPa for H = 1 / 0.5 / 0
(docs/method.md §10; the 50 µm the paper prints gives slopes about 31 times steeper and
pressures of 19-32 GPa: ``--rq 50``). It presses a rigid plane onto each surface until it
carries 20 MPa (E = 210 GPa, nu = 0.3, c = 0.2) and prints the roughness, the force balance
and the contact-pressure statistics, then each surface's mean contact pressure next to the
paper's and to the mean over the study's 100 surfaces per H (1209 / 1504 / 1797 MPa). One
surface scatters around that mean (a surface with few asperities in contact can sit well
above or below it), so the comparison with the paper is the study's means, not the single
surfaces printed here. With ``--plot FILE`` it also saves the height and pressure
maps.

    python examples/surface_contact.py [--n 1024] [--rq 1.6] [--plot maps.png]
"""

from __future__ import annotations

import argparse

import pandas as pd

import contact

#: Mean contact pressures (MPa) per H: the paper's Table 1, and the mean over the 100 surfaces
#: per H of the default ``glstat study`` (Rq = 1.6 µm, 1024², seed 2019).
PAPER_MEAN_MPA = {1.0: 1108.0, 0.5: 1369.0, 0.0: 1724.0}
STUDY_MEAN_MPA = {1.0: 1209.0, 0.5: 1504.0, 0.0: 1797.0}


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

    default_scene = args.n == 1024 and args.rq == 1.6
    print(f"\nMean contact pressure (MPa): this run (one surface per H, {args.n}², Rq = {args.rq:g} µm)"
          " against the paper's Table 1" + (" and the study's mean over 100 surfaces per H:"
                                            if default_scene else ":"))
    for hurst, (_, res) in results.items():
        line = (f"  H = {hurst}: {res.summary()['mean_pressure'] / 1e6:6.0f}   "
                f"paper {PAPER_MEAN_MPA[hurst]:.0f}")
        if default_scene:
            line += f"   study {STUDY_MEAN_MPA[hurst]:.0f}"
        print(line)
    if not default_scene:
        print("  (the study's means, 1209 / 1504 / 1797 MPa for H = 1 / 0.5 / 0, are for 1024² and"
              " Rq = 1.6 µm)")

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
