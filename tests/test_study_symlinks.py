"""Planted symbolic links in an output directory never make glstat write outside it: the lock
file and the report's figure folder are not followed (a victim file outside keeps its bytes)."""

from __future__ import annotations

import os

import pytest

from glstat.study import CampaignError
from glstat.study.errors import write_failure
from glstat.study.lock import LOCK_FILE, lock_directory
from glstat.study.report_document import Report


def test_a_planted_lock_symlink_is_refused_and_its_target_kept(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_bytes(b"precious")
    out = tmp_path / "out"
    out.mkdir()
    os.symlink(victim, out / LOCK_FILE)
    with pytest.raises(CampaignError, match="is a symbolic link"), lock_directory(out):
        pass
    assert victim.read_bytes() == b"precious"


def test_a_planted_figure_folder_symlink_is_refused(tmp_path):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "keep.png").write_bytes(b"png")
    out = tmp_path / "out"
    out.mkdir()
    os.symlink(elsewhere, out / "report_files")
    rep = Report("title")
    rep.paragraph("text")
    with pytest.raises(OSError) as info:
        rep.write(out)
    assert "symbolic link" in write_failure(info.value, info.value.filename)
    assert sorted(p.name for p in elsewhere.iterdir()) == ["keep.png"]
    # without the link the report is written
    os.unlink(out / "report_files")
    html, md = rep.write(out)
    assert html.is_file() and md.is_file()


def test_a_full_disk_while_writing_the_lock_is_one_clear_error(tmp_path, monkeypatch):
    import errno

    import glstat.study.lock as lock_mod

    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(lock_mod.os, "pwrite", full)
    with pytest.raises(CampaignError, match=r"No space left on device.*free some disk space"), \
            lock_directory(tmp_path / "out"):
        pass
    monkeypatch.undo()
    with lock_directory(tmp_path / "out"):  # the failed attempt left no lock behind
        pass
