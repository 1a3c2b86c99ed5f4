"""High-precision references (mpmath) for the glstat tests and benchmarks.

Test-only: mpmath is a test dependency, and glstat never imports it. The tests import this
module as ``mp_reference`` (pytest puts ``tests/glstat`` on ``sys.path``); a benchmark puts
``tests/glstat`` on ``sys.path`` first.

Every function computes at its own working precision (``mp.workdps``) and returns mpmath
numbers; none changes mpmath's global precision.

The standardized GLD (``fam`` 0 = RS, 1 = FKML, shapes ``a`` = lambda3, ``b`` = lambda4),
at 40 significant digits unless told otherwise: :func:`q_mp` evaluates the quantile function
through expm1/log1p, so that u**lam and (1-u)**lam keep full relative precision for u down to
1e-300; :func:`tail_probability` is the smaller of F(y) and 1 - F(y), the root of Q(u) = y
found by bisection in log u to about 1e-50 relative, far below double precision;
:func:`central_moment_closed` and :func:`entropy_reference` give moments and entropy.

Parents as (F, S) = (cdf, sf) pairs at ``PARENT_DPS`` = 60 digits, for the tests of the
maximum and the damage: in closed form for the exponential, logistic and Weibull
(:func:`expon_fs`, :func:`logistic_fs`, :func:`weibull_fs`), and for a GLD in lambda notation
(:func:`gld_fs`, by :func:`tail_probability`; its quantile function is :func:`gld_q`).
:func:`max_ref` is the (cdf, sf) of the maximum of n draws, :func:`rel` a relative error.
"""

import math

import mpmath as mp

DPS = 40
PARENT_DPS = 60
RS, FKML = 0, 1


def q_mp(fam, a, b, t, l1):
    """Standardized Q at u = exp(t), l1 = log1p(-u); fam 0 = RS, 1 = FKML."""
    a = mp.mpf(a)
    b = mp.mpf(b)
    if fam == 0:
        s = 1 if (a >= 0 and b >= 0) else -1
        if a > 0 and b > 0 and a * t < -1 and b * l1 < -1:
            # region 3 with both powers small (large shapes): the powers themselves (mpmath
            # has the exponent range); elsewhere the expm1 form keeps tiny shapes exact
            return s * (mp.exp(a * t) - mp.exp(b * l1))
        return s * (mp.expm1(a * t) - mp.expm1(b * l1))
    if a > 0 and b > 0 and a * t < -1 and b * l1 < -1:
        # both powers small (large shapes): (1/b - 1/a) + u^a/a - (1-u)^b/b, an algebraic
        # identity whose power terms keep every digit in mpmath's exponent range
        return (1 / b - 1 / a) + mp.exp(a * t) / a - mp.exp(b * l1) / b
    ea = mp.expm1(a * t) / a if a != 0 else t
    eb = mp.expm1(b * l1) / b if b != 0 else l1
    return ea - eb


def tail_probability(fam, a, b, y, dps=DPS):
    """(p, upper): the smaller of F(y) and 1 - F(y), and whether it is the upper one.

    ``dps`` must resolve the body: shapes of very different magnitude (1e-300 and 1e4) put
    half of the distribution within 1e-300 of an end point, which needs some 320 digits."""
    with mp.workdps(dps):
        y = mp.mpf(y)
        half = -mp.log(2)
        if y <= q_mp(fam, a, b, half, half):
            def f(t):
                return q_mp(fam, a, b, t, mp.log1p(-mp.exp(t))) - y
            upper = False
        else:
            def f(t):
                return q_mp(fam, b, a, t, mp.log1p(-mp.exp(t))) + y
            upper = True
        lo, hi = mp.mpf(-5000), half
        if f(lo) >= 0:
            return mp.mpf(0), upper
        for _ in range(180):
            mid = (lo + hi) / 2
            if f(mid) < 0:
                lo = mid
            else:
                hi = mid
        return mp.exp((lo + hi) / 2), upper


