"""Text grids are read in memory proportional to the result, however wide their rows.

Peak memory is measured in a subprocess (``VmHWM`` of /proc/self/status after reading, reset
after the imports, minus ``VmRSS`` then), as in tests/test_hostile_inputs.py.
"""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import contact
from contact import _text_files

CHILD = r"""
import hashlib, json, sys
import numpy as np
import contact
from contact._text_files import read_text
path = sys.argv[1]
def _status(key):
    for line in open("/proc/self/status"):
        if line.startswith(key + ":"):
            return int(line.split()[1])
def _reset():  # the peak (VmHWM) back to the current size, so that only the reading counts
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        pass
    return _status("VmRSS")
before = _reset()
h = read_text(path, path)[0]
reader_mb = (_status("VmHWM") - before) / 1024
del h
before = _reset()
s = contact.read(path)
read_mb = (_status("VmHWM") - before) / 1024
heights = np.where(s.mask, 0.0, s.heights)
print(json.dumps({"reader_mb": reader_mb, "read_mb": read_mb, "shape": list(s.shape),
                  "masked": int(s.mask.sum()),
                  "sha": hashlib.sha256(heights.tobytes()).hexdigest()}))
"""


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs /proc (Linux)")
def test_wide_text_grid_is_read_in_memory_proportional_to_the_array(tmp_path):
    """A 1024 x 1024 grid (one 24 kB line per x) costs a small multiple of its 8 MiB array,
    and every value round-trips exactly."""
    n = 1024
    rng = np.random.default_rng(3)
    h = rng.standard_normal((n, n)) * 1e-6
    mask = np.zeros(h.shape, dtype=bool)
    mask[5, 700] = mask[1000, 3] = True
    path = tmp_path / "wide.txt"
    contact.Surface(h, 1e-6, mask=mask).write(path)
    out = subprocess.run([sys.executable, "-c", CHILD, str(path)], capture_output=True,
                         text=True, timeout=120, cwd=Path(__file__).resolve().parents[2])
    assert out.returncode == 0, out.stderr[-2000:]
    got = json.loads(out.stdout.strip().splitlines()[-1])
    array_mb = h.nbytes / 2**20
    assert got["shape"] == [n, n] and got["masked"] == 2, got
    assert got["sha"] == hashlib.sha256(np.where(mask, 0.0, h).tobytes()).hexdigest()
    assert got["reader_mb"] < 2 * array_mb + 20, (got, array_mb)
    assert got["read_mb"] < 3 * array_mb + 50, (got, array_mb)


@pytest.mark.filterwarnings("ignore:the RMS of the heights:contact.errors.ContactWarning")  # unit-free
def test_text_grid_with_more_rows_than_room_and_many_comment_lines(tmp_path, monkeypatch):
    """A grid followed by many comment lines is returned as its own array (not a view of
    the room reserved for them), and rows beyond that room (a file that grew while read)
    are kept."""
    rng = np.random.default_rng(4)
    h = rng.standard_normal((40, 5))
    path = tmp_path / "g.txt"
    np.savetxt(path, h, fmt="%.17g", header="dx = 1e-6", footer="\n".join(["comment"] * 200))
    heights, dx, dy, mask = _text_files.read_text(path, "g.txt")
    np.testing.assert_array_equal(heights, h)
    assert heights.base is None and (dx, dy, mask) == (1e-6, None, None)
    np.testing.assert_array_equal(contact.read(path).heights, h)
    monkeypatch.setattr(_text_files, "_BATCH", 7)
    monkeypatch.setattr(_text_files, "_extent", lambda path, fname: (1, 1))  # room for 1 row
    heights = _text_files.read_text(path, "g.txt")[0]
    np.testing.assert_array_equal(heights, h)
