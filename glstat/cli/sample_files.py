"""Reading the sample of ``glstat fit``: one column of values from the files people have.

Formats, chosen by the file name: delimited text (``.csv``, ``.tsv``, ``.txt`` and any other
name), Parquet (``.parquet``, ``.pq``; needs ``pyarrow``), Excel (``.xlsx``, ``.xlsm``;
needs ``openpyxl``) and NumPy (``.npy``). Text may be compressed (``.gz``, ``.bz2``, ``.xz``,
``.zip``; ``.zst`` with ``zstandard``).

Text files: the separator is found from the first lines (comma, semicolon, tab or
whitespace) unless ``sep`` is given; ``decimal=","`` reads decimal commas, and in a file
separated by semicolons or tabs a column of decimal-comma numbers is recognised without it.
Lines starting with ``#`` are comments. A first row made only of numbers is data (the
columns are then named ``"1"``, ``"2"``, ...). A first column without a header holding
0, 1, 2, ... (the index pandas writes with ``DataFrame.to_csv``) is not data.

Memory is bounded before reading. Text is first read once a chunk at a time, keeping only
its first lines (for the separator and the header): a NUL byte (binary data), a line longer
than :data:`MAX_LINE`, more than :data:`MAX_COLUMNS` columns or no line holding a value is
refused there; compressed text is refused beyond :data:`MAX_DECOMPRESSED` bytes
decompressed, or when its lines times its columns, as 8-byte numbers, exceed that. pandas
then parses the file from a second pass, so the text is never held whole. Parquet and Excel
files whose declared uncompressed size exceeds :data:`MAX_DECOMPRESSED` are refused from
their metadata, and Parquet files whose declared rows times the columns read, as 8-byte
numbers, exceed it; a ``.npy`` header that declares more data than the file holds is refused
without reserving memory. Column names and entries are shortened to about 200 characters in
messages. Everything that is the file's fault raises :class:`InputError` (``glstat fit``
exits with status 2 and the message).
"""

from __future__ import annotations

import bz2
import codecs
import contextlib
import dataclasses
import lzma
import math
import re
import sys
import warnings
import zipfile
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Iterator

    import numpy as np
    import pandas as pd

__all__ = ["MAX_DECOMPRESSED", "STDIN", "InputError", "Sample", "read_sample"]

#: Largest decompressed size (bytes) of a compressed text file, and of the values it may hold as
#: 8-byte numbers (lines x fields x 8); largest declared uncompressed size of the data read from
#: a Parquet or Excel file, and of the values read from a Parquet file (rows x columns x 8):
#: 256 MiB. Reading then takes at most a small multiple of it.
MAX_DECOMPRESSED = 256 * 2**20
COMPRESSION = (".gz", ".bz2", ".xz", ".zip", ".zst")
_SEPARATORS = {",": "commas", ";": "semicolons", "\t": "tabs", r"\s+": "whitespace"}
_SEP_NAMES = {",": ",", ";": ";", "tab": "\t", "\\t": "\t", "\t": "\t", "space": r"\s+",
              "whitespace": r"\s+", " ": r"\s+"}
#: A line of two integers separated by a comma: a number with a decimal comma ("1234,56"), or
#: two columns.
_COMMA_PAIR = re.compile(r"^\s*[-+]?\d+,\d+\s*$")
_DECIMAL_COMMA = re.compile(r"^\s*[-+]?(\d+(,\d*)?|,\d+)([eE][-+]?\d+)?\s*$")
#: Errors of reading or decompressing a file's bytes (corrupt streams, compression methods
#: the standard library cannot read: NotImplementedError from zipfile); the file's fault.
_STREAM_ERRORS = (OSError, EOFError, zlib.error, lzma.LZMAError, RuntimeError,
                  NotImplementedError, zipfile.BadZipFile)
_READ_ERRORS = (*_STREAM_ERRORS, ValueError, MemoryError)


class InputError(ValueError):
    """Bad input file, column or option; the message names the problem and the fix."""


@dataclass(frozen=True)
class Sample:
    """One column of values read from a file.

    Attributes
    ----------
    values : ndarray
        The finite values, in file order (a new array; the file is never modified).
    path : pathlib.Path
        The file read (``-`` for standard input).
    fmt : str
        ``"csv"``, ``"tsv"``, ``"parquet"``, ``"npy"``, ``"excel"`` or ``"text"``.
    column : str
        Name of the column used (``"1"``, ``"2"``, ... for files without a header and for
        NumPy arrays: the 1-based column position).
    n_total : int
        Number of entries in the column, including missing ones.
    n_nan : int
        Missing or NaN entries.
    n_inf : int
        Infinite entries.
    nan_policy : str
        ``"raise"`` or ``"omit"``: how non-finite entries were treated.
    notes : tuple of str
        How the file was read, when it was not the plain case (separator found, decimal
        commas, an index column left out).
    """

    values: np.ndarray
    path: Path
    fmt: str
    column: str
    n_total: int
    n_nan: int
    n_inf: int
    nan_policy: str
    notes: tuple[str, ...] = ()

    @property
    def source(self) -> str:
        """The file name, or "standard input" for ``-``, as messages name the data."""
        return "standard input" if str(self.path) == STDIN else str(self.path)

    @property
    def n_dropped(self) -> int:
        """Number of non-finite entries left out."""
        return self.n_nan + self.n_inf


# ---------------------------------------------------------------------------------------------
# formats and raw bytes
# ---------------------------------------------------------------------------------------------
def format_of(path: Path) -> str:
    """The format of ``path`` from its name: csv, tsv, parquet, npy, excel or text."""
    suffixes = [s.lower() for s in path.suffixes]
    if suffixes and suffixes[-1] in COMPRESSION:
        suffixes = suffixes[:-1]
    last = suffixes[-1] if suffixes else ""
    return {".csv": "csv", ".tsv": "tsv", ".parquet": "parquet", ".pq": "parquet", ".npy": "npy",
            ".xlsx": "excel", ".xlsm": "excel"}.get(last, "text")


def _too_big(path: Path, what: str) -> InputError:
    return InputError(f"{path} {what} more than {_mib(MAX_DECOMPRESSED)}, the limit of glstat fit for "
                      "compressed input; decompress it first (uncompressed files have no limit), or "
                      "fit a part of it")


def _mib(nbytes: float) -> str:
    if nbytes < 2**20:
        return f"{nbytes / 2**10:.0f} KiB"
    return f"{nbytes / 2**20:.0f} MiB" if nbytes < 2**30 else f"{nbytes / 2**30:.1f} GiB"


