"""Compiled core of the data-based GLD fits: maximum likelihood, maximum product of spacings,
starship (numba kernels, no Python objects).

All three objectives need the probability integral transform u_i = F(x_i) of the sorted
sample for every trial parameter. `pit_logit` inverts Q in logit coordinates
w = log(u / (1 - u)) by a bracketed Newton iteration from a warm start.

The parameters are theta = (lambda1, log scale, lambda3, lambda4) of the GLD of the sample
standardized by its median and interquartile range (scale = 1/|lambda2|). The gradient of each
objective follows from implicit differentiation of Q(u_i; lambda3, lambda4) = y_i with
y_i = (z_i - lambda1) / scale:

    dw_i/dtheta = -(dR/dtheta) / (dQ/dw),   dR/dtheta = (1/scale, y_i, dQ/dlambda3, dQ/dlambda4),

and, for ML, from the derivatives of log Q'(u) at fixed u. `minimize_bfgs` is a small
quasi-Newton (BFGS) method with a backtracking line search that rejects every trial step whose
shapes are invalid or whose support misses a data point, so each iterate stays feasible; the
linearisation w + (dw/dtheta) step warm-starts the inversion at each trial point.
"""

import math

import numpy as np
from numba import njit

from .._core.quantile_function import RS, log_qprime_lower, q_lower, qprime_lower, rs_sign
from . import _kernels as K

MLE = 0
MPS = 1
STARSHIP = 2

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

_W_MAX = 740.0  # |logit u| beyond which u or 1 - u underflows


@njit(cache=True)
def _logsig(w):
    """log(1 / (1 + exp(-w))) without overflow."""
    if w > 0.0:
        return -math.log1p(math.exp(-w))
    return w - math.log1p(math.exp(w))


@njit(cache=True, inline="always")
def _spacing(w, i, prev_u):
    """Spacing i of the sorted PIT values u = sigmoid(w) (i = 0..n, with u_0 = 0, u_{n+1} = 1)
    and the new running u; two points in the upper half are differenced through their
    survival probabilities, which keeps the spacing's relative accuracy there."""
    n = w.shape[0]
    if i == n:
        return math.exp(_logsig(-w[n - 1])), prev_u
    wi = w[i]
    ui = math.exp(_logsig(wi))
    if i > 0 and wi > 0.0 and w[i - 1] > 0.0:
        return math.exp(_logsig(-w[i - 1])) - math.exp(_logsig(-wi)), ui
    return ui - prev_u, ui


@njit(cache=True)
def _q_w_ref(fam, a, b, w):
    """Standardized Q and dQ/dw at u = 1 / (1 + exp(-w)) from the generic lower-tail kernels."""
    t = _logsig(w)
    l1 = _logsig(-w)
    if w <= 0.0:
        q = q_lower(fam, a, b, t, l1)
        qp = qprime_lower(fam, a, b, t, l1)
    else:
        q = -q_lower(fam, b, a, l1, t)
        qp = qprime_lower(fam, b, a, l1, t)
    return q, qp * math.exp(t + l1)


@njit(cache=True)
def _q_w(fam, a, b, w):
    """Standardized Q and dQ/dw at u = 1 / (1 + exp(-w)) with four elementary functions.

    Works on the smaller tail probability p = e / (1 + e), e = exp(-|w|) (upper half by the
    reflection Q_{a,b}(u) = -Q_{b,a}(1 - u)); dQ/dw = Q'(u) u (1 - u) is formed without
    dividing by p. The mixed-sign RS regions (2, 6), where the two terms of Q' cancel, use
    the cancellation-free kernel.
    """
    e = math.exp(-abs(w))
    lg = math.log1p(e)
    t = -abs(w) - lg  # log p
    l1 = -lg  # log(1 - p)
    p = e / (1.0 + e)
    q1p = 1.0 / (1.0 + e)
    if w <= 0.0:
        aa = a
        bb = b
    else:
        aa = b
        bb = a
    ema = math.expm1(aa * t) if aa != 0.0 else 0.0
    emb = math.expm1(bb * l1) if bb != 0.0 else 0.0
    # p**aa and (1-p)**bb: 1 + expm1 cancels where the power is small
    ea = 1.0 + ema if ema > -0.5 else math.exp(aa * t)
    eb = 1.0 + emb if emb > -0.5 else math.exp(bb * l1)
    if fam == RS:
        s = rs_sign(a, b)
        q = s * (ema - emb)
        if s > 0.0 or aa <= 0.0:
            dq = s * (aa * ea * q1p + bb * eb * p)
        else:
            dq = qprime_lower(fam, aa, bb, t, l1) * p * q1p
    else:
        ga = ema / aa if aa != 0.0 else t
        gb = emb / bb if bb != 0.0 else l1
        q = ga - gb
        dq = ea * q1p + eb * p
    if w > 0.0:
        q = -q
    return q, dq


