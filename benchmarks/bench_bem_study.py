"""Per-surface cost of ``glstat study --model bem``: the elastic BEM on the study's surfaces.

The default campaign (Weierstrass surfaces of 1024², 1 mm², Rq = 1.6 µm, 20 MPa, E = 210
GPa, ν = 0.3, isolated patch, tolerance 1e-8) on a fixed sample of its surfaces. For each
surface, in the same run and on one core:

* the baseline: :func:`contact._constrained_cg.polonsky_keer` with an isolated-patch
  operator that builds its kernel for every surface and transforms along the strided axis
  (:class:`BaselineOperator`, the operator before the kernel cache and the transposed
  transforms);
* :func:`contact.solve_bem` as the study calls it (kernel from the process's cache);
* the rest of :func:`glstat.study.bem.simulate_bem`: the asperity model and the contact
  records of both solutions.

Times are the best of ``--repeat`` interleaved runs: wall seconds, and CPU seconds of the
process (less sensitive to other jobs on a shared machine). The pressure fields of the two BEM solves are
compared by their relative max-norm and L1 differences. The estimate of the campaign's BEM
stage is the mean time of a whole :func:`simulate_bem` times the surfaces over the workers.
Last, one convolution of each operator is timed on a solution's pressure and on a dense one.

Usage::

    python benchmarks/bench_bem_study.py [--repeat 2] [--surfaces 2] [--workers 2]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np
import scipy.fft as sfft

import contact
from contact._constrained_cg import initial_pressure, polonsky_keer
from contact._influence import NonPeriodicOperator, love_coefficients
from contact.material import effective_modulus
from glstat.study.bem import BEMSettings, simulate_bem
from glstat.study.campaign import campaign_surface
from glstat.study.campaign_settings import CampaignSettings


class BaselineOperator:
    """Isolated-patch operator without the kernel cache, transforming along the strided axis.

    Parameters
    ----------
    shape : tuple of int
        Grid points ``(nx, ny)``.
    dx, dy : float
        Grid spacing in metres.
    e_star : float
        Contact modulus in pascals.
    """

    def __init__(self, shape, dx: float, dy: float, e_star: float):
        nx, ny = shape
        self.shape = (nx, ny)
        self.periodic = False
        self._spacing = (float(dx), float(dy), float(e_star))
        c = love_coefficients(nx, ny, dx, dy) / (np.pi * e_star)
        full = np.empty((2 * nx, 2 * ny))
        full[: nx + 1, : ny + 1] = c
        full[nx + 1 :, : ny + 1] = c[nx - 1 : 0 : -1, :]
        full[:, ny + 1 :] = full[:, ny - 1 : 0 : -1]
        self._self = float(c[0, 0])
        self._kernel_hat = np.ascontiguousarray(sfft.rfft2(full).real)
        self._half = np.empty((nx, ny + 1), dtype=np.complex128)
        self._spec = np.empty((2 * nx, ny + 1), dtype=np.complex128)
        self._wide = np.empty((nx, 2 * ny), dtype=np.float64)

    def inverse_stencil(self) -> np.ndarray:
        """3 x 3 stencil of the inverse compliance (Pa/m)."""
        return contact._influence.inverse_stencil(*self._spacing)

    @property
    def self_compliance(self) -> float:
        """Displacement of a cell under a unit pressure on itself, m/Pa."""
        return self._self

    def apply(self, p: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """Displacement (m) of the cell-wise uniform pressure ``p`` (Pa)."""
        nx, ny = self.shape
        np.fft.rfft(p, n=2 * ny, axis=1, out=self._half)
        spec = self._spec
        np.fft.fft(self._half, n=2 * nx, axis=0, out=spec)
        np.multiply(spec, self._kernel_hat, out=spec)
        np.fft.ifft(spec, axis=0, out=spec)
        np.fft.irfft(spec[:nx], n=2 * ny, axis=1, out=self._wide)
        res = self._wide[:, :ny]
        if out is None:
            return np.array(res)
        out[...] = res
        return out


def baseline_solve(surface, pressure: float, e_star: float, tol: float, max_iter: int):
    """Pressure (Pa) and iterations of the baseline solve (kernel built for the surface)."""
    h = np.asarray(surface.heights, dtype=np.float64)
    valid = np.ones(h.shape, dtype=bool)
    op = BaselineOperator(h.shape, surface.dx, surface.dy, e_star)
    p0 = initial_pressure(h, valid, pressure, e_star, surface.dx, surface.dy)
    out = polonsky_keer(op, h, valid, total_pressure=pressure * h.size, tol=tol,
                        max_iter=max_iter, p0=p0, overwrite_p0=True)
    return out.pressure, out.n_iterations


def timed(fn):
    """(wall s, CPU s of this process, result) of one call of ``fn``."""
    w, c = time.perf_counter(), time.process_time()
    res = fn()
    return time.perf_counter() - w, time.process_time() - c, res


def convolution_ms(op, p: np.ndarray, repeat: int = 20) -> float:
    """Best wall time (ms) of ``op.apply(p, out=...)``."""
    out = np.empty(p.shape)
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        op.apply(p, out=out)
        best = min(best, time.perf_counter() - t)
    return 1e3 * best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--surfaces", type=int, default=2, help="surfaces per H (the first ones)")
    ap.add_argument("--workers", type=int, default=2, help="worker processes of the estimate")
    args = ap.parse_args()
    s, b = CampaignSettings(), BEMSettings()
    e_star = effective_modulus(s.E, s.nu, None)
    pressure = s.pressures[0]
    keys = [(ih, 0, i) for ih in range(len(s.hurst)) for i in range(args.surfaces)]
    simulate_bem(s, b, 0, 0, s.n_surfaces - 1)  # compile the kernels, fill the cache
    print("| H | surface | it. | baseline BEM: wall s (CPU s) | solve_bem: wall s (CPU s) | speed-up "
          "(CPU) | rel. max diff. | rel. L1 diff. | asperity model + records (s) | simulate_bem (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for key in keys:
        surf = campaign_surface(s, *key)
        t = np.full((6, args.repeat), np.inf)
        for k in range(args.repeat):  # interleaved: the machine's load hits both alike
            t[0, k], t[1, k], (pb, itb) = timed(
                lambda surf=surf: baseline_solve(surf, pressure, e_star, b.tol, b.max_iter))
            t[2, k], t[3, k], res = timed(lambda surf=surf: contact.solve_bem(
                surf, pressure, s.E, s.nu, tol=b.tol, max_iter=b.max_iter, workers=1))
            t[4, k], _, rec = timed(lambda key=key: simulate_bem(s, b, *key))
            t[5, k] = t[4, k] - float(rec["seconds_bem"])
        tb, cb, tn, cn, ts, rest = t.min(axis=1)
        pn = res.pressure
        dmax = float(np.abs(pn - pb).max() / np.abs(pb).max())
        dl1 = float(np.abs(pn - pb).sum() / np.abs(pb).sum())
        rows.append((tb, cb, tn, cn, ts))
        print(f"| {s.hurst[key[0]]:g} | {key[2]} | {res.n_iterations} ({itb}) | {tb:.2f} ({cb:.2f}) "
              f"| {tn:.2f} ({cn:.2f}) | {tb / tn:.2f} ({cb / cn:.2f}) | {dmax:.1e} | {dl1:.1e} "
              f"| {rest:.2f} | {ts:.2f} |", flush=True)
    tb, cb, tn, cn, ts = np.mean(rows, axis=0)
    n_all = len(s.hurst) * len(s.pressures) * s.n_surfaces
    print(f"\nmean per surface: baseline BEM {tb:.2f} s ({cb:.2f} CPU s), solve_bem {tn:.2f} s "
          f"({cn:.2f} CPU s), simulate_bem {ts:.2f} s; BEM stage of the campaign "
          f"≈ {n_all} × {ts:.2f} / {args.workers} = {n_all * ts / args.workers:.0f} s "
          f"(with the baseline BEM ≈ {n_all * (ts - tn + tb) / args.workers:.0f} s)")
    surf = campaign_surface(s, *keys[0])
    p = contact.solve_bem(surf, pressure, s.E, s.nu, tol=b.tol, workers=1).pressure
    new_op = NonPeriodicOperator(p.shape, surf.dx, surf.dy, e_star)
    old_op = BaselineOperator(p.shape, surf.dx, surf.dy, e_star)
    dense = np.random.default_rng(0).random(p.shape)
    for name, q in (("the solution's pressure", p), ("a dense pressure", dense)):
        print(f"one convolution at {p.shape[0]}x{p.shape[1]}, {name}: baseline "
              f"{convolution_ms(old_op, q):.1f} ms, operator {convolution_ms(new_op, q):.1f} ms")


if __name__ == "__main__":
    main()
