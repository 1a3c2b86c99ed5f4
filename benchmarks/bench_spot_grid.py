"""How the contact spots of the elastic solution depend on the grid and the BEM tolerance.

    python benchmarks/bench_spot_grid.py [--grids 256 512 1024 2048] [--seeds 3] [--tols 1e-8]
                                         [--guard 0.125]

The same Weierstrass surface of the default study scene (H = 0.5, Rq = 1.6 µm, 6 terms per
axis, γ = 1.5, 1 mm square, 20 MPa nominal, E = 210 GPa, ν = 0.3) is sampled on grids of
increasing resolution (the series is a function of position, so every grid samples one
surface) and solved with the elastic BEM (isolated patch). For each grid and tolerance the
table gives the contact spots (8-connected regions of the contact set), the asperities in
contact of the asperity model on the same grid, the contact fraction, the mean and maximal
pressure, the largest peak of the spots inside the patch (spots touching its border carry the
punch-edge singularity of the isolated patch and are left out, as in the study) with its
relative difference from the finest grid and tightest tolerance of the same seed, and the
solve time. With ``--guard F`` each surface is solved with a guard band of F times the grid
on every side (``contact.weierstrass(pad=...)``, the study's ``--bem-guard``) and a spot
belongs to the analysed 1 mm² when its peak lies in it. Spots closer than a grid step merge
on a coarse grid, and a finer grid resolves
spots too small to hold a grid point: the count is a property of the surface and the grid
together, which the study's random count inherits.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import contact


def _interior_peak(res, pad: int = 0) -> tuple[float, int]:
    """(largest peak of the spots not touching the border and peaking outside the guard band
    of ``pad`` points, in Pa; number of such spots)."""
    spots = contact.contact_spots(res)
    n0, n1 = res.pressure.shape
    i, j = spots.peak_index[:, 0], spots.peak_index[:, 1]
    inside = (i >= pad) & (i < n0 - pad) & (j >= pad) & (j < n1 - pad) & ~spots.touches_border
    inner = spots.peak_pressure[inside]
    return (float(inner.max()) if inner.size else float("nan")), int(inner.size)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grids", type=int, nargs="+", default=[256, 512, 1024, 2048])
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--tols", type=float, nargs="+", default=[1e-8])
    parser.add_argument("--hurst", type=float, default=0.5)
    parser.add_argument("--guard", type=float, default=0.0,
                        help="guard band on every side, as a fraction of the grid")
    args = parser.parse_args()
    E, nu, load = 210e9, 0.3, 20e6
    print("| seed | grid | tol | spots (inside) | asperities in contact (asperity model) | "
          "contact fraction | mean pressure (MPa) | max pressure (MPa) | largest inside peak (MPa) "
          "| vs finest | BEM seconds |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for seed in range(args.seeds):
        rows = []
        for n in args.grids:
            pad = round(args.guard * n)
            surf = contact.weierstrass((n, n), 1e-3, args.hurst, 1.5, rq=1.6e-6, n_terms=6,
                                       rng=np.random.default_rng(seed), pad=pad)
            asp = contact.solve(surf, load, E, nu, 0.2)
            for tol in args.tols:
                t0 = time.perf_counter()
                bem = contact.solve_bem(surf, load, E, nu, tol=tol, workers=1)
                seconds = time.perf_counter() - t0
                spots = contact.contact_spots(bem)
                peak, inside = _interior_peak(bem, pad)
                rows.append((n, tol, spots.n_spots, inside, len(asp.asperities), bem, peak, seconds))
        ref = min(rows, key=lambda r: (-r[0], r[1]))[6]
        for n, tol, n_spots, inside, n_asp, bem, peak, seconds in rows:
            print(f"| {seed} | {n}² | {tol:.0e} | {n_spots} ({inside}) | {n_asp} | "
                  f"{bem.contact_fraction:.3e} | {bem.mean_pressure / 1e6:.0f} | "
                  f"{bem.max_pressure / 1e6:.0f} | {peak / 1e6:.0f} | {peak / ref - 1:+.2%} | "
                  f"{seconds:.2f} |", flush=True)


if __name__ == "__main__":
    main()
