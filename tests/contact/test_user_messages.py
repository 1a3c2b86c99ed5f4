"""What a user reads: the tilt hint of the roughness, where warnings point, the threshold of
the force-jump warning, the repr of ContactSpots and the printout of ContactResult.summary()."""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

import contact
from contact.asperity import JUMP_WARNING_THRESHOLD
from contact.roughness import FORM_HINT_FRACTION, hurst_exponent, roughness_parameters

E, NU = 210e9, 0.3
N, DX = 128, 1e-6


def _messages(record) -> list[str]:
    return [str(w.message) for w in record if issubclass(w.category, contact.ContactWarning)]


def _base_and_tilt() -> tuple[np.ndarray, np.ndarray]:
    """A self-affine height map (m) with its mean and least-squares plane removed, and a
    centred unit tilt orthogonal to it: ``base + a * tilt`` has a plane that explains exactly
    ``a² var(tilt) / (a² var(tilt) + var(base))`` of its variance."""
    base = contact.self_affine((N, N), N * DX, 0.8, rq=1e-7, rng=3).heights
    x = np.arange(N) * DX
    design = np.column_stack([np.ones(N * N), np.repeat(x, N), np.tile(x, N)])
    coef, *_ = np.linalg.lstsq(design, base.ravel(), rcond=None)
    base = base - (design @ coef).reshape(N, N)
    tilt = (x - x.mean())[:, None] + 0.5 * (x - x.mean())[None, :]
    return base, tilt


def _tilted(fraction: float) -> np.ndarray:
    """Heights (m) whose least-squares plane explains ``fraction`` of their variance."""
    base, tilt = _base_and_tilt()
    a = np.sqrt(fraction / (1 - fraction) * np.mean(base**2) / np.mean(tilt**2))
    return base + a * tilt


def test_a_tilted_surface_is_told_to_level_with_a_plane():
    h = _tilted(0.999)
    sq_mean = float(np.sqrt(np.mean((h - h.mean()) ** 2)))
    sq_plane = float(np.sqrt(np.mean(_base_and_tilt()[0] ** 2)))  # residual of the plane fit
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        r = contact.Surface(h, DX).roughness()
    tilt = [m for m in _messages(record) if "dominated by a tilt" in m]
    assert len(tilt) == 1 and 'roughness(level="plane")' in tilt[0]
    numbers = re.search(r"Sq = ([\d.e+-]+) m about the mean height, ([\d.e+-]+) m about the "
                        r"plane", tilt[0])
    assert float(numbers[1]) == pytest.approx(sq_mean, rel=1e-3)
    assert float(numbers[2]) == pytest.approx(sq_plane, rel=1e-3)
    assert "all but 0.1 % of their variance" in tilt[0]
    assert r["Sq"] == pytest.approx(sq_mean, rel=1e-12)  # the default is unchanged
    # levelled, the self-affine base has a Hurst exponent and nothing is warned
    with warnings.catch_warnings():
        warnings.simplefilter("error", contact.ContactWarning)
        levelled = contact.Surface(h, DX).roughness(level="plane")
    assert levelled["Sq"] == pytest.approx(sq_plane, rel=1e-9)


@pytest.mark.parametrize("fraction", [0.45, 0.55])
def test_the_tilt_hint_needs_the_plane_to_explain_more_than_half_the_variance(fraction):
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        roughness_parameters(_tilted(fraction), DX, DX)
    tilt = [m for m in _messages(record) if "dominated by a tilt" in m]
    assert len(tilt) == int(fraction > FORM_HINT_FRACTION)


