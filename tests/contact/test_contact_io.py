"""Topography files: round trips, hand-built X3P archives, and corrupt or truncated files."""

from __future__ import annotations

import hashlib
import importlib.util
import zipfile

import numpy as np
import pytest

import contact
from contact import TopographyFileError

# Many inputs here are unit-free (heights of order 1 on a micrometre or millimetre grid, files of
# small integers); contact's check of the units warns about them, which these tests do not examine.
pytestmark = pytest.mark.filterwarnings("ignore:the RMS of the heights:contact.errors.ContactWarning")


@pytest.fixture
def surface():
    rng = np.random.default_rng(0)
    h = rng.standard_normal((12, 9)) * 1e-6
    mask = np.zeros(h.shape, dtype=bool)
    mask[3, 4] = mask[7, 1] = True
    return contact.Surface(h, 2e-6, 3e-6, mask=mask)


def same(a: contact.Surface, b: contact.Surface):
    assert a.shape == b.shape
    assert a.dx == b.dx and a.dy == b.dy
    np.testing.assert_array_equal(a.mask, b.mask)
    np.testing.assert_array_equal(a.heights[~a.mask], b.heights[~b.mask])


@pytest.mark.parametrize("name", ["s.npz", "s.x3p", "s.txt", "s.csv", "s.asc", "s.xyz"])
def test_round_trip(tmp_path, surface, name):
    path = tmp_path / name
    surface.write(path)
    same(surface, contact.read(path))
    assert not list(tmp_path.glob("*.part"))


def test_npy_needs_spacing(tmp_path, surface):
    path = tmp_path / "s.npy"
    contact.write(surface, path)
    with pytest.raises(ValueError, match=r"stores no grid spacing; pass dx="):
        contact.read(path)
    same(surface, contact.read(path, dx=2e-6, dy=3e-6))


def test_text_grid_without_header_and_override(tmp_path):
    path = tmp_path / "g.dat"
    path.write_text("1 2 3\n4 5 6\n7 8 9\n")
    s = contact.read(path, dx=1e-6)
    np.testing.assert_array_equal(s.heights, [[1, 2, 3], [4, 5, 6], [7, 8, 9]])
    assert s.dx == s.dy == 1e-6


def test_x3p_hand_built_int16_with_scaling_and_validity(tmp_path):
    # ISO 5436-2: x varies fastest; z = raw * increment + offset; validity bits LSB first.
    raw = np.arange(6, dtype="<i2")  # SizeX = 3, SizeY = 2
    valid = bytes([0b111011])  # point 2 (x = 2, y = 0) is invalid
    xml = f"""<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
 <Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>
  <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment></CX>
  <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>2e-6</Increment></CY>
  <CZ><AxisType>A</AxisType><DataType>I</DataType><Increment>1e-9</Increment>
   <Offset>5e-9</Offset></CZ></Axes></Record1>
 <Record3><MatrixDimension><SizeX>3</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension>
  <DataLink><PointDataLink>bindata/data.bin</PointDataLink>
   <MD5ChecksumPointData>{hashlib.md5(raw.tobytes()).hexdigest()}</MD5ChecksumPointData>
   <ValidPointsLink>bindata/valid.bin</ValidPointsLink></DataLink></Record3>
</p:ISO5436_2>"""
    path = tmp_path / "h.x3p"
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("main.xml", xml)
        z.writestr("bindata/data.bin", raw.tobytes())
        z.writestr("bindata/valid.bin", valid)
    heights, dx, dy, mask = contact.x3p.read_x3p(path)
    assert (dx, dy) == (1e-6, 2e-6)
    expected = (np.arange(6.0).reshape(2, 3).T) * 1e-9 + 5e-9  # [i, j] = raw[j * 3 + i]
    assert mask is not None and mask.tolist() == [[False, False], [False, False], [True, False]]
    np.testing.assert_allclose(heights[~mask], expected[~mask], rtol=1e-15)


