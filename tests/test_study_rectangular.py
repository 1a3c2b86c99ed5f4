"""The study on rectangular measured topographies (nx != ny, dx != dy) and the polynomial form."""

from __future__ import annotations

import subprocess
import sys
import warnings

import numpy as np
import pytest

import contact
from glstat.study import AnalysisSettings, run_study
from glstat.study.campaign import campaign_surface
from glstat.study.campaign_settings import CampaignSettings
from glstat.study.measured import like_settings, measured_settings, read_measured
from glstat.study.report_surfaces import scene_sentence, surface_rows
from glstat.study.surface_task import raw_surface
from glstat.study.topography import FORMS, remove_form

FAST = AnalysisSettings(n_resamples=20, grid_resamples=10)
NX, NY, DX, DY = 96, 56, 2e-6, 3e-6  # a 0.192 × 0.168 mm² scan, sampled finer along x


def _paraboloid(nx=NX, ny=NY, dx=DX, dy=DY):
    """A tilted paraboloid in metres on an (nx, ny) grid, and the grid coordinates (m)."""
    x = np.arange(nx)[:, None] * dx
    y = np.arange(ny)[None, :] * dy
    return 2e-6 + 0.03 * x - 0.02 * y + 400.0 * x**2 - 250.0 * x * y + 300.0 * y**2, x, y


def _write_scans(folder, n=10, shape=(NX, NY), dx=DX, dy=DY):
    """``n`` self-affine scans of the given grid and spacing with a paraboloid form, as .npz."""
    folder.mkdir(parents=True, exist_ok=True)
    form, _, _ = _paraboloid(*shape, dx, dy)
    for i in range(n):
        s = contact.self_affine(shape, (shape[0] * dx, shape[1] * dy), hurst=0.7, rq=0.3e-6, rng=i)
        contact.write(contact.Surface(s.heights + form, dx, dy), folder / f"scan_{i:02d}.npz")
    return folder


@pytest.fixture(scope="module")
def rect_dir(tmp_path_factory):
    return _write_scans(tmp_path_factory.mktemp("rect"))


@pytest.fixture(scope="module")
def rect_study(rect_dir, tmp_path_factory):
    settings = measured_settings(rect_dir, form="poly2")
    out = tmp_path_factory.mktemp("rect_study")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = run_study(settings, FAST, out, workers=1, progress=False, compare_bem=2)
    return settings, res


def test_poly2_removes_a_paraboloid_exactly():
    h, x, y = _paraboloid()
    mask = np.zeros(h.shape, dtype=bool)
    mask[10:20, 5:9] = True  # the fit uses the measured points only
    surface = contact.Surface(np.where(mask, 1.0, h), DX, DY, mask=mask)
    flat = remove_form(surface, "poly2")
    assert np.abs(flat.heights[~mask]).max() < 1e-12 * np.ptp(h)
    assert (flat.dx, flat.dy) == (DX, DY) and np.array_equal(flat.mask, mask)
    # a cubic needs poly3; the plane leaves the curvature
    cubic = h + 5e6 * x**3 - 2e6 * x * y**2
    assert np.abs(remove_form(contact.Surface(cubic, DX, DY), "poly3").heights).max() < 1e-12 * np.ptp(h)
    assert np.abs(remove_form(contact.Surface(cubic, DX, DY), "poly2").heights).max() > 1e-3 * np.ptp(h)
    assert np.abs(remove_form(surface, "plane").heights[~mask]).max() > 0.01 * np.ptp(h)
    with pytest.raises(ValueError, match="form must be one of"):
        remove_form(surface, "poly9")


def test_rectangular_scans_give_their_shape_and_spacing(rect_dir):
    settings = measured_settings(rect_dir, form="poly2")
    assert settings.shape == (NX, NY) and (settings.grid, settings.grid_y) == (NX, NY)
    assert settings.size == pytest.approx((NX * DX, NY * DY))
    assert settings.spacing == pytest.approx((DX, DY)) and not settings.square
    surface = raw_surface(settings, 0, 0, 3)
    # the study solves it at its scale: the default S-filter of the coarser spacing (3 µm)
    assert settings.s_filter == contact.default_s_filter(DX, DY) == 10e-6
    solved = campaign_surface(settings, 0, 0, 3)
    np.testing.assert_allclose(solved.heights,
                               surface.s_filter(settings.s_filter, periodic=False).heights, atol=0)
    assert surface.shape == (NX, NY) and (surface.dx, surface.dy) == pytest.approx((DX, DY))
    # the paraboloid is gone: what is left is the self-affine scan less its own quadratic
    truth = contact.self_affine((NX, NY), (NX * DX, NY * DY), hurst=0.7, rq=0.3e-6, rng=3)
    np.testing.assert_allclose(surface.heights, remove_form(truth, "poly2").heights,
                               atol=1e-9 * 0.3e-6 * 1e3)
    assert "96 × 56 points (spacing 2 µm along x, 3 µm along y) on 0.192 mm × 0.168 mm" in \
        scene_sentence(settings)
    rows = dict((r[0], r[1]) for r in surface_rows(settings))
    assert rows["grid"] == "96 × 56" and rows["spacing (µm)"] == "2 × 3"
    assert rows["form removed"].startswith("poly2 (least-squares polynomial of degree 2")


