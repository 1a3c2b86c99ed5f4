"""The tables of a bootstrap: the lambdas and the statistics of every resample, and the
summary of the lambdas over all resamples and per RS region."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from .._fit_engine.equations import STAT_NAMES
from ._intervals import LAMBDA_NAMES, BootstrapInterval

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

    from ._driver import ResampleFits

__all__ = ["lambdas_frame", "statistics_frame", "summary_frame"]


def lambdas_frame(lam: np.ndarray, n_roots: np.ndarray, region: np.ndarray,
                  jump: np.ndarray) -> pd.DataFrame:
    """One row per resample (index ``resample``): ``lambda1..lambda4``, ``n_roots``,
    ``region`` and ``branch_jump``."""
    import pandas as pd

    frame = pd.DataFrame(lam, columns=list(LAMBDA_NAMES))
    frame["n_roots"] = n_roots
    frame["region"] = region
    frame["branch_jump"] = jump
    frame.index.name = "resample"
    return frame


def statistics_frame(fits: ResampleFits, method: str) -> pd.DataFrame | None:
    """One row per resample (index ``resample``): the matched statistics (compiled methods),
    ``min``, ``max`` and, for the compiled methods, ``covers``; None without resamples."""
    import pandas as pd

    if fits.extremes is None:
        return None
    if fits.statistics is None or fits.n_cover is None:
        df = pd.DataFrame(fits.extremes, columns=["min", "max"])
    else:
        df = pd.DataFrame(fits.statistics, columns=list(STAT_NAMES[method]))
        df["min"] = fits.extremes[:, 0]
        df["max"] = fits.extremes[:, 1]
        df["covers"] = fits.n_cover > 0
    df.index.name = "resample"
    return df


def summary_frame(lam: np.ndarray, regions: np.ndarray, param: str, full_region: int | None,
                  interval: Callable[[np.ndarray, str], BootstrapInterval], note: str) -> pd.DataFrame:
    """Percentile intervals of the lambdas over all successful resamples ``lam`` and, when they
    fall in several RS regions, over each region holding at least two of them.

    ``regions`` is the RS region of every row of ``lam``; ``interval(rows, note)`` is the
    percentile interval of the lambdas of ``rows``.
    """
    import pandas as pd

    ci = interval(lam, note).to_frame()
    ci.insert(1, "bootstrap_mean", np.mean(lam, axis=0))
    ci["region"] = "all"
    ci["n_used"] = lam.shape[0]
    frames = [ci]
    if param == "rs" and np.unique(regions).size > 1:
        for r in np.unique(regions):
            sub = lam[regions == r]
            if sub.shape[0] < 2:
                continue
            part = interval(sub, f"resample fits in RS region {r} only").to_frame()
            if full_region != r:
                part["estimate"] = np.nan
            part.insert(1, "bootstrap_mean", np.mean(sub, axis=0))
            part["region"] = int(r)
            part["n_used"] = sub.shape[0]
            part.index = pd.Index([f"{q} [region {r}]" for q in LAMBDA_NAMES], name="quantity")
            frames.append(part)
    return pd.concat(frames) if len(frames) > 1 else ci
