"""glstat.study.scene: the Rq that gives a requested mean contact pressure, and the scene summary.

Every Rq returned is checked by solving the campaign's surfaces again at that Rq with
glstat.study.simulate_surface (the campaign's own code path) on a 256² grid.
"""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pytest

from glstat import ConvergenceWarning
from glstat.study import CampaignSettings, simulate_surface
from glstat.study.scene import RqSearch, rq_for_pressure, scene_summary

SMALL = CampaignSettings(grid=256, n_surfaces=4, n_examples=0)


def _mean_pressures(settings, rq, n_seeds):
    """Mean over surfaces 0..n_seeds-1 of the campaign's mean contact pressure, per H (Pa)."""
    s = dataclasses.replace(settings, rq=rq, n_examples=0)
    return np.array([np.mean([float(simulate_surface(s, ih, 0, i)["mean_pressure"])
                              for i in range(n_seeds)]) for ih in range(len(s.hurst))])


def test_one_rq_for_all_h_gives_the_target_on_rerun():
    target = 1.3e9
    res = rq_for_pressure(target, settings=SMALL, n_seeds=2, full_output=True)
    assert isinstance(res, RqSearch) and res.converged and res.grid == 256
    assert len(set(res.rq)) == 1
    p = _mean_pressures(SMALL, res.rq[0], 2)
    np.testing.assert_allclose(p, res.achieved, rtol=1e-12)
    # one Rq for all H: the geometric mean of achieved / target is 1 within rtol
    ratio = math.exp(np.mean(np.log(p / target)))
    assert abs(math.log(ratio)) <= math.log1p(res.rtol)
    assert rq_for_pressure(target, settings=SMALL, n_seeds=2) == res.rq[0]


def test_one_rq_per_h_at_the_papers_pressures():
    # Table 1 of Bigerelle et al. (2019): 1724 / 1369 / 1108 MPa for H = 0 / 0.5 / 1
    targets = np.array([1724e6, 1369e6, 1108e6])
    res = rq_for_pressure(targets, settings=SMALL, n_seeds=2, per_hurst=True, rtol=0.03,
                          full_output=True)
    assert res.converged
    for ih, rq in enumerate(res.rq):
        p = _mean_pressures(SMALL, rq, 2)[ih]
        assert abs(math.log(p / targets[ih])) <= math.log1p(0.03)
    out = rq_for_pressure(targets, settings=SMALL, n_seeds=2, per_hurst=True, rtol=0.03)
    assert out == res.rq and isinstance(out, tuple)
    # the scale of the paper's pressures: Rq of about 1-3 µm on 1 mm², not 50 µm
    assert all(0.5e-6 < rq < 4e-6 for rq in res.rq)


def test_higher_target_needs_rougher_surfaces():
    lo = rq_for_pressure(0.8e9, 1.0, settings=SMALL, n_seeds=2)
    hi = rq_for_pressure(2.4e9, 1.0, settings=SMALL, n_seeds=2)
    assert hi > 1.5 * lo


def test_hurst_subset_keeps_the_campaigns_seeds():
    res = rq_for_pressure(1.2e9, [0.5], settings=SMALL, n_seeds=2, full_output=True)
    assert res.hurst == (0.5,)
    # H = 0.5 is exponent number 1 of the settings: its surfaces are the campaign's
    assert res.achieved[0] == pytest.approx(_mean_pressures(SMALL, res.rq[0], 2)[1], rel=1e-12)
    # an exponent the settings lack: the surfaces of a campaign with exactly that exponent
    res = rq_for_pressure(1.2e9, [0.25], settings=SMALL, n_seeds=2, full_output=True)
    s = dataclasses.replace(SMALL, hurst=(0.25,), n_terms=(6,))
    assert res.achieved[0] == pytest.approx(_mean_pressures(s, res.rq[0], 2)[0], rel=1e-12)


@pytest.mark.parametrize("bad", [0.0, -1e9, math.nan, math.inf, -math.inf])
def test_non_positive_or_non_finite_target_is_refused(bad):
    with pytest.raises(ValueError, match="positive and finite"):
        rq_for_pressure(bad, settings=SMALL)


