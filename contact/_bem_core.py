"""Constrained conjugate gradient of Polonsky & Keer (1999) for frictionless normal contact.

Pure numerics on plain arrays: the public wrapper is :func:`contact.bem.solve_bem`.

Problem. Find the pressure ``p >= 0`` on the grid such that the gap

    g = u(p) - h + d,     u = K p  (elastic displacement, m),

satisfies ``g >= 0`` everywhere, ``g = 0`` where ``p > 0``, and either the total load
``sum(p) = P_total`` (load control: ``d`` is an unknown, the mean of ``h - u`` on the
contact set) or the rigid-body approach ``d`` is given (displacement control). ``h`` is
the composite height (m) of the rough surface, pointing towards the counter-face.

Each iteration costs two applications of ``K`` (FFT convolutions); the rest is fused into
a few compiled passes over the grid.

Reference: I. A. Polonsky, L. M. Keer, "A numerical method for solving rough contact
problems based on the multi-level multi-summation and conjugate gradient techniques",
Wear 231 (1999) 206-219.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba as nb
import numpy as np

from ._bem_kernel import LinearOperator2D

__all__ = ["PKOutcome", "initial_pressure", "polonsky_keer"]


@nb.njit(cache=True, nogil=True)
def _gap(u, h, p, valid, g, shift):  # pragma: no cover - compiled
    """g = u - h + shift everywhere; return (sum of g on the contact set, its size)."""
    s = 0.0
    c = 0
    for i in range(g.size):
        gi = u[i] - h[i] + shift
        g[i] = gi
        if p[i] > 0.0:
            s += gi
            c += 1
    return s, c


@nb.njit(cache=True, nogil=True)
def _shift_and_norm(g, shift, p):  # pragma: no cover - compiled
    """g -= shift everywhere; return the sum of g² on the contact set."""
    s = 0.0
    for i in range(g.size):
        gi = g[i] - shift
        g[i] = gi
        if p[i] > 0.0:
            s += gi * gi
    return s


@nb.njit(cache=True, nogil=True)
def _direction(t, g, p, beta):  # pragma: no cover - compiled
    """Conjugate direction: t = g + beta t on the contact set, 0 elsewhere."""
    for i in range(t.size):
        if p[i] > 0.0:
            t[i] = g[i] + beta * t[i]
        else:
            t[i] = 0.0


@nb.njit(cache=True, nogil=True)
def _contact_sum(r, p):  # pragma: no cover - compiled
    s = 0.0
    c = 0
    for i in range(r.size):
        if p[i] > 0.0:
            s += r[i]
            c += 1
    return s, c


@nb.njit(cache=True, nogil=True)
def _step_terms(g, t, r, rshift, p):  # pragma: no cover - compiled
    """Return sum(g t) and sum((r - rshift) t) over the contact set."""
    num = 0.0
    den = 0.0
    for i in range(g.size):
        if p[i] > 0.0:
            num += g[i] * t[i]
            den += (r[i] - rshift) * t[i]
    return num, den


@nb.njit(cache=True, nogil=True)
def _update(p, t, g, tau, tau_enter, valid, p_new):  # pragma: no cover - compiled
    """Projected step; points out of contact that interpenetrate enter the contact set.

    On the contact set ``p - tau t`` clipped at 0; an interpenetrating point out of
    contact (``g < 0``) gets ``-tau_enter g``. Returns (sum of the new pressure, number
    of points that entered).
    """
    total = 0.0
    entered = 0
    for i in range(p.size):
        if p[i] > 0.0:
            v = p[i] - tau * t[i]
            if v < 0.0:
                v = 0.0
        elif valid[i] and g[i] < 0.0:
            v = -tau_enter * g[i]
            entered += 1
        else:
            v = 0.0
        p_new[i] = v
        total += v
    return total, entered


@nb.njit(cache=True, nogil=True)
def _rescale_and_change(p_new, p, scale):  # pragma: no cover - compiled
    """p_new *= scale; return sum |p_new - p|."""
    s = 0.0
    for i in range(p.size):
        v = p_new[i] * scale
        p_new[i] = v
        s += abs(v - p[i])
    return s


@nb.njit(cache=True, nogil=True)
def _residuals(p, g, valid):  # pragma: no cover - compiled
    """Return (max |g| on contact, max interpenetration -g off contact, sum p |g|)."""
    on = 0.0
    off = 0.0
    comp = 0.0
    for i in range(p.size):
        if p[i] > 0.0:
            a = abs(g[i])
            if a > on:
                on = a
            comp += p[i] * a
        elif valid[i] and -g[i] > off:
            off = -g[i]
    return on, off, comp


def initial_pressure(
    h: np.ndarray, valid: np.ndarray, mean_pressure: float, e_star: float, dx: float, dy: float
) -> np.ndarray:
    """Starting pressure for load control, concentrated on the highest points.

    The contact fraction of a rough surface under a light load is close to the linear
    estimate ``A/A0 ≈ 2 p / (E* |∇h|_rms)`` (Bush, Gibson & Thomas 1975; Persson 2001).
    The start puts pressure ``∝ h - h_c`` on the points above the height ``h_c`` exceeded
    by twice that fraction, which spares the iterations that would otherwise shrink a
    uniform start down to a tiny contact set.

    Parameters
    ----------
    h : ndarray, shape (nx, ny)
        Heights in metres.
    valid : ndarray of bool, shape (nx, ny)
        Points that may carry pressure.
    mean_pressure : float
        Nominal pressure in pascals.
    e_star : float
        Contact modulus in pascals.
    dx, dy : float
        Grid spacing in metres.

    Returns
    -------
    ndarray, shape (nx, ny)
        Unnormalised starting pressure (the solver rescales it to the load); uniform over
        the valid points when the estimate covers the whole surface.
    """
    sx = np.diff(h, axis=0) / dx
    sy = np.diff(h, axis=1) / dy
    mx = valid[1:, :] & valid[:-1, :]
    my = valid[:, 1:] & valid[:, :-1]
    ms2 = 0.0
    if mx.any():
        ms2 += float(np.mean(sx[mx] ** 2))
    if my.any():
        ms2 += float(np.mean(sy[my] ** 2))
    slope = np.sqrt(ms2)
    fraction = 1.0 if slope == 0 else min(1.0, 4.0 * mean_pressure / (e_star * slope))
    known = h[valid]
    if fraction >= 1.0 or known.size < 2:
        return np.where(valid, 1.0, 0.0)
    level = np.quantile(known, 1.0 - fraction)
    p0 = np.where(valid, np.maximum(h - level, 0.0), 0.0)
    if not p0.any():
        return np.where(valid & (h >= known.max()), 1.0, 0.0)
    return p0


@dataclass
class PKOutcome:
    """Raw output of :func:`polonsky_keer` (arrays in the grid's shape)."""

    pressure: np.ndarray  # Pa
    displacement: np.ndarray  # m
    gap: np.ndarray  # m
    separation: float  # m, rigid-body approach d
    converged: bool
    n_iterations: int
    history: np.ndarray  # relative pressure change per iteration
    reason: str
    gap_residual: float  # max |g| on the contact set, m
    penetration: float  # max interpenetration off the contact set, m


def polonsky_keer(
    op: LinearOperator2D,
    h: np.ndarray,
    valid: np.ndarray,
    *,
    total_pressure: float | None = None,
    separation: float | None = None,
    tol: float = 1e-8,
    max_iter: int = 1000,
    p0: np.ndarray | None = None,
) -> PKOutcome:
    """Solve the contact problem by the Polonsky–Keer constrained conjugate gradient.

    Parameters
    ----------
    op : LinearOperator2D
        Compliance operator, pressure (Pa) to displacement (m).
    h : ndarray, shape (nx, ny)
        Composite heights in metres (towards the counter-face).
    valid : ndarray of bool, shape (nx, ny)
        Points that may carry pressure (False for missing data).
    total_pressure : float, optional
        Load control: required sum of the pressure over the grid (Pa times points).
    separation : float, optional
        Displacement control: height ``d`` of the counter-face plane in metres, in the
        coordinate of ``h`` (the gap is ``g = u - h + d``). Exactly one of
        ``total_pressure`` and ``separation`` is given.
    tol : float
        Stop when the relative change of the pressure field in one iteration,
        ``sum|p_k - p_(k-1)| / sum p_k``, falls below ``tol``.
    max_iter : int
        Iteration limit.
    p0 : ndarray, optional
        Initial pressure (Pa); default uniform over the valid points (load control) or
        ``max(h - d, 0)`` over the self-compliance (displacement control).

    Returns
    -------
    PKOutcome
    """
    if (total_pressure is None) == (separation is None):
        raise ValueError("give exactly one of total_pressure and separation")
    shape = h.shape
    hf = np.ascontiguousarray(h, dtype=float).ravel()
    vf = np.ascontiguousarray(valid, dtype=np.bool_).ravel()
    load_control = total_pressure is not None
    shift = 0.0 if load_control else float(separation)

    if p0 is not None:
        p = np.array(p0, dtype=float).ravel()
        p[~vf] = 0.0
        p[p < 0] = 0.0
    elif load_control:
        p = np.where(vf, 1.0, 0.0)
    else:
        p = np.where(vf, np.maximum(hf - shift, 0.0), 0.0) / op.self_compliance
    if load_control:
        s = p.sum()
        if not s > 0:
            p = np.where(vf, 1.0, 0.0)
            s = p.sum()
        p *= total_pressure / s

    g = np.empty_like(p)
    t = np.zeros_like(p)
    p_new = np.empty_like(p)
    history = []
    g_old = 1.0
    conj = False
    converged = False
    reason = "iteration limit reached"
    n_iter = 0
    d = shift

    for it in range(1, max_iter + 1):
        n_iter = it
        u = op.apply(p.reshape(shape)).ravel()
        s, c = _gap(u, hf, p, vf, g, shift)
        if c == 0:
            if load_control:
                reason = "contact set became empty"
                break
            # displacement control with nothing in contact: p = 0 is the answer if
            # nothing interpenetrates; otherwise restart from the local estimate
            if not np.any(vf & (g < 0)):
                converged = True
                reason = "no contact at this separation"
                history.append(0.0)
                break
        gbar = s / c if (load_control and c > 0) else 0.0
        if load_control:
            d = -gbar
        gnorm = _shift_and_norm(g, gbar, p)
        beta = gnorm / g_old if conj else 0.0
        g_old = gnorm if gnorm > 0 else 1.0
        _direction(t, g, p, beta)
        r = op.apply(t.reshape(shape)).ravel()
        if load_control:
            rs, rc = _contact_sum(r, p)
            rbar = rs / rc if rc else 0.0
        else:
            rbar = 0.0
        num, den = _step_terms(g, t, r, rbar, p)
        tau = num / den if den > 0 else 0.0
        # Polonsky & Keer let interpenetrating points enter with the step length tau;
        # when the contact set admits no descent step (a single point, or g already 0
        # there) the local self-compliance gives the step instead.
        tau_enter = tau if tau > 0 else 1.0 / op.self_compliance
        total, entered = _update(p, t, g, tau, tau_enter, vf, p_new)
        conj = entered == 0
        if load_control:
            if not total > 0:
                reason = "pressure vanished everywhere (step failure)"
                break
            scale = total_pressure / total
        else:
            scale = 1.0
        change = _rescale_and_change(p_new, p, scale)
        p, p_new = p_new, p
        norm = p.sum()
        err = change / norm if norm > 0 else (0.0 if change == 0 else np.inf)
        history.append(err)
        if not np.isfinite(err):
            reason = "non-finite values in the iteration"
            break
        if err < tol and entered == 0:
            converged = True
            reason = "relative pressure change below tolerance"
            break

    # final state: displacement and gap of the returned pressure
    u = op.apply(p.reshape(shape)).ravel()
    s, c = _gap(u, hf, p, vf, g, shift)
    if load_control and c > 0:
        gbar = s / c
        d = -gbar
        _shift_and_norm(g, gbar, p)
    on, off, _ = _residuals(p, g, vf)
    return PKOutcome(
        pressure=p.reshape(shape),
        displacement=u.reshape(shape),
        gap=g.reshape(shape),
        separation=float(d),
        converged=converged,
        n_iterations=n_iter,
        history=np.asarray(history, dtype=float),
        reason=reason,
        gap_residual=float(on),
        penetration=float(off),
    )
