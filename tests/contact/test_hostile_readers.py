"""Readers facing hostile files: a refusal of the built-in reader is final for a layout it
knows, implausible lateral sizes warn, a missing width is reported, the X3P member named in
main.xml is read, and SurfaceTopography's refusals are one line with its loggers kept off the
terminal.

Every file is written by the test. ``TOPOGRAPHY_EXAMPLES`` may name a copy of
SurfaceTopography's test/file_format_examples; the tests of real instrument files are skipped
without it.
"""

from __future__ import annotations

import logging
import os
import warnings
import zipfile
from pathlib import Path

import numpy as np
import pytest

import contact
from contact import ContactWarning, TopographyFileError
from contact import io as contact_io

VALUES = np.random.default_rng(5).normal(size=(5, 6)).round(6)  # 5 lines of 6 values
EXAMPLES = Path(os.environ.get("TOPOGRAPHY_EXAMPLES", "/nonexistent"))


def _matrix(path: Path, factor: str = "6.3e-8", pixel: str = "3.7e-7 m") -> Path:
    head = ["h=5 w=6", f"pixel size={pixel}", "data unit=rad",
            f"height conversion factor (-> m)={factor}"]
    path.write_text("\n".join(head + [" ".join(f"{v:f}" for v in row) for row in VALUES]) + "\n")
    return path


def _gwyddion(path: Path, width: str | None = "12 µm", height: str | None = "5 µm") -> Path:
    lines = ["# Channel: Topography"]
    lines += [f"# Width: {width}"] if width is not None else []
    lines += [f"# Height: {height}"] if height is not None else []
    lines += ["# Value units: nm"] + ["\t".join(repr(float(v)) for v in row) for row in VALUES]
    path.write_text("\n".join(lines) + "\n")
    return path


# --- a known layout's refusal is final -------------------------------------------------------


@pytest.mark.parametrize("factor", ["0", "1e-320", "-0.0", "1e-999"])
def test_a_bad_conversion_factor_is_refused_and_not_handed_on(tmp_path, monkeypatch, factor):
    """The matrix reader knows the layout: its refusal stands (SurfaceTopography read the
    same file as an all-zero surface)."""
    handed_on = []
    monkeypatch.setattr(contact_io, "_read_surfacetopography",
                        lambda *args, **kwargs: handed_on.append(args))
    with pytest.raises(TopographyFileError, match=rf"line 4: height conversion factor {factor} is "
                                                  r"not a finite number of magnitude 1e-200"):
        contact.read(_matrix(tmp_path / "m.txt", factor=factor))
    assert handed_on == []


def test_a_layout_the_reader_does_not_know_is_still_handed_on(tmp_path, monkeypatch):
    """A first data line that is not numbers is another program's layout: tried elsewhere."""
    handed_on = []

    def other_reader(path, fname, unit, spacing):
        handed_on.append(fname)
        return np.zeros((3, 3)), 1e-6, 1e-6, None

    monkeypatch.setattr(contact_io, "_import_surfacetopography", lambda fname: None)
    monkeypatch.setattr(contact_io, "_read_surfacetopography", other_reader)
    path = tmp_path / "other.txt"
    path.write_text("Program X export\n1 2 3\n4 5 6\n7 8 9\n")
    assert contact.read(path).shape == (3, 3) and handed_on == [str(path)]


def test_a_valid_factor_still_scales_the_heights(tmp_path):
    s = contact.read(_matrix(tmp_path / "m.txt", factor="6.3e-8"))
    np.testing.assert_allclose(s.heights, VALUES.T * 6.3e-8, rtol=1e-15)


# --- implausible lateral sizes ----------------------------------------------------------------


def test_a_pixel_of_2147483648_metres_warns(tmp_path):
    with pytest.warns(ContactWarning, match=r"dx = 2\.14748e\+09 m is implausible for a grid "
                                            r"spacing in metres"):
        s = contact.read(_matrix(tmp_path / "m.txt", pixel="2147483648 m"))
    assert s.dx == 2147483648.0


