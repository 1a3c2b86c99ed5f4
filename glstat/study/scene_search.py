"""The root search of :func:`glstat.study.scene.rq_for_pressure`: the asperity model's mean
contact pressure per Hurst exponent at a given Rq, on the campaign's own surfaces (cached per
Rq and grid, :class:`PressureAtRq`), and the Rq at which it meets a target
(:func:`search_log_rq`): a safeguarded secant on log Rq that brackets the root, then Illinois
regula falsi, optionally started on a coarser grid; a target out of reach is a ValueError that
gives the reachable range.

Units are SI: pressures in pascals, Rq in metres (the search runs on its natural logarithm).
"""

from __future__ import annotations

import contextlib
import math

import numpy as np

from .campaign_settings import CampaignSettings
from .surface_task import solve_asperity, weierstrass_surface

__all__ = ["PressureAtRq", "search_log_rq"]


class _Unreachable(Exception):
    """The target lies outside what the searched range of Rq reaches: ``args = (side, x)``,
    side ``"above"`` or ``"below"`` the reachable range and x the log Rq where it ends."""


def _solve_one(settings: CampaignSettings, ih: int, il: int, i: int, rq: float, grid: int,
               load: float):
    """Mean pressure (Pa), asperities and points in contact of surface i at this Rq and grid;
    None when the surface cannot carry the load."""
    surf = weierstrass_surface(settings, ih, il, i, rq=rq, grid=grid)
    try:
        res = solve_asperity(settings, surf, load)
    except ValueError as exc:
        if "unreachable" in str(exc):
            return None
        raise
    p = res.pressure
    return float(res.mean_pressure), len(res.asperities), int(np.count_nonzero(p > 0))


class PressureAtRq:
    """Mean contact pressure per H at a given Rq (cached), on one grid.

    Calling it with an Rq (m) gives ``(mean pressure per H (Pa), asperities in contact per
    H, grid points in contact per H, feasible)``, means over the surfaces ``0 .. n_seeds-1``
    of load number ``il`` (NaN and ``feasible`` False when some surface cannot carry the
    load), and appends the evaluation to ``record``.
    """

    def __init__(self, settings: CampaignSettings, ihs: list[int], il: int, n_seeds: int,
                 grid: int, load: float, record: list) -> None:
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


class _Found(Exception):
    """A root within the tolerance: ``args = (x, g(x))``."""


class _Objective:
    """``g(x) = mean_H log(p_H / t_H)`` at Rq = e^x (``-inf`` where the load is not carried:
    Rq too small), remembering the evaluation closest to 0 and raising :class:`_Found` at the
    first one within ``tol``."""

    def __init__(self, ev: PressureAtRq, targets: np.ndarray, bounds: tuple[float, float],
                 tol: float):
        self.ev, self.targets, self.tol = ev, targets, tol
        self.lo, self.hi = math.log(bounds[0]), math.log(bounds[1])
        self.best = (math.inf, math.nan, math.nan)  # |g|, x, g
        self.n_eval = 0

    def clamp(self, x: float) -> float:
        """``x`` inside the searched range of log Rq."""
        return min(max(x, self.lo), self.hi)

    def __call__(self, x: float) -> float:
        p, _, _, ok = self.ev(math.exp(x))
        gx = float(np.mean(np.log(np.asarray(p) / self.targets))) if ok else -math.inf
        if self.n_eval == 0 or abs(gx) < self.best[0]:
            self.best = (abs(gx), x, gx)
        self.n_eval += 1
        if abs(gx) <= self.tol:
            raise _Found(x, gx)
        return gx


def _secant_step(gx: float, slope: float) -> float:
    """The next step on log Rq from a point where g = ``gx``: the secant step, at most a factor
    30 in Rq and at least 2 % towards the root (a factor 10 up where the load is not carried)."""
    if not math.isfinite(gx):
        step = math.log(10.0)
    else:
        step = min(max(-gx / slope, -math.log(30.0)), math.log(30.0))
    return max(step, 0.02) if gx < 0 else min(step, -0.02)


