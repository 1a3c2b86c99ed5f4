"""Reading heights from ``.npy`` arrays and ``.npz`` archives.

Every ``.npy`` header (dtype, shape, data size) is checked before its data are read, so a
file that declares more data than it holds, or objects instead of numbers, reserves no
memory and runs no code. The readers return what the file stores: heights (m), the spacing
(m) when stored, and the mask.
"""

from __future__ import annotations

import math
import os
import zipfile
from collections.abc import Callable

import numpy as np

from ._zip import DEFLATE_MAX_RATIO, READ_ERRORS, check_declared_heights, check_zip_member
from .errors import TopographyFileError

__all__ = ["read_npy", "read_npz"]

#: What a reader returns: heights (m), the stored spacing dx, dy (m, None when the file
#: stores none) and the mask of missing points (or None).
Stored = tuple[np.ndarray, float | None, float | None, np.ndarray | None]


def _check_heights_header(dtype: np.dtype, shape: tuple, what: str, fname: str) -> None:
    """Refuse heights that are not a 2-D array of real numbers, from the dtype and shape
    declared in a ``.npy`` header (before any data are read)."""
    if dtype.kind not in "iuf" or dtype.fields is not None or dtype.subdtype is not None:
        raise TopographyFileError(
            f"{fname}: {what} has dtype {dtype}; heights must be real numbers "
            "(integer or floating point)"
        )
    if len(shape) != 2:
        raise TopographyFileError(f"{fname}: {what} is {len(shape)}-D; a 2-D height map is needed")


def _heights_array(h: np.ndarray, what: str, fname: str) -> np.ndarray:
    """A 2-D array of real numbers (integer or floating point) as float64."""
    _check_heights_header(h.dtype, h.shape, what, fname)
    return h.astype(float)


def _npy_header(fh, fname: str, what: str) -> tuple[np.dtype, tuple, int]:
    """dtype, shape and data size in bytes declared by the ``.npy`` header at ``fh``."""
    try:
        version = np.lib.format.read_magic(fh)
        if version == (1, 0):
            shape, _fortran, dtype = np.lib.format.read_array_header_1_0(fh)
        elif version in ((2, 0), (3, 0)):
            shape, _fortran, dtype = np.lib.format.read_array_header_2_0(fh)
        else:
            raise ValueError(f"unknown .npy format version {version}")
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: not a readable .npy array (truncated?): {what} has an unreadable "
            f"header ({type(exc).__name__}: {exc})"
        ) from None
    if dtype.hasobject:
        raise TopographyFileError(
            f"{fname}: {what} has dtype {dtype} (Python objects); heights must be real numbers "
            "(integer or floating point)"
        )
    count = math.prod(int(n) for n in shape)
    return dtype, tuple(int(n) for n in shape), count * dtype.itemsize


def _load_npy(fh, fname: str, what: str, available: int) -> np.ndarray:
    """Read the array at ``fh`` whose header was checked, refusing a header that declares more
    data than the ``available`` bytes hold (no memory is reserved for such a header)."""
    start = fh.tell()
    dtype, shape, nbytes = _npy_header(fh, fname, what)
    stored = available - (fh.tell() - start)
    if nbytes != stored:
        raise TopographyFileError(
            f"{fname}: not a readable .npy array (truncated?): {what} declares shape {shape} of "
            f"{dtype} ({nbytes} bytes) but holds {stored} bytes of data"
        )
    fh.seek(start)
    try:
        return np.lib.format.read_array(fh, allow_pickle=False)
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: not a readable .npy array (truncated?): {what}: {type(exc).__name__}: {exc}"
        ) from None


def _stored_spacing(content: dict, name: str, fname: str) -> float | None:
    """A spacing stored in an .npz archive: a finite positive real scalar (m), or None."""
    if name not in content:
        return None
    v = content[name]
    if v.dtype.kind not in "iuf" or v.ndim != 0:
        raise TopographyFileError(
            f"{fname}: {name!r} must be a real scalar in metres, got an array of shape "
            f"{v.shape} and dtype {v.dtype}"
        )
    value = float(v)
    if not (math.isfinite(value) and value > 0):
        raise TopographyFileError(
            f"{fname}: {name!r} must be a positive finite spacing in metres, got {value!r}"
        )
    return value


