"""A measured topography in ISO 25178-72 X3P format: read, characterise, press.

    python examples/measured_x3p.py [scan.x3p] [--pressure 20e6] [--level plane]

Without a file argument a demonstration scan is made first: a self-affine surface with a
slight tilt and a few missing points (as an optical profilometer leaves them), written to
X3P in a temporary directory. The file is read back, levelled, characterised by its ISO
25178 parameters and pressed by a rigid flat.
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

import contact


def demo_scan(path: Path) -> None:
    """Write a 512 x 512 self-affine scan (0.5 mm square, Sq = 1 µm) with missing points."""
    rng = np.random.default_rng(25178)
    base = contact.self_affine((512, 512), 0.5e-3, 0.8, rq=1e-6, rng=rng)
    x = np.arange(512) * base.dx
    tilt = 2e-3 * x[:, None] + 1e-3 * x[None, :]
    mask = rng.random(base.shape) < 0.002
    contact.Surface(base.heights + tilt, base.dx, mask=mask).write(path)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("path", nargs="?", help="an .x3p file (default: a generated scan)")
    parser.add_argument("--pressure", type=float, default=20e6, help="nominal pressure, Pa")
    parser.add_argument("--E", type=float, default=210e9, help="Young's modulus, Pa")
    parser.add_argument("--nu", type=float, default=0.3, help="Poisson ratio")
    parser.add_argument("--level", choices=["mean", "plane"], default="plane")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(args.path) if args.path else Path(tmp) / "demo.x3p"
        if not args.path:
            demo_scan(path)
            print(f"wrote a demonstration scan to {path.name}")
        surface = contact.read(path)
    print(surface)
    missing = 0 if surface.mask is None else int(surface.mask.sum())
    print(f"missing points: {missing}")

    params = surface.roughness(level=args.level)
    print("\nISO 25178 parameters (SI units; Sdr as a fraction):")
    for name, value in params.items():
        print(f"  {name:>18} = {value:.4g} {contact.roughness.UNITS[name]}")

    # Remove the form (tilt) before the contact computation; the mask is kept.
    result = contact.solve(surface.detrend(args.level), args.pressure, args.E, args.nu)
    print("\nContact with a rigid flat:")
    print(result.summary().to_string())


if __name__ == "__main__":
    main()
