"""Regenerate a corpus of hostile and broken inputs and tally how the project handles them.

Run from the repository root::

    python benchmarks/hostile_inputs.py            # corpus in a temporary folder
    python benchmarks/hostile_inputs.py --keep DIR # keep the corpus in DIR
    python benchmarks/hostile_inputs.py --examples DIR  # also mutants of real instrument files

``--examples`` (default: the environment variable ``TOPOGRAPHY_EXAMPLES``) names a folder
holding real instrument files, such as SurfaceTopography's ``test/file_format_examples``;
those of ``tests/hostile.py``'s ``INSTRUMENT_FILES`` found there are read, truncated, with
flipped bytes and with header fields made inconsistent.

Every file is read in its own subprocess (``contact.read`` or ``glstat fit``) under a 6 GiB
address-space limit; the subprocess reports the outcome, the seconds and the peak memory
(``VmHWM`` after reading, reset after the imports, minus ``VmRSS`` then; SurfaceTopography is
imported before the reset for the formats only it reads). Bad API calls run in one
subprocess.
Outcomes:

* clear error: the project's error type (``TopographyFileError``, or the ``ValueError`` of a
  file that needs ``dx=`` or ``unit=`` / exit status 2 of ``glstat fit`` / ``TypeError``,
  ``ValueError``, ``FitError`` for API calls, naming the argument where the call says which)
  with a message on one line;
* accepted: a valid input read correctly; warned: accepted with a ``ContactWarning`` (or
  another warning, for API calls) saying that a value is implausible for its unit;
* unclear error: an API call refused with an error that does not name its argument;
* crash: any other exception (a traceback), more than one error line of ``glstat fit``, or
  more than 4 kB written to stderr while reading a file;
* silent: accepted (or accepted without the warning) although the input should be refused
  (or warned about);
* blow-up: more than ``--max-mb`` MB of peak memory or ``--max-seconds`` seconds, or the
  memory limit reached;
* hang: no answer within ``--hang-seconds`` (the subprocess is stopped).

The table of every case goes to ``benchmarks/results/hostile_inputs.json``.

The totals are those of docs/reliability.md. Campaign scenarios (lock, kill -9 and resume,
swapped files, disk full, signals) are tests: ``pytest tests/test_campaign_safety.py``.
"""

from __future__ import annotations

import argparse
import bz2
import importlib.util
import io
import json
import lzma
import os
import subprocess
import sys
import tempfile
import zipfile
import zlib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("hostile", ROOT / "tests" / "hostile.py")
hostile = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(hostile)


def _write(path: Path, data: bytes | str) -> Path:
    if isinstance(data, str):
        data = data.encode()
    path.write_bytes(data)
    return path


def _good_surface(folder: Path, ext: str) -> Path:
    import contact

    s = contact.weierstrass((16, 16), 1e-4, 0.5, rq=1e-6, rng=0, n_terms=4)
    path = folder / f"good{ext}"
    s.write(path)
    return path