def central_moment_closed(fam, a, b, k):
    """k-th central moment from the beta-function closed form, at 60 digits.

    At this precision the cancellation between the beta terms is harmless, which makes the
    closed form an exact reference for the double-precision kernels.
    """
    with mp.workdps(60):
        a = mp.mpf(a)
        b = mp.mpf(b)
        if fam == 0:
            s = 1 if (a >= 0 and b >= 0) else -1
            c1, c2, c0 = s, -s, mp.mpf(0)
            m = s * (1 / (1 + a) - 1 / (1 + b))
        else:
            c1, c2, c0 = 1 / a, -1 / b, 1 / b - 1 / a
            m = (a - b) / ((1 + a) * (1 + b))
        c0 = c0 - m
        total = mp.mpf(0)
        for i in range(k + 1):
            for j in range(k + 1 - i):
                rest = k - i - j
                total += (
                    mp.factorial(k) / (mp.factorial(i) * mp.factorial(j) * mp.factorial(rest))
                    * c0**rest * c1**i * c2**j * mp.beta(a * i + 1, b * j + 1)
                )
        return m, total


def entropy_reference(fam, a, b, dps=30):
    """Differential entropy int_0^1 log Q'(u) du of the standardized GLD, by mpmath quadrature.

    Q' is written as A + B (or A - B for RS with shapes of opposite signs) with
    A = |a| u^(a-1), B = |b| (1-u)^(b-1) (FKML: no |a|, |b| factors), and log Q' is evaluated
    as max(log A, log B) + log1p(+-exp(-|log A - log B|)), which never over- or underflows.
    The interval is split at every crossing of the two terms (roots of log A - log B, located
    by a sign scan in the logit of u and refined by mpmath's root finder) and geometrically
    around each crossing on the scale of the transition, so that the tanh-sinh rule never
    meets a kink inside a subinterval.
    """
    with mp.workdps(dps):
        a = mp.mpf(a)
        b = mp.mpf(b)
        if fam == 0:
            ca = mp.log(abs(a)) if a != 0 else mp.mpf("-inf")
            cb = mp.log(abs(b)) if b != 0 else mp.mpf("-inf")
            diff = (a > 0 and b < 0) or (a < 0 and b > 0)
        else:
            ca = cb = mp.mpf(0)
            diff = False

        def la(u):
            return ca + (a - 1) * mp.log(u) if ca != mp.mpf("-inf") else ca

        def lb(u):
            return cb + (b - 1) * mp.log1p(-u) if cb != mp.mpf("-inf") else cb

        def lq(u):
            if u <= 0 or u >= 1:
                # a tanh-sinh node rounded onto an end point: its weight is below 10**-dps
                return mp.mpf(0)
            x, y = la(u), lb(u)
            if diff:
                # the larger term is the positive one (Q' > 0)
                hi, lo = (x, y) if x > y else (y, x)
                return hi + mp.log1p(-mp.exp(lo - hi))
            hi, lo = (x, y) if x > y else (y, x)
            if lo == mp.mpf("-inf"):
                return hi
            return hi + mp.log1p(mp.exp(lo - hi))

        def g(s):
            u = 1 / (1 + mp.exp(-s))
            return la(u) - lb(u)

        pts = [mp.mpf(0), mp.mpf(1)]
        if ca != mp.mpf("-inf") and cb != mp.mpf("-inf"):
            grid = [mp.mpf(k) / 2 + mp.mpf(1) / mp.pi for k in range(-1400, 1400)]
            vals = [g(s) for s in grid]
            for s0, s1, g0, g1 in zip(grid[:-1], grid[1:], vals[:-1], vals[1:], strict=True):
                if g0 * g1 < 0:
                    s = mp.findroot(g, (s0, s1), solver="anderson")
                    r = 1 / (1 + mp.exp(-s))
                    slope = abs((a - 1) / r + (b - 1) / (1 - r))
                    pts.append(r)
                    for j in range(-4, 60, 2):
                        d = mp.mpf(2) ** j / slope
                        pts.extend(v for v in (r - d, r + d) if 0 < v < 1)
        if diff:
            # regions 1, 2, 5, 6: no crossing, but log Q' peaks where the ratio of the two
            # terms is closest to 1, at u* = (1-a)/(b-a) (the minimum of |log A - log B|),
            # sharply next to the boundary of regions 5 and 6: split there, geometrically on
            # the scale of the peak, and towards both ends
            us = (1 - a) / (b - a)
            if 0 < us < 1:
                gs = abs(la(us) - lb(us))
                g2 = abs((1 - a) / us**2 + (b - 1) / (1 - us) ** 2)
                delta = mp.sqrt(2 * max(gs, mp.mpf(10) ** (-2 * dps)) / g2)
                pts.append(us)
                for j in range(0, 4 * dps):
                    d = delta * mp.mpf(2) ** j
                    if d > 1:
                        break
                    pts.extend(v for v in (us - d, us + d) if 0 < v < 1)
            pts.extend(v for j in range(1, dps) for v in (mp.mpf(2) ** (-4 * j),
                                                          1 - mp.mpf(2) ** (-4 * j)))
        pts = sorted(set(pts))
        return mp.quad(lq, pts)


