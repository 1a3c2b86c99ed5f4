"""Elastic boundary-element contact solver: the reference for the asperity model.

Frictionless normal contact of a linear elastic half-space with a rigid rough surface (or of
two elastic bodies, through the contact modulus ``E*``), solved on the grid of the surface by
the constrained conjugate gradient of Polonsky & Keer (1999) with FFT convolution. Unlike the
asperity model of :func:`contact.solve`, every point interacts elastically with every other
one. The numerical core is in :mod:`contact._constrained_cg` (the iteration) and
:mod:`contact._influence` (the influence coefficients and FFT operators); this module
validates input and builds the :class:`~contact.result.ContactResult`.
"""

from __future__ import annotations

import logging
import numbers
import warnings
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from _glstat_runtime.validation import (
    finite_separation,
    flag,
    positive_finite,
    positive_integer,
    positive_pressure,
    tolerance,
)

from ._constrained_cg import PKOutcome, initial_pressure, polonsky_keer
from ._influence import NonPeriodicOperator, PeriodicOperator
from .material import effective_modulus
from .result import ContactResult
from .surface import Surface, surface_arrays

__all__ = ["BEMConvergenceWarning", "solve_bem", "solve_bem_displacement"]

logger = logging.getLogger(__name__)


class BEMConvergenceWarning(RuntimeWarning):
    """The boundary-element solver stopped before reaching its tolerance."""


def _check_surface(surface: Surface) -> tuple[np.ndarray, np.ndarray]:
    """Heights (m, masked points set to 0) and measured points of a surface."""
    # read-only below: a copy only where masked points are zeroed (or the dtype differs)
    h, valid = surface_arrays(surface)
    if surface.mask is not None:
        h = h.copy()
        h[~valid] = 0.0  # never used: masked points carry no pressure
    return h, valid


def _check_options(tol, max_iter, workers: int | None) -> tuple[float, int]:
    """``(tol, max_iter)`` checked, and ``workers`` checked."""
    tol = tolerance(tol, "tol", 1.0, "; 1e-8 is typical")
    max_iter = positive_integer(max_iter, "max_iter", "iteration limit")
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, numbers.Integral) or workers == 0
    ):
        raise ValueError(
            f"workers must be None or a non-zero integer (scipy.fft convention), got {workers!r}"
        )
    return tol, max_iter


def _check_hardness(hardness, nominal_pressure: float | None) -> float | None:
    """``hardness`` (Pa) checked: None, or finite, positive and above the nominal pressure."""
    if hardness is None:
        return None
    hardness = positive_finite(hardness, "hardness", "pressure in pascals (or None for elastic contact)")
    if nominal_pressure is not None and not nominal_pressure < hardness:
        raise ValueError(
            f"nominal_pressure={nominal_pressure:g} Pa is not below hardness={hardness:g} Pa: "
            "a surface that yields at the hardness H carries at most H times the nominal area "
            "(every point plastic), so the nominal pressure must be below H; lower the "
            "nominal pressure or raise the hardness")
    return hardness


def _operator(surface: Surface, e_star: float, periodic: bool, workers: int | None):
    """The compliance operator of the surface's grid: periodic or an isolated patch."""
    cls = PeriodicOperator if flag(periodic, "periodic") else NonPeriodicOperator
    return cls(surface.shape, surface.dx, surface.dy, e_star, workers=workers)


class _Problem(NamedTuple):
    """A checked boundary-element problem on the grid of one surface."""

    h: np.ndarray  # heights (m), masked points set to 0
    valid: np.ndarray  # measured points
    tol: float
    max_iter: int
    accelerate: bool
    hardness: float | None  # Pa
    op: PeriodicOperator | NonPeriodicOperator  # compliance, Pa -> m
    info: dict  # e_star (Pa), periodic, accelerate


def _problem(
    surface: Surface, E, nu, counter_face, tol, max_iter, workers: int | None, accelerate,
    hardness, nominal_pressure: float | None, periodic, warn: bool = True,
) -> _Problem:
    """The surface, elastic constants and options checked, and the compliance operator.

    ``nominal_pressure`` (Pa, already checked) is None under displacement control; ``warn``
    False silences the warning on an implausible Young's modulus.
    """
    h, valid = _check_surface(surface)
    e_star = effective_modulus(E, nu, counter_face, warn=warn)
    tol, max_iter = _check_options(tol, max_iter, workers)
    accelerate = flag(accelerate, "accelerate")
    hardness = _check_hardness(hardness, nominal_pressure)
    op = _operator(surface, e_star, periodic, workers)
    info = {"e_star": e_star, "periodic": bool(periodic), "accelerate": accelerate}
    return _Problem(h, valid, tol, max_iter, accelerate, hardness, op, info)


