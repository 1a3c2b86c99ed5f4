"""The allowable load: crossings without clipping artefacts, a monotone damage curve, the
search that brackets, bisects and verifies, and a study whose found load, solved again on its
own, has the target inside its predicted interval."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pandas as pd
import pytest
from scipy.special import expit

from glstat.study.allowable import Probe, allowable_row, crossing, monotone
from glstat.study.allowable_search import next_load


def test_crossing_from_an_exact_zero_moves_with_the_target():
    # from exactly 0 to exactly 1 between 10 and 20: linear in the probability, in log load,
    # so the crossing of 1 % lies 1 % of the way in log load (no clipped logit, which put
    # every target near the same load)
    for target in (0.01, 0.1, 0.5):
        p, status, k = crossing([10, 20], [0.0, 1.0], target)
        assert status == "interpolated" and k == 0
        assert p == pytest.approx(10 * 2 ** target, rel=1e-12)
    # between 0 and a positive probability: linear in the probability as well
    p, _, _ = crossing([1, 4], [0.0, 0.2], 0.05)
    assert p == pytest.approx(4 ** 0.25, rel=1e-12)


def test_monotone_is_the_least_squares_non_decreasing_fit():
    rng = np.random.default_rng(3)
    for _ in range(200):
        x = rng.random(rng.integers(1, 9))
        y = monotone(x)
        assert np.all(np.diff(y) >= -1e-15) and y.sum() == pytest.approx(x.sum())
        # no non-decreasing sequence on a grid of candidates is closer (brute force, n <= 3)
        if x.size <= 3:
            grid = np.linspace(0, 1, 41)
            cands = np.array(np.meshgrid(*[grid] * x.size)).reshape(x.size, -1).T
            cands = cands[np.all(np.diff(cands, axis=1) >= 0, axis=1)]
            best = np.min(np.sum((cands - x) ** 2, axis=1))
            assert np.sum((y - x) ** 2) <= best + 1e-12
    assert monotone([0.0412, 0.0248, 0.3]).tolist() == pytest.approx([0.033, 0.033, 0.3])


def test_ends_beyond_the_loads_are_written_as_bounds():
    # the damage interval's upper end exceeds the target at every load and its lower end
    # stays below it at every load: the allowable load's interval is [< 5, > 20]
    probes = [Probe(5e6, 0.005, 0.0, 0.4), Probe(10e6, 0.02, 0.0, 0.6),
              Probe(20e6, 0.05, 0.001, 0.9)]
    row = allowable_row(probes, 0.01)
    assert row["status"] == "interpolated" and row["interval_mpa"] == "[< 5, > 20]"
    assert math.isnan(row["allowable_low_mpa"]) and math.isnan(row["allowable_high_mpa"])
    assert 5 < row["allowable_pressure_mpa"] < 10


def test_a_falling_damage_is_pooled_and_flagged():
    probes = [Probe(0.02e6, 0.00031, 0.0, 0.01), Probe(0.05e6, 0.0, 0.0, 0.01),
              Probe(0.25e6, 0.0412, 0.0, 0.2), Probe(0.5e6, 0.0248, 0.0, 0.2),
              Probe(1e6, 0.3, 0.1, 0.5)]
    row = allowable_row(probes, 0.01)
    assert row["monotone"] is False
    # the crossing reads the pooled curve: 0.000155 at 0.02 and 0.05, 0.033 at 0.25 and 0.5
    p, _, _ = crossing([0.02, 0.05, 0.25, 0.5, 1.0], monotone([q.estimate for q in probes]), 0.01)
    assert row["allowable_pressure_mpa"] == pytest.approx(p) and 0.05 < p < 0.25


def _truth(load_mpa: float, centre: float = 3.0, slope: float = 4.0,
           half_width: float = 0.04) -> Probe:
    """A damage curve logistic in log load, with an interval of +-half_width."""
    d = float(expit(slope * math.log(load_mpa / centre)))
    return Probe(load_mpa * 1e6, d, max(d - half_width, 0.0), min(d + half_width, 1.0))


@pytest.mark.parametrize("start", [[20.0], [0.01], [1.0, 2.0], [2.9, 3.1]])
def test_search_brackets_bisects_and_verifies(start):
    target = 0.1
    probes = [_truth(p) for p in start]
    for _ in range(30):
        load, role, state = next_load(probes, target, lowest=1e3, highest=1e9)
        if load is None:
            break
        probes.append(dataclasses.replace(_truth(load / 1e6), role=role))
    assert state == "verified"
    exact = 3.0 * math.exp(math.log(target / (1 - target)) / 4.0)
    found = [q for q in probes if q.role == "verification"][-1]
    assert found.low <= target <= found.high
    assert found.pressure / 1e6 == pytest.approx(exact, rel=0.1)
    assert len(probes) - len(start) <= 12


def test_search_reports_a_target_it_cannot_bracket():
    # damage above the target down to the lowest load allowed, and never reaching it
    high = [Probe(1e6, 0.5, 0.4, 0.6)]
    for _ in range(10):
        load, role, state = next_load(high, 0.1, lowest=0.1e6, highest=1e9)
        if load is None:
            break
        assert role == "bracket" and load < high[-1].pressure
        high.append(Probe(load, 0.5, 0.4, 0.6, role=role))
    assert state == "below the lowest load" and min(q.pressure for q in high) >= 0.1e6
    low = [Probe(1e6, 0.0, 0.0, 0.01)]
    for _ in range(10):
        load, role, state = next_load(low, 0.1, lowest=1e3, highest=10e6)
        if load is None:
            break
        low.append(Probe(load, 0.0, 0.0, 0.01, role=role))
    assert state == "above the highest load" and max(q.pressure for q in low) == 10e6


def test_study_finds_a_load_that_holds_when_solved_again(tmp_path):
    from glstat.study import AnalysisSettings, CampaignSettings, run_study

    settings = CampaignSettings(hurst=(0.5,), pressures=(5e6,), n_surfaces=8, grid=48,
                                rq=0.5e-6, n_examples=1)
    a = AnalysisSettings(n_resamples=40, grid_resamples=10, damage_areas=(1e-6,),
                         target_damage=0.1)
    res = run_study(settings, a, tmp_path / "search", workers=1, progress=False, model="both",
                    allowable=True)
    table = pd.read_csv(tmp_path / "search" / "allowable_load.csv")
    probes = pd.read_csv(tmp_path / "search" / "allowable_probes.csv")
    assert list(table["model"]) == ["bem"] and table["status"].iloc[0] == "verified"
    assert set(probes["role"]) >= {"campaign", "bracket", "verification"}
    found = float(table["allowable_pressure_mpa"].iloc[0])
    # the same surfaces solved at the load found, as a study of their own
    again = run_study(CampaignSettings(hurst=(0.5,), pressures=(found * 1e6,), n_surfaces=8,
                                       grid=48, rq=0.5e-6, n_examples=1),
                      a, tmp_path / "again", workers=1, progress=False, model="both")
    d = again.bem_analysis[(0, 0)]["spot"].area_damage.iloc[0]
    assert d["low"] <= 0.1 <= d["high"]
    assert d["estimate"] == pytest.approx(table["damage_at_allowable"].iloc[0], rel=1e-12)
    assert "allowable nominal pressure for damage ≤ 10 %" in res.report_md.read_text()
