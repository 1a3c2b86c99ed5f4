"""Moment, percentile and L-moment fits: every root, reference values, recovery, bad input."""

import math
import warnings

import numpy as np
import pytest
from scipy import stats

import glstat
from glstat import GLD, FitError, fit, fit_batch, fit_lmoments, fit_moments, fit_percentiles

P = np.array([0.01, 0.05, 0.1, 0.25, 0.5, 0.75, 0.9, 0.95, 0.99])


def _mvsk(dist):
    m, v, s, k = (float(t) for t in dist.stats("mvsk"))
    return m, math.sqrt(v), s, k + 3.0


def _has_root(f, lams, rtol=2e-3):
    """True when one of the roots equals ``lams`` as a distribution (quantiles agree)."""
    ref = GLD(*lams, param=f.param)
    spread = ref.ppf(0.9) - ref.ppf(0.1)
    for _, r in f.solutions.iterrows():
        if not r["valid"]:
            continue
        g = GLD(r.lambda1, r.lambda2, r.lambda3, r.lambda4, param=f.param)
        if np.max(np.abs(g.ppf(P) - ref.ppf(P))) < rtol * spread:
            return True
    return False


# --- docs/method.md §14 reference values (Karian & Dudewicz, Handbook of Fitting Statistical
# Distributions with R, 2011, ch. 3 and 5 tables; Freimer et al. 1988 for FKML) ----------------
def test_normal_rs_moments_both_roots():
    f = fit_moments(0, 1, 0, 3)
    assert _has_root(f, (0, 0.197451, 0.134912, 0.134912))
    assert _has_root(f, (0, 0.418108, 5.2029, 5.2029))
    assert f.solutions["selected"].sum() == 1
    # the selected root is the published (normal-like) one; compare quantiles with N(0, 1)
    np.testing.assert_allclose(f.dist.ppf(P), stats.norm.ppf(P), atol=0.02)


def test_normal_fkml_moments():
    f = fit_moments(0, 1, 0, 3, param="fkml")
    assert _has_root(f, (0, 1.46355, 0.134912, 0.134912))
    np.testing.assert_allclose(f.dist.stats("mvsk"), [0, 1, 0, 0], atol=1e-9)


def test_normal_rs_percentiles():
    q = stats.norm.ppf([0.1, 0.25, 0.5, 0.75, 0.9])
    f = fit_percentiles(quantiles=q)
    assert _has_root(f, (0, 0.214248, 0.148820, 0.148820))
    np.testing.assert_allclose(f.dist.ppf([0.1, 0.25, 0.5, 0.75, 0.9]), q, atol=1e-10)


def test_uniform_both_roots():
    f = fit_moments(0.5, 1 / math.sqrt(12), 0, 1.8)
    assert _has_root(f, (0.5, 2, 1, 1))
    assert _has_root(f, (0.5, 2, 2, 2))
    # every valid root matches all four moments
    for _, r in f.solutions[f.solutions.valid].iterrows():
        g = GLD(r.lambda1, r.lambda2, r.lambda3, r.lambda4)
        np.testing.assert_allclose(g.stats("mvsk"), [0.5, 1 / 12, 0, -1.2], atol=1e-9)


@pytest.mark.parametrize(
    ("dist", "lams"),
    [
        (stats.weibull_min(5), (0.993497, 1.04910, 0.212087, 0.106133)),
        (stats.lognorm(1 / 3), (0.845057, 0.108542, 0.0101669, 0.0342151)),
        (stats.gamma(5, scale=3), (10.7621, 0.014452, 0.0251988, 0.093884)),
    ],
    ids=["weibull5", "lognormal", "gamma5"],
)
def test_published_rs_moment_fits(dist, lams):
    f = fit_moments(*_mvsk(dist))
    assert _has_root(f, lams)
    # the selected fit matches the four moments to solver precision
    m, s, sk, ku = _mvsk(dist)
    np.testing.assert_allclose(f.dist.stats("mvsk"), [m, s * s, sk, ku - 3], rtol=1e-8, atol=1e-10)


def test_moment_roots_solve_the_equations():
    for param in ("rs", "fkml"):
        for sk, ku in [(0.5, 3.5), (-1.0, 5.0), (0.0, 2.2), (1.5, 9.0)]:
            f = fit_moments(1.0, 2.0, sk, ku, param=param)
            for _, r in f.solutions[f.solutions.valid & f.solutions.converged].iterrows():
                g = GLD(r.lambda1, r.lambda2, r.lambda3, r.lambda4, param=param)
                np.testing.assert_allclose(g.stats("mvsk"), [1.0, 4.0, sk, ku - 3], rtol=1e-7, atol=1e-9)


