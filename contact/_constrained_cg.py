"""Constrained conjugate gradient of Polonsky & Keer (1999) for frictionless normal contact.

Pure numerics on plain arrays: the public wrapper is :func:`contact.bem.solve_bem`.

Problem. Find the pressure ``p >= 0`` on the grid such that the gap

    g = u(p) - h + d,     u = K p  (elastic displacement, m),

satisfies ``g >= 0`` everywhere, ``g = 0`` where ``p > 0``, and either the total load
``sum(p) = P_total`` (load control: ``d`` is an unknown, the mean of ``h - u`` on the
contact set) or the rigid-body approach ``d`` is given (displacement control). ``h`` is
the composite height (m) of the rough surface, pointing towards the counter-face.

The reference iteration (``accelerate=False``) is that of Polonsky & Keer: two
applications of ``K`` (FFT convolutions) per iteration and a restart to steepest descent
whenever points enter the contact set; after each projected step the load is restored by
scaling the whole pressure field. The accelerated iteration (default) has the same fixed
point and stopping rule and differs in four ways:

* preconditioning: the search direction is built from ``z = S g`` instead of the gap
  ``g``, with ``S`` the 3 x 3 stencil of the inverse compliance (symbol ``E* |q| / 2``),
  restricted to the contact set at both ends. ``S`` is diagonally dominant, so the
  preconditioner is symmetric positive definite on every contact set; it costs a
  compiled pass over the contact points, no convolution. The small eigenvalues of ``K``
  belong to the short wavelengths, which a local stencil inverts well: the conjugate
  gradient needs about half the iterations;
* the conjugate direction is kept when points enter the contact set, so the search does
  not fall back to steepest descent for as long as the contact set is still growing; it is
  restarted when the new gap is far from orthogonal to the previous direction (Powell's
  test, ``|sum g t_old| > 0.2 sum g z``: clipping and new points have spoilt the
  conjugacy), or, elastic under load control after a step that left the contact set
  unchanged, to the previous preconditioned gap (``|sum g z_old| > 0.2 sum g z``, a kept
  direction that has lost its conjugacy), or when it is no longer a descent direction;
* the displacement ``u = K p`` is carried along: when an iteration neither clips a point
  to zero pressure nor adds one, the new pressure is ``s (p - tau t)`` and its displacement
  ``s (u - tau K t)`` costs no convolution (it is recomputed exactly every
  ``_REFRESH`` such iterations and at the end);
* elastic contact under load control: the directions sum to zero on the contact set (the
  kept one too), so a step changes the load only where it is projected, and that change
  is undone by raising the flat (:func:`_restore_load`) rather than by scaling the field.
  Scaling shares the error out in proportion to the pressure, so a single cell carrying a
  large part of the load (an isolated spike of a measured surface) is pushed off its gap
  by far more than the gaps of the rest of the contact, every iteration, and the
  published iteration cycles on such a surface; raising the flat takes the excess where a
  rise of the flat does, from the rims of the contact spots and the points just entering.

On a rough surface at a contact fraction of a few per cent these cut the convolutions by
a factor of 3 to 4. The rest of an iteration is fused into a few compiled passes over
preallocated arrays. A preconditioned constrained conjugate gradient for this problem
(there with an FFT-based preconditioner): E. A. H. Vollebregt, "A new solver for the
elastic normal contact problem using conjugate gradients, deflation, and an FFT-based
preconditioner", J. Comput. Phys. 257 (2014) 333-351.

Reference: I. A. Polonsky, L. M. Keer, "A numerical method for solving rough contact
problems based on the multi-level multi-summation and conjugate gradient techniques",
Wear 231 (1999) 206-219.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numba as nb
import numpy as np

from ._influence import LinearOperator2D

__all__ = ["PKOutcome", "initial_pressure", "polonsky_keer"]

logger = logging.getLogger(__name__)

# consecutive carried-along displacement updates before an exact recomputation
_REFRESH = 50
# restart when |sum g t_old| exceeds this fraction of sum g z on the contact set
# (M. J. D. Powell, Math. Program. 12 (1977) 241-254)
_POWELL = 0.2


@nb.njit(cache=True, nogil=True)
def _gap(u, h, p, valid, g, shift, pmax):  # pragma: no cover - compiled
    """g = u - h + shift everywhere.

    Returns (sum of g on the free contact set ``0 < p < pmax``, its size, sum of g on the
    saturated points ``p >= pmax``, their number).
    """
    s = 0.0
    c = 0
    s_sat = 0.0
    c_sat = 0
    for i in range(g.size):
        gi = u[i] - h[i] + shift
        g[i] = gi
        pi = p[i]
        if pi > 0.0:
            if pi < pmax:
                s += gi
                c += 1
            else:
                s_sat += gi
                c_sat += 1
    return s, c, s_sat, c_sat


@nb.njit(cache=True, nogil=True)
def _shift_and_norm(g, shift, p, pmax):  # pragma: no cover - compiled
    """g -= shift everywhere; return the sum of g² on the free contact set."""
    s = 0.0
    for i in range(g.size):
        gi = g[i] - shift
        g[i] = gi
        if p[i] > 0.0 and p[i] < pmax:
            s += gi * gi
    return s


@nb.njit(cache=True, nogil=True)
def _direction(t, g, p, beta, pmax):  # pragma: no cover - compiled
    """Conjugate direction: t = g + beta t on the free contact set, 0 elsewhere."""
    for i in range(t.size):
        if p[i] > 0.0 and p[i] < pmax:
            t[i] = g[i] + beta * t[i]
        else:
            t[i] = 0.0


@nb.njit(cache=True, nogil=True)
def _contact_sum(r, p, pmax):  # pragma: no cover - compiled
    s = 0.0
    c = 0
    for i in range(r.size):
        if p[i] > 0.0 and p[i] < pmax:
            s += r[i]
            c += 1
    return s, c


@nb.njit(cache=True, nogil=True)
def _step_terms(g, t, r, rshift, p, pmax):  # pragma: no cover - compiled
    """Return sum(g t) and sum((r - rshift) t) over the free contact set."""
    num = 0.0
    den = 0.0
    for i in range(g.size):
        if p[i] > 0.0 and p[i] < pmax:
            num += g[i] * t[i]
            den += (r[i] - rshift) * t[i]
    return num, den


@nb.njit(cache=True, nogil=True)
def _update(p, t, g, tau, tau_enter, valid, p_new, pmax):  # pragma: no cover - compiled
    """Projected step; points that violate their complementarity condition join the free set.

    On the free contact set ``0 < p < pmax``: ``p - tau t`` projected onto ``[0, pmax]``.
    A point out of contact that interpenetrates (``g < 0``) enters with ``-tau_enter g``
    (at most ``pmax``); a saturated point (``p = pmax``) with an open gap (``g > 0``) is
    released to ``pmax - tau_enter g`` (at least ``pmax / 2``). ``pmax`` is ``inf`` for elastic
    contact, where the saturated branches never run.

    Returns (sum of the new pressure, points that entered or were released, points
    projected onto a bound, sum of the new pressure below ``pmax``, points at ``pmax``).
    """
    total = 0.0
    free_total = 0.0
    entered = 0
    clipped = 0
    n_sat = 0
    for i in range(p.size):
        pi = p[i]
        if pi > 0.0 and pi < pmax:
            v = pi - tau * t[i]
            if v <= 0.0:
                v = 0.0
                clipped += 1
            elif v >= pmax:
                v = pmax
                clipped += 1
        elif pi >= pmax:
            if g[i] > 0.0:
                # released, at most half-way down: the point stays in the free set, where
                # the conjugate gradient adjusts it (released at once, a whole plastic
                # zone would overshoot to zero and re-enter at the cap)
                v = pmax - tau_enter * g[i]
                if v < 0.5 * pmax:
                    v = 0.5 * pmax
                if v < pmax:
                    entered += 1
                else:
                    v = pmax  # an open gap at rounding level
            else:
                v = pmax
        elif valid[i] and g[i] < 0.0:
            v = -tau_enter * g[i]
            if v > pmax:
                v = pmax
            entered += 1
        else:
            v = 0.0
        p_new[i] = v
        total += v
        if v >= pmax:
            n_sat += 1
        else:
            free_total += v
    return total, entered, clipped, free_total, n_sat


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
def _capped_load(p, pmax, scale, scale_saturated):  # pragma: no cover - compiled
    """Load ``sum min(scale p, pmax)`` and its derivative in ``scale``.

    With ``scale_saturated`` False the points at ``pmax`` keep it and only the free
    contact points are scaled. Returns (load, derivative).
    """
    f = 0.0
    df = 0.0
    for i in range(p.size):
        v = p[i]
        if v > 0.0:
            if v >= pmax and not scale_saturated:
                f += pmax
                continue
            sv = scale * v
            if sv >= pmax:
                f += pmax
            else:
                f += sv
                df += v
    return f, df


@nb.njit(cache=True, nogil=True)
def _rescale_capped(p_new, p, scale, pmax, scale_saturated, u, r, w, tau, w_coef, carry
                    ):  # pragma: no cover - compiled
    """p_new = min(scale p_new, pmax) on the points being scaled; return (sum |p_new - p|,
    points newly capped).

    The points being scaled are the free contact points, and also the saturated ones when
    ``scale_saturated``. If ``carry``, the displacement is carried along:
    ``u = scale (u - tau r) + w_coef w`` (``w`` the displacement of a unit pressure on the
    saturated points, ``w_coef = (1 - scale) pmax``); it is exact only if no point is
    newly capped, which the caller checks.
    """
    s = 0.0
    capped = 0
    for i in range(p.size):
        v = p_new[i]
        if v > 0.0 and (scale_saturated or v < pmax):
            sv = v * scale
            if sv >= pmax:
                sv = pmax
                if v < pmax:
                    capped += 1
            v = sv
            p_new[i] = v
        s += abs(v - p[i])
        if carry:
            u[i] = scale * (u[i] - tau * r[i]) + w_coef * w[i]
    return s, capped


@nb.njit(cache=True, nogil=True)
def _precondition(stencil, g, gbar, p, t, nx, ny, periodic, z, pmax):  # pragma: no cover - compiled
    """z = S (g - gbar) on the free contact set, both ends restricted to it; 0 elsewhere.

    ``S`` is the local stencil of the inverse compliance (``(2R+1)`` square, centred).
    Returns (sum of z, sum of (g - gbar) z, sum of (g - gbar) t, sum of t, sum of z times
    the values ``z`` held on entry) over the free set; the accelerated iteration passes ``z``
    holding ``K t`` of the previous direction (the two share an array).
    """
    rad = stencil.shape[0] // 2
    zs = 0.0
    gz = 0.0
    gt = 0.0
    ts = 0.0
    zr = 0.0
    for i in range(nx):
        for j in range(ny):
            k = i * ny + j
            if p[k] > 0.0 and p[k] < pmax:
                acc = 0.0
                for a in range(-rad, rad + 1):
                    ii = i + a
                    if ii < 0 or ii >= nx:
                        if not periodic:
                            continue
                        ii %= nx
                    for b in range(-rad, rad + 1):
                        jj = j + b
                        if jj < 0 or jj >= ny:
                            if not periodic:
                                continue
                            jj %= ny
                        kk = ii * ny + jj
                        if p[kk] > 0.0 and p[kk] < pmax:
                            acc += stencil[a + rad, b + rad] * (g[kk] - gbar)
                zr += acc * z[k]
                z[k] = acc
                zs += acc
                gz += (g[k] - gbar) * acc
                gt += (g[k] - gbar) * t[k]
                ts += t[k]
            else:
                z[k] = 0.0
    return zs, gz, gt, ts, zr


@nb.njit(cache=True, nogil=True)
def _direction_preconditioned(t, z, zbar, tbar, g, gbar, p, beta, pmax):  # pragma: no cover - compiled
    """t = (z - zbar) + beta (t - tbar) on the free contact set, 0 elsewhere; g -= gbar everywhere.

    Returns sum((g - gbar) t) over the free contact set.
    """
    s = 0.0
    for i in range(t.size):
        gi = g[i] - gbar
        g[i] = gi
        if p[i] > 0.0 and p[i] < pmax:
            v = z[i] - zbar + beta * (t[i] - tbar)
            t[i] = v
            s += gi * v
        else:
            t[i] = 0.0
    return s


@nb.njit(cache=True, nogil=True)
def _unshift(g, gbar):  # pragma: no cover - compiled
    for i in range(g.size):
        g[i] += gbar


@nb.njit(cache=True, nogil=True)
def _flat_slopes(stencil, p, idx, nx, ny, periodic, tau, tau_enter, s):  # pragma: no cover - compiled
    """Pressure lost per unit rise of the flat by the points ``idx`` of an elastic step.

    Raising the flat opens the gap uniformly. On the contact set ``p > 0`` this changes the
    step ``-tau S (g - gbar)`` by ``-tau S 1`` (the stencil restricted to the contact set at
    both ends: the pressure of a flat punch as the local stencil sees it, largest at the rims
    of the contact spots, positive since ``S`` is diagonally dominant); an entering point's
    ``-tau_enter g`` changes by ``-tau_enter``. Writes ``s[m]`` for the point ``idx[m]``.
    """
    rad = stencil.shape[0] // 2
    for m in range(idx.size):
        k = idx[m]
        if not p[k] > 0.0:
            s[m] = tau_enter
            continue
        i = k // ny
        j = k - i * ny
        acc = 0.0
        if rad <= i < nx - rad and rad <= j < ny - rad:
            # away from the edges: no wrapping, and no branch (the contact set is ragged)
            for a in range(-rad, rad + 1):
                row = k + a * ny
                for b in range(-rad, rad + 1):
                    acc += stencil[a + rad, b + rad] * (p[row + b] > 0.0)
        else:
            for a in range(-rad, rad + 1):
                ii = i + a
                if ii < 0 or ii >= nx:
                    if not periodic:
                        continue
                    ii %= nx
                for b in range(-rad, rad + 1):
                    jj = j + b
                    if jj < 0 or jj >= ny:
                        if not periodic:
                            continue
                        jj %= ny
                    if p[ii * ny + jj] > 0.0:
                        acc += stencil[a + rad, b + rad]
        s[m] = tau * acc


@nb.njit(cache=True, nogil=True)
def _raised_load(p_new, idx, s, delta):  # pragma: no cover - compiled
    """Return (sum of max(p_new[idx] - delta s, 0), sum of s where it is positive)."""
    f = 0.0
    df = 0.0
    for m in range(idx.size):
        v = p_new[idx[m]] - delta * s[m]
        if v > 0.0:
            f += v
            df += s[m]
    return f, df


@nb.njit(cache=True, nogil=True)
def _raise(p_new, idx, s, delta, p):  # pragma: no cover - compiled
    """p_new[idx] = max(p_new[idx] - delta s, 0); return (its sum, points set to zero,
    entering points (``p = 0``) among them)."""
    total = 0.0
    gone = 0
    gone_entering = 0
    for m in range(idx.size):
        k = idx[m]
        v = p_new[k] - delta * s[m]
        if v > 0.0:
            total += v
        else:
            v = 0.0
            gone += 1
            if not p[k] > 0.0:
                gone_entering += 1
        p_new[k] = v
    return total, gone, gone_entering


@nb.njit(cache=True, nogil=True)
def _curvature(r, t, p, pmax):  # pragma: no cover - compiled
    """Return sum(r t), sum(r) and sum(t) over the free contact set and its size."""
    rt = 0.0
    rs = 0.0
    ts = 0.0
    c = 0
    for i in range(r.size):
        if p[i] > 0.0 and p[i] < pmax:
            rt += r[i] * t[i]
            rs += r[i]
            ts += t[i]
            c += 1
    return rt, rs, ts, c


@nb.njit(cache=True, nogil=True)
def _rescale_and_change_carry(p_new, p, scale, u, r, tau, carry):  # pragma: no cover - compiled
    """p_new *= scale; if ``carry``, u = scale (u - tau r); return sum |p_new - p|."""
    s = 0.0
    for i in range(p.size):
        v = p_new[i] * scale
        p_new[i] = v
        s += abs(v - p[i])
        if carry:
            u[i] = scale * (u[i] - tau * r[i])
    return s


@nb.njit(cache=True, nogil=True)
def _residuals(p, g, valid, pmax):  # pragma: no cover - compiled
    """Return (max |g| on the free contact set, max interpenetration -g out of contact,
    sum p |g| on the free set, max open gap g at the saturated points)."""
    on = 0.0
    off = 0.0
    comp = 0.0
    sat = 0.0
    for i in range(p.size):
        pi = p[i]
        if pi > 0.0 and pi < pmax:
            a = abs(g[i])
            if a > on:
                on = a
            comp += pi * a
        elif pi >= pmax:
            if g[i] > sat:
                sat = g[i]
        elif valid[i] and -g[i] > off:
            off = -g[i]
    return on, off, comp, sat


def initial_pressure(
    h: np.ndarray, valid: np.ndarray, mean_pressure: float, e_star: float, dx: float, dy: float,
    hardness: float | None = None,
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
    hardness : float, optional
        Pressure cap in pascals (elastic-perfectly-plastic surface): the start then covers
        at least twice the fraction ``mean_pressure / hardness`` that the load needs at the
        cap.

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
    if hardness is not None:
        fraction = max(fraction, min(1.0, 2.0 * mean_pressure / hardness))
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
    n_convolutions: int = 0  # applications of the compliance operator
    plastic_residual: float = 0.0  # max open gap at a saturated point (p = pmax), m


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
    accelerate: bool = True,
    overwrite_p0: bool = False,
    pmax: float | None = None,
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
        ``sum|p_k - p_(k-1)| / sum p_k``, falls below ``tol`` and no point entered the
        contact set.
    max_iter : int
        Iteration limit.
    p0 : ndarray, optional
        Initial pressure (Pa); default uniform over the valid points (load control) or
        ``max(h - d, 0)`` over the self-compliance (displacement control).
    accelerate : bool, default True
        True: preconditioned directions, kept when points enter the contact set, and the
        displacement carried along (module docstring). False: the iteration of Polonsky &
        Keer as published, the reference.
    overwrite_p0 : bool, default False
        Let the iteration use ``p0`` (C-contiguous float64) as its pressure array instead of
        a copy: one grid array less; ``p0`` is then overwritten.
    pmax : float, optional
        Pressure cap in pascals (the hardness of an elastic-perfectly-plastic surface):
        the pressure is bounded to ``[0, pmax]``, the conjugate gradient runs on the free
        points ``0 < p < pmax``, and saturated points (``p = pmax``) may interpenetrate.
        Under load control ``total_pressure`` must be below ``pmax`` times the number of
        valid points. None: elastic contact (no cap), the unchanged iteration.

    Returns
    -------
    PKOutcome
    """
    if (total_pressure is None) == (separation is None):
        raise ValueError("give exactly one of total_pressure and separation")
    shape = h.shape
    hf = np.ascontiguousarray(h, dtype=np.float64).ravel()
    vf = np.ascontiguousarray(valid, dtype=np.bool_).ravel()
    shift = 0.0 if separation is None else float(separation)
    cap = _check_cap(pmax, total_pressure, vf)
    p = _start(op, hf, vf, p0, overwrite_p0, total_pressure, shift, cap)
    iterate = _iterate_accelerated if accelerate else _iterate_reference
    p, g, state = iterate(op, shape, hf, vf, p, total_pressure, shift, float(tol), int(max_iter),
                          cap)
    return _outcome(op, shape, hf, vf, p, g, state, total_pressure is not None, shift, cap,
                    accelerate)


