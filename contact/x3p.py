"""ISO 25178-72 (ISO 5436-2) X3P files: a zip archive with ``main.xml`` and binary point data.

Supported: areal surfaces (feature type ``SUR``) on a regular grid (x and y axes of type
``I``, incremental), one z layer, data types I (int16), L (int32), F (float32) and D
(float64), binary point data (``PointDataLink``) or an inline ``DataList``, optional
validity bits (``ValidPointsLink``), and the MD5 checksums of the point data and of
``main.xml`` (the line of the checksum file that names ``main.xml``), which are verified
when present.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import os
import xml.etree.ElementTree as ET
import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._zip import DEFLATE_MAX_RATIO as DEFLATE_MAX_RATIO
from ._zip import READ_ERRORS as READ_ERRORS
from ._zip import check_declared_heights
from ._zip import check_zip_member as check_zip_member
from ._zip import read_zip_member as read_zip_member
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


def _number(root, path, fname, convert=float, default=None):
    raw = _text(root, path, fname, None if default is None else str(default))
    try:
        return convert(raw)
    except ValueError:
        raise TopographyFileError(
            f"{fname}: {path.replace('/', ' > ')} should be a number, got {raw!r}"
        ) from None


#: Largest ``main.xml`` read (bytes); inline data lists of up to a few million points fit.
MAX_XML_BYTES = 64 * 2**20


def _info(archive: zipfile.ZipFile, name: str, fname: str) -> zipfile.ZipInfo:
    """The member ``name`` as main.xml names it: the member of exactly that name, else the one
    member whose name differs only in case (files written on case-insensitive systems); two
    members of one name, or several case-folded twins and no exact one, are refused."""
    key = name.replace("\\", "/").lstrip("/")
    infos = archive.infolist()
    exact = [i for i in infos if i.filename.replace("\\", "/").lstrip("/") == key]
    folded = [i for i in infos if i.filename.replace("\\", "/").lstrip("/").lower() == key.lower()]
    found = exact or folded
    if len(found) == 1:
        return found[0]
    if exact:
        raise TopographyFileError(f"{fname}: the archive holds {len(exact)} members named {name!r}; "
                                  "keep one")
    if folded:
        raise TopographyFileError(
            f"{fname}: the archive lacks {name!r} (listed in main.xml) but holds {len(folded)} "
            f"members differing from it only in case ({', '.join(i.filename for i in folded)}); "
            "keep one")
    if key.lower() == "main.xml":
        raise TopographyFileError(
            f"{fname}: not a valid X3P file: the archive lacks 'main.xml', the "
            "description every X3P file starts with"
        )
    raise TopographyFileError(f"{fname}: the archive lacks {name!r} (listed in main.xml)")


def _member(archive: zipfile.ZipFile, name: str, fname: str, limit: int,
            exact: int | None = None, size_error: str | None = None) -> bytearray:
    """Member ``name`` (see :func:`_info`), checked by :func:`check_zip_member` and read with
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

    Notes
    -----
    Three steps: :func:`_parse` reads and checks ``main.xml``, :func:`_layout` validates
    what it declares, :func:`_decode` reads the point data it links.
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
        layout = _layout(_parse(archive, fname), fname)
        check_declared_heights(layout.nx * layout.ny, os.path.getsize(fname), fname,
                               f"main.xml ({layout.nx} x {layout.ny} points)")
        heights, mask = _decode(archive, layout, fname)
    return heights, layout.dx, layout.dy, mask


def _parse(archive: zipfile.ZipFile, fname: str) -> ET.Element:
    """The root element of ``main.xml``, checked against its MD5 checksum when one is listed.

    Parameters
    ----------
    archive : zipfile.ZipFile
        The open X3P archive.
    fname : str
        The file's name, for messages.

    Returns
    -------
    xml.etree.ElementTree.Element
        The ``ISO5436_2`` root.

    Raises
    ------
    TopographyFileError
        No ``main.xml``, one above :data:`MAX_XML_BYTES`, XML that is not well-formed, or a
        description that does not match its checksum file.
    """
    xml_bytes = _member(archive, "main.xml", fname, MAX_XML_BYTES)
    try:
        root = ET.fromstring(xml_bytes)
    except ET.ParseError as exc:
        raise TopographyFileError(f"{fname}: main.xml is not well-formed XML: {exc}") from None
    checksum_name = _text(root, "Record4/ChecksumFile", fname, default="")
    if checksum_name:
        listed = _member(archive, checksum_name, fname, 2**16).decode("utf-8", "replace")
        expected = _listed_xml_md5(listed)
        if expected is not None and expected != hashlib.md5(xml_bytes).hexdigest():
            raise TopographyFileError(
                f"{fname}: main.xml does not match its MD5 checksum in {checksum_name} "
                "(corrupt or edited file)"
            )
    return root