def _load_controlled(problem: _Problem, surface: Surface, nominal_pressure: float) -> PKOutcome:
    """The constrained conjugate gradient under the load of ``nominal_pressure`` (Pa),
    started from :func:`~contact._constrained_cg.initial_pressure`."""
    h, valid, hardness = problem.h, problem.valid, problem.hardness
    e_star = problem.info["e_star"]
    p0 = initial_pressure(h, valid, float(nominal_pressure), e_star, surface.dx, surface.dy,
                          hardness=hardness)
    return polonsky_keer(
        problem.op,
        h,
        valid,
        total_pressure=float(nominal_pressure) * int(valid.sum()),
        tol=problem.tol,
        max_iter=problem.max_iter,
        p0=p0,
        accelerate=problem.accelerate,
        overwrite_p0=True,
        pmax=hardness,
    )


def _result(
    out: PKOutcome,
    surface: Surface,
    problem: _Problem,
    nominal_pressure: float | None,
    method: str,
    warn: bool = True,
) -> ContactResult:
    """The :class:`~contact.result.ContactResult` of an iteration's outcome; warns (for the
    caller of the public function) when it did not converge."""
    valid, max_iter, tol, hardness = problem.valid, problem.max_iter, problem.tol, problem.hardness
    if not np.isfinite(out.pressure).all() or out.reason.startswith(("non-finite", "pressure")):
        raise FloatingPointError(
            f"the boundary-element iteration broke down after {out.n_iterations} "
            f"iterations ({out.reason}); check the surface heights and units"
        )
    if out.reason == "contact set became empty":
        raise RuntimeError(
            f"the contact set became empty after {out.n_iterations} iterations; "
            "the problem is degenerate for this surface"
        )
    cell_area = surface.dx * surface.dy
    force = float(out.pressure.sum() * cell_area)
    if nominal_pressure is None:
        target = None
        force_error = 0.0
    else:
        # the nominal area is the measured one: masked points are no part of it
        target = float(nominal_pressure) * cell_area * int(valid.sum())
        force_error = (force - target) / target
    last = float(out.history[-1]) if out.history.size else float("nan")
    logger.info("%s on %s grid: %s after %d iterations (%d convolutions), last relative change %.3g, "
                "force error %.3g", method, "x".join(map(str, surface.shape)), out.reason, out.n_iterations,
                out.n_convolutions, last, force_error)
    message = ""
    if not out.converged:
        message = (
            f"solve_bem did not converge: {out.reason} after {out.n_iterations} iterations "
            f"(max_iter={max_iter}); the last relative pressure change is {last:.3g}, above "
            f"tol={tol:g}. The result is marked converged=False; raise max_iter or loosen tol.")
        if warn:
            warnings.warn(message, BEMConvergenceWarning, stacklevel=3)
    info = dict(problem.info)
    info.update(
        dx=surface.dx,
        dy=surface.dy,
        warning=message,
        reason=out.reason,
        tol=tol,
        gap_residual=out.gap_residual,
        penetration=out.penetration,
        n_convolutions=out.n_convolutions,
        displacement=out.displacement,
        gap=out.gap,
    )
    plastic = None
    if hardness is not None:
        plastic = out.pressure >= hardness
        info["plastic_residual"] = out.plastic_residual
    return ContactResult(
        pressure=out.pressure,
        separation=out.separation,
        force=force,
        target_force=target,
        force_error=force_error,
        nominal_pressure=None if nominal_pressure is None else float(nominal_pressure),
        cell_area=cell_area,
        asperities=None,
        converged=out.converged,
        n_iterations=out.n_iterations,
        history=out.history,
        method=method,
        info=info,
        mask=None if surface.mask is None else ~valid,
        hardness=hardness,
        plastic=plastic,
    )


