"""Figures (matplotlib, imported only when a figure is drawn).

Every function draws on ``ax`` when given (a new figure otherwise) and returns the Axes.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["plot_integrity_vs_area", "plot_maximum_density"]


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, ax = plt.subplots()
    return ax


def plot_maximum_density(max_dist, interval: float = 0.9, ax=None) -> Any:
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

    Returns
    -------
    matplotlib.axes.Axes
        Lines: the density (label ``"density"``), the mean and the median (vertical lines);
        the shaded interval has label ``"<interval %> interval"``.
    """
    if not 0 < float(interval) < 1:
        raise ValueError(f"interval must be strictly between 0 and 1, got {interval!r}")
    ax = _axes(ax)
    tail = (1.0 - float(interval)) / 2.0
    lo, hi = float(max_dist.ppf(tail)), float(max_dist.isf(tail))
    x0, x1 = float(max_dist.ppf(1e-4)), float(max_dist.isf(1e-4))
    x = np.linspace(x0, x1, 400)
    y = np.asarray(max_dist.pdf(x), dtype=float)
    ax.plot(x, y, color="C0", label="density")
    inside = (x >= lo) & (x <= hi)
    ax.fill_between(x, 0, y, where=inside, color="C0", alpha=0.25,
                    label=f"{100 * float(interval):g}% interval [{lo:.4g}, {hi:.4g}]")
    mean = float(max_dist.mean())
    if np.isfinite(mean):
        ax.axvline(mean, color="C1", linestyle="--", label=f"mean {mean:.4g}")
    median = float(max_dist.ppf(0.5))
    ax.axvline(median, color="C2", linestyle=":", label=f"median {median:.4g}")
    ax.set_xlabel("maximal value")
    ax.set_ylabel("probability density")
    ax.legend()
    return ax


def plot_integrity_vs_area(dist, threshold: float, n: float, area_factors, ax=None) -> Any:
    """Integrity probability ``F(threshold)^(k n)`` against the area factor k (log axis).

    Parameters
    ----------
    dist : frozen continuous distribution, or a sequence of them
        As for :func:`glstat.integrity_probability`. With several distributions (e.g.
        bootstrap fits) the median curve is drawn with the band between the 5 % and 95 %
        points across the distributions.
    threshold : float
        Pressure level (e.g. the hardness), in the units of ``dist``.
    n : float
        Number of points of the analysed area.
    area_factors : array_like
        Ratios k of the area of interest to the analysed one (> 0).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on.

    Returns
    -------
    matplotlib.axes.Axes
        First line: the integrity curve (label ``"integrity"``).
    """
    from .damage import integrity_probability

    k = np.asarray(area_factors, dtype=float).ravel()
    ax = _axes(ax)
    p = np.asarray(integrity_probability(dist, threshold, n, k), dtype=float)
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
