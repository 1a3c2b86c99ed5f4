"""ISO 25178-72 (ISO 5436-2) X3P files: a zip archive with ``main.xml`` and binary point data.

Supported: areal surfaces (feature type ``SUR``) on a regular grid (x and y axes of type
``I``, incremental), one z layer, data types I (int16), L (int32), F (float32) and D
(float64), binary point data (``PointDataLink``) or an inline ``DataList``, optional
validity bits (``ValidPointsLink``), and the MD5 checksums of the point data and of
``main.xml``, which are verified when present.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import io
import os
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np

from .errors import TopographyFileError

__all__ = ["read_x3p", "write_x3p"]

_NS = "http://www.opengps.eu/2008/ISO5436_2"
_DTYPES = {"I": "<i2", "L": "<i4", "F": "<f4", "D": "<f8"}


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _find(node: ET.Element, path: str) -> ET.Element | None:
    """Find a descendant by a '/'-separated path of local tag names (namespaces ignored)."""
    for name in path.split("/"):
        if node is None:
            return None
        node = next((c for c in node if _local(c.tag) == name), None)
    return node


def _text(root: ET.Element, path: str, fname: str, default: str | None = None) -> str:
    node = _find(root, path)
    if node is None or node.text is None or not node.text.strip():
        if default is not None:
            return default
        raise TopographyFileError(f"{fname}: main.xml has no {path.replace('/', ' > ')}")
    return node.text.strip()


def _number(root, path, fname, kind=float, default=None):
    raw = _text(root, path, fname, None if default is None else str(default))
    try:
        return kind(raw)
    except ValueError:
        raise TopographyFileError(
            f"{fname}: {path.replace('/', ' > ')} should be a number, got {raw!r}"
        ) from None


def _member(archive: zipfile.ZipFile, name: str, fname: str) -> bytes:
    names = {n.lower().lstrip("/"): n for n in archive.namelist()}
    key = name.replace("\\", "/").lower().lstrip("/")
    if key not in names:
        if key == "main.xml":
            raise TopographyFileError(
                f"{fname}: not a valid X3P file: the archive lacks 'main.xml', the "
                "description every X3P file starts with"
            )
        raise TopographyFileError(f"{fname}: the archive lacks {name!r} (listed in main.xml)")
    try:
        return archive.read(names[key])
    except (zipfile.BadZipFile, OSError, EOFError, ValueError) as exc:
        raise TopographyFileError(
            f"{fname}: cannot read {name!r} from the archive: {exc}"
        ) from None


def read_x3p(path: str | os.PathLike) -> tuple[np.ndarray, float, float, np.ndarray | None]:
    """Read an X3P file.

    Parameters
    ----------
    path : str or path-like
        The ``.x3p`` file.

    Returns
    -------
    heights : ndarray, shape (nx, ny)
        Heights in metres (axis 0 along x), NaN at invalid points.
    dx, dy : float
        Grid spacing in metres.
    mask : ndarray of bool or None
        True at invalid points, None when every point is valid.

    Raises
    ------
    TopographyFileError
        The file is not a zip archive, is truncated, fails a checksum, or its ``main.xml``
        is missing, malformed or describes something other than a regular areal grid.
    """
    fname = os.fspath(path)
    try:
        with open(fname, "rb") as fh:
            blob = fh.read()
    except OSError as exc:
        raise TopographyFileError(f"{fname}: cannot open: {exc}") from None
    try:
        archive = zipfile.ZipFile(io.BytesIO(blob))
    except (zipfile.BadZipFile, OSError, EOFError, ValueError) as exc:
        raise TopographyFileError(
            f"{fname}: not a valid X3P file (not a readable zip archive; truncated?): {exc}"
        ) from None
    with archive:
        xml_bytes = _member(archive, "main.xml", fname)
        try:
            root = ET.fromstring(xml_bytes)
        except ET.ParseError as exc:
            raise TopographyFileError(f"{fname}: main.xml is not well-formed XML: {exc}") from None
        checksum_name = _text(root, "Record4/ChecksumFile", fname, default="")
        if checksum_name:
            listed = _member(archive, checksum_name, fname).decode("ascii", "replace").split()
            if listed and listed[0].lower() != hashlib.md5(xml_bytes).hexdigest():
                raise TopographyFileError(f"{fname}: main.xml does not match its MD5 checksum")
        feature = _text(root, "Record1/FeatureType", fname)
        if feature != "SUR":
            raise TopographyFileError(
                f"{fname}: feature type {feature!r} is not an areal surface ('SUR'); "
                "profiles and point clouds are not supported"
            )
        for axis in ("CX", "CY"):
            kind = _text(root, f"Record1/Axes/{axis}/AxisType", fname)
            if kind != "I":
                raise TopographyFileError(
                    f"{fname}: axis {axis} has type {kind!r}; only regular grids (type 'I') "
                    "are supported"
                )
        dx = _number(root, "Record1/Axes/CX/Increment", fname)
        dy = _number(root, "Record1/Axes/CY/Increment", fname)
        ztype = _text(root, "Record1/Axes/CZ/DataType", fname, default="D")
        if ztype not in _DTYPES:
            raise TopographyFileError(
                f"{fname}: unknown z data type {ztype!r}; expected one of {sorted(_DTYPES)}"
            )
        zinc = _number(root, "Record1/Axes/CZ/Increment", fname, default=1.0)
        zoff = _number(root, "Record1/Axes/CZ/Offset", fname, default=0.0)
        nx = _number(root, "Record3/MatrixDimension/SizeX", fname, int)
        ny = _number(root, "Record3/MatrixDimension/SizeY", fname, int)
        nz = _number(root, "Record3/MatrixDimension/SizeZ", fname, int, default=1)
        if nz != 1 or nx < 1 or ny < 1:
            raise TopographyFileError(
                f"{fname}: matrix dimension {nx} x {ny} x {nz} is not a single areal layer"
            )
        npts = nx * ny
        link = _find(root, "Record3/DataLink/PointDataLink")
        datalist = _find(root, "Record3/DataList")
        valid = None
        if link is not None and link.text:
            raw = _member(archive, link.text.strip(), fname)
            want = _text(root, "Record3/DataLink/MD5ChecksumPointData", fname, default="")
            if want and want.lower() != hashlib.md5(raw).hexdigest():
                raise TopographyFileError(
                    f"{fname}: point data fail their MD5 checksum (corrupt file)"
                )
            dtype = np.dtype(_DTYPES[ztype])
            if len(raw) != npts * dtype.itemsize:
                raise TopographyFileError(
                    f"{fname}: point data hold {len(raw)} bytes, but {nx} x {ny} points of "
                    f"type {ztype} need {npts * dtype.itemsize} (truncated or corrupt file)"
                )
            values = np.frombuffer(raw, dtype=dtype).astype(np.float64)
            vlink = _find(root, "Record3/DataLink/ValidPointsLink")
            if vlink is not None and vlink.text:
                bits = _member(archive, vlink.text.strip(), fname)
                vwant = _text(root, "Record3/DataLink/MD5ChecksumValidPoints", fname, default="")
                if vwant and vwant.lower() != hashlib.md5(bits).hexdigest():
                    raise TopographyFileError(f"{fname}: validity bits fail their MD5 checksum")
                if len(bits) * 8 < npts:
                    raise TopographyFileError(
                        f"{fname}: validity bits cover {len(bits) * 8} points, need {npts}"
                    )
                valid = np.unpackbits(np.frombuffer(bits, np.uint8), bitorder="little")[:npts]
                valid = valid.astype(bool)
        elif datalist is not None:
            data = [c.text for c in datalist if _local(c.tag) == "Datum"]
            if len(data) != npts:
                raise TopographyFileError(
                    f"{fname}: the data list holds {len(data)} values, need {nx} x {ny}"
                )
            values = np.empty(npts)
            valid = np.ones(npts, dtype=bool)
            for k, t in enumerate(data):
                if t is None or not t.strip():
                    values[k], valid[k] = np.nan, False
                    continue
                try:
                    values[k] = float(t)
                except ValueError:
                    raise TopographyFileError(
                        f"{fname}: data list value {k} is not a number: {t!r}"
                    ) from None
        else:
            raise TopographyFileError(f"{fname}: main.xml links no point data")
    heights = values * zinc + zoff
    if valid is not None:
        heights[~valid] = np.nan
    # X3P stores x fastest: the flat array is (ny, nx) in C order.
    heights = heights.reshape(ny, nx).T.copy()
    missing = ~np.isfinite(heights)
    return heights, dx, dy, (missing if missing.any() else None)


def _xml(nx, ny, dx, dy, md5_data, comment):
    p = f"{{{_NS}}}"
    ET.register_namespace("p", _NS)
    root = ET.Element(p + "ISO5436_2")

    def sub(parent, tag, text=None):
        node = ET.SubElement(parent, tag)
        if text is not None:
            node.text = str(text)
        return node

    r1 = sub(root, "Record1")
    sub(r1, "Revision", "ISO5436 - 2000")
    sub(r1, "FeatureType", "SUR")
    axes = sub(r1, "Axes")
    for name, inc in (("CX", dx), ("CY", dy)):
        ax = sub(axes, name)
        sub(ax, "AxisType", "I")
        sub(ax, "DataType", "D")
        sub(ax, "Increment", repr(float(inc)))
        sub(ax, "Offset", "0")
    cz = sub(axes, "CZ")
    sub(cz, "AxisType", "A")
    sub(cz, "DataType", "D")
    r2 = sub(root, "Record2")
    sub(r2, "Date", _dt.datetime.now(_dt.UTC).replace(microsecond=0).isoformat())
    sub(r2, "Creator", "glstat contact")
    inst = sub(r2, "Instrument")
    sub(inst, "Manufacturer", "glstat")
    sub(inst, "Model", "contact.Surface")
    sub(inst, "Serial", "not available")
    sub(inst, "Version", "1")
    sub(r2, "CalibrationDate", _dt.datetime(1970, 1, 1, tzinfo=_dt.UTC).isoformat())
    probe = sub(r2, "ProbingSystem")
    sub(probe, "Type", "Software")
    sub(probe, "Identification", "glstat contact")
    sub(r2, "Comment", comment)
    r3 = sub(root, "Record3")
    dim = sub(r3, "MatrixDimension")
    sub(dim, "SizeX", nx)
    sub(dim, "SizeY", ny)
    sub(dim, "SizeZ", 1)
    link = sub(r3, "DataLink")
    sub(link, "PointDataLink", "bindata/data.bin")
    sub(link, "MD5ChecksumPointData", md5_data)
    r4 = sub(root, "Record4")
    sub(r4, "ChecksumFile", "md5checksum.hex")
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="utf-8")


def write_x3p(
    path: str | os.PathLike,
    heights: np.ndarray,
    dx: float,
    dy: float,
    mask: np.ndarray | None = None,
    comment: str = "",
) -> None:
    """Write heights (m) on a regular grid as an X3P file (float64 data, NaN for missing).

    The archive is written to a temporary file next to ``path`` and moved into place, so
    a failed write leaves no partial file.
    """
    h = np.array(heights, dtype="<f8", copy=True)
    if mask is not None:
        h[np.asarray(mask, dtype=bool)] = np.nan
    nx, ny = h.shape
    raw = np.ascontiguousarray(h.T).tobytes()
    xml = _xml(nx, ny, dx, dy, hashlib.md5(raw).hexdigest(), comment)
    target = Path(path)
    tmp = target.with_name(target.name + ".part")
    try:
        with zipfile.ZipFile(tmp, "w", compression=zipfile.ZIP_DEFLATED) as archive:
            archive.writestr("main.xml", xml)
            archive.writestr("bindata/data.bin", raw)
            archive.writestr("md5checksum.hex", f"{hashlib.md5(xml).hexdigest()} *main.xml\n")
        os.replace(tmp, target)
    finally:
        if tmp.exists():
            tmp.unlink()
