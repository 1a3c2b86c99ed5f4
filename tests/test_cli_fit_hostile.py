"""``glstat fit`` on hostile and awkward inputs: one line on stderr, exit status 2, no
traceback, refused from what the file declares before reading it (Excel workbooks, Parquet
columns that are not numbers, a full disk), and decimal-comma numbers in one column.

The Excel workbooks are written member by member by ``tests/hostile.py``.
"""

from __future__ import annotations

import errno
import pathlib
import time

import hostile
import numpy as np
import pytest

from glstat.cli.fit import main
from glstat.cli.sample_files import InputError, read_sample

QUICK = ["--bootstrap", "0", "--gof-resamples", "0"]


def _refused(path, capsys, tmp_path, *extra) -> str:
    """Run ``glstat fit`` on ``path``: exit status 2, one line on stderr, nothing written."""
    out = tmp_path / "out"
    t0 = time.perf_counter()
    assert main([str(path), *QUICK, "--out", str(out), *extra]) == 2
    assert time.perf_counter() - t0 < 5
    err = capsys.readouterr().err.strip()
    assert err.startswith("glstat fit: error: ") and "Traceback" not in err, err
    assert len(err.splitlines()) == 1, err
    assert not out.exists()
    return err


@pytest.fixture
def openpyxl():
    return pytest.importorskip("openpyxl", reason="reading Excel files needs openpyxl")


def test_valid_workbook_is_read(tmp_path, openpyxl):
    s = read_sample(hostile.xlsx_valid(tmp_path))
    # reference: the values written into the sheet by the builder
    np.testing.assert_array_equal(s.values, hostile._sample_values())


@pytest.mark.parametrize("builder, words", [
    ("xlsx_far_cell", "has a value in cell XFD1048576, so the table read spans 1048576 rows x "
                      "16384 columns"),
    ("xlsx_far_dimension", "declares the used range A1:XFD1048576"),
    ("xlsx_malformed", "could not be read as an Excel workbook (ParseError: 'no element found"),
    ("xlsx_overflow_cell", "a cell holds a number beyond the floating-point range (such as 1E+400)"),
    ("xlsx_billion_laughs", "its part 'xl/workbook.xml' declares a DOCTYPE"),
])
def test_hostile_workbooks_are_refused_in_one_line(tmp_path, capsys, openpyxl, builder, words):
    """Formerly: 5.6 GB then MemoryError (far cell), a ParseError traceback (malformed XML),
    openpyxl's three-line message (entities)."""
    err = _refused(getattr(hostile, builder)(tmp_path), capsys, tmp_path)
    assert words in err, err
    if "far" in builder:
        assert "export the column to fit as CSV" in err


def test_workbook_with_a_large_sheet_is_refused_from_its_directory(tmp_path, capsys, openpyxl,
                                                                   monkeypatch):
    """A sheet above MAX_EXCEL_SHEET is refused before openpyxl reads it (a 200 MiB sheet took
    minutes); here with the limit lowered to 1 MiB and a 2 MiB sheet."""
    import glstat.cli.sample_files as ci

    monkeypatch.setattr(ci, "MAX_EXCEL_SHEET", 2**20)
    err = _refused(hostile.xlsx_big_sheet(tmp_path, 2), capsys, tmp_path)
    assert "its first sheet holds 2 MiB of XML, more than the 1 MiB" in err
    assert "export the sheet as CSV" in err


def test_sparse_sheet_within_the_cell_limit_is_read(tmp_path, openpyxl, monkeypatch):
    """The cell limit counts from A1 to the farthest cell holding a value: C500 is read."""
    values = hostile._sample_values(20)
    far = '<row r="500"><c r="C500"><v>1</v></c></row>'
    path = hostile.write_xlsx(tmp_path / "sparse.xlsx", hostile.sheet_xml(values, far))
    import glstat.cli.sample_files as ci

    monkeypatch.setattr(ci, "MAX_DECOMPRESSED", 32 * 1500)  # 1500 cells: 500 x 3 is read
    s = read_sample(path, column="p", nan_policy="omit")
    np.testing.assert_array_equal(s.values, values)
    monkeypatch.setattr(ci, "MAX_DECOMPRESSED", 32 * 1499)
    with pytest.raises(InputError, match=r"value in cell C500, .* 500 rows x 3 columns = 1500"):
        read_sample(path, column="p", nan_policy="omit")


