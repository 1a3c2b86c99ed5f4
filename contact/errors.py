"""Exceptions of the contact package."""

from __future__ import annotations

__all__ = ["TopographyFileError"]


class TopographyFileError(ValueError):
    """A topography file is corrupt, truncated or inconsistent; nothing was read from it."""
