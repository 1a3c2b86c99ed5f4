"""``glstat fit`` on your own data: a CSV of contact pressures in, fit, damage and figures out.

Writes ``pressures.csv`` (2000 simulated contact pressures in MPa, with a ``surface`` label
column and a ``pressure`` column, the way a measurement export often looks) and runs the
``glstat fit`` command on it, exactly as ``glstat fit pressures.csv --column pressure ...`` or
``python -m glstat.cli.fit pressures.csv ...`` would from a shell. The analysed area has
1024² grid points; the damage probability at a hardness of 8000 MPa is given for that area
and for areas 10 and 100 times larger, with 90 % bootstrap intervals.

Run: ``python examples/fit_your_data.py [OUTDIR]`` (default ``fit_your_data_out``; about
10 s). OUTDIR receives the CSV, the figures, ``fit.json`` and ``summary.csv``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from glstat.cli import fit as cli_fit


def write_pressures(path: Path, n: int = 2000, seed: int = 2019) -> None:
    """Write ``n`` simulated contact pressures (MPa, gamma with mean 1400 MPa) as a CSV file.

    Parameters
    ----------
    path : pathlib.Path
        The CSV file to write.
    n : int, optional
        Number of pressures.
    seed : int, optional
        Random seed.
    """
    import pandas as pd

    rng = np.random.default_rng(seed)
    pressures = rng.gamma(4.0, 350.0, n)
    surfaces = [f"S{1 + i % 4}" for i in range(n)]
    pd.DataFrame({"surface": surfaces, "pressure": pressures}).to_csv(path, index=False)


def main(argv: list[str] | None = None) -> int:
    """Write the CSV into the output directory and run ``glstat fit`` on it.

    Parameters
    ----------
    argv : list of str, optional
        ``[OUTDIR]`` (default ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status of ``glstat fit``.
    """
    argv = sys.argv[1:] if argv is None else argv
    out = Path(argv[0] if argv else "fit_your_data_out")
    out.mkdir(parents=True, exist_ok=True)
    csv = out / "pressures.csv"
    write_pressures(csv)
    return cli_fit.main([
        str(csv), "--column", "pressure",
        "--param", "rs", "--method", "moments",
        "--bootstrap", "500", "--confidence-level", "0.9",
        "--n-max", str(1024 * 1024),            # grid points of the analysed area
        "--hardness", "8000",                   # MPa
        "--area-factor", "1", "10", "100",
        "--out", str(out), "--seed", "1",
    ])


if __name__ == "__main__":
    sys.exit(main())
