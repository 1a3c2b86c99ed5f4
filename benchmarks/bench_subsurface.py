"""Cost and accuracy of :func:`contact.subsurface.max_von_mises` next to :func:`contact.solve_bem`.

For each grid size, in the same run and on one core:

* a study surface (Weierstrass, 1 mm², Rq = 1.6 µm, 20 MPa, E = 210 GPa, ν = 0.3, the
  default campaign's) is solved by ``solve_bem`` (isolated patch and periodic), and the
  largest von Mises stress beneath its contact pressure is searched over the 10 depths of
  :func:`contact.subsurface.default_depths`: the first call of the process (kernel spectra
  built) and the following ones (kernel spectra from the process's cache, as for every
  surface of a study after the first);
* the Hertz check: a Hertzian pressure ``p0 sqrt(1 - r²/a²)`` with ``a`` a quarter of the
  grid (at least 40 cells), isolated. Its von Mises stress peaks at ``0.6200 p0`` at
  ``z = 0.4809 a`` for ν = 0.3 (Johnson 1985, §4.2, closed form on the axis,
  :func:`contact.reference.hertz_axis_stress`). Reported: the relative error of the peak
  found over the default depths (which includes the depth sampling), and the largest error
  of the on-axis von Mises stress at depths 0.25 a to 2 a (the numerics alone).

Times are the best of ``--repeat`` runs (wall seconds; BEM includes its kernel, taken from
its cache after the first run). Prints a markdown table.

Usage::

    python benchmarks/bench_subsurface.py [--n 384 768] [--repeat 3] [--depths 10]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np

from contact import reference, weierstrass
from contact._subsurface_kernels import clear_cache
from contact.bem import solve_bem
from contact.subsurface import default_depths, max_von_mises, subsurface_stress

LENGTH, RQ, PRESSURE, E, NU = 1e-3, 1.6e-6, 20e6, 210e9, 0.3


def best_time(fn, repeat: int):
    """Run ``fn`` ``repeat`` times; return (best wall time in s, last result)."""
    best, res = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        res = fn()
        best = min(best, time.perf_counter() - t)
    return best, res


def hertz_check(n: int, n_depths: int) -> tuple[float, float, float]:
    """Relative errors of the Hertzian von Mises peak over the default depths and of the
    on-axis von Mises stress at 0.25 a to 2 a; and the time of the search (s)."""
    dx = LENGTH / n
    a = max(n // 4, 40) * dx
    p0 = 1e9
    x = (np.arange(n) - n // 2) * dx
    r = np.hypot(x[:, None], x[None, :])
    p = p0 * np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, None))
    depths = default_depths(dx, dx, (n * dx, n * dx), n=n_depths)
    t0 = time.perf_counter()
    vm = max_von_mises(p, dx, depths=depths, nu=NU)
    elapsed = time.perf_counter() - t0
    peak = reference.hertz_axis_stress(0.48086 * a, a, p0, NU).von_mises
    peak_error = abs(vm.peak.value - peak) / peak
    z = np.array([0.25, 0.4809, 1.0, 2.0]) * a
    axis = subsurface_stress(p, dx, depths=z, nu=NU).von_mises[:, n // 2, n // 2]
    exact = reference.hertz_axis_stress(z, a, p0, NU).von_mises
    return peak_error, float(np.max(np.abs(axis - exact)) / p0), elapsed


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, nargs="+", default=[384, 768], help="grid points per side")
    parser.add_argument("--repeat", type=int, default=3, help="runs per timing (best kept)")
    parser.add_argument("--depths", type=int, default=10, help="number of depths")
    args = parser.parse_args(argv)

    rows = []
    for n in args.n:
        surface = weierstrass((n, n), LENGTH, 0.5, rq=RQ, rng=1)
        depths = default_depths(surface.dx, surface.dy, surface.size, n=args.depths)
        peak_error, axis_error, _ = hertz_check(n, args.depths)
        for periodic in (False, True):
            t_bem, res = best_time(
                lambda s=surface, periodic=periodic: solve_bem(s, PRESSURE, E, NU, periodic=periodic,
                                                               workers=1),
                args.repeat,
            )
            clear_cache()
            t0 = time.perf_counter()
            vm = res.max_von_mises(depths, NU)
            t_cold = time.perf_counter() - t0
            t_warm, vm = best_time(lambda res=res, z=depths: res.max_von_mises(z, NU), args.repeat)
            row = {
                "n": n, "bc": "periodic" if periodic else "isolated",
                "fraction": res.contact_fraction, "bem_s": t_bem, "bem_it": res.n_iterations,
                "cold_s": t_cold, "warm_s": t_warm, "ratio": t_warm / t_bem,
                "vm_MPa": vm.peak.value / 1e6, "depth_um": vm.peak.depth * 1e6,
                "peak_error": peak_error, "axis_error": axis_error,
            }
            rows.append(row)
            print(row, flush=True)

    print()
    print(f"| grid | boundary | contact fraction | solve_bem (s, it.) | max_von_mises, {args.depths} depths: "
          "first call (s) | next calls (s) | next / solve_bem | largest von Mises (MPa, depth µm) "
          "| Hertz peak error, default depths | Hertz on-axis error / p0 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['n']}² | {r['bc']} | {r['fraction']:.3g} | {r['bem_s']:.3f} ({r['bem_it']}) "
              f"| {r['cold_s']:.3f} | {r['warm_s']:.3f} | {r['ratio']:.2f} "
              f"| {r['vm_MPa']:.4g} ({r['depth_um']:.3g}) | {r['peak_error']:.1%} "
              f"| {r['axis_error']:.1e} |")


if __name__ == "__main__":
    main()
