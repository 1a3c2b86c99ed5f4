"""Summits: strict 8-neighbour maxima with the documented border and mask rules."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import contact

# Many inputs here are unit-free (heights of order 1 on a micrometre or millimetre grid, files of
# small integers); contact's check of the units warns about them, which these tests do not examine.
pytestmark = pytest.mark.filterwarnings("ignore:the RMS of the heights:contact.errors.ContactWarning")


def brute_force(h: np.ndarray, valid: np.ndarray) -> set[tuple[int, int]]:
    """Reference: compare every interior point with its 8 neighbours one by one."""
    out = set()
    nx, ny = h.shape
    for i in range(1, nx - 1):
        for j in range(1, ny - 1):
            block = h[i - 1 : i + 2, j - 1 : j + 2]
            ok = valid[i - 1 : i + 2, j - 1 : j + 2].all()
            others = np.delete(block.ravel(), 4)
            if ok and (others < h[i, j]).all():
                out.add((i, j))
    return out


def test_hand_made_grid():
    h = np.zeros((6, 7))
    h[2, 2] = 1.0  # isolated summit
    h[0, 4] = 5.0  # border point: never a summit
    h[3, 5] = 2.0  # summit next to the border
    h[4, 1] = h[4, 2] = 0.5  # plateau of two equal points: not strict, no summit
    s = contact.summits(contact.Surface(h, 1e-6, 2e-6))
    assert set(zip(s.i.tolist(), s.j.tolist(), strict=True)) == {(2, 2), (3, 5)}
    np.testing.assert_array_equal(s.heights, [1.0, 2.0])
    np.testing.assert_allclose(s.x, [2e-6, 3e-6])
    np.testing.assert_allclose(s.y, [4e-6, 10e-6])
    assert len(s) == 2 and s.indices.shape == (2, 2)
    assert list(s.to_frame().columns) == ["i", "j", "x", "y", "height"]


def test_masked_neighbour_disqualifies():
    h = np.zeros((5, 5))
    h[2, 2] = 1.0
    mask = np.zeros((5, 5), bool)
    assert len(contact.summits(contact.Surface(h, 1e-6, mask=mask))) == 1
    mask[1, 3] = True
    assert len(contact.summits(contact.Surface(h, 1e-6, mask=mask))) == 0


@settings(max_examples=60, deadline=None)
@given(arrays(np.int8, st.tuples(st.integers(3, 12), st.integers(3, 12)),
              elements=st.integers(-3, 3)),
       st.integers(0, 2**32 - 1))
def test_matches_brute_force(levels, seed):
    # Small integer heights make ties (plateaus) frequent.
    h = levels.astype(float)
    valid = np.random.default_rng(seed).random(h.shape) > 0.1
    if not valid.any():
        valid[0, 0] = True
    surface = contact.Surface(np.where(valid, h, np.nan), 1e-6, mask=~valid)
    got = contact.summits(surface)
    assert set(zip(got.i.tolist(), got.j.tolist(), strict=True)) == brute_force(h, valid)


def test_egg_crate_count():
    # z = cos(kx) cos(ky), 16 points per period on 64 x 64: maxima where both cosines are
    # +1 (i, j in {16, 32, 48}) or both -1 (i, j in {8, 24, 40, 56}): 9 + 16 interior.
    n = np.arange(64)
    c = np.cos(2 * np.pi * n / 16)
    s = contact.summits(contact.Surface(np.outer(c, c), 1e-6))
    assert len(s) == 25
