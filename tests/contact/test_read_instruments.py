"""Reading other programs' topography files: Gwyddion and matrix text exports, XYZ lists in
text files, Zygo MetroPro binaries, X3P checksums, units, and the SurfaceTopography fallback.

Every file is written by the test. Expected values are computed in the test from the numbers
written (and the format's definition); where SurfaceTopography is installed, its reading of
the same file is a second reference.
"""

from __future__ import annotations

import hashlib
import struct
import warnings
import zipfile

import numpy as np
import pytest

import contact
from contact import TopographyFileError
from contact import io as contact_io

# Many inputs here are unit-free (heights of order 1 on a micrometre or millimetre grid, files of
# small integers); contact's check of the units warns about them, which these tests do not examine.
pytestmark = pytest.mark.filterwarnings("ignore:the RMS of the heights:contact.errors.ContactWarning")

ST_REASON = "SurfaceTopography (optional) is the second reference for this format"

ROWS = np.array([[1.0, 1.5, 3.0], [-2.0, -3.0, -6.0], [0.0, 0.0, 0.0], [9.0, 9.0, 9.0]])


def _st_read(path, **kwargs):
    """SurfaceTopography's reading: heights (NaN where masked), size and unit."""
    st = pytest.importorskip("SurfaceTopography", reason=ST_REASON)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t = st.read_topography(str(path), **kwargs)
    h = np.ma.filled(np.ma.asarray(t.heights(), dtype=float), np.nan)
    return h, tuple(float(v) for v in t.physical_sizes), t.unit


def _same_as_st(s, path, scale, **kwargs):
    """``s`` equals SurfaceTopography's reading of ``path`` (its unit: ``scale`` metres)."""
    h, size, _ = _st_read(path, **kwargs)
    assert s.shape == h.shape
    np.testing.assert_allclose(s.size, np.array(size) * scale, rtol=1e-12)
    ours = np.where(s.mask, np.nan, s.heights) if s.mask is not None else s.heights
    np.testing.assert_allclose(ours, h * scale, rtol=1e-12, atol=0, equal_nan=True)


def _gwyddion(width="12.34 µm", height="5678.9 nm", value_units="m",
              keys=("Channel", "Width", "Height", "Value units"), rows=ROWS,
              channel="Topography") -> str:
    lines = [f"# {keys[0]}: {channel}", f"# {keys[1]}: {width}", f"# {keys[2]}: {height}"]
    if value_units is not None:
        lines.append(f"# {keys[3]}: {value_units}")
    lines += ["\t".join(repr(float(v)) for v in row) for row in rows]
    return "\n".join(lines) + "\n"


# --- Gwyddion text exports --------------------------------------------------------------


@pytest.mark.parametrize(("keys", "encoding"), [
    (("Channel", "Width", "Height", "Value units"), "utf-8"),
    (("Kanal", "Breite", "Höhe", "Value units"), "utf-8"),
    (("Kanal", "Breite", "Höhe", "Einheiten"), "latin-1"),
])
def test_gwyddion_export_one_line_per_y(tmp_path, keys, encoding):
    path = tmp_path / "gwy.txt"
    path.write_text(_gwyddion(keys=keys), encoding=encoding)
    s = contact.read(path)
    # each text line is one y: heights[ix, iy] = ROWS[iy, ix]; width over the columns
    np.testing.assert_array_equal(s.heights, ROWS.T)
    assert s.dx == pytest.approx(12.34e-6 / 3, rel=1e-14)
    assert s.dy == pytest.approx(5678.9e-9 / 4, rel=1e-14)
    if encoding == "utf-8":  # SurfaceTopography reads UTF-8 headers only
        _same_as_st(s, path, 1.0)


def test_gwyddion_sizes_without_unit_take_the_value_unit(tmp_path):
    path = tmp_path / "nm.txt"
    path.write_text(_gwyddion(width="300", height="400", value_units="nm"))
    s = contact.read(path)
    np.testing.assert_allclose(s.heights, ROWS.T * 1e-9, rtol=1e-15)
    assert (s.dx, s.dy) == pytest.approx((100e-9, 100e-9), rel=1e-14)
    _same_as_st(s, path, 1e-9)


