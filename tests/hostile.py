"""Hostile and broken input files, generated on demand (shared by the tests and by
``benchmarks/hostile_inputs.py``, which tallies how every one of them is handled).

Every builder writes one file into a folder and returns its path. The sizes are chosen so that
a reader without bounds would reserve hundreds of megabytes while the files stay small.
"""

from __future__ import annotations

import functools
import io
import re
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


# ---------------------------------------------------------------------------------------------
# files that declare more than they hold: a tiny member behind a huge declared size
# ---------------------------------------------------------------------------------------------
_COMPRESSORS = {
    "deflate": (zipfile.ZIP_DEFLATED, lambda: zlib.compressobj(9, zlib.DEFLATED, -15)),
    "bzip2": (zipfile.ZIP_BZIP2, lambda: __import__("bz2").BZ2Compressor(9)),
    "lzma": (zipfile.ZIP_LZMA, None),
}


def _zeros_stream(method: str, n: int, stored: int) -> tuple[bytes, int]:
    """A zip member's data compressed with ``method``, of the first ``stored`` of ``n`` zero
    bytes (all of them when ``stored >= n``; the rest is never produced), and the CRC-32 of
    the ``n`` zeros (computed a MiB at a time)."""
    chunk = bytes(2**20)
    crc = 0
    for k in range(0, n, len(chunk)):
        crc = zlib.crc32(chunk[:min(len(chunk), n - k)], crc)
    todo = min(n, stored)
    if method == "lzma":
        import lzma

        # zipfile's LZMA members: a 4-byte header (version, properties size) and raw LZMA1
        comp = lzma.LZMACompressor(lzma.FORMAT_RAW, filters=[{"id": lzma.FILTER_LZMA1,
                                                               "preset": 0}])
        props = lzma._encode_filter_properties({"id": lzma.FILTER_LZMA1, "preset": 0})
        head = struct.pack("<BBH", 9, 4, len(props)) + props
    else:
        comp = _COMPRESSORS[method][1]()
        head = b""
    parts = [head]
    for k in range(0, todo, len(chunk)):
        parts.append(comp.compress(chunk[:min(len(chunk), todo - k)]))
    parts.append(comp.flush())
    return b"".join(parts), crc