@pytest.mark.parametrize("kind, words", [
    ("list", "column 'p' in {} holds lists, not one number per row"),
    ("struct", "holds structures"),
    ("map", "holds maps"),
    ("fixed_list", "holds fixed-size lists"),
    ("duplicate", "has 2 columns named 'p'; rename them"),
])
def test_parquet_columns_that_are_not_numbers_are_named(tmp_path, capsys, kind, words):
    pytest.importorskip("pyarrow", reason="reading Parquet needs pyarrow")
    path = hostile.parquet_nested(tmp_path, kind)
    for extra in ((), ("--column", "p"), ("--column", "1")):
        err = _refused(path, capsys, tmp_path, *extra)
        assert words.format(path) in err, err
        assert "__fragment_index" not in err


def test_plain_parquet_columns_are_read_beside_nested_ones(tmp_path):
    pa = pytest.importorskip("pyarrow", reason="reading Parquet needs pyarrow")
    import pyarrow.parquet as pq

    x = hostile._sample_values(20)
    pq.write_table(pa.table({"l": pa.array([[v] for v in x]), "v": x}), tmp_path / "m.parquet")
    s = read_sample(tmp_path / "m.parquet")
    assert s.column == "v"
    np.testing.assert_array_equal(s.values, x)


@pytest.mark.parametrize("where", ["figure", "table"])
def test_full_disk_when_writing_is_one_line(tmp_path, capsys, monkeypatch, where):
    """No space left while writing the outputs: one line naming the file and the fix, status 2
    (formerly two tracebacks)."""
    pytest.importorskip("matplotlib", reason="the figures need matplotlib")
    import matplotlib.figure

    def full(self, name, *args, **kwargs):
        target = self if isinstance(self, pathlib.Path) else name
        raise OSError(errno.ENOSPC, "No space left on device", str(target))

    data = tmp_path / "x.csv"
    data.write_text("p\n" + "\n".join(map(repr, hostile._sample_values(100))) + "\n")
    if where == "figure":
        monkeypatch.setattr(matplotlib.figure.Figure, "savefig", full)
    else:
        monkeypatch.setattr(pathlib.Path, "write_text", full)
    out = tmp_path / "out"
    assert main([str(data), *QUICK, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "Traceback" not in err[0], err
    assert err[0].startswith(f"glstat fit: error: cannot write {out}")
    assert "(No space left on device): free some disk space" in err[0]


def test_decimal_comma_column_without_header_leads_to_a_correct_run(tmp_path, capsys):
    """``1234,56`` lines: the error suggests --decimal , (formerly --column 2, and --column 1
    fitted the integer parts), and --decimal , alone reads them (formerly split on commas)."""
    x = np.random.default_rng(5).gamma(4.0, 100.0, size=200).round(2)
    path = tmp_path / "eu.csv"
    path.write_text("".join(f"{v:.2f}\n".replace(".", ",") for v in x))
    err = _refused(path, capsys, tmp_path)
    assert "looks like one number with a decimal comma" in err and "--decimal ," in err
    assert "--column 2" not in err.split("(or")[0]
    s = read_sample(path, decimal=",")
    np.testing.assert_allclose(s.values, x, rtol=0, atol=1e-9)  # reference: the values written
    assert s.values.size == 200
    s = read_sample(path, column="1")  # asked for: read, and said
    assert any("--decimal , reads them as numbers" in n for n in s.notes)
    assert main([str(path), *QUICK, "--decimal", ",", "--out", str(tmp_path / "o")]) == 0
