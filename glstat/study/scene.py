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

from .campaign import CampaignSettings, nyquist_terms

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


class _Unreachable(Exception):
    pass


def _settings_for(settings: CampaignSettings | None, hurst) -> tuple[CampaignSettings, list[int]]:
    """The settings and the indices of ``hurst`` in them. Exponents of the settings keep their
    index, hence the campaign's seeds and truncation; for others the settings are replaced by
    ones with exactly ``hurst`` (seeds of a campaign with those exponents)."""
    s = settings if settings is not None else CampaignSettings()
    if not isinstance(s, CampaignSettings):
        raise TypeError(f"settings must be a CampaignSettings, got {type(s).__name__}")
    if hurst is None:
        return s, list(range(len(s.hurst)))
    hs = tuple(float(v) for v in np.atleast_1d(np.asarray(hurst, dtype=float)))
    if len(set(hs)) != len(hs):
        raise ValueError(f"hurst exponents must be distinct, got {hs!r}")
    if all(h in s.hurst for h in hs):
        return s, [s.hurst.index(h) for h in hs]
    if len(set(s.n_terms)) != 1:
        raise ValueError(
            f"hurst {hs} are not all among the settings' exponents {s.hurst} and their n_terms "
            f"{s.n_terms} differ, so the truncation is undefined; add them to the settings"
        )
    s2 = dataclasses.replace(s, hurst=hs, n_terms=s.n_terms[:1], n_examples=0)
    return s2, list(range(len(hs)))


def _solve_one(settings: CampaignSettings, ih: int, il: int, i: int, rq: float, grid: int,
               load: float):
    """Mean pressure (Pa), asperities and points in contact of surface i at this Rq and grid;
    None when the surface cannot carry the load."""
    import contact

    rng = np.random.default_rng(settings.seed_sequence(ih, il, i))
    surf = contact.weierstrass((grid, grid), settings.length, settings.hurst[ih], settings.gamma,
                               rq=rq, rng=rng, n_terms=settings.n_terms[ih])
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", contact.ContactWarning)
            res = contact.solve(surf, load, settings.E, settings.nu, settings.cone_factor)
    except ValueError as exc:
        if "unreachable" in str(exc):
            return None
        raise
    p = res.pressure
    return float(res.mean_pressure), len(res.asperities), int(np.count_nonzero(p > 0))


class _Evaluator:
    """Mean contact pressure per H at a given Rq (cached), on one grid."""

    def __init__(self, settings, ihs, il, n_seeds, grid, load, record):
        self.s, self.ihs, self.il, self.n, self.grid, self.load = (settings, ihs, il, n_seeds,
                                                                   grid, load)
        self.cache: dict[float, tuple] = {}
        self.record = record

    def __call__(self, rq: float):
        if rq in self.cache:
            return self.cache[rq]
        p, na, nc, ok = [], [], [], True
        for ih in self.ihs:
            out = [_solve_one(self.s, ih, self.il, i, rq, self.grid, self.load)
                   for i in range(self.n)]
            if any(o is None for o in out):
                ok = False
                p.append(math.nan)
                na.append(math.nan)
                nc.append(math.nan)
                continue
            p.append(float(np.mean([o[0] for o in out])))
            na.append(float(np.mean([o[1] for o in out])))
            nc.append(float(np.mean([o[2] for o in out])))
        val = (tuple(p), tuple(na), tuple(nc), ok)
        self.cache[rq] = val
        self.record.append({"grid": self.grid, "rq": rq, "hurst": tuple(self.s.hurst[i] for i in self.ihs),
                            "mean_pressure": tuple(p), "feasible": ok})
        return val


