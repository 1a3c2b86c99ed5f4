"""-v / -vv / -q on the command line: the library's log records and warnings."""

from __future__ import annotations

import logging
import os
import re
import subprocess
import sys
import warnings

import numpy as np
import pytest

from glstat.cli.commands import _logging_at, _verbosity


@pytest.mark.parametrize("argv, rest, level", [
    (["fit", "x.csv"], ["fit", "x.csv"], 0),
    (["-v", "fit", "x.csv"], ["fit", "x.csv"], 1),
    (["fit", "x.csv", "--verbose", "-v"], ["fit", "x.csv"], 2),
    (["-vv", "study"], ["study"], 2),
    (["study", "-q", "-v"], ["study"], -1),
])
def test_flags_are_taken_wherever_they_stand(argv, rest, level):
    assert _verbosity(argv) == (rest, level)


def _fit(tmp_path, *flags):
    data = tmp_path / "x.csv"
    np.savetxt(data, np.random.default_rng(0).gamma(3.0, 1.0, 300))
    return subprocess.run([sys.executable, "-m", "glstat.cli", *flags, "fit", str(data),
                           "--bootstrap", "30", "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=300)


def test_verbose_shows_the_library_log_and_default_does_not(tmp_path):
    quiet_default = _fit(tmp_path)
    assert quiet_default.returncode == 0 and "glstat.bootstrap:" not in quiet_default.stderr
    verbose = _fit(tmp_path, "-v")
    assert verbose.returncode == 0
    assert re.search(r"glstat\.bootstrap: bootstrap rs moments: \d+ of 30 resamples fitted",
                     verbose.stderr)
    assert "glstat.fitting.fit_functions:" not in verbose.stderr  # DEBUG records need -vv
    assert "glstat.fitting.fit_functions: fit rs moments" in _fit(tmp_path, "-vv").stderr


def test_quiet_silences_warnings_and_logs_and_restores_them():
    before = logging.getLogger("glstat").level, os.environ.get("TQDM_DISABLE")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with _logging_at(-1):
            warnings.warn("not shown", UserWarning, stacklevel=1)
            assert logging.getLogger("contact").level == logging.ERROR
            assert os.environ["TQDM_DISABLE"] == "1"  # no progress bar
        warnings.warn("shown", UserWarning, stacklevel=1)
    assert [str(w.message) for w in caught] == ["shown"]
    assert (logging.getLogger("glstat").level, os.environ.get("TQDM_DISABLE")) == before


def test_dask_logs_are_quiet_during_a_scheduler_run_and_restored_after():
    import logging

    from glstat.cli.commands import _QuietDaskLogs

    before = {n: logging.getLogger(n).level for n in ("distributed", "tornado")}
    with _QuietDaskLogs():
        assert all(logging.getLogger(n).level == logging.CRITICAL for n in before)
    assert {n: logging.getLogger(n).level for n in before} == before