def _bracket(g: _Objective, x: float, max_eval: int) -> tuple[float, float, float, float] | None:
    """``(a, g(a), b, g(b))`` with g(a) < 0 <= g(b), found by secant steps from ``x`` (slope 1
    to start: p roughly proportional to Rq); None when ``max_eval`` evaluations do not bracket
    the root. Raises _Unreachable(side, x) at an end of the range."""
    gx = g(x)
    slope = 1.0
    a: tuple[float, float] | None = (x, gx) if gx < 0 else None
    b: tuple[float, float] | None = None if gx < 0 else (x, gx)
    while a is None or b is None:
        xn = g.clamp(x + _secant_step(gx, slope))
        if xn == x:
            raise _Unreachable("above" if gx < 0 else "below", x)
        gn = g(xn)
        if math.isfinite(gn) and math.isfinite(gx) and gn != gx:
            slope = min(max((gn - gx) / (xn - x), 0.2), 5.0)
        x, gx = xn, gn
        if gx < 0:
            a = (x, gx)
        else:
            b = (x, gx)
        if (a is None or b is None) and g.n_eval >= max_eval:
            return None
    return (*a, *b)


def _regula_falsi(g: _Objective, a: float, ga: float, b: float, gb: float, max_eval: int) -> None:
    """Illinois regula falsi on the bracket [a, b] (bisection while g(a) is infinite); returns
    when the bracket is tiny or after ``max_eval`` evaluations. Raises _Unreachable("below",
    b) when the root sits at the smallest Rq that carries the load."""
    side, n_rf = 0, 0
    while n_rf < max_eval or not math.isfinite(ga):
        if abs(b - a) <= 1e-7:
            return
        if not math.isfinite(ga) and abs(b - a) < 1e-3:
            # the target is lower than any mean pressure the model reaches
            raise _Unreachable("below", b)
        if math.isfinite(ga):
            x = (a * gb - b * ga) / (gb - ga)
            if not (min(a, b) < x < max(a, b)):
                x = 0.5 * (a + b)
        else:
            x = 0.5 * (a + b)
        gx = g(x)
        n_rf += 1
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


def _root(ev: PressureAtRq, targets: np.ndarray, x0: float, bounds: tuple[float, float],
          tol: float, max_eval: int):
    """Find log Rq with mean_H log(p_H / t_H) = 0 (|.| <= tol) by a safeguarded secant on
    log Rq (slope 1 to start: p roughly proportional to Rq), then Illinois regula falsi.

    Returns (x, g, converged); raises _Unreachable(side, info) when the target lies outside
    what ``bounds`` reach.
    """
    g = _Objective(ev, targets, bounds, tol)
    try:
        bracket = _bracket(g, g.clamp(x0), 3 * max_eval)
        if bracket is not None:
            _regula_falsi(g, *bracket, max_eval)
    except _Found as found:
        x, gx = found.args
        return x, gx, True
    return g.best[1], g.best[2], False


def _unreachable_message(ev: PressureAtRq, targets, side: str, rq_end: float,
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


def search_log_rq(fine: PressureAtRq, targets: np.ndarray, rq0: float,
                  bounds: tuple[float, float], coarse_n: int | None, tol: float,
                  max_eval: int) -> tuple[float, bool]:
    """log Rq at which the mean contact pressures of ``fine`` meet ``targets``, and whether
    it met ``tol``.

    Parameters
    ----------
    fine : PressureAtRq
        The exponents searched together (one Rq for all) on the settings' grid.
    targets : ndarray
        Target mean contact pressure per exponent of ``fine``, Pa.
    rq0 : float
        Starting Rq, m (moved inside ``bounds``).
    bounds : (float, float)
        Range of Rq searched, m.
    coarse_n : int or None
        Grid of the first steps (at twice the tolerance, three evaluations after the
        bracket); None to search on the settings' grid only.
    tol : float
        Tolerance on ``|mean_H log(p_H / t_H)|``.
    max_eval : int
        Evaluations on the settings' grid after the root is bracketed (three times as many
        to bracket it).

    Returns
    -------
    (float, bool)
        log Rq (the closest evaluation when the tolerance was not met) and whether it met it.

    Raises
    ------
    ValueError
        The target lies outside what Rq in ``bounds`` reaches (the message gives the
        reachable range).
    """
    x0 = math.log(min(max(rq0, bounds[0]), bounds[1]))
    try:
        if coarse_n is not None:
            coarse = PressureAtRq(fine.s, fine.ihs, fine.il, fine.n, coarse_n, fine.load, fine.record)
            with contextlib.suppress(_Unreachable):  # decided on the settings' grid
                x0, _, _ = _root(coarse, targets, x0, bounds, 2 * tol, 3)
        x, _, ok = _root(fine, targets, x0, bounds, tol, max_eval)
    except _Unreachable as exc:
        side, x_end = exc.args
        raise ValueError(_unreachable_message(fine, targets, side, math.exp(x_end), bounds,
                                              fine.load)) from None
    return x, ok