def quoted(value: Any, limit: int = 200) -> str:
    """``repr(value)`` for a message, shortened to about ``limit`` characters (with the length of
    ``value``) when longer: a column name or an entry of a file may be megabytes long."""
    if not isinstance(value, str):
        text = repr(value)
        return text if len(text) <= limit else f"{text[:limit - 40]}... ({len(text)} characters)"
    if len(value) <= limit - 2:
        return repr(value)
    shown = repr(value[:limit - 40])
    if len(shown) > limit - 38:  # escaped characters
        shown = shown[:limit - 40]
    return f"{shown}... ({len(value)} characters)"


def one_line(exc: BaseException, limit: int = 160) -> str:
    """``Type: message`` of a library's exception on one line: line breaks and other control
    characters (a damaged file's bytes inside the message) become escapes or spaces, and a
    long message is cut to about ``limit`` characters."""
    text = " ".join(str(exc).split())
    text = "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)
    if len(text) > limit:
        text = text[:limit - 3] + "..."
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


#: Columns named in a message at most.
_LISTED = 20


def _listing(names: list, limit: int = _LISTED) -> str:
    """``'a', 'b', ...`` for a message: at most ``limit`` names, each shortened."""
    parts = [quoted(c) for c in names[:limit]]
    if len(names) > limit:
        parts.append(f"... ({len(names) - limit} more)")
    return ", ".join(parts)


def _zip_member(archive: zipfile.ZipFile, path: Path) -> zipfile.ZipInfo:
    from contact.errors import TopographyFileError
    from contact.x3p import check_zip_member

    members = [i for i in archive.infolist() if not i.is_dir()]
    if len(members) != 1:
        raise InputError(f"{path} is a zip archive of {len(members)} files; it must hold exactly "
                         "one data file")
    info = members[0]
    try:
        check_zip_member(info, str(path), repr(info.filename), limit=MAX_DECOMPRESSED)
    except TopographyFileError as exc:
        raise InputError(str(exc)) from None
    return info


@contextlib.contextmanager
def _text_stream(path: Path) -> Iterator[Any]:
    """The bytes of a text file as a binary stream, decompressed when its name says so."""
    suffix = path.suffix.lower()
    if suffix == ".gz":
        import gzip

        with gzip.open(path, "rb") as f:
            yield f
    elif suffix == ".bz2":
        with bz2.open(path, "rb") as f:
            yield f
    elif suffix == ".xz":
        with lzma.open(path, "rb") as f:
            yield f
    elif suffix == ".zip":
        with zipfile.ZipFile(path) as archive, archive.open(_zip_member(archive, path)) as f:
            yield f
    elif suffix == ".zst":
        try:
            import zstandard
        except ImportError:
            raise InputError(f"reading {path.name} needs the package 'zstandard' (pip install "
                             "zstandard), or decompress the file first") from None
        with open(path, "rb") as fh, zstandard.ZstdDecompressor().stream_reader(fh) as f:
            yield f
    else:
        with open(path, "rb") as f:
            yield f


@dataclass
class _Scan:
    """What one pass over the bytes of a text file found (no more than ``_HEAD`` of them kept)."""

    size: int = 0  # bytes (after decompression, without a UTF-8 byte order mark)
    line_ends: int = 0  # line ends: at least the number of lines but one
    head: bytes = b""  # the text from the first line holding a value on (whole lines)
    encoding: str = "utf-8"  # or "latin-1" when the bytes are not UTF-8


#: Bytes read at a time, and longest line (bytes) of a text file: a longer one is no table.
_CHUNK = MAX_LINE = 2**20
#: Most columns of a text file (pandas takes minutes and gigabytes for a few hundred thousand).
MAX_COLUMNS = 10_000
#: Bytes kept from the first line holding a value on, to find the separator and the header.
_HEAD = MAX_LINE + 64 * 2**10
_BOM = b"\xef\xbb\xbf"
_BLANK_OR_HASH = b" \t\n\r\f\v#"
#: The first character of a line that is neither blank nor a comment: a value (or a header);
#: for lines ended by "\r" alone, the slower pattern.
_DATA = re.compile(rb"(?m)^[ \t\f\v]*[^#\s]")
_DATA_CR = re.compile(rb"(?:\A|(?<=\r))[ \t\f\v]*[^#\s]")


def _scan_text(stream, path: Path, compressed: bool) -> _Scan:
    """One pass over the bytes of a text file, a chunk at a time, refusing what is no table of
    values: more than :data:`MAX_DECOMPRESSED` bytes decompressed, a NUL byte (binary data), a
    line longer than :data:`MAX_LINE`, no line holding a value."""
    scan = _Scan()
    decoder = codecs.getincrementaldecoder("utf-8")()
    head = bytearray()
    found = in_comment = False  # a line holding a value seen; in a comment at the chunk's end
    line_start = 0  # offset of the current line
    n_lf = n_cr = 0
    last = b""
    while True:
        chunk = stream.read(_CHUNK)
        if not chunk:
            break
        if scan.size == 0 and chunk.startswith(_BOM):
            chunk = chunk[len(_BOM):]
        offset = scan.size
        scan.size += len(chunk)
        if compressed and scan.size > MAX_DECOMPRESSED:
            if not found:
                raise InputError(f"{path} decompresses to more than {_mib(MAX_DECOMPRESSED)}, the "
                                 "limit of glstat fit for compressed input, and holds no value in "
                                 "them (only blank or comment lines); give a file with one value "
                                 "per line or a column of values")
            raise _too_big(path, "decompresses to")
        nul = chunk.find(b"\x00")
        if nul >= 0:
            raise InputError(f"{path} is not a text file (a NUL byte at byte {offset + nul}"
                             f"{' of the decompressed data' if compressed else ''}); give a CSV, "
                             "Parquet (.parquet), Excel (.xlsx), NumPy (.npy) or plain text file")
        if scan.encoding == "utf-8":
            try:
                decoder.decode(chunk)
            except UnicodeDecodeError:
                scan.encoding = "latin-1"
        n_lf += chunk.count(b"\n")
        n_cr += chunk.count(b"\r")
        ends = [i for i in (chunk.find(b"\n"), chunk.find(b"\r")) if i >= 0]
        line_end = offset + (min(ends) if ends else len(chunk))
        if line_end - line_start > MAX_LINE:  # lines inside a chunk are shorter than it
            raise InputError(f"{path} has a line longer than {_mib(MAX_LINE)} (from byte {line_start}"
                             f"{' of the decompressed data' if compressed else ''}): not a table of "
                             "values; give a file with one value per line or a column of values")
        if ends:
            line_start = offset + max(chunk.rfind(b"\n"), chunk.rfind(b"\r")) + 1
        if not found:
            pos = 0
            if in_comment:  # the comment ends at the first line end
                pos = min(ends) + 1 if ends else len(chunk)
                in_comment = not ends
            rest = chunk[pos:]
            m = None
            if rest.translate(None, _BLANK_OR_HASH):  # something else than blanks and '#'
                m = (_DATA_CR if b"\r" in rest and b"\n" not in rest else _DATA).search(rest)
            if m is not None:
                found = True
                head += rest[m.start():m.start() + _HEAD]
            elif not in_comment:  # is the last line so far a comment?
                in_comment = b"#" in chunk[max(0, line_start - offset):]
        elif len(head) < _HEAD:
            head += chunk[:_HEAD - len(head)]
        last = chunk[-1:]
    if scan.encoding == "utf-8":
        try:
            decoder.decode(b"", final=True)
        except UnicodeDecodeError:
            scan.encoding = "latin-1"
    if not found:
        raise InputError(f"{path} is empty (no values, only blank or comment lines); give a file with "
                         "one value per line or a column of values")
    scan.line_ends = max(n_lf, n_cr) + (last not in (b"\n", b"\r"))
    if len(head) >= _HEAD:  # keep whole lines
        cut = max(head.rfind(b"\n"), head.rfind(b"\r"))
        if cut > 0:
            del head[cut + 1:]
    scan.head = bytes(head)
    return scan