@pytest.mark.parametrize(("dx", "dy", "words"), [
    (1e300, None, r"dx = 1e\+300 m is implausible .*more than 1000 m between neighbouring points"),
    (1e-6, 5e3, r"dy = 5000 m is implausible"),
    (1e-13, None, r"dx = 1e-13 m is implausible .*below 1e-12 m")])
def test_implausible_spacings_warn_at_the_caller(dx, dy, words):
    h = np.random.default_rng(1).normal(size=(16, 16)) * 1e-9
    with pytest.warns(ContactWarning, match=words) as caught:
        contact.Surface(h, dx, dy)
    assert caught[0].filename == __file__


def test_plausible_and_unit_free_spacings_do_not_warn():
    h = np.random.default_rng(1).normal(size=(64, 64))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        contact.Surface(h * 1e-13, 1e-12)  # a picometre: the smallest spacing accepted silently
        contact.Surface(h * 1e-3, 1e3)  # a kilometre: the largest
        contact.Surface(h, 1.0)  # dimensionless: RMS 1 on a side of 64


# --- a missing width is reported ----------------------------------------------------------------


def test_gwyddion_export_without_width_is_refused_unless_dx_is_given(tmp_path):
    path = _gwyddion(tmp_path / "g.txt", width=None)
    # 5 lines (y) of 6 values (x): the height of 5 µm gives dy = 1 µm
    with pytest.raises(TopographyFileError, match=r"g\.txt: its header states the height \(line 2\) "
                                                  r"but no width .*pass dx= .*dx=1e-06 for square "
                                                  r"pixels"):
        contact.read(path)
    s = contact.read(path, dx=2e-6)
    assert s.shape == (6, 5) and (s.dx, s.dy) == pytest.approx((2e-6, 1e-6), rel=1e-14)


def test_gwyddion_export_without_height_is_refused_unless_dy_is_given(tmp_path):
    path = _gwyddion(tmp_path / "g.txt", height=None)
    with pytest.raises(TopographyFileError, match=r"states the width \(line 2\) but no height"):
        contact.read(path)
    s = contact.read(path, dy=3e-6)
    assert (s.dx, s.dy) == pytest.approx((12e-6 / 6, 3e-6), rel=1e-14)


# --- X3P: the member named in main.xml --------------------------------------------------------


def _x3p(path: Path, members: tuple[str, ...]) -> Path:
    """3 x 3 points; member k of ``members`` holds the heights (k + arange(9)) µm."""
    xml = (
        '<?xml version="1.0" encoding="UTF-8"?><p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/'
        'ISO5436_2"><Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType>'
        "<Axes><CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-06</Increment>"
        "<Offset>0</Offset></CX><CY><AxisType>I</AxisType><DataType>D</DataType><Increment>"
        "1e-06</Increment><Offset>0</Offset></CY><CZ><AxisType>A</AxisType><DataType>D"
        "</DataType></CZ></Axes></Record1><Record3><MatrixDimension><SizeX>3</SizeX><SizeY>3"
        "</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataLink><PointDataLink>bindata/data.bin"
        "</PointDataLink></DataLink></Record3></p:ISO5436_2>")
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("main.xml", xml)
        for k, name in enumerate(members):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", UserWarning)  # zipfile: duplicate name
                z.writestr(name, ((k + np.arange(9.0)) * 1e-6).tobytes())
    return path


@pytest.mark.parametrize("order", [("bindata/data.bin", "BINDATA/DATA.BIN"),
                                   ("BINDATA/DATA.BIN", "bindata/data.bin")])
def test_x3p_reads_the_member_main_xml_names_not_its_case_folded_twin(tmp_path, order):
    s = contact.read(_x3p(tmp_path / "twin.x3p", order))
    k = order.index("bindata/data.bin")
    np.testing.assert_array_equal(s.heights.ravel(order="F"), (k + np.arange(9.0)) * 1e-6)


