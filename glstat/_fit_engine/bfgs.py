"""Compiled minimiser of the data-based objectives (:mod:`glstat._fit_engine.likelihood`).

`minimize_bfgs` is a small quasi-Newton (BFGS) method with a backtracking line search that
rejects every trial step whose shapes are invalid or whose support misses a data point, so
each iterate stays feasible; the linearisation w + (dw/dtheta) step warm-starts the inversion
at each trial point. It optimises theta = (lambda1, log scale, lambda3, lambda4), or the
parameters left when one or both support end points are pinned just outside the data.
"""

import math

import numpy as np
from numba import njit

from .._core.quantile_function import RS, q_lower
from . import kernels as K
from .likelihood import W_MAX, feasible, objective_grad

# termination codes of `minimize_bfgs`
GTOL = 0  # gradient below tolerance
FTOL = 1  # relative decrease below tolerance
LSFAIL = 2  # no decrease along the search direction (noise floor or active support bound)
MAXITER = 3  # iteration limit
INFEASIBLE = 4  # the start is infeasible
DEGENERATE = 5  # RS shapes ran into the degenerate origin (lambda3, lambda4 -> 0)

# RS iterates with max(|lambda3|, |lambda4|) below this are heading into the origin, where the
# RS family degenerates: the objective creeps towards its lambda -> 0 limit (the FKML
# distributions with lambda3 = lambda4 = 0 and their ratio family) while the scale diverges,
# which takes hundreds of iterations for a gain far below the tolerance; such a start is stopped
_DEGEN_SHAPE = 1e-4

# parameterisations of `minimize_bfgs`: FREE optimises theta; the others pin the lower, the upper
# or both end points of the support at a distance ``gap`` outside the data and optimise the rest
FREE = 0
PIN_LOWER = 1
PIN_UPPER = 2
PIN_BOTH = 3


@njit(cache=True)
def _ends(fam, a, b):
    """Standardized support end points and d(lower)/da, d(upper)/db (other derivatives are 0).

    RS end points are constant within a region; FKML has -1/a (a > 0) and 1/b (b > 0).
    """
    lo = q_lower(fam, a, b, -math.inf, 0.0)
    hi = -q_lower(fam, b, a, -math.inf, 0.0)
    dlo = 1.0 / (a * a) if (fam != RS and a > 0.0) else 0.0
    dhi = -1.0 / (b * b) if (fam != RS and b > 0.0) else 0.0
    return lo, hi, dlo, dhi


@njit(cache=True)
def n_free(mode):
    """Number of optimised parameters in ``mode``."""
    if mode == FREE:
        return 4
    if mode == PIN_BOTH:
        return 2
    return 3


@njit(cache=True)
def theta_from_phi(mode, fam, phi, zmin, zmax, gap, theta, jac):
    """theta (lambda1, log scale, lambda3, lambda4) and d theta / d phi for ``mode``.

    FREE: phi = theta. PIN_LOWER / PIN_UPPER: phi = (log scale, lambda3, lambda4) and lambda1
    puts the lower (upper) end point at zmin - gap (zmax + gap). PIN_BOTH: phi = (lambda3,
    lambda4), both end points pinned. Returns False where a pinned end point is infinite.
    """
    for j in range(4):
        for k in range(4):
            jac[j, k] = 0.0
    if mode == FREE:
        for j in range(4):
            theta[j] = phi[j]
            jac[j, j] = 1.0
        return True
    if mode == PIN_BOTH:
        a = phi[0]
        b = phi[1]
    else:
        a = phi[1]
        b = phi[2]
    lo, hi, dlo, dhi = _ends(fam, a, b)
    theta[2] = a
    theta[3] = b
    if mode == PIN_BOTH:
        if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
            return False
        scale = (zmax - zmin + 2.0 * gap) / (hi - lo)
        theta[1] = math.log(scale)
        theta[0] = zmin - gap - scale * lo
        dla = dlo / (hi - lo)
        dlb = -dhi / (hi - lo)
        jac[1, 0] = dla
        jac[1, 1] = dlb
        jac[0, 0] = -scale * (dla * lo + dlo)
        jac[0, 1] = -scale * dlb * lo
        jac[2, 0] = 1.0
        jac[3, 1] = 1.0
        return True
    scale = math.exp(phi[0])
    theta[1] = phi[0]
    jac[1, 0] = 1.0
    jac[2, 1] = 1.0
    jac[3, 2] = 1.0
    if mode == PIN_LOWER:
        if not math.isfinite(lo):
            return False
        theta[0] = zmin - gap - scale * lo
        jac[0, 0] = -scale * lo
        jac[0, 1] = -scale * dlo
    else:
        if not math.isfinite(hi):
            return False
        theta[0] = zmax + gap - scale * hi
        jac[0, 0] = -scale * hi
        jac[0, 2] = -scale * dhi
    return True