def _root(ev: _Evaluator, targets: np.ndarray, x0: float, bounds: tuple[float, float],
          tol: float, max_eval: int):
    """Find log Rq with mean_H log(p_H / t_H) = 0 (|.| <= tol) by a safeguarded secant on
    log Rq (slope 1 to start: p roughly proportional to Rq), then Illinois regula falsi.

    Returns (x, g, converged); raises _Unreachable(side, info) when the target lies outside
    what ``bounds`` reach.
    """
    lo_b, hi_b = math.log(bounds[0]), math.log(bounds[1])

    def g(x):
        p, _, _, ok = ev(math.exp(x))
        if not ok:
            return -math.inf  # the load is not carried: Rq too small
        return float(np.mean(np.log(np.asarray(p) / targets)))

    n_eval = 0
    x = min(max(x0, lo_b), hi_b)
    gx = g(x)
    n_eval += 1
    best = (abs(gx), x, gx)
    if abs(gx) <= tol:
        return x, gx, True
    slope = 1.0
    a = b = None  # bracket: g(a) < 0 < g(b)
    if gx < 0:
        a, ga = x, gx
    else:
        b, gb = x, gx
    # expand from x until the root is bracketed
    while a is None or b is None:
        if not math.isfinite(gx):
            step = math.log(10.0)
        else:
            step = min(max(-gx / slope, -math.log(30.0)), math.log(30.0))
        if gx < 0:
            step = max(step, 0.02)
        else:
            step = min(step, -0.02)
        xn = min(max(x + step, lo_b), hi_b)
        if xn == x:
            raise _Unreachable("above" if gx < 0 else "below", x)
        gn = g(xn)
        n_eval += 1
        if math.isfinite(gn) and math.isfinite(gx) and gn != gx:
            slope = min(max((gn - gx) / (xn - x), 0.2), 5.0)
        x, gx = xn, gn
        if abs(gx) < best[0]:
            best = (abs(gx), x, gx)
        if abs(gx) <= tol:
            return x, gx, True
        if gx < 0:
            a, ga = x, gx
        else:
            b, gb = x, gx
        if n_eval >= 3 * max_eval:
            break
    if a is None or b is None:
        return best[1], best[2], False
    # Illinois regula falsi on the bracket (bisection while an end is infeasible)
    side, n_rf = 0, 0
    while n_rf < max_eval or not math.isfinite(ga):
        if abs(b - a) <= 1e-7:
            break
        if not math.isfinite(ga) and abs(b - a) < 1e-3:
            # the root sits at the smallest Rq that carries the load: the target is lower
            # than any mean pressure the model reaches
            raise _Unreachable("below", b)
        if math.isfinite(ga):
            x = (a * gb - b * ga) / (gb - ga)
            if not (min(a, b) < x < max(a, b)):
                x = 0.5 * (a + b)
        else:
            x = 0.5 * (a + b)
        gx = g(x)
        n_rf += 1
        if abs(gx) < best[0]:
            best = (abs(gx), x, gx)
        if abs(gx) <= tol:
            return x, gx, True
        if gx < 0:
            a, ga = x, gx
            if side == -1:
                gb *= 0.5
            side = -1
        else:
            b, gb = x, gx
            if side == 1 and math.isfinite(ga):
                ga *= 0.5
            side = 1
    return best[1], best[2], False