@pytest.mark.parametrize(("written", "metres"), [
    ("3 mm", 1e-3), ("3 um", 1e-6), ("3 μm", 1e-6), ("3 pm", 1e-12), ("3 Å", 1e-10),
    ("3e-3 m", 1.0)])
def test_gwyddion_width_units(tmp_path, written, metres):
    path = tmp_path / "w.txt"
    path.write_text(_gwyddion(width=written, height="4 µm"))
    factor = 3e-3 if written.startswith("3e-3") else 3.0
    assert contact.read(path).dx == pytest.approx(factor * metres / 3, rel=1e-14)


def test_gwyddion_without_value_units_needs_unit(tmp_path):
    path = tmp_path / "nounit.txt"
    path.write_text(_gwyddion(value_units=None))
    with pytest.raises(ValueError, match=r"nounit\.txt states no length unit; pass "
                       r"unit='µm' \(or the unit of its heights\)"):
        contact.read(path)
    s = contact.read(path, unit="nm")
    np.testing.assert_allclose(s.heights, ROWS.T * 1e-9, rtol=1e-15)
    assert s.dx == pytest.approx(12.34e-6 / 3, rel=1e-14)  # the width keeps its own unit


def test_gwyddion_unit_conflict_and_non_length_values(tmp_path):
    path = tmp_path / "m.txt"
    path.write_text(_gwyddion())
    assert contact.read(path, unit="m").shape == (3, 4)
    with pytest.raises(ValueError, match=r"states its heights in m; unit='µm' contradicts it"):
        contact.read(path, unit="um")
    volts = tmp_path / "volts.txt"
    volts.write_text(_gwyddion(value_units="V"))
    with pytest.raises(TopographyFileError, match=r"values are in 'V', not a length"):
        contact.read(volts)


def test_gwyddion_export_of_two_channels_is_not_merged(tmp_path):
    """A second header after the data starts another channel: the built-in reader refuses
    the file rather than appending the rows; SurfaceTopography reads its first channel."""
    path = tmp_path / "two.txt"
    path.write_text(_gwyddion() + _gwyddion(rows=ROWS * 10, channel="Amplitude"))
    try:
        import SurfaceTopography  # noqa: F401
    except ImportError:
        with pytest.raises(TopographyFileError, match=r"second header after data rows"):
            contact.read(path)
        return
    s = contact.read(path)
    np.testing.assert_array_equal(s.heights, ROWS.T)
    _same_as_st(s, path, 1.0)


# --- matrix exports (h= w=, pixel size, height conversion factor) -------------------------


def _matrix(values, pixel="3.69862e-007 m", factor=6.30079e-008, h=None, w=None) -> str:
    ny, nx = values.shape
    head = [f"h={ny if h is None else h} w={nx if w is None else w}", f"pixel size={pixel}",
            "data unit=rad", f"height conversion factor (-> m)={factor}"]
    return "\n".join(head + [" ".join(f"{v:f}" for v in row) for row in values]) + "\n"


def test_matrix_export(tmp_path):
    values = np.round(np.random.default_rng(1).normal(size=(5, 7)), 6)  # 5 lines of 7
    path = tmp_path / "matrix.txt"
    path.write_text(_matrix(values))
    s = contact.read(path)
    assert s.shape == (7, 5)
    np.testing.assert_allclose(s.heights, values.T * 6.30079e-8, rtol=1e-15)
    assert (s.dx, s.dy) == (3.69862e-7, 3.69862e-7)
    _same_as_st(s, path, 1.0)


def test_matrix_export_counts_must_match(tmp_path):
    values = np.arange(20.0).reshape(4, 5)
    path = tmp_path / "short.txt"
    path.write_text(_matrix(values, h=6))
    with pytest.raises(TopographyFileError, match=r"header says h=6 but the data hold 4 lines"):
        contact.read(path)


