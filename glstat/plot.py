"""Figures (matplotlib, imported only when a figure is drawn).

Every function draws on ``ax`` (or ``axes``) when given, on a new figure otherwise, and
returns the Axes (or the Figure for multi-panel plots). No global matplotlib state (rcParams,
styles) is changed.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .gof.inputs import as_float_array, named_distributions

__all__ = [
    "plot_histogram",
    "plot_integrity_vs_area",
    "plot_lambda_densities",
    "plot_maximum_density",
    "plot_pp",
    "plot_qq",
]


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, ax = plt.subplots()
    return ax


def plot_maximum_density(max_dist, interval: float = 0.9, ax=None, *,
                         bounds: tuple[float, float] | None = None,
                         label: str | None = None) -> Any:
    """Density of the maximal value with its central interval shaded.

    Parameters
    ----------
    max_dist : frozen continuous distribution
        Typically ``glstat.maximum(dist, n)``; anything with ``pdf``, ``ppf``, ``isf`` and
        ``mean`` works. Values in the units of the parent (e.g. MPa).
    interval : float, optional
        Probability content of the shaded central interval (the confidence level), in (0, 1).
        Default 0.9.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.
    bounds : (float, float), optional
        Ends of the shaded interval, e.g. the calibrated interval of a prediction; default
        the central ``interval`` of ``max_dist``.
    label : str, optional
        Legend text of the shaded interval, before its ends; default ``"<interval %>
        interval"``.

    Returns
    -------
    matplotlib.axes.Axes
        Lines: the density (label ``"density"``), the mean and the median (vertical lines);
        the shaded interval has label ``"<interval %> interval [lo, hi]"``. The x axis runs
        from the 1e-4 to the 1 - 1e-4 quantile, at most twice the interval's width beyond
        either end (a heavy tail would squeeze the density into a spike); a mean beyond
        the axis is named in the legend without a line.
    """
    if not 0 < float(interval) < 1:
        raise ValueError(f"interval must be strictly between 0 and 1, got {interval!r}")
    ax = _axes(ax)
    tail = (1.0 - float(interval)) / 2.0
    if bounds is None:
        lo, hi = float(max_dist.ppf(tail)), float(max_dist.isf(tail))
    else:
        lo, hi = (float(v) for v in bounds)
    width = hi - lo
    x0, x1 = float(max_dist.ppf(1e-4)), float(max_dist.isf(1e-4))
    if width > 0:
        x0, x1 = max(x0, lo - 2.0 * width), min(x1, hi + 2.0 * width)
    x = np.linspace(x0, x1, 400)
    y = np.asarray(max_dist.pdf(x), dtype=float)
    ax.plot(x, y, color="C0", label="density")
    inside = (x >= lo) & (x <= hi)
    name = f"{100 * float(interval):g}% interval" if label is None else label
    ax.fill_between(x, 0, y, where=inside, color="C0", alpha=0.25,
                    label=f"{name} [{lo:.4g}, {hi:.4g}]")
    mean = float(max_dist.mean())
    if x0 <= mean <= x1:
        ax.axvline(mean, color="C1", linestyle="--", label=f"mean {mean:.4g}")
    elif np.isfinite(mean):
        ax.plot([], [], color="C1", linestyle="--", label=f"mean {mean:.4g} (beyond the axis)")
    median = float(max_dist.ppf(0.5))
    ax.axvline(median, color="C2", linestyle=":", label=f"median {median:.4g}")
    ax.set_xlabel("maximal value")
    ax.set_ylabel("probability density")
    ax.legend()
    return ax


def plot_integrity_vs_area(dist, threshold: float, n: float | None, area_factors, ax=None, *,
                           count=None) -> Any:
    """Integrity probability ``F(threshold)^(k n)`` against the area factor k (log axis).

    Parameters
    ----------
    dist : frozen continuous distribution, or a sequence of them
        As for :func:`glstat.integrity_probability`. With several distributions (e.g.
        bootstrap fits) the median curve is drawn with the band between the 5 % and 95 %
        points across the distributions.
    threshold : float
        Pressure level (e.g. the hardness), in the units of ``dist``.
    n : float or None
        Number of points of the analysed area (None with ``count``).
    area_factors : array_like
        Ratios k of the area of interest to the analysed one (> 0).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.
    count : glstat.PoissonCount, glstat.ObservedCounts or frozen scipy.stats discrete, optional
        A random number of points instead of ``n``: the integrity is ``E[F^N]^k``.

    Returns
    -------
    matplotlib.axes.Axes
        First line: the integrity curve (label ``"integrity"``).
    """
    from .extremes.damage import integrity_probability

    k = np.asarray(area_factors, dtype=float).ravel()
    ax = _axes(ax)
    p = np.asarray(integrity_probability(dist, threshold, n, k, count=count), dtype=float)
    if p.ndim == 2:
        ax.plot(k, np.median(p, axis=0), color="C0", label="integrity")
        lo, hi = np.quantile(p, [0.05, 0.95], axis=0)
        ax.fill_between(k, lo, hi, color="C0", alpha=0.25, label="5-95 % band")
    else:
        ax.plot(k, p, color="C0", label="integrity")
    ax.set_xscale("log")
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("area factor k (area / analysed area)")
    ax.set_ylabel(f"P(max < {threshold:g})")
    ax.legend()
    return ax


# ---------------------------------------------------------------------------------------------
# fitted distributions against data
# ---------------------------------------------------------------------------------------------
def _sample(data) -> np.ndarray:
    x = as_float_array(data)
    x = x[np.isfinite(x)]
    if x.size < 2:
        raise ValueError(f"a plot of the data needs at least 2 finite points, got {x.size}")
    return np.sort(x)


def plot_histogram(data, *fits_or_dists, bins: str | int | Any = "auto", names=None, ax=None) -> Any:
    """Density histogram of the data with the pdf of each fitted distribution.

    Parameters
    ----------
    data : array_like
        The sample (flattened; non-finite values are left out), in its units.
    *fits_or_dists : GLDFit, GLD or frozen continuous scipy.stats distribution
        Models whose densities are drawn (none: only the histogram).
    bins : str, int or sequence, optional
        As for ``numpy.histogram`` (default ``"auto"``).
    names : sequence of str, optional
        Legend labels of the models (default as in :func:`glstat.gof_report`).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.

    Returns
    -------
    matplotlib.axes.Axes
        The histogram bars (label ``"data"``, heights in 1/(data unit), integrating to 1) and
        one line per model, in the order given, evaluated on 400 points spanning the data.
    """
    x = _sample(data)
    models = named_distributions(fits_or_dists, names)
    ax = _axes(ax)
    ax.hist(x, bins=bins, density=True, color="0.75", edgecolor="0.4", label="data")
    pad = 0.05 * (x[-1] - x[0])
    grid = np.linspace(x[0] - pad, x[-1] + pad, 400)
    for j, (name, dist) in enumerate(models):
        with np.errstate(all="ignore"):
            y = np.asarray(dist.pdf(grid), dtype=float)
        ax.plot(grid, y, color=f"C{j}", label=name)
    ax.set_xlabel("value")
    ax.set_ylabel("probability density")
    ax.legend()
    return ax


# Hazen plotting positions (i - 0.5)/n: statsmodels' ProbPlot with a = 0.5 (its default a = 0
# gives i/(n + 1))
_HAZEN_A = 0.5


def _probability_plots(caller: str, data, fits_or_dists, names, ax):
    """The named models of a Q–Q or P–P plot, each with its statsmodels ``ProbPlot``, and the axes.

    Parameters
    ----------
    caller : str
        Name of the plotting function, for the error message.
    data : array_like
        The sample (flattened; non-finite values are left out).
    fits_or_dists : tuple
        The models as passed by the caller.
    names : sequence of str or None
        Legend labels of the models.
    ax : matplotlib.axes.Axes or None
        Axes to draw on (None: a new figure).

    Returns
    -------
    plots : list of (str, statsmodels.graphics.gofplots.ProbPlot)
        One per model, in the order given: the legend label and the probability plot of the
        sorted finite sample against the model (taken as given, ``fit=False``), with Hazen
        plotting positions (i − 0.5)/n.
    ax : matplotlib.axes.Axes

    Raises
    ------
    ValueError
        No model given.
    """
    from statsmodels.graphics.gofplots import ProbPlot

    if not fits_or_dists:
        raise ValueError(f"{caller} needs at least one fit or distribution")
    x = _sample(data)
    models = named_distributions(fits_or_dists, names)
    return [(name, ProbPlot(x, dist=dist, fit=False, a=_HAZEN_A)) for name, dist in models], _axes(ax)


def _style(j: int, name: str) -> dict[str, Any]:
    """Marker style of the j-th model's points (statsmodels colours every face C0 otherwise)."""
    colour = f"C{j}"
    return {"color": colour, "markerfacecolor": colour, "markeredgecolor": colour, "marker": "o",
            "markersize": 3, "linestyle": "none", "label": name}


