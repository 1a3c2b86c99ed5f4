"""The bootstrap on a thread pool leaves the process-wide warning filters alone; the
quantiles of the maximum of every bootstrap fit."""

import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import glstat


def test_thread_pool_bootstrap_keeps_warning_filters():
    x = np.random.default_rng(4).gamma(3.0, 1.0, 150)
    before = list(warnings.filters)
    with ThreadPoolExecutor(2) as pool:
        bf = glstat.bootstrap(x, param="fkml", method="mle", n_resamples=16, rng=1, executor=pool)
    assert bf.n_successful >= 8
    assert list(warnings.filters) == before
    # a later warning is still shown
    with pytest.warns(UserWarning, match="still shown"):
        warnings.warn("still shown", UserWarning, stacklevel=1)


def test_maximum_quantiles_match_each_fit_s_maximum():
    x = np.random.default_rng(5).gamma(4.0, 1.0, 300)
    bf = glstat.bootstrap(x, n_resamples=12, rng=2)
    v = np.array([[1e-6, 0.3, 0.9, 1 - 1e-9]] * bf.n_successful)
    q = bf.maximum_quantiles([[7.0, 7.0, 50.0, 1e6]], v)
    for b, d in enumerate(bf.dists()[:3]):
        for j, n in enumerate((7.0, 7.0, 50.0, 1e6)):
            m = glstat.maximum(d, n)
            ref = m.ppf(v[b, j]) if v[b, j] <= 0.5 else m.isf(1 - v[b, j])
            assert q[b, j] == pytest.approx(ref, rel=1e-9)
