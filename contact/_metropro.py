"""Zygo MetroPro ``.dat`` files: the binary phase maps of Zygo interferometers.

The layout follows the MetroPro Reference Guide (Zygo, OMP-0347): a big-endian header of
834 bytes (header formats 1 and 2) or 4096 bytes (format 3), then the intensity data
(``ac_n_bytes``: 16-bit counts, skipped) and the phase data (``cn_n_bytes``: one 32-bit
signed integer per point, ``cn_org_height`` rows of ``cn_org_width`` values). A phase value
of 2147483640 or more marks an invalid point. A height is, in metres,

    value * intf_scale_factor * obliquity_factor * wavelength_in / R

with R = 4096, 32768 or 131072 for ``phase_res`` 0, 1 or 2, negated when ``phase_sign`` is
set; the spacing is ``lateral_res`` (metres per camera pixel; 0 when not calibrated).
"""

from __future__ import annotations

import math
import os
import struct
from pathlib import Path

import numpy as np

from .errors import TopographyFileError

__all__ = ["is_metropro", "read_metropro"]

#: Magic number of each header format.
MAGIC = {b"\x88\x1b\x03\x6f": 1, b"\x88\x1b\x03\x70": 2, b"\x88\x1b\x03\x71": 3}
_HEADER_SIZE = {1: 834, 2: 834, 3: 4096}
_PHASE_RES = {0: 4096, 1: 32768, 2: 131072}
_INVALID = 2147483640


def is_metropro(path: str | os.PathLike) -> bool:
    """True when the file starts with a MetroPro magic number."""
    try:
        with open(path, "rb") as fh:
            return fh.read(4) in MAGIC
    except OSError:
        return False


def _fields(header: bytes) -> dict[str, int | float]:
    """The header fields that locate and scale the phase data."""
    names_offsets = {
        "header_format": (">H", 4), "header_size": (">i", 6),
        "ac_width": (">H", 52), "ac_height": (">H", 54), "ac_buckets": (">H", 56),
        "ac_n_bytes": (">i", 60),
        "cn_width": (">H", 68), "cn_height": (">H", 70), "cn_n_bytes": (">i", 72),
        "intf_scale_factor": (">f", 164), "wavelength_in": (">f", 168),
        "obliquity_factor": (">f", 176), "lateral_res": (">f", 184),
        "phase_res": (">h", 218), "phase_sign": (">h", 232),
    }
    return {name: struct.unpack_from(fmt, header, offset)[0]
            for name, (fmt, offset) in names_offsets.items()}


def read_metropro(path: str | os.PathLike, fname: str
                  ) -> tuple[np.ndarray, float | None, float | None, np.ndarray | None]:
    """Read the phase map of a MetroPro ``.dat`` file as heights.

    Parameters
    ----------
    path : str or path-like
        The file.
    fname : str
        The file's name, for messages.

    Returns
    -------
    heights : ndarray of float64, shape (nx, ny)
        Heights in metres (axis 0 along the camera's rows, ``cn_org_width`` points), NaN at
        invalid points.
    dx, dy : float or None
        The lateral resolution in metres (the same along x and y); None when the file is not
        laterally calibrated.
    mask : ndarray of bool or None
        True at invalid points, None when every point is valid.

    Raises
    ------
    TopographyFileError
        No MetroPro magic number, a header size or phase resolution the format does not
        define, no phase data, a file shorter than its header declares, or a wavelength or
        scale that is not a finite number.
    """
    p = Path(path)
    size = p.stat().st_size
    with open(p, "rb") as fh:
        header = fh.read(834)
    if header[:4] not in MAGIC or len(header) < 834:
        raise TopographyFileError(f"{fname}: not a MetroPro file (no MetroPro header)")
    f = _fields(header)
    fmt = MAGIC[header[:4]]
    phase_res = int(f["phase_res"])
    if f["header_size"] != _HEADER_SIZE[fmt]:
        raise TopographyFileError(
            f"{fname}: MetroPro header format {fmt} declares a header of {f['header_size']} "
            f"bytes; the format defines {_HEADER_SIZE[fmt]}"
        )
    if phase_res not in _PHASE_RES:
        raise TopographyFileError(
            f"{fname}: unknown MetroPro phase resolution {f['phase_res']} (expected 0, 1 or 2)"
        )
    nx, ny = int(f["cn_width"]), int(f["cn_height"])
    if nx * ny == 0 or f["cn_n_bytes"] == 0:
        raise TopographyFileError(f"{fname}: holds no phase data (an intensity image only)")
    if f["cn_n_bytes"] != 4 * nx * ny:
        raise TopographyFileError(
            f"{fname}: declares {f['cn_n_bytes']} bytes of phase data for {nx} x {ny} points, "
            f"which need {4 * nx * ny} (corrupt header)"
        )
    ac_bytes = 2 * int(f["ac_buckets"]) * int(f["ac_width"]) * int(f["ac_height"])
    if f["ac_n_bytes"] != ac_bytes:
        raise TopographyFileError(
            f"{fname}: declares {f['ac_n_bytes']} bytes of intensity data for "
            f"{f['ac_buckets']} x {f['ac_width']} x {f['ac_height']} counts, which need "
            f"{ac_bytes} (corrupt header)"
        )
    start = int(f["header_size"]) + ac_bytes
    if size < start + 4 * nx * ny:
        raise TopographyFileError(
            f"{fname}: holds {size} bytes, but its header declares {start + 4 * nx * ny} "
            "(truncated file)"
        )
    scale = (f["intf_scale_factor"] * f["obliquity_factor"] * f["wavelength_in"]
             / _PHASE_RES[phase_res])
    if not (math.isfinite(scale) and f["wavelength_in"] > 0):
        raise TopographyFileError(
            f"{fname}: wavelength {f['wavelength_in']!r} m, scale factor "
            f"{f['intf_scale_factor']!r} and obliquity {f['obliquity_factor']!r} give no "
            "finite height scale"
        )
    if f["phase_sign"]:
        scale = -scale
    raw = np.fromfile(p, dtype=">i4", count=nx * ny, offset=start).reshape(ny, nx)
    invalid = raw.T >= _INVALID
    heights = raw.T.astype(np.float64, order="C") * scale
    heights[invalid] = np.nan
    lateral = f["lateral_res"]
    dx = float(lateral) if math.isfinite(lateral) and lateral > 0 else None
    return heights, dx, dx, (invalid if invalid.any() else None)