def plot_qq(data, *fits_or_dists, names=None, ax=None) -> Any:
    """Quantile–quantile plot: sorted data against each model's quantiles.

    Parameters
    ----------
    data : array_like
        The sample (flattened; non-finite values are left out), in its units.
    *fits_or_dists : GLDFit, GLD or frozen continuous scipy.stats distribution
        At least one model.
    names : sequence of str, optional
        Legend labels of the models.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.

    Returns
    -------
    matplotlib.axes.Axes
        One marker line per model (x: model quantile at the plotting positions
        (i − 0.5)/n, y: the i-th smallest data value, both in data units), then the
        reference line y = x (label ``"y = x"``).
    """
    from statsmodels.graphics.gofplots import qqline

    plots, ax = _probability_plots("plot_qq", data, fits_or_dists, names, ax)
    for j, (name, pp) in enumerate(plots):
        with np.errstate(all="ignore"):
            pp.qqplot(ax=ax, xlabel="model quantile", ylabel="sample quantile", **_style(j, name))
    # across the points of every model: ends at the smaller and the larger of the two axis limits
    qqline(ax, "45", fmt="k-", linewidth=1, label="y = x")
    ax.legend()
    return ax


def plot_pp(data, *fits_or_dists, names=None, ax=None) -> Any:
    """Probability–probability plot: each model's cdf at the data against the plotting positions.

    Parameters
    ----------
    data : array_like
        The sample (flattened; non-finite values are left out), in its units.
    *fits_or_dists : GLDFit, GLD or frozen continuous scipy.stats distribution
        At least one model.
    names : sequence of str, optional
        Legend labels of the models.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.

    Returns
    -------
    matplotlib.axes.Axes
        One marker line per model (x: empirical probability (i − 0.5)/n, y: F(x_(i)), both
        dimensionless), then the diagonal (label ``"y = x"``).
    """
    from statsmodels.graphics.gofplots import qqline

    plots, ax = _probability_plots("plot_pp", data, fits_or_dists, names, ax)
    for j, (name, pp) in enumerate(plots):
        with np.errstate(all="ignore"):
            pp.ppplot(ax=ax, xlabel="empirical probability", ylabel="model probability", **_style(j, name))
    # ppplot has set both axes to [0, 1]: the diagonal from (0, 0) to (1, 1)
    qqline(ax, "45", fmt="k-", linewidth=1, label="y = x")
    ax.legend()
    return ax


