"""``print(fit)``: the statsmodels-style text block of a GLDFit; ``summary()`` stays a table."""

from __future__ import annotations

import math
import re

import numpy as np
import pandas as pd

import glstat

X = np.random.default_rng(1).gamma(5.0, 3.0, size=500)


def _value(text: str, label: str) -> str:
    m = re.search(re.escape(label) + r"\s+(\S+(?: \(\d+\))?)", text)
    assert m, f"{label!r} not in\n{text}"
    return m.group(1)


def test_text_of_a_maximum_likelihood_fit():
    f = glstat.fit(X, "rs", "mle")
    text = str(f)
    lines = text.splitlines()
    assert lines[0].strip() == "GLD fit results"
    assert lines[1] == "=" * 78
    assert max(len(line) for line in lines) <= 78
    assert _value(text, "Method:") == "mle"
    assert _value(text, "Parameterisation:") == "RS"
    assert _value(text, "No. observations:") == "500"
    assert _value(text, "RS region:") == str(f.region)
    sel = f.solutions[f.solutions["selected"]].iloc[0]
    assert float(_value(text, "KS distance:")) == float(f"{sel['ks']:.6g}")
    assert _value(text, "Covers the data:") == "yes"
    assert _value(text, "Candidates (valid):") == f"{len(f.solutions)} ({f.n_valid})"
    # the log-likelihood of the data under the fitted GLD, to the 6 digits shown
    ll = float(np.sum(f.dist.logpdf(X)))
    assert float(_value(text, "Log-likelihood:")) == float(f"{ll:.6g}")
    lo, hi = f.dist.support()
    assert f"[{lo:.6g}, {hi:.6g}]" in text
    for i, v in enumerate(f.lambdas, start=1):
        assert float(_value(text, f"lambda{i}")) == float(f"{v:.6g}")
    assert "Options: maxiter=500, starts=2, optimizer='bfgs'" in text
    assert "Standard errors are not part of a fit" in text
    assert "Warning:" not in text  # no issues


def test_text_lists_the_matched_statistics_and_the_warnings():
    f = glstat.fit(X, "rs", "percentiles", warn=False)
    assert f.issues  # a poor fit (support does not cover the data)
    text = str(f)
    flat = " ".join(text.split())
    for name, v in f.statistics.items():
        assert f"{name} = {v:.6g}" in flat
    assert "Log-likelihood" not in text
    assert _value(text, "Covers the data:") == "no"
    for k, issue in enumerate(f.issues, start=3):
        assert f"[{k}] {issue.category.__name__}: {' '.join(issue.message.split())}" in flat
    assert max(len(line) for line in text.splitlines()) <= 78


def test_text_of_fits_without_data_and_of_a_nan_fit():
    f = glstat.fit_moments(0, 1, 0, 3)
    text = str(f)
    assert _value(text, "No. observations:") == "n/a"
    assert _value(text, "KS distance:") == "n/a"
    assert _value(text, "Covers the data:") == "n/a"
    nan = glstat.fit([1.0, 2.0, np.nan, 4.0, 5.0, 6.0], "fkml", nan_policy="propagate")
    text = str(nan)
    assert _value(text, "RS region:") == "n/a"
    assert all(_value(text, f"lambda{i}") == "n/a" for i in range(1, 5))
    assert "No fit: the lambdas are NaN" in text


def test_repr_and_summary_table_unchanged():
    f = glstat.fit(X, "fkml", "moments")
    assert repr(f).startswith("GLDFit(method='moments', param='fkml', lambdas=(")
    assert "\n" not in repr(f)
    tab = f.summary()
    assert isinstance(tab, pd.DataFrame) and len(tab) == 1
    assert list(tab.columns[:7]) == ["method", "param", "n", "lambda1", "lambda2", "lambda3", "lambda4"]
    assert tab["n"].iloc[0] == 500 and not math.isnan(tab["lambda1"].iloc[0])
