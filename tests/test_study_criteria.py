"""The study's damage criteria and its scale: the per-spot figures, the plastic zones, the exact
interval, the settings' checks, and the resolution-dominated warning (it must appear when the
answer moves by more than its interval between the two finest scales, and only then)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from glstat.study import AnalysisSettings, CampaignSettings
from glstat.study.criteria import (
    Criterion,
    exact_interval,
    plastic_zone_areas,
    spot_maxima,
)
from glstat.study.surface_table import resolution_note


def test_spot_maxima_assigns_every_point_to_its_nearest_spot():
    labels = np.zeros((9, 9), dtype=int)
    labels[1, 1] = 1
    labels[7, 7] = 2
    values = np.zeros((9, 9))
    values[2, 3] = 5.0  # nearer spot 1 (distance ~2.2) than spot 2 (~6.4)
    values[6, 8] = 7.0  # nearer spot 2
    values[4, 4] = 1.0  # equidistant: either, but never above the others
    out = spot_maxima(values, labels, 2)
    np.testing.assert_array_equal(out, [5.0, 7.0])
    # the largest spot value is the map's maximum
    assert out.max() == values.max()


def test_spot_maxima_without_spots_and_with_full_contact():
    assert spot_maxima(np.ones((4, 4)), np.zeros((4, 4), dtype=int), 0).size == 0
    labels = np.ones((4, 4), dtype=int)
    np.testing.assert_array_equal(spot_maxima(np.arange(16.0).reshape(4, 4), labels, 1), [15.0])


def test_plastic_zone_areas_are_connected_zones_largest_first():
    p = np.zeros((10, 10), dtype=bool)
    p[1:3, 1:3] = True        # 4 cells
    p[6, 6] = p[7, 7] = True  # diagonal neighbours: one zone of 2 (8-connected)
    p[0, 9] = True            # 1 cell
    areas = plastic_zone_areas(p, 2.5e-12)
    np.testing.assert_allclose(areas, np.array([4, 2, 1]) * 2.5e-12)
    # a guard band of 1 point drops the zone lying wholly in it
    np.testing.assert_allclose(plastic_zone_areas(p, 1.0, guard=1), [4, 2])
    assert plastic_zone_areas(np.zeros((3, 3), dtype=bool), 1.0).size == 0


@pytest.mark.parametrize(("k", "n"), [(0, 12), (3, 12), (12, 12), (40, 97)])
def test_exact_interval_is_clopper_pearson(k, n):
    low, high = exact_interval(k, n, 0.9)
    # Clopper & Pearson (1934): the beta quantiles
    ref_low = 0.0 if k == 0 else stats.beta.ppf(0.05, k, n - k + 1)
    ref_high = 1.0 if k == n else stats.beta.ppf(0.95, k + 1, n - k)
    assert low == pytest.approx(ref_low, abs=1e-12)
    assert high == pytest.approx(ref_high, abs=1e-12)
    assert all(math.isnan(v) for v in exact_interval(0, 0, 0.9))


def test_criterion_thresholds_and_defaults():
    a = AnalysisSettings(hardness=2050e6, criterion="subsurface")
    s = CampaignSettings(n_surfaces=2, grid=64, length=1e-4, hurst=(0.5,), s_filter=8e-6)
    c = a.criterion_of(s)
    assert c.threshold == pytest.approx(2050e6 / 2.8)
    assert "Tabor" in c.threshold_text()
    z = AnalysisSettings(criterion="plastic-zone").criterion_of(s)
    assert z.threshold == pytest.approx(math.pi * (8e-6) ** 2 / 4)  # a disc of diameter λs
    given = AnalysisSettings(criterion="plastic-zone", min_plastic_area=5e-12).criterion_of(s)
    assert given.threshold == 5e-12 and "disc" not in given.threshold_text()
    with pytest.raises(ValueError, match="criterion must be one of"):
        AnalysisSettings(criterion="volume")
    with pytest.raises(ValueError, match="not below the hardness"):
        AnalysisSettings(yield_stress=3000e6)
    with pytest.raises(ValueError, match="criterion must be one of"):
        Criterion("edge")


def test_s_filter_settings_are_checked_and_part_of_the_identity():
    base = dict(n_surfaces=2, grid=64, length=1e-4, hurst=(0.5,))
    plain = CampaignSettings(**base)
    assert "s_filter" not in plain.identity() and "despike" not in plain.identity()
    filtered = CampaignSettings(**base, s_filter=8e-6)
    assert filtered.identity()["s_filter"] == 8e-6
    with pytest.raises(ValueError, match="below two grid spacings"):
        CampaignSettings(**base, s_filter=2e-6)  # spacing 1.56 µm
    with pytest.raises(ValueError, match="quarter of the surface"):
        CampaignSettings(**base, s_filter=30e-6)
    with pytest.raises(ValueError, match="measured files"):
        CampaignSettings(**base, despike=True)


def _scales(fractions, lows, highs, pressures):
    return pd.DataFrame({"hurst": 0.5, "pressure_mpa": 20.0, "scale_factor": [1, 2, 4],
                         "s_filter_um": [5.0, 10.0, 20.0], "fraction": fractions, "low": lows,
                         "high": highs, "max_pressure_mpa": pressures})


def test_resolution_note_flags_an_answer_that_moves_and_only_then():
    settings = CampaignSettings(n_surfaces=2, grid=64, length=1e-4, hurst=(0.5,))
    moving = _scales([0.5, 0.0, 0.0], [0.25, 0.0, 0.0], [0.75, 0.22, 0.22], [2100, 1500, 1100])
    assert "resolution-dominated" in resolution_note(settings, moving)
    # the fraction stays inside the finest scale's interval and the pressure moves little
    stable = _scales([0.5, 0.42, 0.3], [0.25, 0.2, 0.1], [0.75, 0.7, 0.6], [2100, 2000, 1800])
    assert resolution_note(settings, stable) == ""
    # the fraction stays but the maximal pressure falls by a third: still resolution-dominated
    pressure = _scales([0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.2, 0.2, 0.2], [1500, 1000, 800])
    assert "resolution-dominated" in resolution_note(settings, pressure)
    assert resolution_note(settings, pd.DataFrame()) == ""


def test_every_caption_states_the_scale():
    from glstat.study.report_document import Blocks

    b = Blocks()
    b.table(["a"], [[1]], "Damage per area.")
    b.table(["a"], [[1]], "Already at grid spacing 2 µm, no S-filter.")
    b.table(["a"], [[1]])  # no caption: left alone
    b.paragraph("Text is not a caption.")
    b.state_in_captions("grid spacing 1.66 µm, S-filter λs = 5 µm", "grid spacing")
    captions = [blk[3] for blk in b.blocks if blk[0] == "t"]
    assert captions == ["Damage per area (grid spacing 1.66 µm, S-filter λs = 5 µm).",
                        "Already at grid spacing 2 µm, no S-filter.", ""]
    assert b.blocks[-1] == ("p", "Text is not a caption.")


def test_the_scale_names_the_elastic_grid_when_it_differs():
    from glstat.study.scales import scale_text, spacing_um

    s = CampaignSettings(n_surfaces=2, grid=1024, length=1e-3, hurst=(0.5,))
    assert spacing_um(s) == pytest.approx(0.9765625)
    assert spacing_um(s, 384) == pytest.approx(1e3 / 384)
    assert scale_text(s, short=True) == "grid spacing 0.977 µm, no S-filter"
    assert scale_text(s, short=True, bem_grid=384) == \
        "grid spacing 0.977 µm (elastic BEM 2.6 µm), no S-filter"