def _check_cap(pmax: float | None, total_pressure: float | None, vf: np.ndarray) -> float:
    """The pressure cap (Pa; ``inf`` without one), checked against the load."""
    cap = np.inf if pmax is None else float(pmax)
    if pmax is not None:
        if not (np.isfinite(cap) and cap > 0):
            raise ValueError(f"pmax must be finite and > 0, got {pmax!r}")
        if total_pressure is not None and not total_pressure < cap * int(vf.sum()):
            raise ValueError("total_pressure must be below pmax times the number of valid points")
    return cap


def _start(op, hf, vf, p0, overwrite_p0: bool, total_pressure: float | None, shift: float,
           cap: float) -> np.ndarray:
    """The starting pressure (Pa, flattened): ``p0`` or the default of :func:`polonsky_keer`,
    zero off the valid points, capped, and carrying the load under load control."""
    load_control = total_pressure is not None
    if p0 is not None:
        if overwrite_p0:
            p = np.ascontiguousarray(p0, dtype=np.float64).ravel()
        else:
            p = np.array(p0, dtype=np.float64).ravel()
        p[~vf] = 0.0
        p[p < 0] = 0.0
    elif load_control:
        p = np.where(vf, 1.0, 0.0)
    else:
        p = np.where(vf, np.maximum(hf - shift, 0.0), 0.0) / op.self_compliance
    if np.isfinite(cap):
        np.minimum(p, cap, out=p)
    if total_pressure is not None:
        s = p.sum()
        if not s > 0:
            p = np.where(vf, 1.0, 0.0)
            s = p.sum()
        if not np.isfinite(cap):
            p *= total_pressure / s
        else:
            p /= s / total_pressure  # a first guess of the scale; the cap is enforced below
            np.minimum(p, cap, out=p)
            scale, every, _ = _load_scale(p, total_pressure, cap, -hf, vf)
            _rescale_capped(p, p.copy(), scale, cap, every, p, p, p, 0.0, 0.0, False)
    return p