# --- XYZ point lists in text files ----------------------------------------------------------


def _xyz_text(order="xy", nan_at=()) -> str:
    pts = [(x, y) for x in range(4) for y in range(5)] if order == "xy" else \
        [(x, y) for y in range(5) for x in range(4)]
    lines = []
    for x, y in pts:
        z = "NaN" if (x, y) in nan_at else repr(float(x * 10 + y))
        lines.append(f"{x * 0.5} {y * 0.5} {z}")
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("order", ["xy", "yx"])
def test_xyz_list_in_txt_needs_its_unit(tmp_path, order):
    path = tmp_path / "points.txt"
    path.write_text(_xyz_text(order, nan_at={(1, 0), (2, 3)}))
    with pytest.raises(ValueError, match=r"points\.txt states no length unit; pass unit='µm' "
                       r"\(or the unit of its coordinates and heights\)"):
        contact.read(path)
    s = contact.read(path, unit="µm")
    expected = (np.arange(4)[:, None] * 10.0 + np.arange(5)[None, :]) * 1e-6
    assert s.shape == (4, 5) and (s.dx, s.dy) == pytest.approx((0.5e-6, 0.5e-6), rel=1e-14)
    assert s.mask is not None and s.mask[1, 0] and s.mask[2, 3] and s.mask.sum() == 2
    np.testing.assert_allclose(np.where(s.mask, 0, s.heights), np.where(s.mask, 0, expected),
                               rtol=1e-14)
    _same_as_st(s, path, 1e-6, unit="µm")


def test_three_columns_that_are_no_grid_stay_a_height_grid(tmp_path):
    """Three columns whose first two do not list a complete grid: this package's layout."""
    path = tmp_path / "grid.txt"
    np.savetxt(path, np.arange(12.0).reshape(4, 3) ** 2)
    s = contact.read(path, dx=1e-6)
    np.testing.assert_array_equal(s.heights, np.arange(12.0).reshape(4, 3) ** 2)


# --- units of this package's formats ----------------------------------------------------------


def test_unit_of_own_text_grid_npy_and_xyz(tmp_path):
    grid = np.arange(1.0, 10.0).reshape(3, 3)
    text = tmp_path / "g.txt"
    text.write_text("# dx = 2\n# dy = 3 nm\n" + "\n".join(" ".join(map(str, r)) for r in grid))
    s = contact.read(text, unit="µm")
    np.testing.assert_allclose(s.heights, grid * 1e-6, rtol=1e-15)
    assert (s.dx, s.dy) == pytest.approx((2e-6, 3e-9), rel=1e-15)  # '3 nm' keeps its unit
    assert contact.read(text).dx == 2.0  # metres by default, as before
    np.save(tmp_path / "h.npy", grid)
    np.testing.assert_allclose(contact.read(tmp_path / "h.npy", dx=1e-6, unit="nm").heights,
                               grid * 1e-9, rtol=1e-15)
    xyz = tmp_path / "p.xyz"
    xyz.write_text("".join(f"{i} {j} {i + j}\n" for i in range(3) for j in range(3)))
    s = contact.read(xyz, unit="mm")
    assert s.dx == pytest.approx(1e-3, rel=1e-15) and s.heights[2, 2] == pytest.approx(4e-3)


def test_files_in_metres_refuse_another_unit(tmp_path):
    surface = contact.weierstrass((8, 8), 1e-3, 0.5, rng=1)
    for name in ("s.npz", "s.x3p"):
        surface.write(tmp_path / name)
        assert contact.read(tmp_path / name, unit="m").shape == (8, 8)
        with pytest.raises(ValueError, match=r"states its heights in m; unit='nm' contradicts"):
            contact.read(tmp_path / name, unit="nm")


@pytest.mark.parametrize("bad", ["inch", "", "M", 1e-6, "µ"])
def test_unit_must_be_a_length_unit(tmp_path, bad):
    np.save(tmp_path / "h.npy", np.zeros((3, 3)))
    with pytest.raises(ValueError, match=r"unit must be a length unit"):
        contact.read(tmp_path / "h.npy", dx=1e-6, unit=bad)


