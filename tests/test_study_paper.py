"""glstat.study.paper: Table 1 of Bigerelle et al. (2019) and the checks computed from it.

The stored table holds the paper's mean contact pressures only, so the checks that need the
other columns are exercised on tables built here the way the paper's Table 1 is built (moments
of a GLD, rounded as printed; λ's printed as the mirror image of the moment fit, |λ2| printed
for region 4), and every number the module computes is compared with an independent
computation: numerical quadrature for moments, the quantile function itself for the mirror
and for F(Pd).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize

from glstat import GLD, InvalidParameterError
from glstat.study import paper
from glstat.study.paper import paper_consistency, paper_findings
from glstat.study.paper_checks import damage_claims, moment_fit_roots, printed_lambda_check, reading_family
from glstat.study.paper_gld import as_distribution, lambda_moments, mirror_lambdas
from glstat.study.paper_table import CLAIM_RANGES, PAPER_CLAIMS, SCENE_N_CONTACT, TABLE1, table1

# The GLDs the synthetic tables are built from (MPa): a region-3 GLD per H = 1, 0.5 and a
# region-4 GLD (lambda2 < 0) for H = 0, the sign pattern of the paper's H = 0 row.
GENERATORS = {
    1.0: (1050.0, 0.0012, 0.25, 0.12),
    0.5: (1300.0, 0.0009, 0.08, 0.20),
    0.0: (1724.0, -0.0005, -0.05, -0.10),
}


def _q(lam, u):
    """RS quantile function written out (independent of glstat's kernels)."""
    l1, l2, l3, l4 = lam
    return l1 + (u ** l3 - (1 - u) ** l4) / l2


def _quad_moments(lam):
    """Mean, sd, skewness, kurtosis of Q(U) by tanh-sinh quadrature (mpmath, 30 digits, which
    copes with the endpoint singularities of negative λ3, λ4): the mean, then the central
    moments of Q(U) - mean."""
    import mpmath as mp

    with mp.workdps(30):
        l1, l2, l3, l4 = (mp.mpf(v) for v in lam)

        def q(u):
            return l1 + (u ** l3 - (1 - u) ** l4) / l2

        m1 = mp.quad(q, [0, 0.5, 1])
        mu2, mu3, mu4 = (mp.quad(lambda u, k=k: (q(u) - m1) ** k, [0, 0.5, 1]) for k in (2, 3, 4))
        return float(m1), float(mp.sqrt(mu2)), float(mu3 / mu2 ** 1.5), float(mu4 / mu2 ** 2)


def _synthetic_table():
    """Table 1 built as the paper's is: printed moments of the fit (rounded to 1 MPa and 3
    decimals), printed λ's = mirror image of the fit, |λ2| printed for the region-4 row."""
    rows = []
    for h, lam in GENERATORS.items():
        m = _quad_moments(lam)
        pr = mirror_lambdas(lam, m[0])
        rows.append(dict(hurst=h, mean_mpa=round(m[0]), sd_mpa=round(m[1]),
                         skewness=round(m[2], 3), kurtosis=round(m[3], 3),
                         lambda1_mpa=pr[0], lambda2_per_mpa=abs(pr[1]), lambda3=pr[2],
                         lambda4=pr[3]))
    return rows


@pytest.fixture(scope="module")
def synthetic():
    return _synthetic_table()


@pytest.fixture(scope="module")
def consistency(synthetic):
    return paper_consistency(table=synthetic)


# -- the stored table ------------------------------------------------------------------------------
def test_stored_table_holds_the_papers_means_with_provenance():
    t = table1()
    # Bigerelle et al. (2019), Table 1: 1724 / 1369 / 1108 MPa for H = 0 / 0.5 / 1
    assert t["hurst"].tolist() == [0.0, 0.5, 1.0]
    assert t["mean_mpa"].tolist() == [1724.0, 1369.0, 1108.0]
    assert set(t["source"]) == {paper.TABLE1_SOURCE}
    assert "Coatings 10(1):15, 2019, Table 1" in paper.TABLE1_SOURCE
    assert PAPER_CLAIMS == {0.0: "certain", 0.5: "about 1 %", 1.0: "impossible"}
    # the columns not stored are NaN, not made up
    assert t[["sd_mpa", "skewness", "kurtosis", "lambda1_mpa"]].isna().all().all()


def test_stored_table_findings_state_what_they_can_and_cannot_check():
    c = paper_consistency()
    f = c.findings()
    e_star_mpa = 210e3 / (1 - 0.3 ** 2)
    for m in (1724, 1369, 1108):
        assert f"{m / (0.2 * e_star_mpa):.3f}" in f[0]
    assert "2050 MPa is 1.19 / 1.50 / 1.85 times" in f[0]
    assert any(s.startswith("Not checked") for s in f)
    assert c.damage.empty and c.roots["note"].str.contains("not stored").all()


def test_table_rows_are_validated():
    with pytest.raises(ValueError, match="unknown Table 1 column"):
        table1([{"hurst": 0.0, "mean_mpa": 1.0, "sigma": 2.0}])
    with pytest.raises(ValueError, match="'hurst' and 'mean_mpa'"):
        table1([{"hurst": 0.0}])
    with pytest.raises(ValueError, match="no rows"):
        table1([])
    # values in the wrong unit or impossible ones are named, not used
    with pytest.raises(ValueError, match=r"mean_mpa = 1724000000.0 is not a contact pressure in MPa"):
        table1([{"hurst": 0.0, "mean_mpa": 1724e6}])
    with pytest.raises(ValueError, match=r"sd_mpa = -5\.0 must be a positive standard deviation"):
        table1([{"hurst": 0.0, "mean_mpa": 1724.0, "sd_mpa": -5.0}])
    with pytest.raises(ValueError, match=r"kurtosis 0\.8 is below 1, which no distribution"):
        table1([{"hurst": 0.0, "mean_mpa": 1724.0, "skewness": 0.0, "kurtosis": 0.8}])
    with pytest.raises(ValueError, match="one row per H"):
        table1([{"hurst": 0.5, "mean_mpa": 1.0}, {"hurst": 0.5, "mean_mpa": 2.0}])
    with pytest.raises(ValueError, match=r"lambda1_mpa = 1.307e\+09 is not in MPa"):
        table1([{"hurst": 1.0, "mean_mpa": 1108.0, "lambda1_mpa": 1307e6}])


# -- moments, mirror, readings ---------------------------------------------------------------------
@pytest.mark.parametrize("lam", [
    (0.0, 0.197451, 0.134912, 0.134912),      # RS normal approximation
    (1050.0, 0.0012, 0.25, 0.12),
    (1724.0, -0.0005, -0.05, -0.10),
    (1724.0, 0.0005, -0.05, -0.10),           # decreasing Q: still a random variable Q(U)
    (10.7621, 0.014452, 0.0251988, 0.093884),  # Gamma(5, 3), Karian & Dudewicz
])
def test_lambda_moments_match_quadrature(lam):
    got = lambda_moments(*lam)
    ref = _quad_moments(lam)
    np.testing.assert_allclose(got[:2], ref[:2], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(got[2:], ref[2:], rtol=1e-7, atol=1e-7)


def test_lambda_moments_need_the_fourth_moment():
    # the 4th moment of Q(U) exists iff min(l3, l4) > -1/4
    assert all(math.isnan(x) for x in lambda_moments(0, -1, -0.3, -0.1))
    assert all(math.isfinite(x) for x in lambda_moments(0, -1, -0.24, -0.1))
    assert all(math.isnan(x) for x in lambda_moments(0, 0.0, 0.1, 0.1))  # lambda2 = 0


def test_mirror_is_the_reflection_about_the_mean():
    lam = GENERATORS[0.5]
    mean = lambda_moments(*lam)[0]
    gm = GLD(*mirror_lambdas(lam, mean))
    u = np.linspace(0.001, 0.999, 41)
    # 2 a1 - X has quantile function 2 a1 - Q(1 - u), computed from the formula
    np.testing.assert_allclose(gm.ppf(u), 2 * mean - _q(lam, 1 - u), rtol=1e-12)
    m0, m1 = lambda_moments(*lam), lambda_moments(*gm.lambdas)
    np.testing.assert_allclose([m1[0], m1[1], -m1[2], m1[3]], m0, rtol=1e-10)
    assert mirror_lambdas((1.0, 2.0, 3.0, 4.0), 10.0) == (19.0, 2.0, 4.0, 3.0)


def test_invalid_row_is_read_with_the_sign_of_lambda2_changed():
    with pytest.raises(InvalidParameterError) as exc:
        GLD(1957.9, 0.0005, -0.1, -0.05)
    g, reading, err = as_distribution(1957.9, 0.0005, -0.1, -0.05)
    assert err == str(exc.value) and "region 4" in err and "lambda2 must be negative" in err
    assert reading == "λ2 sign changed" and g.lambdas == (1957.9, -0.0005, -0.1, -0.05)
    g, reading, err = as_distribution(*GENERATORS[1.0])
    assert (reading, err) == ("as printed", "")
    assert as_distribution(0.0, 1.0, 0.5, -0.5)[0] is None  # no reading is a GLD


def test_decreasing_q_is_the_gld_with_swapped_shapes():
    # Q(U) with a decreasing Q has quantile function Q(1 - u) = RS(l1, -l2, l4, l3)
    lam = (1724.0, 0.0005, -0.05, -0.10)
    u = np.linspace(0.01, 0.99, 25)
    np.testing.assert_allclose(GLD(1724.0, -0.0005, -0.10, -0.05).ppf(u), _q(lam, 1 - u),
                               rtol=1e-12)


# -- the checks on a table built like the paper's ----------------------------------------------------
def test_printed_lambdas_reproduce_mean_sd_kurtosis_with_the_skewness_flipped(consistency, synthetic):
    p = consistency.printed.set_index("hurst")
    for row in synthetic:
        r = p.loc[row["hurst"]]
        # printed moments are rounded to 1 MPa and 3 decimals
        assert abs(r["mean_mpa"] - row["mean_mpa"]) <= 0.5 + 1e-9
        assert abs(r["sd_mpa"] - row["sd_mpa"]) <= 0.5 + 1e-9
        assert abs(r["kurtosis"] - row["kurtosis"]) <= 5e-4 + 1e-9
        assert abs(r["skewness"] + row["skewness"]) <= 5e-4 + 1e-9          # opposite sign
        assert abs(r["mirrored_skewness"] - row["skewness"]) <= 5e-4 + 1e-9  # mirror restores it
        assert r["sign_flip"]
    assert p.loc[0.0, "valid"] is False or p.loc[0.0, "valid"] == False  # noqa: E712
    assert "region 4" in p.loc[0.0, "error"] and p.loc[0.0, "reading"] == "λ2 sign changed"
    assert (p.loc[[0.5, 1.0], "valid"] == True).all()  # noqa: E712


def test_moment_fit_roots_match_the_generating_gld(consistency):
    roots = consistency.roots
    for h, lam in GENERATORS.items():
        sub = roots[roots["hurst"] == h]
        assert len(sub) >= 1 and sub["selected"].sum() == 1
        g0 = GLD(*lam)
        u = np.linspace(0.02, 0.98, 25)
        # one root is the generating GLD, up to the rounding of the printed moments
        best = min(np.max(np.abs(GLD(r.lambda1_mpa, r.lambda2_per_mpa, r.lambda3, r.lambda4).ppf(u)
                                 - g0.ppf(u))) for r in sub.itertuples())
        assert best < 2.0  # MPa
        for r in sub.itertuples():
            # every root reproduces the printed moments (its moments computed from its λ's)
            row = consistency.table.set_index("hurst").loc[h]
            assert abs(r.mean_mpa - row.mean_mpa) < 1e-6 * row.mean_mpa
            assert abs(r.skewness - row.skewness) < 1e-6
            if r.region == 3:  # support [Q(0), Q(1)] = [l1 - 1/l2, l1 + 1/l2]
                assert r.upper_mpa == pytest.approx(r.lambda1_mpa + 1 / r.lambda2_per_mpa)
                assert r.lower_mpa == pytest.approx(r.lambda1_mpa - 1 / r.lambda2_per_mpa)
                assert r.hardness_beyond_upper == (2050.0 >= r.upper_mpa)
            else:
                assert math.isinf(r.upper_mpa) and not r.hardness_beyond_upper


def _damage_by_inversion(lam, x, n):
    """1 - F(x)^n with F(x) found by solving Q(u) = x (the quantile formula)."""
    bounded = min(lam[2], lam[3]) > 0  # region 3: support [Q(0), Q(1)]
    lo, hi = (_q(lam, 0.0), _q(lam, 1.0)) if bounded else (-math.inf, math.inf)
    if x >= hi:
        return 0.0
    if x <= lo:
        return 1.0
    u = optimize.brentq(lambda v: _q(lam, v) - x, 1e-300, 1 - 1e-16, xtol=1e-300, rtol=1e-15)
    return -math.expm1(n * math.log(u))


def test_damage_claims_equal_one_minus_f_to_the_n(consistency):
    d = consistency.damage
    assert set(d["hurst"]) == {0.0, 0.5, 1.0}
    for r in d.itertuples():
        lam = (r.lambda1_mpa, r.lambda2_per_mpa, r.lambda3, r.lambda4)
        ref = _damage_by_inversion(lam, 2050.0, r.n_contact)
        assert r.damage == pytest.approx(ref, rel=1e-6, abs=1e-300)
        assert r.n_contact == SCENE_N_CONTACT[r.hurst]
        lo_p, hi_p = CLAIM_RANGES[r.claim]
        assert r.reproduced == (lo_p <= r.damage <= hi_p)
        if math.isfinite(r.n_low) and r.n_low > 1:
            # at the lower end of its n range the damage sits on the claim's lower bound
            assert _damage_by_inversion(lam, 2050.0, r.n_low) == pytest.approx(lo_p, rel=1e-6)
        if math.isfinite(r.n_high):
            assert _damage_by_inversion(lam, 2050.0, r.n_high) == pytest.approx(hi_p, rel=1e-6)


def test_gld_ending_below_the_hardness_makes_impossible_an_artefact(consistency):
    roots = consistency.roots
    ends_below = roots[(roots["hurst"] == 1.0) & roots["hardness_beyond_upper"].astype(bool)]
    assert len(ends_below)
    d = consistency.damage
    for r in ends_below.itertuples():
        row = d[(d["hurst"] == 1.0) & (d["lambda3"] == r.lambda3)].iloc[0]
        assert row.damage == 0.0 and row.n_high == math.inf  # for any n
    assert any("damage 0 for any" in s for s in consistency.findings())


def test_common_n_really_reproduces_every_claim(consistency, synthetic):
    common = consistency.common_n
    assert set(common["family"]) == {"printed", "mirror of printed", "moment fits"}
    for r in common.itertuples():
        if not r.exists:
            continue
        n = math.sqrt(r.n_low * r.n_high) if math.isfinite(r.n_high) else 2 * r.n_low
        d = damage_claims(synthetic, n_contact=n)
        fam = d[d["source"].map(reading_family) == r.family]
        ok = fam.groupby("hurst")["reproduced"].any()
        assert ok.all(), (r.family, n)
        # just outside the range the claims are not all reproduced by any choice of reading
        for n_out in (r.n_low / 1.5, r.n_high * 1.5):
            if not (math.isfinite(n_out) and n_out >= 1):
                continue
            d = damage_claims(synthetic, n_contact=n_out)
            fam = d[d["source"].map(reading_family) == r.family]
            assert not fam.groupby("hurst")["reproduced"].any().all()


def test_findings_name_the_sign_flip_and_the_invalid_row(consistency):
    f = paper_findings(consistency)
    assert sum("the skewness has the opposite sign" in s for s in f) == 3
    assert any(s.startswith("H = 0: the printed λ's are not a valid RS GLD") for s in f)
    assert not any(s.startswith("Not checked") for s in f)


def test_n_contact_and_hardness_are_checked(synthetic):
    # an H missing from the mapping takes the stored count of the default scene
    d = damage_claims(synthetic, n_contact={0.0: 1e4, 1.0: 2e4})
    assert d.groupby("hurst")["n_contact"].first().to_dict() == {
        0.0: 1e4, 0.5: SCENE_N_CONTACT[0.5], 1.0: 2e4}
    with pytest.raises(ValueError, match=r"no count for H = 0\.25"):
        damage_claims([{"hurst": 0.25, "mean_mpa": 1500.0, "lambda1_mpa": 1500.0,
                        "lambda2_per_mpa": 0.001, "lambda3": 0.1, "lambda4": 0.1}],
                      n_contact={0.0: 1e4})
    with pytest.raises(ValueError, match=">= 1"):
        damage_claims(synthetic, n_contact=0.5)
    with pytest.raises(ValueError, match="hardness_mpa"):
        paper_consistency(table=synthetic, hardness_mpa=-1.0)
    d = damage_claims(synthetic, n_contact={0.0: 100, 0.5: 200, 1.0: 300})
    assert d.groupby("hurst")["n_contact"].first().to_dict() == {0.0: 100, 0.5: 200, 1.0: 300}


def test_moment_roots_report_impossible_moments():
    roots = moment_fit_roots([{"hurst": 1.0, "mean_mpa": 1108, "sd_mpa": 100, "skewness": 2.0,
                               "kurtosis": 4.0}])  # kurtosis <= 1 + skewness^2: no distribution
    assert roots["note"].iloc[0].startswith("FitError")
    assert printed_lambda_check([TABLE1[0]])["note"].iloc[0] == "Table 1 λ's not stored"


@pytest.mark.slow
def test_stored_contact_counts_are_reproduced():
    # SCENE_N_CONTACT: surfaces 0-19 of each H at the default scene, 1024²
    from glstat.study import CampaignSettings, simulate_surface

    s = CampaignSettings(n_surfaces=20, n_examples=0)
    for ih, h in enumerate(s.hurst):
        n = np.mean([int(simulate_surface(s, ih, 0, i)["n_contact"]) for i in range(20)])
        assert n == pytest.approx(SCENE_N_CONTACT[h], rel=1e-12)


# -- glstat study --paper-table ----------------------------------------------------------------------
def test_study_reads_the_printed_table_and_checks_it(tmp_path, synthetic):
    import pandas as pd

    from glstat.cli.commands import main

    csv = tmp_path / "table1.csv"
    pd.DataFrame(synthetic).to_csv(csv, index=False)
    out = tmp_path / "run"
    rc = main(["study", "--surfaces", "6", "--grid", "64", "--rq", "5", "--bootstrap", "50",
               "--no-progress", "--compare-bem", "0", "--workers", "1", "--out", str(out),
               "--paper-table", str(csv)])
    assert rc == 0
    md = (out / "report.md").read_text()
    section = md.split("## Consistency with the paper", 1)[1].split("\n## ", 1)[0]
    expected = paper.paper_findings(table=synthetic, n_contact=1.0)  # n does not enter these
    assert "Not checked" not in section
    assert any("mirror" in line for line in expected)
    checked = [line for line in expected if ("mirror" in line or "region" in line)
               and "points in contact" not in line]  # the damage lines depend on the run's n
    assert checked
    for line in checked:
        assert line in section
    assert "Damage at 2050 MPa from the mirror image of the printed λ's" in section


def test_bad_paper_table_is_a_usage_error(tmp_path, capsys):
    from glstat.cli.commands import main

    bad = tmp_path / "bad.csv"
    bad.write_text("hurst,mean,sd\n0,1724,200\n")
    rc = main(["study", "--paper-table", str(bad), "--out", str(tmp_path / "o")])
    assert rc == 2
    assert "unknown column(s) mean, sd" in capsys.readouterr().err
    empty_h = tmp_path / "nan.csv"
    empty_h.write_text("hurst,mean_mpa\n0,1724\n,1369\n")
    assert main(["study", "--paper-table", str(empty_h), "--out", str(tmp_path / "o")]) == 2
    assert "a row without hurst or mean_mpa" in capsys.readouterr().err
    good = tmp_path / "good.csv"
    good.write_text("hurst,mean_mpa\n0,1724\n")
    rc = main(["study", "--paper-table", str(good), "--topographies", str(tmp_path),
               "--out", str(tmp_path / "o")])
    assert rc == 2 and "does not apply to measured files" in capsys.readouterr().err


def test_paper_table_rows_for_an_h_not_run_are_said_or_refused(tmp_path, capsys):
    from glstat.cli.commands import main
    from glstat.study.paper_table import Table1Row
    from glstat.study.paper_table import rows_not_run as _paper_rows_not_run

    rows = [Table1Row(hurst=0.0, mean_mpa=1724.0), Table1Row(hurst=0.5, mean_mpa=1369.0)]
    assert _paper_rows_not_run(rows, (0.0, 0.5, 1.0)) is None
    note = _paper_rows_not_run(rows, (0.5,))
    assert note.startswith("--paper-table rows for H = 0 are not in this run (H = 0.5)")
    assert "paper's own contact counts" in note
    odd = tmp_path / "odd.csv"
    odd.write_text("hurst,mean_mpa\n0.3,1500\n")
    rc = main(["study", "--paper-table", str(odd), "--out", str(tmp_path / "o")])
    assert rc == 2
    assert ("--paper-table has rows for H = 0.3, which this run does not simulate (H = 0, 0.5, 1) "
            "and the paper's scene does not have; add --hurst 0.3" in capsys.readouterr().err)


def test_run_study_refuses_paper_rows_for_an_unknown_h_before_solving(tmp_path):
    from glstat.study import AnalysisSettings, CampaignSettings, run_study

    with pytest.raises(ValueError, match=r"paper_table has rows for H = 0\.3, .*add 0\.3 to "
                                         r"CampaignSettings\.hurst"):
        run_study(CampaignSettings(hurst=(0.5,)), AnalysisSettings(), tmp_path / "o",
                  paper_table=[{"hurst": 0.3, "mean_mpa": 1500.0}])
    assert not (tmp_path / "o").exists()  # nothing was solved or written
