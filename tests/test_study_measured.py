"""The study on measured topographies (--topographies) and on surfaces like one (--like)."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys

import numpy as np
import pytest

import contact
from glstat.study import AnalysisSettings, CampaignError, run_study
from glstat.study.campaign import campaign_surface
from glstat.study.campaign_settings import CampaignSettings
from glstat.study.measured import (
    find_topographies,
    like_settings,
    measured_settings,
    read_measured,
)
from glstat.study.surface_task import raw_surface
from glstat.study.topography import read_topography

# The tests that read unit-free heights (small integers, or micrometres as metres) say so: the
# units check warns about them, which those tests do not examine.
UNIT_FREE = pytest.mark.filterwarnings("ignore:the RMS of the heights:contact.errors.ContactWarning")

FAST = AnalysisSettings(n_resamples=20, grid_resamples=10)
TILT = 0.05  # a form (plane) of 50 µm per mm, which the study must remove


def _write_measured(folder, n=10, grid=128, side=0.25e-3, rq=0.5e-6):
    """``n`` self-affine topographies with a tilted plane, as .npz files; returns the levelled
    surfaces."""
    folder.mkdir(parents=True, exist_ok=True)
    truth = []
    for i in range(n):
        s = contact.self_affine((grid, grid), side, hurst=0.7, rq=rq, rng=i)
        tilt = TILT * (np.arange(grid)[:, None] * s.dx + 0.5 * np.arange(grid)[None, :] * s.dy)
        contact.write(contact.Surface(s.heights + tilt, s.dx), folder / f"scan_{i:02d}.npz")
        truth.append(s)
    return truth


@pytest.fixture(scope="module")
def measured_dir(tmp_path_factory):
    folder = tmp_path_factory.mktemp("measured")
    _write_measured(folder)
    return folder


@pytest.fixture(scope="module")
def measured_study(measured_dir, tmp_path_factory):
    out = tmp_path_factory.mktemp("measured_study")
    settings = measured_settings(measured_dir)
    return settings, run_study(settings, FAST, out, workers=1, progress=False, compare_bem=0)


def test_find_topographies_takes_files_folders_and_patterns(measured_dir, tmp_path):
    every = find_topographies(measured_dir)
    assert [p.name for p in every] == [f"scan_{i:02d}.npz" for i in range(10)]
    assert find_topographies(str(measured_dir / "scan_0[12].npz")) == every[1:3]
    assert find_topographies([every[3], str(every[3])]) == [every[3]]  # once
    with pytest.raises(FileNotFoundError, match="no such topography file or folder"):
        find_topographies(tmp_path / "missing.x3p")
    with pytest.raises(FileNotFoundError, match="matches no file"):
        find_topographies(str(tmp_path / "*.x3p"))
    (tmp_path / "notes.md").write_text("not a topography")
    with pytest.raises(FileNotFoundError, match="no topography file in the folder"):
        find_topographies(tmp_path)


def test_form_removal_takes_the_plane_out(measured_dir):
    (surface,) = read_measured([measured_dir / "scan_00.npz"], "plane")
    truth = contact.self_affine((128, 128), 0.25e-3, hurst=0.7, rq=0.5e-6, rng=0).detrend("plane")
    np.testing.assert_allclose(surface.heights, truth.heights, atol=1e-15)
    (raw,) = read_measured([measured_dir / "scan_00.npz"], "none")
    assert np.ptp(raw.heights) > 3 * np.ptp(surface.heights)  # the tilt is still there


def test_files_of_different_grid_spacing_or_shape_are_refused(measured_dir, tmp_path):
    s = contact.self_affine((64, 64), 0.25e-3, hurst=0.7, rq=0.5e-6, rng=1)
    contact.write(s, tmp_path / "small.npz")
    with pytest.raises(ValueError, match=r"small\.npz has 64 × 64 points .* must share grid and spacing"):
        read_measured([measured_dir / "scan_00.npz", tmp_path / "small.npz"])
    wide = contact.Surface(np.zeros((64, 32)), 1e-6, 2e-6)
    contact.write(wide, tmp_path / "wide.npz")
    (s,) = read_measured([tmp_path / "wide.npz"])  # a rectangular grid on its own is fine
    assert s.shape == (64, 32) and (s.dx, s.dy) == (1e-6, 2e-6)
    with pytest.raises(ValueError, match=r"wide\.npz has 64 × 32 points at 1 × 2 µm spacing "
                                         r"\(x × y\) but .*scan_00\.npz has 128 × 128"):
        read_measured([measured_dir / "scan_00.npz", tmp_path / "wide.npz"])


def test_a_changed_file_is_refused_and_never_mixed(measured_dir, measured_study, tmp_path):
    f = tmp_path / "scan.npz"
    f.write_bytes((measured_dir / "scan_00.npz").read_bytes())
    one = measured_settings(f)
    contact.write(contact.self_affine((128, 128), 0.25e-3, hurst=0.7, rq=0.5e-6, rng=99), f)
    with pytest.raises(ValueError, match=r"changed since the campaign .* started"):
        read_topography(f, "plane", one.digests[0])
    # the digests are part of the identity: a rerun in the same directory is refused
    assert measured_settings(f).identity() != one.identity()
    with pytest.raises(CampaignError, match="different settings"):
        run_study(measured_settings(f), FAST, measured_study[1].out, workers=1,
                  progress=False, compare_bem=0)


def test_simulated_identity_is_unchanged_by_the_measured_fields():
    keys = set(CampaignSettings().identity())
    assert not keys & {"topographies", "digests", "form", "like"}


def test_measured_study_reads_every_file_as_one_surface(measured_study):
    settings, res = measured_study
    assert settings.measured and settings.n_surfaces == 10 and settings.grid == 128
    assert settings.length == pytest.approx(0.25e-3)
    table = res.summary()
    row = table[(table["model"] == "asperity") & (table["sample"] == "asperity")].iloc[0]
    assert row["n_surfaces"] == 10
    # the default S-filter: ISO 25178-3's smallest preferred λs of at least 3 spacings
    dx = 0.25e-3 / 128
    assert settings.s_filter == contact.default_s_filter(dx) == 8e-6
    # the contact of each file equals the asperity model on that file with its plane removed,
    # at the study's scale (the S-filter applied after the form removal)
    for i in (0, 7):
        direct = contact.solve(campaign_surface(settings, 0, 0, i), 20e6, settings.E, settings.nu,
                               settings.cone_factor, warn=False)
        stored = np.load(res.out / f"H{settings.hurst[0]:g}_P20MPa" / f"surface_{i:04d}.npz")
        assert float(stored["mean_pressure"]) == pytest.approx(direct.mean_pressure, rel=1e-12)
        truth = contact.self_affine((128, 128), 0.25e-3, hurst=0.7, rq=0.5e-6, rng=i)
        scaled = truth.detrend("plane").s_filter(settings.s_filter, periodic=False)
        assert float(stored["iso_Sq"]) == pytest.approx(float(scaled.roughness()["Sq"]), rel=1e-9)
        # the filter removed the shortest wavelengths: a smaller Sq than the raw surface's
        assert float(stored["iso_Sq"]) < float(truth.detrend("plane").roughness()["Sq"])
    text = res.report_md.read_text()
    assert "## Measured topographies" in text and "scan_09.npz" in text
    # full-spectrum surfaces: the maximum is mostly where asperity patches overlap and add up
    files = sorted(res.out.glob("H*_P20MPa/surface_*.npz"))
    overlaps = [float(z["max_pressure"]) > 1.01 * float(np.max(z["asperity_peak"]))
                for z in map(np.load, files)]
    assert res.analysis[(0, 0)]["summary"]["overlap_fraction"] == pytest.approx(np.mean(overlaps))
    assert np.mean(overlaps) > 0.1 and "Overlapping asperities: on" in text
    assert "| measured |" in text and "paper: damage" not in text
    assert "Consistency with the paper" not in text
    manifest = json.loads((res.out / "manifest.json").read_text())["campaign"]
    assert len(manifest["digests"]) == 10 and manifest["form"] == "plane"


def test_like_study_simulates_the_measured_statistics(measured_dir, tmp_path):
    settings, params = like_settings(measured_dir / "scan_03.npz", 10)
    assert params.fit.r2 > 0.9  # a self-affine template fits its power law
    measured = read_topography(measured_dir / "scan_03.npz", "plane")
    direct = contact.weierstrass_parameters(measured)
    assert (settings.hurst[0], settings.rq, settings.n_terms[0]) == (direct.hurst, direct.rq,
                                                                    direct.n_terms[0])
    assert settings.grid == 128 and not settings.measured and settings.like
    res = run_study(settings, FAST, tmp_path / "like", workers=1, progress=False, compare_bem=0)
    text = res.report_md.read_text()
    assert "## Measured template and simulated surfaces" in text
    assert "scan_03.npz" in text and (res.out / "report_files" / "psd_like.png").is_file()
    # the simulated surfaces carry the template's Rq (the table's Sq row, in µm)
    sq_row = next(line for line in text.splitlines() if line.startswith("| Sq |"))
    measured_sq, simulated_sq = (float(v) for v in sq_row.split("|")[2:4])
    assert simulated_sq == pytest.approx(measured_sq, rel=0.05)


def test_surfacetopography_formats_reach_the_study(tmp_path):
    """An ISO 25178-71 SDF file, which only SurfaceTopography reads (installed with [all])."""
    if importlib.util.find_spec("SurfaceTopography") is None:
        pytest.fail("SurfaceTopography is part of the 'all' extra; install glstat[all]")
    rows = np.arange(1.0, 17.0 * 17.0 + 1).reshape(17, 17)
    header = ["aISO-1.0", "ManufacID = glstat", "CreateDate = 010120251200",
              "ModDate = 010120251200", "NumPoints = 17", "NumProfiles = 17", "Xscale = 2.0E-06",
              "Yscale = 2.0E-06", "Zscale = 1.0E-09", "Zresolution = -1", "Compression = 0",
              "DataType = 7", "CheckType = 0", "NumDataSet = 1", "NanPresent = 0", "*"]
    body = [" ".join(f"{v:g}" for v in r) for r in rows]
    (tmp_path / "scan.sdf").write_text("\n".join([*header, *body, "*", ""]))
    assert find_topographies(tmp_path) == [(tmp_path / "scan.sdf").resolve()]
    (s,) = read_measured([tmp_path / "scan.sdf"], "none")
    assert s.shape == (17, 17) and s.dx == pytest.approx(2e-6)
    np.testing.assert_allclose(s.heights, rows.T * 1e-9, rtol=1e-12)  # rows are profiles (y)


@pytest.mark.parametrize("extra, message", [
    (["--grid", "64"], "--grid: options of simulated surfaces"),
    (["--rq", "2"], "--rq: options of simulated surfaces"),
])
def test_cli_refuses_simulation_options_with_topographies(measured_dir, tmp_path, extra, message):
    r = subprocess.run([sys.executable, "-m", "glstat.cli", "study", "--topographies",
                        str(measured_dir), "--out", str(tmp_path / "o"), *extra],
                       capture_output=True, text=True)
    assert r.returncode == 2 and message in r.stderr and "Traceback" not in r.stderr


def test_cli_names_a_missing_topography(tmp_path):
    r = subprocess.run([sys.executable, "-m", "glstat.cli", "study", "--like",
                        str(tmp_path / "nowhere.x3p"), "--out", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "no such topography file or folder" in r.stderr
    assert "nowhere.x3p" in r.stderr


# -- one scan as many areas (--tile) ---------------------------------------------------------


@UNIT_FREE
def test_tiles_cut_a_grid_into_equal_areas_and_drop_the_rest():
    from glstat.study.topography import cut_tile, tile_bounds

    z = np.arange(70 * 50, dtype=float).reshape(70, 50)
    s = contact.Surface(z, 1e-6, 2e-6, mask=z == 7.0)
    seen = np.zeros(z.shape, dtype=int)
    for t in range(4 * 3):
        sx, sy = tile_bounds(s.shape, (4, 3), t)
        seen[sx, sy] += 1
        piece = cut_tile(s, (4, 3), t)
        assert piece.shape == (17, 16) and (piece.dx, piece.dy) == (1e-6, 2e-6)
        np.testing.assert_array_equal(piece.heights, z[sx, sy])
    # every point of the 68 × 48 points the tiles cover is in exactly one tile, the rest in none
    assert (seen[:68, :48] == 1).all() and seen[68:].sum() == 0 and seen[:, 48:].sum() == 0
    assert cut_tile(s, (4, 3), 0).mask[0, 7] and not cut_tile(s, (4, 3), 1).mask.any()
    a, b = divmod(5, 3)  # tile 5 is column 1 along x, row 2 along y
    assert tile_bounds(s.shape, (4, 3), 5) == (slice(17 * a, 17 * a + 17), slice(16 * b, 16 * b + 16))
    with pytest.raises(ValueError, match="tile 12 does not exist"):
        tile_bounds(s.shape, (4, 3), 12)


def test_one_scan_is_studied_as_many_areas(measured_dir, tmp_path):
    scan = measured_dir / "scan_00.npz"
    settings = measured_settings(scan, tiles=(4, 2))
    assert settings.n_surfaces == 8 and settings.shape == (32, 64)
    assert settings.size == pytest.approx((0.25e-3 / 4, 0.25e-3 / 2))
    assert settings.surface_name(5) == "scan_00.npz, area (3, 2) of 4 × 2"
    assert settings.identity()["tiles"] == [4, 2]
    assert "tiles" not in measured_settings(scan).identity()  # earlier campaigns keep theirs
    raw = contact.read(scan)
    for i in (0, 5, 7):
        a, b = divmod(i, 2)
        piece = contact.Surface(raw.heights[32 * a:32 * (a + 1), 64 * b:64 * (b + 1)], raw.dx)
        np.testing.assert_allclose(raw_surface(settings, 0, 0, i).heights,
                                   piece.detrend("plane").heights, atol=1e-15)
    res = run_study(settings, FAST, tmp_path / "tiles", workers=1, progress=False, compare_bem=0)
    assert res.summary()["n_surfaces"].eq(8).all()
    text = res.report_md.read_text()
    assert "8 areas of 1 measured scan (each cut into 4 × 2 areas" in text
    assert "| scan_00.npz, area (4, 2) of 4 × 2 |" in text
    assert "cannot tell how it varies between parts" in text and "takes about 25 surfaces" in text
    with pytest.raises(ValueError, match=r"16 × 8 points \(its 128 × 128 points cut into 8 × 16 "
                                         r"areas\) is too small .*at most 8 × 8 with --tile"):
        measured_settings(scan, tiles=(8, 16))
    with pytest.raises(ValueError, match="tiles cut measured files"):
        CampaignSettings(tiles=(2, 2))
    # an area size instead of a count: as many areas of at least that size as fit
    by_size = measured_settings(scan, tile_size=(0.06e-3, 0.12e-3))
    assert by_size.tiles == (4, 2) and by_size.identity() == settings.identity()
    with pytest.raises(ValueError, match="does not fit in a scan"):
        measured_settings(scan, tile_size=(1e-3, 1e-3))


def test_one_scan_without_tiles_says_to_cut_it_and_never_names_refused_options(measured_dir, tmp_path):
    settings = measured_settings(measured_dir / "scan_01.npz")
    res = run_study(settings, FAST, tmp_path / "one", workers=1, progress=False, compare_bem=0)
    notes = [r.note for r in res.analysis[(0, 0)].values() if hasattr(r, "note") and r.note]
    assert notes and all("--tile NX NY" in n and "--surfaces" not in n for n in notes)
    assert any("one surface: the interval resamples whole surfaces" in n for n in notes)
    text = res.report_md.read_text()
    assert "--surfaces" not in text and "--rq" not in text and "--target-pressure" not in text
    two = run_study(measured_settings(measured_dir / "scan_01.npz", tiles=(2, 1)), FAST,
                    tmp_path / "two", workers=1, progress=False, compare_bem=0)
    spot = two.analysis[(0, 0)]["spot"]
    assert spot.ok and "needs at least four surfaces" in spot.validation.error
    assert "a larger --tile" in spot.validation.error


# the scan holds micrometres read as metres (the file states no unit): the roughness check warns
@pytest.mark.filterwarnings("ignore:rq = .* is implausible:contact.errors.ContactWarning")
@UNIT_FREE
def test_cli_reads_files_without_spacing_with_spacing_and_unit(tmp_path, capsys):
    from glstat.cli.commands import main

    s = contact.self_affine((64, 48), 0.2e-3, hurst=0.7, rq=0.5e-6, rng=4)
    np.save(tmp_path / "scan.npy", s.heights * 1e6)  # heights in µm, no spacing stored
    assert main(["study", "--topographies", str(tmp_path / "scan.npy"), "--out",
                 str(tmp_path / "a")]) == 2
    err = capsys.readouterr().err
    assert "stores no grid spacing; give its grid spacing with --spacing DX [DY] (µm)" in err
    xyz = tmp_path / "points.txt"  # x y z columns of a regular grid, no unit stated
    xi, yi = np.meshgrid(np.arange(32), np.arange(32), indexing="ij")
    np.savetxt(xyz, np.column_stack([xi.ravel(), yi.ravel(), s.heights[:32, :32].ravel() * 1e6]))
    assert main(["study", "--topographies", str(xyz), "--out", str(tmp_path / "c")]) == 2
    assert "states no length unit; give its length unit with --unit" in capsys.readouterr().err
    with_unit = measured_settings(xyz, unit="µm")
    assert with_unit.spacing == pytest.approx((1e-6, 1e-6)) and with_unit.file_unit == "µm"
    scene = measured_settings(tmp_path / "scan.npy", tiles=(2, 1), spacing=(s.dx, 2 * s.dy))
    assert scene.spacing == pytest.approx((s.dx, 2 * s.dy)) and scene.shape == (32, 48)
    assert scene.identity()["file_spacing"] == pytest.approx([s.dx, 2 * s.dy])
    for argv, message in ((["--tile", "2"], "options of measured files"),
                          (["--topographies", str(tmp_path / "scan.npy"), "--tile", "1", "2", "3"],
                           "--tile takes NX NY"),
                          (["--topographies", str(tmp_path / "scan.npy"), "--spacing", "1", "2",
                            "3"], "--spacing takes DX or DX DY")):
        assert main(["study", *argv, "--out", str(tmp_path / "b")]) == 2
        assert message in capsys.readouterr().err


def test_like_puts_a_scan_with_unequal_spacings_on_the_coarser_one(tmp_path):
    from glstat.study.measured import like_template

    s = contact.self_affine((128, 128), 0.128e-3, hurst=0.7, rq=0.5e-6, rng=6)
    scan = contact.Surface(s.heights[:, ::2], s.dx, 2 * s.dy)  # pixels of 1 × 2 µm
    contact.write(scan, tmp_path / "aniso.npz")
    template, note = like_template(tmp_path / "aniso.npz")
    assert (template.dx, template.dy) == pytest.approx((2e-6, 2e-6)) and template.shape == (64, 64)
    assert "resampled to one spacing, the coarser 2 µm" in note
    settings, params = like_settings(tmp_path / "aniso.npz", 4)
    assert settings.spacing == pytest.approx((2e-6, 2e-6)) and settings.shape == (64, 64)
    assert 0.4 < params.hurst <= 1.0
    # the spectrum of the resampled template is the scan's at the wavelengths both grids hold
    rq = float(np.sqrt(np.mean(template.heights ** 2)))
    assert rq == pytest.approx(float(np.std(scan.detrend("plane").heights)), rel=0.05)


def test_a_file_without_summits_is_refused_before_the_campaign_by_name(measured_dir, tmp_path):
    flat = tmp_path / "terraced.npz"
    steps = np.repeat(np.arange(8, dtype=float), 16)[:, None] * np.ones((1, 128)) * 1e-7
    contact.write(contact.Surface(steps, 0.25e-3 / 128), flat)
    with pytest.raises(ValueError, match=r"terraced\.npz: no summit .* leave the file out"):
        measured_settings([measured_dir / "scan_00.npz", flat], form="none")


def test_like_runs_on_a_scan_with_missing_points(tmp_path):
    s = contact.self_affine((128, 128), 0.128e-3, hurst=0.7, rq=0.5e-6, rng=8)
    mask = np.zeros(s.shape, dtype=bool)
    mask.flat[np.random.default_rng(1).choice(mask.size, 116, replace=False)] = True
    contact.write(contact.Surface(s.heights, s.dx, mask=mask), tmp_path / "holes.npz")
    settings, params = like_settings(tmp_path / "holes.npz", 4)
    full, _ = like_settings(_write_copy(s, tmp_path / "full.npz"), 4)
    assert params.fit.filled_fraction == pytest.approx(116 / 128**2)
    assert params.hurst == pytest.approx(full.hurst[0], abs=0.01)
    assert settings.rq == pytest.approx(full.rq, rel=0.01)
    # unequal spacings and missing points together: filled, then resampled
    aniso = contact.Surface(s.heights[:, ::2], s.dx, 2 * s.dy, mask=mask[:, ::2])
    contact.write(aniso, tmp_path / "aniso_holes.npz")
    settings, _ = like_settings(tmp_path / "aniso_holes.npz", 4)
    assert settings.spacing == pytest.approx((2e-6, 2e-6))


def _write_copy(surface, path):
    contact.write(surface, path)
    return path


def test_report_markdown_quotes_names_from_files_literally():
    from glstat.study.report_document import Report

    rep = Report("study")
    name = "scan\n# injected <script>alert(1)</script> a|b.x3p"
    rep.paragraph(f"The file {name} was read.")
    rep.table(["file"], [[name]])
    md, _ = rep.to_markdown("figs")
    assert "\n# injected" not in md and "<script>" not in md
    assert "&lt;script&gt;" in md and "a\\|b.x3p |" in md
    assert "<script>" not in rep.to_html()
    # a file name holding Markdown link or image syntax stays text
    link = "[x](javascript:alert(1)) ![t](https://example.org/t.png).x3p"
    rep.paragraph(f"The file {link} was read.")
    md, _ = rep.to_markdown("figs")
    assert "](javascript" not in md and "](https://example" not in md
    assert "[x]\\(javascript:alert(1))" in md


@UNIT_FREE
def test_a_scan_in_another_length_unit_is_refused_by_name(measured_dir, tmp_path):
    for i in range(3):
        (tmp_path / f"scan_{i:02d}.npz").write_bytes((measured_dir / f"scan_{i:02d}.npz").read_bytes())
    s = contact.read(measured_dir / "scan_03.npz")
    contact.write(contact.Surface(s.heights * 1e6, s.dx), tmp_path / "in_um.npz")  # µm as m
    with pytest.raises(ValueError, match=r"in_um\.npz has an RMS height of .* another length unit"):
        measured_settings(tmp_path)


def test_implausible_si_values_warn_and_a_huge_grid_is_refused():
    with pytest.warns(contact.ContactWarning, match=r"20 Pa is implausibly small .* 20e6"):
        CampaignSettings(pressures=(20.0,))
    with pytest.warns(contact.ContactWarning, match=r"rq = 1.6 m .* 1.6e-6"):
        CampaignSettings(rq=1.6)
    with pytest.warns(contact.ContactWarning):
        odd = CampaignSettings(E=210.0, rq=1.6, length=1.0, pressures=(20.0,))
    assert len(odd.implausible_values()) == 4
    with pytest.raises(ValueError, match="GiB per height or pressure map"):
        CampaignSettings(grid=10**6)
    with pytest.warns(contact.ContactWarning, match=r"E = 210 Pa .* 210e9"):
        contact.effective_modulus(210.0, 0.3)
    s = contact.weierstrass((64, 64), 1e-3, 0.5, rq=1.6e-6, rng=1, n_terms=5)
    with pytest.warns(contact.ContactWarning, match=r"nominal_pressure = 20 Pa"):
        contact.solve(s, 20.0, 210e9, 0.3, jump="blend")


def test_report_removes_figures_half_written_by_a_killed_run(tmp_path):
    from glstat.study.report_document import Report

    folder = tmp_path / "report_files"
    folder.mkdir()
    stale = folder / ".surfaces.png.k3j2.tmp"  # the temporary name of an atomic write
    stale.write_bytes(b"\x89PNG half")
    Report("study").write(tmp_path)
    assert not stale.exists() and (tmp_path / "report.md").is_file()