def solve_bem(surface: Surface, nominal_pressure: float, E: float, nu: float, *, periodic: bool = False,
              tol: float = 1e-8, max_iter: int = 1000, counter_face: Sequence[float] | None = None,
              workers: int | None = None, accelerate: bool = True, warn: bool = True,
              hardness: float | None = None) -> ContactResult:
    """Elastic contact of a flat with a rough surface under a given nominal pressure.

    Boundary-element solution of frictionless normal contact between a linear elastic
    half-space and a rough surface, by the constrained conjugate gradient of Polonsky &
    Keer (1999) with the load as a constraint inside the iteration.

    Parameters
    ----------
    surface : Surface
        The rough surface (heights in metres, grid spacing ``dx``, ``dy`` in metres).
        Masked points carry no pressure and are no part of the nominal area.
    nominal_pressure : float
        Imposed nominal pressure in pascals (force / nominal area), > 0. The nominal
        area is that of the measured (unmasked) points, ``dx * dy`` times their number,
        as in :func:`contact.solve`; the target force is ``nominal_pressure`` times it.
    E : float
        Young's modulus of the rough body in pascals, > 0.
    nu : float
        Poisson ratio of the rough body, in (-1, 0.5].
    periodic : bool, default False
        False: the surface is an isolated patch on an unloaded half-space (Love's influence
        coefficients of uniformly loaded rectangular cells, linear convolution by zero
        padding to twice the size). True: the surface repeats periodically (spectral
        half-space kernel ``2 / (E* |q|)`` on the grid's wave vectors).
    tol : float, default 1e-8
        Convergence tolerance on the relative change of the pressure field between two
        iterations, ``sum|p_k - p_(k-1)| / sum p_k``.
    max_iter : int, default 1000
        Iteration limit. Each iteration costs two FFT convolutions.
    counter_face : (E2, nu2) or None
        Elastic constants of the flat counter-face (Pa, dimensionless); None for a rigid
        flat. The two bodies enter through ``1/E* = (1 - nu^2)/E + (1 - nu2^2)/E2``.
    workers : int, optional
        Threads for :mod:`scipy.fft` (its convention: negative counts from the number of
        CPUs); None uses scipy's default (one).
    accelerate : bool, default True
        True: the accelerated iteration (preconditioned directions kept while the contact set
        grows, displacement carried between convolutions, the elastic load restored by raising
        the flat; 3-5 times fewer convolutions on rough surfaces). False: Polonsky & Keer
        (1999) as published, for reference: the same criterion and solution to about ``tol``,
        but it can cycle when one cell carries much of the load (a spike of a measurement).
    warn : bool, default True
        False: no :class:`BEMConvergenceWarning` (its message stays in ``info["warning"]``,
        for worker threads, where changing the warning filters is not safe) and no
        :class:`~contact.ContactWarning` on an implausible pressure or Young's modulus.
    hardness : float, optional
        Hardness ``H`` in pascals of an elastic-perfectly-plastic surface: the pressure is
        capped at ``H``, and a point at ``H`` flows plastically (the flat may
        interpenetrate the undeformed surface there), see Notes. Must be above
        ``nominal_pressure``. None (default): elastic contact, unchanged.

    Returns
    -------
    ContactResult
        ``pressure`` (Pa) on the grid, ``separation`` (m, height of the flat in the
        surface's coordinate, i.e. the mean of ``h - u`` over the contact), ``force`` (N),
        ``force_error`` (relative, at rounding level), ``converged``, ``n_iterations``,
        ``history`` (relative pressure change per iteration) and ``method="bem"``.
        ``info`` holds ``e_star`` (Pa), ``periodic``, ``reason`` (why the iteration
        stopped), ``gap_residual`` (largest |gap| on the contact set, m),
        ``penetration`` (largest interpenetration off the contact set, m),
        ``n_convolutions`` (applications of the compliance operator, the cost),
        ``accelerate``, ``warning`` (the text of a :class:`BEMConvergenceWarning`, empty
        when converged), and the ``displacement`` (elastic normal displacement, m) and
        ``gap`` (m) maps. With a ``hardness``: ``hardness`` (Pa), the boolean map
        ``plastic`` (points at ``p = H``), ``plastic_area_fraction``, ``plastic_force``
        (N) and ``plastic_load_fraction``; ``info["gap"]`` is negative at the plastic
        points (minus the plastic interpenetration, m), ``info["plastic_residual"]`` is the
        largest open gap left at a plastic point (m), and ``gap_residual`` refers to the
        elastic contact points (``0 < p < H``).

    Raises
    ------
    TypeError
        ``surface`` is not a :class:`~contact.surface.Surface`.
    ValueError
        Non-positive or non-finite load, invalid elastic constants, NaN heights outside
        the mask, a tolerance outside (0, 1), a non-positive ``max_iter``, a hardness that
        is not a positive finite number or not above ``nominal_pressure``.

    Warns
    -----
    BEMConvergenceWarning
        The tolerance was not reached within ``max_iter`` iterations; the result is
        returned with ``converged=False``.

    Notes
    -----
    With ``u = K p`` the elastic displacement and ``g = u - h + d`` the gap to the flat at
    height ``d``, the solution satisfies ``p >= 0``, ``g >= 0``, ``p g = 0`` and
    ``sum(p) dx dy = nominal_pressure * A0`` with ``A0`` the measured area. The
    iteration minimises the complementary energy ``p K p / 2 - p h`` over non-negative
    pressures of the given total, conjugate gradient on the current contact set, with
    the mean gap removed there (the Lagrange multiplier of the load, ``-d``), projection
    onto ``p >= 0``, interpenetrating points added to the contact set (and a restart to
    steepest descent when that happens), and restoring the load. See ``docs/bem.md``.

    With a hardness ``H`` (elastic-perfectly-plastic surface, Almqvist et al. 2007) the
    pressure is bounded, ``0 <= p <= H``, and the conditions become ``g = 0`` where
    ``0 < p < H``, ``g >= 0`` where ``p = 0`` and ``g <= 0`` where ``p = H`` (plastic
    interpenetration). The same iteration runs on the free points ``0 < p < H``, projects
    onto ``[0, H]``, lets saturated points with an open gap come off the cap, and restores
    the load by scaling the free points. Only the surface yields: there is no hardening and
    no subsurface plasticity (see ``docs/bem.md``, "Elasto-plastic contact").

    References
    ----------
    I. A. Polonsky, L. M. Keer, Wear 231 (1999) 206-219. A. E. H. Love, Phil. Trans. R.
    Soc. A 228 (1929) 377-420. H. M. Stanley, T. Kato, J. Tribol. 119 (1997) 481-485.
    A. Almqvist, F. Sahlin, R. Larsson, S. Glavatskih, Tribol. Int. 40 (2007) 574-579.
    """
    nominal_pressure = positive_pressure(nominal_pressure, warn=warn)
    problem = _problem(surface, E, nu, counter_face, tol, max_iter, workers, accelerate, hardness,
                       nominal_pressure, periodic, warn)
    out = _load_controlled(problem, surface, nominal_pressure)
    return _result(out, surface, problem, nominal_pressure, "bem", warn)