def _outcome(op, shape, hf, vf, p, g, state: dict, load_control: bool, shift: float, cap: float,
             accelerate: bool) -> PKOutcome:
    """The :class:`PKOutcome` of the final pressure: its displacement and gap computed
    afresh, the separation from the mean gap on the contact set (load control)."""
    u = op.apply(p.reshape(shape)).ravel()
    s, c, s_sat, c_sat = _gap(u, hf, p, vf, g, shift, cap)
    d = state["d"]
    if load_control and c > 0:
        gbar = s / c
        d = -gbar
        _shift_and_norm(g, gbar, p, cap)
    elif load_control and c_sat > 0:
        gbar = s_sat / c_sat
        d = -gbar
        _shift_and_norm(g, gbar, p, cap)
    on, off, _, sat = _residuals(p, g, vf, cap)
    logger.debug("%s iteration stopped after %d iterations and %d convolutions: %s",
                 "accelerated" if accelerate else "reference", state["n_iter"], state["n_conv"] + 1,
                 state["reason"])
    return PKOutcome(
        pressure=p.reshape(shape),
        displacement=u.reshape(shape),
        gap=g.reshape(shape),
        separation=float(d),
        converged=state["converged"],
        n_iterations=state["n_iter"],
        history=np.asarray(state["history"], dtype=float),
        reason=state["reason"],
        gap_residual=float(on),
        penetration=float(off),
        n_convolutions=state["n_conv"] + 1,
        plastic_residual=float(sat),
    )


