"""A Surface taller than wide (the heights' RMS above its side: heights and spacing in different
units) is accepted with a warning that names the likely mix-up; plausible surfaces raise none,
in metres or in dimensionless units."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import contact

H = np.random.default_rng(1).normal(size=(64, 64))


def test_heights_of_a_tenth_of_a_metre_on_a_64_micrometre_patch_warn():
    with pytest.warns(contact.ContactWarning, match=r"RMS of the heights \(0\.1\d*\) exceeds the "
                                                    r"surface's side \(6\.4e-05\).*micrometres"):
        contact.Surface(0.1 * H, 1e-6)


def test_a_plausible_surface_raises_no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = contact.Surface(1e-6 * H, 1e-6, mask=np.abs(H) > 3)  # 1 µm rms on a 64 µm patch
        contact.Surface(H, 1.0)  # dimensionless: RMS 1 on a side of 64
        contact.Surface(1e-6 * H, 0.1)  # 1 µm on 6.4 m: odd, but not taller than wide
    assert s.shape == (64, 64)
