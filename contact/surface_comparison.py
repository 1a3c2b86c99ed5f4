"""Measured surfaces set against simulated ones: roughness parameters and power spectra.

:func:`compare_surfaces` tabulates the ISO 25178 parameters of both, :func:`psd_comparison`
their radially averaged PSDs on common rings and :func:`plot_psd_comparison` draws them
(docs/contact.md, "Surfaces like a measurement").
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np

from ._fill import MAX_FILLED_FRACTION
from .roughness import UNITS
from .spectrum import (
    check_convention,
    filled_surface,
    fit_spectrum,
    ring_edges,
    ring_means,
    spectrum_2d,
)
from .surface import Surface, require_surface

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["compare_surfaces", "plot_psd_comparison", "psd_comparison"]


def _as_list(surfaces, name: str) -> list[Surface]:
    """One surface or an iterable of them as a non-empty list of surfaces."""
    items = [surfaces] if isinstance(surfaces, Surface) else surfaces
    if not isinstance(items, Iterable) or isinstance(items, (str, bytes, np.ndarray)):
        raise TypeError(
            f"{name} must be a contact.Surface or a list of them, got {type(surfaces).__name__}"
        )
    items = list(items)
    if not items:
        raise ValueError(f"{name} holds no surface")
    for item in items:
        require_surface(item)
    return items


def compare_surfaces(
    measured: Surface | Iterable[Surface], simulated: Iterable[Surface]
) -> pd.DataFrame:
    """ISO 25178 parameters of measured surfaces next to those of simulated ones.

    Every surface's parameters are taken about its least-squares plane
    (``Surface.roughness(level="plane")``), the reference of :func:`fit_spectrum`.

    Parameters
    ----------
    measured : Surface or iterable of Surface
        The measured surface(s).
    simulated : Surface or iterable of Surface
        The simulated surfaces, e.g. from :func:`self_affine_like`.

    Returns
    -------
    pandas.DataFrame
        One row per parameter of :meth:`contact.Surface.roughness` (``Sa, Sq, ..., hurst,
        ...``) plus ``psd_hurst`` (H of :func:`fit_spectrum`; NaN for a surface with more
        than 5 % of its points missing, which the spectrum does not fill);
        columns ``measured`` (mean over the measured surfaces), ``measured_std`` (their
        standard deviation, NaN for one), ``simulated_mean``, ``simulated_std`` (ddof = 1,
        NaN for one), ``z`` (``(measured - simulated_mean) / simulated_std``) and ``unit``.

    Warns
    -----
    contact.ContactWarning
        A surface has no physical structure-function Hurst exponent (its ``hurst`` is NaN).

    Examples
    --------
    >>> import contact
    >>> measured = contact.self_affine((64, 64), 1e-3, hurst=0.5, rq=1e-6, rng=3)
    >>> table = contact.compare_surfaces(measured, contact.self_affine_like(measured, 4, rng=1))
    >>> list(table.columns)
    ['measured', 'measured_std', 'simulated_mean', 'simulated_std', 'z', 'unit']
    >>> round(float(table.loc["Sq", "simulated_mean"] / table.loc["Sq", "measured"]), 6)
    1.0
    """
    import pandas as pd

    meas = _as_list(measured, "measured")
    sims = _as_list(simulated, "simulated")

    def params(s: Surface) -> pd.Series:
        row = s.roughness(level="plane").copy()
        try:
            row["psd_hurst"] = fit_spectrum(s).hurst
        except ValueError:
            row["psd_hurst"] = float("nan")
        return row

    m = pd.DataFrame([params(s) for s in meas])
    s = pd.DataFrame([params(x) for x in sims])
    table = pd.DataFrame(
        {
            "measured": m.mean(),
            "measured_std": m.std(ddof=1) if len(m) > 1 else m.mean() * np.nan,
            "simulated_mean": s.mean(),
            "simulated_std": s.std(ddof=1) if len(s) > 1 else s.mean() * np.nan,
        }
    )
    with np.errstate(divide="ignore", invalid="ignore"):
        table["z"] = (table["measured"] - table["simulated_mean"]) / table["simulated_std"]
    table["unit"] = [UNITS.get(k, "1") for k in table.index]
    table.index.name = "parameter"
    return table


def psd_comparison(
    measured: Surface | Iterable[Surface],
    simulated: Iterable[Surface],
    *,
    convention: str = "contact",
    max_filled: float = MAX_FILLED_FRACTION,
) -> pd.DataFrame:
    """Radially averaged PSDs of measured and simulated surfaces on common rings.

    The rings are those of the first measured surface (:func:`radial_psd`); every surface's
    PSD (plane-levelled, Tukey-windowed heights) is averaged on them.

    Parameters
    ----------
    measured : Surface or iterable of Surface
        The measured surface(s); up to ``max_filled`` of the points of each may be missing,
        and are filled by harmonic interpolation first.
    simulated : Surface or iterable of Surface
        The simulated surfaces.
    convention : {"contact", "surfacetopography"}
        PSD normalisation. ``"contact"``: ``Rq² = ∫ C d²q`` with q in rad/m;
        ``"surfacetopography"``: ``Rq² = ∫ C d²q / (2π)²``, as SurfaceTopography's
        ``power_spectrum_from_area``, ``(2π)² ≈ 39.48`` times larger. m^4 either way.
    max_filled : float, default 0.05
        Largest fraction of missing points that is filled.

    Returns
    -------
    pandas.DataFrame
        Columns ``q`` (rad/m, geometric mean over the first measured surface's ring),
        ``measured`` (mean PSD of the measured surfaces, m^4), ``simulated_mean``,
        ``simulated_low``, ``simulated_high`` (mean and 2.5 % / 97.5 % quantiles over the
        simulated surfaces, m^4); rings empty on some surface are dropped.

    Examples
    --------
    >>> import contact
    >>> measured = contact.self_affine((64, 64), 1e-3, hurst=0.5, rq=1e-6, rng=3)
    >>> psd = contact.psd_comparison(measured, contact.self_affine_like(measured, 3, rng=1))
    >>> list(psd.columns)
    ['q', 'measured', 'simulated_mean', 'simulated_low', 'simulated_high']
    """
    import pandas as pd

    check_convention(convention)
    meas = [filled_surface(s, "psd_comparison", max_filled)[0]
            for s in _as_list(measured, "measured")]
    sims = [filled_surface(s, "psd_comparison", max_filled)[0]
            for s in _as_list(simulated, "simulated")]
    edges = ring_edges(meas[0])
    q, _, counts = ring_means(*spectrum_2d(meas[0], convention), edges)
    m = np.array([ring_means(*spectrum_2d(x, convention), edges)[1] for x in meas])
    s = np.array([ring_means(*spectrum_2d(x, convention), edges)[1] for x in sims])
    ok = (counts > 0) & np.isfinite(m).all(axis=0) & np.isfinite(s).all(axis=0)
    return pd.DataFrame(
        {
            "q": q[ok],
            "measured": m.mean(axis=0)[ok],
            "simulated_mean": s.mean(axis=0)[ok],
            "simulated_low": np.quantile(s, 0.025, axis=0)[ok],
            "simulated_high": np.quantile(s, 0.975, axis=0)[ok],
        }
    )


def plot_psd_comparison(
    measured: Surface | Iterable[Surface],
    simulated: Iterable[Surface],
    ax=None,
    *,
    convention: str = "contact",
):
    """Plot the measured and simulated radially averaged PSDs on log-log axes.

    Parameters
    ----------
    measured : Surface or iterable of Surface
        The measured surface(s).
    simulated : Surface or iterable of Surface
        The simulated surfaces.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure is made when omitted.
    convention : {"contact", "surfacetopography"}
        PSD normalisation (see :func:`psd_comparison`).

    Returns
    -------
    matplotlib.axes.Axes
        The measured PSD as a line, the simulated mean as a dashed line and their
        2.5–97.5 % band shaded, with the fitted power law over its range.
    """
    import matplotlib.pyplot as plt

    table = psd_comparison(measured, simulated, convention=convention)
    fit = fit_spectrum(_as_list(measured, "measured")[0])
    if ax is None:
        _, ax = plt.subplots()
    ax.fill_between(table["q"], table["simulated_low"], table["simulated_high"], alpha=0.3,
                    color="C1", label="simulated, 95 % band")
    ax.loglog(table["q"], table["simulated_mean"], "--", color="C1", label="simulated, mean")
    ax.loglog(table["q"], table["measured"], color="C0", label="measured")
    inside = (table["q"] >= fit.q_fit_min) & (table["q"] <= fit.q_fit_max)
    if inside.any():
        q = table["q"][inside].to_numpy()
        ref = table["measured"][inside].to_numpy()
        law = q ** (-2 * (fit.hurst + 1))
        scale = math.exp(float(np.mean(np.log(ref) - np.log(law))))
        ax.loglog(q, scale * law, ":", color="k", label=f"fit, H = {fit.hurst:.2f}")
    ax.set_xlabel("wavevector q (rad/m)")
    ax.set_ylabel("PSD C(q) (m$^4$)")
    ax.legend()
    return ax