def test_x3p_with_one_case_folded_member_is_still_read(tmp_path):
    s = contact.read(_x3p(tmp_path / "upper.x3p", ("BINDATA/DATA.BIN",)))
    np.testing.assert_array_equal(s.heights.ravel(order="F"), np.arange(9.0) * 1e-6)


def test_x3p_with_ambiguous_members_is_refused(tmp_path):
    with pytest.raises(TopographyFileError, match=r"lacks 'bindata/data.bin' .* but holds 2 "
                                                  r"members differing from it only in case"):
        contact.read(_x3p(tmp_path / "two.x3p", ("BINDATA/DATA.BIN", "Bindata/Data.bin")))
    with pytest.raises(TopographyFileError, match=r"holds 2 members named 'bindata/data.bin'"):
        contact.read(_x3p(tmp_path / "dup.x3p", ("bindata/data.bin", "bindata/data.bin")))


# --- SurfaceTopography's refusals: one line, its loggers off the terminal ------------------------


def test_quiet_loggers_keep_records_off_the_terminal_and_restore_the_loggers(capfd):
    """While SurfaceTopography reads, the records of its loggers (and igor2's) reach no
    handler of the process; afterwards they do again, and the loggers are as before."""
    seen: list[str] = []

    class Collect(logging.Handler):
        def emit(self, record):
            seen.append(record.getMessage())

    collect = Collect()
    logging.getLogger().addHandler(collect)
    logger = logging.getLogger("igor2.binarywave")
    top = logging.getLogger("igor2")
    before = (list(top.handlers), top.propagate, list(logger.handlers), logger.propagate)
    try:
        with contact_io._quiet_loggers():
            logger.error("could not reshape data from %s", b"\x00" * 10_000)
            logging.getLogger("SurfaceTopography.IO").warning("a note")
        assert seen == [] and capfd.readouterr().err == ""
        assert (list(top.handlers), top.propagate, list(logger.handlers), logger.propagate) == before
        logger.error("after the reading")
        assert seen == ["after the reading"]
    finally:
        logging.getLogger().removeHandler(collect)


@pytest.mark.parametrize("suffix", [".di", ".opd", ".plu", ".sur"])
def test_damaged_instrument_file_is_refused_in_one_line(tmp_path, suffix):
    pytest.importorskip("SurfaceTopography", reason="these formats are read by SurfaceTopography")
    path = tmp_path / f"random{suffix}"
    path.write_bytes(np.random.default_rng(2).bytes(4096))
    with pytest.raises(TopographyFileError) as exc:
        contact.read(path)
    message = str(exc.value)
    assert "\n" not in message and len(message) < 400, message
    assert message.startswith(f"{path}: SurfaceTopography cannot read it: ")


def test_empty_instrument_file_is_refused_as_empty(tmp_path):
    pytest.importorskip("SurfaceTopography", reason="these formats are read by SurfaceTopography")
    (tmp_path / "e.sur").write_bytes(b"")
    with pytest.raises(TopographyFileError, match=r"e\.sur: the file is empty"):
        contact.read(tmp_path / "e.sur")


@pytest.mark.skipif(not (EXAMPLES / "opd-1.opd").is_file(),
                    reason="TOPOGRAPHY_EXAMPLES does not hold SurfaceTopography's opd-1.opd")
@pytest.mark.parametrize("name", ["opd-1.opd", "plu-1.plu", "di-1.di", "sur-2.sur"])
def test_truncated_real_file_is_one_line_and_quiet(tmp_path, capfd, name):
    """A truncated .opd made igor2 (tried by SurfaceTopography) log 6.4 MB of its bytes."""
    pytest.importorskip("SurfaceTopography", reason="these formats are read by SurfaceTopography")
    blob = (EXAMPLES / name).read_bytes()
    path = tmp_path / name
    path.write_bytes(blob[: len(blob) // 2])
    capfd.readouterr()
    with pytest.raises(TopographyFileError) as exc:
        contact.read(path)
    assert "\n" not in str(exc.value) and "says: " in str(exc.value)
    assert len(capfd.readouterr().err) < 4096
