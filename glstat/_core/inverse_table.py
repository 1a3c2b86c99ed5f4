"""Fast inversion of Q for many points sharing one set of shapes.

The inverse map y -> t = log F is tabulated on each side of the median at nodes uniform in
t (from t = -36, F ~ 2e-16, to the median), with the first and second derivatives of t(y)
from Q' and Q'', and interpolated by quintic Hermite polynomials. Every interval is checked
at its midpoint against the exact forward map (the interpolation error of a quintic Hermite
is largest there); intervals that miss the tolerance, and points outside the table, go to
the exact per-point solver in :mod:`.quantile_function`.
"""

import math

import numpy as np
from numba import njit

from .double_double import EPS
from .quantile_function import (
    FKML,
    LN2,
    R3A,
    RMX,
    RS,
    emit,
    end_density,
    invert_kernel,
    overflow_point,
    q_lower,
    qprime_lower,
    residual,
    rs_sign,
    rs_tiny,
    solve_lower,
    standardize,
    tail_case,
)

T_MIN = -36.0
N_NODES = 2048
# an interval failing the interpolation check is halved at most this many times
MAX_SPLIT = 3
# accepted absolute interpolation error in t = log p (relative error of p)
TOL = 2e-15


@njit(cache=True, error_model="numpy")
def _qsecond_lower(fam, a, b, t, l1):
    """Standardized Q''(p) (only used to shape the interpolant; its accuracy is verified)."""
    if fam == FKML:
        return (a - 1.0) * math.exp((a - 2.0) * t) - (b - 1.0) * math.exp((b - 2.0) * l1)
    s = rs_sign(a, b)
    ta = 0.0 if (a == 0.0 or a == 1.0) else a * (a - 1.0) * math.exp((a - 2.0) * t)
    tb = 0.0 if (b == 0.0 or b == 1.0) else b * (b - 1.0) * math.exp((b - 2.0) * l1)
    return s * (ta - tb)


@njit(cache=True, error_model="numpy")
def _offset(fam, a, b):
    """Finite, exactly representable lower end point to tabulate from (0 if none)."""
    case = tail_case(fam, a, b)
    if case == R3A and a >= 0.05:
        return -1.0, case
    if case == RMX:
        return 1.0, case
    return 0.0, 0


@njit(cache=True, error_model="numpy")
def _value(fam, a, b, t, l1, case):
    """Q(e^t) minus the lower end point when ``case`` is an offset case, else Q(e^t)."""
    if case == 0:
        return q_lower(fam, a, b, t, l1)
    return residual(case, a, b, 0.0, 0.0, 0.0, t)[0]


@njit(cache=True, error_model="numpy")
def _node(fam, a, b, t, case):
    """y(t) (offset form when ``case``), dt/dy and d2t/dy2 at t = log p."""
    p = math.exp(t)
    l1 = math.log1p(-p)
    y = _value(fam, a, b, t, l1, case)
    q1 = qprime_lower(fam, a, b, t, l1)
    q2 = _qsecond_lower(fam, a, b, t, l1)
    g1 = p * q1  # dy/dt
    g2 = g1 + p * p * q2  # d2y/dt2
    return y, 1.0 / g1, -g2 / (g1 * g1 * g1)


@njit(cache=True, inline="always", error_model="numpy")
def _hermite5(y, y0, y1, f0, f1, d0, d1, s0, s1):
    h = y1 - y0
    s = (y - y0) / h
    s2 = s * s
    s3 = s2 * s
    s4 = s3 * s
    s5 = s4 * s
    h0 = 1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5
    h1 = s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5
    h2 = 0.5 * (s2 - 3.0 * s3 + 3.0 * s4 - s5)
    h3 = 0.5 * (s3 - 2.0 * s4 + s5)
    h4 = -4.0 * s3 + 7.0 * s4 - 3.0 * s5
    return h0 * f0 + (1.0 - h0) * f1 + h * (h1 * d0 + h4 * d1) + h * h * (h2 * s0 + h3 * s1)