def test_text_without_spacing_still_asks_for_dx(tmp_path):
    path = tmp_path / "plain.txt"
    path.write_text("1 2 3\n4 5 6\n7 8 9\n")
    with pytest.raises(ValueError, match=r"stores no grid spacing; pass dx= \(and dy=\)"):
        contact.read(path)


# --- Zygo MetroPro ---------------------------------------------------------------------------


def _metropro(path, phase, *, header_format=1, phase_res=1, sign=0, scale=0.5,
              wavelength=6.328e-7, obliquity=1.0, lateral=1.1e-6, buckets=1):
    """A MetroPro file laid out as the MetroPro Reference Guide defines it: big-endian
    header, ``buckets`` intensity frames of 16-bit counts, then 32-bit phase values."""
    ny, nx = phase.shape
    size = 4096 if header_format == 3 else 834
    header = bytearray(size)
    magic = {1: b"\x88\x1b\x03\x6f", 2: b"\x88\x1b\x03\x70", 3: b"\x88\x1b\x03\x71"}
    header[0:4] = magic[header_format]
    struct.pack_into(">Hi", header, 4, header_format, size)
    struct.pack_into(">hhHHHhi", header, 48, 0, 0, nx, ny, buckets, 255, 2 * buckets * nx * ny)
    struct.pack_into(">hhHHi", header, 64, 0, 0, nx, ny, 4 * nx * ny)
    struct.pack_into(">ff", header, 164, scale, wavelength)
    struct.pack_into(">f", header, 176, obliquity)
    struct.pack_into(">f", header, 184, lateral)
    struct.pack_into(">h", header, 218, phase_res)
    struct.pack_into(">h", header, 232, sign)
    intensity = np.arange(buckets * nx * ny, dtype=">i2").tobytes()
    path.write_bytes(bytes(header) + intensity + phase.astype(">i4").tobytes())
    return path


@pytest.mark.parametrize(("header_format", "phase_res", "sign"), [(1, 1, 0), (2, 0, 1),
                                                                  (3, 2, 0)])
def test_metropro(tmp_path, header_format, phase_res, sign):
    rng = np.random.default_rng(header_format)
    phase = rng.integers(-20000, 20000, size=(6, 9))  # 6 camera rows of 9 points
    phase[2, 4] = phase[5, 0] = 2147483640  # invalid points
    path = _metropro(tmp_path / "zygo.dat", phase, header_format=header_format,
                     phase_res=phase_res, sign=sign)
    s = contact.read(path)
    resolution = {0: 4096, 1: 32768, 2: 131072}[phase_res]
    step = np.float64(np.float32(0.5)) * np.float32(6.328e-7) * 1.0 / resolution
    expected = phase.T * step * (-1.0 if sign else 1.0)
    assert s.shape == (9, 6) and s.dx == s.dy == np.float64(np.float32(1.1e-6))
    assert s.mask[4, 2] and s.mask[0, 5] and s.mask.sum() == 2
    np.testing.assert_allclose(np.where(s.mask, 0, s.heights),
                               np.where(s.mask, 0, expected), rtol=1e-12)
    _same_as_st(s, path, 1.0)


def test_metropro_damaged(tmp_path):
    phase = np.zeros((4, 5), dtype=int)
    path = _metropro(tmp_path / "t.dat", phase)
    path.write_bytes(path.read_bytes()[:-8])
    with pytest.raises(TopographyFileError, match=r"truncated file"):
        contact.read(path)
    path = _metropro(tmp_path / "r.dat", phase, phase_res=7)
    with pytest.raises(TopographyFileError, match=r"unknown MetroPro phase resolution 7"):
        contact.read(path)
    path = _metropro(tmp_path / "u.dat", phase, lateral=0.0)
    with pytest.raises(ValueError, match=r"stores no grid spacing; pass dx="):
        contact.read(path)
    assert contact.read(path, dx=2e-6).dx == 2e-6
    with pytest.raises(ValueError, match=r"states its heights in m; unit='nm'"):
        contact.read(path, dx=2e-6, unit="nm")


