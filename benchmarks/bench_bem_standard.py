"""Benchmark of :func:`contact.bem.solve_bem` on the standard rough-contact problem, against tamaas.

The standard problem: a periodic self-affine surface (Hurst exponent 0.8, power spectrum
``q^-2(1+H)`` from the lowest wave vector to the grid's Nyquist limit, ``contact.self_affine``)
scaled to an rms slope of 1 (spectral gradient), pressed by a rigid flat at the nominal
pressure ``0.01 E*`` (E = 210 GPa, nu = 0.3, 1 mm x 1 mm), tolerance 1e-8, one core.

Sections (``--part``):

``standard``
    1024² (``--n``): the periodic problem and its isolated-patch version. solve_bem
    (accelerated, the default), solve_bem with ``accelerate=False`` (the published
    Polonsky-Keer iteration, the project's previous solver) and tamaas's
    ``PolonskyKeerRey`` are timed alternately in the same process, ``--repeat`` times each.
    tamaas solves the isolated patch the way its periodic model allows: the surface in one
    quarter of a 2n x 2n periodic grid whose other points lie far below the flat (zero
    padding), at a quarter of the nominal pressure (the same force). Pressure fields are
    compared with a tight reference: the published iteration at tol 1e-12.
``sweep``
    Error against time for tol = 1e-4 ... 1e-10 (periodic, ``--n``), solve_bem and tamaas,
    error relative to the same tight reference.
``sizes``
    2048² and 4096² (``--sizes``): time (wall and CPU) and peak memory of each solve, each in
    a fresh process (peak resident set ``VmHWM``, and its increase over the resident set
    just before the solve). tamaas at the sizes in ``--tamaas-sizes``.

Everything runs on one core: ``OMP_NUM_THREADS=1`` for tamaas, ``workers=1`` for solve_bem.
Times are those of the whole call (kernel set-up included for solve_bem, ``solve`` only for
tamaas). tamaas is an optional benchmark dependency (``pip install tamaas``); without it
solve_bem is compared with its published iteration only. Errors are relative:
``sum|p - p_ref| / sum p_ref`` (L1) and ``max|p - p_ref| / max p_ref`` (max).

Usage::

    python benchmarks/bench_bem_standard.py [--part standard sweep sizes] [--n 1024]
        [--repeat 2] [--sizes 2048 4096] [--tamaas-sizes 2048]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

os.environ["OMP_NUM_THREADS"] = "1"

import numpy as np
import scipy.fft as sfft

from contact import Surface, self_affine
from contact.bem import solve_bem

LENGTH, HURST, E, NU = 1e-3, 0.8, 210e9, 0.3
E_STAR = E / (1 - NU**2)
PRESSURE = 0.01 * E_STAR
TOL = 1e-8


def rms_slope(heights: np.ndarray, dx: float) -> float:
    """Spectral rms slope sqrt(<|grad h|^2>) of a periodic square grid."""
    nx, ny = heights.shape
    qx = 2 * np.pi * sfft.fftfreq(nx, d=dx)
    qy = 2 * np.pi * sfft.rfftfreq(ny, d=dx)
    spec = np.abs(sfft.rfft2(heights)) ** 2
    weight = np.full(spec.shape[1], 2.0)
    weight[0] = 1.0
    if ny % 2 == 0:
        weight[-1] = 1.0
    q2 = qx[:, None] ** 2 + qy[None, :] ** 2
    return float(np.sqrt((weight * q2 * spec).sum()) / (nx * ny))


def standard_surface(n: int, seed: int = 0) -> Surface:
    """The standard problem's surface: self-affine, H = 0.8, rms slope 1, n x n on 1 mm."""
    s = self_affine((n, n), LENGTH, HURST, rq=1e-6, rng=seed)
    return Surface(s.heights / rms_slope(s.heights, s.dx), s.dx)


def run_bem(s: Surface, periodic: bool, tol: float = TOL, accelerate: bool = True):
    t = time.perf_counter()
    c = time.process_time()
    res = solve_bem(s, PRESSURE, E, NU, periodic=periodic, tol=tol, workers=1,
                    accelerate=accelerate, max_iter=5000)
    return time.perf_counter() - t, time.process_time() - c, res


def run_tamaas(s: Surface, periodic: bool, tol: float = TOL):
    """tamaas PolonskyKeerRey; the isolated patch by zero padding to 2n x 2n."""
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.error)
    n = s.shape[0]
    if periodic:
        heights, size, pressure = s.heights, [LENGTH, LENGTH], PRESSURE
    else:
        depth = s.heights.min() - 10 * np.ptp(s.heights)
        heights = np.full((2 * n, 2 * n), depth)
        heights[:n, :n] = s.heights
        size, pressure = [2 * LENGTH, 2 * LENGTH], PRESSURE / 4
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, size, list(heights.shape))
    model.E = E
    model.nu = NU
    solver = tm.PolonskyKeerRey(model, np.ascontiguousarray(heights), tol)
    solver.max_iter = 5000
    t = time.perf_counter()
    c = time.process_time()
    solver.solve(pressure)
    wall, cpu = time.perf_counter() - t, time.process_time() - c
    p = np.array(model.traction, copy=True)
    return wall, cpu, p[:n, :n]


def errors(p: np.ndarray, ref: np.ndarray) -> tuple[float, float]:
    d = np.abs(p - ref)
    return float(d.sum() / np.abs(ref).sum()), float(d.max() / np.abs(ref).max())


def have_tamaas() -> bool:
    try:
        import tamaas  # noqa: F401
    except ImportError:
        print("tamaas is not installed: comparing with the published iteration only")
        return False
    return True


