"""The study's analysis pieces: the choice of fit, the hardness levels, the check verdict, the
degenerate-scene warning and the end-point note."""

import math
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from glstat.formatting import fmt_mpa, fmt_probability
from glstat.study.analysis import SampleAnalysis, _end_note
from glstat.study.analysis_settings import AnalysisSettings
from glstat.study.answer import degenerate_scene
from glstat.study.fit_choice import choose_fit
from glstat.study.validation import Validation, hardness_levels


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


def _validation(damage, coverage, interval=None):
    """A validation whose checks are ``(predicted, hits, n)`` triples: the damage against
    ``interval`` (default: the point), the coverage one-sided as the study checks it."""
    from glstat.study.validation import held_out_check

    return Validation(table=pd.DataFrame({"x": [1]}), coverage=coverage[1] / coverage[2],
                      damage_check=held_out_check(*damage, interval=interval),
                      coverage_check=held_out_check(*coverage, alternative="less"))


def test_verdict_is_failed_when_either_binomial_test_rejects():
    assert _validation((0.5, 50, 100), (0.9, 90, 100)).verdict() == "passed"
    # the damage is off: 75 of 100 surfaces damaged where 50 % [40 %, 60 %] was predicted
    off = _validation((0.5, 75, 100), (0.9, 90, 100), (0.4, 0.6))
    assert off.verdict() == "failed" and not off.passes()
    assert "75 of 100 held-out surfaces damaged, 50 % [40 %, 60 %] predicted" in off.short_text()
    # the interval of the maximum covers 70 of 100 where 90 % were promised
    assert _validation((0.5, 50, 100), (0.9, 70, 100)).verdict() == "failed"


def test_the_damage_check_holds_the_predicted_interval():
    # 62 of 100 damaged: rejected against the estimate 50 % (scipy.stats.binomtest p = 0.02),
    # not against its interval [40 %, 65 %]; the check fails only outside the interval
    assert stats.binomtest(62, 100, 0.5).pvalue < 0.05
    assert _validation((0.5, 62, 100), (0.9, 90, 100)).verdict() == "failed"
    v = _validation((0.5, 62, 100), (0.9, 90, 100), (0.4, 0.65))
    assert v.verdict() == "passed" and v.damage_check.p_value == 1.0
    assert _validation((0.5, 20, 100), (0.9, 90, 100), (0.4, 0.65)).verdict() == "failed"
    # an interval that does not hold the estimate is widened to hold it
    w = _validation((0.5, 50, 100), (0.9, 90, 100), (0.55, 0.7))
    assert (w.damage_check.low, w.damage_check.high) == (0.5, 0.7)


def test_a_conservative_interval_of_the_maximum_does_not_fail():
    # 99 of 100 held-out maxima inside the 90 % interval: more often than stated (the
    # two-sided test would reject: scipy.stats.binomtest p = 1e-3), not a failure
    assert stats.binomtest(99, 100, 0.9).pvalue < 0.05
    v = _validation((0.5, 50, 100), (0.9, 99, 100), (0.4, 0.6))
    assert v.verdict() == "passed" and v.coverage_check.conservative
    assert v.short_text().endswith("; the interval of the maximum is conservative (99 of 100 "
                                   "inside))")
    assert "one-sided" in _validation((0.5, 50, 100), (0.9, 70, 100)).short_text()


def test_verdict_is_never_passed_with_too_few_surfaces():
    # 6 of 12 against 50 %: consistent, but 12 surfaces cannot detect a miss of 20 points
    v = _validation((0.5, 6, 12), (0.9, 11, 12))
    assert v.verdict() == "not checkable" and not v.passes()
    assert "not checkable with 12 held-out surfaces" in v.short_text()
    assert Validation(error="too few surfaces").verdict() == "not checked"
    # an interval of the damage wider than [20 %, 80 %] cannot be checked by any number
    wide = _validation((0.5, 50, 100), (0.9, 90, 100), (0.1, 0.85))
    assert wide.verdict() == "not checkable"
    assert wide.short_text() == "not checkable: the predicted damage interval [10 %, 85 %] is too " \
                                "wide to be checked"


