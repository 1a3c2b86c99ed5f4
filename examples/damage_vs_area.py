"""Damage probability against area from a small contact campaign (docs/method.md §6–§7).

Simulates 20 Weierstrass surfaces at the study's scene (H = 0.5, 512², 1 mm², Rq = 1.6 µm,
6 terms per axis, 20 MPa), pools the per-asperity peak pressures with the surface each comes
from, bootstraps an FKML GLD fitted by L-moments by resampling whole surfaces (so the number
of asperities in contact per surface is a random count, E[F(x)^N]; an RS fit by moments ends
near 6.7 GPa here, so its damage above that level would be 0 by construction), then prints the
damage probability at several pressure levels and area factors with 90 % intervals, and the pressure
exceeded somewhere on an area k times the analysed one with probability 1 %.
Run: ``python examples/damage_vs_area.py`` (about 20 s; writes damage_vs_area.png).
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

per_surface = [r["asperity_peak"] / 1e6 for r in results.values()]  # MPa
peaks = np.concatenate(per_surface)
surface = np.repeat(np.arange(len(per_surface)), [p.size for p in per_surface])
print(f"{peaks.size} asperity peak pressures, mean {peaks.mean():.0f} MPa, "
      f"{peaks.size / len(per_surface):.2f} asperities per mm²")

bf = glstat.bootstrap(peaks, param="fkml", method="lmoments", n_resamples=1000, rng=1, groups=surface)
print(bf.fit.dist, bf.counts)

k = np.array([1.0, 10.0, 100.0, 1000.0])  # area factors: 1 mm² ... 10 cm²
for level in (2050.0, 4000.0, 8000.0):
    d = bf.damage_probability(level, area_factor=k)
    print(f"\ndamage probability at {level:.0f} MPa")
    print(d.to_frame().to_string(index=False, float_format=lambda v: f"{v:.4g}"))

g = glstat.guaranteed_threshold(bf.fit.dist, damage=0.01, area_factor=k, count=bf.counts)
for ki, gi in zip(k, np.atleast_1d(g), strict=True):
    print(f"area factor {ki:6g}: the pressure exceeds {gi:.0f} MPa somewhere with probability 0.01")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

kk = np.logspace(0, 3, 31)
fig, ax = plt.subplots(figsize=(6, 4))
for level in (4000.0, 8000.0, 16000.0):
    it = bf.integrity_probability(level, area_factor=kk)
    line, = ax.semilogx(kk, it.estimate, label=f"{level / 1e3:g} GPa")
    ax.fill_between(kk, it.low, it.high, color=line.get_color(), alpha=0.2)
ax.set_xlabel("area factor k (area / 1 mm²)")
ax.set_ylabel("integrity probability")
ax.legend(title="pressure level")
fig.savefig("damage_vs_area.png", dpi=100, bbox_inches="tight")
print("wrote damage_vs_area.png")
