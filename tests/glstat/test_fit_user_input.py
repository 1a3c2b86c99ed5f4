"""What glstat.fit does with the shapes users pass: a table of columns is fitted as one sample,
but not silently."""

import warnings

import numpy as np
import pytest

import glstat


def test_a_table_of_columns_is_fitted_as_one_sample_with_a_warning():
    x = np.random.default_rng(3).gamma(4.0, 2.0, size=(250, 2))
    with pytest.warns(glstat.FitWarning, match=r"data of shape \(250, 2\) were fitted as one sample "
                                               r"of 500 values; pass one column"):
        f = glstat.fit(x)
    g = glstat.fit(x.ravel())  # the documented way to fit them as one sample: no warning
    assert f.lambdas == g.lambdas
    with warnings.catch_warnings():
        warnings.simplefilter("error", glstat.FitWarning)
        glstat.fit(x[:, :1])  # one column (250, 1): one sample, no warning