def _load_scale(p: np.ndarray, total_pressure: float, pmax: float, g: np.ndarray,
                vf: np.ndarray, sums: tuple[float, float, int] | None = None
                ) -> tuple[float, bool, bool]:
    """The scale that brings a capped pressure to the load, ``sum min(s p, pmax) = total``.

    The free points are scaled and the saturated ones kept at ``pmax``; if these alone
    carry the load or more, every point in contact is scaled (and the saturated ones come
    off the cap). The load is concave and piecewise linear in ``s``: Newton's iteration from
    ``s0`` (the scale without capping, below the root) climbs to it monotonically and ends
    in a few steps. If the points in contact cannot carry the load at the cap, they are all
    set to ``pmax`` and the rest of the load is spread over the valid points out of contact
    with the smallest gap ``g`` (which then join the contact set; ``p`` is changed in place).

    ``sums`` is (sum of ``p``, sum of ``p`` below ``pmax``, points at ``pmax``) when known.

    Returns (scale, whether the saturated points are scaled too, whether points were added).
    """
    if sums is None:
        saturated = p >= pmax
        sums = (float(p.sum()), float(p[~saturated].sum()), int(np.count_nonzero(saturated)))
    total, free_total, n_sat = sums
    every = not total_pressure > n_sat * pmax
    base = 0.0 if every else n_sat * pmax
    varying = total if every else free_total
    if varying > 0:
        scale = (total_pressure - base) / varying
        for _ in range(100):
            f, df = _capped_load(p, pmax, scale, every)
            if f >= total_pressure or not df > 0:
                break
            step = (total_pressure - f) / df
            if not step > 1e-16 * scale:
                break
            scale += step
        if f >= total_pressure * (1.0 - 1e-12):
            return scale, every, False
    # not reachable with the present contact set: more points must carry the load
    np.copyto(p, pmax, where=p > 0)
    deficit = total_pressure - pmax * float(np.count_nonzero(p))
    candidates = np.flatnonzero(vf & (p <= 0))
    k = min(candidates.size, max(1, int(np.ceil(2.0 * deficit / pmax))))
    chosen = candidates[np.argpartition(g[candidates], k - 1)[:k]] if k < candidates.size \
        else candidates
    p[chosen] = deficit / chosen.size
    return 1.0, False, True