@njit(cache=True)
def phi_from_theta(mode, theta, phi):
    """The optimised parameters of ``mode`` taken from theta (see `theta_from_phi`)."""
    if mode == FREE:
        for j in range(4):
            phi[j] = theta[j]
    elif mode == PIN_BOTH:
        phi[0] = theta[2]
        phi[1] = theta[3]
    else:
        phi[0] = theta[1]
        phi[1] = theta[2]
        phi[2] = theta[3]


@njit(cache=True)
def _violated(fam, theta, zmin, zmax):
    """Bit mask of the support end points that miss the data (1 lower, 2 upper); 0 when the
    shapes are invalid or the scale is not finite."""
    a = theta[2]
    b = theta[3]
    scale = math.exp(theta[1])
    if not (K.shape_valid(fam, a, b) and scale > 0.0 and math.isfinite(scale)):
        return 0
    lo, hi, _, _ = _ends(fam, a, b)
    bits = 0
    if not ((zmin - theta[0]) / scale > lo):
        bits |= 1
    if not ((zmax - theta[0]) / scale < hi):
        bits |= 2
    return bits


@njit(cache=True)
def _chain_gradient(m, jac, gth, g):
    """The gradient ``g`` in the ``m`` optimised parameters from ``gth``, that in theta, and
    the Jacobian d theta / d phi."""
    for k in range(m):
        g[k] = 0.0
        for j in range(4):
            g[k] += jac[j, k] * gth[j]


@njit(cache=True)
def _search_direction(m, h, g, p, scaled):
    """The quasi-Newton direction ``p = -H g``; the steepest descent (and H reset to the
    identity) when that is not a descent direction. Returns (g'p, scaled)."""
    gp = 0.0
    for j in range(m):
        p[j] = 0.0
        for k in range(m):
            p[j] -= h[j, k] * g[k]
        gp += p[j] * g[j]
    if not (gp < 0.0):
        h[:, :] = np.eye(m)
        scaled = False
        gp = 0.0
        for j in range(m):
            p[j] = -g[j]
            gp -= g[j] * g[j]
    return gp, scaled