def x3p_declared_grid(folder: Path, n: int = 8192, method: str = "deflate",
                      full: bool = False) -> Path:
    """main.xml declares ``n`` x ``n`` float64 points (512 MiB for 8192); the data member,
    compressed with ``method`` (deflate, bzip2, lzma), holds all of these zeros when ``full``
    (about 0.5 MB with Deflate, a few hundred bytes with bzip2), else only the first MiB."""
    size = n * n * 8
    data, crc = _zeros_stream(method, size, size if full else 2**20)
    if method == "deflate" and not full:  # as long as a real stream, within Deflate's ratio
        data += bytes(size // 1032 - len(data))
    code = _COMPRESSORS[method][0]
    return _x3p_with_data(folder / f"declared_{n}_{method}{'_full' if full else ''}.x3p", n, n,
                          data, code, crc, size)


def mat_declared(folder: Path, nx: int = 8192, ny: int = 8192, full: bool = False) -> Path:
    """A MATLAB 5 file of one ``nx`` x ``ny`` double matrix of zeros in a compressed element
    (about 0.5 MB for 8192 x 8192 when ``full``; else the stream stops after a MiB)."""
    nbytes = nx * ny * 8
    body = (struct.pack("<II", 6, 8) + struct.pack("<II", 6, 0)       # array flags: double
            + struct.pack("<II", 5, 8) + struct.pack("<ii", nx, ny)   # dimensions
            + struct.pack("<HH", 1, 1) + b"h\0\0\0"                    # name 'h' (small element)
            + struct.pack("<II", 9, nbytes))                           # real part: miDOUBLE
    comp = zlib.compressobj(9)
    parts = [comp.compress(struct.pack("<II", 14, len(body) + nbytes) + body)]
    chunk = bytes(2**20)
    todo = nbytes if full else 2**20
    for k in range(0, todo, len(chunk)):
        parts.append(comp.compress(chunk[:min(len(chunk), todo - k)]))
    parts.append(comp.flush())
    data = b"".join(parts)
    header = b"MATLAB 5.0 MAT-file, hostile test file".ljust(116) + bytes(8) + struct.pack(
        "<H", 0x0100) + b"IM"
    path = folder / f"declared_{nx}x{ny}{'_full' if full else ''}.mat"
    path.write_bytes(header + struct.pack("<II", 15, len(data)) + data)
    return path


# ---------------------------------------------------------------------------------------------
# Excel workbooks written member by member (no spreadsheet library needed)
# ---------------------------------------------------------------------------------------------
_XLSX_NS = "http://schemas.openxmlformats.org/spreadsheetml/2006/main"
_REL_NS = "http://schemas.openxmlformats.org/officeDocument/2006/relationships"


def _xlsx_parts(sheet: bytes, workbook: bytes | None = None) -> dict[str, bytes]:
    types = (
        '<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/'
        'package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.'
        'openxmlformats-package.relationships+xml"/><Default Extension="xml" ContentType='
        '"application/xml"/><Override PartName="/xl/workbook.xml" ContentType="application/vnd.'
        'openxmlformats-officedocument.spreadsheetml.sheet.main+xml"/><Override PartName="/xl/'
        'worksheets/sheet1.xml" ContentType="application/vnd.openxmlformats-officedocument.'
        'spreadsheetml.worksheet+xml"/></Types>')
    rels = (
        '<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.'
        'openxmlformats.org/package/2006/relationships"><Relationship Id="rId1" Type="http://'
        'schemas.openxmlformats.org/officeDocument/2006/relationships/officeDocument" Target='
        '"xl/workbook.xml"/></Relationships>')
    wb_rels = (
        '<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.'
        'openxmlformats.org/package/2006/relationships"><Relationship Id="rId1" Type="http://'
        'schemas.openxmlformats.org/officeDocument/2006/relationships/worksheet" Target='
        '"worksheets/sheet1.xml"/></Relationships>')
    wb = (f'<?xml version="1.0" encoding="UTF-8"?><workbook xmlns="{_XLSX_NS}" xmlns:r='
          f'"{_REL_NS}"><sheets><sheet name="Sheet1" sheetId="1" r:id="rId1"/></sheets>'
          '</workbook>').encode()
    return {"[Content_Types].xml": types.encode(), "_rels/.rels": rels.encode(),
            "xl/workbook.xml": workbook or wb, "xl/_rels/workbook.xml.rels": wb_rels.encode(),
            "xl/worksheets/sheet1.xml": sheet}


def sheet_xml(values, extra: str = "", dimension: str | None = None) -> bytes:
    """A worksheet with the header ``p`` in A1 and ``values`` below it, then ``extra`` cells
    (XML of whole rows)."""
    rows = ['<row r="1"><c r="A1" t="inlineStr"><is><t>p</t></is></c></row>']
    rows += [f'<row r="{i + 2}"><c r="A{i + 2}"><v>{v!r}</v></c></row>'
             for i, v in enumerate(values)]
    dim = f'<dimension ref="{dimension}"/>' if dimension else ""
    return (f'<?xml version="1.0" encoding="UTF-8"?><worksheet xmlns="{_XLSX_NS}">{dim}'
            f'<sheetData>{"".join(rows)}{extra}</sheetData></worksheet>').encode()


def write_xlsx(path: Path, sheet: bytes, workbook: bytes | None = None) -> Path:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in _xlsx_parts(sheet, workbook).items():
            z.writestr(name, data)
    return path


def _sample_values(n: int = 200) -> list[float]:
    return np.random.default_rng(3).gamma(4.0, 1.0, size=n).round(6).tolist()


def xlsx_valid(folder: Path) -> Path:
    return write_xlsx(folder / "valid.xlsx", sheet_xml(_sample_values()))


def xlsx_overflow_cell(folder: Path) -> Path:
    """200 values and one cell of 1E+400, beyond the floating-point range."""
    over = '<row r="202"><c r="A202"><v>1E+400</v></c></row>'
    return write_xlsx(folder / "overflow_cell.xlsx", sheet_xml(_sample_values(), over))


def xlsx_far_cell(folder: Path) -> Path:
    """200 values in column A and one more in the last cell of a sheet, XFD1048576."""
    far = '<row r="1048576"><c r="XFD1048576"><v>1</v></c></row>'
    return write_xlsx(folder / "far_cell.xlsx", sheet_xml(_sample_values(), far))


def xlsx_far_dimension(folder: Path) -> Path:
    """200 values whose sheet declares the used range A1:XFD1048576."""
    return write_xlsx(folder / "far_dimension.xlsx",
                      sheet_xml(_sample_values(), dimension="A1:XFD1048576"))


def xlsx_malformed(folder: Path) -> Path:
    """A sheet whose XML stops in the middle of a cell."""
    return write_xlsx(folder / "malformed.xlsx", sheet_xml(_sample_values())[:-60])


def xlsx_billion_laughs(folder: Path) -> Path:
    """A workbook part with nested entities (a "billion laughs")."""
    ents = "".join(f'<!ENTITY e{i} "&e{i - 1};&e{i - 1};&e{i - 1};&e{i - 1};&e{i - 1};&e{i - 1};'
                   f'&e{i - 1};&e{i - 1};&e{i - 1};&e{i - 1};">' for i in range(1, 10))
    wb = (f'<?xml version="1.0" encoding="UTF-8"?><!DOCTYPE workbook [<!ENTITY e0 "lol">{ents}]>'
          f'<workbook xmlns="{_XLSX_NS}" xmlns:r="{_REL_NS}"><sheets><sheet name="&e9;" '
          'sheetId="1" r:id="rId1"/></sheets></workbook>').encode()
    return write_xlsx(folder / "laughs.xlsx", sheet_xml(_sample_values()), wb)


def xlsx_big_sheet(folder: Path, mib: int = 200) -> Path:
    """A sheet of about ``mib`` MiB of XML: one column of numbers (a few MB compressed)."""
    path = folder / f"big_{mib}.xlsx"
    rng = np.random.default_rng(4)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as z:
        for name, data in _xlsx_parts(b"").items():
            if name != "xl/worksheets/sheet1.xml":
                z.writestr(name, data)
        with z.open("xl/worksheets/sheet1.xml", "w", force_zip64=True) as f:
            f.write(f'<?xml version="1.0" encoding="UTF-8"?><worksheet xmlns="{_XLSX_NS}">'
                    '<sheetData><row r="1"><c r="A1" t="inlineStr"><is><t>p</t></is></c></row>'
                    .encode())
            written, row = 0, 2
            while written < mib * 2**20:
                v = rng.gamma(4.0, 1.0, size=10_000).round(6)
                block = "".join(f'<row r="{row + i}"><c r="A{row + i}"><v>{x!r}</v></c></row>'
                                for i, x in enumerate(v.tolist())).encode()
                f.write(block)
                written += len(block)
                row += v.size
            f.write(b"</sheetData></worksheet>")
    return path


# ---------------------------------------------------------------------------------------------
# Parquet columns that are no column of numbers
# ---------------------------------------------------------------------------------------------
def parquet_nested(folder: Path, kind: str) -> Path:
    """A Parquet file whose column ``p`` holds ``kind``: list, struct, map, fixed_list, or
    ``duplicate`` (two columns named ``p``)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    x = _sample_values(20)
    col = {"list": lambda: pa.array([[v, v] for v in x]),
           "struct": lambda: pa.array([{"a": v, "b": v} for v in x]),
           "map": lambda: pa.array([[("a", v)] for v in x], type=pa.map_(pa.string(), pa.float64())),
           "fixed_list": lambda: pa.array([[v, v] for v in x], type=pa.list_(pa.float64(), 2)),
           "duplicate": lambda: pa.array(x)}[kind]()
    table = pa.Table.from_arrays([col, pa.array(x)], names=["p", "p" if kind == "duplicate" else "q"])
    if kind != "duplicate":
        table = table.select(["p"])
    path = folder / f"{kind}.parquet"
    pq.write_table(table, path)
    return path


# ---------------------------------------------------------------------------------------------
# text exports of other programs with bad header values, X3P archives with twin members
# ---------------------------------------------------------------------------------------------
def matrix_export(folder: Path, factor: str = "6.3e-8", pixel: str = "3.7e-7 m",
                  name: str = "matrix.txt") -> Path:
    """A matrix export (``h= w=``, ``pixel size=``, ``height conversion factor``) of 5 lines
    of 6 values, with the factor and the pixel size as written."""
    values = np.random.default_rng(5).normal(size=(5, 6)).round(6)
    head = ["h=5 w=6", f"pixel size={pixel}", "data unit=rad",
            f"height conversion factor (-> m)={factor}"]
    path = folder / name
    path.write_text("\n".join(head + [" ".join(f"{v:f}" for v in row) for row in values]) + "\n")
    return path


def gwyddion_export(folder: Path, width: str | None = "12 µm", height: str | None = "5 µm",
                    name: str = "gwyddion.txt") -> Path:
    """A Gwyddion text export of 4 lines of 3 heights (nm) whose header states the width and
    the height given (None: the line is left out)."""
    lines = ["# Channel: Topography"]
    lines += [f"# Width: {width}"] if width is not None else []
    lines += [f"# Height: {height}"] if height is not None else []
    lines += ["# Value units: nm"]
    values = np.random.default_rng(6).normal(size=(4, 3)).round(6)
    path = folder / name
    path.write_text("\n".join(lines + ["\t".join(repr(float(v)) for v in row) for row in values])
                    + "\n")
    return path


def x3p_twins(folder: Path, names: tuple[str, ...], name: str = "twins.x3p") -> Path:
    """An X3P of 3 x 3 points whose main.xml links 'bindata/data.bin' and whose archive holds
    one data member under each of ``names`` (in this order): member k holds the heights
    ``k + arange(9)`` micrometres, so the member read is known from its heights."""
    xml = x3p_xml(3, 3)
    path = folder / name
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("main.xml", xml)
        for k, member in enumerate(names):
            z.writestr(member, ((k + np.arange(9.0)) * 1e-6).tobytes())
    return path


# ---------------------------------------------------------------------------------------------
# mutants of real instrument files (a folder such as SurfaceTopography's file_format_examples)
# ---------------------------------------------------------------------------------------------
#: Real files mutated, when present in the folder given: read by SurfaceTopography (.di,
#: .opd, .plu, .sur) or by this package (MetroPro .dat, .x3p, matrix and Gwyddion exports).
INSTRUMENT_FILES = ("di-1.di", "di-2.di", "opd-1.opd", "plu-1.plu", "sur-2.sur", "sur-3.sur",
                    "metropro-1.dat", "x3p-2.x3p", "matrix-2.txt", "matrix-3.txt",
                    "gwyddion-export-english.txt")


def _flip(blob: bytes, start: int, count: int) -> bytes:
    data = bytearray(blob)
    for k in range(start, min(start + count, len(data))):
        data[k] ^= 0xFF
    return bytes(data)


def _x3p_resized(blob: bytes) -> bytes:
    """The X3P ``blob`` with main.xml declaring twice its SizeX."""
    out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(blob)) as src, zipfile.ZipFile(out, "w") as dst:
        for info in src.infolist():
            data = src.read(info)
            if info.filename.lower() == "main.xml":
                data = re.sub(rb"<SizeX>(\d+)</SizeX>",
                              lambda m: b"<SizeX>%d</SizeX>" % (2 * int(m.group(1))), data)
            dst.writestr(info.filename, data)
    return out.getvalue()


def _header_mutants(name: str, blob: bytes) -> list[tuple[str, bytes, str]]:
    """Mutants of a header field of the formats whose header this package reads."""
    if name.startswith("metropro"):
        huge = bytearray(blob)
        struct.pack_into(">H", huge, 68, 65535)  # cn_width: the phase map's width
        return [("width_65535", bytes(huge), "refused")]
    if name.endswith(".x3p"):
        return [("sizex_doubled", _x3p_resized(blob), "refused")]
    if name.startswith("matrix"):
        text = blob.decode("latin-1")
        out = []
        for label, old, new, expected in (
                ("h_plus_1", r"h=(\d+)", lambda m: f"h={int(m.group(1)) + 1}", "refused"),
                ("factor_0", r"(conversion factor[^=]*=)\s*\S+", lambda m: m.group(1) + "0",
                 "refused"),
                ("factor_1e-320", r"(conversion factor[^=]*=)\s*\S+",
                 lambda m: m.group(1) + "1e-320", "refused"),
                ("pixel_2147483648_m", r"(pixel size=)\s*\S+", lambda m: m.group(1) + "2147483648",
                 "warned")):
            mutated, n = re.subn(old, new, text, count=1, flags=re.IGNORECASE)
            if n:
                out.append((label, mutated.encode("latin-1"), expected))
        return out
    if name.startswith("gwyddion"):
        text = blob.decode("utf-8")
        kept = "\n".join(ln for ln in text.splitlines() if not ln.startswith("# Width"))
        return [("without_width", (kept + "\n").encode(), "refused")]
    return []


def instrument_mutants(examples: Path, folder: Path) -> list[tuple[str, Path, str]]:
    """(name, file, expected) for every file of :data:`INSTRUMENT_FILES` in ``examples``: the
    file itself ("accepted", "warned" for the Gwyddion example of unit-free heights), its
    truncations ("refused"; "any" for a text file cut at a line's end, and for the last byte
    of formats that may end in padding), byte flips in the header and in the data ("any": a
    reader may not see them, but must neither crash nor flood stderr) and header fields made
    inconsistent (see :func:`_header_mutants`)."""
    out = []
    sub = folder / "instruments"
    sub.mkdir(exist_ok=True)
    for name in INSTRUMENT_FILES:
        source = examples / name
        if not source.is_file() or source.stat().st_size == 0:
            continue
        blob = source.read_bytes()
        stem, ext = name.rsplit(".", 1)
        binary = ext not in ("txt",)
        own = ext in ("dat", "x3p")  # formats whose size this package checks exactly
        cases = [("valid", blob, "warned" if name.startswith("gwyddion") else "accepted"),
                 ("half", blob[: len(blob) // 2], "refused" if binary else "any"),
                 # .opd and .plu files end in padding: SurfaceTopography reads them without it
                 ("last_byte_missing", blob[:-1], "refused" if own else "any"),
                 ("header_flipped", _flip(blob, 16, 32), "any"),
                 ("data_flipped", _flip(blob, len(blob) // 2, 64), "any")]
        if len(blob) > 4096:
            cases.append(("first_300_bytes", blob[:300], "refused"))
        cases += _header_mutants(name, blob)
        for label, data, expected in cases:
            path = sub / f"{stem}-{label}.{ext}"
            path.write_bytes(data)
            out.append((f"{stem}_{label}", path, expected))
    return out
