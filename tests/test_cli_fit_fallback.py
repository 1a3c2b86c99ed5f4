"""``glstat fit`` answers a sample whose requested fit has no solution when a maximum or a
damage is asked for: it falls back to the next fit of glstat.prediction.FALLBACK_FITS and
says so; asked for the fit alone it still exits 1 with the reason. The sample: 200 Fréchet
values of tail index 3 whose skewness (13) and kurtosis (187) no RS GLD has."""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy import stats

import glstat
from glstat.cli import fit as cli_fit


@pytest.fixture(scope="module")
def heavy(tmp_path_factory):
    x = stats.invweibull(3.0).rvs(size=200, random_state=np.random.default_rng(91))
    path = tmp_path_factory.mktemp("frechet") / "heavy.csv"
    np.savetxt(path, x, header="pressure", comments="")
    return path, x


def _run(capsys, argv):
    code = cli_fit.main([str(a) for a in argv])
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def test_a_prediction_falls_back_to_a_fit_with_a_solution(heavy, tmp_path, capsys):
    path, x = heavy
    with pytest.raises(glstat.FitError, match="no RS GLD matches the moments"):
        glstat.fit(x)
    code, out, err = _run(capsys, [path, "--hardness", "20", "--n-max", "1000", "--bootstrap",
                                   "60", "--gof-resamples", "0", "--seed", "1", "--out",
                                   tmp_path / "o"])
    assert code == 0, err
    assert "GLD fit: FKML parameterisation, L-moments, n = 200" in out
    notes = [line for line in out.splitlines() if line.startswith("note: ")]
    assert any(n.startswith("note: RS method of moments: no RS GLD matches the moments") and
               "used the FKML L-moments fit instead, a fallback fit" in n for n in notes)
    assert not any("unreliable" in n for n in notes)  # the tail gives the answer
    assert "  damage P(max > 20) on n = 1000 points: " in out
    doc = json.loads((tmp_path / "o" / "fit.json").read_text())
    assert (doc["fit"]["param"], doc["fit"]["method"]) == ("fkml", "lmoments")
    assert (doc["settings"]["param"], doc["settings"]["method"]) == ("rs", "moments")
    ref = glstat.predict_maximum(x, [("fkml", "lmoments")], n=1000.0, threshold=20.0,
                                 n_resamples=60, rng=1, maximum=False)
    assert doc["damage"]["estimate"][0] == pytest.approx(float(ref.damage.estimate), rel=1e-12)


def test_the_fit_alone_still_fails_with_the_reason(heavy, tmp_path, capsys):
    path, _ = heavy
    code, out, err = _run(capsys, [path, "--bootstrap", "0", "--gof-resamples", "0",
                                   "--out", tmp_path / "o"])
    assert code == 1 and "GLD fit:" not in out
    assert err.startswith("glstat fit: no GLD fit: no RS GLD matches the moments")