# --------------------------------------------------------------------------- lambda notation
def _family(param):
    if param not in ("rs", "fkml"):
        raise ValueError(f"param must be 'rs' or 'fkml', got {param!r}")
    return RS if param == "rs" else FKML


def gld_q(lambdas, param):
    """Q(u, s) of the GLD (l1, l2, l3, l4), s = 1 - u given separately (exact for tiny s).

    ``l1 + Q_std(u) / |l2|`` with the standardized :func:`q_mp`, at ``PARENT_DPS`` digits.
    """
    fam = _family(param)
    l1, l2, a, b = lambdas

    def q(u, s):
        with mp.workdps(PARENT_DPS):
            return mp.mpf(l1) + q_mp(fam, a, b, mp.log(u), mp.log(s)) / abs(mp.mpf(l2))

    return q


def gld_fs(lambdas, param, dps=PARENT_DPS):
    """x -> (F, S) of the GLD (l1, l2, l3, l4), by :func:`tail_probability` at ``dps`` digits.

    The smaller of the two is the root found in logarithms, the other its complement; below
    the lower end point (0, 1), above the upper one (1, 0).
    """
    fam = _family(param)
    l1, l2, a, b = lambdas

    def fs(x):
        with mp.workdps(dps):
            y = (mp.mpf(x) - mp.mpf(l1)) * abs(mp.mpf(l2))
            p, upper = tail_probability(fam, a, b, y, dps=dps)
            return (1 - p, p) if upper else (p, 1 - p)

    return fs


# --------------------------------------------------------------------------- closed-form parents
def expon_fs(x):
    """(F, S) of the standard exponential at x."""
    with mp.workdps(PARENT_DPS):
        x = mp.mpf(x)
        if x <= 0:
            return mp.mpf(0), mp.mpf(1)
        return -mp.expm1(-x), mp.exp(-x)


def logistic_fs(x):
    """(F, S) of the standard logistic at x."""
    with mp.workdps(PARENT_DPS):
        x = mp.mpf(x)
        return 1 / (1 + mp.exp(-x)), 1 / (1 + mp.exp(x))


def weibull_fs(c):
    """x -> (F, S) of the standard Weibull of shape c."""

    def fs(x):
        with mp.workdps(PARENT_DPS):
            x = mp.mpf(x)
            if x <= 0:
                return mp.mpf(0), mp.mpf(1)
            k = mp.mpf(c)
            return -mp.expm1(-(x**k)), mp.exp(-(x**k))

    return fs


# --------------------------------------------------------------------------- the maximum
def max_ref(fs, x, n):
    """(cdf, sf) of the maximum of n at x: F^n and 1 - F^n = -expm1(n log1p(-S))."""
    with mp.workdps(PARENT_DPS):
        f, s = fs(x)
        n = mp.mpf(n)
        if s < mp.mpf("0.5"):
            y = n * mp.log1p(-s)
        else:
            y = n * mp.log(f) if f > 0 else mp.mpf("-inf")
        if y == mp.mpf("-inf"):
            return mp.mpf(0), mp.mpf(1)
        return mp.exp(y), -mp.expm1(y)


def rel(a, b):
    """Relative error of the float a against the mpmath b (0 when both are 0)."""
    if b == 0:
        return 0.0 if a == 0 else math.inf
    with mp.workdps(PARENT_DPS):
        return float(abs((mp.mpf(a) - b) / b))