@njit(cache=True)
def _logqp_w(fam, a, b, w):
    """log Q'(u) at u = 1 / (1 + exp(-w)) (minus the log density of the standardized GLD)."""
    t = _logsig(w)
    l1 = _logsig(-w)
    if w <= 0.0:
        return log_qprime_lower(fam, a, b, t, l1)
    return log_qprime_lower(fam, b, a, l1, t)


@njit(cache=True)
def pit_logit(fam, a, b, y, w):
    """Solve Q(u_i) = y_i for sorted standardized ``y``; ``w`` (logit u) is the warm start
    and receives the solution. Returns False when a point lies outside the support or an
    iteration fails."""
    n = y.shape[0]
    lo_end = q_lower(fam, a, b, -math.inf, 0.0)
    hi_end = -q_lower(fam, b, a, -math.inf, 0.0)
    if not (y[0] > lo_end and y[n - 1] < hi_end):
        return False
    for i in range(n):
        lo0 = -_W_MAX
        if i > 0 and w[i - 1] > lo0:
            lo0 = w[i - 1] - 1e-9 * (1.0 + abs(w[i - 1]))
        ok = False
        wi = w[i]
        # first from the warm start, then (should that fail, e.g. after a large change of the
        # parameters) from the plotting position of the point
        for attempt in range(2):
            if attempt == 1:
                wi = math.log((i + 0.5) / (n - i - 0.5))
            lo = lo0
            hi = _W_MAX
            if not (wi > lo and wi < hi):
                wi = lo + 1e-9 * (1.0 + abs(lo)) if lo > -_W_MAX else 0.0
            for _ in range(200):
                q, dq = _q_w(fam, a, b, wi)
                r = q - y[i]
                if abs(r) <= 4e-16 * (abs(q) + abs(y[i])):
                    ok = True
                    break
                # a Newton step below 1e-8 leaves an error of ~1e-16 (quadratic convergence);
                # taken before the bracket update, which a warm start at the root would
                # otherwise empty (a step below the spacing of doubles lands on its end)
                if dq > 0.0 and abs(r) <= 1e-8 * (1.0 + abs(wi)) * dq:
                    wi = wi - r / dq
                    ok = True
                    break
                if r > 0.0:
                    hi = wi
                elif r < 0.0:
                    lo = wi
                else:
                    ok = True
                    break
                wn = wi - r / dq if dq > 0.0 else math.nan
                if not (wn > lo and wn < hi):
                    wn = 0.5 * (lo + hi)
                    if hi - lo <= 4e-16 * (1.0 + abs(wn)):
                        wi = wn
                        ok = True
                        break
                wi = wn
            if ok:
                break
        if not ok:
            return False
        w[i] = wi
    return True


@njit(cache=True)
def feasible(fam, a, b, l1, scale, zmin, zmax):
    """True when the shapes are valid and the support of the GLD (lambda1 = ``l1``, scale
    ``scale``) strictly contains [zmin, zmax]."""
    if not (K.shape_valid(fam, a, b) and scale > 0.0 and math.isfinite(scale) and math.isfinite(l1)):
        return False
    lo_end = q_lower(fam, a, b, -math.inf, 0.0)
    hi_end = -q_lower(fam, b, a, -math.inf, 0.0)
    return (zmin - l1) / scale > lo_end and (zmax - l1) / scale < hi_end


