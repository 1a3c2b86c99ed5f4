"""compare_models: the asperity model and the BEM reference side by side."""

from __future__ import annotations

import numpy as np
import pytest

from contact import Surface, self_affine
from contact.asperity import solve
from contact.bem import solve_bem
from contact.bem_compare import compare_models

E, NU, P = 210e9, 0.3, 20e6


@pytest.fixture(scope="module")
def surface() -> Surface:
    return self_affine((48, 48), 1e-3, 0.8, rq=2e-6, rng=5)


def test_frame_reports_both_models(surface):
    frame = compare_models(surface, P, E, NU)
    assert list(frame.index) == ["contact_fraction", "mean_pressure", "max_pressure"]
    assert list(frame.columns) == ["asperity", "bem", "ratio", "relative_error"]
    a = solve(surface, P, E, NU)
    b = solve_bem(surface, P, E, NU)
    for q in frame.index:
        assert frame.loc[q, "asperity"] == pytest.approx(getattr(a, q), rel=1e-12)
        assert frame.loc[q, "bem"] == pytest.approx(getattr(b, q), rel=1e-9)
    np.testing.assert_allclose(frame["ratio"], frame["asperity"] / frame["bem"], rtol=1e-15)
    np.testing.assert_allclose(frame["relative_error"], frame["ratio"] - 1, rtol=1e-15)
    assert frame.attrs["bem_converged"] is True
    res = frame.attrs["results"]
    assert res["asperity"].method == "asperity" and res["bem"].method == "bem"
    # the BEM carries the load exactly, so its mean contact pressure is P / fraction
    assert frame.loc["mean_pressure", "bem"] == pytest.approx(
        P / frame.loc["contact_fraction", "bem"], rel=1e-9)


def test_options_reach_both_solvers(surface):
    frame = compare_models(surface, P, E, NU, cone_factor=0.5, counter_face=(E, NU),
                           periodic=True)
    res = frame.attrs["results"]
    assert res["bem"].info["periodic"] is True
    assert res["bem"].info["e_star"] == pytest.approx(E / (2 * (1 - NU**2)), rel=1e-15)
    ref = solve(surface, P, E, NU, 0.5, (E, NU))
    assert frame.loc["max_pressure", "asperity"] == pytest.approx(ref.max_pressure, rel=1e-12)


def test_bad_input_propagates(surface):
    with pytest.raises(ValueError, match="nominal_pressure"):
        compare_models(surface, -1.0, E, NU)
    with pytest.raises(ValueError, match="tol"):
        compare_models(surface, P, E, NU, tol=0.0)


def test_masked_surface_compares_equal_loads(surface):
    mask = np.zeros(surface.shape, bool)
    mask[:, 24:] = True
    masked = Surface(surface.heights, surface.dx, surface.dy, mask=mask)
    res = compare_models(masked, P, E, NU).attrs["results"]
    measured = P * surface.dx * surface.dy * int((~mask).sum())
    assert res["asperity"].target_force == pytest.approx(measured, rel=1e-12)
    assert res["bem"].target_force == pytest.approx(measured, rel=1e-12)
    assert res["bem"].force == pytest.approx(measured, rel=1e-9)
