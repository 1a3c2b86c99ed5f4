"""contact_spots: connected contact regions of a pressure map, checked on hand-made maps."""

from __future__ import annotations

import numpy as np
import pytest

import contact
from contact import ContactResult, Surface, contact_spots
from contact.bem import solve_bem

CELL = 4e-12  # m², a 2 µm x 2 µm cell


def _map() -> np.ndarray:
    """Three spots: an L of three points, a diagonal pair (8-connected), a single point."""
    p = np.zeros((6, 7))
    p[0, 0], p[1, 0], p[1, 1] = 1e9, 3e9, 2e9  # L: 3 points, peak 3 GPa at (1, 0)
    p[3, 3], p[4, 4] = 5e8, 7e8  # diagonal neighbours: one spot under 8-connectivity
    p[2, 6] = 4e9  # alone (its nearest point (1, 1) is 5 columns away)
    return p


def test_spots_of_a_hand_made_map():
    spots = contact_spots(_map(), cell_area=CELL)
    assert len(spots) == spots.n_spots == 3
    # labels in row-major order of each spot's first point: L, single point, diagonal pair
    np.testing.assert_array_equal(spots.n_points, [3, 1, 2])
    np.testing.assert_allclose(spots.peak_pressure, [3e9, 4e9, 7e8], rtol=0)
    np.testing.assert_array_equal(spots.peak_index, [[1, 0], [2, 6], [4, 4]])
    np.testing.assert_allclose(spots.area, np.array([3, 1, 2]) * CELL, rtol=1e-15)
    np.testing.assert_allclose(spots.load, np.array([6e9, 4e9, 1.2e9]) * CELL, rtol=1e-15)
    assert spots.labels[3, 3] == spots.labels[4, 4] == 3
    assert spots.labels[0, 5] == 0
    assert spots.periodic is False and spots.cell_area == CELL
    frame = spots.to_frame()
    assert list(frame.columns) == ["label", "peak_pressure", "i", "j", "area", "load",
                                   "n_points"]
    assert frame["load"].sum() == pytest.approx(_map().sum() * CELL, rel=1e-15)


def test_four_connected_points_only_touch_diagonally_yet_form_one_spot():
    p = np.zeros((5, 5))
    p[np.arange(5), np.arange(5)] = 1.0  # a diagonal line
    assert len(contact_spots(p, cell_area=1.0)) == 1


def test_periodic_spots_join_across_opposite_edges_and_corners():
    p = np.zeros((6, 7))
    p[0, 2], p[5, 2] = 1.0, 2.0  # first and last rows, same column
    p[3, 0], p[4, 6] = 3.0, 4.0  # first and last columns, diagonal across the edge
    p[5, 6] = 5.0  # next to (4, 6)
    flat = contact_spots(p, cell_area=1.0)
    wrapped = contact_spots(p, cell_area=1.0, periodic=True)
    assert len(flat) == 4  # (0,2) | (3,0) | (4,6)+(5,6) | (5,2)
    assert len(wrapped) == 2
    np.testing.assert_allclose(np.sort(wrapped.load), [3.0, 12.0])
    np.testing.assert_allclose(np.sort(wrapped.peak_pressure), [2.0, 5.0])
    corner = np.zeros((4, 4))
    corner[0, 0], corner[3, 3] = 1.0, 1.0
    assert len(contact_spots(corner, cell_area=1.0, periodic=True)) == 1
    assert len(contact_spots(corner, cell_area=1.0)) == 2


def test_result_input_uses_its_cell_area_and_periodicity():
    s = Surface(np.zeros((8, 8)), 2e-6)
    s.heights[2, 2] = s.heights[6, 6] = 1e-7
    res = solve_bem(s, 1e6, 210e9, 0.3, periodic=True)
    spots = contact_spots(res)
    assert spots.periodic is True and spots.cell_area == pytest.approx(4e-12, rel=1e-15)
    assert len(spots) == 2
    assert spots.load.sum() == pytest.approx(res.force, rel=1e-12)
    assert spots.area.sum() == pytest.approx(res.contact_fraction * s.area, rel=1e-12)
    hand = ContactResult(pressure=_map(), separation=0.0, force=0.0, target_force=None,
                         force_error=0.0, nominal_pressure=None, cell_area=CELL)
    np.testing.assert_allclose(contact_spots(hand).load, contact_spots(_map(), CELL).load)


def test_no_contact_gives_empty_arrays():
    spots = contact_spots(np.zeros((4, 4)), cell_area=1.0)
    assert len(spots) == 0
    assert spots.peak_index.shape == (0, 2) and spots.load.size == 0
    assert not spots.labels.any()


@pytest.mark.parametrize(
    ("args", "kwargs", "error", "match"),
    [
        ((np.zeros((3, 3)),), {}, ValueError, "cell_area"),
        ((np.zeros((3, 3)), -1.0), {}, ValueError, "cell_area"),
        ((np.zeros(3), 1.0), {}, ValueError, "2-D"),
        ((np.full((3, 3), np.nan), 1.0), {}, ValueError, "NaN"),
        ((np.zeros((3, 3)), 1.0), {"periodic": "yes"}, TypeError, "periodic"),
    ],
)
def test_bad_input_is_rejected(args, kwargs, error, match):
    with pytest.raises(error, match=match):
        contact_spots(*args, **kwargs)


def test_cell_area_contradicting_the_result_is_rejected():
    hand = ContactResult(pressure=_map(), separation=0.0, force=0.0, target_force=None,
                         force_error=0.0, nominal_pressure=None, cell_area=CELL)
    with pytest.raises(ValueError, match="contradicts"):
        contact_spots(hand, cell_area=2 * CELL)


def test_exported_from_the_package():
    assert "contact_spots" in contact.__all__ and contact.contact_spots is contact_spots


def test_spots_touching_the_border_are_flagged_unless_the_map_is_periodic():
    p = np.zeros((6, 6))
    p[0, 2] = 1e9          # top row
    p[2:4, 2:4] = 2e9      # inside
    p[3, 5] = 3e9          # right column
    spots = contact_spots(p, cell_area=1e-12)
    assert spots.touches_border.tolist() == [True, False, True]
    periodic = contact_spots(p, cell_area=1e-12, periodic=True)
    assert periodic.touches_border.tolist() == [False] * periodic.n_spots
    assert contact_spots(np.zeros((4, 4)), cell_area=1e-12).touches_border.size == 0


def test_spot_peaks_and_positions_match_ndimage_with_ties():
    # scipy.ndimage as the reference for the largest pressure, load and points of each spot;
    # the peak's position is the first point in row-major order holding it (the documented
    # rule; ndimage.maximum_position picks any of the tied points); pressures rounded to make
    # ties
    from scipy import ndimage

    rng = np.random.default_rng(7)
    p = np.round(rng.random((60, 50)) * 4) * (rng.random((60, 50)) < 0.35) * 1e8
    spots = contact.contact_spots(p, cell_area=1e-12)
    labels, n = ndimage.label(p > 0, structure=np.ones((3, 3), dtype=bool))
    index = np.arange(1, n + 1)
    assert spots.n_spots == n > 10
    np.testing.assert_array_equal(spots.peak_pressure, ndimage.maximum(p, labels, index))
    for k in index:
        first = np.argwhere((labels == k) & (p == spots.peak_pressure[k - 1]))[0]
        np.testing.assert_array_equal(spots.peak_index[k - 1], first)
    np.testing.assert_allclose(spots.load, ndimage.sum_labels(p, labels, index) * 1e-12, rtol=1e-13)
    np.testing.assert_array_equal(spots.n_points, np.bincount(labels.ravel())[1:])
