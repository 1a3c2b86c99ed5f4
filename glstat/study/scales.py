"""The lateral scale at which a study's answer holds: the grid spacing and the S-filter of its
surfaces, the surfaces prepared at that scale (outliers replaced when asked, then the ISO
16610-61 Gaussian S-filter), the coarser scales the answer is checked against, and the scale in
words for every table and caption (docs/method.md §15)."""

from __future__ import annotations

import math
from typing import Any

__all__ = [
    "SCALE_FACTORS",
    "prepared_surface",
    "s_filter_um",
    "scale_factors",
    "scale_text",
    "spacing_um",
]

#: Multiples of the declared nesting index λs at which the surfaces are solved again to show
#: how the answer moves with the scale (the first is the answer's own scale).
SCALE_FACTORS = (1, 2, 4)


def scale_factors(settings: Any) -> tuple[int, ...]:
    """The multiples of λs a study solves at: :data:`SCALE_FACTORS` whose λs fits four times in
    the surface's smaller side (the filter would flatten it otherwise); ``(1,)`` without an
    S-filter."""
    lam = getattr(settings, "s_filter", None)
    if lam is None:
        return (1,)
    side = min(settings.size)
    return tuple(k for k in SCALE_FACTORS if 4 * k * lam <= side * (1 + 1e-9))


def spacing_um(settings: Any, bem_grid: int | None = None) -> float:
    """The grid spacing in µm (the coarser axis when the spacings differ), or with ``bem_grid``
    that of the square grid of that many points per side the elastic BEM solves on."""
    if bem_grid is not None:
        return settings.length / bem_grid * 1e6
    return max(settings.spacing) * 1e6


def s_filter_um(settings: Any) -> float:
    """The S-filter nesting index λs in µm (NaN without an S-filter)."""
    lam = getattr(settings, "s_filter", None)
    return math.nan if lam is None else lam * 1e6


def _is_default(settings: Any) -> bool:
    """Whether a measured study's λs is the ISO 25178-3 default of its spacing."""
    import contact

    if not getattr(settings, "measured", False) or settings.s_filter is None:
        return False
    return math.isclose(settings.s_filter, contact.default_s_filter(*settings.spacing), rel_tol=1e-9)


def scale_text(settings: Any, short: bool = False, bem_grid: int | None = None) -> str:
    """The scale of a study's answer in words: "grid spacing 1.66 µm, S-filter λs = 5 µm (the
    ISO 25178-3 default for this spacing)", or "... no S-filter" (``short``: without the
    explanation in brackets); ``bem_grid``: the points per side of the grid the elastic BEM
    solves simulated surfaces on, when it is not the campaign's ("grid spacing 0.977 µm,
    elastic BEM 2.6 µm")."""
    (dx, dy) = settings.spacing
    spacing = (f"{dx * 1e6:.3g} µm" if math.isclose(dx, dy, rel_tol=1e-6)
               else f"{dx * 1e6:.3g} × {dy * 1e6:.3g} µm")
    if bem_grid is not None:
        spacing += f" (elastic BEM {spacing_um(settings, bem_grid):.3g} µm)"
    lam = getattr(settings, "s_filter", None)
    if lam is None:
        what = "no S-filter"
        if not short and not getattr(settings, "topographies", ()):
            what += " (the simulated surfaces end at their shortest wavelength)"
        elif not short:
            what += " (the answer holds at the instrument's sampling)"
        return f"grid spacing {spacing}, {what}"
    text = f"grid spacing {spacing}, S-filter λs = {lam * 1e6:.3g} µm"
    if not short and _is_default(settings):
        text += " (the ISO 25178-3 default for this spacing: λs at least 3 spacings)"
    return text


def prepared_surface(settings: Any, surface: Any, factor: int = 1) -> Any:
    """``surface`` as the study solves it at ``factor`` × λs: the outlier points of a measured
    file replaced by the local median of their neighbours when ``settings.despike``, then the
    Gaussian S-filter at ``factor * settings.s_filter`` (non-periodic edges: the weights are
    renormalised over the measured area); unchanged without either."""
    if getattr(settings, "despike", False):
        surface = surface.despiked()
    lam = getattr(settings, "s_filter", None)
    if lam is not None:
        surface = surface.s_filter(factor * lam, periodic=False)
    return surface