def solve_bem_displacement(
    surface: Surface,
    separation: float,
    E: float,
    nu: float,
    *,
    tol: float = 1e-8,
    max_iter: int = 1000,
    counter_face: Sequence[float] | None = None,
    workers: int | None = None,
    accelerate: bool = True,
    warn: bool = True,
    hardness: float | None = None,
) -> ContactResult:
    """Elastic contact with the flat held at a given height (displacement control).

    Parameters
    ----------
    surface : Surface
        The rough surface (heights in metres).
    separation : float
        Height of the flat in metres, in the surface's height coordinate: points of the
        undeformed surface above it interpenetrate and are pressed down.
    E, nu, tol, max_iter, counter_face, workers, accelerate, warn
        As in :func:`solve_bem`.
    hardness : float, optional
        Hardness in pascals of an elastic-perfectly-plastic surface, as in
        :func:`solve_bem` (any positive finite value: there is no load to compare it with).

    Returns
    -------
    ContactResult
        As in :func:`solve_bem`, with ``target_force`` and ``nominal_pressure`` None,
        ``force_error`` 0 and ``method="bem-displacement"``. A flat above the highest
        point gives zero pressure. With a ``hardness``, the plastic fields of
        :func:`solve_bem`.

    Raises
    ------
    TypeError, ValueError
        As in :func:`solve_bem`, and for a non-finite separation.

    Warns
    -----
    BEMConvergenceWarning
        As in :func:`solve_bem`.

    Notes
    -----
    The same iteration as :func:`solve_bem` with ``d`` fixed: no mean-gap removal and no
    rescaling to a load. The surface is an isolated patch (``periodic=False`` of
    :func:`solve_bem`): on a periodic half-space the mean displacement under a non-zero
    mean pressure is unbounded, so a rigid-body approach has no absolute meaning there.
    """
    separation = finite_separation(separation)
    problem = _problem(surface, E, nu, counter_face, tol, max_iter, workers, accelerate, hardness,
                       None, False, warn)
    out = polonsky_keer(
        problem.op, problem.h, problem.valid, separation=float(separation), tol=problem.tol,
        max_iter=problem.max_iter, accelerate=problem.accelerate, pmax=problem.hardness,
    )
    return _result(out, surface, problem, None, "bem-displacement", warn)