def part_standard(n: int, repeat: int, tamaas: bool) -> list[dict]:
    s = standard_surface(n)
    solve_bem(standard_surface(32), PRESSURE, E, NU)  # compile the kernels outside timing
    rows = []
    for periodic in (True, False):
        kind = "periodic" if periodic else "isolated"
        _, _, ref = run_bem(s, periodic, tol=1e-12, accelerate=False)
        times = {"bem": [], "bem_cpu": [], "plain": [], "plain_cpu": [], "tamaas": [],
                 "tamaas_cpu": []}
        for _ in range(repeat):  # alternate the solvers
            wall, cpu, fast = run_bem(s, periodic)
            times["bem"].append(wall)
            times["bem_cpu"].append(cpu)
            if tamaas:
                wall, cpu, p_tm = run_tamaas(s, periodic)
                times["tamaas"].append(wall)
                times["tamaas_cpu"].append(cpu)
            wall, cpu, plain = run_bem(s, periodic, accelerate=False)
            times["plain"].append(wall)
            times["plain_cpu"].append(cpu)
        row = {
            "problem": kind, "n": n,
            "fraction": fast.contact_fraction,
            "bem_it": fast.n_iterations, "bem_conv": fast.info["n_convolutions"],
            "plain_it": plain.n_iterations, "plain_conv": plain.info["n_convolutions"],
            "ref_it": ref.n_iterations,
            "bem_err": errors(fast.pressure, ref.pressure),
            "plain_err": errors(plain.pressure, ref.pressure),
            **times,
        }
        if tamaas:
            row["tamaas_err"] = errors(p_tm, ref.pressure)
            row["bem_vs_tamaas"] = errors(fast.pressure, p_tm)
        rows.append(row)
        print(json.dumps(row), flush=True)
    return rows


def part_sweep(n: int, tamaas: bool) -> list[dict]:
    s = standard_surface(n)
    solve_bem(standard_surface(32), PRESSURE, E, NU)
    _, _, ref = run_bem(s, True, tol=1e-12, accelerate=False)
    rows = []
    for tol in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
        wall, cpu, fast = run_bem(s, True, tol=tol)
        row = {"tol": tol, "bem": wall, "bem_cpu": cpu, "bem_it": fast.n_iterations,
               "bem_err": errors(fast.pressure, ref.pressure)}
        if tamaas:
            wall, cpu, p_tm = run_tamaas(s, True, tol=tol)
            row.update(tamaas=wall, tamaas_cpu=cpu, tamaas_err=errors(p_tm, ref.pressure))
        rows.append(row)
        print(json.dumps(row), flush=True)
    return rows


_CHILD = r"""
import json, os, sys, time
os.environ["OMP_NUM_THREADS"] = "1"
sys.path.insert(0, {here!r})
import bench_bem_standard as b


def rss(key):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(key):
                return int(line.split()[1]) / 1024.0
    return float("nan")


n, solver, periodic = {n}, {solver!r}, {periodic}
s = b.standard_surface(n)
if solver == "bem":
    b.solve_bem(b.standard_surface(32), b.PRESSURE, b.E, b.NU)
else:
    import tamaas  # noqa: F401
before = rss("VmRSS")
if solver == "bem":
    wall, cpu, res = b.run_bem(s, periodic)
    extra = dict(it=res.n_iterations, conv=res.info["n_convolutions"],
                 converged=res.converged, fraction=res.contact_fraction)
    p = res.pressure
else:
    wall, cpu, p = b.run_tamaas(s, periodic)
    extra = dict(fraction=float((p > 0).mean()))
import numpy as np
np.save({out!r}, p)
print(json.dumps(dict(n=n, solver=solver, periodic=periodic, wall=wall, cpu=cpu,
                      peak_mib=rss("VmHWM"), before_mib=before, **extra)))
"""


def child(n: int, solver: str, periodic: bool, out: str) -> dict:
    here = os.path.dirname(os.path.abspath(__file__))
    code = _CHILD.format(here=here, n=n, solver=solver, periodic=periodic, out=out)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def part_sizes(sizes: list[int], tamaas_sizes: list[int], tamaas: bool, tmp: str) -> list[dict]:
    rows = []
    for n in sizes:
        runs = [("bem", True), ("bem", False)]
        if tamaas and n in tamaas_sizes:
            runs.insert(1, ("tamaas", True))
        for solver, periodic in runs:
            out = os.path.join(tmp, f"p_{solver}_{n}_{int(periodic)}.npy")
            row = child(n, solver, periodic, out)
            if solver == "tamaas":
                p_bem = np.load(os.path.join(tmp, f"p_bem_{n}_1.npy"))
                row["bem_vs_tamaas"] = errors(p_bem, np.load(out))
            rows.append(row)
            print(json.dumps(row), flush=True)
    return rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--part", nargs="+", default=["standard", "sweep", "sizes"],
                        choices=["standard", "sweep", "sizes"])
    parser.add_argument("--n", type=int, default=1024, help="grid points per side")
    parser.add_argument("--repeat", type=int, default=2, help="alternating runs per solver")
    parser.add_argument("--sizes", type=int, nargs="*", default=[2048, 4096])
    parser.add_argument("--tamaas-sizes", type=int, nargs="*", default=[2048])
    parser.add_argument("--tmp", default="/tmp", help="folder for the size runs' fields")
    args = parser.parse_args(argv)
    tamaas = have_tamaas()
    if "standard" in args.part:
        part_standard(args.n, args.repeat, tamaas)
    if "sweep" in args.part:
        part_sweep(args.n, tamaas)
    if "sizes" in args.part:
        part_sizes(args.sizes, args.tamaas_sizes, tamaas, args.tmp)


if __name__ == "__main__":
    main()