# ---------------------------------------------------------------------------------------------
# delimited text
# ---------------------------------------------------------------------------------------------
def _is_number(token: str, decimal: str = ".") -> bool:
    token = token.strip()
    if decimal == ",":
        if "." in token:
            return False
        token = token.replace(",", ".")
    if "_" in token:
        return False
    try:
        float(token)
    except (TypeError, ValueError):
        return False
    return True


def _data_lines(text: str, limit: int = 50) -> list[str]:
    """The first ``limit`` lines of ``text`` that hold something else than blanks and a comment
    (read one at a time: never all the lines of a long text)."""
    out = []
    for m in re.finditer(r"[^\r\n]+", text):
        body = m.group().split("#", 1)[0].rstrip()
        if body.strip():
            out.append(body)
            if len(out) >= limit:
                break
    return out


def sniff_separator(text: str, decimal: str = ".") -> str | None:
    """The separator of delimited text, from its first lines.

    Tab, semicolon or comma when every line splits into the same number (at least 2) of
    fields; else whitespace when it does; else the one of them found in most lines (at least
    80 %: rows of unequal length are then reported); else None (one column, or unknown).
    A comma is not a candidate with ``decimal=","``.
    """
    lines = _data_lines(text)
    if not lines:
        return None
    candidates = [c for c in ("\t", ";", ",") if not (c == "," and decimal == ",")]
    for sep in candidates:
        counts = {len(line.split(sep)) for line in lines}
        if len(counts) == 1 and counts.pop() > 1:
            return sep
    counts = {len(line.split()) for line in lines}
    if len(counts) == 1 and counts.pop() > 1:
        return r"\s+"
    best = max(candidates, key=lambda c: sum(len(line.split(c)) > 1 for line in lines))
    if sum(len(line.split(best)) > 1 for line in lines) >= 0.8 * len(lines):
        return best
    return None


def _mismatch(exc: Exception, path: Path, sep: str) -> InputError:
    text = str(exc)
    m = re.search(r"Expected (\d+) fields in line (\d+), saw (\d+)", text)
    how = _SEPARATORS.get(sep, repr(sep))
    fix = ("check the separator (this file was read as separated by " + how + "; pass --sep to "
           "choose another) and decimal points (decimal commas need --decimal ,)")
    if m:
        want, line, got = m.groups()
        return InputError(f"{path}: line {line} has {got} fields but the lines before it have {want}; "
                          f"{fix}")
    return InputError(f"{path}: some rows have more fields than the header; {fix}")


def _open_text(path: Path, compressed: bool, read, errors: tuple = ()):
    """``read(stream)`` on the bytes of a text file; the errors of reading or decompressing the
    file (and ``errors``) are the file's fault."""
    errors = (*errors, *_STREAM_ERRORS)
    if path.suffix.lower() == ".zst":
        try:
            import zstandard
        except ImportError:
            pass
        else:
            errors = (*errors, zstandard.ZstdError)
    try:
        with _text_stream(path) as f:
            return read(f)
    except InputError:
        raise
    except errors as exc:
        what = "decompressed" if compressed else "read"
        hint = "; the file is damaged or not compressed the way its name says" if compressed else ""
        raise InputError(f"{path} could not be {what} ({one_line(exc)}){hint}") from None


