"""Load- and displacement-controlled contact of a rigid flat with a rough surface.

The semi-analytical, non-interacting asperity model (docs/method.md §3; Bigerelle et al.,
Coatings 10(1):15, 2019, §2.2). The numerical work is done by the compiled kernels of
:mod:`contact._asperity_kernels`; this module validates input, controls the load and builds
the :class:`~contact.result.ContactResult`.
"""

from __future__ import annotations

import logging
import math
import warnings
from collections.abc import Sequence

import numpy as np

from _glstat_runtime.validation import (
    finite_separation,
    positive_integer,
    positive_pressure,
    real_scalar,
    tolerance,
)

from . import _asperity_kernels as kernels
from ._deprecation import renamed_keywords
from .errors import ContactWarning
from .material import effective_modulus
from .result import ContactResult
from .surface import Surface, surface_arrays

__all__ = ["solve", "solve_displacement"]

logger = logging.getLogger(__name__)

#: A load inside a force jump is warned about only when the jump or the returned state's
#: ``|force_error|`` exceeds this fraction of the load (1 %); a smaller one, the first touch
#: of one summit among many in contact, is recorded in ``info`` only.
JUMP_WARNING_THRESHOLD = 0.01

_COLUMNS = ["i", "j", "x", "y", "height", "delta", "a", "b", "beta", "p_m", "F"]


def _check_surface(surface: Surface) -> tuple[np.ndarray, np.ndarray]:
    """Heights (m) and measured points of a surface that has asperities to carry a load."""
    h, valid = surface_arrays(surface)
    known = h[valid]
    span = float(known.max() - known.min())
    if not span > 0:
        raise ValueError(
            f"the surface is flat (all heights equal {known[0]!r} m): it has no asperities "
            "to carry a load"
        )
    return h, valid


class _Model:
    """The asperity model of one surface, with its summits sorted by decreasing height."""

    def __init__(self, surface: Surface, E, nu, cone_factor, counter_face, warn: bool = True):
        c = real_scalar(cone_factor)
        if c is None or not (math.isfinite(c) and c > 0):
            raise ValueError(
                f"cone_factor must be a positive number, got {cone_factor!r} "
                "(0.2 in Bigerelle et al. 2019, 0.5 for Sneddon's elastic cone)"
            )
        self.h, self.valid = _check_surface(surface)
        self.surface = surface
        self.e_star = effective_modulus(E, nu, counter_face, warn=warn)
        self.cone_factor = c
        self.pm_coef = self.cone_factor * self.e_star
        self.dx, self.dy = surface.dx, surface.dy
        self.cell = self.dx * self.dy
        self.nominal_area = self.cell * int(self.valid.sum())
        ii, jj = kernels.find_summits(self.h, self.valid)
        if ii.size == 0:
            raise ValueError(
                "the surface has no summit (no point strictly higher than its 8 neighbours "
                "away from the border), so no asperity can touch the plane"
            )
        z = self.h[ii, jj]
        order = np.argsort(-z, kind="stable")
        self.si = np.ascontiguousarray(ii[order])
        self.sj = np.ascontiguousarray(jj[order])
        self.sz = z[order]
        self._z_ascending = self.sz[::-1].copy()
        self.n_evaluations = 0

    def n_in_contact(self, d: float) -> int:
        """Number of summits strictly above the plane at height ``d``."""
        return int(self.sz.size - np.searchsorted(self._z_ascending, d, side="right"))

    def force(self, d: float) -> float:
        self.n_evaluations += 1
        n = self.n_in_contact(d)
        if n == 0:
            return 0.0
        return float(
            kernels.total_force(
                self.h, self.valid, self.si, self.sj, n, d, self.dx, self.dy, self.pm_coef
            )
        )

    def table(self, d: float) -> np.ndarray:
        n = self.n_in_contact(d)
        return kernels.asperity_state(
            self.h, self.valid, self.si, self.sj, n, d, self.dx, self.dy, self.pm_coef
        )

    def result(self, d, tables, weights, target, nominal_pressure, method, **extra):
        """Build the result from one state (weight 1), or a blend of two states at a jump."""
        import pandas as pd

        pressure = np.zeros_like(self.h)
        for tab, w in zip(tables, weights, strict=True):
            if w > 0:
                kernels.paint_pressure(
                    pressure, self.valid, self.si, self.sj, tab, self.dx, self.dy, w
                )
        main = tables[0]
        n = main.shape[0]
        forces = np.zeros(n)
        for tab, w in zip(tables, weights, strict=True):
            forces[: tab.shape[0]] += w * tab[:, 5]
        si, sj = self.si[:n], self.sj[:n]
        frame = pd.DataFrame(
            {
                "i": si,
                "j": sj,
                "x": si * self.dx,
                "y": sj * self.dy,
                "height": self.sz[:n],
                "delta": main[:, 0],
                "a": main[:, 1],
                "b": main[:, 2],
                "beta": main[:, 3],
                "p_m": main[:, 4],
                "F": forces,
            },
            columns=_COLUMNS,
        )
        force = float(forces.sum())
        force_error = 0.0 if target is None else (force - target) / target
        info = {
            "e_star": self.e_star,
            "cone_factor": self.cone_factor,
            "nominal_area": self.nominal_area,
            "n_summits": int(self.sz.size),
            "n_evaluations": self.n_evaluations,
            "dx": self.dx,
            "dy": self.dy,
            "warning": "",
        }
        info.update(extra)
        return ContactResult(
            pressure=pressure,
            separation=float(d),
            force=force,
            target_force=target,
            force_error=float(force_error),
            nominal_pressure=nominal_pressure,
            cell_area=self.cell,
            asperities=frame,
            converged=True,
            n_iterations=int(extra.get("n_iterations", 0)),
            method=method,
            info=info,
            mask=None if self.surface.mask is None else ~self.valid,
        )