def test_lmoment_fit_matches_lmoments():
    g0 = GLD(1.0, 0.7, 0.2, 0.05, param="fkml")
    lm = g0.lmoment_ratios(4)
    f = fit_lmoments(*lm, param="fkml")
    assert _has_root(f, g0.lambdas, rtol=1e-6)
    g0 = GLD(0.0, 0.3, 0.1, 0.3, param="rs")
    f = fit_lmoments(*g0.lmoment_ratios(4), param="rs")
    assert _has_root(f, g0.lambdas, rtol=1e-6)


# --- recovery from data: error shrinks as n grows -----------------------------------------------
@pytest.mark.parametrize("method", ["moments", "percentiles", "lmoments"])
@pytest.mark.parametrize("param", ["rs", "fkml"])
def test_recovery_converges(method, param):
    true = GLD(2.0, 0.5, 0.15, 0.05, param=param) if param == "fkml" else GLD(2.0, 0.2, 0.1, 0.2)
    rng = np.random.default_rng(12345)
    errs = []
    for n in (200, 20000):
        worst = []
        for _ in range(5):
            x = true.rvs(size=n, random_state=rng)
            # some percentile fits of 200 values do not cover them (a FitWarning, checked
            # elsewhere): here only the quantile error counts
            f = fit(x, param, method, warn=False)
            worst.append(np.max(np.abs(f.dist.ppf(P[1:-1]) - true.ppf(P[1:-1]))))
        errs.append(np.median(worst))
    assert errs[1] < errs[0] / 3
    assert errs[1] < 0.1


def test_data_fit_selection_and_table():
    x = stats.gamma(5, scale=3).rvs(size=500, random_state=np.random.default_rng(3))
    f = fit(x, "rs", "percentiles")
    sol = f.solutions
    assert sol["selected"].sum() == 1
    sel = sol[sol.selected].iloc[0]
    ok = sol[sol.valid & sol.converged & (sol.covers_data == True)]  # noqa: E712
    assert sel.ks == ok.ks.min()
    assert f.n == 500
    assert set(f.statistics) == {"rho1", "rho2", "rho3", "rho4"}
    assert f.summary().shape[0] == 1
    assert list(f.to_frame().columns)[:4] == ["lambda1", "lambda2", "lambda3", "lambda4"]


def test_fit_batch_matches_single_fits():
    rng = np.random.default_rng(0)
    rows = np.column_stack([rng.normal(size=20), 1 + rng.random(20), rng.uniform(-0.5, 0.5, 20),
                            rng.uniform(3.0, 4.0, 20)])
    lam, cnt = fit_batch(rows, "moments", "rs")
    assert np.all(cnt >= 1)
    for r, lm in zip(rows, lam, strict=True):
        g = GLD(*lm)
        np.testing.assert_allclose(g.stats("mvsk"), [r[0], r[1] ** 2, r[2], r[3] - 3], rtol=1e-7, atol=1e-9)


# --- bad input -----------------------------------------------------------------------------------
def test_bad_input_messages():
    x = np.array([1.0, 2.0, np.nan, 4.0, 5.0, 7.0, 3.0])
    x0 = x.copy()
    with pytest.raises(ValueError, match="nan_policy"):
        fit(x)
    f = fit(x, method="percentiles", nan_policy="omit")
    assert f.n == 6
    np.testing.assert_array_equal(x, x0)  # never mutated
    assert np.all(np.isnan(fit(x, nan_policy="propagate").lambdas))
    with pytest.raises(FitError, match="at least 5"):
        fit([1.0, 2.0, 3.0])
    with pytest.raises(FitError, match="all equal"):
        fit(np.ones(10))
    with pytest.raises(ValueError, match="method"):
        fit(np.arange(10.0), method="magic")
    with pytest.raises(ValueError, match="param"):
        fit(np.arange(10.0), param="xyz")
    with pytest.raises(FitError, match="Pearson"):
        fit_moments(0, 1, 2.0, 4.0)
    with pytest.raises(FitError, match="tied"):
        fit(np.r_[np.zeros(50), np.arange(5.0)], method="percentiles")


def test_out_of_reach_names_alternatives():
    # flat symmetric shape below the reach of both parameterisations (the smallest kurtosis of a
    # symmetric GLD is about 1.75, Karian & Dudewicz 2011, sec. 3.3)
    with pytest.raises(FitError, match="regions 3 and 4") as e:
        fit_moments(0, 1, 0, 1.5)
    assert "percentiles" in str(e.value) and "kurt=1.5" in str(e.value)
    with pytest.raises(FitError, match="lmoments"):
        fit_moments(0, 1, 0, 1.5, param="fkml")
    # skewness 1 with kurtosis 2.5: a valid pair (> 1 + skew^2) that no GLD reaches
    with pytest.raises(FitError, match="skew=1"):
        fit_moments(0, 1, 1.0, 2.5)