def read_npy(path: os.PathLike, fname: str) -> Stored:
    """Heights of a ``.npy`` file (no spacing, no mask).

    Parameters
    ----------
    path : path-like
        The file.
    fname : str
        The file's name, for messages.

    Returns
    -------
    heights : ndarray of float64, shape (nx, ny)
        The stored array, in metres.
    dx, dy : None
        A ``.npy`` file stores no spacing.
    mask : None

    Raises
    ------
    TopographyFileError
        Not a readable ``.npy`` file, or not a 2-D array of real numbers.
    """
    try:
        # the file is opened here so that it is closed even when numpy fails to parse it
        with open(path, "rb") as fh:
            dtype, shape, _ = _npy_header(fh, fname, "the array")
            _check_heights_header(dtype, shape, "the array", fname)
            fh.seek(0)
            h = _load_npy(fh, fname, "the array", os.fstat(fh.fileno()).st_size)
    except OSError as exc:
        raise TopographyFileError(f"{fname}: not a readable .npy array: {exc}") from None
    return _heights_array(h, "the array", fname), None, None, None


def _npz_member(archive: zipfile.ZipFile, info: zipfile.ZipInfo, name: str, fname: str,
                limit: int, check: Callable[[np.dtype, tuple], None] | None = None) -> np.ndarray:
    """One array of an .npz archive, its zip entry and .npy header checked before reading."""
    what = repr(name)
    check_zip_member(info, fname, what, limit=limit)
    try:
        with archive.open(info) as f:
            dtype, shape, _ = _npy_header(f, fname, what)
            if check is not None:
                check(dtype, shape)
        with archive.open(info) as f:
            return _load_npy(f, fname, what, info.file_size)
    except TopographyFileError:
        raise
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: not a readable .npz archive (truncated?): {what}: {type(exc).__name__}: "
            f"{exc}"
        ) from None


def read_npz(path: os.PathLike, fname: str) -> Stored:
    """Heights, spacing and mask of an ``.npz`` archive written by :func:`contact.write`.

    Parameters
    ----------
    path : path-like
        The archive: ``heights`` (2-D, m), optional scalars ``dx`` and ``dy`` (m) and an
        optional boolean ``mask``; other members are never read.
    fname : str
        The file's name, for messages.

    Returns
    -------
    heights : ndarray of float64, shape (nx, ny)
        Heights in metres.
    dx, dy : float or None
        The stored spacing in metres, None when absent.
    mask : ndarray or None
        The stored mask (True at missing points), None when absent.

    Raises
    ------
    TopographyFileError
        Not a readable archive, no ``heights``, a member whose header or zip entry is
        refused, a spacing that is not a positive finite scalar, a mask of another shape.
    """
    content: dict[str, np.ndarray] = {}
    try:
        with zipfile.ZipFile(path) as archive:
            infos = {i.filename.removesuffix(".npy"): i for i in archive.infolist()}
            if "heights" not in infos:
                raise TopographyFileError(
                    f"{fname}: no 'heights' array (found {sorted(infos)}); save with "
                    "Surface.write or numpy.savez(path, heights=..., dx=..., dy=...)"
                )
            # a member may not declare more than Deflate can expand the whole file to
            size = os.path.getsize(path)
            limit = max(size, 1) * DEFLATE_MAX_RATIO + 2**20

            def check(dtype: np.dtype, shape: tuple) -> None:
                _check_heights_header(dtype, shape, "'heights'", fname)
                check_declared_heights(math.prod(shape), size, fname,
                                       f"'heights' (shape {shape})")

            h = _npz_member(archive, infos["heights"], "heights", fname, limit, check)
            content["heights"] = h
            for name in ("dx", "dy"):
                if name in infos:
                    content[name] = _npz_member(archive, infos[name], name, fname, 2**16)
            if "mask" in infos:
                content["mask"] = _npz_member(archive, infos["mask"], "mask", fname,
                                              h.size * 8 + 2**16)
    except TopographyFileError:
        raise
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: not a readable .npz archive (truncated?): {exc}"
        ) from None
    h = _heights_array(content["heights"], "'heights'", fname)
    dx, dy = (_stored_spacing(content, k, fname) for k in ("dx", "dy"))
    mask = content.get("mask")
    if mask is not None and (mask.dtype.kind not in "biu" or mask.shape != h.shape):
        raise TopographyFileError(
            f"{fname}: mask must be a boolean array of the heights' shape {h.shape}, got shape "
            f"{mask.shape} and dtype {mask.dtype}"
        )
    return h, dx, dy, mask
