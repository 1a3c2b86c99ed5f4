"""The bootstrap on a thread pool leaves the process-wide warning filters alone."""

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
