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
import lzma
import os
import xml.etree.ElementTree as ET
import zipfile
import zlib
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
    found: ET.Element | None = node
    for name in path.split("/"):
        if found is None:
            return None
        found = next((c for c in found if _local(c.tag) == name), None)
    return found


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


#: Largest expansion of a Deflate stream (the format's limit is about 1032:1); a member that
#: declares more is not a valid archive (a "zip bomb" or a corrupt header).
DEFLATE_MAX_RATIO = 1100
#: Largest ``main.xml`` read (bytes); inline data lists of up to a few million points fit.
MAX_XML_BYTES = 64 * 2**20
_READABLE = {zipfile.ZIP_STORED: "stored", zipfile.ZIP_DEFLATED: "Deflate",
             zipfile.ZIP_BZIP2: "bzip2", zipfile.ZIP_LZMA: "LZMA"}
_UNREADABLE = {9: "Deflate64", 6: "Implode", 1: "Shrink", 98: "PPMd", 99: "AES encryption",
               93: "Zstandard", 95: "XZ"}
#: What reading a damaged member may raise (zlib, bz2 and lzma errors, numpy's
#: ``_ArrayMemoryError`` for an absurd header, ...); all are the file's fault.
READ_ERRORS = (zipfile.BadZipFile, OSError, EOFError, ValueError, RuntimeError,
               NotImplementedError, MemoryError, zlib.error, lzma.LZMAError)


def check_zip_member(info: zipfile.ZipInfo, fname: str, what: str,
                     limit: int | None = None, exact: int | None = None) -> None:
    """Refuse a zip member that cannot or must not be read, before reading any of it.

    Parameters
    ----------
    info : zipfile.ZipInfo
        The member.
    fname : str
        The archive's name, for messages.
    what : str
        What the member is, for messages (e.g. ``"'bindata/data.bin'"``).
    limit : int, optional
        Largest acceptable uncompressed size in bytes.
    exact : int, optional
        The uncompressed size the member must have (e.g. SizeX x SizeY x item size).

    Raises
    ------
    TopographyFileError
        Encrypted member; a compression method zipfile cannot read (Deflate64, ...); a
        declared size larger than Deflate can produce from the stored bytes; a declared size
        above ``limit`` or different from ``exact``.
    """
    if info.flag_bits & 0x1:
        raise TopographyFileError(
            f"{fname}: {what} is encrypted; save the file again without a password"
        )
    if info.compress_type not in _READABLE:
        method = _UNREADABLE.get(info.compress_type, f"method {info.compress_type}")
        raise TopographyFileError(
            f"{fname}: {what} is compressed with {method}, which cannot be read; save the "
            f"archive again with Deflate (the zip default)"
        )
    if (info.compress_type == zipfile.ZIP_DEFLATED
            and info.file_size > DEFLATE_MAX_RATIO * info.compress_size + 4096):
        raise TopographyFileError(
            f"{fname}: {what} declares {info.file_size} bytes from {info.compress_size} "
            f"compressed bytes, more than Deflate can produce: a corrupt archive or a zip bomb"
        )
    if exact is not None and info.file_size != exact:
        raise TopographyFileError(f"{fname}: {what} holds {info.file_size} bytes, need {exact}")
    if limit is not None and info.file_size > limit:
        raise TopographyFileError(
            f"{fname}: {what} declares {info.file_size} bytes, more than the {limit} bytes "
            f"it can need"
        )


def read_zip_member(archive: zipfile.ZipFile, info: zipfile.ZipInfo, fname: str, what: str,
                    limit: int) -> bytes:
    """The bytes of a checked member, reading at most ``limit`` bytes (a member whose stream
    is longer than its declared size fails its CRC check instead of filling memory)."""
    try:
        with archive.open(info) as f:
            data = f.read(limit + 1)
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: cannot read {what} from the archive ({type(exc).__name__}: {exc})"
        ) from None
    if len(data) > limit:
        raise TopographyFileError(f"{fname}: {what} is longer than the {limit} bytes declared")
    return data


def _info(archive: zipfile.ZipFile, name: str, fname: str) -> zipfile.ZipInfo:
    names = {n.lower().lstrip("/"): n for n in archive.namelist()}
    key = name.replace("\\", "/").lower().lstrip("/")
    if key not in names:
        if key == "main.xml":
            raise TopographyFileError(
                f"{fname}: not a valid X3P file: the archive lacks 'main.xml', the "
                "description every X3P file starts with"
            )
        raise TopographyFileError(f"{fname}: the archive lacks {name!r} (listed in main.xml)")
    return archive.getinfo(names[key])


def _member(archive: zipfile.ZipFile, name: str, fname: str, limit: int,
            exact: int | None = None, size_error: str | None = None) -> bytes:
    """Member ``name`` (case-insensitive), checked by :func:`check_zip_member` and read with
    a cap of ``limit`` bytes (``exact``: the size it must have; ``size_error``: the message
    when it has another)."""
    info = _info(archive, name, fname)
    if exact is not None and info.file_size != exact and size_error is not None:
        check_zip_member(info, fname, repr(name))
        raise TopographyFileError(size_error.format(size=info.file_size))
    check_zip_member(info, fname, repr(name), limit=limit, exact=exact)
    return read_zip_member(archive, info, fname, repr(name), limit if exact is None else exact)


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
        archive = zipfile.ZipFile(fname)
    except FileNotFoundError:
        raise
    except READ_ERRORS as exc:
        raise TopographyFileError(
            f"{fname}: not a valid X3P file (not a readable zip archive; truncated?): {exc}"
        ) from None
    with archive:
        return _read_archive(archive, fname)


def _read_archive(archive: zipfile.ZipFile, fname: str):
    """The body of :func:`read_x3p` for an open archive."""
    xml_bytes = _member(archive, "main.xml", fname, MAX_XML_BYTES)
    try:
        root = ET.fromstring(xml_bytes)
    except ET.ParseError as exc:
        raise TopographyFileError(f"{fname}: main.xml is not well-formed XML: {exc}") from None
    checksum_name = _text(root, "Record4/ChecksumFile", fname, default="")
    if checksum_name:
        listed = _member(archive, checksum_name, fname, 2**16).decode("ascii", "replace").split()
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
    dtype = np.dtype(_DTYPES[ztype])
    datalist = _find(root, "Record3/DataList")
    valid = None
    if link is not None and link.text:
        need = npts * dtype.itemsize
        raw = _member(archive, link.text.strip(), fname, need, exact=need, size_error=(
            f"{fname}: point data hold {{size}} bytes, but {nx} x {ny} points of type "
            f"{ztype} need {need} (truncated or corrupt file)"))
        want = _text(root, "Record3/DataLink/MD5ChecksumPointData", fname, default="")
        if want and want.lower() != hashlib.md5(raw).hexdigest():
            raise TopographyFileError(
                f"{fname}: point data fail their MD5 checksum (corrupt file)"
            )
        values = np.frombuffer(raw, dtype=dtype).astype(np.float64)
        vlink = _find(root, "Record3/DataLink/ValidPointsLink")
        if vlink is not None and vlink.text:
            bits = _member(archive, vlink.text.strip(), fname, (npts + 7) // 8 + 64)
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
                if "_" in t:
                    raise ValueError(t)
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
    n_inf = int(np.isinf(heights).sum())
    if n_inf:
        raise TopographyFileError(
            f"{fname}: {n_inf} height(s) are infinite; mark missing points as invalid (or NaN), "
            "not as infinite heights"
        )
    missing = np.isnan(heights)
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