# --- X3P checksums ---------------------------------------------------------------------------


def test_x3p_written_by_surfacetopography(tmp_path):
    st = pytest.importorskip("SurfaceTopography", reason=ST_REASON)
    h = np.random.default_rng(2).normal(size=(6, 5))
    path = tmp_path / "st.x3p"
    st.Topography(h, (3.0, 2.5), unit="µm").to_x3p(str(path))
    s = contact.read(path)
    np.testing.assert_allclose(s.heights, h * 1e-6, rtol=1e-14)
    assert (s.dx, s.dy) == pytest.approx((0.5e-6, 0.5e-6), rel=1e-14)
    _same_as_st(s, path, 1.0)
    # SurfaceTopography lists the point data in md5checksum.hex; damaged data still fail
    with zipfile.ZipFile(path) as z:
        members = {n: z.read(n) for n in z.namelist()}
    data = bytearray(members["bindata/data.bin"])
    data[3] ^= 0xFF
    bad = tmp_path / "bad.x3p"
    with zipfile.ZipFile(bad, "w") as z:
        for name, content in {**members, "bindata/data.bin": bytes(data)}.items():
            z.writestr(name, content)
    with pytest.raises(TopographyFileError, match=r"point data fail their MD5 checksum"):
        contact.read(bad)


@pytest.mark.parametrize(("line", "accepted"), [
    ("{md5} *main.xml\n", True),
    ("{MD5} *main.xml\r\n", True),
    ("{md5}  main.xml", True),
    ("{md5}", True),
    ("{other} *bindata/data.bin\n{md5} *main.xml\n", True),
    ("{other} *main.xml\n", False),
    ("{other}\n", False),
])
def test_x3p_main_xml_checksum(tmp_path, line, accepted):
    """The checksum file's line for main.xml (ISO 25178-72: the MD5 of main.xml, md5sum
    layout ``<hex> *main.xml``) is checked; a mismatch is refused."""
    contact.weierstrass((8, 8), 1e-3, 0.5, rng=1).write(tmp_path / "s.x3p")
    with zipfile.ZipFile(tmp_path / "s.x3p") as z:
        members = {n: z.read(n) for n in z.namelist()}
    md5 = hashlib.md5(members["main.xml"]).hexdigest()
    other = hashlib.md5(members["main.xml"] + b" ").hexdigest()
    members["md5checksum.hex"] = line.format(md5=md5, MD5=md5.upper(), other=other).encode()
    path = tmp_path / "c.x3p"
    with zipfile.ZipFile(path, "w") as z:
        for name, content in members.items():
            z.writestr(name, content)
    if accepted:
        assert contact.read(path).shape == (8, 8)
    else:
        with pytest.raises(TopographyFileError, match=r"main.xml does not match its MD5"):
            contact.read(path)


# --- SurfaceTopography as the fallback ----------------------------------------------------------


def test_line_profile_in_csv_is_refused_as_a_profile(tmp_path):
    path = tmp_path / "profile.csv"
    path.write_text("X_(microns),height\n" + "".join(f"{i * 0.1:.1f},{np.sin(i):.5f}\n"
                                                     for i in range(20)))
    try:
        import SurfaceTopography  # noqa: F401
    except ImportError:
        with pytest.raises(TopographyFileError, match=r"line 1 holds a non-number"):
            contact.read(path)
        return
    with pytest.raises(TopographyFileError, match=r"holds a line profile \(1-D\); need an "
                       r"areal map"):
        contact.read(path)


@pytest.mark.parametrize("columns", [1, 2])
def test_one_or_two_columns_are_a_profile_not_a_grid(tmp_path, columns):
    path = tmp_path / "xy.txt"
    np.savetxt(path, np.column_stack([np.arange(30.0), np.cos(np.arange(30.0))])[:, -columns:])
    try:
        import SurfaceTopography  # noqa: F401
    except ImportError:
        with pytest.raises(TopographyFileError, match=rf"holds {columns} column\(s\): a line "
                           "profile or x-y list"):
            contact.read(path, dx=1e-6)
        return
    with pytest.raises(TopographyFileError, match=r"holds a line profile \(1-D\)"):
        contact.read(path, dx=1e-6)


