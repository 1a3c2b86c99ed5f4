"""Benchmarks of the contact package: time next to error.

Run ``python benchmarks/bench_contact.py [--max-n 4096] [--repeat 3]``; it prints Markdown
tables (recorded in ``docs/benchmarks.md``, section ``contact``):

1. Weierstrass surface at 1024²: the matrix-product evaluation against the direct double
   sum of docs/method.md §2 in the same run (time and maximal relative difference).
2. Generation, summit detection and load-controlled solve against grid size at the paper's
   settings (1 mm², Rq = 50 µm, H = 0.5, 20 MPa, E = 210 GPa, nu = 0.3), with the force
   balance error.
3. Convergence with grid resolution: one band-limited surface (fixed number of Weierstrass
   terms) sampled on finer and finer grids; mean and maximal contact pressure and contact
   fraction, with their relative difference to the finest grid.
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np

import contact

E, NU, P0, RQ, L = 210e9, 0.3, 20e6, 50e-6, 1e-3


def best_time(fn, repeat: int):
    """Smallest wall time of ``repeat`` calls (s) and the last result."""
    best, out = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def weierstrass_vs_direct(repeat: int) -> None:
    kw = dict(shape=(1024, 1024), length=L, hurst=0.5, rq=RQ, rng=1)
    t_fast, fast = best_time(lambda: contact.weierstrass(**kw), max(repeat, 5))
    t_slow, slow = best_time(lambda: contact.weierstrass(**kw, method="direct"), 1)
    err = np.abs(fast.heights - slow.heights).max() / np.abs(slow.heights).max()
    print("| method | time (s) | max relative difference |")
    print("|---|---|---|")
    print(f"| matrix products | {t_fast:.4f} | {err:.1e} |")
    print(f"| direct double sum | {t_slow:.2f} | (reference) |")
    print()


def scaling(sizes, repeat: int, hurst: float = 0.5) -> None:
    print(
        "| grid | generate (s) | summits (s) | n summits | solve (s) | force evals | "
        "force error | 1 − α | mean p (GPa) | max p (GPa) |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n in sizes:
        reps = 1 if n >= 4096 else repeat
        t_gen, s = best_time(
            lambda n=n: contact.weierstrass((n, n), L, hurst, rq=RQ, rng=2019), reps
        )
        t_sum, sm = best_time(lambda s=s: contact.summits(s), reps)
        t_sol, r = best_time(lambda s=s: contact.solve(s, P0, E, NU), reps)
        print(
            f"| {n}² | {t_gen:.3f} | {t_sum:.3f} | {len(sm)} | {t_sol:.3f} | "
            f"{r.info['n_evaluations']} | {r.force_error:.1e} | {r.contact_fraction:.2e} | "
            f"{r.mean_pressure / 1e9:.1f} | {r.max_pressure / 1e9:.1f} |"
        )
    print()


def convergence(sizes, repeat: int, hurst: float, n_terms: int) -> None:
    finest = max(sizes)
    # One scale factor for every grid: Rq = 50 µm on the finest grid.
    ref = contact.weierstrass((finest, finest), L, hurst, rng=7, n_terms=n_terms)
    scale = RQ / ref.heights.std()
    rows = []
    for n in sizes:
        raw = contact.weierstrass((n, n), L, hurst, rng=7, n_terms=n_terms)
        s = contact.Surface(raw.heights * scale, raw.dx)
        reps = 1 if n >= 4096 else repeat
        t, r = best_time(lambda s=s: contact.solve(s, P0, E, NU), reps)
        rows.append((n, t, r.mean_pressure, r.max_pressure, r.contact_fraction,
                     len(r.asperities)))
    _, _, pm_ref, px_ref, cf_ref, _ = rows[-1]
    print(
        f"H = {hurst}, {n_terms} terms per axis (shortest wavelength "
        f"{L / 1.5 ** (n_terms - 1) * 1e6:.1f} µm), Rq = 50 µm, 20 MPa:"
    )
    print()
    print(
        "| grid | dx (µm) | solve (s) | asperities | mean p (GPa) | error | max p (GPa) | "
        "error | 1 − α | error |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n, t, pm, px, cf, na in rows:
        print(
            f"| {n}² | {L / n * 1e6:.3f} | {t:.3f} | {na} | {pm / 1e9:.3f} | "
            f"{pm / pm_ref - 1:+.1e} | {px / 1e9:.3f} | {px / px_ref - 1:+.1e} | "
            f"{cf:.3e} | {cf / cf_ref - 1:+.1e} |"
        )
    print()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-n", type=int, default=4096, help="largest grid side")
    parser.add_argument("--repeat", type=int, default=3, help="timing repeats (best of)")
    parser.add_argument("--skip-direct", action="store_true", help="skip the direct sum")
    args = parser.parse_args()
    sizes = [n for n in (256, 512, 1024, 2048, 4096) if n <= args.max_n]
    print(f"Python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}")
    print()
    # Compile (or load from cache) every kernel before timing.
    warm = contact.weierstrass((32, 32), L, 0.5, rq=RQ, rng=0)
    contact.solve(warm, P0, E, NU)
    if not args.skip_direct:
        weierstrass_vs_direct(args.repeat)
    scaling(sizes, args.repeat)
    for hurst in (1.0, 0.5):
        convergence(sizes, args.repeat, hurst, n_terms=12)


if __name__ == "__main__":
    main()
