"""Elastic constants of the two bodies in contact: the contact modulus ``E*``."""

from __future__ import annotations

from collections.abc import Sequence

from _glstat_runtime.validation import elastic_constants

__all__ = ["effective_modulus"]


def effective_modulus(E: float, nu: float, counter_face: Sequence[float] | None = None, *,
                      warn: bool = True) -> float:
    """Contact modulus ``E*`` in pascals.

    Parameters
    ----------
    E : float
        Young's modulus of the rough body, Pa.
    nu : float
        Poisson ratio of the rough body, in (-1, 0.5].
    counter_face : (E2, nu2) or None
        Young's modulus (Pa) and Poisson ratio of the flat counter-face; None for a rigid
        plane.
    warn : bool, default True
        Warn (:class:`contact.ContactWarning`) when a modulus is implausibly small for
        pascals (below 1 MPa: GPa given as Pa?).

    Returns
    -------
    float
        ``E*`` with ``1/E* = (1 - nu^2)/E + (1 - nu2^2)/E2`` (the second term is 0 for a
        rigid plane), Pa.

    Raises
    ------
    ValueError
        A modulus that is not one positive finite number, a Poisson ratio outside
        (-1, 0.5], or a ``counter_face`` that is not a pair.
    """
    E, nu = elastic_constants(E, nu, warn=warn)
    inv = (1.0 - nu * nu) / E
    if counter_face is not None:
        try:
            e2, nu2 = counter_face
        except (TypeError, ValueError):
            raise ValueError(
                f"counter_face must be a pair (E2, nu2) in pascals and dimensionless, "
                f"got {counter_face!r}; use None for a rigid plane"
            ) from None
        e2, nu2 = elastic_constants(e2, nu2, which="2 (counter_face)", warn=warn)
        inv += (1.0 - nu2 * nu2) / e2
    return 1.0 / inv