def _lognormal_surfaces(n=120, seed=4):
    rng = np.random.default_rng(seed)
    per = _surfaces(rng, n, lambda r, k: r.lognormal(7.0, 0.3, k))
    a = AnalysisSettings(hardness=1e6 * float(np.median([m for _, _, m in per])), n_resamples=100)
    levels = hardness_levels(np.array([m for _, _, m in per]), a.hardness_mpa, a.n_levels)
    return per, a, levels


def test_validate_sample_fails_when_the_observed_maxima_exceed_the_peaks():
    # the per-surface maxima lie above every value of the sample (as where asperity patches
    # overlap and add up): the prediction from the values cannot see them, and the check
    # must say so; the same surfaces with their true maxima are not rejected
    from glstat.study.validation import validate_sample

    per, a, levels = _lognormal_surfaces()
    honest = validate_sample(per, "spot", a, 0, 0, "rs", "moments", levels)
    assert honest.damage_check.verdict != "failed" and honest.verdict() != "failed"
    assert honest.damage_check.n == 120 and honest.damage_check.is_interval
    assert honest.coverage_check.alternative == "less"
    # the check's interval is the folds' intervals pooled, as damage_calibration.csv has it
    cal = honest.calibration
    at = cal[np.isclose(cal["hardness_mpa"], a.hardness_mpa) & (cal["area_factor"] == 1)].iloc[0]
    assert honest.damage_check.low <= at["predicted_low"] + 1e-15
    assert honest.damage_check.high >= at["predicted_high"] - 1e-15
    assert (cal["predicted_low"] <= cal["predicted_high"]).all()
    lifted = [(v, k, 1.3 * m) for v, k, m in per]
    v = validate_sample(lifted, "spot", a, 0, 0, "rs", "moments", levels)
    assert v.damage_check.verdict == "failed" and v.verdict() == "failed"
    assert v.damage_check.observed >= 0.85 and v.damage_check.high < 0.7


def test_validate_sample_fails_when_the_observed_maxima_are_too_low():
    # the other direction: maxima of a parent scaled by 0.7, far below the predicted ones
    from glstat.study.validation import validate_sample

    per, a, levels = _lognormal_surfaces()
    lowered = [(v, k, 0.7 * m) for v, k, m in per]
    v = validate_sample(lowered, "spot", a, 0, 0, "rs", "moments", levels)
    assert v.verdict() == "failed" and v.damage_check.verdict == "failed"
    assert v.damage_check.observed < v.damage_check.low
    assert v.coverage_check.verdict == "failed"


def test_degenerate_scene_warning():
    def case(n_asp, damage):
        d = SimpleNamespace(estimate=np.array(damage))
        return {"summary": {"n_asperities": n_asp + 1, "n_spots": n_asp},
                "spot": SimpleNamespace(damage=d)}

    assert degenerate_scene({(0, 0): case(6.0, 0.5), (1, 0): case(8.0, 0.9)}) == ""
    msg = degenerate_scene({(0, 0): case(1.4, 1.0), (1, 0): case(1.8, 1.0)})
    assert "1.4 contact spots" in msg and "for every H" in msg and "--target-pressure" in msg


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


def test_analysis_hardness_is_in_pascals_and_the_old_mpa_form_warns():
    a = AnalysisSettings()
    assert a.hardness == 2050e6 and a.hardness_mpa == 2050.0  # SI, and MPa for the tables
    with pytest.warns(DeprecationWarning, match=r"hardness is in Pa; 2050 was read as 2050 MPa"):
        old = AnalysisSettings(hardness=2050)
    assert old.hardness == 2050e6
    assert AnalysisSettings(hardness=1.2e6).hardness_mpa == pytest.approx(1.2)  # no warning