@njit(cache=True)
def objective(kind, fam, a, b, l1, scale, x, w):
    """Objective of ``kind`` (to minimise) for the sorted sample ``x``; +inf when infeasible.

    MLE: negative log-likelihood. MPS: minus the mean log spacing F(x_(i)) - F(x_(i-1)),
    i = 1..n+1 (a tie uses the log density, Cheng & Amin 1983). STARSHIP: the
    Anderson–Darling statistic of u_i = F(x_i) against the uniform.
    """
    if not K.shape_valid(fam, a, b) or not (scale > 0.0):
        return math.inf
    n = x.shape[0]
    y = (x - l1) / scale
    if not pit_logit(fam, a, b, y, w):
        return math.inf
    total = 0.0
    if kind == MLE:
        for i in range(n):
            total += _logqp_w(fam, a, b, w[i])
        return total + n * math.log(scale)
    if kind == MPS:
        prev_u = 0.0
        for i in range(n + 1):
            d, prev_u = _spacing(w, i, prev_u)
            if d > 0.0:
                total -= math.log(d)
            else:
                total += _logqp_w(fam, a, b, w[i - 1]) + math.log(scale)
        return total / (n + 1)
    for i in range(n):
        total += (2.0 * i + 1.0) * (_logsig(w[i]) + _logsig(-w[n - 1 - i]))
    return -n - total / n


@njit(cache=True)
def _point_terms(fam, a, b, wi):
    """Derivatives at one sample point with logit probability ``wi`` (standardized GLD).

    Returns (dQ/dw, dQ/da, dQ/db, dlogQ'/dw, dlogQ'/da, dlogQ'/db, log Q'): the first three
    give the implicit derivatives of w through Q(u(w); a, b) = y, the others the log
    quantile density and its derivatives (ML). Derivatives in a and b are taken at fixed u
    and, for RS, at the fixed sign of lambda2 of the region.
    """
    e = math.exp(-abs(wi))
    lg = math.log1p(e)
    if wi <= 0.0:
        lu = wi - lg
        lv = -lg
        u = e / (1.0 + e)
        v = 1.0 / (1.0 + e)
    else:
        lu = -lg
        lv = -wi - lg
        u = 1.0 / (1.0 + e)
        v = e / (1.0 + e)
    ea = math.exp(a * lu)
    eb = math.exp(b * lv)
    if fam == RS:
        s = rs_sign(a, b)
        if s > 0.0 or (a <= 0.0 and b <= 0.0):
            dqdw = s * (a * ea * v + b * eb * u)
        else:
            dqdw = _q_w(fam, a, b, wi)[1]
        qa = s * ea * lu
        qb = -s * eb * lv
        # Q'' u^2 v^2 and (dQ'/da) u v, (dQ'/db) u v
        huv = s * (a * (a - 1.0) * ea * v * v - b * (b - 1.0) * eb * u * u)
        gau = s * ea * v * (1.0 + a * lu)
        gbu = s * eb * u * (1.0 + b * lv)
    else:
        dqdw = ea * v + eb * u
        qa = lu * lu * _dem_e(a * lu, ea)
        qb = -lv * lv * _dem_e(b * lv, eb)
        huv = (a - 1.0) * ea * v * v - (b - 1.0) * eb * u * u
        gau = ea * v * lu
        gbu = eb * u * lv
    if dqdw > 1e-300 and dqdw < 1e300:
        lq = math.log(dqdw) - lu - lv
    else:
        lq = _logqp_w(fam, a, b, wi)
    return dqdw, qa, qb, huv / dqdw, gau / dqdw, gbu / dqdw, lq


@njit(cache=True)
def _dem_e(t, et):
    """d/dt of expm1(t)/t given et = exp(t), with its series near 0."""
    if abs(t) < 1e-3:
        return 0.5 + t * (1.0 / 3 + t * (1.0 / 8 + t / 30))
    return (t * et - (et - 1.0)) / (t * t)