def _find_separation(model: _Model, target: float, tol: float, max_iter: int):
    """Bracket and solve F(d) = target for the plane height d.

    Returns ``(d_lo, d_hi, f_lo, f_hi, iterations, converged)`` with
    ``f_lo >= target >= f_hi``; the two ends coincide (``d_lo == d_hi``) when the force
    matched to ``tol``, otherwise they bracket a jump of F(d) to machine precision.
    """
    known = model.h[model.valid]
    zmin = float(known.min())
    zmax = float(model.sz[0])
    hi, f_hi = zmax, 0.0
    # Step down from the highest summit with doubling steps: the force is cheap to
    # evaluate while little is in contact, so the bracket is found near the solution.
    step = max((zmax - zmin) * 1e-4, np.finfo(float).eps * max(abs(zmax), abs(zmin)))
    it = 0
    while True:
        lo = max(hi - step, zmin)
        f_lo = model.force(lo)
        it += 1
        if f_lo >= target:
            break
        if lo <= zmin:
            p_max = f_lo / model.nominal_area
            raise ValueError(
                f"the requested load is unreachable: nominal pressure "
                f"{target / model.nominal_area:.6g} Pa needs {target:.6g} N, but the "
                f"asperity model carries at most {f_lo:.6g} N ({p_max:.6g} Pa nominal) with "
                f"the plane at the lowest point of the surface (d = {zmin:.6g} m); lower "
                "nominal_pressure or check its unit (pascals)"
            )
        hi, f_hi = lo, f_lo
        step *= 2.0
    if abs(f_lo - target) <= tol * target:
        return lo, lo, f_lo, f_lo, it, True
    # Illinois regula falsi, safeguarded by bisection; F decreases with d.
    g_lo, g_hi = f_lo - target, f_hi - target
    last, stall = 0, 0
    for _ in range(max_iter):
        if hi - lo <= 4.0 * np.finfo(float).eps * max(abs(lo), abs(hi), zmax - zmin):
            return lo, hi, g_lo + target, g_hi + target, it, True
        d = (lo * g_hi - hi * g_lo) / (g_hi - g_lo)
        if stall >= 3 or not (lo < d < hi):
            d, stall = 0.5 * (lo + hi), 0
        g = model.force(d) - target
        it += 1
        if abs(g) <= tol * target:
            return d, d, g + target, g + target, it, True
        if g > 0:
            lo, g_lo = d, g
            if last == 1:
                g_hi *= 0.5
                stall += 1
            else:
                stall = 0
            last = 1
        else:
            hi, g_hi = d, g
            if last == -1:
                g_lo *= 0.5
                stall += 1
            else:
                stall = 0
            last = -1
    return lo, hi, g_lo + target, g_hi + target, it, False


