"""Copy the figures of the examples into docs/img/ (gallery_*.png) for docs/gallery.md.

Run: ``python docs/gallery_figures.py`` (about a minute). Each example that writes a figure is
run as a user would run it, in a temporary directory, with the Agg backend; its PNGs are
copied to docs/img/gallery_<script>.png (gallery_<script>_<figure>.png when it writes
several), scaled down to at most 900 pixels wide.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from PIL import Image

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "img"
MAX_WIDTH = 900
MAX_BYTES = 150_000

# script, its arguments, the PNG files it writes (relative to its working directory)
FIGURES = [
    ("fit_compare_gof.py", [], ["fit_compare_gof.png"]),
    ("maximum_and_damage.py", [], ["maximum_and_damage.png"]),
    ("damage_vs_area.py", [], ["damage_vs_area.png"]),
    ("surface_contact.py", ["--n", "512", "--plot", "maps.png"], ["maps.png"]),
    ("surfaces_like_measurement.py", ["--n", "20", "--plot", "spectra.png"], ["spectra.png"]),
    ("fit_your_data.py", ["out"], None),  # None: every PNG in the output folder
]


def _shrink(src: Path, dst: Path) -> None:
    with Image.open(src) as im:
        im = im.convert("RGB")
        if im.width > MAX_WIDTH:
            im = im.resize((MAX_WIDTH, round(im.height * MAX_WIDTH / im.width)), Image.LANCZOS)
        im.save(dst, optimize=True)
        if dst.stat().st_size > MAX_BYTES:  # a palette keeps large figures small
            im.quantize(colors=256, method=Image.Quantize.FASTOCTREE).save(dst, optimize=True)


def main() -> int:
    OUT.mkdir(exist_ok=True)
    env = dict(os.environ, MPLBACKEND="Agg")
    for script, args, pngs in FIGURES:
        t0 = time.perf_counter()
        with tempfile.TemporaryDirectory() as tmp:
            run = subprocess.run([sys.executable, str(ROOT / "examples" / script), *args], cwd=tmp,
                                 env=env, capture_output=True, text=True, timeout=300)
            if run.returncode:
                sys.stderr.write(run.stdout + run.stderr)
                raise SystemExit(f"{script} failed with status {run.returncode}")
            found = ([Path(tmp) / p for p in pngs] if pngs is not None
                     else sorted((Path(tmp) / args[0]).glob("*.png")))
            stem = Path(script).stem
            for src in found:
                dst = OUT / (f"gallery_{stem}.png" if len(found) == 1 else f"gallery_{stem}_{src.stem}.png")
                _shrink(src, dst)
                print(f"{script}: {src.name} -> {dst.relative_to(ROOT)} ({dst.stat().st_size // 1024} KB)")
        print(f"{script}: {time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
