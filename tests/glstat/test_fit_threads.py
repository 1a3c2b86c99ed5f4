"""Fits and goodness of fit in worker threads, data-based fits that do not fit, scipy guesses,
and the cost of fits from summary statistics.

* Worker threads must not change process-wide state: ``glstat.fit(..., warn=False)`` and the
  parametric bootstrap of :func:`glstat.gof_report` emit nothing and never touch the warning
  filters (``warnings.catch_warnings``/``simplefilter`` are not thread-safe).
* ML, MPS and starship fits that do not fit (KS beyond the 1 % critical value) warn with
  the figures, like the equation methods.
* ``gld_fkml.fit(data, *guesses, loc=..., scale=...)`` (what ``scipy.stats.goodness_of_fit``
  calls with ``guessed_params``) is never worse than the fit without guesses.
* ``fit_moments`` builds its table and frozen distribution only when asked.
"""

from __future__ import annotations

import pickle
import sys
import threading
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from scipy import stats

import glstat
from glstat import GLD, FitWarning, fit

# a quarter zeros and a half-normal remainder: the shape of contact pressures (zero where
# the surfaces do not touch)
ZI = np.concatenate([np.zeros(50), np.abs(np.random.default_rng(0).normal(size=150))])


class _Spy:
    """Records calls of ``warnings.catch_warnings`` and ``warnings.simplefilter`` made by
    glstat code outside the main thread."""

    def __init__(self, monkeypatch):
        self.calls: list[str] = []
        orig_cw = warnings.catch_warnings
        orig_sf = warnings.simplefilter
        spy = self

        def note(what):
            caller = sys._getframe(2).f_globals.get("__name__", "")
            if threading.current_thread() is not threading.main_thread() and caller.startswith("glstat"):
                spy.calls.append(f"{what} from {caller}")

        class CatchWarnings(orig_cw):
            def __enter__(self):
                note("catch_warnings")
                return super().__enter__()

        def simplefilter(*args, **kwargs):
            note("simplefilter")
            return orig_sf(*args, **kwargs)

        monkeypatch.setattr(warnings, "catch_warnings", CatchWarnings)
        monkeypatch.setattr(warnings, "simplefilter", simplefilter)


def _worker_jobs():
    x = np.random.default_rng(5).gamma(3.0, 2.0, size=80)
    return [
        lambda: glstat.gof_report(x, fit(x, "rs", "moments", warn=False), n_resamples=5, rng=1),
        lambda: glstat.gof_report(x, fit(x, "fkml", "mle", warn=False), stats.norm(3, 1),
                                  refit=[None, lambda s: stats.norm(*stats.norm.fit(s))],
                                  n_resamples=3, rng=2),
        lambda: glstat.compare_families(x, ["gld_rs", "norm"], n_resamples=2, rng=3),
        lambda: fit(ZI, "rs", "mle", warn=False),
        lambda: fit(ZI, "fkml", "moments", warn=False),
        lambda: glstat.gld_fkml.fit(ZI, 0.1, 0.1, loc=0.5, scale=1.0),
    ]


def test_worker_threads_leave_the_warning_filters_alone(monkeypatch):
    spy = _Spy(monkeypatch)
    before = list(warnings.filters)
    with warnings.catch_warnings(record=True) as caught:  # in the main thread, around the pool
        with ThreadPoolExecutor(max_workers=2) as pool:
            results = [f.result() for f in [pool.submit(job) for job in _worker_jobs()]]
    assert spy.calls == []
    assert warnings.filters == before
    # nothing was warned from the workers: the issues are returned instead
    assert [str(w.message) for w in caught] == []
    assert any(i.category is FitWarning for i in results[3].issues)
    # a later warning is still shown (recorded under the current filters, none added)
    with warnings.catch_warnings(record=True) as later:
        warnings.warn("a later warning", UserWarning, stacklevel=1)
    assert [str(w.message) for w in later] == ["a later warning"]


def test_warn_false_returns_the_issues_warn_true_emits_them():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        quiet = fit(ZI, "rs", "mle", warn=False)
    assert quiet.issues and all(issubclass(i.category, Warning) for i in quiet.issues)
    with pytest.warns(FitWarning) as rec:
        loud = fit(ZI, "rs", "mle")
    assert [str(w.message) for w in rec] == [i.message for i in loud.issues]
    assert loud.lambdas == quiet.lambdas
    assert rec[0].filename == __file__  # points at the caller of fit


# ---------------------------------------------------------------------------------------------
# data-based fits that do not fit warn with the figures
# ---------------------------------------------------------------------------------------------
@pytest.mark.filterwarnings("ignore::glstat.ConvergenceWarning")
@pytest.mark.parametrize("param", ["rs", "fkml"])
@pytest.mark.parametrize("method", ["mle", "mps", "starship"])
def test_data_based_fit_of_zero_inflated_data_warns(method, param):
    with pytest.warns(FitWarning) as rec:
        f = fit(ZI, param, method)
    msg = str(rec[0].message)
    sol = f.solutions
    sel = sol[sol.selected].iloc[0]
    crit = 1.6276 / np.sqrt(ZI.size)  # sqrt(-ln(0.005) / 2) / sqrt(n)
    assert sel.ks > crit
    assert f"KS distance {sel.ks:.3g} (1 % critical value {crit:.3g})" in msg
    # the atom at zero is named: 50 of 200 points, KS at least 50 / 400 for any continuous law
    assert "50 of the 200 data (25 %) equal 0" in msg and "at least 0.125" in msg
    # the stated rule: the best objective among the valid candidates covering the data
    ok = sol[sol.valid & sol.converged & sol.covers_data.astype(bool)]
    assert sel.objective == ok.objective.min()
    better_ks = ok[ok.ks < 0.9 * sel.ks]
    if len(better_ks):
        assert f"has KS {better_ks.ks.min():.3g}" in msg


