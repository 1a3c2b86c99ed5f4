"""Data quality of a measured topography: how finely its heights are resolved.

Instruments store heights as integers times a resolution (an interferometer's phase
counts, an AFM's DAC steps, a text export's last printed digit). When that step is not
small against the roughness, the heights sit on a few levels: the height distribution is a
staircase and the slopes and curvatures of neighbouring points (Sdq, summit curvatures,
the contact's local geometry) are those of the steps. :func:`height_steps` measures it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .roughness import level_heights
from .surface import Surface, surface_arrays

__all__ = ["QUANTISED_BELOW", "HeightSteps", "height_steps"]

#: A surface counts as quantised when its Sq spans fewer height steps than this. Rounding
#: to a step ``q`` adds ``q / sqrt(12)`` of RMS noise, 1.4 % of Sq at 20 steps per Sq, but
#: a neighbour-to-neighbour slope changes by a whole step at a time: with fewer than about
#: 20 steps per Sq the histogram of the heights shows its levels (fewer than about 120
#: across ±3 Sq) and the finite differences are dominated by them.
QUANTISED_BELOW = 20.0


@dataclass(frozen=True)
class HeightSteps:
    """Height resolution of a surface.

    Attributes
    ----------
    step : float
        Smallest difference between two distinct measured heights, in metres (NaN when all
        heights are equal). Heights closer than a few units in the last place of the
        largest height count as one level.
    n_levels : int
        Number of distinct measured heights.
    sq : float
        RMS height about the least-squares plane of the measured points, in metres.
    steps_per_sq : float
        ``sq / step`` (dimensionless; 0 when all heights are equal).
    quantised : bool
        ``steps_per_sq`` below :data:`QUANTISED_BELOW`.
    """

    step: float
    n_levels: int
    sq: float
    steps_per_sq: float
    quantised: bool


def distinct_levels(values: np.ndarray) -> tuple[float, int]:
    """Smallest nonzero step (m) between the sorted distinct ``values`` and their number;
    values within ``64 ε max|value|`` of each other are one level (NaN step for one level)."""
    levels = np.unique(values)
    gaps = np.diff(levels)
    tol = 64 * np.finfo(float).eps * float(np.max(np.abs(levels)))
    real = gaps[gaps > tol]
    if real.size == 0:
        return math.nan, 1
    return float(real.min()), int(real.size + 1)


def height_steps(surface: Surface) -> HeightSteps:
    """The height resolution of a surface: its smallest height step and the steps per Sq.

    Parameters
    ----------
    surface : Surface
        Heights in metres; only the measured points count.

    Returns
    -------
    HeightSteps
        ``step`` (m), ``n_levels``, ``sq`` (m, about the least-squares plane),
        ``steps_per_sq`` and ``quantised`` (fewer than :data:`QUANTISED_BELOW` steps per Sq).
        A surface without roughness (all heights equal, or a plane) has 0 steps per Sq and
        counts as quantised: its heights resolve no roughness.

    Raises
    ------
    TypeError
        ``surface`` is not a :class:`Surface`.

    Examples
    --------
    >>> import numpy as np, contact
    >>> from contact.quality import height_steps
    >>> z = contact.self_affine((64, 64), 64e-6, 0.8, rq=1e-8, rng=0).heights
    >>> coarse = contact.Surface(np.round(z / 2e-9) * 2e-9, dx=1e-6)  # 2 nm levels
    >>> q = height_steps(coarse)
    >>> round(q.step * 1e9, 3), q.quantised
    (2.0, True)
    """
    h, valid = surface_arrays(surface)
    values = h[valid]
    step, n_levels = distinct_levels(values)
    z = level_heights(h, valid, surface.dx, surface.dy, "plane")[valid]
    sq = math.sqrt(float(np.mean(z * z)))
    per_sq = 0.0 if math.isnan(step) else sq / step
    return HeightSteps(step=step, n_levels=n_levels, sq=sq, steps_per_sq=per_sq,
                       quantised=bool(per_sq < QUANTISED_BELOW))
