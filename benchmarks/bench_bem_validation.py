"""Validation of :func:`contact.bem.solve_bem` against analytic contact solutions.

Prints the tables of ``docs/bem.md``: Hertz (sphere on a flat,
:func:`contact.reference.hertz_sphere`) and Westergaard (periodic wavy surface,
:func:`contact.reference.westergaard`) under grid refinement, and the convergence history of
a rough surface at the paper's load. With ``--plot DIR`` it also draws the validation figures
into ``DIR`` (matplotlib).

Usage::

    python benchmarks/bench_bem_validation.py [--plot DIR]
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from contact import Surface, effective_modulus, reference, self_affine
from contact.bem import solve_bem

E, NU = 210e9, 0.3
E_STAR = effective_modulus(E, NU)

# Hertz: sphere of radius R under the force W
R_SPHERE, W_LOAD = 0.01, 10.0
HERTZ = reference.hertz_sphere(W_LOAD, R_SPHERE, E_STAR)
A_HERTZ, P0_HERTZ = HERTZ.contact_radius, HERTZ.max_pressure

# Westergaard: h = DELTA cos(2 pi x / LAMBDA), full contact above P_STAR
LAMBDA, DELTA = 1e-3, 1e-6
P_STAR = reference.full_contact_pressure(DELTA, LAMBDA, E_STAR)


def hertz(n: int):
    """Solve the Hertz problem on an n x n grid spanning 4 a; return errors and fields."""
    dx = 4 * A_HERTZ / n
    x = (np.arange(n) - n / 2 + 0.5) * dx
    X, Y = np.meshgrid(x, x, indexing="ij")
    s = Surface(-(X**2 + Y**2) / (2 * R_SPHERE), dx)
    t = time.perf_counter()
    res = solve_bem(s, W_LOAD / s.area, E, NU)
    t = time.perf_counter() - t
    exact = HERTZ.pressure(np.hypot(X, Y))
    a_num = math.sqrt(res.in_contact.sum() * dx * dx / math.pi)
    row = {
        "n": n,
        "a/dx": A_HERTZ / dx,
        "pmax": res.max_pressure / P0_HERTZ - 1,
        "profile": float(np.sqrt(np.mean((res.pressure - exact) ** 2)) / P0_HERTZ),
        "radius": a_num / A_HERTZ - 1,
        "approach": -res.separation / HERTZ.approach - 1,
        "iterations": res.n_iterations,
        "time": t,
    }
    return row, x, res.pressure[:, n // 2], exact[:, n // 2]


def westergaard(n: int, ratio: float):
    dx = LAMBDA / n
    x = np.arange(n) * dx
    h = np.repeat((DELTA * np.cos(2 * np.pi * x / LAMBDA))[:, None], 4, axis=1)
    res = solve_bem(Surface(h, dx), ratio * P_STAR, E, NU, periodic=True)
    w = reference.westergaard(ratio * P_STAR, LAMBDA, DELTA, E_STAR)
    fraction, exact = w.contact_fraction, w.pressure(x)
    central = exact > 0.5 * exact.max()
    return {
        "n": n,
        "ratio": ratio,
        "fraction": res.contact_fraction,
        "exact": fraction,
        "profile": float(np.sqrt(np.mean((res.pressure[:, 0] - exact) ** 2)) / exact.max()),
        "central": float(np.abs(res.pressure[central, 0] - exact[central]).max()
                         / exact.max()),
        "pmax": res.max_pressure / exact.max() - 1,
        "iterations": res.n_iterations,
    }


def table(rows, cols, fmt):
    print("| " + " | ".join(cols) + " |")
    print("|" + "---|" * len(cols))
    for r in rows:
        print("| " + " | ".join(format(r[c], fmt.get(c, "")) for c in cols) + " |")
    print()


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--plot", type=Path, default=None, help="directory for the figures")
    args = parser.parse_args(argv)

    print("Hertz, sphere on flat (non-periodic), grid spanning 4a")
    hz = [hertz(n) for n in (32, 64, 128, 256)]
    table([h[0] for h in hz], ["n", "a/dx", "pmax", "profile", "radius", "approach",
                               "iterations", "time"],
          {"a/dx": ".0f", "pmax": ".2e", "profile": ".2e", "radius": ".2e",
           "approach": ".2e", "time": ".3f"})

    print("Westergaard, contact fraction vs load (periodic, n = 256)")
    ratios = [0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 0.98]
    wg = [westergaard(256, r) for r in ratios]
    table(wg, ["ratio", "fraction", "exact", "pmax", "profile", "iterations"],
          {"fraction": ".4f", "exact": ".4f", "pmax": ".2e", "profile": ".2e"})

    print("Westergaard under refinement, pbar = 0.3 p*")
    ref = [westergaard(n, 0.3) for n in (32, 64, 128, 256, 512, 1024)]
    for r in ref:
        r["fraction error"] = abs(r["fraction"] - r["exact"])
    table(ref, ["n", "fraction error", "pmax", "central", "profile", "iterations"],
          {"fraction error": ".2e", "pmax": ".2e", "central": ".2e", "profile": ".2e"})

    print("Rough surface at the paper's load (self-affine H = 0.5, 512^2, Rq 50 um on 1 mm)")
    s = self_affine((512, 512), 1e-3, 0.5, rq=50e-6, rng=11)
    rough = {}
    for periodic in (False, True):
        res = solve_bem(s, 20e6, E, NU, periodic=periodic)
        rough[periodic] = res
        print(f"periodic={periodic}: {res.n_iterations} iterations, contact fraction "
              f"{res.contact_fraction:.3g}, history {np.array2string(res.history, precision=1)}")

    if args.plot is not None:
        plot(args.plot, hz, ratios, wg, ref, rough)


def plot(folder: Path, hz, ratios, wg, ref, rough) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    folder.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(1, 3, figsize=(13, 3.8))
    _, x, p, exact = hz[2]
    ax[0].plot(x / A_HERTZ, exact / P0_HERTZ, "k-", label="Hertz")
    ax[0].plot(x / A_HERTZ, p / P0_HERTZ, "o", ms=3, label="solve_bem, n = 128")
    ax[0].set(xlabel="x / a", ylabel="p / p0", title="Hertz pressure profile")
    ax[0].legend()
    r = np.linspace(1e-4, 1, 400)
    ax[1].plot(r, [reference.westergaard(v * P_STAR, LAMBDA, DELTA, E_STAR).contact_fraction
                   for v in r], "k-", label="Westergaard")
    ax[1].plot(ratios, [w["fraction"] for w in wg], "o", label="solve_bem, n = 256")
    ax[1].set(xlabel="pbar / p*", ylabel="contact fraction", title="Wavy surface")
    ax[1].legend()
    ns = [h[0]["n"] for h in hz]
    ax[2].loglog(ns, [abs(h[0]["pmax"]) for h in hz], "o-", label="Hertz max p")
    ax[2].loglog(ns, [h[0]["profile"] for h in hz], "s-", label="Hertz profile (rms)")
    ax[2].loglog([w["n"] for w in ref], [w["central"] for w in ref], "^-",
                 label="Westergaard, central half (max)")
    ax[2].set(xlabel="grid points per side", ylabel="relative error", title="Refinement")
    ax[2].legend()
    fig.tight_layout()
    fig.savefig(folder / "bem_validation.png", dpi=120)
    fig, ax = plt.subplots(figsize=(5, 3.8))
    for periodic, res in rough.items():
        ax.semilogy(np.arange(1, res.history.size + 1), res.history, "o-",
                    label="periodic" if periodic else "isolated")
    ax.axhline(1e-8, color="k", lw=0.8, ls="--")
    ax.set(xlabel="iteration", ylabel="relative pressure change",
           title="Rough surface, 20 MPa")
    ax.legend()
    fig.tight_layout()
    fig.savefig(folder / "bem_history.png", dpi=120)


if __name__ == "__main__":
    main()