@njit(cache=True)
def _line_search(kind, fam, mode, z, gap, m, phi, p, f, gp, alpha0, pmax, theta, w, dw,
                 pt, tt, jact, wt, dwt, gth, y):
    """Backtracking line search from ``phi`` along ``p``, starting at step ``alpha0``.

    Infeasible trial points halve the step; feasible ones are accepted by the Armijo
    condition, or shrink the step to the minimiser of the quadratic through f, the slope
    g'p and the trial value, kept in [0.1, 0.5] of the step. The trial point's phi, theta,
    Jacobian, warm start, its derivatives and gradient are left in ``pt``, ``tt``, ``jact``,
    ``wt``, ``dwt`` and ``gth``.

    Returns
    -------
    accepted : bool
    alpha, ft : float
        The last step and the objective there.
    nfev : int
        Objective evaluations.
    hit : int
        Bit mask of the support end points (1 lower, 2 upper) missed by trial points.
    """
    n = z.shape[0]
    zmin = z[0]
    zmax = z[n - 1]
    alpha = alpha0
    accepted = False
    ft = math.inf
    nfev = 0
    hit = 0
    for _ in range(60):
        for j in range(m):
            pt[j] = phi[j] + alpha * p[j]
        ok = theta_from_phi(mode, fam, pt, zmin, zmax, gap, tt, jact)
        if ok and feasible(fam, tt[2], tt[3], tt[0], math.exp(tt[1]), zmin, zmax):
            for i in range(n):
                pred = w[i]
                for j in range(4):
                    pred += dw[i, j] * (tt[j] - theta[j])
                wt[i] = min(max(pred, -W_MAX), W_MAX)
            ft = objective_grad(kind, fam, tt, z, wt, dwt, gth, y)
            nfev += 1
            if ft <= f + 1e-4 * alpha * gp:
                accepted = True
                break
            if math.isfinite(ft):
                # minimiser of the quadratic through f, the slope and ft, kept in [0.1, 0.5]
                den = 2.0 * (ft - f - alpha * gp)
                anew = -gp * alpha * alpha / den if den > 0.0 else 0.5 * alpha
                alpha = min(0.5 * alpha, max(0.1 * alpha, anew))
            else:
                alpha *= 0.5
        else:
            if ok:
                hit |= _violated(fam, tt, zmin, zmax)
            alpha *= 0.5
        size = 1.0
        for j in range(m):
            size += abs(phi[j])
        if alpha * pmax <= 1e-15 * size:
            break
    return accepted, alpha, ft, nfev, hit


@njit(cache=True)
def _bfgs_update(m, h, phi, pt, g, gt, s, yv, hy, scaled):
    """BFGS update of the inverse Hessian ``h`` with the step ``pt - phi`` and the gradient
    change ``gt - g``, skipped unless the curvature s'y is positive; the first update also
    scales ``h`` to s'y / y'y. Returns whether ``h`` is scaled."""
    sy = 0.0
    yy = 0.0
    ss = 0.0
    for j in range(m):
        s[j] = pt[j] - phi[j]
        yv[j] = gt[j] - g[j]
        sy += s[j] * yv[j]
        yy += yv[j] * yv[j]
        ss += s[j] * s[j]
    if sy > 1e-12 * math.sqrt(ss * yy):
        if not scaled:
            h[:, :] = np.eye(m) * (sy / yy)
            scaled = True
        # H <- (I - rho s y') H (I - rho y s') + rho s s'
        rho = 1.0 / sy
        for j in range(m):
            hy[j] = 0.0
            for k in range(m):
                hy[j] += h[j, k] * yv[k]
        yhy = 0.0
        for j in range(m):
            yhy += yv[j] * hy[j]
        for j in range(m):
            for k in range(m):
                h[j, k] += (rho * rho * yhy + rho) * s[j] * s[k] - rho * (hy[j] * s[k] + s[j] * hy[k])
    return scaled