def test_the_hurst_warning_suggests_a_plane_only_for_unlevelled_heights_with_a_tilt():
    """Noise has no Hurst exponent: with a tilt that a plane explains a noticeable share of
    (30 %, below the tilt warning's half), the Hurst warning suggests level="plane"; without
    a tilt, or once levelled, it does not."""
    rng = np.random.default_rng(0)
    noise = rng.standard_normal((64, 64)) * 1e-7
    x = np.arange(64)[:, None] * np.ones((1, 64))
    tilt = x - x.mean()
    tilted = noise + np.sqrt(0.3 / 0.7 * np.mean(noise**2) / np.mean(tilt**2)) * tilt
    with pytest.warns(contact.ContactWarning, match=r'Hurst exponent undefined.*level="plane"'):
        contact.Surface(tilted, DX).roughness()
    for h, level in ((noise, "mean"), (tilted, "plane")):
        with pytest.warns(contact.ContactWarning, match="Hurst exponent undefined") as record:
            contact.Surface(h, DX).roughness(level=level)
        assert not any("level=" in m for m in _messages(record))


def test_roughness_warnings_point_at_the_callers_line():
    h = _tilted(0.9) + np.random.default_rng(1).standard_normal((N, N)) * 1e-6  # both warnings
    calls = [lambda: contact.Surface(h, DX).roughness(),
             lambda: roughness_parameters(h, DX, DX),
             lambda: hurst_exponent(h, DX, DX)]
    for call in calls:
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            call()
        assert record and all(w.filename == __file__ for w in record), [
            (w.filename, w.lineno) for w in record]


def _load_inside_first_touch(k: int) -> tuple[contact.Surface, float, float]:
    """A surface, a nominal pressure (Pa) inside the force jump of its ``k``-th highest
    summit's first touch, and that jump relative to the load, from displacement control."""
    s = contact.weierstrass((128, 128), 1e-3, 0.5, rq=5e-6, rng=3)
    hk = np.sort(contact.summits(s).heights)[::-1][k]
    above = contact.solve_displacement(s, np.nextafter(hk, np.inf), E, NU).force
    below = contact.solve_displacement(s, np.nextafter(hk, -np.inf), E, NU).force
    target = above + 0.25 * (below - above)
    return s, target / s.area, (below - above) / target


@pytest.mark.parametrize("k", [20, 60])
def test_a_force_jump_is_warned_about_only_above_one_percent_of_the_load(k):
    s, pressure, jump = _load_inside_first_touch(k)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        res = contact.solve(s, pressure, E, NU)
    warned = [m for m in _messages(record) if "falls inside a jump" in m]
    assert res.info["in_jump"] and res.info["force_jump"] == pytest.approx(jump, rel=1e-9)
    big = max(jump, abs(res.force_error)) > JUMP_WARNING_THRESHOLD
    assert big == (k == 20)  # 1.3 % and 0.58 % of the load: one on each side of 1 %
    assert len(warned) == int(big)
    assert res.info["warning"] == (warned[0] if big else "")
    assert abs(res.force_error) <= jump


def test_contact_spots_print_in_one_line():
    p = np.zeros((6, 6))
    p[0, 0], p[2, 2], p[2, 3] = 3e9, 1e9, 2e9
    spots = contact.contact_spots(p, cell_area=1e-12)
    # the areas (3 points of 1 µm²) and peaks set above
    assert repr(spots) == ("ContactSpots(2 spots, 1 touching the border, largest peak 3000 MPa, "
                           "total area 3 µm², not periodic)")
    wide = contact.contact_spots(p, cell_area=1e-7, periodic=True)
    assert repr(wide) == ("ContactSpots(2 spots, largest peak 3000 MPa, total area 0.3 mm², "
                          "periodic)")
    assert repr(contact.contact_spots(np.zeros((3, 3)), cell_area=1e-12)) == (
        "ContactSpots(0 spots, not periodic)")