@njit(cache=True)
def objective_grad(kind, fam, theta, z, w, dw, grad, y):
    """Objective of ``kind`` at theta = (lambda1, log scale, lambda3, lambda4) and its gradient.

    Parameters
    ----------
    kind, fam : int
        Objective (MLE, MPS, STARSHIP) and family (RS, FKML).
    theta : ndarray, shape (4,)
        Parameters of the GLD of the standardized sample.
    z : ndarray, shape (n,)
        Sorted standardized sample.
    w : ndarray, shape (n,)
        Warm start of the logit probabilities; receives logit F(z_i).
    dw : ndarray, shape (n, 4)
        Receives dw_i/dtheta.
    grad : ndarray, shape (4,)
        Receives the gradient.
    y : ndarray, shape (n,)
        Work space.

    Returns
    -------
    float
        The value of `objective`; +inf when the parameters are infeasible (``grad`` undefined).
    """
    l1 = theta[0]
    lsc = theta[1]
    a = theta[2]
    b = theta[3]
    scale = math.exp(lsc)
    n = z.shape[0]
    if not feasible(fam, a, b, l1, scale, z[0], z[n - 1]):
        return math.inf
    for i in range(n):
        y[i] = (z[i] - l1) / scale
    if not pit_logit(fam, a, b, y, w):
        return math.inf
    for j in range(4):
        grad[j] = 0.0
    total = 0.0
    for i in range(n):
        dqdw, qa, qb, cw, ca, cb, lq = _point_terms(fam, a, b, w[i])
        if not (dqdw > 0.0 and math.isfinite(dqdw + qa + qb + cw + ca + cb)):
            return math.inf
        dw[i, 0] = -1.0 / (scale * dqdw)
        dw[i, 1] = -y[i] / dqdw
        dw[i, 2] = -qa / dqdw
        dw[i, 3] = -qb / dqdw
        if kind == MLE:
            total += lq
            for j in range(4):
                grad[j] += cw * dw[i, j]
            grad[2] += ca
            grad[3] += cb
    if kind == MLE:
        grad[1] += n
        return total + n * lsc
    if kind == MPS:
        prev_u = 0.0
        for i in range(n + 1):
            d, prev_u = _spacing(w, i, prev_u)
            if d > 0.0:
                total -= math.log(d)
                # d(spacing)/dw = u (1 - u) at its upper point minus the same at its lower point
                if i < n:
                    c = math.exp(_logsig(w[i]) + _logsig(-w[i])) / d
                    for j in range(4):
                        grad[j] -= c * dw[i, j]
                if i > 0:
                    c = math.exp(_logsig(w[i - 1]) + _logsig(-w[i - 1])) / d
                    for j in range(4):
                        grad[j] += c * dw[i - 1, j]
            else:
                total += _logqp_w(fam, a, b, w[i - 1]) + lsc
                _, _, _, cw, ca, cb, _ = _point_terms(fam, a, b, w[i - 1])
                for j in range(4):
                    grad[j] += cw * dw[i - 1, j]
                grad[1] += 1.0
                grad[2] += ca
                grad[3] += cb
        for j in range(4):
            grad[j] /= n + 1
        return total / (n + 1)
    for i in range(n):
        total += (2.0 * i + 1.0) * (_logsig(w[i]) + _logsig(-w[n - 1 - i]))
        # d log u_i / dw_i = 1 - u_i (weight 2i + 1), d log(1 - u_i) / dw_i = -u_i (weight 2(n-i) - 1)
        c = ((2.0 * (n - i) - 1.0) * math.exp(_logsig(w[i])) - (2.0 * i + 1.0) * math.exp(_logsig(-w[i]))) / n
        for j in range(4):
            grad[j] += c * dw[i, j]
    return -n - total / n


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
    for k in range(m):
        g[k] = 0.0
        for j in range(4):
            g[k] += jac[j, k] * gth[j]
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
        alpha = alpha0
        accepted = False
        ft = math.inf
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
                    wt[i] = min(max(pred, -_W_MAX), _W_MAX)
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
        if not accepted:
            status = LSFAIL
            break
        for k in range(m):
            gt[k] = 0.0
            for j in range(4):
                gt[k] += jact[j, k] * gth[j]
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
