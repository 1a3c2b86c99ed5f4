"""Tests of the goodness-of-fit and bootstrap figures in glstat.plot (Agg backend)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest
from scipy import stats

import glstat
from glstat.plot import plot_histogram, plot_lambda_densities, plot_pp, plot_qq

# RS approximation of N(0, 1) by moments (docs/method.md §14)
RS_NORMAL = glstat.GLD(0.0, 0.197451, 0.134912, 0.134912)
X = RS_NORMAL.rvs(size=300, random_state=np.random.default_rng(0))
FIT = glstat.fit(X, "rs", "moments")


@pytest.fixture(autouse=True)
def _close_figures():
    rc = dict(matplotlib.rcParams)
    yield
    plt.close("all")
    # no global matplotlib state changed by the plotting functions
    assert dict(matplotlib.rcParams) == rc


def test_histogram_density_integrates_to_one_and_draws_each_pdf():
    norm = stats.norm(X.mean(), X.std())
    ax = plot_histogram(X, FIT, norm, bins=20)
    heights = np.array([p.get_height() for p in ax.patches])
    widths = np.array([p.get_width() for p in ax.patches])
    assert heights.size == 20
    assert np.sum(heights * widths) == pytest.approx(1.0, rel=1e-12)
    lines = ax.get_lines()
    assert [ln.get_label() for ln in lines] == ["GLD-RS (moments)", "norm"]
    for line, dist in zip(lines, (FIT.dist, norm), strict=True):
        x, y = line.get_xdata(), line.get_ydata()
        assert x.min() < X.min() and x.max() > X.max()
        np.testing.assert_allclose(y, dist.pdf(x), rtol=1e-12)


def test_histogram_only_data_and_given_axes_and_names():
    _, ax = plt.subplots()
    assert plot_histogram(X, ax=ax) is ax
    assert len(ax.get_lines()) == 0 and len(ax.patches) > 0
    ax2 = plot_histogram(X, RS_NORMAL, names=["true"])
    assert ax2.get_lines()[0].get_label() == "true"


def test_qq_points_are_model_quantiles_against_sorted_data():
    norm = stats.norm()
    ax = plot_qq(X, FIT, norm)
    lines = ax.get_lines()
    assert len(lines) == 3 and lines[-1].get_label() == "y = x"
    p = (np.arange(1, X.size + 1) - 0.5) / X.size
    for line, dist in zip(lines[:2], (FIT.dist, norm), strict=True):
        np.testing.assert_allclose(line.get_xdata(), dist.ppf(p), rtol=1e-12)
        np.testing.assert_array_equal(line.get_ydata(), np.sort(X))
    ref = lines[-1]
    np.testing.assert_array_equal(ref.get_xdata(), ref.get_ydata())


def test_pp_points_are_model_cdf_against_plotting_positions():
    ax = plot_pp(X, FIT, stats.norm(0.5, 1.0))
    lines = ax.get_lines()
    assert len(lines) == 3
    p = (np.arange(1, X.size + 1) - 0.5) / X.size
    np.testing.assert_allclose(lines[0].get_xdata(), p, rtol=1e-15)
    np.testing.assert_allclose(lines[0].get_ydata(), FIT.dist.cdf(np.sort(X)), rtol=1e-12)
    np.testing.assert_allclose(lines[1].get_ydata(), stats.norm(0.5, 1.0).cdf(np.sort(X)), rtol=1e-12)
    assert ax.get_xlim() == (0.0, 1.0) and ax.get_ylim() == (0.0, 1.0)


def _lambda_table(b=200, seed=1):
    rng = np.random.default_rng(seed)
    lam = np.column_stack([rng.normal(0, 0.1, b), rng.normal(0.2, 0.01, b),
                           rng.normal(0.13, 0.02, b), rng.normal(0.13, 0.02, b)])
    return pd.DataFrame(lam, columns=["lambda1", "lambda2", "lambda3", "lambda4"])


def test_lambda_densities_from_dataframe_with_truth():
    tab = _lambda_table()
    fig = plot_lambda_densities(tab, true=(0, 0.197451, 0.134912, 0.134912))
    axes = fig.get_axes()
    assert len(axes) == 4
    for j, ax in enumerate(axes):
        kde_line, true_line = ax.get_lines()
        x, y = kde_line.get_xdata(), kde_line.get_ydata()
        kde = stats.gaussian_kde(tab[f"lambda{j + 1}"].to_numpy())
        np.testing.assert_allclose(y, kde(x), rtol=1e-12)
        # the curve covers the bulk of the kernel density (trapezoid rule)
        assert np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)) == pytest.approx(1.0, abs=1e-3)
        assert true_line.get_xdata()[0] == pytest.approx((0, 0.197451, 0.134912, 0.134912)[j])
        assert ax.get_title() == f"lambda{j + 1} (200 values)"


def test_lambda_densities_accepts_array_and_object_with_lambdas():
    tab = _lambda_table()

    class Result:  # a bootstrap result carrying its lambdas as a table
        lambdas = tab

    f1 = plot_lambda_densities(tab.to_numpy())
    f2 = plot_lambda_densities(Result())
    for a1, a2 in zip(f1.get_axes(), f2.get_axes(), strict=True):
        np.testing.assert_array_equal(a1.get_lines()[0].get_ydata(), a2.get_lines()[0].get_ydata())
        assert len(a1.get_lines()) == 1


def test_lambda_densities_on_given_axes_drops_failed_fits_and_handles_constants():
    tab = _lambda_table(50)
    tab.loc[3, :] = np.nan  # a failed fit
    tab["lambda4"] = 0.5  # a shape held fixed
    fig, axes = plt.subplots(1, 4)
    out = plot_lambda_densities(tab, axes=axes)
    assert out is fig
    assert axes[0].get_title() == "lambda1 (49 values)"
    assert axes[3].get_lines()[0].get_label() == "all equal"
    assert axes[3].get_lines()[0].get_xdata()[0] == 0.5


def test_bad_input():
    with pytest.raises(ValueError, match="at least 2"):
        plot_histogram([])
    with pytest.raises(ValueError, match="at least 2"):
        plot_qq([np.nan, 1.0], FIT)
    with pytest.raises(TypeError, match="numeric"):
        plot_pp(["a", "b"], FIT)
    with pytest.raises(ValueError, match="at least one"):
        plot_qq(X)
    with pytest.raises(ValueError, match="at least one"):
        plot_pp(X)
    with pytest.raises(TypeError, match="GLDFit, a GLD or a frozen"):
        plot_histogram(X, "norm")
    with pytest.raises(TypeError, match="GLDFit, a GLD or a frozen"):
        plot_qq(X, stats.norm)
    with pytest.raises(ValueError, match=r"shape \(B, 4\)"):
        plot_lambda_densities(np.zeros((10, 3)))
    with pytest.raises(ValueError, match="lacks column"):
        plot_lambda_densities(pd.DataFrame({"lambda1": [1.0, 2.0]}))
    with pytest.raises(TypeError, match="lambdas must be"):
        plot_lambda_densities([["a", "b", "c", "d"]] * 3)
    with pytest.raises(ValueError, match="at least 2"):
        plot_lambda_densities(np.ones((1, 4)))
    with pytest.raises(ValueError, match="4 lambdas"):
        plot_lambda_densities(_lambda_table(), true=(1, 2))
    with pytest.raises(ValueError, match="4 Axes"):
        _, axes = plt.subplots(1, 3)
        plot_lambda_densities(_lambda_table(), axes=axes)


def test_plot_and_gof_import_matplotlib_and_pandas_lazily():
    import subprocess
    import sys

    code = "import sys, glstat.plot, glstat.gof; print('matplotlib' in sys.modules, 'pandas' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]
