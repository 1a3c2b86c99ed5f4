"""The study's answer tables and figures: the held-out check, the area scaling sentence."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np


def test_validation_figure_draws_intervals_that_exclude_the_point_prediction():
    # a point prediction outside its interval (possible for a mixture's bootstrap interval)
    # is drawn, not refused as a negative error bar

    import pandas as pd

    from glstat.study import AnalysisSettings, CampaignSettings
    from glstat.study.report_figures import validation_figure

    t = pd.DataFrame({"surface": [0, 1, 2], "predicted": [5.0, 6.0, 7.0], "low": [5.5, 4.0, 5.0],
                      "high": [8.0, 9.0, 6.5], "observed": [6.0, 3.0, 7.0],
                      "covered": [True, False, False]})
    v = SimpleNamespace(table=t, error=None, coverage=1 / 3, coverage_interval=(0.1, 0.7))
    analysis = {(0, 0): {"asperity": SimpleNamespace(validation=v, note="")}}
    fig = validation_figure(CampaignSettings(hurst=(0.5,)), AnalysisSettings(), analysis, "asperity")
    ax = fig.axes[0]
    assert len(ax.collections) == 1 and len(ax.collections[0].get_segments()) == 3


def test_area_scaling_sentence_counts_levels_inside_per_group_size():

    import pandas as pd

    from glstat.study import CampaignSettings
    from glstat.study.answer import area_scaling_sentence
    from glstat.study.validation import Validation

    rows = []
    for k, inside in ((1, 7), (2, 6), (4, 3)):
        for i in range(8):
            rows.append({"hardness_mpa": 1000.0 + i, "area_factor": k, "predicted": 0.5,
                         "observed": 0.5, "observed_low": 0.4 if i < inside else 0.55,
                         "observed_high": 0.6, "n_surfaces": 50})
    v = Validation(table=pd.DataFrame({"x": [1]}), coverage=0.9, coverage_interval=(0.8, 0.95),
                   reject=False, calibration=pd.DataFrame(rows))
    analysis = {(0, 0): {"spot": SimpleNamespace(validation=v)}}
    text = area_scaling_sentence(CampaignSettings(hurst=(0.5,)), analysis)
    assert "H = 0.5, 20 MPa: k = 2: 6 of 8, k = 4: 3 of 8" in text
    assert v.damage_hits() == (7, 8) and v.damage_hits(4) == (3, 8)
    v1 = Validation(table=pd.DataFrame({"x": [1]}), coverage=0.9, coverage_interval=(0.8, 0.95),
                    reject=False, calibration=pd.DataFrame([r for r in rows if r["area_factor"] == 1]))
    assert area_scaling_sentence(CampaignSettings(hurst=(0.5,)),
                                 {(0, 0): {"spot": SimpleNamespace(validation=v1)}}) == ""


def test_a_wide_damage_interval_says_what_would_narrow_it():
    import glstat
    from glstat.study import CampaignSettings
    from glstat.study.analysis import SampleAnalysis
    from glstat.study.answer import width_note

    rng = np.random.default_rng(1)
    x = rng.lognormal(0.0, 1.0, 60)
    groups = np.repeat(np.arange(3), 20)  # three surfaces of 20 spots
    t = float(np.median([x[groups == i].max() for i in range(3)]))
    p = glstat.predict_maximum(x, groups=groups, threshold=t, n_resamples=200, rng=2)
    settings = CampaignSettings(hurst=(0.5,), pressures=(20e6,))
    wide = {(0, 0): {"spot": SampleAnalysis(sample="spot", data=x, n_ref=20.0, prediction=p)}}
    assert p.damage.high - p.damage.low > 0.5
    text = width_note(settings, wide)
    need = p.data_for_width().iloc[0]
    assert f"from 3 surfaces; at least about {math.ceil(need['needed'])} surfaces" in text
    assert "±10 percentage points" in text and "an area of" in text
    # a narrow interval says nothing
    q = glstat.predict_maximum(rng.lognormal(0.0, 1.0, 2000), groups=np.repeat(np.arange(100), 20),
                               threshold=t, n_resamples=200, rng=2)
    narrow = {(0, 0): {"spot": SampleAnalysis(sample="spot", data=x, n_ref=20.0, prediction=q)}}
    assert q.damage.high - q.damage.low < 0.5 and width_note(settings, narrow) == ""