@njit(cache=True, error_model="numpy")
def _interval_ok(fam, a, b, case, t0, y0, d10, d20, t1, y1, d11, d21):
    """Check one interval at its midpoint: (interpolation ok, rounding ok)."""
    if not (y1 > y0) or not (math.isfinite(d10) and math.isfinite(d11)):
        return False, False
    if not (math.isfinite(d20) and math.isfinite(d21)):
        return False, False
    tm = 0.5 * (t0 + t1)
    ym = _value(fam, a, b, tm, math.log1p(-math.exp(tm)), case)
    if not (ym > y0 and ym < y1):
        return False, False
    th = _hermite5(ym, y0, y1, t0, t1, d10, d11, d20, d21)
    tol = TOL * max(1.0, abs(tm))
    # the nodes carry a rounding error of eps*|y|, which maps to eps*|y|*|dt/dy| in t;
    # near a finite end point far from 0 that exceeds the tolerance (the exact solver,
    # which works with the offset from the end point, takes those points)
    cond = EPS * max(abs(y0), abs(y1)) * max(abs(d10), abs(d11))
    return abs(th - tm) <= tol, cond <= tol


@njit(cache=True, error_model="numpy")
def build_table(fam, a, b, use_offset):
    """Search keys y, node rows (t, dt/dy, d2t/dy2, valid) and the end-point offset.

    Nodes start uniform in t; an interval whose midpoint check fails on interpolation
    error (not on rounding) is halved, up to ``MAX_SPLIT`` times. With ``use_offset`` (and a
    finite, exactly representable lower end point) the table is in the offset ``y - Q(0)``,
    which resolves the neighbourhood of the end point.
    """
    y0, case = _offset(fam, a, b)
    if not use_offset:
        y0 = 0.0
        case = 0
    n = N_NODES
    cap = (n - 1) * (1 << MAX_SPLIT) + 1
    ys = np.empty(cap)
    pl = np.zeros((cap, 4))
    step = (-LN2 - T_MIN) / (n - 1)
    stack_t = np.empty(2 * MAX_SPLIT + 2)
    stack_d = np.empty(2 * MAX_SPLIT + 2, dtype=np.int64)
    m = 0
    for k in range(n - 1):
        tl = T_MIN + k * step
        tr = T_MIN + (k + 1) * step if k < n - 2 else -LN2
        # depth-first over [tl, tr]: the stack holds right ends, left end is the cursor
        top = 0
        stack_t[0] = tr
        stack_d[0] = 0
        cur = tl
        yc, d1c, d2c = _node(fam, a, b, cur, case)
        while top >= 0:
            right = stack_t[top]
            depth = stack_d[top]
            yr, d1r, d2r = _node(fam, a, b, right, case)
            interp_ok, round_ok = _interval_ok(fam, a, b, case, cur, yc, d1c, d2c, right, yr,
                                               d1r, d2r)
            if not interp_ok and round_ok and depth < MAX_SPLIT:
                top += 1
                stack_t[top] = 0.5 * (cur + right)
                stack_d[top - 1] = depth + 1
                stack_d[top] = depth + 1
                continue
            ys[m] = yc
            pl[m, 0] = cur
            pl[m, 1] = d1c
            pl[m, 2] = d2c
            pl[m, 3] = 1.0 if (interp_ok and round_ok) else 0.0
            m += 1
            cur = right
            yc, d1c, d2c = yr, d1r, d2r
            top -= 1
    ys[m], pl[m, 1], pl[m, 2] = _node(fam, a, b, -LN2, case)
    pl[m, 0] = -LN2
    m += 1
    return ys[:m].copy(), pl[:m].copy(), y0


