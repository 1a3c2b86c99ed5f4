"""How the number of contact spots of the elastic solution depends on the grid.

    python benchmarks/bench_spot_grid.py [--grids 256 512 1024 2048] [--seeds 3]

The same Weierstrass surface of the default study scene (H = 0.5, Rq = 1.6 µm, 6 terms per
axis, γ = 1.5, 1 mm square, 20 MPa nominal, E = 210 GPa, ν = 0.3) is sampled on grids of
increasing resolution (the series is a function of position, so every grid samples one
surface) and solved with the elastic BEM (isolated patch, tolerance 1e-8). For each grid the
table gives the contact spots (8-connected regions of the contact set), the asperities in
contact of the asperity model on the same grid, the contact fraction, the mean and maximal
pressure and the solve time. Spots closer than a grid step merge on a coarse grid, and a
finer grid resolves spots too small to hold a grid point: the count is a property of the
surface and the grid together, which the study's random count inherits.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import contact


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grids", type=int, nargs="+", default=[256, 512, 1024, 2048])
    parser.add_argument("--seeds", type=int, default=3)
    args = parser.parse_args()
    E, nu, load = 210e9, 0.3, 20e6
    print("| seed | grid | spots | asperities in contact (asperity model) | contact fraction | "
          "mean pressure (MPa) | max pressure (MPa) | BEM seconds |")
    print("|---|---|---|---|---|---|---|---|")
    for seed in range(args.seeds):
        for n in args.grids:
            surf = contact.weierstrass((n, n), 1e-3, 0.5, 1.5, rq=1.6e-6, n_terms=6,
                                       rng=np.random.default_rng(seed))
            t0 = time.perf_counter()
            bem = contact.solve_bem(surf, load, E, nu, tol=1e-8, workers=1)
            seconds = time.perf_counter() - t0
            spots = contact.contact_spots(bem)
            asp = contact.solve(surf, load, E, nu, 0.2)
            print(f"| {seed} | {n}² | {spots.peak_pressure.size} | {len(asp.asperities)} | "
                  f"{bem.contact_fraction:.3e} | {bem.mean_pressure / 1e6:.0f} | "
                  f"{bem.max_pressure / 1e6:.0f} | {seconds:.1f} |", flush=True)


if __name__ == "__main__":
    main()