def _projected_step(p, t, g, tau, tau_enter, vf, p_new, pmax, total_pressure):
    """:func:`_update`, with the step halved (up to 20 times) while the projected pressure
    of a capped load-controlled problem either cannot carry the load (too many points
    clipped to zero) or carries it on its saturated points alone (too many capped).

    A step that clips a large part of the free set is what makes the bound-constrained
    iteration cycle; shortening it costs a pass over the grid, no convolution.
    Returns the outputs of :func:`_update`.
    """
    out = _update(p, t, g, tau, tau_enter, vf, p_new, pmax)
    if total_pressure is None or not np.isfinite(pmax):
        return out
    for _ in range(20):
        n_sat = out[4]
        if n_sat * pmax < total_pressure <= pmax * np.count_nonzero(p_new):
            break
        tau *= 0.5
        tau_enter *= 0.5
        out = _update(p, t, g, tau, tau_enter, vf, p_new, pmax)
    return out


def _restore_load(stencil, p, p_new, tau, tau_enter, total_pressure, total, nx, ny, periodic,
                  work) -> tuple[float, int, int]:
    """Bring the projected step ``p_new`` of an elastic contact back to the load by raising
    the flat; return (its new sum, points that left its support, entering points among them).

    The direction sums to zero on the contact set, so the step keeps the load there and
    only projection adds to it: a point clipped to zero gives back its negative pressure,
    an entering one brings ``-tau_enter g``. Scaling the whole field by ``P / sum(p)``
    (the published iteration) then shares the excess out in proportion to the pressure:
    a cell that carries a large part of the load (a tall isolated pixel) has its gap thrown
    off by its share times its compliance, far beyond the gaps of the rest of the contact,
    and the next step, spent on that cell, clips and adds thousands of other points again:
    the iteration cycles. The load is balanced instead the way it is at the solution, by
    the height of the flat. Raising it by ``delta >= 0`` takes ``delta s_i`` off each point
    of the step (:func:`_flat_slopes`); points that reach zero leave. The load
    ``sum max(p_new - delta s, 0)`` is piecewise linear, convex and decreasing in
    ``delta``: Newton's iteration from ``delta = 0`` climbs to the root monotonically, in a
    few passes over the support of the step, no convolution. ``work`` is a free array of the
    grid's size (overwritten).
    """
    idx = np.flatnonzero(p_new > 0)  # the support of the step
    s = work[: idx.size]
    _flat_slopes(stencil, p, idx, nx, ny, periodic, tau, tau_enter, s)
    delta = 0.0
    f, df = total, float(s.sum())
    for _ in range(100):
        if not (f > total_pressure * (1.0 + 1e-12) and df > 0):
            break
        delta += (f - total_pressure) / df
        f, df = _raised_load(p_new, idx, s, delta)
    return _raise(p_new, idx, s, delta, p)