def test_unknown_text_is_refused_with_the_own_message(tmp_path, monkeypatch):
    path = tmp_path / "nonsense.txt"
    path.write_text("This is no topography.\nNeither is this.\n")
    with pytest.raises(TopographyFileError, match=r"line 1 holds a non-number"):
        contact.read(path)
    # files above the cap are never handed to SurfaceTopography (it holds text as lists)
    two = tmp_path / "two.txt"
    two.write_text(_gwyddion() + _gwyddion())
    monkeypatch.setattr(contact_io, "TEXT_FALLBACK_MAX_BYTES", 16)
    with pytest.raises(TopographyFileError, match=r"second header after data rows"):
        contact.read(two)


def test_surfacetopography_format_takes_unit(tmp_path):
    pytest.importorskip("SurfaceTopography", reason=ST_REASON)
    path = tmp_path / "points.txt"
    path.write_text(_xyz_text())
    with pytest.raises(ValueError, match=r"states no length unit; pass unit='µm'"):
        contact.read(path, format="surfacetopography")
    ours = contact.read(path, unit="nm")
    theirs = contact.read(path, unit="nm", format="surfacetopography")
    np.testing.assert_allclose(theirs.heights, ours.heights, rtol=1e-14)
    assert (theirs.dx, theirs.dy) == pytest.approx((ours.dx, ours.dy), rel=1e-14)
    gwy = tmp_path / "gwy.txt"
    gwy.write_text(_gwyddion())
    with pytest.raises(ValueError, match=r"states its heights in m; unit='nm' contradicts"):
        contact.read(gwy, unit="nm", format="surfacetopography")


def test_surfacetopography_file_without_size_takes_dx(tmp_path):
    pytest.importorskip("SurfaceTopography", reason=ST_REASON)
    h = np.arange(20.0).reshape(4, 5)
    np.save(tmp_path / "h.npy", h)  # SurfaceTopography reads .npy without size or unit
    with pytest.raises(ValueError, match=r"stores no grid spacing; pass dx="):
        contact.read(tmp_path / "h.npy", format="surfacetopography", unit="µm")
    s = contact.read(tmp_path / "h.npy", format="surfacetopography", unit="µm", dx=2e-6,
                     dy=3e-6)
    np.testing.assert_allclose(s.heights, h * 1e-6, rtol=1e-15)
    assert (s.dx, s.dy) == pytest.approx((2e-6, 3e-6), rel=1e-14)
    np.testing.assert_allclose(s.heights, contact.read(tmp_path / "h.npy", dx=2e-6,
                                                       unit="µm").heights, rtol=1e-15)


def test_without_surfacetopography_text_refusals_are_the_own_ones(tmp_path, monkeypatch):
    """The fallback is optional: without SurfaceTopography the text reader's errors stand."""
    def missing(fname):
        raise ImportError("SurfaceTopography is not installed")

    monkeypatch.setattr(contact_io, "_import_surfacetopography", missing)
    xy = tmp_path / "xy.txt"
    np.savetxt(xy, np.column_stack([np.arange(30.0), np.cos(np.arange(30.0))]))
    with pytest.raises(TopographyFileError, match=r"holds 2 column\(s\): a line profile"):
        contact.read(xy, dx=1e-6)
    two = tmp_path / "two.txt"
    two.write_text(_gwyddion() + _gwyddion(channel="Amplitude"))
    with pytest.raises(TopographyFileError, match=r"second header after data rows"):
        contact.read(two)
    # the own formats need no SurfaceTopography
    gwy = tmp_path / "gwy.txt"
    gwy.write_text(_gwyddion())
    np.testing.assert_array_equal(contact.read(gwy).heights, ROWS.T)
