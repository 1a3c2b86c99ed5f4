"""Exceptions and warnings of the contact package."""

from __future__ import annotations

__all__ = ["ContactWarning", "TopographyFileError"]


class TopographyFileError(ValueError):
    """A topography file is corrupt, truncated or inconsistent; nothing was read from it."""


class ContactWarning(UserWarning):
    """A result of the contact package is valid but limited in a way the caller must know.

    Raised, for example, when a requested load falls inside a jump of the asperity model's
    force (no physical state carries it exactly) or when a surface has no physical Hurst
    exponent.
    """