def _empty_contact(vf: np.ndarray, g: np.ndarray, load_control: bool, state: dict) -> bool:
    """Handle an empty contact set; return True if the iteration must stop."""
    if load_control:
        state["reason"] = "contact set became empty"
        return True
    # displacement control with nothing in contact: p = 0 is the answer if nothing
    # interpenetrates; otherwise the points that do enter in the update
    if not np.any(vf & (g < 0)):
        state["converged"] = True
        state["reason"] = "no contact at this separation"
        state["history"].append(0.0)
        return True
    return False


def _new_state(shift: float) -> dict:
    return {
        "converged": False,
        "reason": "iteration limit reached",
        "n_iter": 0,
        "n_conv": 0,
        "history": [],
        "d": shift,
    }


def _load_multiplier(s: float, c: int, s_sat: float, c_sat: int, load_control: bool) -> float:
    """Mean gap removed under load control: over the free contact set, or over the
    saturated points when no point is free (displacement control: 0)."""
    if not load_control:
        return 0.0
    if c > 0:
        return s / c
    return s_sat / c_sat if c_sat > 0 else 0.0


def _iterate_reference(op, shape, hf, vf, p, total_pressure, shift, tol, max_iter, pmax):
    """The iteration of Polonsky & Keer (1999): two convolutions per iteration.

    With a finite ``pmax`` the bound-constrained form (Almqvist et al. 2007): the
    conjugate gradient on the free points ``0 < p < pmax``, projection onto ``[0, pmax]``.
    """
    load_control = total_pressure is not None
    capped = np.isfinite(pmax)
    state = _new_state(shift)
    g = np.empty_like(p)
    t = np.zeros_like(p)
    p_new = np.empty_like(p)
    g_old = 1.0
    conj = False

    for it in range(1, max_iter + 1):
        state["n_iter"] = it
        u = op.apply(p.reshape(shape)).ravel()
        s, c, s_sat, c_sat = _gap(u, hf, p, vf, g, shift, pmax)
        if c == 0 and c_sat == 0 and _empty_contact(vf, g, load_control, state):
            break
        gbar = _load_multiplier(s, c, s_sat, c_sat, load_control)
        if load_control:
            state["d"] = -gbar
        gnorm = _shift_and_norm(g, gbar, p, pmax)
        beta = gnorm / g_old if conj else 0.0
        g_old = gnorm if gnorm > 0 else 1.0
        _direction(t, g, p, beta, pmax)
        r = op.apply(t.reshape(shape)).ravel()
        state["n_conv"] += 2
        if load_control:
            rs, rc = _contact_sum(r, p, pmax)
            rbar = rs / rc if rc else 0.0
        else:
            rbar = 0.0
        num, den = _step_terms(g, t, r, rbar, p, pmax)
        tau = num / den if den > 0 else 0.0
        # Polonsky & Keer let interpenetrating points enter with the step length tau;
        # when the contact set admits no descent step (a single point, or g already 0
        # there) the local self-compliance gives the step instead.
        tau_enter = tau if tau > 0 else 1.0 / op.self_compliance
        total, entered, _, free_total, n_sat = _projected_step(p, t, g, tau, tau_enter, vf, p_new,
                                                               pmax, total_pressure)
        conj = entered == 0
        if load_control and capped:
            scale, every, added = _load_scale(p_new, total_pressure, pmax, g, vf,
                                              (total, free_total, n_sat))
            conj = conj and not added
            change, _ = _rescale_capped(p_new, p, scale, pmax, every, p, p, p, 0.0, 0.0, False)
        else:
            if load_control:
                if not total > 0:
                    state["reason"] = "pressure vanished everywhere (step failure)"
                    break
                scale = total_pressure / total
            else:
                scale = 1.0
            change = _rescale_and_change(p_new, p, scale)
        p, p_new = p_new, p
        if _stop(p, change, entered, tol, state):
            break
    return p, g, state