def test_bad_arguments_are_refused():
    with pytest.raises(ValueError, match="at least the nominal pressure 20 MPa"):
        rq_for_pressure(15e6, settings=SMALL)
    with pytest.raises(ValueError, match=r"one per Hurst exponent \(3\)"):
        rq_for_pressure([1e9, 1e9], settings=SMALL)
    with pytest.raises(ValueError, match="n_seeds"):
        rq_for_pressure(1e9, settings=SMALL, n_seeds=0)
    with pytest.raises(ValueError, match="rtol"):
        rq_for_pressure(1e9, settings=SMALL, rtol=0.0)
    with pytest.raises(ValueError, match="rq_bounds"):
        rq_for_pressure(1e9, settings=SMALL, rq_bounds=(1e-5, 1e-6))


def test_target_above_the_reachable_range_names_target_and_range():
    with pytest.raises(ValueError) as exc:
        rq_for_pressure(1e12, settings=SMALL, n_seeds=1, rq_bounds=(1e-7, 1e-5))
    msg = str(exc.value)
    assert "1e+06 MPa" in msg and "above the reachable range" in msg
    top = float(re.search(r"at most ([0-9.e+]+) MPa at Rq = 1e-05 m", msg).group(1))
    # the stated upper end is the geometric mean over H at Rq = 10 µm, recomputed
    p = _mean_pressures(SMALL, 1e-5, 1)
    assert top == pytest.approx(math.exp(np.mean(np.log(p))) / 1e6, rel=1e-5)


def test_target_below_the_reachable_range_names_target_and_range():
    with pytest.raises(ValueError) as exc:
        rq_for_pressure(1e8, 1.0, settings=SMALL, n_seeds=1, rq_bounds=(1e-6, 1e-4))
    msg = str(exc.value)
    assert "100 MPa (H = 1)" in msg and "below the reachable range" in msg
    low = float(re.search(r"runs from ([0-9.e+]+) MPa at Rq = 1e-06 m", msg).group(1))
    p = _mean_pressures(SMALL, 1e-6, 1)[2]  # H = 1 is the settings' exponent number 2
    assert low == pytest.approx(p / 1e6, rel=1e-5)
    assert low > 100


def test_unmet_tolerance_warns_and_returns_the_closest_evaluation():
    with pytest.warns(ConvergenceWarning, match="differs from the target"):
        res = rq_for_pressure(1.5e9, 0.0, settings=SMALL, n_seeds=1, rtol=1e-6,
                              max_evaluations=1, coarse_grid=None, full_output=True)
    assert not res.converged
    evaluated = {(e["rq"], e["mean_pressure"]) for e in res.evaluations}
    assert (res.rq[0], res.achieved) in evaluated
    best = min(abs(math.log(e["mean_pressure"][0] / 1.5e9)) for e in res.evaluations)
    assert abs(math.log(res.achieved[0] / 1.5e9)) == best


def test_scene_summary_numbers():
    t = scene_summary(SMALL, n_seeds=2)
    e_star = 210e9 / (1 - 0.3 ** 2)
    # the paper's means (Table 1) and tan(beta) = p / (c E*)
    np.testing.assert_allclose(t["paper_mean_pressure_pa"], [1724e6, 1369e6, 1108e6])
    np.testing.assert_allclose(t["paper_tan_beta"], t["paper_mean_pressure_pa"] / (0.2 * e_star))
    np.testing.assert_allclose(t["mean_pressure_pa"], _mean_pressures(SMALL, SMALL.rq, 2),
                               rtol=1e-12)
    np.testing.assert_allclose(t["tan_beta_implied"], t["mean_pressure_pa"] / (0.2 * e_star))
    # the measured rms slope scatters around its expectation over the random coefficients
    assert ((t["rms_slope"] / t["rms_slope_expected"]).between(0.5, 1.5)).all()
    # slopes scale with Rq: the paper's printed 50 µm gives slopes 50 / 1.6 times larger
    t50 = scene_summary(dataclasses.replace(SMALL, rq=50e-6), n_seeds=2, solve=False)
    np.testing.assert_allclose(t50["rms_slope"] / t["rms_slope"], 50 / 1.6, rtol=1e-9)
    assert (t50["rms_slope_over_paper_tan_beta"] > 10 * t["rms_slope_over_paper_tan_beta"]).all()
    np.testing.assert_allclose(t["shortest_wavelength_m"], 1e-3 / 1.5 ** 5)


