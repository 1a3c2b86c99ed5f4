"""The order statistics evaluate only the parent tails that each function needs: the rank-1
tail of the binomial and the one-sided ``TailAccess.lower``/``upper`` give exactly the values
of the full computation (``binomial_tails`` and ``TailAccess.tail``)."""

import numpy as np
import pytest
import scipy.stats as st
from scipy import special

from glstat import GLD, order_statistic
from glstat._core.incomplete_beta import binomial_tail_rank_one, binomial_tails
from glstat.extremes.tails import TailAccess

PARENTS = {
    "normal": st.norm,
    "t3": st.t(3),
    "gld": GLD(0.0, 0.197451, 0.134912, 0.134912),
    "gld bounded": GLD(0.0, 1.0, 0.2, 0.05),
}


def _same(a, b):
    """Bit for bit, NaN equal to NaN."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(
        np.all((a.view(np.int64) == b.view(np.int64)) | (np.isnan(a) & np.isnan(b)))
    )


def _points(o, rng):
    with np.errstate(all="ignore"):
        return np.concatenate([
            o.ppf(rng.uniform(size=300)), o.ppf(np.logspace(-300, -1, 30)),
            o.isf(np.logspace(-300, -1, 30)), [-np.inf, np.inf, np.nan, -40.0, 40.0, 0.0],
        ])


@pytest.mark.parametrize("n", [1.0, 2.0, 1e3, 1e9, 1e12])
def test_rank_one_tail_is_the_rank_one_field_of_binomial_tails(n):
    rng = np.random.default_rng(3)
    q = np.concatenate([rng.uniform(size=200), np.logspace(-320, -1, 40), 1 - np.logspace(-16, -1, 20),
                        [0.0, 1.0, 0.5]])
    p = 1.0 - q
    with np.errstate(divide="ignore"):
        logq = np.where(q < 0.5, np.log(q), np.log1p(-p))
        logp = np.where(p < 0.5, np.log(p), np.log1p(-q))
    full = binomial_tails(1, n, p, q, logp, logq)
    for field in ("low", "up", "loglow", "logup"):
        assert _same(binomial_tail_rank_one(n, q, logq, field), getattr(full, field)), field
    with pytest.raises(ValueError, match="which"):
        binomial_tail_rank_one(n, q, logq, "cdf")


@pytest.mark.parametrize("name", sorted(PARENTS))
def test_one_sided_tails_match_the_full_tail(name):
    parent = TailAccess(PARENTS[name])
    x = _points(order_statistic(PARENTS[name], 1, 1000), np.random.default_rng(4))
    f, logf, s, logs = parent.tail(x)
    with np.errstate(divide="ignore", invalid="ignore"):
        logs = np.where(s >= 0.5, np.log1p(-f), logs)
    fl, logfl = parent.lower(x)
    su, logsu = parent.upper(x)
    assert _same(fl, f) and _same(logfl, logf)
    assert _same(su, s) and _same(logsu, logs)
    assert parent.upper(np.float64(0.5))[0].shape == ()


@pytest.mark.parametrize("name", sorted(PARENTS))
@pytest.mark.parametrize(("k", "n"), [(1, 1), (1, 1000), (1000, 1000), (1, 1e12), (3, 1000),
                                      (998, 1000)])
def test_each_function_matches_the_all_tails_evaluation(name, k, n):
    """cdf, sf and their logs from one tail equal the fields of the full binomial tails."""
    o = order_statistic(PARENTS[name], k, n)
    gen = o.dist
    x = _points(o, np.random.default_rng(5))
    r, near = gen._rank()
    f, logf, s, logs = gen._logs(x)
    with np.errstate(all="ignore"):
        if near:
            t = binomial_tails(r, float(n), f, s, logf, logs)
            expected = {"cdf": t.up, "sf": t.low, "logcdf": t.logup, "logsf": t.loglow}
        else:
            t = binomial_tails(r, float(n), s, f, logs, logf)
            expected = {"cdf": t.low, "sf": t.up, "logcdf": t.loglow, "logsf": t.logup}
        for method, want in expected.items():
            assert _same(getattr(o, method)(x), want), method
        k_, m = float(k), float(n) - k + 1.0
        lp = gen._parent.logpdf(x)
        a = 0.0 if k_ == 1 else (k_ - 1.0) * logf
        b = 0.0 if m == 1 else (m - 1.0) * logs
        assert _same(o.logpdf(x), a + b + lp - special.betaln(k_, m))