def test_x3p_inline_data_list(tmp_path):
    xml = """<?xml version="1.0"?><ISO5436_2><Record1><FeatureType>SUR</FeatureType><Axes>
<CX><AxisType>I</AxisType><Increment>1e-6</Increment></CX>
<CY><AxisType>I</AxisType><Increment>1e-6</Increment></CY>
<CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1>
<Record3><MatrixDimension><SizeX>3</SizeX><SizeY>3</SizeY><SizeZ>1</SizeZ></MatrixDimension>
<DataList>""" + "".join(f"<Datum>{v}</Datum>" for v in range(8)) + "<Datum/></DataList>" \
        "</Record3></ISO5436_2>"
    path = tmp_path / "l.x3p"
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("main.xml", xml)
    s = contact.read(path)
    assert s.mask[2, 2] and s.mask.sum() == 1
    assert s.heights[1, 2] == 7.0  # index 7 = y 2 * SizeX 3 + x 1


def test_x3p_truncated_file(tmp_path, surface):
    path = tmp_path / "s.x3p"
    surface.write(path)
    blob = path.read_bytes()
    for cut in (len(blob) // 2, len(blob) - 30, 10):
        bad = tmp_path / f"cut{cut}.x3p"
        bad.write_bytes(blob[:cut])
        with pytest.raises(TopographyFileError, match=r"not a valid X3P file|cannot read"):
            contact.read(bad)


def test_x3p_corrupt_data_and_xml(tmp_path, surface):
    path = tmp_path / "s.x3p"
    surface.write(path)
    with zipfile.ZipFile(path) as z:
        members = {n: z.read(n) for n in z.namelist()}

    def rebuild(name, **change):
        out = tmp_path / name
        with zipfile.ZipFile(out, "w") as z:
            for n, data in {**members, **change}.items():
                z.writestr(n, data)
        return out

    data = bytearray(members["bindata/data.bin"])
    data[5] ^= 0xFF
    with pytest.raises(TopographyFileError, match=r"fail their MD5 checksum"):
        contact.read(rebuild("flip.x3p", **{"bindata/data.bin": bytes(data)}))
    with pytest.raises(TopographyFileError, match=r"main.xml does not match its MD5"):
        contact.read(rebuild("xml.x3p", **{"main.xml": members["main.xml"] + b" "}))
    short_xml = members["main.xml"].replace(b"<MD5ChecksumPointData>", b"<Ignored>").replace(
        b"</MD5ChecksumPointData>", b"</Ignored>"
    )
    short = rebuild(
        "short.x3p",
        **{
            "bindata/data.bin": members["bindata/data.bin"][:-8],
            "main.xml": short_xml,
            "md5checksum.hex": hashlib.md5(short_xml).hexdigest().encode() + b" *main.xml",
        },
    )
    with pytest.raises(TopographyFileError, match=r"truncated or corrupt"):
        contact.read(short)
    with pytest.raises(TopographyFileError, match=r"not well-formed XML"):
        contact.read(rebuild("bad.x3p", **{"main.xml": b"<ISO5436_2><Record1>"}))


def test_truncated_or_ragged_other_formats(tmp_path, surface):
    npz = tmp_path / "s.npz"
    surface.write(npz)
    (tmp_path / "t.npz").write_bytes(npz.read_bytes()[:-40])
    with pytest.raises(TopographyFileError, match=r"not a readable .npz archive"):
        contact.read(tmp_path / "t.npz")
    npy = tmp_path / "s.npy"
    surface.write(npy)
    (tmp_path / "t.npy").write_bytes(npy.read_bytes()[:-40])
    with pytest.raises(TopographyFileError, match=r"not a readable .npy array"):
        contact.read(tmp_path / "t.npy", dx=1e-6)
    txt = tmp_path / "s.txt"
    surface.write(txt)
    lines = txt.read_text().splitlines()
    lines[-1] = " ".join(lines[-1].split()[:-3])
    (tmp_path / "t.txt").write_text("\n".join(lines))
    with pytest.raises(TopographyFileError, match=r"rows have different lengths"):
        contact.read(tmp_path / "t.txt")
    (tmp_path / "w.npz").write_bytes(b"")
    np.savez(tmp_path / "w.npz", z=np.zeros((4, 4)))
    with pytest.raises(TopographyFileError, match=r"no 'heights' array \(found \['z'\]\)"):
        contact.read(tmp_path / "w.npz")


def test_xyz_non_uniform_and_duplicates(tmp_path):
    path = tmp_path / "p.xyz"
    pts = [(x, y, 0.0) for x in (0.0, 1e-6, 3e-6) for y in (0.0, 1e-6, 2e-6)]
    np.savetxt(path, pts)
    with pytest.raises(TopographyFileError, match=r"non-uniform spacing along x"):
        contact.read(path)
    pts = [(x, y, 0.0) for x in (0.0, 1e-6, 2e-6) for y in (0.0, 1e-6, 2e-6)]
    np.savetxt(path, [*pts, pts[0]])
    with pytest.raises(TopographyFileError, match=r"share the same \(x, y\) position"):
        contact.read(path)


def test_missing_file_and_bad_spacing(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"no such topography file"):
        contact.read(tmp_path / "nothing.x3p")
    (tmp_path / "a.txt").write_text("1 2 3\n4 5 6\n7 8 9\n")
    with pytest.raises(ValueError, match=r"dx must be a positive finite spacing"):
        contact.read(tmp_path / "a.txt", dx=-1.0)


def test_other_formats_go_through_surfacetopography(tmp_path):
    path = tmp_path / "scan.sur"
    path.write_bytes(b"not a real instrument file")
    if importlib.util.find_spec("SurfaceTopography") is None:
        with pytest.raises(ImportError, match=r"needs the optional package SurfaceTopography"):
            contact.read(path)
    else:
        with pytest.raises(TopographyFileError, match=r"SurfaceTopography cannot read it"):
            contact.read(path)
    with pytest.raises(ValueError, match=r"cannot write '.sur' files"):
        contact.weierstrass((8, 8), 1e-3, 0.5).write(path)


def test_write_does_not_touch_the_surface(tmp_path, surface):
    before = surface.heights.copy()
    surface.write(tmp_path / "s.txt")
    surface.write(tmp_path / "s.x3p")
    np.testing.assert_array_equal(surface.heights, before)


def test_xyz_with_rounded_coordinates(tmp_path):
    # dx = 1/3 um printed with 6 significant digits: the printed steps differ by ~1e-6
    rng = np.random.default_rng(2)
    h = rng.normal(size=(64, 48)) * 1e-7
    dx, dy = 1e-6 / 3, 0.7e-6
    ii, jj = np.meshgrid(np.arange(64), np.arange(48), indexing="ij")
    pts = np.column_stack([ii.ravel() * dx, jj.ravel() * dy, h.ravel()])
    path = tmp_path / "g.xyz"
    np.savetxt(path, pts, fmt="%g")
    printed = np.loadtxt(path)
    steps = np.diff(np.unique(printed[:, 0]))
    assert not np.allclose(steps, steps.mean(), rtol=1e-6, atol=0)
    s = contact.read(path)
    assert s.shape == (64, 48)
    assert s.dx == pytest.approx(dx, rel=1e-5)
    assert s.dy == pytest.approx(dy, rel=1e-5)
    np.testing.assert_allclose(s.heights, h, rtol=1e-5, atol=1e-12)
    assert s.mask is None


def test_xyz_irregular_grids_still_rejected(tmp_path):
    path = tmp_path / "p.xyz"
    # a column displaced by 1 % of a step
    xs = np.arange(8) * 1e-6
    xs[3] += 1e-8
    np.savetxt(path, [(x, y, 0.0) for x in xs for y in np.arange(4) * 1e-6], fmt="%.17g")
    with pytest.raises(TopographyFileError, match=r"non-uniform spacing along x"):
        contact.read(path)
    # a jittered axis along y
    ys = np.arange(6) * 1e-6 + np.array([0, 2e-8, -3e-8, 1e-8, 0, 0])
    np.savetxt(path, [(x, y, 0.0) for x in np.arange(4) * 1e-6 for y in ys], fmt="%.17g")
    with pytest.raises(TopographyFileError, match=r"non-uniform spacing along y"):
        contact.read(path)
    # a missing interior column: the remaining coordinates are not on a uniform grid
    xs = np.delete(np.arange(8) * 1e-6, 4)
    np.savetxt(path, [(x, y, 0.0) for x in xs for y in np.arange(4) * 1e-6], fmt="%g")
    with pytest.raises(TopographyFileError, match=r"non-uniform spacing along x"):
        contact.read(path)


@pytest.mark.parametrize("name", ["s.txt", "s.csv"])
def test_text_grid_truncated_at_a_row_boundary(tmp_path, surface, name):
    path = tmp_path / name
    surface.write(path)
    text = path.read_text()
    assert f"# shape = {surface.shape[0]} {surface.shape[1]}\n" in text
    lines = text.splitlines(keepends=True)
    (tmp_path / ("t" + path.suffix)).write_text("".join(lines[:-2]))
    with pytest.raises(TopographyFileError, match=r"holds \d+ rows of \d+ values, but its "
                       r"header says shape = \d+ \d+ \(truncated file\?\)"):
        contact.read(tmp_path / ("t" + path.suffix))
    # without the shape line, the same rows read as a smaller surface
    kept = [ln for ln in lines[:-2] if not ln.startswith("# shape")]
    (tmp_path / ("n" + path.suffix)).write_text("".join(kept))
    assert contact.read(tmp_path / ("n" + path.suffix)).shape == (
        surface.shape[0] - 2, surface.shape[1])


def test_xyz_truncated_at_a_row_boundary(tmp_path, surface):
    path = tmp_path / "s.xyz"
    surface.write(path)
    lines = path.read_text().splitlines(keepends=True)
    assert f"# points = {surface.heights.size}\n" in lines
    ny = surface.shape[1]
    (tmp_path / "t.xyz").write_text("".join(lines[:-ny]))
    with pytest.raises(TopographyFileError, match=rf"holds {surface.heights.size - ny} points, "
                       rf"but its header says points = {surface.heights.size}"):
        contact.read(tmp_path / "t.xyz")
    kept = [ln for ln in lines[:-ny] if not ln.startswith("# points")]
    (tmp_path / "n.xyz").write_text("".join(kept))
    assert contact.read(tmp_path / "n.xyz").shape == (surface.shape[0] - 1, ny)


GRID = "1 2 3\n4 5 6\n7 8 9\n"


@pytest.mark.parametrize(("value", "metres"), [
    ("1e-06", 1e-6), ("1e-06,", 1e-6), ("1 um", 1e-6), ("1um", 1e-6), ("1 µm", 1e-6),
    ("2.5 nm", 2.5e-9), ("0.5 mm,", 5e-4), ("3e-6 m", 3e-6), ("1e-06 ,", 1e-6),
])
def test_text_header_values_and_units(tmp_path, value, metres):
    path = tmp_path / "g.txt"
    path.write_text(f"# dx = {value}\n" + GRID, encoding="utf-8")
    s = contact.read(path)
    assert s.dx == pytest.approx(metres, rel=1e-15)
    assert s.dy == s.dx


@pytest.mark.parametrize("value", ["abc", "1 inch", "1e-6 um um", "-1e-6", "0 nm", "inf", ""])
def test_text_header_bad_values(tmp_path, value):
    path = tmp_path / "g.txt"
    path.write_text("# a comment\n# dy = " + value + "\n" + GRID, encoding="utf-8")
    with pytest.raises(TopographyFileError, match=r"g\.txt: line 2: dy = .* (not a length|"
                       r"not a positive finite spacing)"):
        contact.read(path, dx=1e-6)


def test_csv_with_trailing_commas(tmp_path):
    path = tmp_path / "g.csv"
    path.write_text("# heights in metres,\n# dx = 1e-06,\n# dy = 2e-06,\n"
                    "1,2,3,\n4,5,6,\n7,8,9,\n")
    s = contact.read(path)
    assert (s.dx, s.dy) == (1e-6, 2e-6)
    np.testing.assert_array_equal(s.heights, np.arange(1, 10.0).reshape(3, 3))


def test_text_encodings(tmp_path):
    bom = tmp_path / "bom.txt"
    bom.write_bytes(b"\xef\xbb\xbf# dx = 1e-06\n" + GRID.encode())
    assert contact.read(bom).dx == 1e-6
    bom_data = tmp_path / "bom_data.txt"
    bom_data.write_bytes(b"\xef\xbb\xbf" + GRID.encode())
    np.testing.assert_array_equal(contact.read(bom_data, dx=1e-6).heights[0], [1, 2, 3])
    latin = tmp_path / "latin.txt"
    latin.write_bytes("# heights in µm from the profiler\n# dx = 2 µm\n".encode("latin-1")
                      + GRID.encode())
    assert contact.read(latin).dx == pytest.approx(2e-6, rel=1e-15)
    xyz = tmp_path / "latin.xyz"
    pts = "".join(f"{i * 1e-6} {j * 1e-6} {i + j}\n" for i in range(3) for j in range(3))
    xyz.write_bytes(b"\xef\xbb\xbf" + "# x y z in m (0.001 µm resolution)\n".encode("latin-1")
                    + pts.encode())
    assert contact.read(xyz).shape == (3, 3)


@pytest.mark.parametrize(("array", "dtype"), [
    (np.array([["a", "b"], ["c", "d"]]), "<U1"),
    (np.ones((3, 3)) + 1j, "complex128"),
    (np.zeros((3, 3), dtype=[("a", "f8")]), r"\[\('a', '<f8'\)\]"),
    (np.ones((3, 3), dtype=bool), "bool"),
])
def test_npy_and_npz_need_real_heights(tmp_path, array, dtype):
    np.save(tmp_path / "h.npy", array)
    with pytest.raises(TopographyFileError, match=rf"the array has dtype {dtype}; heights "
                       "must be real numbers"):
        contact.read(tmp_path / "h.npy", dx=1e-6)
    np.savez(tmp_path / "h.npz", heights=array, dx=1e-6)
    with pytest.raises(TopographyFileError, match=rf"'heights' has dtype {dtype}"):
        contact.read(tmp_path / "h.npz")


def test_npy_and_npz_accept_integer_and_single_precision_heights(tmp_path):
    h = np.arange(12, dtype=np.int16).reshape(3, 4)
    np.save(tmp_path / "h.npy", h)
    np.testing.assert_array_equal(contact.read(tmp_path / "h.npy", dx=1e-6).heights, h)
    np.savez(tmp_path / "h.npz", heights=h.astype(np.float32), dx=np.float32(1e-6), dy=2)
    s = contact.read(tmp_path / "h.npz")
    assert s.dx == pytest.approx(1e-6, rel=1e-7) and s.dy == 2.0
    np.save(tmp_path / "v.npy", np.ones(5))
    with pytest.raises(TopographyFileError, match=r"the array is 1-D; a 2-D height map"):
        contact.read(tmp_path / "v.npy", dx=1e-6)


@pytest.mark.parametrize(("dx", "match"), [
    (np.array([1e-6, 2e-6]), r"'dx' must be a real scalar in metres, got an array of shape "
                             r"\(2,\)"),
    (np.array("abc"), r"'dx' must be a real scalar in metres, got an array of shape \(\) "
                      r"and dtype <U3"),
    (np.array(1e-6 + 0j), r"'dx' must be a real scalar"),
    (np.array(-1e-6), r"'dx' must be a positive finite spacing in metres, got -1e-06"),
    (np.array(np.nan), r"'dx' must be a positive finite spacing in metres, got nan"),
    (np.array(0), r"'dx' must be a positive finite spacing in metres, got 0.0"),
])
def test_npz_spacing_must_be_a_positive_scalar(tmp_path, dx, match):
    np.savez(tmp_path / "h.npz", heights=np.zeros((3, 3)), dx=dx)
    with pytest.raises(TopographyFileError, match=match):
        contact.read(tmp_path / "h.npz")


def test_x3p_without_main_xml_and_without_a_listed_member(tmp_path, surface):
    path = tmp_path / "s.x3p"
    surface.write(path)
    with zipfile.ZipFile(path) as z:
        members = {n: z.read(n) for n in z.namelist()}
    listed = next(n for n in members if n.lower().endswith(".bin"))
    for name, drop, match in [
        ("nomain.x3p", "main.xml",
         r"not a valid X3P file: the archive lacks 'main.xml', the description every X3P"),
        ("nodata.x3p", listed, rf"the archive lacks '{listed}' \(listed in main.xml\)"),
    ]:
        with zipfile.ZipFile(tmp_path / name, "w") as z:
            for n, data in members.items():
                if n != drop:
                    z.writestr(n, data)
        with pytest.raises(TopographyFileError, match=match) as info:
            contact.read(tmp_path / name)
        if drop == "main.xml":
            assert "listed in main.xml" not in str(info.value)
