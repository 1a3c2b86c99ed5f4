"""Cost and accuracy of the lateral-scale tools: :func:`contact.s_filter` (ISO 16610-61
Gaussian S-filter) and :func:`contact.find_spikes`, next to a peer in the same run.

* ``s_filter`` (periodic and non-periodic, first-order edge correction) against
  :func:`scipy.ndimage.gaussian_filter` with the same Gaussian (σ = α λs / √(2π), ``mode="wrap"``
  for the periodic case). Error: the transmission of a sine of wavelength λs, which the
  standard sets to 0.5 (periodic, exact; non-periodic, measured in the interior), and the
  largest deviation from a plane kept by the non-periodic filter (its edge treatment).
* ``find_spikes`` against :func:`scipy.ndimage.median_filter` over the same 5 × 5 footprint
  (the bulk of its work), on a self-affine surface with 50 planted one-pixel spikes of 20 Sq.
  Error: planted spikes missed and clean points flagged.

Prints a markdown table. Usage::

    python benchmarks/bench_scale.py [--n 1024 2048] [--repeat 3]
"""

from __future__ import annotations

import argparse
import math
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np
from scipy import ndimage

import contact

ALPHA = math.sqrt(math.log(2) / math.pi)


def best(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def filter_rows(n, repeat):
    dx = 1e-6
    lam = 16e-6
    x = np.arange(n) * dx
    k = max(1, round(n * dx / lam))  # a sine of (nearly) λs that is periodic on the grid
    wavelength = n * dx / k
    sine = contact.Surface(np.sin(2 * np.pi * x / wavelength)[:, None] * np.ones((1, n)) * 1e-7, dx)
    exact = math.exp(-math.pi * (ALPHA * lam / wavelength) ** 2)
    sigma = ALPHA * lam / math.sqrt(2 * math.pi) / dx
    rows = []
    for periodic in (True, False):
        t, out = best(lambda periodic=periodic: sine.s_filter(lam, periodic=periodic), repeat)
        core = slice(n // 4, 3 * n // 4)
        amp = np.abs(out.heights[core, n // 2]).max() / 1e-7
        mode = "wrap" if periodic else "constant"
        tp, _ = best(lambda mode=mode: ndimage.gaussian_filter(sine.heights, sigma, mode=mode), repeat)
        plane_err = math.nan
        if not periodic:
            plane = contact.Surface((x[:, None] + 0.5 * x[None, :]) * 1e-2, dx)
            plane_err = float(np.abs(plane.s_filter(lam, periodic=False).heights
                                     - plane.heights).max() / np.ptp(plane.heights))
        rows.append((f"s_filter {'periodic' if periodic else 'non-periodic'}", n, t, tp,
                     f"transmission at λs {amp:.4f} (exact {exact:.4f}); plane kept to {plane_err:.1e}"
                     if not periodic else f"transmission at λs {amp:.6f} (exact {exact:.6f})"))
    return rows


def spike_rows(n, repeat):
    s = contact.self_affine((n, n), n * 1e-6, hurst=0.8, rq=0.5e-6, rng=1)
    h = s.heights.copy()
    rng = np.random.default_rng(2)
    idx = rng.choice(n * n, 50, replace=False)
    i, j = np.unravel_index(idx, (n, n))
    h[i, j] += 20 * h.std()
    spiked = contact.Surface(h, s.dx)
    t, found = best(lambda: contact.find_spikes(spiked), repeat)
    footprint = np.ones((5, 5), bool)
    tp, _ = best(lambda: ndimage.median_filter(h, footprint=footprint, mode="nearest"), repeat)
    planted = set(zip(i.tolist(), j.tolist(), strict=True))
    hits = {tuple(v) for v in found.indices.tolist()}
    missed = len(planted - hits)
    false = len(hits - planted)
    return [("find_spikes", n, t, tp, f"{missed} of 50 planted spikes missed, {false} clean points flagged")]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, nargs="+", default=[1024, 2048])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print("| operation | grid | time (s) | peer (s) | accuracy |")
    print("|---|---|---|---|---|")
    for n in args.n:
        for name, grid, t, tp, acc in filter_rows(n, args.repeat) + spike_rows(n, args.repeat):
            print(f"| {name} | {grid}² | {t:.3f} | {tp:.3f} | {acc} |")


if __name__ == "__main__":
    main()