def _read_delimited(path: Path, fmt: str, sep: str | None, decimal: str,
                    notes: list[str]) -> pd.DataFrame:
    import pandas as pd

    compressed = path.suffix.lower() in COMPRESSION
    scan = _open_text(path, compressed, lambda f: _scan_text(f, path, compressed), (ValueError,))
    head = scan.head.decode(scan.encoding, errors="replace")
    if sep is None:
        default = {"csv": ",", "tsv": "\t"}.get(fmt, r"\s+")
        if decimal == "," and default == ",":
            default = ";"  # decimal commas: a comma separates no fields
        sep = sniff_separator(head, decimal) or default
        if sep != default:
            notes.append(f"fields separated by {_SEPARATORS[sep]} (found in the file; --sep to "
                         "choose another)")
    first = _data_lines(head, 1)[0]
    tokens = first.split() if sep == r"\s+" else first.split(sep)
    if len(tokens) > MAX_COLUMNS:
        raise InputError(f"{path} has {len(tokens)} fields in its first line (read as separated by "
                         f"{_SEPARATORS[sep]}), more than the {MAX_COLUMNS} columns glstat fit reads; "
                         "check the separator (--sep), or save the column to fit in a file of its own")
    if compressed and scan.line_ends * len(tokens) * 8 > MAX_DECOMPRESSED:
        # as many numbers as the decompressed text allows: 4 times its size for "1\n1\n..."
        raise InputError(f"{path} decompresses to {scan.line_ends} lines of {len(tokens)} field(s): up "
                         f"to {scan.line_ends * len(tokens)} values, "
                         f"{_mib(8 * scan.line_ends * len(tokens))} as numbers, more than the "
                         f"{_mib(MAX_DECOMPRESSED)} glstat fit holds for compressed input; decompress "
                         "it first (uncompressed files have no limit), or fit a part of it")
    opts: dict[str, Any] = {"sep": sep, "comment": "#", "index_col": False, "decimal": decimal}
    if sep != r"\s+":
        opts["skipinitialspace"] = True
    if decimal == "." and int(pd.__version__.split(".")[0]) < 3:
        opts["float_precision"] = "round_trip"  # pandas 3 parses floats exactly by default
    headerless = all(_is_number(t, decimal) for t in tokens)
    try:
        with warnings.catch_warnings():
            # rows longer than the header: an error, not a silent loss of fields
            warnings.simplefilter("error", pd.errors.ParserWarning)
            # numbers and text in one column: said when the column is used
            warnings.simplefilter("ignore", pd.errors.DtypeWarning)
            df = _open_text(path, compressed, lambda f: pd.read_csv(
                f, header=None if headerless else 0, encoding=scan.encoding, **opts))
    except pd.errors.ParserWarning as exc:
        raise _mismatch(exc, path, sep) from None
    except pd.errors.EmptyDataError:
        raise InputError(f"{path} is empty (no values, only blank or comment lines); give a file with "
                         "one value per line or a column of values") from None
    except pd.errors.ParserError as exc:
        raise _mismatch(exc, path, sep) from None
    except (ValueError, MemoryError) as exc:
        raise InputError(f"{path} could not be read as text separated by {_SEPARATORS.get(sep, sep)} "
                         f"({type(exc).__name__}); check the separator (--sep) and that every row has "
                         "the same number of fields") from None
    if headerless:
        df.columns = [str(i + 1) for i in range(df.shape[1])]
        lines = _data_lines(head)
        if sep == "," and decimal == "." and df.shape[1] == 2 and lines and all(
                _COMMA_PAIR.match(line) for line in lines):
            df.attrs["decimal_comma_like"] = lines[0].strip()
    else:
        df.columns = [str(c).strip() for c in df.columns]
        df = _drop_index_column(df, notes)
    return df


def _drop_index_column(df, notes: list[str]):
    """``df`` without a first column that has no header and holds 0, 1, 2, ... (or 1, 2, ...):
    the row index ``DataFrame.to_csv`` writes."""
    if df.shape[1] < 2:
        return df
    name = str(df.columns[0])
    if name and not name.startswith("Unnamed: 0"):
        return df
    col = df.iloc[:, 0]
    import numpy as np
    import pandas as pd

    if not pd.api.types.is_integer_dtype(col):
        return df
    values = col.to_numpy()
    start = int(values[0]) if values.size else 0
    if start in (0, 1) and np.array_equal(values, np.arange(start, start + values.size)):
        notes.append("the first column (no header, 0, 1, 2, ...) is a row index, not data")
        return df.iloc[:, 1:]
    return df


# ---------------------------------------------------------------------------------------------
# Parquet, Excel, NumPy
# ---------------------------------------------------------------------------------------------
def _read_parquet(path: Path, column: str | None) -> pd.DataFrame:
    try:
        import pyarrow  # noqa: F401
        import pyarrow.parquet as pq
    except ImportError as exc:
        raise InputError(f"reading Parquet ({path.name}) needs the package 'pyarrow', which is not "
                         "installed; install it with: pip install pyarrow   (or: pip install "
                         "'glstat[all]'), or save the data as CSV or .npy") from exc
    import pandas as pd

    try:
        pf = pq.ParquetFile(path)
        meta = pf.metadata
        wanted = _parquet_columns(pf.schema_arrow, column, path)
        size = 0
        for g in range(meta.num_row_groups):
            rg = meta.row_group(g)
            for c in range(rg.num_columns):
                chunk = rg.column(c)
                if chunk.path_in_schema in wanted:
                    size += int(chunk.total_uncompressed_size)
        values = meta.num_rows * len(wanted)
        if size > MAX_DECOMPRESSED or 8 * values > MAX_DECOMPRESSED:
            what = (f"{size} bytes of uncompressed data" if size > MAX_DECOMPRESSED else
                    f"{meta.num_rows} rows x {len(wanted)} column(s) = {values} values "
                    f"({_mib(8 * values)} as 8-byte numbers)")
            raise InputError(f"{path} declares {what} in the column(s) read, more than the "
                             f"{_mib(MAX_DECOMPRESSED)} glstat fit reads from Parquet; choose one "
                             "column with --column, or fit a part of the rows (a .npy or an "
                             "uncompressed CSV file has no limit)")
        df = pd.read_parquet(path, engine="pyarrow", columns=wanted)
    except InputError:
        raise
    except (OSError, ValueError, MemoryError, IndexError, KeyError) as exc:
        # pyarrow's ArrowInvalid derives from ValueError, ArrowMemoryError from MemoryError
        raise InputError(f"{path} could not be read as Parquet ({one_line(exc)}); the file is "
                         "damaged or not Parquet: write it again, or save the column as CSV") from None
    df.columns = [str(c) for c in df.columns]
    return df


#: Largest uncompressed XML of the sheet read from an Excel workbook, with its shared strings
#: (bytes): 32 MiB, about 600 000 numbers. openpyxl reads about 2.5 MiB of sheet XML a second
#: (32 MiB: 13 s on the reference machine); a larger sheet is refused before reading, and CSV
#: has no limit.
MAX_EXCEL_SHEET = 32 * 2**20
_XML_START = 2**16  # bytes of an XML part where a DOCTYPE or the <dimension> of a sheet is found
_DIMENSION = re.compile(rb'<(?:\w+:)?dimension\s[^>]*?\bref="([^"]*)"')
#: A cell with its reference; group 3 is "/" for an empty cell (``<c r="B2" s="1"/>``).
_CELL = re.compile(rb'<(?:\w+:)?c\s[^>]*?\br="([A-Z]{1,3})([0-9]{1,7})"[^>]*?(/?)>')
_REF = re.compile(r"\$?([A-Z]{1,3})\$?([0-9]{1,7})$")


def _column_number(letters: str) -> int:
    """1 for A, 27 for AA, 16384 for XFD."""
    n = 0
    for ch in letters:
        n = 26 * n + ord(ch) - 64
    return n


def _excel_error(path: Path, exc: BaseException) -> InputError:
    """An unreadable workbook, in one line (openpyxl's messages span lines and name their
    cause separately)."""
    def first(e: BaseException) -> str:
        lines = str(e).strip().splitlines()
        return f"{type(e).__name__}: {quoted(lines[0], 160) if lines else ''}".rstrip(": ")

    why = first(exc)
    if exc.__cause__ is not None:
        why += f"; {first(exc.__cause__)}"
    return InputError(f"{path} could not be read as an Excel workbook ({why}); the file is damaged "
                      "or not a workbook: open it in a spreadsheet and save the sheet as CSV")