def _check_options(jump, nominal_pressure, tol, max_iter, warn: bool) -> tuple[float, float, int]:
    """``jump`` checked; ``(nominal_pressure, tol, max_iter)`` checked and converted."""
    if jump not in ("nearest", "deeper", "blend"):
        raise ValueError(f"jump must be 'nearest', 'deeper' or 'blend', got {jump!r}")
    nominal_pressure = positive_pressure(nominal_pressure, warn=warn)
    tol = tolerance(tol, "tol", 1e-3)
    max_iter = positive_integer(max_iter, "max_iter", "iteration limit")
    return nominal_pressure, tol, max_iter


def _separation(model: _Model, target: float, tol: float, max_iter: int) -> tuple[float, float, int]:
    """Plane heights ``(lo, hi)`` (m) that carry the load ``target`` (N), and the number of
    force evaluations; ``lo == hi`` when the force matched, else the two bracket a jump.

    Raises
    ------
    RuntimeError
        The search did not converge in ``max_iter`` iterations.
    """
    lo, hi, f_lo, f_hi, it, ok = _find_separation(model, target, tol, max_iter)
    logger.debug("separation search: %s after %d force evaluations, bracket [%.17g, %.17g] m, forces %.6g N "
                 "and %.6g N for a target of %.6g N", "converged" if ok else "not converged", it, lo, hi,
                 f_lo, f_hi, target)
    if not ok:
        raise RuntimeError(
            f"the separation search did not converge in max_iter={max_iter} iterations "
            f"(bracket [{lo:.17g}, {hi:.17g}] m, forces {f_lo:.6g} N and {f_hi:.6g} N for a "
            f"target of {target:.6g} N); raise max_iter"
        )
    return lo, hi, it


def _balanced_state(
    model: _Model, d: float, target: float, nominal_pressure: float, it: int, jump: str
) -> ContactResult:
    """The result of the state with the plane at ``d`` (m), whose force matches the load."""
    return model.result(
        d, [model.table(d)], [1.0], target, float(nominal_pressure), "asperity",
        n_iterations=it, jump=jump, in_jump=False, blend_weight=1.0, force_jump=0.0,
        other_force=float("nan"), other_separation=float("nan"),
    )


def _jump_state(
    model: _Model, lo: float, hi: float, target: float, nominal_pressure: float, it: int,
    jump: str, warn: bool,
) -> ContactResult:
    """The result when the load falls inside a jump of F(d) between the planes at ``lo`` and
    ``hi`` (m): one of the two states (warned when ``warn`` and the jump or the force error
    exceeds :data:`JUMP_WARNING_THRESHOLD`), or their blend."""
    # The deeper state (plane at lo) carries more than the load, the shallower one (plane at
    # hi, a hair higher) less.
    tab_lo, tab_hi = model.table(lo), model.table(hi)
    f_lo, f_hi = float(tab_lo[:, 5].sum()), float(tab_hi[:, 5].sum())
    force_jump = (f_lo - f_hi) / target
    bracket = (lo, hi)
    if jump == "blend":
        theta = 1.0 if f_lo == f_hi else (target - f_hi) / (f_lo - f_hi)
        theta = min(max(theta, 0.0), 1.0)
        return model.result(
            lo, [tab_lo, tab_hi], [theta, 1.0 - theta], target, float(nominal_pressure),
            "asperity", n_iterations=it, jump=jump, in_jump=True, blend_weight=theta,
            force_jump=force_jump, other_force=f_hi, other_separation=hi,
            separation_bracket=bracket,
        )
    deeper = (
        jump == "deeper"
        or tab_hi.shape[0] == 0
        or f_hi <= 0.0
        or abs(f_lo - target) <= abs(f_hi - target)
    )
    d, tab, other_f, other_d = (lo, tab_lo, f_hi, hi) if deeper else (hi, tab_hi, f_lo, lo)
    force = float(tab[:, 5].sum())
    small = max(abs(force_jump), abs(force - target) / target) <= JUMP_WARNING_THRESHOLD
    message = "" if small else (
        f"the requested load {target:.6g} N ({nominal_pressure:.6g} Pa nominal) falls inside "
        f"a jump of the asperity model's force at separation {lo:.10g} m: F jumps from "
        f"{f_hi:.6g} N to {f_lo:.6g} N ({force_jump:.3g} of the load) as the plane passes "
        f"it, so no state of the model carries the load exactly; returned the "
        f"{'deeper' if deeper else 'shallower'} state with F = {force:.6g} N "
        f"(force_error = {(force - target) / target:+.3g}); pass jump='blend' for a "
        "force-balanced mix of the two states that is not a state of the model"
    )
    if warn and message:
        # stacklevel 4: the caller of solve, past solve and its renamed_keywords wrapper
        warnings.warn(message, ContactWarning, stacklevel=4)
    return model.result(
        d, [tab], [1.0], target, float(nominal_pressure), "asperity", n_iterations=it,
        jump=jump, in_jump=True, blend_weight=1.0, force_jump=force_jump,
        other_force=other_f, other_separation=other_d, separation_bracket=bracket,
        warning=message,
    )


