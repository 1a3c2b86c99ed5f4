"""The study with plasticity: the plastic area fraction of the capped elastic BEM (its interval
checked on held-out surfaces, a check that fails when the halves disagree) and the allowable
nominal pressure from a campaign of several loads (interpolated, never extrapolated)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

import contact
from glstat.study import AnalysisSettings, CampaignSettings, run_study
from glstat.study.allowable import crossing
from glstat.study.campaign import campaign_surface
from glstat.study.plasticity import plastic_summary


def test_crossing_interpolates_in_the_logit_and_never_extrapolates():
    p, status, k = crossing([10, 20, 40], [0.001, 0.01, 0.2], 0.05)
    # the logit of 0.05 between those of 0.01 (at 20) and 0.2 (at 40), linearly in log load
    logit = [math.log(v / (1 - v)) for v in (0.01, 0.05, 0.2)]
    w = (logit[1] - logit[0]) / (logit[2] - logit[0])
    assert status == "interpolated" and k == 1
    assert p == pytest.approx(math.exp(math.log(20) + w * math.log(2)), rel=1e-12)
    assert crossing([10, 20], [0.02, 0.5], 0.01)[:2] == (pytest.approx(math.nan, nan_ok=True),
                                                          "below the lowest load")
    assert crossing([10, 20], [0.0, 0.005], 0.01)[1] == "above the highest load"
    assert crossing([10, 20], [0.0, math.nan], 0.01)[1] == "no estimate"


def test_plastic_interval_covers_a_non_gld_parent_and_its_check_fails_when_halves_disagree():
    rng = np.random.default_rng(5)
    same = rng.beta(4.0, 300.0, 120)  # fractions of about 1.3 %, a Beta parent (not a GLD)
    s = plastic_summary(same, 0.9)
    assert s["plastic_check"] == "passed" and s["plastic_p_value"] > 0.05
    assert s["plastic_area_fraction"] == pytest.approx(same.mean())
    truth = np.array([0.05, 0.95])
    from scipy import stats

    low, high = stats.beta.ppf(truth, 4.0, 300.0)
    assert s["plastic_area_fraction_low"] == pytest.approx(low, rel=0.25)
    assert s["plastic_area_fraction_high"] == pytest.approx(high, rel=0.25)
    shifted = same.copy()
    shifted[1::2] *= 3.0  # the held-out half yields three times as much
    assert plastic_summary(shifted, 0.9)["plastic_check"] == "failed"
    assert plastic_summary(same[:3], 0.9)["plastic_check"] == "not checked"
    zeros = np.r_[np.zeros(15), 1e-4]  # no GLD fits: the sample's quantiles
    z = plastic_summary(zeros, 0.9)
    assert z["plastic_fit"] == "empirical quantiles" and z["plastic_area_fraction_high"] >= 0


def test_study_with_plasticity_writes_the_plastic_columns_and_the_allowable_load(tmp_path):
    settings = CampaignSettings(hurst=(0.5,), pressures=(2e6, 5e6, 10e6), n_surfaces=8, grid=64,
                                rq=0.5e-6, n_examples=1)
    a = AnalysisSettings(hardness=4000e6, n_resamples=20, grid_resamples=10,
                         damage_areas=(1e-6, 25e-6))
    res = run_study(settings, a, tmp_path, workers=1, progress=False, model="both")
    table = res.summary()
    bem = table[(table["model"] == "bem") & (table["sample"] == "spot")]
    assert bem["plastic_area_fraction"].notna().all() and bem["plastic_check"].ne("").all()
    assert (bem["plastic_area_fraction_low"] <= bem["plastic_area_fraction_high"]).all()
    assert table[table["model"] == "asperity"]["plastic_area_fraction"].isna().all()
    # the stored fraction is the capped solve of the campaign's surface
    surface = campaign_surface(settings, 0, 2, 3)
    capped = contact.solve_bem(surface, 10e6, settings.E, settings.nu, hardness=4000e6, tol=1e-8,
                               max_iter=1000)
    stored = np.load(tmp_path / "H0.5_P10MPa" / "bem_0003.npz")
    assert float(stored["plastic_area_fraction"]) == pytest.approx(capped.plastic_area_fraction,
                                                                   abs=1e-12)
    allowable = pd.read_csv(tmp_path / "allowable_load.csv")
    assert set(allowable["area_mm2"]) == {1.0, 25.0} and set(allowable["model"]) == {"bem", "asperity"}
    assert allowable["status"].isin(["interpolated", "below the lowest load",
                                     "above the highest load", "no estimate"]).all()
    text = res.report_md.read_text()
    assert "allowable nominal pressure for damage ≤ 1 %" in text
    assert "plastic area at 4000 MPa" in text
    with pytest.raises(ValueError, match="not below the hardness"):
        run_study(settings, AnalysisSettings(hardness=5e6), tmp_path / "x", workers=1,
                  progress=False, model="both")


def test_areas_and_allowable_pressures_in_words():
    from glstat.study.allowable import allowable_text, area_words

    assert [area_words(a) for a in (1e-6, 25e-6, 1e-4, 1e-3)] == ["1 mm²", "25 mm²", "1 cm²",
                                                                  "10 cm²"]
    row = {"status": "interpolated", "allowable_pressure_mpa": 7.3019,
           "allowable_low_mpa": 2.969, "allowable_high_mpa": math.nan}
    assert allowable_text(row, [5e6, 10e6]) == "7.3 MPa [2.97, —]"
    row["interval_mpa"] = "[2.97, > 10]"
    assert allowable_text(row, [5e6, 10e6]) == "7.3 MPa [2.97, > 10]"
    assert allowable_text(row, [5e6, 10e6], interval=False) == "7.3 MPa"
    assert allowable_text({"status": "below the lowest load"}, [5e6, 10e6]) == \
        "< 5 MPa (below the lowest load)"