def _first_sheet(archive: zipfile.ZipFile, path: Path) -> zipfile.ZipInfo | None:
    """The part of the first worksheet (the one pandas reads), from the workbook's listing."""
    import xml.etree.ElementTree as ET

    try:
        book = ET.fromstring(archive.read("xl/workbook.xml"))
        rels = ET.fromstring(archive.read("xl/_rels/workbook.xml.rels"))
    except KeyError:
        return None
    except ET.ParseError as exc:
        raise _excel_error(path, exc) from None
    targets = {r.get("Id"): r.get("Target", "") for r in rels
               if r.get("Type", "").endswith("/worksheet")}
    for sheet in book.iter():
        if sheet.tag.rsplit("}", 1)[-1] != "sheet":
            continue
        rid = next((v for k, v in sheet.attrib.items() if k.rsplit("}", 1)[-1] == "id"), None)
        target = targets.get(rid)
        if target:
            name = target.lstrip("/") if target.startswith("/") else f"xl/{target}"
            names = {n.lower(): n for n in archive.namelist()}
            found = names.get(name.lower())
            return archive.getinfo(found) if found else None
    return None


def _check_workbook(path: Path) -> None:
    """Refuse, from the archive's directory and a streamed scan of the first sheet, a workbook
    that would take more than :data:`MAX_DECOMPRESSED` to read or more than about ten seconds:
    members above the cap, XML with a DOCTYPE (entity expansion), a sheet above
    :data:`MAX_EXCEL_SHEET`, a used range (declared, or of the cells holding a value) of more
    than :data:`MAX_DECOMPRESSED` / 32 cells."""
    from contact.errors import TopographyFileError
    from contact.x3p import check_zip_member

    try:
        with zipfile.ZipFile(path) as archive:
            total = 0
            for info in archive.infolist():
                check_zip_member(info, str(path), repr(info.filename), limit=MAX_DECOMPRESSED)
                total += info.file_size
            if total > MAX_DECOMPRESSED:
                raise _too_big(path, "holds")
            for info in archive.infolist():
                if info.filename.lower().endswith((".xml", ".rels", ".vml")):
                    with archive.open(info) as f:
                        head = f.read(_XML_START)
                    if head.startswith((b"\xff\xfe", b"\xfe\xff")):
                        head = head.decode("utf-16", "replace").encode()
                    if b"<!DOCTYPE" in head or b"<!ENTITY" in head:
                        raise InputError(
                            f"{path} is not a valid Excel workbook: its part {quoted(info.filename)} "
                            "declares a DOCTYPE (XML entities, which workbooks never use: a damaged "
                            "file or an entity-expansion attack); save the sheet as CSV from the "
                            "program that made it")
            sheet = _first_sheet(archive, path)
            if sheet is None:
                return  # openpyxl says what is missing
            strings = next((i for i in archive.infolist()
                            if i.filename.lower() == "xl/sharedstrings.xml"), None)
            size = sheet.file_size + (strings.file_size if strings is not None else 0)
            if size > MAX_EXCEL_SHEET:
                raise InputError(
                    f"{path}: its first sheet holds {_mib(size)} of XML, more than the "
                    f"{_mib(MAX_EXCEL_SHEET)} glstat fit reads from Excel (reading takes about 0.4 s "
                    "per MiB); export the sheet as CSV (File > Save As > CSV), which has no limit")
            _check_used_range(archive, sheet, path)
    except TopographyFileError as exc:
        raise InputError(str(exc).replace("cannot be read", "cannot be read as Excel")) from None
    except (zipfile.BadZipFile, *_STREAM_ERRORS) as exc:
        raise _excel_error(path, exc) from None


def _check_used_range(archive: zipfile.ZipFile, sheet: zipfile.ZipInfo, path: Path) -> None:
    """Refuse a sheet whose declared used range (``<dimension ref=...>``) or whose farthest cell
    holding a value spans more than :data:`MAX_DECOMPRESSED` / 32 cells from A1: pandas makes a
    table of them all, about 30 bytes a cell (one cell at XFD1048576 is 17 billion)."""
    most = MAX_DECOMPRESSED // 32
    fix = ("delete the rows and columns after the data (select them, Delete; then save), or "
           "export the column to fit as CSV")
    with archive.open(sheet) as f:
        head = f.read(_XML_START)
        m = _DIMENSION.search(head)
        if m is not None:
            last = _REF.match(m.group(1).decode("ascii", "replace").split(":")[-1])
            if last is not None:
                rows, cols = int(last.group(2)), _column_number(last.group(1))
                if rows * cols > most:
                    raise InputError(
                        f"{path}: its first sheet declares the used range {m.group(1).decode()} "
                        f"({rows} rows x {cols} columns = {rows * cols} cells), more than the "
                        f"{most} cells glstat fit reads from Excel; {fix}")
        far_row = far_col = 0
        far = ""
        tail = b""
        chunk = head
        while chunk:
            block = tail + chunk
            cut = block.rfind(b"<")  # a cell tag cut by the chunk's end is scanned with the next
            cut = cut if cut > len(block) - 512 else len(block)
            for c in _CELL.finditer(block, 0, cut):
                if c.group(3):
                    continue
                row, col = int(c.group(2)), _column_number(c.group(1).decode())
                if row > far_row or col > far_col:
                    far_row, far_col = max(far_row, row), max(far_col, col)
                    if far_row * far_col > most:
                        far = c.group(1).decode() + c.group(2).decode()
                        raise InputError(
                            f"{path}: its first sheet has a value in cell {far}, so the table read "
                            f"spans {far_row} rows x {far_col} columns = {far_row * far_col} cells "
                            f"from A1, more than the {most} cells glstat fit reads from Excel; "
                            f"{fix}")
            tail = block[cut:]
            chunk = f.read(_CHUNK)


def _nested(dtype) -> str | None:
    """What a nested Arrow type holds, in words (None for a plain type)."""
    import pyarrow as pa

    if pa.types.is_fixed_size_list(dtype):
        return "fixed-size lists"
    if pa.types.is_map(dtype):
        return "maps (key-value pairs)"
    if pa.types.is_list(dtype) or pa.types.is_large_list(dtype) or (
            hasattr(pa.types, "is_list_view") and pa.types.is_list_view(dtype)):
        return "lists"
    if pa.types.is_struct(dtype):
        return "structures (several fields in one column)"
    if pa.types.is_nested(dtype) or pa.types.is_union(dtype):
        return f"nested values ({dtype})"
    return None


