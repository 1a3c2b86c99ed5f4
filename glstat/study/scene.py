"""The scene of the study: the roughness that puts the asperity model at a given pressure level.

The paper (Bigerelle et al., Coatings 10(1):15, 2019) prints Rq = 50 µm on 1 mm², yet its mean
contact pressures (1.1–1.7 GPa) imply surface slopes about 30 times smaller than such surfaces
have (docs/method.md §10). The asperity model's mean contact pressure grows with the roughness
at fixed everything else (roughly in proportion to the slopes), so the roughness that gives a
requested pressure level is a one-dimensional root: :func:`rq_for_pressure` finds it on the
campaign's own surfaces, and :func:`scene_summary` states what a scene implies (rms slope,
attack angle tan β ≈ p_m / (c E*), asperities and grid points in contact).

Units are SI throughout: pressures in pascals, lengths in metres.
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from .campaign_settings import CampaignSettings, check_hurst, nyquist_terms, terms_of
from .scene_search import PressureAtRq, search_log_rq
from .surface_task import solve_asperity, weierstrass_surface

__all__ = ["RqSearch", "rq_for_pressure", "scene_summary"]

#: Default range of Rq searched by :func:`rq_for_pressure`, in metres (1 nm to 100 µm).
RQ_BOUNDS: tuple[float, float] = (1e-9, 1e-4)


@dataclass
class RqSearch:
    """What :func:`rq_for_pressure` found (``full_output=True``).

    Attributes
    ----------
    rq : tuple of float
        Rq in metres, one per Hurst exponent (all equal without ``per_hurst``).
    hurst : tuple of float
        The Hurst exponents.
    target : tuple of float
        Requested mean contact pressure per Hurst exponent, Pa.
    achieved : tuple of float
        Mean contact pressure at the returned Rq per Hurst exponent (mean over the seeds of
        the mean of the non-zero grid pressures), Pa.
    n_asperities, n_contact : tuple of float
        Mean number of asperities and of grid points in contact at the returned Rq.
    converged : bool
        Whether every root met the tolerance (``|log(achieved / target)| <= log(1 + rtol)``,
        for one Rq the mean of that log over H).
    rtol : float
        The relative tolerance on the mean pressure.
    grid, n_seeds : int
        Grid points per side and surfaces per Hurst exponent of the final evaluations.
    nominal_pressure : float
        The load, Pa.
    evaluations : list of dict
        Every evaluation: ``grid``, ``rq`` (m), ``hurst``, ``mean_pressure`` (Pa, per H),
        ``feasible`` (False when some surface cannot carry the load at that Rq).
    seconds : float
        Wall time of the search.
    """

    rq: tuple[float, ...]
    hurst: tuple[float, ...]
    target: tuple[float, ...]
    achieved: tuple[float, ...]
    n_asperities: tuple[float, ...]
    n_contact: tuple[float, ...]
    converged: bool
    rtol: float
    grid: int
    n_seeds: int
    nominal_pressure: float
    evaluations: list = field(default_factory=list)
    seconds: float = 0.0

    def summary(self):
        """One row per Hurst exponent: Rq (m), target and achieved mean pressure (Pa), their
        relative difference, asperities and grid points in contact (a pandas DataFrame)."""
        import pandas as pd

        return pd.DataFrame({
            "hurst": self.hurst, "rq_m": self.rq, "target_pa": self.target,
            "achieved_pa": self.achieved,
            "relative_error": [a / t - 1.0 for a, t in zip(self.achieved, self.target, strict=True)],
            "n_asperities": self.n_asperities, "n_contact": self.n_contact,
        })


def _settings_for(settings: CampaignSettings | None, hurst) -> tuple[CampaignSettings, list[int]]:
    """The settings and the indices of ``hurst`` in them. Exponents of the settings keep their
    index, hence the campaign's seeds and truncation; for others the settings are replaced by
    ones with exactly ``hurst`` (seeds of a campaign with those exponents)."""
    s = settings if settings is not None else CampaignSettings()
    if not isinstance(s, CampaignSettings):
        raise TypeError(f"settings must be a CampaignSettings, got {type(s).__name__}")
    if hurst is None:
        return s, list(range(len(s.hurst)))
    hs = check_hurst(tuple(float(v) for v in np.atleast_1d(np.asarray(hurst, dtype=float))))
    if all(h in s.hurst for h in hs):
        return s, [s.hurst.index(h) for h in hs]
    if len(set(s.n_terms)) != 1:
        raise ValueError(
            f"hurst {hs} are not all among the settings' exponents {s.hurst} and their n_terms "
            f"{s.n_terms} differ, so the truncation is undefined; add them to the settings"
        )
    s2 = dataclasses.replace(s, hurst=hs, n_terms=s.n_terms[:1], rq=s.rq_geometric_mean,
                             n_examples=0)
    return s2, list(range(len(hs)))


def _as_targets(target, n_h: int) -> np.ndarray:
    t = np.atleast_1d(np.asarray(target, dtype=float)).ravel()
    if t.size == 1:
        t = np.repeat(t, n_h)
    if t.size != n_h:
        raise ValueError(
            f"target_mean_pressure must be one value or one per Hurst exponent ({n_h}), got "
            f"{t.size} values"
        )
    bad = ~(np.isfinite(t) & (t > 0))
    if bad.any():
        raise ValueError(
            f"target_mean_pressure must be positive and finite (Pa), got {t[bad][0]!r}"
        )
    return t


def rq_for_pressure(
    target_mean_pressure: float | Sequence[float], hurst: float | Sequence[float] | None = None,
    *, settings: CampaignSettings | None = None, n_seeds: int = 3, per_hurst: bool = False,
    rtol: float = 0.03, rq_bounds: tuple[float, float] = RQ_BOUNDS, coarse_grid: int | None = 256,
    max_evaluations: int = 10, full_output: bool = False,
) -> float | tuple[float, ...] | RqSearch:
    """The roughness Rq at which the asperity model gives a requested mean contact pressure.

    The mean contact pressure of a surface is the mean of the non-zero grid pressures of
    :func:`contact.solve` (``ContactResult.mean_pressure``) on the campaign's Weierstrass
    surfaces — the same seeds (surfaces ``0 .. n_seeds-1`` of each H at the first load),
    truncation, grid, material and load as :func:`glstat.study.simulate_surface` — with only
    Rq changed; it is averaged over ``n_seeds`` surfaces. It grows with Rq at fixed everything
    else (roughly in proportion: the attack angles scale with Rq), so Rq is found by a short
    root find on log Rq: secant steps from the settings' Rq (starting from slope 1 in log-log),
    then Illinois regula falsi once the root is bracketed. With ``coarse_grid`` the first steps
    run on a coarser grid of the same band-limited surfaces; the answer is always that of the
    settings' grid.

    Parameters
    ----------
    target_mean_pressure : float or sequence of float
        Requested mean contact pressure in Pa, one value for every H or one per H (e.g.
        Table 1 of the paper: 1.724e9, 1.369e9, 1.108e9 Pa for H = 0, 0.5, 1).
    hurst : float or sequence of float, optional
        Hurst exponents (default: the settings'). Exponents of the settings keep their seeds
        and truncation (those of the campaign); otherwise the surfaces are those of a campaign
        with exactly these exponents (one truncation for all of them).
    settings : CampaignSettings, optional
        The campaign (default ``CampaignSettings()``); its ``rq`` is the starting point.
    n_seeds : int
        Surfaces per H averaged at every evaluation (default 3).
    per_hurst : bool
        One Rq per H, each matching its own target. Default: one Rq for all H, at which the
        mean over H of ``log(mean pressure / target)`` is 0 (the geometric mean of the
        achieved-to-target ratios is 1).
    rtol : float
        Relative tolerance on the mean pressure, in (0, 0.5): stop when
        ``|log(achieved / target)| <= log(1 + rtol)``. The mean pressure jumps when an asperity
        enters or leaves the contact, so with few seeds a tight tolerance may not be met; the
        closest evaluated Rq is then returned with a :class:`glstat.ConvergenceWarning`.
    rq_bounds : (float, float)
        Range of Rq searched, m (default 1 nm to 100 µm).
    coarse_grid : int or None
        Grid of the starting steps when the settings' grid is at least twice as fine and the
        truncation fits under its Nyquist limit; None to search on the settings' grid only.
    max_evaluations : int
        Evaluations on the settings' grid after the root is bracketed (each one solves
        ``n_seeds`` surfaces per H); the steps that bracket it are limited to three times as
        many.
    full_output : bool
        Return an :class:`RqSearch` with the achieved pressures, counts and every evaluation.

    Returns
    -------
    float, tuple of float or RqSearch
        Rq in metres: one float, or one per H (aligned with ``hurst``) with ``per_hurst``.

    Raises
    ------
    ValueError
        A target that is not positive and finite, or below the nominal pressure (the mean
        contact pressure is at least the nominal one); a target outside what Rq in
        ``rq_bounds`` reaches (the message gives the target and the reachable range: below
        its lower end the surfaces cannot carry the load, above its upper end Rq would exceed
        the bound); bad ``n_seeds``, ``rtol`` or ``rq_bounds``.

    Warns
    -----
    glstat.ConvergenceWarning
        The tolerance was not met within ``max_evaluations`` (a jump of the mean pressure).

    Examples
    --------
    >>> from glstat.study import CampaignSettings
    >>> from glstat.study.scene import rq_for_pressure
    >>> s = CampaignSettings(grid=256)
    >>> rq = rq_for_pressure(1.5e9, settings=s, n_seeds=2)
    >>> 0.5e-6 < rq < 5e-6
    True
    """
    t0 = time.perf_counter()
    s, idx, n_seeds, rtol, bounds, targets = _checked_search(
        target_mean_pressure, hurst, settings, n_seeds, rtol, rq_bounds)
    load = s.pressures[0]
    record: list = []
    rq_out, ach, na, nc, converged = _search_groups(
        s, idx, targets, n_seeds, per_hurst, math.log1p(rtol), bounds,
        _coarse_grid(s, idx, coarse_grid), max_evaluations, record)
    hs = tuple(s.hurst[i] for i in idx)
    if not converged:
        _warn_not_converged(rtol, hs, ach, targets)
    out = RqSearch(rq=tuple(rq_out), hurst=hs, target=tuple(float(v) for v in targets),
                   achieved=tuple(ach), n_asperities=tuple(na), n_contact=tuple(nc),
                   converged=bool(converged), rtol=float(rtol), grid=s.grid, n_seeds=n_seeds,
                   nominal_pressure=load, evaluations=record, seconds=time.perf_counter() - t0)
    if full_output:
        return out
    return out.rq if per_hurst else out.rq[0]


def _checked_search(target_mean_pressure, hurst, settings, n_seeds, rtol, rq_bounds):
    """The checked arguments of :func:`rq_for_pressure`: the settings, the indices of the
    searched exponents in them, ``n_seeds``, ``rtol``, the Rq bounds (m) and one target per
    exponent (Pa), each target above the nominal pressure."""
    from _glstat_runtime.validation import positive_integer, tolerance

    s, idx = _settings_for(settings, hurst)
    n_seeds = positive_integer(n_seeds, "n_seeds", "surfaces per Hurst exponent")
    rtol = tolerance(rtol, "rtol", 0.5)
    bounds = _as_bounds(rq_bounds)
    targets = _as_targets(target_mean_pressure, len(idx))
    load = s.pressures[0]
    if (targets <= load).any():
        t = targets[targets <= load][0]
        raise ValueError(
            f"target mean contact pressure {t / 1e6:.6g} MPa is unreachable: the mean pressure "
            f"over the points in contact is at least the nominal pressure {load / 1e6:.6g} MPa "
            "(the contact area cannot exceed the nominal area)"
        )
    return s, idx, n_seeds, rtol, bounds, targets


def _search_groups(s, idx, targets, n_seeds, per_hurst, tol, bounds, coarse_n, max_evaluations,
                   record):
    """One root find per group of exponents (each H alone with ``per_hurst``, else all of them
    at one Rq); every evaluation is appended to ``record``. Returns, per searched exponent,
    Rq (m), the achieved mean pressure (Pa), the asperities and grid points in contact, and
    whether every root met the tolerance."""
    load = s.pressures[0]
    # groups of positions k in idx solved together (one Rq each)
    groups = [[k] for k in range(len(idx))] if per_hurst else [list(range(len(idx)))]
    n = len(idx)
    rq_out, ach, na, nc = [math.nan] * n, [math.nan] * n, [math.nan] * n, [math.nan] * n
    converged = True
    for ks in groups:
        fine = PressureAtRq(s, [idx[k] for k in ks], 0, n_seeds, s.grid, load, record)
        start = math.exp(float(np.mean([math.log(s.rq_of(idx[k])) for k in ks])))
        x, ok = search_log_rq(fine, targets[ks], start, bounds, coarse_n, tol, max_evaluations)
        converged &= ok
        p, a_, c_, _ = fine(math.exp(x))  # cached: the evaluation that gave x
        for j, k in enumerate(ks):
            rq_out[k] = math.exp(x)
            ach[k], na[k], nc[k] = p[j], a_[j], c_[j]
    return rq_out, ach, na, nc, converged


def _warn_not_converged(rtol, hs, achieved, targets) -> None:
    """The :class:`glstat.ConvergenceWarning` of :func:`rq_for_pressure`, attributed to its
    caller."""
    warnings.warn(
        "rq_for_pressure: the mean contact pressure at the returned Rq differs from the "
        "target by more than rtol = " + f"{rtol:g} (" + ", ".join(
            f"H = {h:g}: {a / 1e6:.6g} vs {t / 1e6:.6g} MPa"
            for h, a, t in zip(hs, achieved, targets, strict=True))
        + "); the mean pressure jumps when an asperity enters or leaves the contact: "
        "average more surfaces (n_seeds) or loosen rtol",
        _convergence_warning(), stacklevel=3)


def _as_bounds(rq_bounds) -> tuple[float, float]:
    """``rq_bounds`` as (low, high) floats, 0 < low < high, in metres."""
    lo_b, hi_b = (float(v) for v in rq_bounds)
    if not (math.isfinite(lo_b) and math.isfinite(hi_b) and 0 < lo_b < hi_b):
        raise ValueError(f"rq_bounds must be 0 < low < high (m), got {rq_bounds!r}")
    return lo_b, hi_b


def _coarse_grid(s: CampaignSettings, idx: list[int], coarse_grid: int | None) -> int | None:
    """The grid of the starting steps: ``coarse_grid`` when the settings' grid is at least
    twice as fine and the truncation of every searched H fits under its Nyquist limit."""
    if coarse_grid is None:
        return None
    n = int(coarse_grid)
    if s.grid < 2 * n:
        return None
    limit = nyquist_terms(n, s.length, s.gamma)
    terms = [s.n_terms[i] for i in idx]
    return n if all(nt is not None and nt <= limit for nt in terms) else None


def _convergence_warning():
    from ..errors import ConvergenceWarning

    return ConvergenceWarning


def _expected_slope_ratio(settings: CampaignSettings, ih: int) -> float:
    """Expected rms gradient over rms height of the truncated Weierstrass series (random
    N(0,1) amplitudes and uniform phases), 1/m."""
    k = settings.gamma ** np.arange(terms_of(settings, ih))
    h = settings.hurst[ih]
    amp2 = np.outer(k, k) / (k[:, None] ** 2 + k[None, :] ** 2) ** (h + 1)
    grad2 = (2 * math.pi / settings.length) ** 2 * (k[:, None] ** 2 + k[None, :] ** 2)
    return float(math.sqrt((amp2 * grad2).sum() / amp2.sum()))


def scene_summary(settings: CampaignSettings | None = None, *, n_seeds: int = 3,
                  paper_pressures: dict[float, float] | None = None, solve: bool = True):
    """What a scene implies: slopes, attack angles, pressures and counts, per Hurst exponent.

    Parameters
    ----------
    settings : CampaignSettings, optional
        The scene (default ``CampaignSettings()``, Rq = 1.6 µm on 1 mm², 1024², 6 terms).
    n_seeds : int
        Campaign surfaces per H measured (the first ones at the first load).
    paper_pressures : dict, optional
        ``{H: mean contact pressure in Pa}`` to compare with (default: Table 1 of the paper,
        :data:`glstat.study.paper.TABLE1`).
    solve : bool
        Also solve the contact on the surfaces (mean pressure, counts); False gives the
        geometry only.

    Returns
    -------
    pandas.DataFrame
        One row per H: ``hurst``, ``rq_m``, ``n_terms``, ``shortest_wavelength_m``,
        ``rms_slope`` (measured: root mean square of the height gradient on the grid, mean
        over the surfaces), ``rms_slope_expected`` (its expectation over the random
        coefficients, from the series), ``e_star_pa``, ``cone_factor``,
        ``mean_pressure_pa`` (asperity model, mean over the surfaces), ``tan_beta_implied``
        (= mean pressure / (c E*), the attack angle that pressure implies since the mean of
        ``1.5 p_m sqrt(1 - r²)`` over an ellipse is ``p_m``), ``tan_beta_asperities``
        (mean tan β of the asperities in contact), ``n_asperities``, ``n_contact`` (grid
        points in contact), ``paper_mean_pressure_pa`` and ``paper_tan_beta`` (the paper's
        pressure and the attack angle it implies with these settings' c and E*) and
        ``rms_slope_over_paper_tan_beta``.

    Examples
    --------
    >>> from glstat.study import CampaignSettings
    >>> from glstat.study.scene import scene_summary
    >>> t = scene_summary(CampaignSettings(grid=256), n_seeds=1, solve=False)
    >>> [round(v, 3) for v in t["paper_tan_beta"]]
    [0.037, 0.03, 0.024]
    """
    import pandas as pd

    import contact
    from _glstat_runtime.validation import positive_integer

    s = settings if settings is not None else CampaignSettings()
    n_seeds = positive_integer(n_seeds, "n_seeds", "surfaces per Hurst exponent")
    if paper_pressures is None:
        from .paper_table import TABLE1

        paper_pressures = {r.hurst: r.mean_mpa * 1e6 for r in TABLE1}
    e_star = contact.effective_modulus(s.E, s.nu)
    ce = s.cone_factor * e_star
    nan = math.nan
    rows = []
    for ih, h in enumerate(s.hurst):
        m = _measure_scene(s, ih, n_seeds, solve)
        pp = paper_pressures.get(float(h), math.nan)
        row = {
            "hurst": h, "rq_m": s.rq_of(ih), "n_terms": terms_of(s, ih),
            "shortest_wavelength_m": 1.0 / s.max_frequency(ih),
            "rms_slope": float(np.mean(m["slope"])),
            "rms_slope_expected": s.rq_of(ih) * _expected_slope_ratio(s, ih),
            "e_star_pa": e_star, "cone_factor": s.cone_factor,
            "mean_pressure_pa": float(np.mean(m["mean_pressure"])) if solve else nan,
            "tan_beta_implied": float(np.mean(m["mean_pressure"])) / ce if solve else nan,
            "tan_beta_asperities": float(np.mean(m["tan_beta"])) if solve else nan,
            "n_asperities": float(np.mean(m["n_asperities"])) if solve else nan,
            "n_contact": float(np.mean(m["n_contact"])) if solve else nan,
            "paper_mean_pressure_pa": pp, "paper_tan_beta": pp / ce,
        }
        row["rms_slope_over_paper_tan_beta"] = row["rms_slope"] / row["paper_tan_beta"]
        rows.append(row)
    return pd.DataFrame(rows)


def _measure_scene(s: CampaignSettings, ih: int, n_seeds: int, solve: bool) -> dict[str, list]:
    """Per campaign surface 0 .. n_seeds-1 of Hurst exponent number ``ih`` at the first load:
    the rms slope of its heights on the grid and, with ``solve``, its mean contact pressure
    (Pa), mean tan β of the asperities in contact, asperities and grid points in contact."""
    out: dict[str, list] = {"slope": [], "mean_pressure": [], "tan_beta": [], "n_asperities": [],
                            "n_contact": []}
    for i in range(n_seeds):
        surf = weierstrass_surface(s, ih, 0, i)
        gx, gy = np.gradient(surf.heights, surf.dx, surf.dy)
        out["slope"].append(math.sqrt(float(np.mean(gx * gx + gy * gy))))
        if solve:
            res = solve_asperity(s, surf, s.pressures[0])
            out["mean_pressure"].append(res.mean_pressure)
            out["tan_beta"].append(float(np.mean(np.tan(res.asperities["beta"].to_numpy(float)))))
            out["n_asperities"].append(len(res.asperities))
            out["n_contact"].append(int(np.count_nonzero(res.pressure > 0)))
    return out