def _unreachable_message(ev: _Evaluator, targets, side: str, rq_end: float,
                         bounds: tuple[float, float], load: float) -> str:
    """The error message of an unreachable target: the target and the reachable range."""
    s = ev.s
    hs = ", ".join(f"{s.hurst[i]:g}" for i in ev.ihs)
    tstr = ", ".join(f"{v / 1e6:.6g}" for v in targets)
    many = len(ev.ihs) > 1

    def pm(rq):
        p, _, _, ok = ev(rq)
        return float(np.exp(np.mean(np.log(p)))) if ok else math.nan

    what = (f"{'geometric mean over the H of the ' if many else ''}mean over {ev.n} "
            f"surface(s), {ev.grid}² grid")
    p_end = pm(rq_end)
    if side == "above":
        low = ev.cache.get(bounds[0])
        if low is not None and low[3]:
            start = f"runs from {pm(bounds[0]) / 1e6:.6g} MPa at Rq = {bounds[0]:.3g} m"
        else:  # not evaluated (solves with nearly the whole surface in contact are slow)
            start = (f"is never below the nominal {load / 1e6:.6g} MPa (approached as nearly "
                     "the whole surface comes into contact at small Rq)")
        return (
            f"target mean contact pressure {tstr} MPa (H = {hs}) is above the reachable range: "
            f"with Rq in [{bounds[0]:.3g}, {bounds[1]:.3g}] m the asperity model's mean contact "
            f"pressure ({what}) {start} and reaches at most {p_end / 1e6:.6g} MPa at "
            f"Rq = {rq_end:.3g} m; raise rq_bounds[1] or lower the target"
        )
    p_top = pm(bounds[1])
    why = ("smaller Rq cannot carry the load" if rq_end > bounds[0] * (1 + 1e-9)
           else "the lower end of rq_bounds")
    return (
        f"target mean contact pressure {tstr} MPa (H = {hs}) is below the reachable range: the "
        f"asperity model's mean contact pressure ({what}) runs from {p_end / 1e6:.6g} MPa at "
        f"Rq = {rq_end:.3g} m ({why}) up to {p_top / 1e6:.6g} MPa at Rq = {bounds[1]:.3g} m; "
        "lower rq_bounds[0] or raise the target"
    )


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
    target_mean_pressure: float | Sequence[float],
    hurst: float | Sequence[float] | None = None,
    *,
    settings: CampaignSettings | None = None,
    n_seeds: int = 3,
    per_hurst: bool = False,
    rtol: float = 0.03,
    rq_bounds: tuple[float, float] = RQ_BOUNDS,
    coarse_grid: int | None = 256,
    max_evaluations: int = 10,
    full_output: bool = False,
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
    s, idx = _settings_for(settings, hurst)
    if isinstance(n_seeds, bool) or int(n_seeds) != n_seeds or n_seeds < 1:
        raise ValueError(f"n_seeds must be a positive integer, got {n_seeds!r}")
    n_seeds = int(n_seeds)
    if not (isinstance(rtol, int | float) and 0 < rtol < 0.5):
        raise ValueError(f"rtol must be in (0, 0.5), got {rtol!r}")
    lo_b, hi_b = (float(v) for v in rq_bounds)
    if not (math.isfinite(lo_b) and math.isfinite(hi_b) and 0 < lo_b < hi_b):
        raise ValueError(f"rq_bounds must be 0 < low < high (m), got {rq_bounds!r}")
    targets = _as_targets(target_mean_pressure, len(idx))
    load = s.pressures[0]
    if (targets <= load).any():
        t = targets[targets <= load][0]
        raise ValueError(
            f"target mean contact pressure {t / 1e6:.6g} MPa is unreachable: the mean pressure "
            f"over the points in contact is at least the nominal pressure {load / 1e6:.6g} MPa "
            "(the contact area cannot exceed the nominal area)"
        )
    tol = math.log1p(rtol)
    record: list = []
    # groups of positions k in idx solved together (one Rq each)
    groups = [[k] for k in range(len(idx))] if per_hurst else [list(range(len(idx)))]
    coarse_n = None if coarse_grid is None else int(coarse_grid)
    if coarse_n is not None and not (
            s.grid >= 2 * coarse_n
            and all(nt is not None and nt <= nyquist_terms(coarse_n, s.length, s.gamma)
                    for nt in (s.n_terms[i] for i in idx))):
        coarse_n = None
    n = len(idx)
    rq_out, ach, na, nc = [math.nan] * n, [math.nan] * n, [math.nan] * n, [math.nan] * n
    converged = True
    for ks in groups:
        ihs = [idx[k] for k in ks]
        tg = targets[ks]
        x0 = math.log(min(max(s.rq, lo_b), hi_b))
        fine = _Evaluator(s, ihs, 0, n_seeds, s.grid, load, record)
        try:
            if coarse_n is not None:
                coarse = _Evaluator(s, ihs, 0, n_seeds, coarse_n, load, record)
                try:
                    x0, _, _ = _root(coarse, tg, x0, (lo_b, hi_b), 2 * tol, 3)
                except _Unreachable:
                    pass  # decided on the settings' grid
            x, _, ok = _root(fine, tg, x0, (lo_b, hi_b), tol, max_evaluations)
        except _Unreachable as exc:
            side, x_end = exc.args
            raise ValueError(_unreachable_message(fine, tg, side, math.exp(x_end), (lo_b, hi_b),
                                                  load)) from None
        converged &= ok
        p, a_, c_, _ = fine(math.exp(x))  # cached: the evaluation that gave x
        for j, k in enumerate(ks):
            rq_out[k] = math.exp(x)
            ach[k], na[k], nc[k] = p[j], a_[j], c_[j]
    hs = tuple(s.hurst[i] for i in idx)
    if not converged:
        warnings.warn(
            "rq_for_pressure: the mean contact pressure at the returned Rq differs from the "
            "target by more than rtol = " + f"{rtol:g} (" + ", ".join(
                f"H = {h:g}: {a / 1e6:.6g} vs {t / 1e6:.6g} MPa"
                for h, a, t in zip(hs, ach, targets, strict=True))
            + "); the mean pressure jumps when an asperity enters or leaves the contact: "
            "average more surfaces (n_seeds) or loosen rtol",
            _convergence_warning(), stacklevel=2)
    out = RqSearch(rq=tuple(rq_out), hurst=hs, target=tuple(float(v) for v in targets),
                   achieved=tuple(ach), n_asperities=tuple(na), n_contact=tuple(nc),
                   converged=bool(converged), rtol=float(rtol), grid=s.grid, n_seeds=n_seeds,
                   nominal_pressure=load, evaluations=record, seconds=time.perf_counter() - t0)
    if full_output:
        return out
    return out.rq if per_hurst else out.rq[0]