def _parquet_columns(schema, column: str | None, path: Path) -> list[str]:
    """The top-level columns of a Parquet file to read: the one chosen with ``column``, else
    every column of plain values; a chosen column holding lists, structures or maps, and
    columns whose names appear more than once, are refused."""
    from collections import Counter

    fields = list(schema)
    names = [f.name for f in fields]
    counts = Counter(names)
    hint = "choose a numeric column"
    plain = [f.name for f in fields if _nested(f.type) is None]
    listing = f" (columns of plain values: {_listing(plain)})" if plain else ""
    if column is not None:
        key = column.strip()
        if key in counts:
            chosen = [f for f in fields if f.name == key]
        elif key.isdigit() and 1 <= int(key) <= len(fields):
            chosen = [fields[int(key) - 1]]
        else:
            return names if all(n == 1 for n in counts.values()) else plain
        if counts[chosen[0].name] > 1:
            raise InputError(f"{path} has {counts[chosen[0].name]} columns named "
                             f"{quoted(chosen[0].name)}; rename them so that each name is unique, or "
                             "save the column to fit in a file of its own")
        kind = _nested(chosen[0].type)
        if kind is not None:
            raise InputError(f"column {quoted(chosen[0].name)} in {path} holds {kind}, not one number "
                             f"per row; {hint}{listing}")
        return [chosen[0].name]
    if not plain:
        first = fields[0]
        raise InputError(f"column {quoted(first.name)} in {path} holds {_nested(first.type)}, not one "
                         f"number per row, and no column holds plain values; {hint}, e.g. save the "
                         "values to fit as a column of numbers")
    repeated = [n for n in plain if counts[n] > 1]
    if repeated:
        raise InputError(f"{path} has {counts[repeated[0]]} columns named {quoted(repeated[0])}; "
                         "rename them so that each name is unique, or choose another column with "
                         "--column")
    return plain


def _read_excel(path: Path) -> pd.DataFrame:
    try:
        import openpyxl  # noqa: F401
    except ImportError as exc:
        raise InputError(f"reading Excel files ({path.name}) needs the package 'openpyxl', which is not "
                         "installed; install it with: pip install openpyxl   (or: pip install "
                         "'glstat[all]'), or save the sheet as CSV") from exc
    import xml.etree.ElementTree as ET

    import pandas as pd

    _check_workbook(path)
    try:
        df = pd.read_excel(path, engine="openpyxl")
    except MemoryError:
        raise
    except OverflowError:  # pandas converts a cell of 1E+400 (read as inf) with int()
        raise InputError(f"{path}: a cell holds a number beyond the floating-point range (such "
                         f"as 1E+400); correct the cell, or save the sheet as CSV") from None
    except (*_READ_ERRORS, KeyError, TypeError, IndexError, AttributeError, ET.ParseError) as exc:
        # openpyxl's errors of damaged parts: ValueError, KeyError, ParseError, ...
        raise _excel_error(path, exc) from None
    df.columns = [str(c).strip() for c in df.columns]
    return df


def _read_npy(path: Path) -> pd.DataFrame:
    import numpy as np
    import pandas as pd

    try:
        with open(path, "rb") as fh:
            try:
                version = np.lib.format.read_magic(fh)
            except ValueError as exc:
                if zipfile.is_zipfile(path):
                    raise InputError(f"{path} is a .npz archive, not a .npy array; save one array "
                                     "with numpy.save") from None
                raise InputError(f"{path} is not a NumPy .npy file ({one_line(exc)}); give a file "
                                 "written by numpy.save, or use a .csv or .txt name for text"
                                 ) from None
            read_header = (np.lib.format.read_array_header_1_0 if version == (1, 0)
                           else np.lib.format.read_array_header_2_0)
            shape, _fortran, dtype = read_header(fh)
            if dtype.hasobject:
                raise InputError(f"{path} holds Python objects (a pickled object array); save the "
                                 "values as a numeric array, e.g. np.save(path, np.asarray(values, "
                                 "dtype=float))")
            need = math.prod(shape) * dtype.itemsize
            stored = path.stat().st_size - fh.tell()
            if need > stored:
                raise InputError(f"{path} declares an array of shape {shape} and dtype {dtype} "
                                 f"({need} bytes) but holds {stored} bytes of data: a truncated or "
                                 "damaged file")
            fh.seek(0)
            arr = np.lib.format.read_array(fh, allow_pickle=False)
    except InputError:
        raise
    except EOFError as exc:
        raise InputError(f"{path} is empty: it holds no array") from exc
    except (ValueError, OSError, MemoryError) as exc:
        raise InputError(f"{path} is not a NumPy .npy file ({one_line(exc)}); give a file "
                         "written by numpy.save, or use a .csv or .txt name for text") from None
    if arr.dtype.names:
        sub = [n for n in arr.dtype.names if arr.dtype[n].shape != ()]
        if sub:
            raise InputError(f"{path} holds a structured array whose field(s) {', '.join(map(repr, sub))} "
                             "are arrays, not single values; save one plain column of values")
        return pd.DataFrame({str(name): arr[name].ravel() for name in arr.dtype.names})
    if arr.ndim == 0:
        arr = arr.reshape(1)
    if arr.ndim > 2:
        raise InputError(f"{path} holds an array of shape {arr.shape}; expected a 1-D array of values or "
                         "a 2-D array with one column per variable")
    if arr.ndim == 1:
        arr = arr[:, None]
    return pd.DataFrame({str(j + 1): arr[:, j] for j in range(arr.shape[1])})


# ---------------------------------------------------------------------------------------------
# the column
# ---------------------------------------------------------------------------------------------
def _numeric(series) -> bool:
    import pandas as pd

    return bool(pd.api.types.is_numeric_dtype(series) and not pd.api.types.is_bool_dtype(series)
                and not pd.api.types.is_complex_dtype(series))


def describe_columns(df) -> str:
    """The columns of ``df`` as ``'a', 'b' (not numeric)`` (the first 20, names shortened)."""
    parts = []
    for c in list(df.columns)[:_LISTED]:
        parts.append(quoted(c) + ("" if _numeric(df[c]) else " (not numeric)"))
    if df.shape[1] > _LISTED:
        parts.append(f"... ({df.shape[1] - _LISTED} more)")
    return ", ".join(parts)