def _listed_xml_md5(listed: str) -> str | None:
    """The MD5 (lower-case hex) that a checksum file lists for ``main.xml``, None if none.

    ISO 25178-72 has the checksum file hold the MD5 of ``main.xml``, one line in the
    ``md5sum`` layout: 32 hex digits, a blank, ``*`` (binary mode) and the file name, e.g.
    ``f4758b0e...e781 *main.xml``, as the openGPS reference implementation writes it. Hex
    digits of either case are accepted, and a line without a name is taken as the one of
    ``main.xml``. A line naming another member (some writers list the point data,
    ``*bindata/data.bin``) says nothing about ``main.xml``; the point data are checked
    against the checksum ``main.xml`` gives them.
    """
    for line in listed.splitlines():
        parts = line.strip().split(None, 1)
        if not parts or len(parts[0]) != 32:
            continue
        digest = parts[0].lower()
        if any(c not in "0123456789abcdef" for c in digest):
            continue
        name = parts[1].strip().lstrip("*").strip() if len(parts) > 1 else ""
        if name.replace("\\", "/").lower() in ("", "main.xml", "./main.xml"):
            return digest
    return None


@dataclass(frozen=True)
class _Layout:
    """The grid and point data that ``main.xml`` declares, validated.

    Attributes
    ----------
    nx, ny : int
        Points along x and y.
    dx, dy : float
        Grid spacing in metres.
    z_type : str
        Stored type of the heights: ``"I"``, ``"L"``, ``"F"`` or ``"D"``.
    z_increment, z_offset : float
        Height in metres is ``value * z_increment + z_offset``.
    data_link, data_md5 : str
        Archive member of the binary point data and its MD5 (empty: none).
    valid_link, valid_md5 : str
        Archive member of the validity bits and its MD5 (empty: none).
    data_list : xml.etree.ElementTree.Element or None
        The inline ``DataList`` when no binary point data are linked.
    """

    nx: int
    ny: int
    dx: float
    dy: float
    z_type: str
    z_increment: float
    z_offset: float
    data_link: str
    data_md5: str
    valid_link: str
    valid_md5: str
    data_list: ET.Element | None


def _layout(root: ET.Element, fname: str) -> _Layout:
    """Validate the description in ``main.xml``: an areal surface on a regular grid.

    Parameters
    ----------
    root : xml.etree.ElementTree.Element
        The root of ``main.xml`` (see :func:`_parse`).
    fname : str
        The file's name, for messages.

    Returns
    -------
    _Layout
        Grid size and spacing (m), the height type and scale (m), the point data's source.

    Raises
    ------
    TopographyFileError
        A profile or point cloud, irregular axes, an unknown height type, a matrix that is
        not one areal layer, a missing or non-numeric entry, or no point data.
    """
    feature = _text(root, "Record1/FeatureType", fname)
    if feature != "SUR":
        raise TopographyFileError(
            f"{fname}: feature type {feature!r} is not an areal surface ('SUR'); "
            "profiles and point clouds are not supported"
        )
    for axis in ("CX", "CY"):
        axis_type = _text(root, f"Record1/Axes/{axis}/AxisType", fname)
        if axis_type != "I":
            raise TopographyFileError(
                f"{fname}: axis {axis} has type {axis_type!r}; only regular grids (type 'I') "
                "are supported"
            )
    z_type = _text(root, "Record1/Axes/CZ/DataType", fname, default="D")
    if z_type not in _DTYPES:
        raise TopographyFileError(
            f"{fname}: unknown z data type {z_type!r}; expected one of {sorted(_DTYPES)}"
        )
    nx = _number(root, "Record3/MatrixDimension/SizeX", fname, int)
    ny = _number(root, "Record3/MatrixDimension/SizeY", fname, int)
    nz = _number(root, "Record3/MatrixDimension/SizeZ", fname, int, default=1)
    if nz != 1 or nx < 1 or ny < 1:
        raise TopographyFileError(
            f"{fname}: matrix dimension {nx} x {ny} x {nz} is not a single areal layer"
        )
    data_link = _text(root, "Record3/DataLink/PointDataLink", fname, default="")
    data_list = _find(root, "Record3/DataList")
    if not data_link and data_list is None:
        raise TopographyFileError(f"{fname}: main.xml links no point data")
    return _Layout(
        nx=nx,
        ny=ny,
        dx=_number(root, "Record1/Axes/CX/Increment", fname),
        dy=_number(root, "Record1/Axes/CY/Increment", fname),
        z_type=z_type,
        z_increment=_number(root, "Record1/Axes/CZ/Increment", fname, default=1.0),
        z_offset=_number(root, "Record1/Axes/CZ/Offset", fname, default=0.0),
        data_link=data_link,
        data_md5=_text(root, "Record3/DataLink/MD5ChecksumPointData", fname, default=""),
        valid_link=_text(root, "Record3/DataLink/ValidPointsLink", fname, default=""),
        valid_md5=_text(root, "Record3/DataLink/MD5ChecksumValidPoints", fname, default=""),
        data_list=None if data_link else data_list,
    )