def test_exported():
    for name in ("fit", "fit_moments", "fit_percentiles", "fit_lmoments", "fit_batch", "GLDFit"):
        assert hasattr(glstat, name)


def test_rs_moment_root_with_large_lambda3():
    # skewness 2.8, kurtosis 16.34: the RS root has lambda3 ~ 97.5, lambda4 ~ 0.240 (located
    # independently by minimising the moment residual over region 3 from random starts); the
    # seed grid must reach such shapes
    f = fit_moments(0.0, 1.0, 2.8, 16.34)
    sol = f.solutions[f.solutions.valid & f.solutions.converged]
    assert ((sol.lambda3 > 90) & (sol.lambda3 < 105) & (abs(sol.lambda4 - 0.2403) < 0.01)).any()
    np.testing.assert_allclose(f.dist.stats("mvsk"), [0.0, 1.0, 2.8, 13.34], rtol=1e-8, atol=1e-10)


def _hint_cases():
    """(method, stats) on a grid of shape statistics, including pairs out of every reach."""
    cases = []
    for sk in (0.0, 0.8, 1.6, 2.4, 3.2):
        for excess in (0.02, 0.3, 1.0, 4.0, 12.0):
            cases.append(("moments", (0.0, 1.0, sk, 1.0 + sk * sk + excess)))
    for r3 in (0.1, 0.4, 1.0):
        for r4 in (0.05, 0.3, 0.5, 0.7, 0.95):
            cases.append(("percentiles", (0.0, 1.0, r3, r4)))
    for t3 in (0.0, 0.5, 0.9):
        lower = (5 * t3 * t3 - 1) / 4  # Hosking's bound
        for t4 in (lower + 0.001, 0.2, 0.77214407, 0.95):
            if t4 > lower:
                cases.append(("lmoments", (0.0, 1.0, t3, t4)))
    return cases


_FIT_FROM = {"moments": lambda st, p: fit_moments(*st, param=p),
             "percentiles": lambda st, p: fit_percentiles(st, param=p),
             "lmoments": lambda st, p: fit_lmoments(*st, param=p)}


def test_reach_hint_is_correct():
    # a scan of (skewness, kurtosis) found no pair that FKML moments reach and RS moments do not
    # (up to skewness 6), so the hint is checked on the messages that occur: whenever a FitError
    # says the other parameterisation reaches the statistics, that fit succeeds, and whenever it
    # does not say so, that fit fails too
    seen = {"hint": 0, "no hint": 0}
    for method, st in _hint_cases():
        for param, other in (("rs", "fkml"), ("fkml", "rs")):
            try:
                _FIT_FROM[method](st, param)
            except FitError as e:
                msg = str(e)
                assert method in msg and "other options" in msg
                if f"param='{other}' with method='{method}' reaches them" in msg:
                    seen["hint"] += 1
                    alt = _FIT_FROM[method](st, other)
                    assert alt.dist is not None
                else:
                    seen["no hint"] += 1
                    with pytest.raises(FitError):
                        _FIT_FROM[method](st, other)
    # both kinds of message occur in the scan (the hint: L-moments t3 = 0.9, t4 = 0.772, whose
    # FKML root has lambda4 ~ 1300, beyond the seed grid, while the RS root is found)
    assert seen["hint"] >= 1 and seen["no hint"] >= 1


def test_published_gld_quartile_and_density():
    # Karian & Dudewicz (2000), Fitting Statistical Distributions, p. 10, as quoted in the
    # documentation of the R package lmomco (pdfgld): the RS GLD (0.0305, 1.3673, 0.004581,
    # 0.01020) has first quartile 0.028013 and density 43.04 there. Its percentile statistics
    # are fitted back (all roots) and the published values hold for the fitted distribution.
    g = GLD(0.0305, 1.3673, 0.004581, 0.01020)
    q = g.ppf([0.1, 0.25, 0.5, 0.75, 0.9])
    f = fit_percentiles(quantiles=q)
    assert _has_root(f, g.lambdas, rtol=1e-6)
    checked = 0
    for _, r in f.solutions[f.solutions.valid].iterrows():
        h = GLD(r.lambda1, r.lambda2, r.lambda3, r.lambda4)
        if np.allclose(h.ppf(P), g.ppf(P), rtol=0, atol=1e-9):
            # printed to 5 significant digits (quartile) and 4 (density)
            assert float(h.ppf(0.25)) == pytest.approx(0.028013, abs=5e-7)
            assert float(h.pdf(0.028013)) == pytest.approx(43.04, abs=0.005)
            checked += 1
    assert checked >= 1


# --- the branch into the degenerate RS origin (lambda3, lambda4 -> 0) ---------------------------
def _ray_cases():
    """Generating RS shapes on rays lambda3 = c * lambda4 into the origin, both regions."""
    cases = []
    for method in ("moments", "percentiles", "lmoments"):
        for ratio in (0.1, 0.5, 1.0, 3.0):
            for mag in (0.02, 2e-3, 1e-4, 1e-6):
                for sign in (1.0, -1.0):
                    cases.append((method, ratio, sign * mag))
    return cases