@njit(cache=True, inline="always", error_model="numpy")
def _lookup(y, ys, payload):
    """Interpolated t for y, or NaN when y is outside the verified table.

    The search keys ``ys`` are contiguous; the data of node k (t, dt/dy, d2t/dy2, valid)
    are one row of ``payload``, so an interpolation touches one or two cache lines.
    """
    n = ys.shape[0]
    if not (y >= ys[0] and y <= ys[n - 1]):
        return math.nan
    lo = 0
    hi = n - 1
    while hi - lo > 1:
        mid = (lo + hi) >> 1
        if ys[mid] <= y:
            lo = mid
        else:
            hi = mid
    if payload[lo, 3] == 0.0 or not (ys[lo] <= y and y <= ys[hi]):
        # unverified interval, or keys made non-monotone by rounding (extreme shapes): the
        # search did not bracket y, so the exact solver takes the point
        return math.nan
    return _hermite5(y, ys[lo], ys[hi], payload[lo, 0], payload[hi, 0], payload[lo, 1],
                     payload[hi, 1], payload[lo, 2], payload[hi, 2])


@njit(cache=True, inline="always", error_model="numpy")
def _lookup2(y, y_lo, d_ys, d_pl, o_ys, o_pl, y0):
    """t from the offset table near the end point, else from the direct one."""
    if y0 != 0.0 and abs(y - y0) < abs(y):
        t = _lookup((y - y0) + y_lo, o_ys, o_pl)
        if t == t:
            return t
    return _lookup(y, d_ys, d_pl)


@njit(cache=True, error_model="numpy")
def invert_table_kernel(y, a, b, fam, what, out, status, loc=0.0, inv_scale=1.0):
    """Same contract as ``quantile_function.invert_kernel`` for scalar shapes a, b and many points."""
    if rs_tiny(fam, a, b) or (fam == RS and (a == 0.0 or b == 0.0)) or (
            fam == FKML and a == 0.0 and b == 0.0):
        # the linear regime of tiny RS shapes has its own per-point solver; RS with a shape
        # exactly 0 is inverted in closed form, and so is FKML(0, 0), the logistic
        invert_kernel(y, np.array([a]), np.array([b]), fam, what, out, status, loc, inv_scale)
        return
    log_scale = math.log(inv_scale)
    l_ys, l_pl, _ = build_table(fam, a, b, False)
    u_ys, u_pl, _ = build_table(fam, b, a, False)
    lo_ys, lo_pl, l_y0 = build_table(fam, a, b, True)
    uo_ys, uo_pl, u_y0 = build_table(fam, b, a, True)
    med = q_lower(fam, a, b, -LN2, -LN2)
    for i in range(y.shape[0]):
        yi, yi_lo = standardize(y[i], loc, inv_scale)
        if yi != yi:
            out[i] = math.nan
            continue
        upper = yi > med
        if upper:
            t = _lookup2(-yi, -yi_lo, u_ys, u_pl, uo_ys, uo_pl, u_y0)
            ae = b
            be = a
        else:
            t = _lookup2(yi, yi_lo, l_ys, l_pl, lo_ys, lo_pl, l_y0)
            ae = a
            be = b
        if t == t:
            p = math.exp(t)
        else:
            if yi == -math.inf or yi == math.inf:
                if math.isfinite(y[i]):
                    out[i] = overflow_point(what, fam, a, b, y[i], loc, inv_scale, log_scale)
                    continue
                p = 0.0
                t = -math.inf
            else:
                p, t, st = solve_lower(fam, ae, be, -yi if upper else yi,
                                       -yi_lo if upper else yi_lo)
                status[i] = st
                if what >= 4 and t == -math.inf:
                    out[i] = end_density(what, fam, ae, be, -yi if upper else yi,
                                         -yi_lo if upper else yi_lo, y[i], upper, loc,
                                         inv_scale, log_scale)
                    continue
        out[i] = emit(what, fam, ae, be, p, t, upper, inv_scale, log_scale)