def test_summary_is_a_float_series_that_prints_small_lengths():
    s = contact.weierstrass((64, 64), 1e-3, 0.5, rq=5e-7, rng=0, n_terms=6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", contact.ContactWarning)
        res = contact.solve(s, 20e6, E, NU)
    summary = res.summary()
    assert summary.dtype == np.float64 and summary.name == "asperity"
    assert summary["separation"] == res.separation and summary["force"] == res.force
    assert summary["mean_pressure"] == res.mean_pressure
    assert summary["n_asperities"] == len(res.asperities) and summary["converged"] == 1.0
    line = next(x for x in repr(summary).splitlines() if x.startswith("separation"))
    assert float(line.split()[1]) == pytest.approx(res.separation, rel=1e-6)
    assert abs(res.separation) < 1e-5  # a length that a fixed-point printout shows as 0.0
    shown = contact.solve_displacement(s, res.separation, E, NU).summary()
    assert np.isnan(shown["target_force"]) and shown.name == "asperity-displacement"


def test_a_rough_small_scan_is_named_without_a_unit_guess_and_like_adds_no_warning():
    """Sq 7.4 µm on a 64 µm scan is more than a tenth of the side: the message says so and does
    not suggest micrometres (the value already is some); surfaces like it are generated at a
    plausible roughness first, so weierstrass_like itself warns of nothing."""
    with pytest.warns(contact.ContactWarning) as caught:
        scan = contact.self_affine((64, 64), 64e-6, hurst=0.7, rq=7.4e-6, rng=3)
    text = " ".join(str(w.message) for w in caught)
    assert "more than a tenth of the surface's side (6.4e-05 m)" in text and "did you mean" not in text
    with warnings.catch_warnings():
        warnings.simplefilter("error", contact.ContactWarning)
        like = contact.weierstrass_like(scan, 1, rng=1)[0]
    assert float(like.roughness(level="plane", warn=False)["Sq"]) == pytest.approx(
        contact.fit_spectrum(scan).rq, rel=1e-10)


@pytest.mark.parametrize("load, words", [(1e-300, "implausibly small"), (1e30, "implausibly large")])
def test_an_implausible_nominal_pressure_warns_at_either_end(load, words):
    surface = contact.self_affine((32, 32), 1e-4, 0.8, rq=1e-7, rng=1)
    with pytest.warns(contact.ContactWarning, match=words):
        contact.solve_bem(surface, load, 210e9, 0.3, max_iter=5)


_IMPLAUSIBLE = [(1e-300, 210e9, None), (1e6, 210.0, None), (1e6, 210e9, (70.0, 0.3)),
                (1.0, 1.0, (1.0, 0.3))]


@pytest.mark.parametrize("solver, load, modulus, counter_face", [
    *(("solve_bem", *case) for case in [*_IMPLAUSIBLE, (1e30, 210e9, None)]),
    # loads the asperity model reaches with the soft moduli (1 Pa is implausible too)
    *(("solve", *case) for case in [(1e-300, 210e9, None), (1.0, 210.0, None),
                                    (1.0, 210e9, (70.0, 0.3))]),
])
def test_warn_false_silences_every_implausibility_warning(solver, load, modulus, counter_face):
    surface = contact.self_affine((32, 32), 1e-4, 0.8, rq=1e-7, rng=1)
    solve = getattr(contact, solver)
    kwargs = {"max_iter": 5} if solver == "solve_bem" else {}
    with pytest.warns(contact.ContactWarning, match="implausibly"):
        solve(surface, load, modulus, 0.3, counter_face=counter_face, **kwargs)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solve(surface, load, modulus, 0.3, counter_face=counter_face, warn=False, **kwargs)


def test_warn_false_silences_the_modulus_warning_under_displacement_control():
    surface = contact.self_affine((32, 32), 1e-4, 0.8, rq=1e-7, rng=1)
    with pytest.warns(contact.ContactWarning, match="Young's modulus"):
        contact.solve_bem_displacement(surface, 0.0, 210.0, 0.3, max_iter=5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        contact.solve_bem_displacement(surface, 0.0, 210.0, 0.3, max_iter=5, warn=False)
    with pytest.warns(contact.ContactWarning, match="Young's modulus"):
        contact.effective_modulus(210.0, 0.3)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert contact.effective_modulus(210.0, 0.3, warn=False) > 0
