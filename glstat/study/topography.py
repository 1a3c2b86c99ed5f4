"""One measured topography as the study uses it: read (:func:`contact.read`), checked against the
SHA-256 recorded when the campaign started, its form removed; and the RMS height of the
measured points."""

from __future__ import annotations

import hashlib
import os
from typing import Any

import numpy as np

__all__ = ["FORMS", "file_digest", "measured_rq", "read_topography", "remove_form"]

#: Form removal applied to each measured file: the least-squares plane, the mean, or nothing.
FORMS = ("plane", "mean", "none")
def file_digest(path: str | os.PathLike) -> str:
    """SHA-256 of a file's bytes (hex), read in blocks."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def remove_form(surface: Any, form: str) -> Any:
    """``surface`` less its least-squares plane (``"plane"``) or mean (``"mean"``), fitted on
    the measured points, or unchanged (``"none"``)."""
    if form not in FORMS:
        raise ValueError(f"form must be one of {', '.join(FORMS)}, got {form!r}")
    return surface if form == "none" else surface.detrend(form)


def read_topography(path: str | os.PathLike, form: str, digest: str | None = None) -> Any:
    """Read one measured file (:func:`contact.read`) and remove its form; with ``digest``,
    refuse a file whose content changed since the campaign started."""
    import contact

    if digest is not None and file_digest(path) != digest:
        raise ValueError(
            f"{os.fspath(path)} changed since the campaign in this directory started (its SHA-256 "
            f"differs); results of the old and new file must not be mixed: restore the file, or "
            f"start over with --force or another --out")
    return remove_form(contact.read(path), form)


def measured_rq(surface: Any) -> float:
    """RMS height (m) of a surface's measured points about their mean."""
    h = surface.heights if surface.mask is None else surface.heights[~np.asarray(surface.mask, bool)]
    return float(np.sqrt(np.mean((h - h.mean()) ** 2)))
