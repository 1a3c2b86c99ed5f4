"""Conversion between contact.Surface and SurfaceTopography's Topography.

References: the heights and spacing put in (round trips), and unit factors by definition
(1 µm = 1e-6 m, 1 Å = 1e-10 m).
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import contact

# Many inputs here are unit-free (heights of order 1 on a micrometre or millimetre grid, files of
# small integers); contact's check of the units warns about them, which these tests do not examine.
pytestmark = pytest.mark.filterwarnings("ignore:the RMS of the heights:contact.errors.ContactWarning")


@pytest.fixture
def st():
    """The SurfaceTopography package (optional)."""
    return pytest.importorskip("SurfaceTopography", reason="SurfaceTopography is optional")


def test_round_trip_in_metres_and_in_micrometres(st):
    rng = np.random.default_rng(0)
    h = rng.normal(size=(20, 30)) * 1e-6
    s = contact.Surface(h, 2e-6, 3e-6)
    t = s.to_topography()
    assert t.unit == "m" and not t.is_periodic
    assert t.nb_grid_pts == (20, 30)
    np.testing.assert_allclose(t.physical_sizes, (40e-6, 90e-6), rtol=1e-15)
    back = contact.Surface.from_topography(t)
    np.testing.assert_array_equal(back.heights, h)
    assert (back.dx, back.dy) == pytest.approx((2e-6, 3e-6), rel=1e-15)
    assert back.mask is None
    tu = s.to_topography(unit="µm")
    np.testing.assert_allclose(tu.heights(), h * 1e6, rtol=1e-15)
    np.testing.assert_allclose(tu.physical_sizes, (40.0, 90.0), rtol=1e-15)
    back = contact.Surface.from_topography(tu)
    np.testing.assert_allclose(back.heights, h, rtol=1e-15)
    assert back.dx == pytest.approx(2e-6, rel=1e-15)
    assert back.dy == pytest.approx(3e-6, rel=1e-15)


@pytest.mark.parametrize("unit, metres", [("mm", 1e-3), ("um", 1e-6), ("nm", 1e-9),
                                           ("pm", 1e-12), ("Å", 1e-10)])
def test_units_are_converted_to_metres(unit, metres, st):
    h = np.arange(12.0).reshape(3, 4)
    t = st.Topography(h, (3.0, 8.0), unit=unit, periodic=False)
    s = contact.Surface.from_topography(t)
    np.testing.assert_allclose(s.heights, h * metres, rtol=1e-15)
    assert (s.dx, s.dy) == pytest.approx((metres, 2 * metres), rel=1e-15)


def test_missing_points_become_the_mask_and_back(st):
    h = np.arange(20.0).reshape(4, 5)
    mask = np.zeros(h.shape, bool)
    mask[1, 2] = mask[3, 0] = True
    t = st.Topography(np.ma.masked_array(h, mask), (4.0, 5.0), unit="nm", periodic=False)
    s = contact.Surface.from_topography(t)
    np.testing.assert_array_equal(s.mask, mask)
    np.testing.assert_allclose(s.heights[~mask], h[~mask] * 1e-9, rtol=1e-15)
    back = s.to_topography(unit="nm")
    assert back.has_undefined_data
    np.testing.assert_array_equal(np.ma.getmaskarray(back.heights()), mask)
    # a pipeline result (a detrended topography) converts as well
    assert contact.Surface.from_topography(t.detrend("center")).mask.sum() == 2


def test_refusals_name_the_problem(st):
    with pytest.raises(ValueError, match=r"2-D topography map.*line scan"):
        contact.Surface.from_topography(st.UniformLineScan(np.arange(8.0), 8.0, unit="m"))
    nonuniform = st.NonuniformLineScan(np.array([0.0, 1.0, 3.0]), np.arange(3.0), unit="m")
    with pytest.raises(ValueError, match="uniform grid; this one is nonuniform"):
        contact.Surface.from_topography(nonuniform)
    with pytest.raises(TypeError, match="SurfaceTopography topography"):
        contact.Surface.from_topography(np.zeros((4, 4)))
    no_unit = st.Topography(np.ones((3, 3)), (1.0, 1.0))
    with pytest.raises(ValueError, match=r"no length unit.*unit="):
        contact.Surface.from_topography(no_unit)
    s = contact.Surface.from_topography(no_unit, unit="mm")
    assert s.dx == pytest.approx(1e-3 / 3)
    with pytest.raises(ValueError, match="contradicts"):
        contact.Surface.from_topography(st.Topography(np.ones((3, 3)), (1.0, 1.0), unit="m"),
                                        unit="mm")
    with pytest.raises(ValueError, match="unknown length unit"):
        contact.Surface(np.ones((3, 3)), 1.0).to_topography(unit="inch")


def test_without_surfacetopography_the_error_says_how_to_install(monkeypatch):
    s = contact.Surface(np.ones((3, 3)), 1.0)
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)  # import fails
    with pytest.raises(ImportError, match=r'pip install "glstat\[topography\]"'):
        s.to_topography()
    with pytest.raises(ImportError, match=r'pip install "glstat\[topography\]"'):
        contact.Surface.from_topography(object())


def test_import_contact_does_not_import_surfacetopography():
    code = "import sys, contact; print('SurfaceTopography' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False"
