"""``glstat fit`` on decompression bombs and oversized inputs, with the shipped limits: one line of
error (status 2) within seconds, at the memory of refusing a three-line file; and the text reader
on ordinary files (compressed, commented, other encodings and line ends), read in two passes.

The bombs are written inside the tests by streaming writes (about 1 MB on disk each); peak memory
is the maximum resident size of the ``glstat fit`` process (``ru_maxrss`` of a child of a small
wrapper process, so that no other child of the test run counts).
"""

from __future__ import annotations

import bz2
import gzip
import json
import lzma
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

from glstat.cli import sample_files as ci
from glstat.cli.sample_files import MAX_DECOMPRESSED, InputError, read_sample

#: The shipped limit; the bombs below exceed it without lowering it.
CAP_MB = MAX_DECOMPRESSED / 2**20
#: Memory a refusal may take above refusing a three-line file (chunks of 1 MiB are read).
EXTRA_MB = 64
#: The bound the issue states: a small multiple of the limit plus Python, numpy and pandas.
BOUND_MB = 4 * CAP_MB + 300
SECONDS = 20

WRAPPER = r"""
import json, resource, subprocess, sys, time
t0 = time.perf_counter()
proc = subprocess.run(sys.argv[1:], capture_output=True, text=True, timeout=120)
print(json.dumps({"code": proc.returncode, "stderr": proc.stderr, "seconds": time.perf_counter() - t0,
                  "peak_mb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024}))
"""


def _glstat_fit(path: Path, out: Path, *options: str) -> dict:
    """Exit status, stderr, seconds and peak resident memory (MB) of ``glstat fit path``."""
    script = Path(sys.executable).with_name("glstat")
    command = [str(script)] if script.exists() else [sys.executable, "-m", "glstat"]
    command += ["fit", str(path), "--bootstrap", "0", "--out", str(out), *options]
    proc = subprocess.run([sys.executable, "-c", WRAPPER, *command], capture_output=True, text=True,
                          timeout=180, check=True)
    return json.loads(proc.stdout)