def _convergence_warning():
    from ..errors import ConvergenceWarning

    return ConvergenceWarning


def _expected_slope_ratio(settings: CampaignSettings, ih: int) -> float:
    """Expected rms gradient over rms height of the truncated Weierstrass series (random
    N(0,1) amplitudes and uniform phases), 1/m."""
    nt = settings.n_terms[ih]
    if nt is None:
        nt = nyquist_terms(settings.grid, settings.length, settings.gamma)
    k = settings.gamma ** np.arange(nt)
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

    s = settings if settings is not None else CampaignSettings()
    if isinstance(n_seeds, bool) or int(n_seeds) != n_seeds or n_seeds < 1:
        raise ValueError(f"n_seeds must be a positive integer, got {n_seeds!r}")
    if paper_pressures is None:
        from .paper import TABLE1

        paper_pressures = {r.hurst: r.mean_mpa * 1e6 for r in TABLE1}
    e_star = contact.effective_modulus(s.E, s.nu)
    ce = s.cone_factor * e_star
    rows = []
    for ih, h in enumerate(s.hurst):
        slopes, mp, tb, na, nc = [], [], [], [], []
        for i in range(int(n_seeds)):
            rng = np.random.default_rng(s.seed_sequence(ih, 0, i))
            surf = contact.weierstrass((s.grid, s.grid), s.length, h, s.gamma, rq=s.rq, rng=rng,
                                       n_terms=s.n_terms[ih])
            gx, gy = np.gradient(surf.heights, surf.dx, surf.dy)
            slopes.append(math.sqrt(float(np.mean(gx * gx + gy * gy))))
            if solve:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", contact.ContactWarning)
                    res = contact.solve(surf, s.pressures[0], s.E, s.nu, s.cone_factor)
                mp.append(res.mean_pressure)
                tb.append(float(np.mean(np.tan(res.asperities["beta"].to_numpy(float)))))
                na.append(len(res.asperities))
                nc.append(int(np.count_nonzero(res.pressure > 0)))
        nt = s.n_terms[ih]
        if nt is None:
            nt = nyquist_terms(s.grid, s.length, s.gamma)
        pp = paper_pressures.get(float(h), math.nan)
        row = {
            "hurst": h, "rq_m": s.rq, "n_terms": nt,
            "shortest_wavelength_m": 1.0 / s.max_frequency(ih),
            "rms_slope": float(np.mean(slopes)),
            "rms_slope_expected": s.rq * _expected_slope_ratio(s, ih),
            "e_star_pa": e_star, "cone_factor": s.cone_factor,
            "mean_pressure_pa": float(np.mean(mp)) if solve else math.nan,
            "tan_beta_implied": float(np.mean(mp)) / ce if solve else math.nan,
            "tan_beta_asperities": float(np.mean(tb)) if solve else math.nan,
            "n_asperities": float(np.mean(na)) if solve else math.nan,
            "n_contact": float(np.mean(nc)) if solve else math.nan,
            "paper_mean_pressure_pa": pp, "paper_tan_beta": pp / ce,
        }
        row["rms_slope_over_paper_tan_beta"] = row["rms_slope"] / row["paper_tan_beta"]
        rows.append(row)
    return pd.DataFrame(rows)