def test_glstat_study_target_pressure_places_the_scene(tmp_path, capsys):
    """`glstat study --target-pressure` runs the campaign at the Rq rq_for_pressure finds and
    records it in the manifest and the report."""
    import json

    from glstat.cli.commands import main

    out = tmp_path / "run"
    rc = main(["study", "--surfaces", "4", "--grid", "128", "--hurst", "0.5", "--bootstrap", "20",
               "--target-pressure", "1300", "--compare-bem", "0", "--no-progress", "--workers",
               "1", "--out", str(out)])
    assert rc == 0
    err = capsys.readouterr().err
    rq_um = float(re.search(r"glstat study: Rq = ([\d.]+) µm", err).group(1))
    s128 = CampaignSettings(grid=128, n_surfaces=4, hurst=(0.5,), n_examples=0)
    expected = rq_for_pressure(1.3e9, settings=s128)
    assert rq_um == pytest.approx(expected * 1e6, rel=1e-3)
    manifest = json.loads((out / "manifest.json").read_text())
    assert any(abs(v - expected) <= 1e-9 * expected for v in _floats(manifest))
    assert f"Rq = {rq_um:.4g} µm" in (out / "report.md").read_text()


def _floats(obj):
    """Every float in a JSON document."""
    if isinstance(obj, dict):
        for v in obj.values():
            yield from _floats(v)
    elif isinstance(obj, list):
        for v in obj:
            yield from _floats(v)
    elif isinstance(obj, float):
        yield obj


def test_one_rq_per_h_drives_the_campaign():
    """CampaignSettings takes one Rq per H (as rq_for_pressure(per_hurst=True) returns): each
    H's surfaces have their own Rq; one value for all H stays a float (the same identity)."""
    from glstat.study.surface_task import weierstrass_surface

    rqs = (1.0e-6, 2.0e-6, 3.0e-6)
    s = CampaignSettings(grid=128, n_surfaces=2, rq=rqs, n_examples=0)
    assert s.rq == rqs and [s.rq_of(i) for i in range(3)] == list(rqs)
    for ih, rq in enumerate(rqs):
        h = weierstrass_surface(s, ih, 0, 0).heights
        assert float(np.sqrt(np.mean((h - h.mean()) ** 2))) == pytest.approx(rq, rel=1e-6)
    same = CampaignSettings(grid=128, rq=(1.6e-6,) * 3)
    assert same.rq == 1.6e-6 and same.identity() == CampaignSettings(grid=128).identity()
    assert s.identity()["rq"] == list(rqs)
    with pytest.raises(ValueError, match="one value or one per Hurst exponent"):
        CampaignSettings(rq=(1e-6, 2e-6))
    with pytest.raises(ValueError, match="rq"):
        CampaignSettings(rq=(1e-6, -2e-6, 1e-6))


def test_glstat_study_target_pressure_per_h(tmp_path, capsys):
    from glstat.cli.commands import main

    out = tmp_path / "run"
    rc = main(["study", "--surfaces", "3", "--grid", "128", "--hurst", "0", "1", "--bootstrap",
               "20", "--target-pressure", "1724", "1108", "--compare-bem", "0", "--no-progress",
               "--workers", "1", "--out", str(out)])
    assert rc == 0
    s128 = CampaignSettings(grid=128, n_surfaces=3, hurst=(0.0, 1.0), n_examples=0)
    expected = rq_for_pressure([1.724e9, 1.108e9], settings=s128, per_hurst=True)
    err = capsys.readouterr().err
    assert f"Rq = {expected[0] * 1e6:.4g}, {expected[1] * 1e6:.4g} µm (per H)" in err
    rc = main(["study", "--hurst", "0", "1", "--target-pressure", "1724", "1369", "1108",
               "--out", str(tmp_path / "bad")])
    assert rc == 2 and "one value or one per --hurst (2), got 3" in capsys.readouterr().err
