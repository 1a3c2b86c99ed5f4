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


def test_qq_and_pp_points_by_hand():
    # three points against U(0, 4): Hazen positions (i - 0.5)/n = 1/6, 1/2, 5/6
    data = [3.0, np.nan, 1.0, 2.0]  # the NaN is left out
    unif = stats.uniform(0.0, 4.0)
    p = np.array([1.0, 3.0, 5.0]) / 6.0
    qq = plot_qq(data, unif).get_lines()
    np.testing.assert_allclose(qq[0].get_xdata(), 4.0 * p, rtol=1e-15)
    np.testing.assert_array_equal(qq[0].get_ydata(), [1.0, 2.0, 3.0])
    pp = plot_pp(data, unif).get_lines()
    np.testing.assert_allclose(pp[0].get_xdata(), p, rtol=1e-15)
    np.testing.assert_allclose(pp[0].get_ydata(), [0.25, 0.5, 0.75], rtol=1e-15)
    np.testing.assert_array_equal(pp[-1].get_xdata(), [0.0, 1.0])
    np.testing.assert_array_equal(pp[-1].get_ydata(), [0.0, 1.0])


def test_probability_plots_are_statsmodels_probplot_with_hazen_positions():
    from statsmodels.graphics.gofplots import ProbPlot

    norm = stats.norm(0.1, 1.1)
    qq = plot_qq(X, FIT, norm).get_lines()
    pp = plot_pp(X, FIT, norm).get_lines()
    for j, dist in enumerate((FIT.dist, norm)):
        ref = ProbPlot(X, dist=dist, fit=False, a=0.5)
        np.testing.assert_array_equal(ref.theoretical_percentiles, (np.arange(1, X.size + 1) - 0.5) / X.size)
        np.testing.assert_array_equal(qq[j].get_xdata(), ref.theoretical_quantiles)
        np.testing.assert_array_equal(qq[j].get_ydata(), ref.sample_quantiles)
        np.testing.assert_array_equal(pp[j].get_xdata(), ref.theoretical_percentiles)
        np.testing.assert_array_equal(pp[j].get_ydata(), ref.sample_percentiles)


def test_qq_style_labels_and_reference_line():
    far = stats.norm(3.0, 2.0)  # its quantiles reach well beyond the data
    ax = plot_qq(X, FIT, far, names=["fit", "far"])
    lines = ax.get_lines()
    assert [ln.get_label() for ln in lines] == ["fit", "far", "y = x"]
    for j, line in enumerate(lines[:2]):
        assert line.get_linestyle() == "None" and line.get_marker() == "o"
        assert line.get_markerfacecolor() == line.get_markeredgecolor() == line.get_color() == f"C{j}"
    # the reference line runs across every model's points, and the axes are square
    ref = lines[-1]
    lo, hi = ref.get_xdata()
    np.testing.assert_array_equal(ref.get_ydata(), [lo, hi])
    assert ax.get_xlim() == ax.get_ylim() == (lo, hi)
    for line in lines[:2]:
        for v in (line.get_xdata(), line.get_ydata()):
            assert lo <= v.min() and v.max() <= hi
    assert lo < far.ppf(0.5 / X.size) and hi > far.ppf(1 - 0.5 / X.size)
    assert ref.get_color() == "k"
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("model quantile", "sample quantile")
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["fit", "far", "y = x"]


def test_pp_on_given_axes():
    _, ax = plt.subplots()
    assert plot_pp(X, FIT, ax=ax) is ax
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("empirical probability", "model probability")
    assert [ln.get_label() for ln in ax.get_lines()] == ["GLD-RS (moments)", "y = x"]


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
    with pytest.raises(TypeError, match="real numbers"):
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
