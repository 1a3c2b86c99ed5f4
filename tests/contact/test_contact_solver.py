"""The asperity contact model against hand-computed answers.

References: for a paraboloid ``z = -x^2/(2 Rx) - y^2/(2 Ry)`` cut at depth delta the
crossings are ``sqrt(2 R delta)`` and the slope ``delta / r``; for a cone of slope
``tan(theta)`` the crossings are ``delta / tan(theta)`` and the attack angle is theta. The
elliptic profile ``1.5 p_m sqrt(1 - (x/a)^2 - (y/b)^2)`` integrates to ``p_m pi a b``
(docs/method.md §3), which the grid sum must approach under refinement.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import contact

E, NU, C = 210e9, 0.3, 0.2
E_STAR = E / (1 - NU**2)


def paraboloid(n: int, length=1e-3, rx=2e-3, ry=4e-3) -> contact.Surface:
    dx = length / (n - 1)
    x = (np.arange(n) - (n - 1) // 2) * dx
    return contact.Surface(-(x[:, None] ** 2 / (2 * rx) + x[None, :] ** 2 / (2 * ry)), dx)


def cone(n: int, length=1e-3, slope=0.1) -> contact.Surface:
    dx = length / (n - 1)
    x = (np.arange(n) - (n - 1) // 2) * dx
    return contact.Surface(-slope * np.hypot(x[:, None], x[None, :]), dx)


def paraboloid_answer(delta, rx=2e-3, ry=4e-3, c=C):
    a, b = math.sqrt(2 * rx * delta), math.sqrt(2 * ry * delta)
    beta = 0.5 * (math.atan(delta / a) + math.atan(delta / b))
    p_m = c * E_STAR * math.tan(beta)
    return a, b, beta, p_m, p_m * math.pi * a * b


def test_paraboloid_geometry_and_force_converge():
    delta = 7e-6  # the crossings fall between grid points at every resolution
    a0, b0, beta0, pm0, f0 = paraboloid_answer(delta)
    errors = []
    for n in (51, 201, 801):
        res = contact.solve_displacement(paraboloid(n), -delta, E, NU)
        assert len(res.asperities) == 1
        row = res.asperities.iloc[0]
        assert row.delta == pytest.approx(delta, rel=1e-12)
        errors.append(
            [abs(row.a / a0 - 1), abs(row.b / b0 - 1), abs(row.beta / beta0 - 1),
             abs(row.p_m / pm0 - 1), abs(row.F / f0 - 1)]
        )
        assert res.force == pytest.approx(row.F, rel=1e-12)
        assert res.pressure.sum() * res.cell_area == pytest.approx(res.force, rel=1e-12)
    errors = np.array(errors)
    assert (np.diff(errors, axis=0) < 0).all(), errors
    assert errors[-1, :4].max() < 1e-5
    assert errors[-1, 4] < 1e-4


def test_cone_is_exact_in_geometry_and_converges_in_force():
    slope, delta = 0.1, 20e-6
    a0 = delta / slope
    f0 = C * E_STAR * slope * math.pi * a0**2
    errors = []
    for n in (51, 201, 801):
        res = contact.solve_displacement(cone(n, slope=slope), -delta, E, NU)
        row = res.asperities.iloc[0]
        # Heights are linear along grid lines through the apex: crossings are exact.
        assert row.a == pytest.approx(a0, rel=1e-12)
        assert row.b == pytest.approx(a0, rel=1e-12)
        assert row.beta == pytest.approx(math.atan(slope), rel=1e-12)
        assert row.p_m == pytest.approx(C * E_STAR * slope, rel=1e-12)
        errors.append(abs(row.F / f0 - 1))
    assert errors[0] > errors[1] > errors[2]
    assert errors[-1] < 1e-4


def test_cone_factor_and_counter_face_scale_the_pressure():
    s = cone(101)
    base = contact.solve_displacement(s, -20e-6, E, NU)
    sneddon = contact.solve_displacement(s, -20e-6, E, NU, cone_factor=0.5)
    np.testing.assert_allclose(sneddon.pressure, base.pressure * 2.5, rtol=1e-12)
    same = contact.solve_displacement(s, -20e-6, E, NU, counter_face=(E, NU))
    # Two identical elastic bodies: 1/E* doubles (Johnson, Contact Mechanics, eq. 4.3).
    np.testing.assert_allclose(same.pressure, base.pressure / 2, rtol=1e-12)
    assert contact.effective_modulus(E, NU) == pytest.approx(E_STAR, rel=1e-15)


def test_load_control_matches_force_and_paraboloid_depth():
    s = paraboloid(401)
    for pressure in (1e3, 1e5, 1e6, 1e7):
        res = contact.solve(s, pressure, E, NU)
        target = pressure * s.area
        assert res.target_force == pytest.approx(target, rel=1e-15)
        assert abs(res.force / target - 1) <= 1e-6
        assert abs(res.force_error) <= 1e-6
        assert res.pressure.sum() * res.cell_area == pytest.approx(res.force, rel=1e-12)
        # The depth solves the continuum F(delta) = p_m pi a b up to the grid error, once
        # the patch spans several grid steps (at 1e3 Pa it is about one step wide).
        if pressure >= 1e6:
            assert res.asperities["a"].iloc[0] > 10 * s.dx
            assert paraboloid_answer(-res.separation)[4] == pytest.approx(target, rel=1e-3)


def test_force_is_monotone_in_separation():
    s = contact.weierstrass((128, 128), 1e-3, 0.5, rq=50e-6, rng=3)
    top = s.heights.max()
    ds = np.linspace(top - 4 * 50e-6, top, 200)
    forces = [contact.solve_displacement(s, d, E, NU).force for d in ds]
    assert np.all(np.diff(forces) <= 0)
    assert forces[0] > 0 and forces[-1] == 0


def check_physical_state(s, res, target):
    """The result is one state of the model and its force error is reported honestly."""
    state = contact.solve_displacement(s, res.separation, E, NU)
    np.testing.assert_array_equal(res.pressure, state.pressure)
    np.testing.assert_array_equal(res.asperities.to_numpy(), state.asperities.to_numpy())
    assert res.force == state.force
    assert res.force_error == pytest.approx((state.force - target) / target, rel=1e-12)
    if not res.info["in_jump"]:
        assert abs(res.force_error) <= 1e-6
        assert res.info["force_jump"] == 0
        return
    # In a jump: the two limiting states lie on either side of the load; "nearest" returns
    # the closer unless the other carries nothing, "deeper" the one above the load.
    other = res.info["other_force"]
    assert (res.force - target) * (other - target) < 0
    assert abs(res.info["force_jump"]) == pytest.approx(abs(res.force - other) / target,
                                                        rel=1e-9)
    if res.info["jump"] == "nearest":
        assert abs(res.force - target) <= abs(other - target) or other == 0
    else:
        assert res.info["jump"] == "deeper" and res.force > target
    lo, hi = res.info["separation_bracket"]
    assert 0 < hi - lo <= 1e-12 * max(abs(lo), 1e-3)


@pytest.mark.parametrize("hurst", [0.0, 0.5, 1.0])
def test_rough_surface_force_balance_and_consistency(hurst):
    s = contact.weierstrass((256, 256), 1e-3, hurst, rq=50e-6, rng=11)
    target = 20e6 * 1e-6
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = contact.solve(s, 20e6, E, NU)
    jump_warnings = [w for w in caught if issubclass(w.category, contact.ContactWarning)]
    assert len(jump_warnings) == int(res.info["in_jump"])
    # H = 0 with this seed loads inside the jump of a summit's first contact.
    assert res.info["in_jump"] == (hurst == 0.0)
    check_physical_state(s, res, target)
    assert res.pressure.sum() * res.cell_area == pytest.approx(res.force, rel=1e-9)
    tab = res.asperities
    assert list(tab.columns) == ["i", "j", "x", "y", "height", "delta", "a", "b", "beta",
                                 "p_m", "F"]
    assert tab["F"].sum() == pytest.approx(res.force, rel=1e-12)
    assert (tab["delta"] > 0).all() and (tab["a"] > 0).all() and (tab["b"] > 0).all()
    np.testing.assert_allclose(tab["delta"], tab["height"] - res.separation, atol=1e-18)
    np.testing.assert_allclose(tab["p_m"], C * E_STAR * np.tan(tab["beta"]), rtol=1e-12)
    # Every point in contact lies in some asperity's patch: the samples are its pressures.
    assert res.samples.size == int((res.pressure > 0).sum())
    assert 0 < res.alpha < 1
    assert res.info["blend_weight"] == 1.0


def test_paper_settings_mean_pressure_rises_as_hurst_falls():
    # Bigerelle et al. 2019 (docs/method.md): Rq = 50 µm on 1 mm², 1024², 20 MPa, E = 210 GPa.
    means = {}
    for hurst in (1.0, 0.5, 0.0):
        s = contact.weierstrass((1024, 1024), 1e-3, hurst, rq=50e-6, rng=2019)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", contact.ContactWarning)
            res = contact.solve(s, 20e6, E, NU)
        if res.info["in_jump"]:
            assert abs(res.force_error) <= abs(res.info["force_jump"])
        else:
            assert abs(res.force_error) <= 1e-6
        assert 1 - res.alpha < 0.05
        means[hurst] = res.mean_pressure
    assert means[1.0] < means[0.5] < means[0.0]


def test_samples_come_from_one_state_of_the_model_at_the_paper_settings():
    # H = 0 with every term up to Nyquist: a handful of asperities, and 20 MPa falls in a
    # force jump of about 22 % of the load. Each sample must be a pressure of the model at
    # the returned separation, consistent with the asperity table (no blended values).
    s = contact.weierstrass((1024, 1024), 1e-3, 0.0, rq=50e-6, rng=2019)
    target = 20e6 * s.area
    with pytest.warns(contact.ContactWarning, match=r"falls inside a jump.*\(0\.2\d+ of the load\)"):
        res = contact.solve(s, 20e6, E, NU)
    assert res.info["in_jump"] and 0.1 < res.info["force_jump"] < 0.5
    check_physical_state(s, res, target)
    assert abs(res.force_error) <= 0.5 * res.info["force_jump"]
    # Summits whose patch is a single grid point carry exactly 1.5 p_m there.
    tab = res.asperities
    single = tab[(tab["a"] < s.dx) & (tab["b"] < s.dy)]
    assert len(single) > 0
    np.testing.assert_allclose(res.pressure[single["i"], single["j"]], 1.5 * single["p_m"],
                               rtol=1e-12)
    # The deeper state, on request, carries more than the load; the blend balances it.
    with pytest.warns(contact.ContactWarning, match=r"returned the deeper state"):
        deep = contact.solve(s, 20e6, E, NU, jump="deeper")
    assert deep.force > target and deep.separation < res.separation + 1e-12
    check_physical_state(s, deep, target)
    blend = contact.solve(s, 20e6, E, NU, jump="blend")
    assert abs(blend.force_error) <= 1e-6
    assert 0 < blend.info["blend_weight"] < 1


def test_mask_points_never_carry_pressure_and_alpha_ignores_them():
    s = contact.weierstrass((128, 128), 1e-3, 0.7, rq=50e-6, rng=5)
    mask = np.zeros(s.shape, dtype=bool)
    mask[40:60, :] = True
    masked = contact.Surface(s.heights, s.dx, mask=mask)
    res = contact.solve(masked, 20e6, E, NU)
    assert (res.pressure[mask] == 0).all()
    assert res.alpha == pytest.approx(np.mean(res.pressure[~mask] <= 0))
    assert res.target_force == pytest.approx(20e6 * (~mask).sum() * s.dx * s.dy)


# The 64² surface loads inside a force jump (warned); this test is about the inputs.
@pytest.mark.filterwarnings("ignore::contact.ContactWarning")
def test_inputs_are_not_mutated():
    s = contact.weierstrass((64, 64), 1e-3, 0.5, rq=50e-6, rng=1)
    before = s.heights.copy()
    contact.solve(s, 20e6, E, NU)
    contact.summits(s)
    s.roughness()
    np.testing.assert_array_equal(s.heights, before)
    raw = before.copy()
    wrapped = contact.Surface(raw, 1e-6)
    wrapped.heights[0, 0] = 1.0
    np.testing.assert_array_equal(raw, before)


def test_summary_and_frames():
    res = contact.solve(paraboloid(101), 1e5, E, NU)
    summary = res.summary()
    assert summary["force"] == res.force and summary["n_asperities"] == 1
    frame = res.to_frame()
    assert len(frame) == res.samples.size
    assert frame["pressure"].sum() == pytest.approx(res.samples.sum())


def test_load_inside_the_first_contact_jump_returns_the_touching_state():
    # Cone of slope 0.1: as the plane passes the apex, the apex point alone carries
    # 1.5 c E* tan(theta) at once, i.e. a force jump of 1.5 c E* 0.1 dx^2 (docs/method.md §3).
    # No state carries a quarter of it: the state above the apex carries nothing, so the
    # touching state is returned, with force error 0.75 jump / (0.25 jump) = 3.
    s = cone(401, slope=0.1)
    jump = 1.5 * C * E_STAR * 0.1 * s.dx * s.dy
    target = 0.25 * jump
    with pytest.warns(contact.ContactWarning, match=r"jumps from 0 N to [\d.e-]+ N \(4 of the load\)"):
        res = contact.solve(s, target / s.area, E, NU)
    assert res.force == pytest.approx(jump, rel=1e-12)
    assert res.force_error == pytest.approx(3.0, rel=1e-9)
    assert res.info["force_jump"] == pytest.approx(4.0, rel=1e-9)
    assert res.info["other_force"] == 0.0
    assert abs(res.separation) < 1e-15  # the apex height
    centre = (s.shape[0] // 2, s.shape[1] // 2)
    assert (res.pressure > 0).sum() == 1
    assert res.pressure[centre] == pytest.approx(1.5 * C * E_STAR * 0.1, rel=1e-12)
    assert res.pressure[centre] == pytest.approx(1.5 * res.asperities["p_m"].iloc[0], rel=1e-15)
    # The explicit blend balances the force with a pressure that is not the model's.
    blend = contact.solve(s, target / s.area, E, NU, jump="blend")
    assert blend.force == pytest.approx(target, rel=1e-12)
    assert blend.info["blend_weight"] == pytest.approx(0.25, rel=1e-9)
    assert blend.pressure[centre] == pytest.approx(target / (s.dx * s.dy), rel=1e-12)


def two_cones(n=201, slope=0.1, drop=2e-6):
    """Cones with apices at height 0 and -drop, a quarter of the side apart."""
    dx = 1e-3 / (n - 1)
    x = np.arange(n) * dx
    r1 = np.hypot(x[:, None] - x[n // 4], x[None, :] - x[n // 2])
    r2 = np.hypot(x[:, None] - x[3 * n // 4], x[None, :] - x[n // 2])
    return contact.Surface(np.maximum(-slope * r1, -drop - slope * r2), dx)


@pytest.mark.parametrize("fraction", [0.3, 0.7])
def test_nearest_state_in_a_jump_between_two_contacts(fraction):
    # As the plane reaches the second apex the force jumps by its apex point's load; a load
    # a fraction of the way up that jump gets the nearer of the two states.
    s = two_cones()
    below = contact.solve_displacement(s, -2e-6 + 1e-15, E, NU)
    above = contact.solve_displacement(s, -2e-6 - 1e-15, E, NU)
    assert len(below.asperities) == 1 and len(above.asperities) == 2
    target = below.force + fraction * (above.force - below.force)
    with pytest.warns(contact.ContactWarning, match=r"falls inside a jump"):
        res = contact.solve(s, target / s.area, E, NU)
    check_physical_state(s, res, target)
    expected = above if fraction > 0.5 else below
    assert len(res.asperities) == len(expected.asperities)
    assert res.force == pytest.approx(expected.force, rel=1e-4)  # the jump is 3 %
    assert res.info["other_force"] == pytest.approx((below if fraction > 0.5 else above).force,
                                                    rel=1e-4)
    with pytest.warns(contact.ContactWarning):
        deep = contact.solve(s, target / s.area, E, NU, jump="deeper")
    assert len(deep.asperities) == 2 and deep.force > target


def test_unknown_jump_rule():
    with pytest.raises(ValueError, match=r"jump must be 'nearest', 'deeper' or 'blend'"):
        contact.solve(cone(51), 1e3, E, NU, jump="middle")


def test_rectangular_cells():
    # Elliptic paraboloid on a grid with dy = 2 dx: same analytic answer as square cells.
    n, dx, delta = 801, 1.25e-6, 7e-6
    x = (np.arange(n) - n // 2) * dx
    y = (np.arange(n // 2 + 1) - n // 4) * 2 * dx
    s = contact.Surface(-(x[:, None] ** 2 / 4e-3 + y[None, :] ** 2 / 8e-3), dx, 2 * dx)
    row = contact.solve_displacement(s, -delta, E, NU).asperities.iloc[0]
    a0, b0, beta0, _, f0 = paraboloid_answer(delta)
    assert row.a == pytest.approx(a0, rel=1e-5)
    assert row.b == pytest.approx(b0, rel=1e-4)
    assert row.beta == pytest.approx(beta0, rel=1e-4)
    assert row.F == pytest.approx(f0, rel=1e-3)