def _stop(p: np.ndarray, change: float, entered: int, tol: float, state: dict) -> bool:
    """Record the relative pressure change; return True when the iteration must stop."""
    norm = p.sum()
    err = change / norm if norm > 0 else (0.0 if change == 0 else np.inf)
    state["history"].append(err)
    logger.debug("iteration %d: relative pressure change %.3e, %d point(s) entered the contact set",
                 state["n_iter"], err, entered)
    if not np.isfinite(err):
        state["reason"] = "non-finite values in the iteration"
        return True
    if err < tol and entered == 0:
        state["converged"] = True
        state["reason"] = "relative pressure change below tolerance"
        return True
    return False


def _conjugation(conj: bool, capped: bool, gz: float, gt: float, gz_old: float,
                 gz_prev: float = 0.0) -> float:
    """``beta`` of the preconditioned conjugate direction: ``gz / gz_old``, or 0 (a restart
    to steepest descent) when the direction is not to be kept (``conj`` False) or fails
    Powell's test, against the previous direction (``gt``) or the previous preconditioned
    gap (``gz_prev``, the sum of ``g z_old``), or, with a cap, when the residual grew."""
    if conj and abs(gt) > _POWELL * gz:
        conj = False
    if conj and abs(gz_prev) > _POWELL * gz:
        # the directions are no longer conjugate: after an exact line search on an
        # unchanged contact set the gap is orthogonal to the last direction whatever the
        # conjugacy (the test above passes), to the last preconditioned gap only with it
        conj = False
    if conj and capped and gz * _POWELL > gz_old:
        # the free set changed so much that the residual grew (the old one may have
        # been almost solved): the kept direction would swamp the new gradient
        conj = False
    return gz / gz_old if conj else 0.0


