"""The whole method on the elastic BEM (`glstat study --model both`)."""

import numpy as np
import pandas as pd
import pytest

from glstat.cli.commands import main
from glstat.study import BEMSettings, CampaignSettings, run_bem, run_campaign
from glstat.study.bem import elastic_results

ARGS = ["study", "--surfaces", "6", "--grid", "64", "--rq", "1.6", "--bootstrap", "40", "--no-progress",
        "--workers", "1", "--hurst", "0.5", "1"]


@pytest.fixture(scope="module")
def both(tmp_path_factory):
    out = tmp_path_factory.mktemp("elastic") / "run"
    assert main([*ARGS, "--model", "both", "--out", str(out)]) == 0
    return out


def test_both_models_side_by_side(both):
    summary = pd.read_csv(both / "summary.csv")
    assert set(summary["model"]) == {"asperity", "bem"}
    bem = summary[summary["model"] == "bem"]
    assert len(bem) == 4  # 2 H x 2 samples (contact spots, grid points), each with its checks
    assert set(bem["sample"]) == {"spot", "grid"}
    assert bem["n_surfaces"].eq(6).all()
    # the elastic spot sample is the peak of every contact spot inside the patch
    assert (bem["spots_per_surface"] > 0).all() and bem["asperities_per_surface"].isna().all()
    spot = bem[bem["sample"] == "spot"]
    assert ((spot["values_per_surface"] - spot["spots_per_surface"]).abs() < 1e-12).all()
    cal = pd.read_csv(both / "damage_calibration.csv")
    assert set(cal["model"]) == {"asperity", "bem"}
    md = (both / "report.md").read_text()
    assert "H = 0.5, elastic BEM" in md and "H = 1, asperity model" in md
    # every surface was solved by both models
    assert len(list(both.glob("H*/bem_*.npz"))) == 12


def test_elastic_results_match_the_stored_solves(both):
    s = CampaignSettings(hurst=(0.5, 1.0), n_surfaces=6, grid=64, rq=1.6e-6)
    res, dropped = elastic_results(both, s, BEMSettings(n_compare=6))
    assert not dropped and len(res) == 12
    with np.load(both / "H0.5_P20MPa" / "bem_0002.npz") as z:
        r = res[(0, 0, 2)]
        np.testing.assert_array_equal(r["spot_peak"], z["bem_cluster_peaks"])
        assert r["n_spots"] == int(z["bem_n_clusters"]) == r["spot_peak"].size
        assert r["max_pressure"] == pytest.approx(float(r["spot_peak"].max()))


def test_unconverged_solves_are_left_out_and_listed(tmp_path):
    s = CampaignSettings(hurst=(0.5,), n_surfaces=2, grid=64, rq=1.6e-6)
    run_campaign(s, tmp_path, workers=1, progress=False)
    b = BEMSettings(n_compare=2, max_iter=2)
    run_bem(s, b, tmp_path, workers=1, progress=False)
    res, dropped = elastic_results(tmp_path, s, b)
    assert dropped == [(0, 0, 0), (0, 0, 1)] and res == {}