def _decimal_comma_column(series) -> bool:
    values = series.dropna()
    if not values.size:
        return False
    first = values.iloc[:1000].astype(str)  # a column of text is told at once, not entry by entry
    if not first.map(lambda v: bool(_DECIMAL_COMMA.match(v))).all():
        return False
    values = values.astype(str)
    return bool(values.map(lambda v: bool(_DECIMAL_COMMA.match(v))).all()) \
        and bool(values.str.contains(",").any())


def _select_column(df, column: str | None, path: Path, fmt: str) -> tuple[str, Any]:
    names = list(df.columns)
    if column is not None:
        if column in names:
            return column, df[column]
        stripped = column.strip()
        if stripped in names:
            return stripped, df[stripped]
        if stripped.isdigit() and 1 <= int(stripped) <= len(names):
            name = names[int(stripped) - 1]
            return name, df[name]
        raise InputError(f"column {quoted(column)} not found in {path}; available columns: "
                         f"{describe_columns(df)} (or a 1-based position 1..{len(names)})")
    numeric = [c for c in names if _numeric(df[c])]
    if len(numeric) == 1:
        return numeric[0], df[numeric[0]]
    if not numeric and len(names) == 1 and fmt not in ("npy", "parquet", "excel"):
        import pandas as pd

        col = df[names[0]]
        # numbers among the entries: say which entries are not (a long column of text is told
        # from its first entries: converting every one takes a minute per 50 million)
        if pd.to_numeric(col.iloc[:10_000], errors="coerce").notna().any() or (
                len(col) <= 100_000 and pd.to_numeric(col, errors="coerce").notna().any()):
            return names[0], col
    if not numeric:
        hint = ("save the values as numbers (e.g. numpy.asarray(values, dtype=float))"
                if fmt in ("npy", "parquet", "excel") else
                "check the separator (--sep) and the decimal mark (--decimal), or choose a column "
                "with --column")
        raise InputError(f"{path} has no numeric column (columns: {describe_columns(df)}); the values "
                         f"to fit must be numbers - {hint}")
    if df.attrs.get("decimal_comma_like"):
        line = quoted(df.attrs["decimal_comma_like"])
        raise InputError(f"{path}: every line looks like one number with a decimal comma (e.g. "
                         f"{line}), read here as 2 columns separated by commas; "
                         "pass --decimal , to read them as numbers (or --column 1 or --column 2 if "
                         "they are two columns of integers)")
    example = numeric[-1] if len(str(numeric[-1])) <= 60 else names.index(numeric[-1]) + 1
    raise InputError(f"{path} has {len(numeric)} numeric columns ({_listing(numeric)}); choose the one "
                     f"to fit with --column, e.g. --column {example}")


def _to_float(series, name: str, path: Path, df) -> np.ndarray:
    import numpy as np
    import pandas as pd

    if _numeric(series):
        return series.to_numpy(dtype=float, na_value=np.nan)
    if pd.api.types.is_bool_dtype(series):
        raise InputError(f"column {quoted(name)} in {path} holds true/false values, not numbers; choose a "
                         f"numeric column (columns: {describe_columns(df)})")
    if pd.api.types.is_complex_dtype(series):
        raise InputError(f"column {quoted(name)} in {path} holds complex numbers; fit a real quantity")
    if pd.api.types.is_datetime64_any_dtype(series) or pd.api.types.is_timedelta64_dtype(series):
        raise InputError(f"column {quoted(name)} in {path} holds dates or times, not numbers; choose a "
                         f"numeric column (columns: {describe_columns(df)})")
    # a million entries at a time: converting text makes a Python object of every entry
    step = 1_000_000
    coerced = np.empty(len(series))
    stopped = False
    for start in range(0, len(series), step):
        part = series.iloc[start:start + step]
        underscore = part.astype("string").str.contains("_", regex=False).fillna(False)
        coerced[start:start + step] = pd.to_numeric(part.where(~underscore.to_numpy(dtype=bool)),
                                                    errors="coerce").to_numpy(dtype=float,
                                                                              na_value=np.nan)
        if start == 0 and len(series) > step and np.isnan(coerced[:step]).all() \
                and part.notna().any():
            stopped = True  # a long column of text: say so now, not after a minute
            break
    n = step if stopped else len(series)
    bad = np.isnan(coerced[:n]) & series.iloc[:n].notna().to_numpy()
    nbad = int(bad.sum())
    if nbad:
        row = int(np.flatnonzero(bad)[0])
        value = series.iloc[row]
        numeric = [c for c in df.columns if _numeric(df[c])]
        hint = (f"choose a numeric column ({_listing(numeric)}) with --column"
                if numeric else "clean the file so that the column holds only numbers")
        count = (f"none of its first {step} entries (of {len(series)}) is a number" if stopped
                 else f"{nbad} of {len(series)} entries are not numbers")
        raise InputError(f"column {quoted(name)} in {path} is not numeric: {count} (first: "
                         f"{quoted(value)} in data row {row + 1}); {hint}")
    return coerced


def read_sample(path: str | Path, column: str | None = None, nan_policy: str = "raise", *,
                sep: str | None = None, decimal: str = ".") -> Sample:
    """Read one column of values from a delimited text, Parquet, Excel or NPY file.

    Parameters
    ----------
    path : str or pathlib.Path
        The file; the format follows the name (see the module documentation). ``"-"`` reads
        standard input (:data:`STDIN`), its format found from its first bytes.
    column : str, optional
        Column name, or its 1-based position. Default: the only numeric column.
    nan_policy : {"raise", "omit"}, optional
        Missing, NaN or infinite entries: refuse the file, or leave them out.
    sep : str, optional
        Field separator of text files: ``","``, ``";"``, ``"tab"`` or ``"space"``
        (whitespace); found from the file when omitted.
    decimal : {".", ","}, optional
        Decimal mark of text files.

    Returns
    -------
    Sample
        The finite values (float64, in file order) and what was read.

    Raises
    ------
    InputError
        File not found, empty, unreadable, damaged or larger than the limits; unknown column
        (the message lists the available ones); several numeric columns and no ``column``; a
        non-numeric column; non-finite entries with ``nan_policy="raise"``; Parquet without
        ``pyarrow``, Excel without ``openpyxl``; standard input that is a terminal.
    """
    if str(path) != STDIN:
        return _read_file(Path(path), column, nan_policy, sep, decimal)
    if sys.stdin is None or sys.stdin.isatty():
        raise InputError("FILE is '-' (standard input) but standard input is a terminal; pipe "
                         "the data in (cat data.csv | glstat fit -) or give a file name")
    with _stdin_file(sys.stdin.buffer) as tmp:
        try:
            sample = _read_file(tmp, column, nan_policy, sep, decimal)
        except InputError as exc:
            raise InputError(str(exc).replace(str(tmp), "standard input")) from None
    notes = tuple(n.replace(str(tmp), "standard input") for n in sample.notes)
    return dataclasses.replace(sample, path=Path(STDIN), notes=notes)


