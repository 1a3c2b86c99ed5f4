"""Tests of the maximum-density and integrity-vs-area figures (Agg backend)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
import scipy.stats as st

from glstat import GLD, integrity_probability, maximum
from glstat.plot import plot_integrity_vs_area, plot_maximum_density

G = GLD(0.0, 0.197451, 0.134912, 0.134912)


def test_plot_maximum_density_draws_density_and_interval():
    m = maximum(G, 1e6)
    ax = plot_maximum_density(m, interval=0.9)
    try:
        line = ax.get_lines()[0]
        x, y = line.get_xdata(), line.get_ydata()
        np.testing.assert_allclose(y, m.pdf(x), rtol=1e-12)
        # the shaded polygon spans the 90 % interval
        lo, hi = m.interval(0.9)
        verts = ax.collections[0].get_paths()[0].vertices[:, 0]
        assert verts.min() >= lo - (x[1] - x[0]) and verts.max() <= hi + (x[1] - x[0])
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert any(lab.startswith("90% interval") for lab in labels)
        assert ax.get_lines()[1].get_xdata()[0] == pytest.approx(m.mean())
    finally:
        plt.close(ax.figure)


def test_plot_maximum_density_uses_given_axes_and_validates():
    fig, ax = plt.subplots()
    try:
        assert plot_maximum_density(maximum(G, 10), ax=ax) is ax
        with pytest.raises(ValueError, match="interval must be"):
            plot_maximum_density(maximum(G, 10), interval=1.0, ax=ax)
    finally:
        plt.close(fig)


def test_plot_integrity_vs_area_single_and_sequence():
    k = np.logspace(0, 6, 25)
    ax = plot_integrity_vs_area(G, 4.6, 1e4, k)
    try:
        _, y = ax.get_lines()[0].get_data()
        np.testing.assert_allclose(y, integrity_probability(G, 4.6, 1e4, k), rtol=1e-14)
        assert ax.get_xscale() == "log"
        assert np.all(np.diff(y) <= 0)
    finally:
        plt.close(ax.figure)
    dists = [GLD(0.0, 0.197451 * s, 0.134912, 0.134912) for s in (0.98, 1.0, 1.02)]
    ax = plot_integrity_vs_area(dists, 4.6, 1e4, k)
    try:
        _, y = ax.get_lines()[0].get_data()
        np.testing.assert_allclose(y, integrity_probability(dists[1], 4.6, 1e4, k), rtol=1e-14)
        assert len(ax.collections) == 1  # the band
    finally:
        plt.close(ax.figure)


def test_plot_maximum_density_heavy_tail_given_bounds_and_label():
    """A heavy tail (lognormal, sigma 4.5: mean e^10.1 against a 96.5 % point of e^8.2): the
    axis stops twice the interval's width above it, the mean lies beyond and is named without
    a line; given bounds and label are shown."""
    m = st.lognorm(4.5)
    lo, hi = float(m.ppf(0.035)), float(m.isf(0.035))
    assert m.mean() > hi + 2 * (hi - lo)  # the case this test is about
    ax = plot_maximum_density(m, interval=0.9, bounds=(lo, hi), label="90 % interval (calibrated)")
    try:
        x = ax.get_lines()[0].get_xdata()
        assert x[-1] == pytest.approx(hi + 2 * (hi - lo), rel=1e-12)
        verts = ax.collections[0].get_paths()[0].vertices[:, 0]
        assert verts.min() >= lo - (x[1] - x[0]) and verts.max() <= hi + (x[1] - x[0])
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert f"90 % interval (calibrated) [{lo:.4g}, {hi:.4g}]" in labels
        assert f"mean {m.mean():.4g} (beyond the axis)" in labels
        assert all(len(line.get_xdata()) == 0 or line is ax.get_lines()[0] or
                   line.get_xdata()[0] != pytest.approx(m.mean()) for line in ax.get_lines())
    finally:
        plt.close(ax.figure)
