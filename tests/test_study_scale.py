"""The study at a declared scale, end to end on measured files: a planted spike is found and
reported in surfaces.csv, the subsurface criterion runs, the answer is solved again at 2λs and
4λs, and the report names the S-filter and the criterion."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import contact
from glstat.study import AnalysisSettings, run_study
from glstat.study.measured import measured_settings

FAST = AnalysisSettings(n_resamples=20, grid_resamples=10, criterion="subsurface")
SPIKED = 5  # the file holding a one-pixel spike


@pytest.fixture(scope="module")
def spiked_study(tmp_path_factory):
    folder = tmp_path_factory.mktemp("spiked")
    for i in range(8):
        s = contact.self_affine((64, 64), 0.128e-3, hurst=0.8, rq=0.3e-6, rng=i)
        h = s.heights.copy()
        if i == SPIKED:  # 20 Sq above its neighbourhood, in the middle
            h[30, 33] += 20 * float(np.std(h))
        contact.write(contact.Surface(h, s.dx), folder / f"scan_{i}.npz")
    settings = measured_settings(folder)
    out = tmp_path_factory.mktemp("spiked_study")
    res = run_study(settings, FAST, out, workers=1, progress=False, model="both")
    return settings, res


def test_a_planted_spike_is_flagged_in_one_of_eight_files(spiked_study):
    settings, res = spiked_study
    table = pd.read_csv(res.out / "surfaces.csv")
    assert len(table) == 8
    flagged = table[table["spikes"] > 0]
    assert list(flagged["name"]) == [f"scan_{SPIKED}.npz"]
    assert int(flagged["spikes"].iloc[0]) == 1
    assert flagged["spike_largest_um"].iloc[0] > 10 * table["sq_um"].iloc[0]
    assert not table["spikes_replaced"].any()
    # every row states its scale
    np.testing.assert_allclose(table["spacing_um"], 0.128e3 / 64, rtol=1e-9)
    np.testing.assert_allclose(table["s_filter_um"], settings.s_filter * 1e6, rtol=1e-12)


def test_the_subsurface_criterion_runs_end_to_end(spiked_study):
    settings, res = spiked_study
    summary = res.summary()
    bem = summary[(summary["model"] == "bem") & (summary["sample"] == "spot")]
    assert (bem["criterion"] == "subsurface").all() and "yield stress" in bem["threshold"].iloc[0]
    np.testing.assert_allclose(summary["s_filter_um"], settings.s_filter * 1e6, rtol=1e-12)
    table = pd.read_csv(res.out / "surfaces.csv")
    # the von Mises maximum beneath the surface is below the surface pressure's maximum
    # (at most about 0.6 of a Hertzian peak) and positive
    assert (table["bem_max_von_mises_mpa"] > 0).all()
    assert (table["bem_max_von_mises_mpa"] < table["bem_max_pressure_mpa"]).all()
    y = 2050 / 2.8
    assert list(table["damaged_subsurface"]) == list(table["bem_max_von_mises_mpa"] >= y)
    html = res.report_html.read_text()
    assert "S-filter λs = " in html and "von Mises stress" in html and "Tabor" in html


def test_the_answer_is_solved_again_at_coarser_scales(spiked_study):
    settings, res = spiked_study
    scales = pd.read_csv(res.out / "scales.csv")
    assert list(scales["scale_factor"]) == [1, 2, 4]
    assert scales["s_filter_um"].to_numpy() == pytest.approx(
        settings.s_filter * 1e6 * np.array([1, 2, 4]))
    # a coarser filter smooths the surface: the maximal pressure falls
    assert np.all(np.diff(scales["max_pressure_mpa"].to_numpy()) < 0)
    # the finest scale is the answer's own: the same maxima as surfaces.csv
    table = pd.read_csv(res.out / "surfaces.csv")
    assert scales["max_pressure_mpa"].iloc[0] == pytest.approx(
        float(np.median(table["bem_max_pressure_mpa"])), rel=1e-9)
