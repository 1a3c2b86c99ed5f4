"""One surface of a campaign, simulated: the surface (a Weierstrass surface of its own seed, or a
measured file), its contact with a rigid flat under the asperity model (:func:`contact.solve`),
and the arrays stored for it (:func:`simulate_surface`, the task a campaign runs on its
workers)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .campaign_settings import CampaignSettings
from .scales import prepared_surface
from .topography import measured_rq, measured_surface

__all__ = [
    "MEASURED_PARAMETERS",
    "campaign_surface",
    "quality_arrays",
    "raw_surface",
    "simulate_surface",
    "solve_asperity",
    "weierstrass_surface",
]

#: ISO 25178 parameters stored for every measured surface (``iso_<name>``).
MEASURED_PARAMETERS = ("Sq", "Ssk", "Sku", "Sdq", "Sp", "Sv", "hurst")


def weierstrass_surface(settings: CampaignSettings, ih: int, il: int, i: int, *,
                        rq: float | None = None, grid: int | None = None, pad: int = 0) -> Any:
    """The Weierstrass surface of seed ``settings.seed_sequence(ih, il, i)`` (a
    :class:`contact.Surface`, metres).

    Parameters
    ----------
    settings : CampaignSettings
    ih, il, i : int
        Hurst exponent number, load number and surface number.
    rq : float, optional
        RMS roughness in metres instead of the settings'.
    grid : int, optional
        Grid points per side of a square grid instead of the settings' (the same band-limited
        surface sampled on another grid when the truncation fits under its Nyquist limit).
        Without it the surface has the settings' grid ``shape`` and side lengths ``size``,
        rectangular or square.
    pad : int, default 0
        A guard band of ``pad`` points on every side (``contact.weierstrass(pad=...)``): the
        central part is the surface without it.
    """
    import contact

    rng = np.random.default_rng(settings.seed_sequence(ih, il, i))
    shape = settings.shape if grid is None else (grid, grid)
    length = settings.size if grid is None else settings.length
    return contact.weierstrass(shape, length, settings.hurst[ih], settings.gamma,
                               rq=settings.rq_of(ih) if rq is None else rq, rng=rng,
                               n_terms=settings.n_terms[ih], pad=pad)


def raw_surface(settings: CampaignSettings, ih: int, il: int, i: int) -> Any:
    """Surface i of (H index ``ih``, load index ``il``) before its scale is set: measured
    surface i (a file, or an area of one, its form removed:
    :func:`glstat.study.topography.measured_surface`), or the Weierstrass surface of seed
    ``settings.seed_sequence(ih, il, i)`` (a :class:`contact.Surface`, metres)."""
    if settings.measured:
        return measured_surface(settings, i)
    return weierstrass_surface(settings, ih, il, i)


def campaign_surface(settings: CampaignSettings, ih: int, il: int, i: int) -> Any:
    """Surface i of (H index ``ih``, load index ``il``) as the study solves it: the
    :func:`raw_surface` at the study's scale (outliers replaced with ``despike``, then the
    S-filter: :func:`glstat.study.scales.prepared_surface`)."""
    return prepared_surface(settings, raw_surface(settings, ih, il, i))


def solve_asperity(settings: CampaignSettings, surface: Any, load: float) -> Any:
    """:func:`contact.solve` of ``surface`` at the nominal pressure ``load`` (Pa) with the
    settings' material and cone factor, without its per-surface :class:`contact.ContactWarning`
    (a load inside a jump of the model's force is recorded in the result's ``info``; no
    warning filter is touched, so this is safe in worker threads)."""
    import contact

    return contact.solve(surface, load, settings.E, settings.nu, settings.cone_factor, warn=False)


def _contact_arrays(res: Any) -> dict[str, Any]:
    """The stored arrays of one solve (see :func:`simulate_surface`)."""
    import contact

    asp = res.asperities
    p = res.pressure
    spots = contact.contact_spots(res)
    return {
        "samples": p[p > 0].astype(np.float64),
        "spot_peak": spots.peak_pressure.astype(np.float64),
        "n_spots": np.int64(spots.n_spots),
        "asperity_peak": 1.5 * asp["p_m"].to_numpy(dtype=float),
        "asperity_p_m": asp["p_m"].to_numpy(dtype=float),
        "asperity_beta": asp["beta"].to_numpy(dtype=float),
        "asperity_a": asp["a"].to_numpy(dtype=float),
        "asperity_b": asp["b"].to_numpy(dtype=float),
        "max_pressure": np.float64(res.max_pressure),
        "mean_pressure": np.float64(res.mean_pressure),
        "alpha": np.float64(res.alpha),
        "n_contact": np.int64(np.count_nonzero(p > 0)),
        "n_points": np.int64(p.size),
        "n_asperities": np.int64(len(asp)),
        "separation": np.float64(res.separation),
        "force_error": np.float64(res.force_error),
        "in_jump": np.int64(bool(res.info.get("in_jump", False))),
        "force_jump": np.float64(abs(res.info.get("force_jump", 0.0))),
    }


def _measured_arrays(surface: Any) -> dict[str, Any]:
    """The ISO 25178 parameters of a measured file (its form removed, at the study's scale) and
    the fraction of its points that were not measured."""
    iso = surface.roughness(level="mean", warn=False)
    out = {f"iso_{k}": np.float64(iso[k]) for k in MEASURED_PARAMETERS}
    out["masked_fraction"] = np.float64(0.0 if surface.mask is None else np.mean(surface.mask))
    return out


def quality_arrays(raw: Any) -> dict[str, Any]:
    """The data quality of a measured surface as read (its form removed, before despiking and
    filtering): ``spike_count`` (outlier points, :func:`contact.find_spikes`),
    ``spike_clusters``, ``spike_positions`` (grid indices, shape (n, 2)),
    ``spike_largest`` (m, the largest outlier's height above or below its neighbourhood, 0
    without any), ``height_step`` (m, the smallest step between stored heights) and
    ``steps_per_sq`` (Sq over that step: few steps mean quantised heights)."""
    from contact.quality import height_steps

    spikes = raw.spikes()
    steps = height_steps(raw)
    res = np.abs(np.asarray(spikes.residuals, dtype=float))
    return {"spike_count": np.int64(spikes.count), "spike_clusters": np.int64(spikes.n_clusters),
            "spike_positions": np.asarray(spikes.indices, dtype=np.int64).reshape(-1, 2),
            "spike_largest": np.float64(res.max() if res.size else 0.0),
            "height_step": np.float64(steps.step), "steps_per_sq": np.float64(steps.steps_per_sq)}


def simulate_surface(settings: CampaignSettings, ih: int, il: int, i: int) -> dict[str, np.ndarray]:
    """Generate and solve one surface (a campaign task; runs on a worker).

    Returns
    -------
    dict of ndarray
        ``samples`` (non-zero grid pressures, Pa, row-major order), ``spot_peak`` (the
        largest pressure of every 8-connected contact spot of the pressure map, Pa, in the
        order of :func:`contact.contact_spots`), ``n_spots``, ``asperity_peak``
        (``1.5 p_m`` per asperity in contact, Pa), ``asperity_p_m``, ``asperity_beta`` (rad),
        ``asperity_a``, ``asperity_b`` (m), and scalars ``max_pressure``, ``mean_pressure``
        (Pa), ``alpha``, ``n_contact``, ``n_points``, ``n_asperities``, ``separation`` (m),
        ``force_error``, ``in_jump`` (1 when the load fell inside a jump of the model's force,
        whose relative size is ``force_jump``), ``rq`` (m, achieved); for example surfaces also
        ``heights`` (m) and
        ``pressure`` (Pa) maps as float32.
    """
    raw = raw_surface(settings, ih, il, i)
    surf = prepared_surface(settings, raw)
    # a load inside a jump of the model's force is recorded per surface (in_jump,
    # force_jump) and summarised once in the report, rather than warned about per surface
    res = solve_asperity(settings, surf, settings.pressures[il])
    out = _contact_arrays(res)
    out["rq"] = np.float64(measured_rq(surf))
    if settings.measured:
        out.update(_measured_arrays(surf))
        out.update(quality_arrays(raw))
    if i < settings.n_examples:
        out["heights"] = surf.heights.astype(np.float32)
        out["pressure"] = res.pressure.astype(np.float32)
    return out
