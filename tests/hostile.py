"""Hostile and broken input files, generated on demand (shared by the tests and by
``benchmarks/hostile_inputs.py``, which tallies how every one of them is handled).

Every builder writes one file into a folder and returns its path. The sizes are chosen so that
a reader without bounds would reserve hundreds of megabytes while the files stay small.
"""

from __future__ import annotations

import functools
import io
import struct
import zipfile
import zlib
from pathlib import Path

import numpy as np

#: Bytes of zeros behind the decompression bombs (a reader without bounds holds them all).
BOMB_BYTES = 128 * 2**20


@functools.lru_cache(maxsize=2)
def _zeros_deflate(n: int) -> tuple[bytes, int]:
    """A raw Deflate stream of ``n`` zero bytes and their CRC-32."""
    comp = zlib.compressobj(6, zlib.DEFLATED, -15)
    chunk = bytes(2**20)
    parts = []
    crc = 0
    for _ in range(n // len(chunk)):
        parts.append(comp.compress(chunk))
        crc = zlib.crc32(chunk, crc)
    parts.append(comp.flush())
    return b"".join(parts), crc


def raw_zip(members: list[tuple[str, bytes, int, int, int, int]]) -> bytes:
    """A zip archive from raw members ``(name, data, method, crc, declared_size, flags)``:
    the data are stored as given, so headers may lie about them."""
    out = io.BytesIO()
    central = []
    for name, data, method, crc, size, flags in members:
        offset = out.tell()
        fname = name.encode()
        out.write(struct.pack("<4s5H3L2H", b"PK\x03\x04", 20, flags, method, 0, 0x21,
                              crc, len(data), size, len(fname), 0))
        out.write(fname)
        out.write(data)
        central.append(struct.pack("<4s6H3L5H2L", b"PK\x01\x02", 20, 20, flags, method, 0, 0x21,
                                   crc, len(data), size, len(fname), 0, 0, 0, 0, 0, offset) + fname)
    start = out.tell()
    for c in central:
        out.write(c)
    end = out.tell()
    out.write(struct.pack("<4s4H2LH", b"PK\x05\x06", 0, 0, len(central), len(central),
                          end - start, start, 0))
    return out.getvalue()


def x3p_xml(nx: int, ny: int, link: str = "bindata/data.bin", ztype: str = "D") -> bytes:
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n<p:ISO5436_2 '
        'xmlns:p="http://www.opengps.eu/2008/ISO5436_2"><Record1><Revision>ISO5436 - 2000'
        "</Revision><FeatureType>SUR</FeatureType><Axes><CX><AxisType>I</AxisType><DataType>D"
        "</DataType><Increment>1e-06</Increment><Offset>0</Offset></CX><CY><AxisType>I</AxisType>"
        "<DataType>D</DataType><Increment>1e-06</Increment><Offset>0</Offset></CY><CZ><AxisType>A"
        f"</AxisType><DataType>{ztype}</DataType></CZ></Axes></Record1><Record3><MatrixDimension>"
        f"<SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataLink>"
        f"<PointDataLink>{link}</PointDataLink></DataLink></Record3></p:ISO5436_2>"
    ).encode()


def _x3p_with_data(path: Path, nx: int, ny: int, data: bytes, method: int, crc: int, size: int,
                   flags: int = 0) -> Path:
    xml = x3p_xml(nx, ny)
    path.write_bytes(raw_zip([("main.xml", xml, 0, zlib.crc32(xml), len(xml), 0),
                              ("bindata/data.bin", data, method, crc, size, flags)]))
    return path


def x3p_zip_bomb(folder: Path) -> Path:
    """main.xml declares 100 x 100 points (80 kB); the data member inflates to BOMB_BYTES."""
    data, crc = _zeros_deflate(BOMB_BYTES)
    return _x3p_with_data(folder / "bomb.x3p", 100, 100, data, 8, crc, BOMB_BYTES)


def x3p_lying_bomb(folder: Path) -> Path:
    """The member declares exactly 100 x 100 x 8 bytes but its stream inflates to BOMB_BYTES."""
    data, crc = _zeros_deflate(BOMB_BYTES)
    return _x3p_with_data(folder / "lying.x3p", 100, 100, data, 8, crc, 80_000)


def x3p_huge_grid(folder: Path) -> Path:
    """SizeX x SizeY = 1e12 points with an 8-byte data member."""
    data = bytes(8)
    return _x3p_with_data(folder / "huge.x3p", 10**6, 10**6, data, 0, zlib.crc32(data), 8)


def x3p_encrypted(folder: Path) -> Path:
    data = np.zeros(9).tobytes()
    return _x3p_with_data(folder / "encrypted.x3p", 3, 3, data, 0, zlib.crc32(data), len(data),
                          flags=0x1)