def contact_corpus(d: Path, examples: Path | None = None) -> list[tuple[str, Path, str]]:
    """(name, file, expected) with expected "refused", "accepted", "warned" or "any" (either a
    reading or a clear error); mutants of the real files in ``examples`` when given."""
    cases = [(name, getattr(hostile, name)(d), "refused") for name in (
        "x3p_zip_bomb", "x3p_lying_bomb", "x3p_huge_grid", "x3p_encrypted", "x3p_deflate64",
        "x3p_broken_deflate", "x3p_inf", "x3p_entity_expansion", "npy_huge_header",
        "npz_huge_header", "npy_subarray", "xyz_diagonal", "text_inf", "text_underscore")]
    cases.append(("npz_junk_member", hostile.npz_junk_member(d), "accepted"))
    cases.append(("text_grid_300k_rows", hostile.text_grid(d, 300_000), "accepted"))
    for ext in (".npz", ".npy", ".txt", ".csv", ".xyz", ".x3p"):
        good = _good_surface(d, ext)
        cases.append((f"valid{ext}", good, "accepted"))
        blob = good.read_bytes()
        cases.append((f"truncated_half{ext}", _write(d / f"half{ext}", blob[: len(blob) // 2]), "refused"))
        cases.append((f"truncated_10_bytes{ext}", _write(d / f"ten{ext}", blob[:10]), "refused"))
        cases.append((f"empty{ext}", _write(d / f"empty{ext}", b""), "refused"))
        cases.append((f"random_bytes{ext}", _write(d / f"rand{ext}", np.random.default_rng(1).bytes(4096)),
                      "refused"))
    np.save(d / "bool.npy", np.ones((4, 4), bool))
    np.save(d / "complex.npy", np.ones((4, 4)) + 1j)
    np.save(d / "strings.npy", np.array([["a"] * 4] * 4))
    np.save(d / "objects.npy", np.array([[1.0, None]] * 4, dtype=object), allow_pickle=True)
    np.save(d / "oned.npy", np.ones(9))
    np.save(d / "twobytwo.npy", np.ones((2, 2)))
    np.save(d / "allnan.npy", np.full((4, 4), np.nan))
    np.savez(d / "noheights.npz", z=np.ones((4, 4)))
    np.savez(d / "negdx.npz", heights=np.ones((4, 4)), dx=-1.0)
    np.savez(d / "badmask.npz", heights=np.ones((4, 4)), dx=1e-6, mask=np.ones((3, 3), bool))
    np.savez(d / "objmember.npz", heights=np.array([[None] * 4] * 4, dtype=object), dx=1e-6)
    for name in ("bool.npy", "complex.npy", "strings.npy", "objects.npy", "oned.npy", "twobytwo.npy",
                 "allnan.npy", "noheights.npz", "negdx.npz", "badmask.npz", "objmember.npz"):
        cases.append((name.replace(".", "_"), d / name, "refused"))
    text = {
        "ragged.txt": "# dx = 1e-6\n1 2 3\n4 5\n7 8 9\n",
        "comments_only.txt": "# dx = 1e-6\n# nothing\n",
        "shape_mismatch.txt": "# shape = 4 3\n# dx = 1e-6\n1 2 3\n4 5 6\n7 8 9\n",
        "bad_dx.txt": "# dx = fast\n1 2 3\n4 5 6\n7 8 9\n",
        "hex.txt": "# dx = 1e-6\n1 2 3\n4 0x10 6\n7 8 9\n",
        "decimal_comma.csv": "# dx = 1e-6\n1,5;2,5;3,5\n",
        "nan_coords.xyz": "nan 0 1\n0 0 1\n1 0 1\n2 0 1\n0 1 1\n",
        "duplicates.xyz": "\n".join(f"{i % 3} {i // 3} 1" for i in range(9)) + "\n0 0 2\n",
        "irregular.xyz": "\n".join(f"{x} {y} 1" for x in (0, 1, 2.5) for y in (0, 1, 2)) + "\n",
        "two_columns.xyz": "0 0\n1 1\n2 2\n",
        "points_mismatch.xyz": "# points = 10\n" + "\n".join(f"{i % 3} {i // 3} 1" for i in range(9)),
        "latin1_garbage.txt": "# dx = 1e-6\n1 2 3\n4 \xe9 6\n7 8 9\n",
    }
    for name, content in text.items():
        cases.append((name.replace(".", "_"), _write(d / name, content.encode("latin-1")), "refused"))
    xml = hostile.x3p_xml(3, 3)
    with zipfile.ZipFile(d / "nomain.x3p", "w") as z:
        z.writestr("bindata/data.bin", bytes(72))
    with zipfile.ZipFile(d / "badxml.x3p", "w") as z:
        z.writestr("main.xml", b"<ISO5436_2><Record1>")
    with zipfile.ZipFile(d / "profile.x3p", "w") as z:
        z.writestr("main.xml", xml.replace(b"SUR", b"PRF"))
    with zipfile.ZipFile(d / "nodata.x3p", "w") as z:
        z.writestr("main.xml", xml)
    with zipfile.ZipFile(d / "external_entity.x3p", "w") as z:
        z.writestr("main.xml", b'<?xml version="1.0"?><!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]>'
                               b"<r><Record1><FeatureType>&x;</FeatureType></Record1></r>")
    for name in ("nomain.x3p", "badxml.x3p", "profile.x3p", "nodata.x3p", "external_entity.x3p"):
        cases.append((name.replace(".", "_"), d / name, "refused"))
    # complete compressed streams declaring 512 MiB to 2 GiB of heights in at most 0.5 MB
    for n, method in ((8192, "deflate"), (8192, "bzip2"), (8192, "lzma"), (16384, "bzip2")):
        cases.append((f"x3p_{n}x{n}_{method}", hostile.x3p_declared_grid(d, n, method, full=True),
                      "refused"))
    cases.append(("mat_8192x8192_in_0.5MB", hostile.mat_declared(d, 8192, 8192, full=True),
                  "refused"))
    # a known header with a bad value: refused by the built-in reader, never handed on
    for factor in ("0", "1e-320"):
        cases.append((f"matrix_factor_{factor}",
                      hostile.matrix_export(d, factor=factor, name=f"factor_{factor}.txt"),
                      "refused"))
    cases.append(("matrix_pixel_2147483648_m",
                  hostile.matrix_export(d, pixel="2147483648 m", name="pixel_2G.txt"), "warned"))
    cases.append(("gwyddion_without_width",
                  hostile.gwyddion_export(d, width=None, name="no_width.txt"), "refused"))
    cases.append(("gwyddion_without_height",
                  hostile.gwyddion_export(d, height=None, name="no_height.txt"), "refused"))
    cases.append(("x3p_case_folded_twin", hostile.x3p_twins(
        d, ("bindata/data.bin", "BINDATA/DATA.BIN"), "twin.x3p"), "accepted"))
    cases.append(("x3p_two_case_folded_twins", hostile.x3p_twins(
        d, ("BINDATA/DATA.BIN", "Bindata/Data.bin"), "two_twins.x3p"), "refused"))
    cases.append(("x3p_duplicate_member", hostile.x3p_twins(
        d, ("bindata/data.bin", "bindata/data.bin"), "duplicate.x3p"), "refused"))
    for ext in (".di", ".opd", ".plu", ".sur"):
        cases.append((f"random_bytes{ext}", _write(d / f"rand{ext}",
                                                   np.random.default_rng(2).bytes(4096)), "refused"))
        cases.append((f"empty{ext}", _write(d / f"empty{ext}", b""), "refused"))
    if examples is not None and examples.is_dir():
        cases += hostile.instrument_mutants(examples, d)
    return cases


def fit_corpus(d: Path) -> list[tuple[str, Path, str]]:
    rng = np.random.default_rng(2)
    x = rng.gamma(4.0, 1.0, size=300)
    f = d / "fit"
    f.mkdir(exist_ok=True)
    good = "\n".join(["pressure", *map(repr, x.tolist())]) + "\n"
    cases = [("valid_csv", _write(f / "good.csv", good), "accepted"),
             ("semicolon_decimal_comma", _write(f / "eu.csv", "id;pressure\n" + "\n".join(
                 f"s{i};{v!r}".replace(".", ",") for i, v in enumerate(x.tolist())) + "\n"), "accepted"),
             ("tab_separated_txt", _write(f / "tab.txt", "a\tpressure\n" + "\n".join(
                 f"s{i}\t{v!r}" for i, v in enumerate(x.tolist())) + "\n"), "accepted"),
             ("pandas_index_column", _write(f / "idx.csv", ",pressure\n" + "\n".join(
                 f"{i},{v!r}" for i, v in enumerate(x.tolist())) + "\n"), "accepted"),
             ("gzip_valid", _write(f / "good.csv.gz", __import__("gzip").compress(good.encode())),
              "accepted"),
             ("gzip_bomb", hostile.gzip_bomb(f), "refused-cap"),
             ("bz2_bomb", _write(f / "bomb.csv.bz2", bz2.compress(bytes(hostile.BOMB_BYTES))),
              "refused-cap"),
             ("xz_bomb", _write(f / "bomb.csv.xz", lzma.compress(bytes(hostile.BOMB_BYTES),
                                                                 preset=1)), "refused-cap"),
             ("header_mismatch", _write(f / "mm.csv", "a,b\n1,2\n3,4,5\n"), "refused"),
             ("underscore_number", _write(f / "us.csv", "p\n1_000\n" + good.split("\n", 1)[1]),
              "refused"),
             ("binary_garbage_csv", _write(f / "rand.csv", rng.bytes(5000)), "refused"),
             ("empty_csv", _write(f / "empty.csv", ""), "refused"),
             ("only_header", _write(f / "hdr.csv", "pressure\n"), "refused"),
             ("all_nan", _write(f / "nan.csv", "p\n" + "nan\n" * 20), "refused"),
             ("inf_values", _write(f / "inf.csv", "p\n" + "inf\n" + good.split("\n", 1)[1]),
              "refused"),
             ("broken_gzip", _write(f / "broken.csv.gz", __import__("gzip").compress(good.encode())[:200]),
              "refused"),
             ("npy_huge_header", hostile.npy_huge_header(f), "refused"),
             ("npy_subarray", hostile.npy_subarray(f), "refused"),
             ("npz_named_npy", _write(f / "z.npy", (d / "noheights.npz").read_bytes()), "refused"),
             ("npy_complex", _write(f / "c.npy", _npy(x + 1j)), "refused"),
             ("npy_3d", _write(f / "3d.npy", _npy(np.zeros((2, 3, 4)))), "refused"),
             ("npy_constant", _write(f / "k.npy", _npy(np.full(50, 3.0))), "refused-fit")]
    raw = b"1\n2\n3\n"
    cases.append(("zip_encrypted", _write(f / "enc.csv.zip", hostile.raw_zip(
        [("a.csv", raw, 0, zlib.crc32(raw), len(raw), 1)])), "refused"))
    comp = zlib.compressobj(9, zlib.DEFLATED, -15)
    cases.append(("zip_deflate64", _write(f / "d64.csv.zip", hostile.raw_zip(
        [("a.csv", comp.compress(raw) + comp.flush(), 9, zlib.crc32(raw), len(raw), 0)])), "refused"))
    with zipfile.ZipFile(f / "two.csv.zip", "w") as z:
        z.writestr("a.csv", good)
        z.writestr("b.csv", good)
    cases.append(("zip_two_members", f / "two.csv.zip", "refused"))
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq

        pq.write_table(pa.table({"pressure": x}), f / "good.parquet")
        cases.append(("valid_parquet", f / "good.parquet", "accepted"))
        _write(f / "trunc.parquet", (f / "good.parquet").read_bytes()[:300])
        cases.append(("truncated_parquet", f / "trunc.parquet", "refused"))
        for kind in ("list", "struct", "map", "fixed_list", "duplicate"):
            cases.append((f"parquet_{kind}_column", hostile.parquet_nested(f, kind), "refused"))
    except ImportError:
        pass
    cases.append(("valid_xlsx", hostile.xlsx_valid(f), "accepted"))
    for name in ("xlsx_far_cell", "xlsx_far_dimension", "xlsx_malformed", "xlsx_billion_laughs"):
        cases.append((name, getattr(hostile, name)(f), "refused"))
    cases.append(("xlsx_200MiB_sheet", hostile.xlsx_big_sheet(f, 200), "refused"))
    cases.append(("decimal_comma_one_column", _write(f / "dc.csv", "".join(
        f"{v:.2f}\n".replace(".", ",") for v in 100 * x)), "refused"))
    cases.append(("disk_full_when_writing", f / "good.csv", "refused-disk"))
    return cases


def _judged(outcome: str, expected: str) -> str:
    """``outcome`` of a file against ``expected``: a reading where a refusal or a warning was
    expected is silent; ``any`` accepts a reading, a warning or a clear error."""
    read = outcome in ("accepted", "warned")
    if expected == "warned" and outcome == "accepted":
        return "silent: accepted without a warning"
    if read and expected not in ("accepted", "warned", "any"):
        return "silent: accepted, expected a refusal"
    return outcome


def _npy(a: np.ndarray) -> bytes:
    buf = io.BytesIO()
    np.save(buf, a)
    return buf.getvalue()


CHILD = r"""
import json, resource, sys, time, traceback
resource.setrlimit(resource.RLIMIT_AS, (6 * 2**30, 6 * 2**30))
path, kind, out = sys.argv[1], sys.argv[2], sys.argv[3]
if kind == "fit":
    import glstat.cli.sample_files as ci
    from glstat.cli.fit import main
    import pandas, pyarrow.parquet, openpyxl, matplotlib.pyplot, glstat.gof, glstat.bootstrap
    ci.MAX_DECOMPRESSED = int(sys.argv[4])
    if sys.argv[5] == "refused-disk":  # every output file meets a full disk
        import errno, pathlib, matplotlib.figure
        def full(self, name=None, *args, **kwargs):
            target = self if isinstance(self, pathlib.Path) else name
            raise OSError(errno.ENOSPC, "No space left on device", str(target))
        pathlib.Path.write_text = full
        matplotlib.figure.Figure.savefig = full
else:
    import warnings
    import contact
    if sys.argv[6] == "st":  # read by SurfaceTopography: its import is not the reading
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                import SurfaceTopography
        except ImportError:
            pass
def _status(key):
    for line in open("/proc/self/status"):
        if line.startswith(key + ":"):
            return int(line.split()[1])
try:  # reset the peak (VmHWM) to the current size, so that only the reading counts
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")
except OSError:
    pass
before = _status("VmRSS")
t0 = time.perf_counter()
try:
    if kind == "fit":
        status = main([path, "--bootstrap", "0", "--gof-resamples", "0", "--out", out])
        outcome = {0: "accepted", 2: "clear error", 1: "clear error (no fit)"}.get(status, f"status {status}")
    else:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            contact.read(path, dx=1e-6 if path.endswith(".npy") else None)
        said = [w for w in caught if issubclass(w.category, contact.ContactWarning)]
        outcome = "warned" if said else "accepted"
except MemoryError:
    outcome = "blow-up (memory limit)"
except Exception as exc:
    import contact.errors
    text = str(exc)
    if "\n" in text.strip():
        outcome = f"crash: an error of {len(text.splitlines())} lines: " + text[:200]
    elif isinstance(exc, contact.errors.TopographyFileError):
        outcome = "clear error"
    elif type(exc) is ValueError and ("pass dx=" in text or "unit=" in text):
        outcome = "clear error (asks for dx= or unit=)"
    else:
        outcome = "crash: " + type(exc).__name__ + ": " + text[:200]
after = _status("VmHWM")
print(json.dumps({"outcome": outcome, "seconds": time.perf_counter() - t0,
                  "peak_mb": max(0, after - before) / 1024}))
"""

API = r"""
import json, re, sys, time, warnings
import numpy as np, pandas as pd
import contact, glstat
from glstat.errors import FitError
from glstat.study import AnalysisSettings, CampaignSettings
x = np.random.default_rng(0).normal(size=200)
h = np.random.default_rng(1).normal(size=(16, 16)) * 1e-6
s = contact.Surface(h, 1e-6)
calls = {
  "fit complex": lambda: glstat.fit(x + 1j),
  "fit datetime64": lambda: glstat.fit(x.astype("datetime64[s]")),
  "fit object with pd.NA": lambda: glstat.fit(np.array([*x, pd.NA], dtype=object)),
  "fit object with None": lambda: glstat.fit(np.array([*x, None], dtype=object)),
  "fit strings": lambda: glstat.fit(x.astype(str)),
  "fit booleans": lambda: glstat.fit(x > 0),
  "fit empty": lambda: glstat.fit([]),
  "fit scalar": lambda: glstat.fit(3.0),
  "fit 4 values": lambda: glstat.fit(x[:4]),
  "fit constant": lambda: glstat.fit(np.ones(50)),
  "fit nan raise": lambda: glstat.fit(np.r_[x, np.nan]),
  "fit bad param": lambda: glstat.fit(x, "xyz"),
  "fit bad method": lambda: glstat.fit(x, "rs", "guess"),
  "fit bad nan_policy": lambda: glstat.fit(x, nan_policy="drop"),
  "bootstrap complex": lambda: glstat.bootstrap(x + 1j, n_resamples=10),
  "bootstrap masked": lambda: glstat.bootstrap(np.ma.masked_less(x, -3), n_resamples=10, rng=1),
  "fit masked": lambda: glstat.fit(np.ma.masked_less(x, -3)),
  "fit pandas Float64 NA omit": lambda: glstat.fit(pd.Series([*x, pd.NA], dtype="Float64"),
                                                   nan_policy="omit"),
  "GLD bad lambdas": lambda: glstat.GLD(0, -1, 0.1, 0.1),
  "GLD nan": lambda: glstat.GLD(np.nan, 1, 0.1, 0.1),
  "Surface complex": lambda: contact.Surface(h + 1j, 1e-6),
  "Surface datetime": lambda: contact.Surface(h.astype("datetime64[s]"), 1e-6),
  "Surface pd.NA": lambda: contact.Surface(np.where(h > 0, h, pd.NA).astype(object), 1e-6),
  "Surface masked": lambda: contact.Surface(np.ma.masked_greater(h, 1e-6), 1e-6),
  "Surface 1-D": lambda: contact.Surface(h.ravel(), 1e-6),
  "Surface 2x2": lambda: contact.Surface(h[:2, :2], 1e-6),
  "Surface inf": lambda: contact.Surface(np.where(h > 1e-6, np.inf, h), 1e-6),
  "Surface dx 0": lambda: contact.Surface(h, 0.0),
  "Surface dx complex": lambda: contact.Surface(h, 1e-6 + 1j),
  "Surface dx string": lambda: contact.Surface(h, "1e-6"),
  "Surface mask shape": lambda: contact.Surface(h, 1e-6, mask=np.zeros((3, 3), bool)),
  "Surface mask all": lambda: contact.Surface(h, 1e-6, mask=np.ones(h.shape, bool)),
  "solve negative pressure": lambda: contact.solve(s, -1e6, 210e9, 0.3),
  "solve nan pressure": lambda: contact.solve(s, np.nan, 210e9, 0.3),
  "solve nu 0.7": lambda: contact.solve(s, 1e6, 210e9, 0.7),
  "solve E string": lambda: contact.solve(s, 1e6, "210e9", 0.3),
  "solve not a surface": lambda: contact.solve(h, 1e6, 210e9, 0.3),
  "weierstrass hurst 2": lambda: contact.weierstrass((16, 16), 1e-3, 2.0),
  "weierstrass shape 2": lambda: contact.weierstrass((2, 2), 1e-3, 0.5),
  "read missing file": lambda: contact.read("/nonexistent/file.npz"),
  "read dx negative": lambda: contact.read(__import__("sys").executable, dx=-1),
  "read bad format": lambda: contact.read(__import__("sys").executable, format="tiff"),
  "CampaignSettings one H": lambda: CampaignSettings(hurst=(0.5,)),
  "CampaignSettings H 2": lambda: CampaignSettings(hurst=(2.0,)),
  "CampaignSettings nu 0.6": lambda: CampaignSettings(nu=0.6),
  "CampaignSettings seed -1": lambda: CampaignSettings(seed=-1),
  "CampaignSettings grid 8": lambda: CampaignSettings(grid=8),
  "CampaignSettings n_terms 3 for 1 H": lambda: CampaignSettings(hurst=(0.5,), n_terms=(4, 4, 4)),
  "CampaignSettings grid 1e6": lambda: CampaignSettings(grid=10**6),
  "predict_maximum n 0.5": lambda: glstat.predict_maximum(x, n=0.5, n_resamples=10, rng=1),
  "predict_maximum n and count": lambda: glstat.predict_maximum(
      x, n=10, count=glstat.PoissonCount(10), n_resamples=10, rng=1),
  "GLD moment 1000": lambda: glstat.GLD(0, 0.197451, 0.134912, 0.134912).moment(1000),
}
#: Refused, with a message that must match the pattern (the argument's name): (call, pattern).
named = {
  "GLD lambda2 1e-320 (infinite scale)": (lambda: glstat.GLD(0, 1e-320, 0.1, 0.1), "lambda2"),
  "GLD shapes 1e308 (a point mass)": (lambda: glstat.GLD(0, 0.2, 1e308, 1e308), "lambda3"),
  "GLD FKML shapes 1e308": (lambda: glstat.GLD(0, 1, 1e308, 1e308, "fkml"), "lambda3"),
  "GLD lambda1 10**400": (lambda: glstat.GLD(10**400, 0.2, 0.1, 0.1), "lambda1"),
  "GLD lambda2 '0.2'": (lambda: glstat.GLD(0, "0.2", 0.1, 0.1), "lambda2"),
  "GLD lambda2 Decimal": (lambda: glstat.GLD(0, __import__("decimal").Decimal("0.2"), 0.1, 0.1),
                          "lambda2"),
  "GLD lambda1 pd.NA": (lambda: glstat.GLD(pd.NA, 0.2, 0.1, 0.1), "lambda1"),
  "GLD moment 10**6": (lambda: glstat.GLD(0, 0.197451, 0.134912, 0.134912).moment(10**6), "order"),
  "GLD moment 2.5": (lambda: glstat.GLD(0, 0.197451, 0.134912, 0.134912).moment(2.5), "order"),
  "gld_rs moment 10**6": (lambda: glstat.gld_rs.moment(10**6, 0.134912, 0.134912), "order"),
  "predict_maximum n 10**400": (lambda: glstat.predict_maximum(x, n=10**400, n_resamples=10),
                                r"\bn\b"),
  "predict_maximum n '10'": (lambda: glstat.predict_maximum(x, n="10", n_resamples=10), r"\bn\b"),
  "predict_maximum threshold pd.NA": (lambda: glstat.predict_maximum(
      x, n=10, threshold=pd.NA, n_resamples=10, rng=1), "threshold"),
  "predict_maximum threshold complex": (lambda: glstat.predict_maximum(
      x, n=10, threshold=1j, n_resamples=10, rng=1), "threshold"),
  "predict_maximum threshold array": (lambda: glstat.predict_maximum(
      x, n=10, threshold=np.array([1.0, 2.0]), n_resamples=10, rng=1), "threshold"),
  "predict_maximum threshold '5'": (lambda: glstat.predict_maximum(
      x, n=10, threshold="5", n_resamples=10, rng=1), "threshold"),
  "fit Series of text": (lambda: glstat.fit(pd.Series([str(v) for v in x])), "text"),
  "fit x * 1e307 (overflow)": (lambda: glstat.fit(x * 1e307), "1e\\+300"),
  "fit x * 1e-310 (subnormal)": (lambda: glstat.fit(x * 1e-310), "subnormal"),
  "Surface object array of text": (lambda: contact.Surface(h.astype(str).astype(object), 1e-6),
                                   "text"),
}
#: Valid but implausible for their unit: accepted with a warning that says so.
warned = {
  "fit a 250 x 2 table": lambda: glstat.fit(np.c_[x[:100], x[100:]] + 5),
  "AnalysisSettings hardness in MPa": lambda: AnalysisSettings(hardness=2050),
  "CampaignSettings pressure 20 Pa": lambda: CampaignSettings(pressures=(20.0,)),
  "CampaignSettings E 210 Pa": lambda: CampaignSettings(E=210.0),
  "CampaignSettings rq 1.6 m": lambda: CampaignSettings(rq=1.6),
  "CampaignSettings length 1 m": lambda: CampaignSettings(length=1.0),
  "solve_bem load 20 Pa": lambda: contact.solve_bem(s, 20.0, 210e9, 0.3),
  "weierstrass rq 1.6 m": lambda: contact.weierstrass((16, 16), 1e-3, 0.5, rq=1.6),
  "Surface dx 1e300 m": lambda: contact.Surface(h, 1e300),
  "Surface dx 2147483648 m": lambda: contact.Surface(h, 2147483648.0),
  "Surface dx 1e-13 m": lambda: contact.Surface(h * 1e-9, 1e-13),
}
clear = (TypeError, ValueError, FitError, FileNotFoundError)
out = {}
for name, call in warned.items():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            call()
        except Exception as exc:
            out[name] = "crash: " + type(exc).__name__ + ": " + str(exc)[:120]
            continue
    said = [w for w in caught if issubclass(w.category, (UserWarning, DeprecationWarning))]
    out[name] = "warned" if said else "silent: accepted without a warning"
warnings.simplefilter("ignore")
for name, call in [*calls.items(), *named.items()]:
    call, pattern = call if isinstance(call, tuple) else (call, None)
    t0 = time.perf_counter()
    try:
        call()
        out[name] = "accepted" if pattern is None else "silent: accepted, expected a refusal"
    except clear as exc:
        text = str(exc).strip()
        if not text or "\n" in text:
            out[name] = "crash: " + ("empty message" if not text else "a message of several lines")
        elif pattern is not None and not re.search(pattern, text):
            out[name] = f"unclear error: does not name {pattern!r}: " + text[:120]
        else:
            out[name] = "clear error"
    except MemoryError:
        out[name] = "blow-up (memory)"
    except Exception as exc:
        out[name] = "crash: " + type(exc).__name__ + ": " + str(exc)[:120]
    if time.perf_counter() - t0 > float(sys.argv[1]) and not out[name].startswith("blow-up"):
        out[name] = f"blow-up: {time.perf_counter() - t0:.1f} s: " + out[name]
print(json.dumps(out))
"""


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--keep", help="write the corpus to this folder and keep it")
    p.add_argument("--examples", default=os.environ.get("TOPOGRAPHY_EXAMPLES"),
                   help="a folder of real instrument files (SurfaceTopography's "
                        "test/file_format_examples) to mutate; default $TOPOGRAPHY_EXAMPLES")
    p.add_argument("--max-mb", type=float, default=200.0, help="peak memory counted as a blow-up")
    p.add_argument("--max-seconds", type=float, default=10.0, help="time counted as a blow-up")
    p.add_argument("--hang-seconds", type=float, default=120.0,
                   help="time after which a case is stopped and counted as a hang")
    p.add_argument("--cap-mb", type=int, default=256,
                   help="decompression cap of glstat fit during the run (MiB; default the "
                        "shipped 256)")
    args = p.parse_args(argv)
    tmp = None
    if args.keep:
        d = Path(args.keep)
        d.mkdir(parents=True, exist_ok=True)
    else:
        tmp = tempfile.TemporaryDirectory()
        d = Path(tmp.name)
    rows = []
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    examples = Path(args.examples) if args.examples else None
    from contact.io import FORMATS

    for kind, cases in (("contact", contact_corpus(d, examples)), ("fit", fit_corpus(d))):
        for name, path, expected in cases:
            st = "st" if kind == "contact" and path.suffix.lower() not in FORMATS else "-"
            try:
                proc = subprocess.run([sys.executable, "-c", CHILD, str(path), kind,
                                       str(d / "out" / name), str(args.cap_mb * 2**20), expected,
                                       st],
                                      capture_output=True, text=True, timeout=args.hang_seconds,
                                      cwd=ROOT, env=env, errors="replace")
            except subprocess.TimeoutExpired:
                got = {"outcome": f"hang: no answer within {args.hang_seconds:.0f} s",
                       "seconds": args.hang_seconds, "peak_mb": float("nan")}
            else:
                try:
                    got = json.loads(proc.stdout.strip().splitlines()[-1])
                except (IndexError, ValueError):
                    got = {"outcome": f"crash: child died ({proc.returncode}) {proc.stderr[-200:]}",
                           "seconds": float("nan"), "peak_mb": float("nan")}
                if "Traceback" in proc.stderr and not got["outcome"].startswith("crash"):
                    got["outcome"] = "crash: traceback on stderr"
                lines = [ln for ln in proc.stderr.splitlines() if ln.startswith("glstat fit: error")]
                if got["outcome"].startswith("clear error") and kind == "fit" and len(lines) != 1:
                    got["outcome"] = f"crash: {len(lines)} error lines on stderr"
                if kind == "contact" and len(proc.stderr) > 4096:
                    got["outcome"] = f"crash: {len(proc.stderr)} bytes on stderr"
                got["stderr_bytes"] = len(proc.stderr)
                got["outcome"] = _judged(got["outcome"], expected)
            if got["peak_mb"] > args.max_mb or got["seconds"] > args.max_seconds:
                if not got["outcome"].startswith("hang"):
                    got["outcome"] = "blow-up: " + got["outcome"]
            rows.append({"kind": kind, "name": name, "expected": expected, **got})
            print(f"{kind:8s} {name:32s} {got['outcome'][:60]:60s} {got['seconds']:6.2f} s "
                  f"{got['peak_mb']:8.1f} MB", flush=True)
    api = subprocess.run([sys.executable, "-c", API, str(args.max_seconds)], capture_output=True,
                         text=True, timeout=600, cwd=ROOT)
    calls = json.loads(api.stdout.strip().splitlines()[-1])
    for name, outcome in calls.items():
        print(f"api      {name:32s} {outcome[:60]}")
    outcomes = [r["outcome"] for r in rows] + list(calls.values())
    wrong_accept = [r["name"] for r in rows if r["outcome"].startswith("silent")]
    wrong_refuse = [r["name"] for r in rows if r["expected"] in ("accepted", "warned")
                    and r["outcome"] not in ("accepted", "warned")
                    and not r["outcome"].startswith("silent")]
    total = {
        "files": len(rows), "api calls": len(calls),
        "clear errors": sum(o.startswith("clear error") for o in outcomes),
        "accepted": sum(o == "accepted" for o in outcomes),
        "warned (valid but implausible for its unit)": sum(o == "warned" for o in outcomes),
        "unclear errors (refused without naming the argument)":
            sum(o.startswith("unclear") for o in outcomes),
        "crashes": sum(o.startswith("crash") for o in outcomes),
        "blow-ups": sum(o.startswith("blow-up") for o in outcomes),
        "hangs": sum(o.startswith("hang") for o in outcomes),
        "silent (accepted, expected a refusal or a warning)":
            len(wrong_accept) + sum(o.startswith("silent") for o in calls.values()),
        "refused files expected to be read": wrong_refuse,
        "read files expected to be refused": wrong_accept,
        "largest peak of a refused file (MB)": max((r["peak_mb"] for r in rows
                                                    if r["outcome"].startswith("clear")), default=0),
        "slowest refusal (s)": max((r["seconds"] for r in rows if r["outcome"].startswith("clear")),
                                   default=0),
    }
    print(json.dumps(total, indent=1))
    if tmp is not None:
        tmp.cleanup()
    out = ROOT / "benchmarks" / "results" / "hostile_inputs.json"
    out.write_text(json.dumps({"totals": total, "cases": rows, "api": calls}, indent=1) + "\n")
    print(f"wrote {out.relative_to(ROOT)}")
    silent_calls = [n for n, o in calls.items() if o.startswith(("silent", "unclear"))]
    return 1 if (total["crashes"] or total["blow-ups"] or total["hangs"] or wrong_accept
                 or wrong_refuse or silent_calls) else 0


if __name__ == "__main__":
    sys.exit(main())
