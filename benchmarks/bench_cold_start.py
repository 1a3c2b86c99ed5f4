"""First use: how long a new user waits, with an empty kernel cache and with a warm one.

Each measurement runs in a fresh Python process (``NUMBA_CACHE_DIR`` pointing at a new, empty
folder for the cold runs, at the folder the cold run filled for the warm ones) and times, in
that process:

* ``glstat --version`` (the console script's module, no package import);
* ``import glstat``;
* the first ``glstat.fit(x)`` (RS by moments of 1000 gamma values);
* the first ``fit.dist.cdf`` of 1000 points;
* the first ``glstat.predict_maximum(x, n=1000, threshold=...)`` with B = 200.

The difference between the cold and the warm run is numba compiling the kernels these calls
need. The table is printed and written to ``benchmarks/results/cold_start.csv``; the machine's
load average is printed beside it (compiling is CPU-bound: a loaded machine stretches it).

Usage::

    python benchmarks/bench_cold_start.py [--repeat 1]
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "results" / "cold_start.csv"

#: The timed session of a first-time user (printed as JSON by the child process).
SESSION = r"""
import json, time
t = {}
t0 = time.perf_counter()
import numpy as np
import glstat
t["import glstat"] = time.perf_counter() - t0
x = np.random.default_rng(1).gamma(3.0, 1.0, 1000)
t1 = time.perf_counter()
fit = glstat.fit(x)
t["first fit (RS moments, n = 1000)"] = time.perf_counter() - t1
t2 = time.perf_counter()
fit.dist.cdf(np.linspace(x.min(), x.max(), 1000))
t["first cdf (1000 points)"] = time.perf_counter() - t2
t3 = time.perf_counter()
glstat.predict_maximum(x, n=1000, threshold=12.0, n_resamples=200, rng=2)
t["first predict_maximum (B = 200)"] = time.perf_counter() - t3
t["session total"] = time.perf_counter() - t0
print(json.dumps(t))
"""


def _session(cache: str) -> dict[str, float]:
    env = {**os.environ, "NUMBA_CACHE_DIR": cache}
    out = subprocess.run([sys.executable, "-c", SESSION], capture_output=True, text=True,
                         env=env, cwd=ROOT, timeout=1800)
    if out.returncode != 0:
        raise RuntimeError(out.stderr[-2000:])
    return json.loads(out.stdout.strip().splitlines()[-1])


def _version_time() -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import _glstat_entry; _glstat_entry.main(['--version'])"],
                   capture_output=True, cwd=ROOT, check=True, timeout=60)
    return time.perf_counter() - t0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1, help="cold/warm pairs to run")
    args = parser.parse_args(argv)
    rows = []
    for r in range(args.repeat):
        with tempfile.TemporaryDirectory(prefix="glstat-cold-") as cache:
            cold = _session(cache)
            warm = _session(cache)
        for stage in cold:
            rows.append({"run": r, "stage": stage, "cold_s": round(cold[stage], 3),
                         "warm_s": round(warm[stage], 3)})
        rows.append({"run": r, "stage": "glstat --version", "cold_s": round(_version_time(), 3),
                     "warm_s": round(_version_time(), 3)})
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"load average (1 min) at the end: {load:.2f}")
    print(f"{'stage':<36} {'cold (s)':>9} {'warm (s)':>9}")
    for row in rows:
        print(f"{row['stage']:<36} {row['cold_s']:>9.3f} {row['warm_s']:>9.3f}")
    OUT.parent.mkdir(parents=True, exist_ok=True)
    with open(OUT, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=["run", "stage", "cold_s", "warm_s"])
        writer.writeheader()
        writer.writerows(rows)
    print(f"written: {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
