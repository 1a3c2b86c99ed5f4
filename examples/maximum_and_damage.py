"""Maximum pressure, damage probability and integrity against area for a fitted GLD.

The GLD below stands for a fitted contact-pressure distribution G (MPa) of a surface analysed
on n = 1024 x 1024 grid points (docs/method.md §6–§8), then the same questions when the
number of draws is itself random: a Poisson number of asperities in contact, or the counts
observed on a few surfaces. Run: ``python examples/maximum_and_damage.py``;
writes ``maximum_and_damage.png``.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np

import glstat
from glstat.plot import plot_integrity_vs_area, plot_maximum_density

# FKML GLD: location 1300 MPa, scale 1/lambda2 = 250 MPa, heavier upper tail
g = glstat.GLD(1300.0, 1 / 250.0, 0.3, -0.05, param="fkml")
n = 1024 * 1024
hardness = 8000.0  # MPa

m = glstat.maximum(g, n)
lo, hi = m.interval(0.9)
print(f"maximal pressure on the analysed area: mean {m.mean():.0f} MPa, "
      f"median {m.median():.0f} MPa, 90 % interval [{lo:.0f}, {hi:.0f}] MPa")

for k in [1.0, 10.0, 100.0]:
    d = glstat.damage_probability(g, hardness, n, area_factor=k)
    t = glstat.guaranteed_threshold(g, n, 0.99, area_factor=k)
    print(f"area x{k:>5g}: P(damage at {hardness:g} MPa) = {d:.3e}; "
          f"pressure not exceeded with probability 0.99: {t:.0f} MPa")

# the maximum over an area where the number of asperities in contact is random: E[F(x)^N]
peaks = glstat.GLD(1300.0, 1 / 400.0, 0.1, -0.2, param="fkml")  # peak pressure of one asperity
for count in (glstat.PoissonCount(6.2), glstat.ObservedCounts([4, 5, 5, 6, 7, 7, 8, 9, 12])):
    d = glstat.damage_probability(peaks, 2050.0, count=count)
    d10 = glstat.damage_probability(peaks, 2050.0, count=count, area_factor=10)
    t = glstat.guaranteed_threshold(peaks, damage=1e-3, count=count)
    print(f"{count!r}: P(damage at 2050 MPa) = {d:.3f} on one area, {d10:.3f} on ten; "
          f"pressure exceeded with probability 1e-3: {t:.0f} MPa")

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
plot_maximum_density(m, interval=0.9, ax=ax1)
ax1.set_xlabel("maximal contact pressure (MPa)")
plot_integrity_vs_area(g, hardness, n, np.logspace(-2, 4, 100), ax=ax2)
fig.tight_layout()
fig.savefig("maximum_and_damage.png", dpi=120)
print("wrote maximum_and_damage.png")