def x3p_deflate64(folder: Path) -> Path:
    raw = np.zeros(9).tobytes()
    comp = zlib.compressobj(9, zlib.DEFLATED, -15)
    data = comp.compress(raw) + comp.flush()
    return _x3p_with_data(folder / "deflate64.x3p", 3, 3, data, 9, zlib.crc32(raw), len(raw))


def x3p_broken_deflate(folder: Path) -> Path:
    raw = np.arange(400.0).tobytes()
    comp = zlib.compressobj(9, zlib.DEFLATED, -15)
    data = bytearray(comp.compress(raw) + comp.flush())
    for k in range(2, len(data) - 2, 3):
        data[k] ^= 0x5A
    return _x3p_with_data(folder / "broken.x3p", 20, 20, bytes(data), 8, zlib.crc32(raw), len(raw))


def x3p_inf(folder: Path) -> Path:
    raw = np.r_[np.zeros(7), np.inf, -np.inf].tobytes()
    return _x3p_with_data(folder / "inf.x3p", 3, 3, raw, 0, zlib.crc32(raw), len(raw))


def x3p_entity_expansion(folder: Path) -> Path:
    """A "billion laughs" main.xml."""
    ents = "".join(f'<!ENTITY e{i} "&e{i - 1};&e{i - 1};&e{i - 1};&e{i - 1};&e{i - 1};">'
                   for i in range(1, 12))
    xml = (f'<?xml version="1.0"?><!DOCTYPE r [<!ENTITY e0 "lol">{ents}]>'
           "<r><Record1><FeatureType>&e11;</FeatureType></Record1></r>").encode()
    path = folder / "laughs.x3p"
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("main.xml", xml)
    return path


def npz_junk_member(folder: Path) -> Path:
    """A valid topography plus an unused member inflating to BOMB_BYTES (a few hundred kB)."""
    buf = io.BytesIO()
    np.lib.format.write_array(buf, np.random.default_rng(0).normal(size=(16, 16)))
    heights = buf.getvalue()
    dx = io.BytesIO()
    np.lib.format.write_array(dx, np.float64(1e-6))
    junk, crc = _zeros_deflate(BOMB_BYTES)
    path = folder / "junk.npz"
    path.write_bytes(raw_zip([
        ("heights.npy", heights, 0, zlib.crc32(heights), len(heights), 0),
        ("dx.npy", dx.getvalue(), 0, zlib.crc32(dx.getvalue()), len(dx.getvalue()), 0),
        ("junk.npy", junk, 8, crc, BOMB_BYTES, 0),
    ]))
    return path


def npy_huge_header(folder: Path) -> Path:
    """A .npy header declaring 1e12 float64 values, followed by 8 bytes."""
    buf = io.BytesIO()
    np.lib.format.write_array_header_1_0(buf, {"descr": "<f8", "fortran_order": False,
                                               "shape": (10**6, 10**6)})
    path = folder / "huge.npy"
    path.write_bytes(buf.getvalue() + bytes(8))
    return path


def npz_huge_header(folder: Path) -> Path:
    path = folder / "huge.npz"
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("heights.npy", npy_huge_header(folder).read_bytes())
    return path


def npy_subarray(folder: Path) -> Path:
    path = folder / "subarray.npy"
    np.save(path, np.zeros((4, 4), dtype=[("a", "<f8", (3,))]))
    return path


def xyz_diagonal(folder: Path, n: int = 20_000) -> Path:
    """N points on a diagonal: a grid of N x N if taken at its word."""
    t = np.arange(n) * 1e-6
    path = folder / "diagonal.xyz"
    np.savetxt(path, np.column_stack([t, t, np.zeros(n)]), fmt="%.9g")
    return path


def text_inf(folder: Path) -> Path:
    path = folder / "inf.txt"
    path.write_text("# dx = 1e-6\n1 2 3\n4 inf 6\n7 8 -inf\n")
    return path


def text_underscore(folder: Path) -> Path:
    path = folder / "underscore.txt"
    path.write_text("# dx = 1e-6\n1 2 3\n4 1_000 6\n7 8 9\n")
    return path


def text_grid(folder: Path, rows: int = 300_000) -> Path:
    """A valid text grid of ``rows`` x 3 values (about 20 bytes per value)."""
    path = folder / "long.txt"
    rng = np.random.default_rng(1)
    with open(path, "w") as f:
        f.write("# dx = 1e-6\n")
        for block in range(0, rows, 50_000):
            h = rng.normal(size=(min(50_000, rows - block), 3))
            f.write("\n".join(f"{a!r} {b!r} {c!r}" for a, b, c in h.tolist()) + "\n")
    return path


def gzip_bomb(folder: Path) -> Path:
    """A .csv.gz inflating to BOMB_BYTES of zero bytes (a few hundred kB on disk)."""
    data, crc = _zeros_deflate(BOMB_BYTES)
    path = folder / "bomb.csv.gz"
    path.write_bytes(b"\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\xff" + data
                     + struct.pack("<LL", crc, BOMB_BYTES & 0xFFFFFFFF))
    return path
