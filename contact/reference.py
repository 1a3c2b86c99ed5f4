"""Analytic solutions of elastic contact, the references the contact solvers are checked against.

Frictionless normal contact of linear elastic bodies with small slopes, in SI units (metres,
newtons, pascals). Both bodies enter through the contact modulus ``E*``, with
``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2`` (``E/(1 - nu^2)`` against a rigid body), which
:func:`contact.effective_modulus` computes:

- :func:`hertz_sphere`: a sphere pressed on a flat (Hertz 1882; Johnson 1985, §4.2), and
  :func:`hertz_axis_stress`, the stresses beneath the centre of its pressure (Johnson 1985,
  §3.4);
- :func:`westergaard`: the periodic wavy surface ``h = Δ cos(2πx/λ)`` pressed on a flat,
  in partial and in full contact (Westergaard 1939; Johnson 1985, §13.2);
- :func:`full_contact_pressure` and :func:`sinusoidal_displacement`: a sinusoidal pressure and
  the sinusoidal surface displacement it causes, for the one-dimensional wavy surface and the
  two-dimensional ``cos(2πx/λx) cos(2πy/λy)`` surface (Johnson 1985, §13.2; Johnson,
  Greenwood & Higginson 1985);
- :func:`cone`: a rigid cone pressed on a flat (Sneddon 1965; Johnson 1985, ch. 5), whose mean
  pressure ``0.5 E* tan β`` is the asperity model's ``cone_factor=0.5``.

The tests and ``benchmarks/bench_bem_validation.py`` validate :func:`contact.solve_bem`
against these functions (docs/bem.md, section Validation).

References
----------
- K. L. Johnson, *Contact Mechanics*, Cambridge University Press (1985).
- H. M. Westergaard, *Bearing pressures and cracks*, J. Appl. Mech. 6 (1939) 49–53.
- K. L. Johnson, J. A. Greenwood, J. G. Higginson, *The contact of elastic regular wavy
  surfaces*, Int. J. Mech. Sci. 27 (1985) 383–396.
- I. N. Sneddon, *The relation between load and penetration in the axisymmetric Boussinesq
  problem for a punch of arbitrary profile*, Int. J. Eng. Sci. 3 (1965) 47–57.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from _glstat_runtime.validation import positive_finite, real_scalar

__all__ = [
    "Cone",
    "HertzAxisStress",
    "HertzSphere",
    "Westergaard",
    "cone",
    "full_contact_pressure",
    "hertz_axis_stress",
    "hertz_sphere",
    "sinusoidal_displacement",
    "westergaard",
]


def _as_output(p: np.ndarray):
    """A float for a scalar argument, else the array."""
    return float(p) if p.ndim == 0 else p


def _inverse_wavelength(wavelength) -> float:
    """``|q| / (2π) = sqrt(1/λx² + 1/λy²)`` in 1/m for a pair ``(λx, λy)``."""
    try:
        lx, ly = wavelength
    except (TypeError, ValueError):
        raise ValueError(
            f"wavelength must be a number or a pair (lambda_x, lambda_y) in metres, "
            f"got {wavelength!r}"
        ) from None
    lx = positive_finite(lx, "wavelength lambda_x", "length in metres")
    ly = positive_finite(ly, "wavelength lambda_y", "length in metres")
    return math.hypot(1.0 / lx, 1.0 / ly)


# --------------------------------------------------------------------------- Hertz
@dataclass(frozen=True)
class HertzSphere:
    """Hertz contact of a sphere with a flat under a force; made by :func:`hertz_sphere`.

    Attributes
    ----------
    force : float
        Normal force ``F``, N.
    radius : float
        Radius ``R`` of the sphere (or the relative radius ``1/R = 1/R1 + 1/R2`` of two
        spheres), m.
    E_star : float
        Contact modulus ``E*``, Pa.
    contact_radius : float
        Radius ``a`` of the circle of contact, m.
    max_pressure : float
        Pressure ``p0`` at the centre, Pa.
    mean_pressure : float
        ``F / (π a²) = 2 p0 / 3``, Pa.
    approach : float
        Approach ``δ = a² / R`` of distant points of the two bodies, m.
    """

    force: float
    radius: float
    E_star: float
    contact_radius: float
    max_pressure: float
    mean_pressure: float
    approach: float

    def pressure(self, r):
        """Contact pressure ``p0 sqrt(1 - r²/a²)`` at distance ``r`` from the centre, 0 outside.

        Parameters
        ----------
        r : float or array_like
            Distance from the centre of the contact, m (for example
            ``numpy.hypot(x, y)`` on a grid centred on the contact).

        Returns
        -------
        float or ndarray
            Pressure in pascals, of the shape of ``r``.
        """
        r = np.asarray(r, dtype=float)
        a = self.contact_radius
        return _as_output(self.max_pressure * np.sqrt(np.clip(1 - (r / a) ** 2, 0, None)))


def hertz_sphere(force: float, radius: float, E_star: float) -> HertzSphere:
    """Hertz solution for a sphere pressed on a flat by a normal force.

    Parameters
    ----------
    force : float
        Normal force ``F`` in newtons, > 0.
    radius : float
        Radius ``R`` of the sphere in metres, > 0 (for two spheres, ``1/R = 1/R1 + 1/R2``).
    E_star : float
        Contact modulus ``E*`` in pascals, > 0 (:func:`contact.effective_modulus`).

    Returns
    -------
    HertzSphere
        ``contact_radius`` ``a`` (m), ``max_pressure`` ``p0`` and ``mean_pressure`` (Pa),
        ``approach`` ``δ`` (m), and the profile ``pressure(r)`` (Pa).

    Raises
    ------
    ValueError
        An argument that is not one positive finite number.

    Notes
    -----
    Johnson (1985), §4.2::

        a  = (3 F R / (4 E*))^(1/3)
        p0 = 3 F / (2 π a²)                 (mean pressure 2 p0 / 3)
        δ  = a² / R                         (so F = 4/3 E* R^(1/2) δ^(3/2))
        p(r) = p0 sqrt(1 - r²/a²),  r <= a

    Valid for ``a << R`` (small slopes).

    Examples
    --------
    A steel ball of radius 10 mm on a rigid flat under 10 N:

    >>> import contact
    >>> from contact.reference import hertz_sphere
    >>> h = hertz_sphere(10.0, 0.01, contact.effective_modulus(210e9, 0.3))
    >>> print(f"a = {h.contact_radius * 1e6:.1f} um, p0 = {h.max_pressure / 1e6:.0f} MPa, "
    ...       f"delta = {h.approach * 1e6:.3f} um")
    a = 68.8 um, p0 = 1010 MPa, delta = 0.473 um
    >>> print(f"{h.pressure(0.5 * h.contact_radius) / h.max_pressure:.4f}")
    0.8660
    """
    force = positive_finite(force, "force", "value in newtons")
    radius = positive_finite(radius, "radius", "length in metres")
    E_star = positive_finite(E_star, "E_star", "modulus in pascals")
    a = (3 * force * radius / (4 * E_star)) ** (1 / 3)
    return HertzSphere(
        force=force,
        radius=radius,
        E_star=E_star,
        contact_radius=a,
        max_pressure=3 * force / (2 * math.pi * a**2),
        mean_pressure=force / (math.pi * a**2),
        approach=a**2 / radius,
    )


class HertzAxisStress(NamedTuple):
    """Stresses on the axis of a Hertzian contact; made by :func:`hertz_axis_stress`."""

    #: Radial (and hoop) stress ``σr = σθ``, Pa, compression negative.
    sigma_r: float | np.ndarray
    #: Vertical stress ``σz``, Pa.
    sigma_z: float | np.ndarray
    #: Von Mises stress ``|σr - σz|``, Pa.
    von_mises: float | np.ndarray


def hertz_axis_stress(depth, contact_radius: float, max_pressure: float, nu: float) -> HertzAxisStress:
    """Stresses beneath the centre of a Hertzian pressure ``p0 sqrt(1 - r²/a²)``.

    Parameters
    ----------
    depth : float or array_like
        Depth ``z >= 0`` below the surface on the axis, m.
    contact_radius : float
        Radius ``a`` of the contact, m, > 0.
    max_pressure : float
        Pressure ``p0`` at the centre, Pa, > 0.
    nu : float
        Poisson ratio of the body, in (-1, 0.5].

    Returns
    -------
    HertzAxisStress
        ``sigma_r``, ``sigma_z`` and ``von_mises`` in pascals (compression negative), floats
        for a scalar depth, else arrays of its shape.

    Raises
    ------
    ValueError
        A negative or non-finite depth, a radius or pressure that is not positive and finite,
        a Poisson ratio outside (-1, 0.5].

    Notes
    -----
    Johnson (1985), eq. 3.45 (§3.4, a Hertzian pressure on a half-space), with ``ζ = z/a``::

        σr = σθ = p0 [-(1 + ν) (1 - ζ arctan(1/ζ)) + 1 / (2 (1 + ζ²))]
        σz = -p0 / (1 + ζ²)

    The axis is a principal direction and ``σr = σθ``, so the von Mises stress is
    ``|σr - σz|``, twice the largest shear stress. For ν = 0.3 it peaks at ``0.6200 p0``
    at ``z = 0.4809 a`` (§4.2: the largest shear stress ``0.31 p0`` at ``0.48 a``).

    Examples
    --------
    >>> from contact.reference import hertz_axis_stress
    >>> s = hertz_axis_stress(0.4809e-3, 1e-3, 1e9, 0.3)
    >>> print(f"{s.sigma_r / 1e9:.4f} {s.sigma_z / 1e9:.4f} {s.von_mises / 1e9:.4f}")
    -0.1921 -0.8122 0.6200
    """
    z = np.asarray(depth, dtype=float)
    if not np.all(np.isfinite(z) & (z >= 0)):
        raise ValueError(f"depth must be finite and >= 0 (metres below the surface), got {depth!r}")
    a = positive_finite(contact_radius, "contact_radius", "length in metres")
    p0 = positive_finite(max_pressure, "max_pressure", "pressure in pascals")
    n = real_scalar(nu)
    if n is None or not (-1.0 < n <= 0.5):
        raise ValueError(f"nu must be a Poisson ratio in (-1, 0.5], got {nu!r}")
    zeta = z / a
    # ζ arctan(1/ζ) = ζ (π/2 - arctan ζ), 0 at the surface
    term = zeta * (0.5 * math.pi - np.arctan(zeta))
    sigma_r = p0 * (-(1.0 + n) * (1.0 - term) + 0.5 / (1.0 + zeta**2))
    sigma_z = -p0 / (1.0 + zeta**2)
    return HertzAxisStress(_as_output(sigma_r), _as_output(sigma_z), _as_output(np.abs(sigma_r - sigma_z)))


# --------------------------------------------------------------------------- wavy surfaces
def full_contact_pressure(amplitude: float, wavelength: float | Sequence[float], E_star: float) -> float:
    """Mean pressure ``p*`` that flattens a sinusoidal surface completely.

    Parameters
    ----------
    amplitude : float
        Amplitude ``Δ`` of the surface in metres, > 0: ``h = Δ cos(2πx/λ)``, or
        ``h = Δ cos(2πx/λx) cos(2πy/λy)`` in two dimensions.
    wavelength : float or (float, float)
        ``λ`` of the one-dimensional wavy surface, or ``(λx, λy)`` of the two-dimensional one,
        in metres, > 0.
    E_star : float
        Contact modulus ``E*`` in pascals, > 0.

    Returns
    -------
    float
        ``p*`` in pascals: in full contact (mean pressure ``P̄ >= p*``) the pressure is
        ``P̄ + p* cos(2πx/λ)`` (``P̄ + p* cos(2πx/λx) cos(2πy/λy)``); below ``p*`` the contact
        is partial.

    Raises
    ------
    ValueError
        An argument that is not positive and finite, or a wavelength that is neither a
        number nor a pair.

    Notes
    -----
    A pressure ``p* cos(q·x)`` on an elastic half-space displaces its surface by
    ``2 p* / (E* |q|) cos(q·x)`` (:func:`sinusoidal_displacement`); full contact needs that
    displacement to equal the surface. Hence (Johnson 1985, §13.2)::

        p* = π E* Δ / λ                               (one-dimensional)
        p* = π E* Δ sqrt(1/λx² + 1/λy²)               (two-dimensional)

    which is ``√2 π E* Δ / λ`` for ``λx = λy = λ`` (Johnson, Greenwood & Higginson 1985).

    Examples
    --------
    >>> from contact.reference import full_contact_pressure
    >>> print(f"{full_contact_pressure(1e-6, 1e-3, 230.8e9) / 1e6:.1f} MPa")
    725.1 MPa
    >>> print(f"{full_contact_pressure(1e-6, (1e-3, 1e-3), 230.8e9) / 1e6:.1f} MPa")
    1025.4 MPa
    """
    amplitude = positive_finite(amplitude, "amplitude", "length in metres")
    E_star = positive_finite(E_star, "E_star", "modulus in pascals")
    if np.ndim(wavelength) == 0:
        wavelength = positive_finite(wavelength, "wavelength", "length in metres")
        return math.pi * E_star * amplitude / wavelength
    return math.pi * E_star * amplitude * _inverse_wavelength(wavelength)


def sinusoidal_displacement(
    pressure_amplitude: float, wavelength: float | Sequence[float], E_star: float
) -> float:
    """Amplitude of the surface displacement under a sinusoidal pressure.

    Parameters
    ----------
    pressure_amplitude : float
        Amplitude ``p`` of the pressure in pascals, > 0: ``p cos(2πx/λ)``, or
        ``p cos(2πx/λx) cos(2πy/λy)`` in two dimensions.
    wavelength : float or (float, float)
        ``λ``, or ``(λx, λy)``, in metres, > 0.
    E_star : float
        Contact modulus ``E*`` in pascals, > 0.

    Returns
    -------
    float
        Amplitude ``u`` in metres of the (same-shaped) displacement of the surface towards
        the body.

    Raises
    ------
    ValueError
        An argument that is not positive and finite, or a wavelength that is neither a
        number nor a pair.

    Notes
    -----
    ``u = 2 p / (E* |q|)`` with ``|q| = 2π/λ`` (``2π sqrt(1/λx² + 1/λy²)``), i.e.
    ``u = p λ / (π E*)`` in one dimension (Johnson 1985, §13.2); the inverse of
    :func:`full_contact_pressure`.

    Examples
    --------
    >>> from contact.reference import sinusoidal_displacement
    >>> print(f"{sinusoidal_displacement(100e6, 1e-3, 230.8e9) * 1e6:.4f} um")
    0.1379 um
    """
    pressure_amplitude = positive_finite(
        pressure_amplitude, "pressure_amplitude", "pressure in pascals"
    )
    E_star = positive_finite(E_star, "E_star", "modulus in pascals")
    if np.ndim(wavelength) == 0:
        wavelength = positive_finite(wavelength, "wavelength", "length in metres")
        return pressure_amplitude * wavelength / (math.pi * E_star)
    return pressure_amplitude / (math.pi * E_star * _inverse_wavelength(wavelength))


@dataclass(frozen=True)
class Westergaard:
    """Contact of the wavy surface ``Δ cos(2πx/λ)`` with a flat; made by :func:`westergaard`.

    Attributes
    ----------
    mean_pressure : float
        Nominal (mean) pressure ``P̄``, Pa.
    wavelength : float
        ``λ``, m.
    amplitude : float
        ``Δ``, m.
    E_star : float
        Contact modulus, Pa.
    p_star : float
        Full-contact pressure ``p* = π E* Δ / λ``, Pa.
    contact_half_width : float
        Half-width ``a`` of each contact strip, centred on the crests ``x = kλ``; ``λ/2``
        in full contact, m.
    contact_fraction : float
        ``2a / λ``.
    max_pressure : float
        Pressure on the crests, ``2 sqrt(P̄ p*)`` in partial contact, ``P̄ + p*`` in full
        contact, Pa.
    full_contact : bool
        ``P̄ >= p*``.
    """

    mean_pressure: float
    wavelength: float
    amplitude: float
    E_star: float
    p_star: float
    contact_half_width: float
    contact_fraction: float
    max_pressure: float
    full_contact: bool

    def pressure(self, x):
        """Contact pressure at ``x`` (periodic, crests at ``x = kλ``).

        Parameters
        ----------
        x : float or array_like
            Position along the waves, m.

        Returns
        -------
        float or ndarray
            Pressure in pascals, of the shape of ``x``: ``P̄ + p* cos(2πx/λ)`` in full
            contact, else Westergaard's profile (see :func:`westergaard`), 0 outside the
            contact strips.
        """
        x = np.asarray(x, dtype=float)
        lam, pbar = self.wavelength, self.mean_pressure
        if self.full_contact:
            return _as_output(pbar + self.p_star * np.cos(2 * np.pi * x / lam))
        s2 = math.sin(math.pi * self.contact_half_width / lam) ** 2
        xw = x - lam * np.round(x / lam)
        p = (2 * pbar * np.cos(np.pi * xw / lam) / s2
             * np.sqrt(np.clip(s2 - np.sin(np.pi * xw / lam) ** 2, 0, None)))
        return _as_output(p)


def westergaard(mean_pressure: float, wavelength: float, amplitude: float, E_star: float) -> Westergaard:
    """Westergaard's solution for a periodic wavy surface pressed on a flat.

    Parameters
    ----------
    mean_pressure : float
        Nominal pressure ``P̄`` in pascals (force per unit nominal area), > 0.
    wavelength : float
        Wavelength ``λ`` of the surface ``h = Δ cos(2πx/λ)`` in metres, > 0.
    amplitude : float
        Amplitude ``Δ`` in metres, > 0 (peak to valley ``2Δ``).
    E_star : float
        Contact modulus ``E*`` in pascals, > 0.

    Returns
    -------
    Westergaard
        ``p_star`` (Pa), ``contact_half_width`` ``a`` (m), ``contact_fraction`` ``2a/λ``,
        ``max_pressure`` (Pa), ``full_contact`` and the profile ``pressure(x)`` (Pa).

    Raises
    ------
    ValueError
        An argument that is not one positive finite number.

    Notes
    -----
    Westergaard (1939); Johnson (1985), §13.2. With ``p* = π E* Δ / λ``
    (:func:`full_contact_pressure`), for ``P̄ < p*`` contact strips of half-width ``a``
    centred on the crests carry::

        P̄ = p* sin²(πa/λ)               i.e.  2a/λ = (2/π) asin sqrt(P̄/p*)
        p(x) = 2 P̄ cos(πx/λ) sqrt(sin²(πa/λ) - sin²(πx/λ)) / sin²(πa/λ),   |x| <= a

    and for ``P̄ >= p*`` the contact is complete, ``p(x) = P̄ + p* cos(2πx/λ)``. At light
    loads each strip is the Hertz contact of a cylinder of radius ``λ² / (4π² Δ)``.

    Examples
    --------
    >>> from contact.reference import westergaard
    >>> w = westergaard(200e6, 1e-3, 1e-6, 230.8e9)
    >>> print(f"p* = {w.p_star / 1e6:.1f} MPa, contact fraction {w.contact_fraction:.4f}, "
    ...       f"max p = {w.max_pressure / 1e6:.1f} MPa")
    p* = 725.1 MPa, contact fraction 0.3520, max p = 761.6 MPa
    >>> print(f"{w.pressure(0.0) / 1e6:.1f} MPa, {w.pressure(0.25e-3):.1f} Pa")
    761.6 MPa, 0.0 Pa
    >>> westergaard(1e9, 1e-3, 1e-6, 230.8e9).full_contact
    True
    """
    pbar = positive_finite(mean_pressure, "mean_pressure", "pressure in pascals")
    wavelength = positive_finite(wavelength, "wavelength", "length in metres")
    p_star = full_contact_pressure(amplitude, wavelength, E_star)
    ratio = pbar / p_star
    full = ratio >= 1.0
    if full:
        a, pmax = wavelength / 2, pbar + p_star
    else:
        a = wavelength / math.pi * math.asin(math.sqrt(ratio))
        pmax = 2 * math.sqrt(pbar * p_star)
    return Westergaard(
        mean_pressure=pbar,
        wavelength=wavelength,
        amplitude=float(amplitude),
        E_star=float(E_star),
        p_star=p_star,
        contact_half_width=a,
        contact_fraction=2 * a / wavelength,
        max_pressure=pmax,
        full_contact=full,
    )


# --------------------------------------------------------------------------- cone
@dataclass(frozen=True)
class Cone:
    """Contact of a rigid cone with a flat under a force; made by :func:`cone`.

    Attributes
    ----------
    force : float
        Normal force ``F``, N.
    slope : float
        ``tan β``, β the attack angle between the flank and the flat (``cot α``, α the
        half-angle of the cone).
    E_star : float
        Contact modulus, Pa.
    contact_radius : float
        Radius ``a`` of the circle of contact, m.
    mean_pressure : float
        ``F / (π a²) = E* tan β / 2``, independent of the force, Pa.
    approach : float
        Penetration ``δ = (π/2) a tan β`` of the apex, m.
    """

    force: float
    slope: float
    E_star: float
    contact_radius: float
    mean_pressure: float
    approach: float

    def pressure(self, r):
        """Contact pressure ``(E* tan β / 2) arccosh(a/r)``, infinite at the apex, 0 outside.

        Parameters
        ----------
        r : float or array_like
            Distance from the axis of the cone, m.

        Returns
        -------
        float or ndarray
            Pressure in pascals, of the shape of ``r``.
        """
        r = np.abs(np.asarray(r, dtype=float))
        with np.errstate(divide="ignore"):
            ratio = np.maximum(self.contact_radius / r, 1.0)
        return _as_output(self.mean_pressure * np.arccosh(ratio))


def cone(force: float, slope: float, E_star: float) -> Cone:
    """Sneddon's solution for a rigid cone pressed on an elastic flat by a normal force.

    Parameters
    ----------
    force : float
        Normal force ``F`` in newtons, > 0.
    slope : float
        ``tan β`` of the flanks, > 0, β the attack angle (``cot α`` for the half-angle α).
    E_star : float
        Contact modulus ``E*`` in pascals, > 0.

    Returns
    -------
    Cone
        ``contact_radius`` ``a`` (m), ``mean_pressure`` (Pa), ``approach`` ``δ`` (m) and the
        profile ``pressure(r)`` (Pa).

    Raises
    ------
    ValueError
        An argument that is not one positive finite number.

    Notes
    -----
    Sneddon (1965); Johnson (1985), ch. 5::

        F = (π/2) a² E* tan β               (mean pressure E* tan β / 2)
        δ = (π/2) a tan β                   (so F = 2 E* δ² / (π tan β))
        p(r) = (E* tan β / 2) arccosh(a/r),  r <= a

    The mean pressure is that of :func:`contact.solve` with ``cone_factor=0.5``.

    Examples
    --------
    >>> from contact.reference import cone
    >>> c = cone(100.0, 0.1, 230.8e9)
    >>> print(f"a = {c.contact_radius * 1e6:.2f} um, p_m = {c.mean_pressure / 1e9:.2f} GPa, "
    ...       f"delta = {c.approach * 1e6:.3f} um")
    a = 52.52 um, p_m = 11.54 GPa, delta = 8.250 um
    """
    force = positive_finite(force, "force", "value in newtons")
    slope = positive_finite(slope, "slope", "slope tan(beta) of the flanks")
    E_star = positive_finite(E_star, "E_star", "modulus in pascals")
    a = math.sqrt(2 * force / (math.pi * E_star * slope))
    return Cone(
        force=force,
        slope=slope,
        E_star=E_star,
        contact_radius=a,
        mean_pressure=E_star * slope / 2,
        approach=math.pi / 2 * a * slope,
    )
