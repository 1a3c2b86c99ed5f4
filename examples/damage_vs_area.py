"""Damage probability against area from a small contact campaign (docs/method.md §7).

Simulates 20 Weierstrass surfaces (H = 0.5, 512², 1 mm², Rq = 50 µm, 20 MPa, the study's
default truncation of 6 terms per axis), pools the per-asperity peak pressures, bootstraps an
RS GLD fitted by moments, then prints the damage probability at several pressure levels and
area factors with 90 % intervals, and the pressure that guarantees integrity of an area k
times the analysed one with probability 0.99.
Run: ``python examples/damage_vs_area.py`` (about 15 s; writes damage_vs_area.png).
"""

from __future__ import annotations

import tempfile

import numpy as np

import glstat
from glstat.study import CampaignSettings, load_results, run_campaign

settings = CampaignSettings(hurst=(0.5,), n_surfaces=20, grid=512, n_terms=(6,), n_examples=0)
with tempfile.TemporaryDirectory() as out:
    run_campaign(settings, out, workers=2, progress=False)
    results = load_results(out, settings)

peaks = np.concatenate([r["asperity_peak"] for r in results.values()]) / 1e6  # MPa
n = np.mean([r["n_asperities"] for r in results.values()])  # asperities per analysed area
print(f"{peaks.size} asperity peak pressures, mean {peaks.mean():.0f} MPa, {n:.2f} asperities / mm²")

bf = glstat.bootstrap(peaks, param="rs", method="moments", n_resamples=1000, rng=1)
print(bf.fit.dist)

k = np.array([1.0, 10.0, 100.0, 1000.0])  # area factors: 1 mm² ... 10 cm²
for level in (20_000.0, 40_000.0, 60_000.0):
    d = bf.damage_probability(level, n, area_factor=k)
    print(f"\ndamage probability at {level:.0f} MPa")
    print(d.to_frame().to_string(index=False, float_format=lambda v: f"{v:.4g}"))

g = glstat.guaranteed_threshold(bf.fit.dist, n, 0.99, k)
for ki, gi in zip(k, np.atleast_1d(g), strict=True):
    print(f"area factor {ki:6g}: all asperities stay below {gi:.0f} MPa with probability 0.99")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

kk = np.logspace(0, 3, 31)
fig, ax = plt.subplots(figsize=(6, 4))
for level in (40_000.0, 60_000.0, 80_000.0):
    it = bf.integrity_probability(level, n, area_factor=kk)
    line, = ax.semilogx(kk, it.estimate, label=f"{level / 1e3:g} GPa")
    ax.fill_between(kk, it.low, it.high, color=line.get_color(), alpha=0.2)
ax.set_xlabel("area factor k (area / 1 mm²)")
ax.set_ylabel("integrity probability")
ax.legend(title="pressure level")
fig.savefig("damage_vs_area.png", dpi=100, bbox_inches="tight")
print("wrote damage_vs_area.png")