def test_data_based_fit_of_good_data_is_silent():
    x = np.random.default_rng(11).normal(size=500)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for method in ("mle", "mps", "starship"):
            f = fit(x, "fkml", method)
            assert f.issues == ()


# ---------------------------------------------------------------------------------------------
# scipy guesses: one more start, never worse
# ---------------------------------------------------------------------------------------------
def test_guesses_never_make_the_scipy_fit_worse():
    true = GLD(2.0, 0.5, 0.15, 0.05, param="fkml")
    rng = np.random.default_rng(8)
    far = (1.0, -0.5, 2.0, 3.0)  # lam3, lam4, loc, scale: another basin than the optimum
    for _ in range(6):
        x = true.rvs(size=150, random_state=rng)
        base = glstat.gld_fkml.fit(x)
        ll = np.sum(glstat.gld_fkml.logpdf(x, *base))
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            near = glstat.gld_fkml.fit(x, 0.15, 0.05, loc=2.0, scale=2.0)
            other = glstat.gld_fkml.fit(x, *far[:2], loc=far[2], scale=far[3])
        for p in (near, other):
            assert np.sum(glstat.gld_fkml.logpdf(x, *p)) >= ll - 1e-9 * abs(ll)
    # a guess in the basin of a usual start is not refined again (same cost); a far one is
    # one more candidate
    f0 = fit(x, "fkml", "mle")
    f1 = fit(x, "fkml", "mle", start=(2.0, 0.5, 0.15, 0.05))
    f2 = fit(x, "fkml", "mle", start=(far[2], 1 / far[3], *far[:2]))
    assert len(f1.solutions) == len(f0.solutions) and f1.lambdas == f0.lambdas
    assert len(f2.solutions) == len(f0.solutions) + 1
    assert f2.statistics["neg_loglik"] <= f0.statistics["neg_loglik"]


def test_scipy_goodness_of_fit_with_guesses_is_silent_and_agrees():
    x = np.random.default_rng(3).gamma(5.0, 3.0, size=150)
    l1, l2, l3, l4 = fit(x, "fkml", "mle").lambdas
    guessed = {"lam3": l3, "lam4": l4, "loc": l1, "scale": 1 / l2}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ref = stats.goodness_of_fit(glstat.gld_fkml, x, statistic="ad", n_mc_samples=19, rng=1)
        res = stats.goodness_of_fit(glstat.gld_fkml, x, statistic="ad", n_mc_samples=19, rng=1,
                                    guessed_params=guessed)
    # the guess is the optimum of the data and near that of every replicate: the same fits
    np.testing.assert_allclose(res.null_distribution, ref.null_distribution, rtol=1e-6)
    assert res.pvalue == ref.pvalue


def test_bad_guesses():
    x = np.random.default_rng(1).normal(size=100)
    with pytest.raises(TypeError, match="at most 2 shape guesses"):
        glstat.gld_rs.fit(x, 0.1, 0.1, 0.1)
    with pytest.raises(ValueError, match="start must be"):
        fit(x, "rs", "mle", start=(1.0, 2.0))
    # an invalid GLD as guess is ignored: the usual fit
    assert glstat.gld_rs.fit(x, 0.5, -0.5, loc=0, scale=1) == glstat.gld_rs.fit(x)


# ---------------------------------------------------------------------------------------------
# fits from summary statistics build the table and the distribution only when asked
# ---------------------------------------------------------------------------------------------
def test_summary_fit_is_lazy(monkeypatch):
    ref = glstat.fit_moments(0, 1, 0, 3)
    monkeypatch.setattr(glstat.fitting.result, "GLD", None)  # building a GLD now fails
    f = glstat.fit_moments(0, 1, 0, 3)
    assert "dist" not in f.__dict__ and "solutions" not in f.__dict__
    assert f.lambdas == ref.lambdas and f.region == 3
    assert f.n_valid == int(ref.solutions.valid.sum()) >= 1
    monkeypatch.undo()
    # RS approximation of N(0, 1) by moments: (0, 0.197451, 0.134912, 0.134912) in
    # Karian & Dudewicz (2011), table values to 6 digits
    np.testing.assert_allclose(f.lambdas, [0, 0.197451, 0.134912, 0.134912], atol=2e-6)
    assert f.dist == GLD(*f.lambdas) and f.dist is f.dist
    sol = f.solutions
    assert sol.equals(ref.solutions) and sol.selected.sum() == 1
    assert list(sol.region) == list(glstat.regions.rs_region(sol.lambda3, sol.lambda4))
    g = pickle.loads(pickle.dumps(f))
    assert g.dist == f.dist and g.solutions.equals(f.solutions)
