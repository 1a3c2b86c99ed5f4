"""``glstat fit --n-max``: a random number of points (Poisson or observed counts)."""

import json

import numpy as np
import pytest

import glstat
from glstat.cli.commands import main
from glstat.cli.fit_options import parse_n_max
from glstat.cli.sample_files import InputError


@pytest.fixture(scope="module")
def peaks(tmp_path_factory):
    path = tmp_path_factory.mktemp("fit") / "peaks.csv"
    x = np.random.default_rng(0).gamma(4.0, 400.0, 300)
    np.savetxt(path, x, header="peak", comments="")
    return path, x


def test_parse_n_max_forms():
    assert parse_n_max("1048576") == (1048576.0, None)
    n, c = parse_n_max("poisson:6.2")
    assert n == 6.2 and isinstance(c, glstat.PoissonCount) and c.mu == 6.2
    n, c = parse_n_max("counts:4, 5,5,8")
    assert n == 5.5 and isinstance(c, glstat.ObservedCounts)
    for bad in ("0", "nan", "poisson:-1", "poisson:x", "counts:", "counts:1.5,2", "counts:-1,2",
                "counts:0,0", "binom:3"):
        with pytest.raises(InputError, match="--n-max must be"):
            parse_n_max(bad)


def test_fit_with_a_poisson_count_matches_the_library(peaks, tmp_path, capsys):
    path, x = peaks
    out = tmp_path / "o"
    rc = main(["fit", str(path), "--hardness", "2050", "--n-max", "poisson:6.2", "--bootstrap", "0",
               "--gof-resamples", "0", "--out", str(out), "--seed", "1"])
    assert rc == 0
    text = capsys.readouterr().out
    assert "PoissonCount(mu=6.2)" in text
    doc = json.loads((out / "fit.json").read_text())
    # without a bootstrap: the full-sample model, the GLD with its default Pareto tail
    model = glstat.ParetoTailGLD.fit(x, body=glstat.fit(x, "rs", "moments").dist)
    ref = glstat.damage_probability(model, 2050.0, count=glstat.PoissonCount(6.2))
    got = doc["damage"]["estimate"][0] if isinstance(doc["damage"]["estimate"], list) \
        else doc["damage"]["estimate"]
    assert got == pytest.approx(float(ref), rel=1e-10)


def test_bad_count_is_a_usage_error(peaks, tmp_path, capsys):
    path, _ = peaks
    rc = main(["fit", str(path), "--n-max", "counts:4,x", "--out", str(tmp_path / "o")])
    assert rc == 2
    assert "--n-max must be" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()
