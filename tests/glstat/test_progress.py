"""Progress on standard error: a bar on a terminal, whole lines in a log."""

from __future__ import annotations

import io

from _glstat_runtime.progress import LineProgress, progress_bar


def test_a_log_gets_a_line_per_tenth_and_one_at_the_end():
    out = io.StringIO()
    p = LineProgress(20, "surfaces", "surface", initial=4, stream=out)
    for _ in range(16):
        p.update(1)
    p.close()
    p.close()  # once
    lines = out.getvalue().splitlines()
    assert [line.split(",")[0] for line in lines] == [
        f"surfaces: {k} of 20 surfaces ({5 * k} %)" for k in (6, 8, 10, 12, 14, 16, 18, 20)]
    assert "\r" not in out.getvalue()


def test_not_a_terminal_gives_lines_and_disabled_gives_nothing(capsys):
    bar = progress_bar(10, "resamples", "resample")  # pytest's stderr is not a terminal
    assert isinstance(bar, LineProgress)
    bar.update(10)
    bar.close()
    off = progress_bar(10, "resamples", "resample", enabled=False)
    off.update(10)
    off.close()
    assert capsys.readouterr().err.splitlines()[-1].startswith("resamples: 10 of 10 resamples")


def test_tqdm_disable_in_the_environment_silences_the_lines_too(capsys, monkeypatch):
    monkeypatch.setenv("TQDM_DISABLE", "1")  # as glstat -q sets it
    bar = progress_bar(10, "resamples", "resample")
    assert not isinstance(bar, LineProgress)
    bar.update(10)
    bar.close()
    assert capsys.readouterr().err == ""
