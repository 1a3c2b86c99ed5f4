"""contact.reference against facts derived independently of its formulas.

References:
- Boussinesq (Johnson 1985, ch. 3): the surface displacement of a half-space under an
  axisymmetric pressure p(s) is u(r) = 1/(π E*) ∫ p(s) s ∫ dθ / |r - s| ds, the angular
  integral being 4 K(m) / (r + s) with 1 - m = ((r - s)/(r + s))² (complete elliptic integral
  of the first kind); evaluated here by quadrature, it must close the gap of a sphere
  (δ - r²/2R) and of a cone (δ - r tan β) over the contact.
- Hertz force–approach law F = 4/3 E* R^(1/2) δ^(3/2) (Johnson 1985, §4.2), against the
  force integrated from the pressure profile.
- Flamant (Johnson 1985, ch. 2): a line load P on a half-plane displaces the surface by
  -(2 P / (π E*)) ln|x|; periodised, the kernel is -(2/(π E*)) ln|2 sin(π x/λ)|, whose
  convolution with cos(2πx/λ) gives the displacement of a sinusoidal pressure.
- Westergaard's load–width relation in its limits: at light loads each strip is the Hertz
  contact of a cylinder of radius R = λ²/(4π²Δ), carrying P' = π a² E* / (4R) per unit
  length with peak pressure (P' E* / (π R))^(1/2) (Johnson 1985, ch. 4); at P̄ = p* the
  contact closes and the profile becomes P̄ + p* cos(2πx/λ).
- Sneddon's cone: ∫_0^1 arccosh(1/x) dx = π/2 and the Boussinesq displacement above.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, special

import contact
from contact import reference

E, NU = 210e9, 0.3
E_STAR = E / (1 - NU**2)


def _quad(f, a, b, points=None):
    value, _ = integrate.quad(f, a, b, points=points, limit=400, epsabs=0.0, epsrel=1e-11)
    return value


def _boussinesq(pressure, r, a, e_star):
    """Surface displacement at r of an axisymmetric pressure carried on the disc r <= a."""
    if r == 0:
        return 2.0 / e_star * _quad(pressure, 0.0, a)

    def integrand(s):
        # K(m) with 1 - m = ((r - s)/(r + s))², exact next to the logarithmic peak at s = r
        return pressure(s) * s * 4 * special.ellipkm1(((r - s) / (r + s)) ** 2) / (r + s)

    inner = [r] if 0 < r < a else None
    return _quad(integrand, 0.0, a, points=inner) / (math.pi * e_star)


# --------------------------------------------------------------------------- Hertz
def test_hertz_force_integrates_from_the_profile_and_obeys_the_force_approach_law():
    h = reference.hertz_sphere(10.0, 0.01, E_STAR)
    a = h.contact_radius
    force = _quad(lambda r: h.pressure(r) * 2 * math.pi * r, 0.0, a)
    assert force == pytest.approx(10.0, rel=1e-10)
    assert 4 / 3 * E_STAR * math.sqrt(h.radius) * h.approach**1.5 == pytest.approx(10.0, rel=1e-12)
    assert h.mean_pressure == pytest.approx(force / (math.pi * a**2), rel=1e-10)
    assert h.mean_pressure == pytest.approx(2 / 3 * h.max_pressure, rel=1e-14)
    assert h.pressure(0.0) == h.max_pressure
    assert h.pressure(a) == 0.0 and h.pressure(2 * a) == 0.0
    r = np.array([[0.0, 0.5 * a], [a, 3 * a]])
    assert h.pressure(r).shape == (2, 2)


@pytest.mark.parametrize("fraction", [0.0, 0.3, 0.7, 1.0])
def test_hertz_pressure_closes_the_gap_of_the_sphere(fraction):
    h = reference.hertz_sphere(10.0, 0.01, E_STAR)
    r = fraction * h.contact_radius
    u = _boussinesq(h.pressure, r, h.contact_radius, E_STAR)
    assert u == pytest.approx(h.approach - r**2 / (2 * h.radius), rel=1e-10)


def test_hertz_two_elastic_bodies_through_the_contact_modulus():
    rigid = reference.hertz_sphere(10.0, 0.01, contact.effective_modulus(E, NU))
    same = reference.hertz_sphere(10.0, 0.01, contact.effective_modulus(E, NU, (E, NU)))
    # 1/E* doubles: a grows by 2^(1/3), p0 falls by 2^(2/3)
    assert same.contact_radius == pytest.approx(rigid.contact_radius * 2 ** (1 / 3), rel=1e-14)
    assert same.max_pressure == pytest.approx(rigid.max_pressure / 2 ** (2 / 3), rel=1e-14)


# --------------------------------------------------------------------------- sinusoids
def test_sinusoidal_displacement_is_the_periodic_flamant_convolution():
    lam = 1e-3
    # u(0) = (2/(π E*)) ∫_0^λ cos(2πs/λ) (-ln|2 sin(πs/λ)|) ds for a unit pressure amplitude
    u0 = 2 / (math.pi * E_STAR) * _quad(
        lambda s: -math.cos(2 * math.pi * s / lam) * math.log(abs(2 * math.sin(math.pi * s / lam))),
        0.0, lam, points=[lam / 2])
    assert reference.sinusoidal_displacement(1.0, lam, E_STAR) == pytest.approx(u0, rel=1e-9)
    assert reference.sinusoidal_displacement(1.0, lam, E_STAR) == pytest.approx(
        lam / (math.pi * E_STAR), rel=1e-15)


def test_full_contact_pressure_and_displacement_are_inverse():
    for lam in (1e-3, (1e-3, 1e-3), (1e-3, 3e-4)):
        p = reference.full_contact_pressure(2e-6, lam, E_STAR)
        assert reference.sinusoidal_displacement(p, lam, E_STAR) == pytest.approx(2e-6, rel=1e-14)
    one = reference.full_contact_pressure(1e-6, 1e-3, E_STAR)
    assert one == pytest.approx(math.pi * E_STAR * 1e-6 / 1e-3, rel=1e-15)
    # equal wavelengths: √2 p* (Johnson, Greenwood & Higginson 1985); a very long second
    # wavelength: the one-dimensional surface
    assert reference.full_contact_pressure(1e-6, (1e-3, 1e-3), E_STAR) == pytest.approx(
        math.sqrt(2) * one, rel=1e-14)
    assert reference.full_contact_pressure(1e-6, (1e-3, 1e6), E_STAR) == pytest.approx(one, rel=1e-12)


# --------------------------------------------------------------------------- Westergaard
LAM, DELTA = 1e-3, 1e-6


def test_westergaard_light_load_is_a_row_of_hertz_cylinders():
    p_star = reference.full_contact_pressure(DELTA, LAM, E_STAR)
    radius = LAM**2 / (4 * math.pi**2 * DELTA)  # curvature radius of the crests
    for ratio in (1e-8, 1e-6, 1e-4):
        w = reference.westergaard(ratio * p_star, LAM, DELTA, E_STAR)
        a = w.contact_half_width
        per_length = math.pi * a**2 * E_STAR / (4 * radius)
        tol = (math.pi * a / LAM) ** 2  # relative size of the next term of sin²(πa/λ)
        assert w.mean_pressure == pytest.approx(per_length / LAM, rel=tol)
        p0 = math.sqrt(per_length * E_STAR / (math.pi * radius))
        assert w.max_pressure == pytest.approx(p0, rel=tol)
        assert w.pressure(0.0) == pytest.approx(w.max_pressure, rel=1e-12)


def test_westergaard_closes_at_full_contact_pressure():
    p_star = reference.full_contact_pressure(DELTA, LAM, E_STAR)
    x = np.linspace(-LAM, LAM, 401)
    below = reference.westergaard(p_star * (1 - 1e-12), LAM, DELTA, E_STAR)
    at = reference.westergaard(p_star, LAM, DELTA, E_STAR)
    assert not below.full_contact and at.full_contact
    assert below.contact_fraction == pytest.approx(1.0, abs=1e-5)
    assert at.contact_fraction == 1.0 and at.contact_half_width == LAM / 2
    np.testing.assert_allclose(below.pressure(x), at.pressure(x), atol=1e-5 * p_star)
    np.testing.assert_allclose(at.pressure(x), p_star + p_star * np.cos(2 * np.pi * x / LAM),
                               rtol=1e-14, atol=1e-9 * p_star)
    assert at.max_pressure == pytest.approx(2 * p_star, rel=1e-15)
    above = reference.westergaard(1.5 * p_star, LAM, DELTA, E_STAR)
    assert above.pressure(LAM / 2) == pytest.approx(0.5 * p_star, rel=1e-12)


@pytest.mark.parametrize("ratio", [0.02, 0.3, 0.9])
def test_westergaard_profile_carries_the_load_and_satisfies_contact(ratio):
    p_star = reference.full_contact_pressure(DELTA, LAM, E_STAR)
    w = reference.westergaard(ratio * p_star, LAM, DELTA, E_STAR)
    a = w.contact_half_width
    assert w.contact_fraction == pytest.approx(2 / math.pi * math.asin(math.sqrt(ratio)), rel=1e-14)
    # the mean over a period is the load; periodic in λ, zero between the strips
    assert _quad(w.pressure, -a, a) / LAM == pytest.approx(w.mean_pressure, rel=1e-9)
    assert w.pressure(0.3 * a + 7 * LAM) == pytest.approx(w.pressure(0.3 * a), rel=1e-12)
    assert w.pressure(np.array([a, LAM / 2, -LAM / 2])).tolist() == [0.0, 0.0, 0.0]
    # contact: the displacement of the profile (half-space response 2 p_k / (E* q_k)) follows
    # the surface inside the strips and stays below it outside
    n = 2**16
    x = np.arange(n) * LAM / n
    p = w.pressure(x)
    assert (p >= 0).all()
    pk = np.fft.rfft(p)
    q = 2 * np.pi * np.fft.rfftfreq(n, d=LAM / n)
    uk = np.zeros_like(pk)
    uk[1:] = 2 * pk[1:] / (E_STAR * q[1:])
    u = np.fft.irfft(uk, n)
    gap = DELTA * np.cos(2 * np.pi * x / LAM) - u  # surface minus displacement, up to a constant
    xw = x - LAM * np.round(x / LAM)
    inside, outside = np.abs(xw) < 0.95 * a, np.abs(xw) > 1.05 * a
    top = gap[inside].mean()
    assert np.ptp(gap[inside]) < 1e-6 * DELTA
    assert gap[outside].max() < top


# --------------------------------------------------------------------------- cone
def test_cone_force_and_gap_from_the_profile():
    c = reference.cone(100.0, 0.1, E_STAR)
    a = c.contact_radius
    force = _quad(lambda r: c.pressure(r) * 2 * math.pi * r, 0.0, a)
    assert force == pytest.approx(100.0, rel=1e-9)
    assert c.mean_pressure == pytest.approx(force / (math.pi * a**2), rel=1e-9)
    assert 2 * E_STAR * c.approach**2 / (math.pi * c.slope) == pytest.approx(100.0, rel=1e-13)
    for r in (0.0, 0.4 * a, 0.8 * a):
        u = _boussinesq(c.pressure, r, a, E_STAR)
        assert u == pytest.approx(c.approach - r * c.slope, rel=1e-10)
    assert c.pressure(0.0) == math.inf and c.pressure(a) == 0.0 and c.pressure(-2 * a) == 0.0


def test_cone_mean_pressure_is_the_asperity_model_with_sneddon_cone_factor():
    n, slope = 101, 0.1
    dx = 1e-3 / (n - 1)
    x = (np.arange(n) - (n - 1) // 2) * dx
    s = contact.Surface(-slope * np.hypot(x[:, None], x[None, :]), dx)
    res = contact.solve_displacement(s, -20e-6, E, NU, cone_factor=0.5)
    p_m = res.asperities["p_m"].iloc[0]
    assert p_m == pytest.approx(reference.cone(1.0, slope, E_STAR).mean_pressure, rel=1e-12)


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf, True, "1", None, [1.0]])
def test_arguments_must_be_positive_finite_numbers(bad):
    with pytest.raises(ValueError, match="force must be a positive finite"):
        reference.hertz_sphere(bad, 0.01, E_STAR)
    with pytest.raises(ValueError, match="E_star must be a positive finite"):
        reference.hertz_sphere(1.0, 0.01, bad)
    with pytest.raises(ValueError, match="mean_pressure must be a positive finite"):
        reference.westergaard(bad, LAM, DELTA, E_STAR)
    with pytest.raises(ValueError, match="amplitude must be a positive finite"):
        reference.westergaard(1e6, LAM, bad, E_STAR)
    with pytest.raises(ValueError, match="slope must be a positive finite"):
        reference.cone(1.0, bad, E_STAR)


@pytest.mark.parametrize("bad", [(1e-3,), (1e-3, 1e-3, 1e-3), (1e-3, 0.0), (math.nan, 1e-3)])
def test_wavelength_is_a_number_or_a_pair(bad):
    with pytest.raises(ValueError, match="wavelength"):
        reference.full_contact_pressure(1e-6, bad, E_STAR)
    with pytest.raises(ValueError, match="wavelength"):
        reference.sinusoidal_displacement(1e6, bad, E_STAR)