def _iterate_accelerated(op, shape, hf, vf, p, total_pressure, shift, tol, max_iter, pmax):
    """Preconditioned directions kept across contact-set growth; displacement carried along;
    elastic, under load control, the load restored by the height of the flat.

    With a finite ``pmax`` the same on the free points ``0 < p < pmax``; the load is then
    restored by scaling the free points only, so a carried-along displacement also needs
    that of the saturated points, ``w = K 1_sat``, computed once for each saturated set
    that lasts more than one iteration.
    """
    load_control = total_pressure is not None
    capped = np.isfinite(pmax)
    state = _new_state(shift)
    g = np.empty_like(p)
    t = np.zeros_like(p)
    p_new = np.empty_like(p)
    u = np.empty_like(p)  # K p, carried along or recomputed
    r = np.zeros_like(p)  # K t (zero before the first direction)
    w = np.zeros_like(p) if capped and load_control else None  # K 1_sat
    w_fresh = False  # w belongs to the present saturated set
    op.apply(p.reshape(shape), out=u.reshape(shape))
    state["n_conv"] += 1
    stencil = op.inverse_stencil()
    stencil_centre = float(stencil[stencil.shape[0] // 2, stencil.shape[1] // 2])
    nx, ny = shape
    z = r  # the preconditioned gap is used up before K t is computed into the same array
    gz_old = 1.0
    conj = False
    carried = 0  # carried-along updates of u since it was last computed exactly
    unchanged = False  # elastic load control: the last step kept the contact set
    tau_old = rbar_old = 0.0

    for it in range(1, max_iter + 1):
        state["n_iter"] = it
        s, c, s_sat, c_sat = _gap(u, hf, p, vf, g, shift, pmax)
        if c == 0 and c_sat == 0 and _empty_contact(vf, g, load_control, state):
            break
        gbar = _load_multiplier(s, c, s_sat, c_sat, load_control)
        if load_control:
            state["d"] = -gbar
        zs, gz, gt, ts, zr = _precondition(stencil, g, gbar, p, t, nx, ny, op.periodic, z,
                                           pmax)
        # the load constraint: directions of zero sum on the contact set; elastic, the kept
        # one too (built on the previous contact set, it need not sum to zero on this one),
        # so that a step on an unchanged contact set keeps the load to rounding
        zbar = zs / c if (load_control and c > 0) else 0.0
        tbar = ts / c if (load_control and not capped and c > 0) else 0.0
        # Powell's test on consecutive gaps (elastic, load control): after a step that left
        # the contact set unchanged, the gap (mean removed) is g_old - tau_old (K t_old -
        # rbar_old), K t_old being what z held on entry to the pass above; S being symmetric,
        # sum g z_old = sum z g_old = gz + tau_old (zr - rbar_old zs), without z_old stored
        gz_prev = gz + tau_old * (zr - rbar_old * zs) if unchanged else 0.0
        beta = _conjugation(conj, capped, gz, gt, gz_old, gz_prev)
        gz_old = gz if gz > 0 else 1.0
        num = _direction_preconditioned(t, z, zbar, tbar, g, gbar, p, beta, pmax)
        if beta != 0.0 and not num > 0.0:
            # the kept direction is no longer a descent direction: restart
            _unshift(g, gbar)
            num = _direction_preconditioned(t, z, zbar, 0.0, g, gbar, p, 0.0, pmax)
        op.apply(t.reshape(shape), out=r.reshape(shape))
        state["n_conv"] += 1
        rt, rs, ts, rc = _curvature(r, t, p, pmax)
        # sum over the contact set of (r - rbar) t, rbar the mean of r there (load control)
        den = rt - (rs / rc) * ts if (load_control and rc) else rt
        tau = num / den if den > 0 else 0.0
        tau_old, rbar_old = tau, (rs / rc if rc else 0.0)
        # an interpenetrating point enters with the pressure the preconditioned step would
        # give it alone, tau S0 |g| (S0 the local stiffness, the stencil's centre)
        tau_enter = tau * stencil_centre if tau > 0 else 1.0 / op.self_compliance
        total, entered, clipped, free_total, n_sat = _projected_step(
            p, t, g, tau, tau_enter, vf, p_new, pmax, total_pressure)
        conj = tau > 0
        carry = entered == 0 and clipped == 0 and carried < _REFRESH
        if load_control and capped:
            scale, every, added = _load_scale(p_new, total_pressure, pmax, g, vf,
                                              (total, free_total, n_sat))
            carry = carry and not (every or added)
            if added:
                conj = False
            w_coef = 0.0
            if carry and n_sat > 0:
                if not w_fresh:
                    op.apply(np.where(p_new >= pmax, 1.0, 0.0).reshape(shape), out=w.reshape(shape))
                    state["n_conv"] += 1
                    w_fresh = True
                w_coef = (1.0 - scale) * pmax
            change, newly = _rescale_capped(p_new, p, scale, pmax, every, u, r, w, tau, w_coef,
                                            carry)
            carry = carry and newly == 0
        else:
            if load_control:
                if (entered or clipped) and tau > 0 and total > total_pressure:
                    # K t in r is free: no displacement is carried along after a step that
                    # changed the contact set, nor is it used by the next Powell test
                    total, gone, gone_entering = _restore_load(
                        stencil, p, p_new, tau, tau_enter, total_pressure, total, nx, ny,
                        op.periodic, r)
                    entered -= gone_entering
                    clipped += gone - gone_entering
                if not total > 0:
                    state["reason"] = "pressure vanished everywhere (step failure)"
                    break
                # at rounding level once the flat has restored the load, or after a step
                # that neither clipped nor added a point
                scale = total_pressure / total
            else:
                scale = 1.0
            change = _rescale_and_change_carry(p_new, p, scale, u, r, tau, carry)
        p, p_new = p_new, p
        unchanged = load_control and not capped and not (entered or clipped)
        if carry:
            carried += 1
        else:
            op.apply(p.reshape(shape), out=u.reshape(shape))
            state["n_conv"] += 1
            carried = 0
            w_fresh = False
        if _stop(p, change, entered, tol, state):
            break
    return p, g, state
