"""Benchmark of ``solve_bem(..., hardness=H)`` (elastic-perfectly-plastic surface) against tamaas.

The standard rough-contact problem of ``bench_bem_standard.py`` (periodic self-affine surface,
Hurst exponent 0.8, rms slope 1, 1 mm x 1 mm, E = 210 GPa, nu = 0.3, nominal pressure
``0.01 E*``, tolerance 1e-8) with the pressure capped at a hardness ``H``, for
``H / E* = 0.3`` and ``0.1`` (a third and a tenth of the elastic solution's peak is far
exceeded: 5 % to 15 % of the grid is plastic). For each grid size the script times

* ``solve_bem(periodic=True, hardness=H)`` (the whole call, kernel set-up included);
* tamaas's ``KatoSaturated`` (its ``solve`` only), the same periodic spectral half-space
  kernel with the pressure bounded by ``pmax = H``. tamaas is given the problem in reduced
  units (lengths over the side of the surface, pressures over E): the contact problem is
  invariant under that scaling, and its saturated solver stalls at the uniform start with
  SI inputs. Its tractions are scaled back to pascals.

and compares the two pressure fields: ``max|p - p_tamaas| / H`` and the relative L1
difference ``sum|p - p_tamaas| / sum p_tamaas``, and the plastic area fractions (ours: the
points at ``H``; tamaas: the points within 1e-9 H of it). Everything runs on one core
(``OMP_NUM_THREADS=1``, ``workers=1``); times are the best of ``--repeat`` runs for
solve_bem and of ``--tamaas-repeat`` runs for tamaas (which needs tens of seconds from 256²
on), tamaas only on the grids of ``--tamaas-sizes``. tamaas is an optional benchmark
dependency (``pip install tamaas``); without it only solve_bem is timed. The table is
printed and written to ``benchmarks/results/bem_plastic.csv``.

Usage::

    python benchmarks/bench_bem_plastic.py [--n 256 512 1024] [--ratios 0.3 0.1] [--repeat 3]
        [--tamaas-repeat 1] [--tamaas-sizes 256 512]
"""

from __future__ import annotations

import argparse
import os
import sys
import time

os.environ["OMP_NUM_THREADS"] = "1"

import numpy as np
import pandas as pd

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_bem_standard import E_STAR, LENGTH, NU, PRESSURE, TOL, E, standard_surface

from contact import Surface
from contact.bem import solve_bem

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results", "bem_plastic.csv")


def run_bem(s: Surface, hardness: float):
    t = time.perf_counter()
    res = solve_bem(s, PRESSURE, E, NU, periodic=True, tol=TOL, workers=1, hardness=hardness,
                    max_iter=5000)
    return time.perf_counter() - t, res


def run_tamaas(s: Surface, hardness: float):
    """tamaas KatoSaturated in reduced units; returns (solve time in s, pressure in Pa)."""
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.error)
    nx, ny = s.shape
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [nx, ny])
    model.E = 1.0
    model.nu = NU
    solver = tm.KatoSaturated(model, np.ascontiguousarray(s.heights / LENGTH), TOL, hardness / E)
    solver.max_iter = 5000
    t = time.perf_counter()
    solver.solve(PRESSURE / E)
    wall = time.perf_counter() - t
    return wall, np.array(model.traction, copy=True) * E


def have_tamaas() -> bool:
    try:
        import tamaas  # noqa: F401
    except ImportError:
        print("tamaas is not installed: timing solve_bem only")
        return False
    return True


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, nargs="+", default=[256, 512, 1024], help="grid sizes")
    parser.add_argument("--ratios", type=float, nargs="+", default=[0.3, 0.1],
                        help="hardness over E*")
    parser.add_argument("--repeat", type=int, default=3, help="solve_bem runs per timing")
    parser.add_argument("--tamaas-repeat", type=int, default=1, help="tamaas runs per timing")
    parser.add_argument("--tamaas-sizes", type=int, nargs="*", default=[256, 512],
                        help="grids on which tamaas runs")
    parser.add_argument("--out", default=RESULTS, help="CSV file of the table")
    args = parser.parse_args(argv)
    tamaas = have_tamaas()
    solve_bem(standard_surface(32), PRESSURE, E, NU, periodic=True, hardness=0.1 * E_STAR)
    rows = []
    for n in args.n:
        s = standard_surface(n)
        for ratio in args.ratios:
            hardness = ratio * E_STAR
            t_bem, t_tm, p_tm = [], [], None
            for _ in range(args.repeat):
                wall, res = run_bem(s, hardness)
                t_bem.append(wall)
            with_tamaas = tamaas and n in args.tamaas_sizes
            for _ in range(args.tamaas_repeat if with_tamaas else 0):
                wall, p_tm = run_tamaas(s, hardness)
                t_tm.append(wall)
            row = {
                "n": n, "H_over_Estar": ratio, "bem_s": min(t_bem),
                "bem_iterations": res.n_iterations, "bem_convolutions": res.info["n_convolutions"],
                "converged": res.converged, "contact_fraction": res.contact_fraction,
                "plastic_fraction": res.plastic_area_fraction,
            }
            if with_tamaas:
                d = np.abs(res.pressure - p_tm)
                row.update(
                    tamaas_s=min(t_tm),
                    speed_ratio=min(t_tm) / min(t_bem),
                    max_diff_over_H=float(d.max() / hardness),
                    l1_diff=float(d.sum() / p_tm.sum()),
                    tamaas_plastic_fraction=float(np.mean(p_tm >= hardness * (1 - 1e-9))),
                )
            rows.append(row)
            print(row, flush=True)
    table = pd.DataFrame(rows)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    table.to_csv(args.out, index=False, float_format="%.4g")
    print(f"written to {args.out}")
    print()
    head = "| grid | H/E* | solve_bem (s, it.) | plastic fraction |"
    sep = "|---|---|---|---|"
    if tamaas:
        head += (" tamaas KatoSaturated (s) | speed ratio | max abs diff / H | rel. L1 diff "
                 "| plastic fraction tamaas |")
        sep += "---|---|---|---|---|"
    print(head)
    print(sep)
    for r in rows:
        line = (f"| {r['n']}² | {r['H_over_Estar']:g} | {r['bem_s']:.3f} ({r['bem_iterations']}) "
                f"| {r['plastic_fraction']:.4f} |")
        if tamaas and "tamaas_s" in r:
            line += (f" {r['tamaas_s']:.2f} | {r['speed_ratio']:.1f} | {r['max_diff_over_H']:.1e} "
                     f"| {r['l1_diff']:.1e} | {r['tamaas_plastic_fraction']:.4f} |")
        elif tamaas:
            line += " – | – | – | – | – |"
        print(line)


if __name__ == "__main__":
    main()