@renamed_keywords(rtol="tol", maxiter="max_iter")
def solve(
    surface: Surface, nominal_pressure: float, E: float, nu: float, cone_factor: float = 0.2,
    counter_face: Sequence[float] | None = None, *, tol: float = 1e-10, max_iter: int = 200,
    jump: str = "nearest", warn: bool = True,
) -> ContactResult:
    """Press a flat onto a rough surface until it carries a given nominal pressure.

    Parameters
    ----------
    surface : Surface
        The rough surface (heights in metres).
    nominal_pressure : float
        Imposed nominal pressure in pascals (force / nominal area), > 0.
    E : float
        Young's modulus of the rough body in pascals, > 0.
    nu : float
        Poisson ratio of the rough body, in (-1, 0.5].
    cone_factor : float, default 0.2
        ``c`` in ``p_m = c E* tan(beta)``: 0.2 as in Bigerelle et al. (2019), 0.5 for
        Sneddon's elastic cone (Johnson, *Contact Mechanics*, ch. 5).
    counter_face : (E2, nu2) or None
        Elastic constants of the flat (Pa, dimensionless); None for a rigid plane.
    tol : float, default 1e-10
        Relative tolerance on the force balance, in (0, 1e-3). ``rtol=`` is a deprecated
        name of it.
    max_iter : int, default 200
        Iteration limit of the root finder on the separation. ``maxiter=`` is a deprecated
        name of it.
    jump : {"nearest", "deeper", "blend"}, default "nearest"
        What to return when the load falls inside a jump of the force ``F(d)`` (see Notes):
        the state of the model whose force is closest to the load (``"nearest"``; never a
        state without contact), the deeper state, which carries more than the load
        (``"deeper"``), or a force-balanced blend of the two states, which is not a state
        of the model (``"blend"``).
    warn : bool, default True
        Issue the :class:`~contact.ContactWarning` of a load inside a jump; False keeps its
        message in ``info["warning"]`` only (for worker threads, where changing the warning
        filters is not safe). False also silences the warnings on an implausible nominal
        pressure or Young's modulus.

    Returns
    -------
    ContactResult
        Pressure map (Pa), plane height ``separation`` (m), ``force`` (N), ``force_error``
        (relative to the load), ``alpha``, ``samples`` and the per-asperity table
        ``asperities`` with columns ``i``, ``j``, ``x``, ``y`` (m), ``height`` (m),
        ``delta`` (interference, m), ``a``, ``b`` (semi-axes along x and y, m), ``beta``
        (attack angle, rad), ``p_m`` (mean pressure, Pa) and ``F`` (force, N). ``info``
        holds ``in_jump`` (bool), ``force_jump`` (jump of F relative to the load, 0 outside
        a jump), ``other_force`` (N) and ``other_separation`` (m) of the other limiting
        state (NaN outside a jump), ``separation_bracket`` (m, in a jump), ``jump`` and
        ``blend_weight`` (the deeper state's weight with ``jump="blend"``, else 1), and
        ``warning``, the text of the :class:`~contact.ContactWarning` of a load inside a
        jump (empty otherwise, and for a jump too small to warn about).

    Raises
    ------
    ValueError
        Non-positive load, invalid elastic constants, flat surface, no summit, NaN heights
        outside the mask, a load no separation can carry, or an unknown ``jump``.

    Warns
    -----
    contact.ContactWarning
        The load falls inside a jump of F(d), a state of the model is returned (``jump``
        is ``"nearest"`` or ``"deeper"``) and the jump or ``|force_error|`` exceeds
        :data:`JUMP_WARNING_THRESHOLD` (1 % of the load): the state's force differs from the
        load by ``force_error``; the message gives the jump. A smaller jump is recorded in
        ``info`` (``in_jump``, ``force_jump``) only.

    Notes
    -----
    The plane at height ``d`` touches every summit higher than ``d`` (see
    :func:`contact.summits`). For each, the patch semi-axes are measured on the surface by
    walking from the summit along the four grid directions until the height drops to ``d``
    or below (crossings linearly interpolated; a walk that meets the border or a missing
    point stops at the last measured point); ``a`` and ``b`` are the means of the two
    one-sided distances along x and y. The attack angle ``beta`` is the mean over the four
    directions of ``arctan(delta / run)``. The pressure ``1.5 p_m sqrt(1 - (x/a)^2 -
    (y/b)^2)`` is sampled at the grid points inside the ellipse centred on the summit;
    overlapping patches add up. ``F = sum(cell area * p)``.

    ``F(d)`` is monotone but has jumps: when a summit first touches (its centre point
    carries ``1.5 p_m`` at once) and when a walk passes a valley as the plane descends.
    The separation is found by bracketing and safeguarded regula falsi to ``tol``. When
    the load falls inside a jump, the bracket shrinks to the jump's separation (to machine
    precision) and no state of the model carries the load: the pressure map, ``samples``
    and ``asperities`` are those of one state (by default the one with the force closest to
    the load), ``force_error`` is that state's honest error, of order the jump, and a
    :class:`~contact.ContactWarning` is issued when the jump or the error exceeds 1 % of
    the load. A smaller jump (typically one summit's first touch among many in contact) is
    recorded in ``info`` only: the returned state then carries the load to within 1 %.
    With ``jump="blend"`` the map is instead ``theta * (deeper state) + (1 - theta) *
    (shallower state)`` with the weight ``theta`` that balances the force; its samples
    (e.g. ``theta * 1.5 p_m`` at a summit that just touched) are not pressures of the model,
    and the table's geometry and ``p_m`` are those of the deeper state with the blended
    ``F``.
    """
    nominal_pressure, tol, max_iter = _check_options(jump, nominal_pressure, tol, max_iter, warn)
    model = _Model(surface, E, nu, cone_factor, counter_face, warn)
    target = float(nominal_pressure) * model.nominal_area
    lo, hi, it = _separation(model, target, tol, max_iter)
    if lo == hi:
        return _balanced_state(model, lo, target, nominal_pressure, it, jump)
    return _jump_state(model, lo, hi, target, nominal_pressure, it, jump, warn)


def solve_displacement(
    surface: Surface,
    separation: float,
    E: float,
    nu: float,
    cone_factor: float = 0.2,
    counter_face: Sequence[float] | None = None,
) -> ContactResult:
    """Contact with the flat held at a given height (displacement control).

    Parameters
    ----------
    surface : Surface
        The rough surface (heights in metres).
    separation : float
        Height of the plane in metres, in the surface's height coordinate; summits above it
        are in contact.
    E, nu, cone_factor, counter_face
        As in :func:`solve`.

    Returns
    -------
    ContactResult
        As in :func:`solve`, with ``target_force`` None and ``force_error`` 0.
    """
    d = finite_separation(separation)
    model = _Model(surface, E, nu, cone_factor, counter_face)
    return model.result(d, [model.table(d)], [1.0], None, None, "asperity-displacement")