def _gzip(path: Path, unit: bytes, nbytes: int, first: bytes = b"") -> Path:
    """A gzip file of ``first`` and ``unit`` repeated to ``nbytes``, written 4 MiB at a time."""
    chunk = unit * (2**22 // len(unit))
    with gzip.open(path, "wb", compresslevel=1) as f:
        f.write(first)
        for _ in range(-(-nbytes // len(chunk))):
            f.write(chunk)
    return path


def _error_line(got: dict) -> str:
    lines = [line for line in got["stderr"].splitlines() if line.startswith("glstat fit: error: ")]
    assert len(lines) == 1, got["stderr"][:2000]
    assert len(got["stderr"]) < 2000 and "Traceback" not in got["stderr"], got["stderr"][:2000]
    return lines[0]


@pytest.fixture(scope="module")
def baseline_mb(tmp_path_factory) -> float:
    """Peak memory of ``glstat fit`` refusing a three-line file (imports and all)."""
    folder = tmp_path_factory.mktemp("baseline")
    small = folder / "three.csv"
    small.write_text("x\n1\n2\n")
    got = _glstat_fit(small, folder / "o")
    assert got["code"] == 2 and "has 2 finite value(s)" in _error_line(got), got
    return got["peak_mb"]


def _check_refusal(got: dict, baseline: float, words: str, out: Path) -> None:
    assert got["code"] == 2, got
    assert words in _error_line(got), got["stderr"][:2000]
    assert got["seconds"] < SECONDS, got
    assert got["peak_mb"] < baseline + EXTRA_MB, (got, baseline)
    assert got["peak_mb"] < BOUND_MB, got
    assert not out.exists()


def test_gzip_of_zero_bytes_beyond_the_shipped_limit(tmp_path, baseline_mb):
    bomb = _gzip(tmp_path / "zeros.csv.gz", b"\0", MAX_DECOMPRESSED + 2**25)
    assert bomb.stat().st_size < 3 * 2**20
    got = _glstat_fit(bomb, tmp_path / "o")
    _check_refusal(got, baseline_mb, "is not a text file (a NUL byte at byte 0", tmp_path / "o")


def test_gzip_of_newlines_beyond_the_shipped_limit(tmp_path, baseline_mb):
    bomb = _gzip(tmp_path / "newlines.csv.gz", b"\n", MAX_DECOMPRESSED + 2**25)
    got = _glstat_fit(bomb, tmp_path / "o")
    _check_refusal(got, baseline_mb, f"decompresses to more than {CAP_MB:.0f} MiB", tmp_path / "o")
    assert "holds no value" in got["stderr"]


def test_gzip_of_numbers_beyond_the_shipped_limit(tmp_path, baseline_mb):
    """Text that is a column of numbers, longer than the limit: refused at the limit."""
    bomb = _gzip(tmp_path / "numbers.csv.gz", b"1234.56789012345678\n", MAX_DECOMPRESSED + 2**25,
                 first=b"pressure\n")
    got = _glstat_fit(bomb, tmp_path / "o")
    _check_refusal(got, baseline_mb, f"decompresses to more than {CAP_MB:.0f} MiB", tmp_path / "o")


def test_gzip_of_more_numbers_than_the_limit_holds(tmp_path, baseline_mb):
    """Within the limit as text, "1\\n" repeated is four times the limit as numbers: refused."""
    bomb = _gzip(tmp_path / "ones.csv.gz", b"1\n", MAX_DECOMPRESSED - 2**20)
    got = _glstat_fit(bomb, tmp_path / "o")
    _check_refusal(got, baseline_mb, "as numbers, more than the", tmp_path / "o")


def test_gzip_of_one_long_line(tmp_path, baseline_mb):
    """A name of a hundred megabytes is no header: refused at the first megabyte."""
    bomb = _gzip(tmp_path / "name.csv.gz", b"a", 100 * 2**20)
    got = _glstat_fit(bomb, tmp_path / "o")
    _check_refusal(got, baseline_mb, "has a line longer than 1 MiB", tmp_path / "o")


def test_parquet_declaring_200_million_rows(tmp_path, baseline_mb):
    """Run-length and dictionary encoding keep the pages tiny; the declared rows count."""
    pa = pytest.importorskip("pyarrow", reason="Parquet needs pyarrow")
    import pyarrow.parquet as pq

    path = tmp_path / "rows.parquet"
    batch = pa.table({"x": pa.repeat(pa.scalar(1.5, pa.float64()), 10_000_000)})
    with pq.ParquetWriter(path, batch.schema) as writer:
        for _ in range(20):
            writer.write_table(batch, row_group_size=10_000_000)
    del batch
    assert path.stat().st_size < 3 * 2**20
    assert pq.ParquetFile(path).metadata.num_rows == 200_000_000
    got = _glstat_fit(path, tmp_path / "o")
    _check_refusal(got, baseline_mb, "declares 200000000 rows x 1 column(s)", tmp_path / "o")


# ---------------------------------------------------------------------------------------------
# the reader on ordinary and odd text, in process
# ---------------------------------------------------------------------------------------------
VALUES = [1.5, 2.25, -3.0, 4e-3, 1234.5]
CSV = "# measured 2024\n\n# another comment\n\npressure,tag\n" + "".join(
    f"{v!r},a{i}\n" for i, v in enumerate(VALUES))


def _write_compressed(path: Path, data: bytes) -> Path:
    suffix = path.suffix
    if suffix == ".gz":
        path.write_bytes(gzip.compress(data))
    elif suffix == ".bz2":
        path.write_bytes(bz2.compress(data))
    elif suffix == ".xz":
        path.write_bytes(lzma.compress(data))
    elif suffix == ".zip":
        with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
            z.writestr("data.csv", data)
    elif suffix == ".zst":
        zstandard = pytest.importorskip("zstandard")
        path.write_bytes(zstandard.ZstdCompressor().compress(data))
    else:
        path.write_bytes(data)
    return path


@pytest.mark.parametrize("name", ["p.csv", "p.csv.gz", "p.csv.bz2", "p.csv.xz", "p.csv.zip",
                                  "p.csv.zst"])
def test_compressed_and_commented_text_is_read_exactly(tmp_path, name):
    path = _write_compressed(tmp_path / name, CSV.encode())
    s = read_sample(path)
    assert s.column == "pressure" and s.values.tolist() == VALUES


@pytest.mark.parametrize("eol", ["\n", "\r\n", "\r"])
def test_line_ends_bom_and_latin1(tmp_path, eol):
    text = CSV.replace("\n", eol)
    (tmp_path / "u.csv").write_bytes(b"\xef\xbb\xbf" + text.encode())
    assert read_sample(tmp_path / "u.csv").values.tolist() == VALUES
    latin = text.replace("pressure", "pression (°C)").encode("latin-1")
    (tmp_path / "l.csv.gz").write_bytes(gzip.compress(latin))
    s = read_sample(tmp_path / "l.csv.gz")
    assert s.column == "pression (°C)" and s.values.tolist() == VALUES


def test_separator_is_found_from_the_first_lines_only(tmp_path):
    """Semicolons and decimal commas after 10 000 blank and comment lines; a 300 kB header."""
    body = "".join(f"{v};{str(v).replace('.', ',')}\n" for v in VALUES)
    path = tmp_path / "s.txt.gz"
    path.write_bytes(gzip.compress(("\n# c\n" * 10_000 + "a;b\n" + body).encode()))
    s = read_sample(path, "b")
    assert s.values.tolist() == VALUES
    assert any("semicolons" in n for n in s.notes) and any("decimal commas" in n for n in s.notes)
    wide = tmp_path / "w.csv"
    names = [f"column {i:04d} " + "x" * 50 for i in range(5000)]
    wide.write_text(",".join(names) + "\n"
                    + "".join(",".join(["0"] * 4999 + [repr(v)]) + "\n" for v in VALUES))
    assert read_sample(wide, names[-1]).values.tolist() == VALUES


@pytest.mark.parametrize("content, words", [
    (b"\n" * 3_000_000, "is empty (no values, only blank or comment lines)"),
    (b"# note\n  \r\n" * 300_000, "is empty (no values, only blank or comment lines)"),
    (b"x\n1\n2\x00\n", "is not a text file (a NUL byte at byte 5"),
    (b"\x00" * 3_000_000, "is not a text file (a NUL byte at byte 0"),
    (b"x\n" + b"9" * (2**20 + 1) + b"\n", "has a line longer than 1 MiB (from byte 2"),
    (b",".join([b"1"] * 20_000) + b"\n", "has 20000 fields in its first line"),
])
def test_text_that_is_no_table_is_refused_from_one_pass(tmp_path, content, words):
    for name in ("bad.csv", "bad.csv.gz"):
        path = _write_compressed(tmp_path / name, content)
        with pytest.raises(InputError) as exc:
            read_sample(path)
        text = str(exc.value)
        assert text.startswith(str(path)) and words in text and len(text) < 400, text


def test_limits_of_compressed_text(tmp_path, monkeypatch):
    """Decompressed bytes, and lines x fields as 8-byte numbers, against the limit (lowered)."""
    monkeypatch.setattr(ci, "MAX_DECOMPRESSED", 2**16)
    ok = _write_compressed(tmp_path / "ok.csv.gz", b"a,b\n" + b"1.2345678,2.5\n" * 2000)
    assert read_sample(ok, "b").values.size == 2000
    plain = _write_compressed(tmp_path / "plain.csv", b"a,b\n" + b"1.2345678,2.5\n" * 20_000)
    assert read_sample(plain, "a").values.size == 20_000  # uncompressed: no limit
    with pytest.raises(InputError, match="decompresses to more than 64 KiB, the limit"):
        read_sample(_write_compressed(tmp_path / "big.csv.gz", plain.read_bytes()))
    with pytest.raises(InputError, match=r"decompresses to 8193 lines of 2 field\(s\): up to 16386 "
                                         r"values"):
        read_sample(_write_compressed(tmp_path / "dense.csv.zip", b"a,b\n" + b"1,2\n" * 8192))


def test_parquet_declared_rows_against_the_limit(tmp_path, monkeypatch):
    pa = pytest.importorskip("pyarrow", reason="Parquet needs pyarrow")
    import pyarrow.parquet as pq

    path = tmp_path / "t.parquet"
    pq.write_table(pa.table({"x": np.full(10_000, 2.5), "y": np.arange(10_000.0)}), path)
    monkeypatch.setattr(ci, "MAX_DECOMPRESSED", 120_000)
    assert read_sample(path, "y").values.size == 10_000  # 80 000 bytes as numbers
    with pytest.raises(InputError, match=r"declares 10000 rows x 2 column\(s\) = 20000 values"):
        read_sample(path)


def test_long_column_names_and_entries_are_shortened_in_messages(tmp_path, capsys):
    from glstat.cli import fit as cli_fit

    name = "n" * 5000
    path = tmp_path / "long.csv"
    path.write_text(f"{name},b\n1,{'y' * 3000}\n2,x\n")
    with pytest.raises(InputError, match=r"is not numeric: 2 of 2 entries .*\(3000 characters\) in "
                                         r"data row 1"):
        read_sample(path, "2")
    with pytest.raises(InputError) as exc:
        read_sample(path, "zz" * 400)
    text = str(exc.value)
    assert "(5000 characters)" in text and "(800 characters)" in text and len(text) < 800
    one = tmp_path / "one.csv"
    one.write_text(f"{name}\n1\n2\n")
    out = tmp_path / "o"
    assert cli_fit.main([str(one), "--bootstrap", "0", "--out", str(out)]) == 2
    err = [line for line in capsys.readouterr().err.splitlines() if "error:" in line]
    assert len(err) == 1 and "has 2 finite value(s)" in err[0] and "(5000 characters)" in err[0]
    assert len(err[0]) < 600, err
    assert not out.exists()
    assert ci.quoted(name) == repr("n" * 160) + "... (5000 characters)"
    assert ci.quoted("short") == "'short'"
    many = tmp_path / "many.csv"
    many.write_text(",".join(f"c{i}" for i in range(100)) + "\n" + ",".join(["1"] * 100) + "\n")
    with pytest.raises(InputError, match=r"has 100 numeric columns \('c0', .* 'c19', \.\.\. \(80 more\)\)"):
        read_sample(many)