def _decode(archive: zipfile.ZipFile, layout: _Layout, fname: str
            ) -> tuple[np.ndarray, np.ndarray | None]:
    """The heights the layout describes, read from the archive or the inline data list.

    Parameters
    ----------
    archive : zipfile.ZipFile
        The open X3P archive.
    layout : _Layout
        The validated description (see :func:`_layout`).
    fname : str
        The file's name, for messages.

    Returns
    -------
    heights : ndarray, shape (nx, ny)
        Heights in metres (axis 0 along x), NaN at invalid points.
    mask : ndarray of bool or None
        True at invalid points, None when every point is valid.

    Raises
    ------
    TopographyFileError
        Point data or validity bits of the wrong size or failing their checksum, a data
        list of the wrong length or holding a non-number, infinite heights.
    """
    if layout.data_list is None:
        values, valid = _binary_values(archive, layout, fname)
    else:
        values, valid = _listed_values(layout, fname)
    # X3P stores x fastest: the flat array is (ny, nx) in C order; converted and scaled in
    # place, so that reading holds the stored bytes and one array of heights
    heights = np.empty((layout.nx, layout.ny))
    heights.T[...] = values.reshape(layout.ny, layout.nx)
    del values
    heights *= layout.z_increment
    heights += layout.z_offset
    if valid is not None:
        heights.T[~valid.reshape(layout.ny, layout.nx)] = np.nan
    n_inf = int(np.isinf(heights).sum())
    if n_inf:
        raise TopographyFileError(
            f"{fname}: {n_inf} height(s) are infinite; mark missing points as invalid (or NaN), "
            "not as infinite heights"
        )
    missing = np.isnan(heights)
    return heights, (missing if missing.any() else None)


def _binary_values(archive: zipfile.ZipFile, layout: _Layout, fname: str
                   ) -> tuple[np.ndarray, np.ndarray | None]:
    """Stored values (unscaled, of the stored type) of the linked point data and the validity
    bits."""
    npts = layout.nx * layout.ny
    dtype = np.dtype(_DTYPES[layout.z_type])
    need = npts * dtype.itemsize
    raw = _member(archive, layout.data_link, fname, need, exact=need, size_error=(
        f"{fname}: point data hold {{size}} bytes, but {layout.nx} x {layout.ny} points of "
        f"type {layout.z_type} need {need} (truncated or corrupt file)"))
    if layout.data_md5 and layout.data_md5.lower() != hashlib.md5(raw).hexdigest():
        raise TopographyFileError(f"{fname}: point data fail their MD5 checksum (corrupt file)")
    values = np.frombuffer(raw, dtype=dtype)
    if not layout.valid_link:
        return values, None
    bits = _member(archive, layout.valid_link, fname, (npts + 7) // 8 + 64)
    if layout.valid_md5 and layout.valid_md5.lower() != hashlib.md5(bits).hexdigest():
        raise TopographyFileError(f"{fname}: validity bits fail their MD5 checksum")
    if len(bits) * 8 < npts:
        raise TopographyFileError(
            f"{fname}: validity bits cover {len(bits) * 8} points, need {npts}"
        )
    valid = np.unpackbits(np.frombuffer(bits, np.uint8), bitorder="little")[:npts]
    return values, valid.astype(bool)


def _listed_values(layout: _Layout, fname: str) -> tuple[np.ndarray, np.ndarray]:
    """Values (float64, unscaled) of the inline data list; empty entries are invalid."""
    if layout.data_list is None:
        raise TopographyFileError(f"{fname}: main.xml links no point data")
    npts = layout.nx * layout.ny
    data = [c.text for c in layout.data_list if _local(c.tag) == "Datum"]
    if len(data) != npts:
        raise TopographyFileError(
            f"{fname}: the data list holds {len(data)} values, need {layout.nx} x {layout.ny}"
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
    return values, valid


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