def _read_file(path: Path, column: str | None, nan_policy: str, sep: str | None,
               decimal: str) -> Sample:
    """:func:`read_sample` of a file."""
    if nan_policy not in ("raise", "omit"):
        raise InputError(f"--nan-policy must be 'raise' or 'omit', got {nan_policy!r}")
    if decimal not in (".", ","):
        raise InputError(f"--decimal must be '.' or ',', got {decimal!r}")
    if sep is not None:
        if sep not in _SEP_NAMES:
            raise InputError(f"--sep must be one of ',', ';', 'tab' or 'space', got {quoted(sep)}")
        sep = _SEP_NAMES[sep]
        if sep == "," and decimal == ",":
            raise InputError("--sep , and --decimal , cannot both be commas; decimal commas come with "
                             "--sep ';' (or tab)")
    if not path.exists():
        raise InputError(f"file not found: {path} (looked in {path.resolve().parent}); check the path "
                         "and the file name")
    if path.is_dir():
        raise InputError(f"{path} is a directory; give a data file (.csv, .parquet, .xlsx, .npy or "
                         "text)")
    if path.stat().st_size == 0:
        raise InputError(f"{path} is empty (0 bytes); give a file with the values to fit")
    fmt = format_of(path)
    notes: list[str] = []
    try:
        if fmt == "parquet":
            df = _read_parquet(path, column)
        elif fmt == "npy":
            df = _read_npy(path)
        elif fmt == "excel":
            df = _read_excel(path)
        else:
            df = _read_delimited(path, fmt, sep, decimal, notes)
    except MemoryError:
        raise InputError(f"{path} is too large to read into memory; fit a part of it") from None
    if df.shape[1] == 0:
        raise InputError(f"{path} is empty: it has no columns")
    if df.shape[0] == 0:
        raise InputError(f"{path} has no data rows (columns: {describe_columns(df)}); give a file with "
                         "the values to fit")
    if fmt in ("csv", "tsv", "text") and decimal == ".":
        seps = [n for n in notes if "separated by" in n]
        comma_ok = not seps or "commas" not in seps[0]
        for c in list(df.columns):
            if comma_ok and not _numeric(df[c]) and _decimal_comma_column(df[c]):
                df[c] = pd_to_numeric_comma(df[c])
                if not any("decimal commas" in n for n in notes):
                    notes.append("decimal commas read as decimal points (--decimal , says so "
                                 "explicitly)")
    name, series = _select_column(df, column, path, fmt)
    if df.attrs.get("decimal_comma_like"):
        line = quoted(df.attrs["decimal_comma_like"])
        notes.append(f"every line looks like one number with a decimal comma (e.g. {line}); "
                     "read as two columns separated by commas, as "
                     "--column asks (--decimal , reads them as numbers)")
    import numpy as np

    values = _to_float(series, name, path, df)
    nan = np.isnan(values)
    inf = np.isinf(values)
    n_nan, n_inf = int(nan.sum()), int(inf.sum())
    if n_nan + n_inf == values.size:
        raise InputError(f"column {quoted(name)} in {path} holds no finite value ({values.size} entries, all "
                         "missing, NaN or infinite); choose another column or fix the file")
    if n_nan + n_inf:
        first = int(np.flatnonzero(nan | inf)[0]) + 1
        kinds = " and ".join(p for p in (f"{n_nan} missing/NaN" if n_nan else "",
                                         f"{n_inf} infinite" if n_inf else "") if p)
        if nan_policy == "raise":
            raise InputError(f"column {quoted(name)} in {path} has {kinds} value(s) out of {values.size} "
                             f"(first in data row {first}); they are refused (--nan-policy raise). Remove "
                             "them from the file, or pass --nan-policy omit to drop them")
        values = values[~(nan | inf)]
    return Sample(values=np.array(values, dtype=float), path=path, fmt=fmt, column=str(name),
                  n_total=int(nan.size), n_nan=n_nan, n_inf=n_inf, nan_policy=nan_policy,
                  notes=tuple(notes))


#: The file name that stands for standard input.
STDIN = "-"
#: The first bytes of the binary formats and compressions read from standard input.
_MAGIC = ((b"\x1f\x8b", ".gz"), (b"BZh", ".bz2"), (b"\xfd7zXZ\x00", ".xz"),
          (b"\x28\xb5\x2f\xfd", ".zst"), (b"\x93NUMPY", ".npy"), (b"PAR1", ".parquet"),
          (b"PK\x03\x04", ".zip"))


@contextlib.contextmanager
def _stdin_file(stream) -> Iterator[Path]:
    """Standard input copied, a chunk at a time, into a temporary file whose name gives its
    format (the files of a folder that is removed afterwards): the same reader, with the same
    limits, then reads it as any file."""
    import shutil
    import tempfile

    with tempfile.TemporaryDirectory(prefix="glstat-stdin-") as folder:
        raw = Path(folder) / "stdin"
        with open(raw, "wb") as f:
            shutil.copyfileobj(stream, f, _CHUNK)
        with open(raw, "rb") as f:
            first = f.read(_HEAD)
        yield raw.rename(raw.with_name("stdin" + _stdin_suffix(first, raw)))


def _stdin_suffix(first: bytes, path: Path) -> str:
    """The file name suffix of data whose first bytes are ``first``: a binary format or a
    compression from its signature, an Excel workbook among zip archives, ``.tsv`` or
    ``.csv`` for text whose first line holding a value has tabs or commas, else ``.txt``."""
    for magic, suffix in _MAGIC:
        if first.startswith(magic):
            if suffix == ".zip":
                with contextlib.suppress(zipfile.BadZipFile, OSError), zipfile.ZipFile(path) as z:
                    if "xl/workbook.xml" in z.namelist():
                        return ".xlsx"
            return suffix
    lines = _data_lines(first.decode("utf-8", errors="replace"), 1)
    line = lines[0] if lines else ""
    return ".tsv" if "\t" in line else ".csv" if "," in line else ".txt"


def pd_to_numeric_comma(series):
    """A column of decimal-comma numbers (``"1,5"``) as floats."""
    import pandas as pd

    return pd.to_numeric(series.astype("string").str.strip().str.replace(",", ".", regex=False))
