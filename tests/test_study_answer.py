"""The study's answer tables: the Holm adjustment of the centring tests across cases."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from glstat.study.answer import _holm_across_cases


def _case(p_asperity, p_grid):
    def sample(p):
        return SimpleNamespace(validation=SimpleNamespace(table=object(), t_pvalue=p))
    return {"asperity": sample(p_asperity), "grid": sample(p_grid)}


def test_holm_is_one_family_per_model_and_sample_across_cases():
    items = [((0, 0), _case(0.01, 0.5), ""), ((1, 0), _case(0.04, 0.2), ""),
             ((2, 0), _case(0.03, 0.9), "")]
    got = _holm_across_cases(items)
    # Holm (1979) by hand, m = 3: sorted 0.01, 0.03, 0.04 -> 3 * 0.01, max(0.03, 2 * 0.03),
    # max(0.06, 1 * 0.04)
    assert [got[(ih, 0, "", "asperity")] for ih in range(3)] == pytest.approx([0.03, 0.06, 0.06])
    # grid: sorted 0.2, 0.5, 0.9 -> 0.6, max(0.6, 1.0) capped at 1, max(1, 0.9)
    assert [got[(ih, 0, "", "grid")] for ih in range(3)] == pytest.approx([1.0, 0.6, 1.0])


def test_each_model_is_its_own_family():
    items = [((0, 0), _case(0.01, 0.5), ", asperity model"), ((0, 0), _case(0.01, 0.5), ", elastic BEM")]
    got = _holm_across_cases(items)
    assert got[(0, 0, ", asperity model", "asperity")] == pytest.approx(0.01)  # a family of one
    assert got[(0, 0, ", elastic BEM", "asperity")] == pytest.approx(0.01)