def _stats_of(g, method):
    if method == "moments":
        return _mvsk(g)
    if method == "percentiles":
        return _rho_of(g)
    return tuple(g.lmoment_ratios(4))


def _rho_of(g):
    q = g.ppf([0.1, 0.25, 0.5, 0.75, 0.9])
    return (q[2], q[4] - q[0], (q[2] - q[0]) / (q[4] - q[2]), (q[3] - q[1]) / (q[4] - q[0]))


def test_small_shapes_recovered_on_both_sides_of_the_origin():
    # region 3 (lambda > 0) and region 4 (lambda < 0) rays down to |lambda| = 1e-6: near the
    # origin the statistics depend on lambda3 / lambda4 only, the grid triangles there have a
    # degenerate corner, and the generating root used to be missed (a distant bounded root
    # was returned instead, e.g. (5.01, 50.7) for (-0.0015, -0.005) by moments)
    missed = []
    for method, ratio, lam4 in _ray_cases():
        g = GLD(0.0, lam4, ratio * lam4, lam4)
        f = _FIT_FROM[method](_stats_of(g, method), "rs")
        if not _has_root(f, g.lambdas, rtol=1e-4):
            missed.append((method, ratio, lam4))
    assert missed == []


def test_small_shapes_reported_case():
    g = GLD(0.0, -0.005, -0.0015, -0.005)
    m, s, sk, ku = _mvsk(g)
    f = fit_moments(0, 1, sk, ku)
    g1 = GLD(*f.lambdas)
    # the selected root is the generating one (same standardized distribution)
    z = (g.ppf(P) - m) / s
    np.testing.assert_allclose(g1.ppf(P), z, atol=1e-6)


def test_small_shapes_in_fit_batch():
    rows, truth = [], []
    for ratio in (0.2, 0.7):
        for lam4 in (-1e-5, -3e-3, 1e-5, 3e-3):
            g = GLD(0.0, lam4, ratio * lam4, lam4)
            rows.append(_mvsk(g))
            truth.append((ratio * lam4, lam4))
    lams, cnt = fit_batch(rows, "moments", "rs", ref=(0.0, 0.0))
    assert (cnt >= 1).all()
    for (l3, l4), row in zip(truth, lams, strict=True):
        assert row[2] == pytest.approx(l3, rel=1e-5) and row[3] == pytest.approx(l4, rel=1e-5)


# --- a selected root that describes the data poorly is reported -----------------------------------
EXPO = np.random.default_rng(0).exponential(size=10_000)


def test_root_not_covering_the_data_warns():
    # the only FKML moment root, (11.3, 22.3), is bounded above the largest observation
    with pytest.warns(glstat.FitWarning, match=r"KS distance 0\.33.* \(1 % critical value 0\.0163\), "
                      r"support does not cover the data; try param='rs', method='percentiles' or "
                      r"'lmoments', or a data-based method") as rec:
        f = fit(EXPO, "fkml", "moments")
    sel = f.solutions[f.solutions.selected].iloc[0]
    assert not sel.covers_data and sel.ks > 0.3
    assert rec[0].filename == __file__  # points at the caller of fit
    assert issubclass(glstat.FitWarning, UserWarning) and "FitWarning" in glstat.__all__


def test_ks_beyond_the_critical_value_warns_even_when_covered():
    # t with 2 degrees of freedom: no finite variance, the sample moments are erratic; the RS
    # moment root covers the sample but is far from it in KS distance
    x = np.random.default_rng(3).standard_t(2, 4000)
    with pytest.warns(glstat.FitWarning, match=r"support covers the data") as rec:
        f = fit(x, "rs", "moments")
    sel = f.solutions[f.solutions.selected].iloc[0]
    assert sel.covers_data and sel.ks > 1.63 / np.sqrt(x.size)
    assert "method='percentiles' or 'lmoments'" in str(rec[0].message)
    # the percentile fit of the same data is silent
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fit(x, "rs", "percentiles")


def test_good_fit_and_fit_batch_are_silent():
    x = np.random.default_rng(1).normal(size=2000)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        f = fit(x, "rs", "moments")
        # the bootstrap core counts non-covering fits itself
        mvsk = glstat._fit_engine.sample_statistics.sample_moments(EXPO)
        lam, nroots = fit_batch([mvsk], "moments", "fkml",
                                extremes=[[EXPO.min(), EXPO.max()]])
    assert f.solutions.ks[f.solutions.selected].iloc[0] < 1.63 / np.sqrt(x.size)
    assert nroots[0] >= 1 and np.all(np.isnan(lam))
