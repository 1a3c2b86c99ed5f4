"""Compare ``contact.read`` with SurfaceTopography's reader on every file of a folder.

Usage::

    python benchmarks/survey_formats.py FOLDER [--unit UNIT]

FOLDER is, for example, ``test/file_format_examples`` of a SurfaceTopography checkout.
For each file (empty files are skipped) one line tells what SurfaceTopography reads (a 2-D
map with its grid and unit, a line profile, or its refusal) and what ``contact.read`` gives:
whether the shape, the physical size and the heights agree with SurfaceTopography's (to
1e-9 relative), or its refusal. A summary counts the outcomes. Files that state no unit
are read by both with ``--unit`` when given.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from collections import Counter
from pathlib import Path

import numpy as np

import contact
from contact._units import UNITS, checked_unit

RTOL = 1e-9


def _st(path: Path, unit: str | None):
    """SurfaceTopography's reading: (topography or None, description)."""
    import SurfaceTopography as st

    try:
        topo = st.read_topography(str(path))
        if topo.unit is None and unit is not None:
            topo = st.read_topography(str(path), unit=unit)
    except Exception as exc:  # any refusal, whatever its type
        return None, f"refused ({type(exc).__name__})"
    if topo.dim != 2:
        return None, "line profile"
    return topo, f"2-D {tuple(topo.nb_grid_pts)} {topo.unit}"


def _compare(surface: contact.Surface, topo) -> str:
    scale = UNITS.get(topo.unit or "", np.nan)
    h = np.ma.filled(np.ma.asarray(topo.heights(), dtype=float), np.nan) * scale
    if surface.shape != h.shape:
        return f"shape differs: {surface.shape} vs {h.shape}"
    size = np.array(topo.physical_sizes, dtype=float) * scale
    if not np.allclose(surface.size, size, rtol=RTOL, atol=0):
        return f"size differs: {surface.size} vs {tuple(size)}"
    ours = np.where(surface.mask, np.nan, surface.heights) if surface.mask is not None \
        else surface.heights
    atol = RTOL * np.nanmax(np.abs(h)) if np.isfinite(h).any() else 0.0
    if not np.allclose(ours, h, rtol=RTOL, atol=atol, equal_nan=True):
        return "heights differ"
    return "agree"


def _ours(path: Path, unit: str | None):
    """``contact.read``'s surface, or its refusal; with ``unit`` for a file without one."""
    try:
        return contact.read(path)
    except ValueError as exc:
        if unit is None or "states no length unit" not in str(exc):
            return exc
    except Exception as exc:  # report every refusal, whatever its type
        return exc
    try:
        return contact.read(path, unit=unit)
    except Exception as exc:  # report every refusal, whatever its type
        return exc


def survey(folder: Path, unit: str | None = None) -> Counter:
    """Print one line per file and return the count of each outcome."""
    outcomes: Counter = Counter()
    for path in sorted(folder.iterdir()):
        if not path.is_file() or path.stat().st_size == 0:
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            topo, st_says = _st(path, unit)
            surface = _ours(path, unit)
        kind = "2-D map for SurfaceTopography" if topo is not None else \
            "no 2-D map for SurfaceTopography"
        if isinstance(surface, Exception):
            ours = f"refused: {str(surface).splitlines()[0][:110]}"
            outcomes[f"{kind}, refused"] += 1
        elif topo is not None:
            ours = _compare(surface, topo)
            outcomes[f"{kind}, {ours.split(':')[0]}"] += 1
        else:
            ours = f"read {surface.shape}"
            outcomes[f"{kind}, read"] += 1
        print(f"{path.name:38s} {st_says:28s} -> {ours}")
    return outcomes


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=Path, help="folder of topography files")
    parser.add_argument("--unit", help="unit of files that state none (m, mm, µm, nm, ...)")
    args = parser.parse_args(argv)
    if not args.folder.is_dir():
        parser.error(f"no such folder: {args.folder}")
    try:
        import SurfaceTopography  # noqa: F401
    except ImportError:
        print("survey_formats needs SurfaceTopography (pip install SurfaceTopography)",
              file=sys.stderr)
        return 2
    outcomes = survey(args.folder, checked_unit(args.unit))
    print(f"\nsummary ({os.fspath(args.folder)}):")
    for outcome, n in sorted(outcomes.items()):
        print(f"  {n:4d}  {outcome}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