# ---------------------------------------------------------------------------------------------
# bootstrap lambdas
# ---------------------------------------------------------------------------------------------
_LAMBDA_COLUMNS = ("lambda1", "lambda2", "lambda3", "lambda4")


def _lambda_array(lambdas) -> np.ndarray:
    obj = getattr(lambdas, "lambdas", lambdas)
    if hasattr(obj, "columns"):
        missing = [c for c in _LAMBDA_COLUMNS if c not in obj.columns]
        if missing:
            raise ValueError(f"the lambda table lacks column(s) {missing}")
        obj = obj[list(_LAMBDA_COLUMNS)].to_numpy()
    try:
        arr = np.asarray(obj, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError("lambdas must be a DataFrame with columns lambda1..lambda4, a (B, 4) array or an "
                        f"object with such a .lambdas table, got {type(lambdas).__name__}") from exc
    if arr.ndim != 2 or arr.shape[1] != 4:
        raise ValueError(f"lambdas must have shape (B, 4), got {arr.shape}")
    return arr


def plot_lambda_densities(lambdas, true=None, axes=None, *, true_label: str = "true") -> Any:
    """Kernel density estimates of bootstrapped lambda1..lambda4 on a 2 × 2 grid.

    Parameters
    ----------
    lambdas : pandas.DataFrame, array_like or object with a ``lambdas`` DataFrame
        Columns ``lambda1``..``lambda4`` (one row per resample), a (B, 4) array, or e.g. a
        bootstrap result carrying such a table as ``.lambdas``. Non-finite entries (failed
        fits) are left out column by column; the number used is shown in each title.
    true : sequence of 4 float, optional
        Reference lambdas (e.g. the fit to the full sample, or the true values in a
        simulation), drawn as vertical dashed lines.
    axes : array of 4 matplotlib.axes.Axes, optional
        Axes to draw on (any shape holding 4 Axes, in the order lambda1..lambda4).
    true_label : str
        Legend label of the reference lines (e.g. ``"full-sample fit"`` when ``true`` is the
        fit to the whole sample rather than known true values).

    Returns
    -------
    matplotlib.figure.Figure
        Each panel: the Gaussian kernel density estimate (``scipy.stats.gaussian_kde``,
        Scott's bandwidth; label ``"KDE"``) on 200 points, or a vertical line when all
        values are equal (label ``"all equal"``), then the reference line (label
        ``true_label``). Tick labels use at most 5 ticks and scientific notation for very small
        or large values, so they do not overlap.
        lambda1 is in data units, lambda2 in 1/(data unit), lambda3 and lambda4 are
        dimensionless.
    """
    from scipy.stats import gaussian_kde

    arr = _lambda_array(lambdas)
    if true is not None:
        true = np.asarray(true, dtype=float).ravel()
        if true.size != 4:
            raise ValueError(f"true must hold 4 lambdas, got {true.size}")
    created = axes is None
    if created:
        import matplotlib.pyplot as plt

        _, axes = plt.subplots(2, 2, figsize=(8, 6))
    flat = list(np.asarray(axes, dtype=object).ravel())
    if len(flat) != 4:
        raise ValueError(f"axes must hold 4 Axes, got {len(flat)}")
    fig = flat[0].figure
    for j, ax in enumerate(flat):
        v = arr[:, j]
        v = v[np.isfinite(v)]
        if v.size < 2:
            raise ValueError(f"lambda{j + 1} has {v.size} finite value(s); a density needs at least 2")
        if v.min() == v.max():
            ax.axvline(v[0], color="C0", label="all equal")
        else:
            kde = gaussian_kde(v)
            bw = float(np.sqrt(kde.covariance[0, 0]))
            grid = np.linspace(v.min() - 3 * bw, v.max() + 3 * bw, 200)
            ax.plot(grid, kde(grid), color="C0", label="KDE")
        if true is not None:
            ax.axvline(true[j], color="C3", linestyle="--", label=true_label)
        from matplotlib.ticker import MaxNLocator

        ax.xaxis.set_major_locator(MaxNLocator(5))
        ax.ticklabel_format(axis="both", style="sci", scilimits=(-3, 4), useOffset=False)
        ax.set_title(f"lambda{j + 1} ({v.size} values)")
        ax.set_xlabel(f"lambda{j + 1}")
        ax.set_ylabel("density")
        ax.legend(fontsize=8)
    if created:
        fig.tight_layout()
    return fig