def test_rectangular_study_runs_end_to_end_with_both_models(rect_study):
    settings, res = rect_study
    folder = res.out / f"H{settings.hurst[0]:g}_P20MPa"
    for i in (0, 6):
        surface = campaign_surface(settings, 0, 0, i)
        direct = contact.solve(surface, 20e6, settings.E, settings.nu, settings.cone_factor)
        stored = np.load(folder / f"surface_{i:04d}.npz")
        assert float(stored["mean_pressure"]) == pytest.approx(direct.mean_pressure, rel=1e-12)
        assert int(stored["n_points"]) == NX * NY
        # the nominal area is the measured one: the target force is the load times nx ny dx dy
        assert direct.target_force == pytest.approx(20e6 * NX * NY * DX * DY, rel=1e-12)
    # the elastic BEM of the first surfaces, on the same rectangular grid and spacing
    bem = np.load(folder / "bem_0000.npz")
    direct = contact.solve_bem(campaign_surface(settings, 0, 0, 0), 20e6, settings.E, settings.nu)
    assert float(bem["bem_max_pressure"]) == pytest.approx(direct.max_pressure, rel=1e-6)
    assert bem["bem_pressure"].shape == (NX, NY)
    text = res.report_md.read_text()
    assert "96 × 56 points (spacing 2 µm along x, 3 µm along y)" in text
    assert "least-squares polynomial of degree 2" in text and "measured area (mm²)" in text
    assert "| measured |" in text and "scan_09.npz" in text


def test_files_of_another_shape_or_spacing_are_named(rect_dir, tmp_path):
    first = rect_dir / "scan_00.npz"
    turned = contact.Surface(np.zeros((NY, NX)), DY, DX)
    contact.write(turned, tmp_path / "turned.npz")
    with pytest.raises(ValueError, match=r"turned\.npz has 56 × 96 points at 3 × 2 µm spacing "
                                         r"\(x × y\) but .*scan_00\.npz has 96 × 56 points at 2 × 3 "
                                         r"µm spacing .* must share grid and spacing"):
        read_measured([first, tmp_path / "turned.npz"])
    stretched = contact.Surface(np.zeros((NX, NY)), DX, 1.01 * DY)
    contact.write(stretched, tmp_path / "stretched.npz")
    with pytest.raises(ValueError, match=r"stretched\.npz has 96 × 56 points at 2 × 3\.03 µm"):
        read_measured([first, tmp_path / "stretched.npz"])
    contact.write(contact.Surface(np.zeros((NX, 12)), DX), tmp_path / "strip.npz")
    with pytest.raises(ValueError, match=r"strip\.npz: 96 × 12 points is too small a grid"):
        read_measured([tmp_path / "strip.npz"])


def test_the_identity_differs_by_form_and_shape(rect_dir, tmp_path):
    plane = measured_settings(rect_dir, form="plane")
    poly2 = measured_settings(rect_dir, form="poly2")
    assert plane.identity() != poly2.identity() and poly2.identity()["form"] == "poly2"
    assert plane.identity()["grid_y"] == NY and plane.identity()["length_y"] == pytest.approx(NY * DY)
    square = CampaignSettings(grid=64, length=0.2e-3)
    assert "grid_y" not in square.identity() and "length_y" not in square.identity()
    assert CampaignSettings(grid=64, length=0.2e-3, grid_y=64, length_y=0.2e-3).identity() == \
        square.identity()
    assert CampaignSettings(grid=64, length=0.2e-3, grid_y=48, length_y=0.15e-3).identity() != \
        square.identity()
    for bad in ({"grid_y": 8}, {"grid_y": 2.5}, {"length_y": -1.0}, {"length_y": float("nan")}):
        with pytest.raises(ValueError, match=r"grid_y|length_y"):
            CampaignSettings(grid=64, length=0.2e-3, **bad)
    # a square scan with one spacing keeps the square identity (no grid_y, no length_y)
    contact.write(contact.self_affine((64, 64), 0.2e-3, hurst=0.7, rq=0.3e-6, rng=1),
                  tmp_path / "square.npz")
    one = measured_settings(tmp_path / "square.npz")
    assert one.square and "grid_y" not in one.identity()


def test_like_simulates_the_rectangular_template(rect_dir, tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", contact.ContactWarning)
        template = _write_scans(tmp_path / "t", n=1, shape=(96, 64), dx=2e-6, dy=2e-6)
        settings, params = like_settings(template / "scan_00.npz", 10, form="poly2")
    assert settings.shape == (96, 64) == params.shape and settings.like
    assert settings.size == pytest.approx(params.length)
    simulated = campaign_surface(settings, 0, 0, 0)
    assert simulated.shape == (96, 64) and (simulated.dx, simulated.dy) == pytest.approx((2e-6, 2e-6))
    assert np.sqrt(np.mean(simulated.heights**2)) == pytest.approx(settings.rq, rel=1e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = run_study(settings, FAST, tmp_path / "like", workers=1, progress=False, compare_bem=0)
    text = res.report_md.read_text()
    assert "## Measured template and simulated surfaces" in text
    assert "96 × 64 points (spacing" not in text and "96 × 64 points on 0.192 mm × 0.128 mm" in text
    # unequal spacings are put on the coarser one (3 µm) on both axes
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", contact.ContactWarning)
        aniso, params = like_settings(rect_dir / "scan_00.npz", 10)
    assert aniso.spacing == pytest.approx((3e-6, 3e-6)) and aniso.shape == (64, 56)
    assert params.n_terms[0] == params.n_terms[1]


def test_cli_offers_the_polynomial_forms():
    r = subprocess.run([sys.executable, "-m", "glstat.cli", "study", "--help"],
                       capture_output=True, text=True)
    assert r.returncode == 0
    assert "{" + ",".join(FORMS) + "}" in r.stdout.replace("\n", "").replace(" ", "")
