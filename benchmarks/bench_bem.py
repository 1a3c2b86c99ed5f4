"""Benchmark of :func:`contact.bem.solve_bem` against the tamaas library on identical surfaces.

The paper's problem (Bigerelle et al. 2019): surfaces of 1 mm x 1 mm with Rq = 50 µm,
a rigid flat at 20 MPa nominal pressure, E = 210 GPa, nu = 0.3. For each surface the script
times

* ``solve_bem(periodic=True)`` and tamaas's ``PolonskyKeerRey`` (both periodic, the same
  spectral half-space kernel), and compares their pressure fields;
* ``solve_bem(periodic=False)`` (isolated patch, Love coefficients, zero padding), which
  tamaas's basic 2-D model does not offer.

Everything runs on one core (``OMP_NUM_THREADS=1`` for tamaas, ``workers=1`` for
scipy.fft); times are the best of ``--repeat`` runs of the whole call (kernel set-up
included for solve_bem, ``solve`` only for tamaas). tamaas is an optional benchmark
dependency (``pip install tamaas``); without it only solve_bem is timed.

Usage::

    python benchmarks/bench_bem.py [--n 1024] [--repeat 2] [--tol 1e-8]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np

from contact import Surface, self_affine, weierstrass
from contact.bem import solve_bem

LENGTH, RQ, PRESSURE, E, NU = 1e-3, 50e-6, 20e6, 210e9, 0.3


def surfaces(n: int) -> list[tuple[str, Surface]]:
    """The benchmark surfaces: self-affine (Fourier filtering) and Weierstrass."""
    out = [
        (f"self-affine H={h}", self_affine((n, n), LENGTH, h, rq=RQ, rng=10 + i))
        for i, h in enumerate((0.0, 0.5, 1.0))
    ]
    out.append(("Weierstrass H=0.5", weierstrass((n, n), LENGTH, 0.5, rq=RQ, rng=7)))
    return out


def best_time(fn, repeat: int):
    """Run ``fn`` ``repeat`` times; return (best wall time in s, last result)."""
    best, res = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        res = fn()
        best = min(best, time.perf_counter() - t)
    return best, res


def run_tamaas(surface: Surface, tol: float):
    """Periodic Polonsky-Keer solve with tamaas; returns the pressure field (Pa)."""
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.error)
    nx, ny = surface.shape
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, list(surface.size), [nx, ny])
    model.E = E
    model.nu = NU
    solver = tm.PolonskyKeerRey(model, surface.heights, tol)
    solver.solve(PRESSURE)
    return np.array(model.traction, copy=True)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, default=1024, help="grid points per side")
    parser.add_argument("--repeat", type=int, default=2, help="runs per timing (best kept)")
    parser.add_argument("--tol", type=float, default=1e-8, help="solver tolerance")
    args = parser.parse_args(argv)
    try:
        import tamaas  # noqa: F401

        have_tamaas = True
    except ImportError:
        have_tamaas = False
        print("tamaas is not installed: timing solve_bem only")

    rows = []
    for name, s in surfaces(args.n):
        t_per, per = best_time(
            lambda s=s: solve_bem(s, PRESSURE, E, NU, periodic=True, tol=args.tol, workers=1),
            args.repeat,
        )
        t_iso, iso = best_time(
            lambda s=s: solve_bem(s, PRESSURE, E, NU, periodic=False, tol=args.tol, workers=1),
            args.repeat,
        )
        row = {
            "surface": name,
            "fraction": per.contact_fraction,
            "pmax_GPa": per.max_pressure / 1e9,
            "bem_per_s": t_per,
            "bem_per_it": per.n_iterations,
            "bem_iso_s": t_iso,
            "bem_iso_it": iso.n_iterations,
            "iso_fraction": iso.contact_fraction,
        }
        if have_tamaas:
            t_tm, p_tm = best_time(lambda s=s: run_tamaas(s, args.tol), args.repeat)
            diff = per.pressure - p_tm
            row.update(
                tamaas_s=t_tm,
                l1_diff=float(np.abs(diff).sum() / np.abs(p_tm).sum()),
                max_diff=float(np.abs(diff).max() / p_tm.max()),
                same_contact=bool(np.array_equal(per.pressure > 0, p_tm > 0)),
            )
        rows.append(row)
        print(row, flush=True)

    print()
    head = ("| surface | contact fraction | max p (GPa) | solve_bem periodic (s, it.) "
            "| solve_bem isolated (s, it.) |")
    sep = "|---|---|---|---|---|"
    if have_tamaas:
        head += " tamaas periodic (s) | rel. L1 diff. | rel. max diff. | same contact set |"
        sep += "---|---|---|---|"
    print(head)
    print(sep)
    for r in rows:
        line = (f"| {r['surface']} | {r['fraction']:.3g} | {r['pmax_GPa']:.4g} "
                f"| {r['bem_per_s']:.2f} ({r['bem_per_it']}) "
                f"| {r['bem_iso_s']:.2f} ({r['bem_iso_it']}) |")
        if have_tamaas:
            line += (f" {r['tamaas_s']:.2f} | {r['l1_diff']:.1e} | {r['max_diff']:.1e} "
                     f"| {'yes' if r['same_contact'] else 'no'} |")
        print(line)


if __name__ == "__main__":
    main()