@njit(cache=True)
def minimize_bfgs(kind, fam, z, theta, w, maxiter, unit, gtol, ftol, mode, gap):
    """Minimise `objective_grad` by BFGS with a feasible backtracking line search.

    Parameters
    ----------
    kind, fam : int
        Objective and family.
    z : ndarray, shape (n,)
        Sorted standardized sample.
    theta : ndarray, shape (4,)
        Feasible start (lambda1, log scale, lambda3, lambda4); receives the minimiser.
    w : ndarray, shape (n,)
        Warm start of the logit probabilities; receives those at the minimiser.
    maxiter : int
        Iteration limit.
    unit : float
        Objective unit for the tolerances (the objective divided by ``unit`` is a mean per
        data point).
    gtol : float
        Stop when max |gradient| / unit <= gtol.
    ftol : float
        Stop when the decrease predicted by the quasi-Newton model, or that of a full
        quasi-Newton step, is <= ftol * max(unit, |f|).
    mode : int
        FREE, or PIN_LOWER, PIN_UPPER, PIN_BOTH: the support end point(s) held at ``gap``
        outside the data (see `theta_from_phi`).
    gap : float
        Distance of pinned end points from the data (units of z).

    Returns
    -------
    f : float
        Objective at the minimiser (+inf when the start is infeasible).
    nit, nfev : int
        Iterations and objective evaluations.
    status : int
        GTOL, FTOL, LSFAIL, MAXITER, INFEASIBLE or DEGENERATE (RS shapes below
        ``_DEGEN_SHAPE`` in magnitude: the start heads into the degenerate origin and is
        stopped there).
    hit : int
        Bit mask of the support end points (1 lower, 2 upper) that cut the last line search
        short: a constraint that is active at the minimiser.
    """
    n = z.shape[0]
    m = n_free(mode)
    zmin = z[0]
    zmax = z[n - 1]
    y = np.empty(n)
    dw = np.empty((n, 4))
    dwt = np.empty((n, 4))
    wt = np.empty(n)
    gth = np.empty(4)
    g = np.zeros(4)
    gt = np.zeros(4)
    phi = np.zeros(4)
    pt = np.zeros(4)
    tt = np.empty(4)
    jac = np.empty((4, 4))
    jact = np.empty((4, 4))
    p = np.zeros(4)
    s = np.zeros(4)
    yv = np.zeros(4)
    hy = np.zeros(4)
    h = np.eye(m)
    phi_from_theta(mode, theta, phi)
    hit = 0
    if not theta_from_phi(mode, fam, phi, zmin, zmax, gap, tt, jac):
        return math.inf, 0, 0, INFEASIBLE, hit
    f = objective_grad(kind, fam, tt, z, w, dw, gth, y)
    nfev = 1
    if not math.isfinite(f):
        return f, 0, nfev, INFEASIBLE, hit
    for j in range(4):
        theta[j] = tt[j]
    _chain_gradient(m, jac, gth, g)
    scaled = False
    status = MAXITER
    nit = 0
    for it in range(maxiter):
        nit = it + 1
        gmax = 0.0
        for j in range(m):
            gmax = max(gmax, abs(g[j]))
        if gmax <= gtol * unit:
            status = GTOL
            nit = it
            break
        gp, scaled = _search_direction(m, h, g, p, scaled)
        if scaled and -gp <= ftol * max(unit, abs(f)):
            # the quasi-Newton model predicts no further decrease worth having
            status = FTOL
            nit = it
            break
        pmax = 0.0
        for j in range(m):
            pmax = max(pmax, abs(p[j]))
        # trust the first (unscaled) direction to 0.1 in each coordinate, later ones to 1
        alpha0 = min(1.0, (1.0 if scaled else 0.1) / pmax)
        accepted, alpha, ft, evals, hit = _line_search(kind, fam, mode, z, gap, m, phi, p, f, gp,
                                                       alpha0, pmax, theta, w, dw, pt, tt, jact, wt,
                                                       dwt, gth, y)
        nfev += evals
        if not accepted:
            status = LSFAIL
            break
        _chain_gradient(m, jact, gth, gt)
        scaled = _bfgs_update(m, h, phi, pt, g, gt, s, yv, hy, scaled)
        decrease = f - ft
        for j in range(4):
            phi[j] = pt[j]
            g[j] = gt[j]
            theta[j] = tt[j]
        for i in range(n):
            w[i] = wt[i]
            for j in range(4):
                dw[i, j] = dwt[i, j]
        f = ft
        if fam == RS and max(abs(theta[2]), abs(theta[3])) < _DEGEN_SHAPE:
            status = DEGENERATE
            break
        if decrease <= ftol * max(unit, abs(f)) and alpha == alpha0:
            # a full quasi-Newton step gains nothing
            status = FTOL
            break
    return f, nit, nfev, status, hit
