"""The study's analysis pieces: the choice of fit, the hardness levels, the check verdict, the
degenerate-scene warning and the end-point note."""

import math
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from glstat.formatting import fmt_mpa, fmt_probability
from glstat.study.analysis import (
    AnalysisSettings,
    SampleAnalysis,
    Validation,
    _end_note,
    choose_fit,
    hardness_levels,
)
from glstat.study.answer import degenerate_scene


def _surfaces(rng, n, sampler):
    per = []
    for _ in range(n):
        k = int(rng.integers(3, 10))
        v = sampler(rng, k)
        per.append((v, k, float(v.max())))
    return per


def test_choose_fit_scores_only_the_surfaces_given():
    rng = np.random.default_rng(0)
    per = _surfaces(rng, 40, lambda r, k: r.lognormal(7.0, 0.6, k))
    ch = choose_fit(per)
    assert (ch.param, ch.method) in {("rs", "moments"), ("fkml", "moments"), ("rs", "lmoments"),
                                     ("fkml", "lmoments"), ("fkml", "mle")}
    assert next(iter(ch.scores)) == f"{ch.param.upper()} {ch.method}"
    assert "predicts the held-out half's maxima best" in ch.reason
    # the same surfaces give the same choice; other surfaces may not, and the order of the
    # candidates to fall back on starts with the choice
    assert choose_fit(per) == ch
    assert ch.order()[0] == (ch.param, ch.method)
    assert len(ch.order()) == len(set(ch.order()))


def test_choose_fit_prefers_fits_whose_support_holds_the_held_out_maxima():
    # a bounded sample: every candidate ends below some held-out maximum; the choice is the
    # one missing the fewest, and says so
    rng = np.random.default_rng(1)
    per = _surfaces(rng, 30, lambda r, k: r.uniform(1000.0, 2000.0, k))
    ch = choose_fit(per)
    assert math.isfinite(next(iter(ch.scores.values())))
    assert "beyond its support" in ch.reason


def test_choice_reason_names_denser_candidates_ranked_lower_by_the_support():
    # a candidate with a higher mean log density but more held-out maxima beyond its support
    # is ranked lower; the reason says why, so it never contradicts its own numbers
    rng = np.random.default_rng(2)
    per = _surfaces(rng, 30, lambda r, k: r.uniform(1000.0, 2000.0, k))
    ch = choose_fit(per)
    best = next(iter(ch.scores))
    denser = [k for k, v in ch.scores.items() if v > ch.scores[best]]
    assert denser, "the sample no longer gives the case this test is about"
    for k in denser:
        assert k in ch.reason and "beyond its support" in ch.reason.split(k, 1)[1]


def test_hardness_levels_span_the_maxima_and_include_the_hardness():
    maxima = np.random.default_rng(2).gamma(5.0, 500.0, 100)
    lv = hardness_levels(maxima, 2050.0, 7)
    assert lv.size >= 5 and 2050.0 in lv
    assert lv.min() <= np.quantile(maxima, 0.1) and lv.max() >= np.quantile(maxima, 0.9)
    assert np.all(np.diff(lv) > 0)


def _validation(coverage_interval, reject, inside):
    cal = pd.DataFrame({"hardness_mpa": np.arange(10.0), "area_factor": 1,
                        "predicted": [0.5] * 10,
                        "observed": [0.5] * 10,
                        "observed_low": [0.4 if i < inside else 0.6 for i in range(10)],
                        "observed_high": [0.6] * 10, "n_surfaces": 100})
    return Validation(table=pd.DataFrame({"x": [1]}), coverage=0.9,
                      coverage_interval=coverage_interval, reject=reject, calibration=cal)


def test_passes_needs_coverage_centring_and_damage_levels():
    assert _validation((0.83, 0.95), False, 8).passes(0.9)
    assert not _validation((0.70, 0.85), False, 10).passes(0.9)  # coverage too low
    assert not _validation((0.83, 0.95), True, 10).passes(0.9)   # biased
    assert not _validation((0.83, 0.95), False, 7).passes(0.9)   # 7 of 10 levels < 80 %
    assert _validation((0.83, 0.95), False, 8).damage_hits() == (8, 10)
    assert not Validation(error="too few surfaces").passes(0.9)


def test_degenerate_scene_warning():
    def case(n_asp, damage):
        d = SimpleNamespace(estimate=np.array(damage))
        return {"summary": {"n_asperities": n_asp}, "asperity": SimpleNamespace(damage=d)}

    assert degenerate_scene({(0, 0): case(6.0, 0.5), (1, 0): case(8.0, 0.9)}) == ""
    msg = degenerate_scene({(0, 0): case(1.4, 1.0), (1, 0): case(1.8, 1.0)})
    assert "1.4 asperities" in msg and "for every H" in msg and "--target-pressure" in msg


def test_end_note_and_formats():
    sa = SampleAnalysis(sample="asperity", data=np.ones(5), n_ref=5.0, upper_end=1983.0)
    assert "beyond the fitted GLD's upper end point 1983 MPa" in _end_note(sa, 2050.0)
    sa.upper_end = 2100.0
    assert "within 10 %" in _end_note(sa, 2050.0)
    sa.upper_end = math.inf
    assert _end_note(sa, 2050.0) == ""
    assert fmt_mpa(1797.3) == "1.80 GPa" and fmt_mpa(512.0) == "512 MPa"
    assert fmt_mpa(31000.0) == "31.0 GPa" and fmt_mpa(999.96) == "1.00 GPa" and fmt_mpa(0.0) == "0 MPa"
    assert fmt_probability(0.5829) == "58.3 %" and fmt_probability(1.2e-7) == "1.2e-05 %"
    assert fmt_probability(0.0) == "0 %" and fmt_probability(float("nan")) == "—"


def test_analysis_settings_refuse_bad_hardness():
    for bad in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="hardness must be a positive finite pressure"):
            AnalysisSettings(hardness=bad)
    with pytest.raises(ValueError, match="n_levels"):
        AnalysisSettings(n_levels=3)
