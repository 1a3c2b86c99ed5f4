"""Every ```python block in README.md and docs/*.md runs as written.

Each block runs on its own, in a fresh namespace and an empty working directory, with the
Agg matplotlib backend. Text that is not meant to run (shell sessions, pseudo-code, output)
is fenced as ``text`` or ``bash``, never ``python``. docs/api.md is generated from the
docstrings and is checked by tests/test_docs_api.py.
"""

import re
import sys
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCUMENTS = [ROOT / "README.md", *sorted(p for p in (ROOT / "docs").glob("*.md") if p.name != "api.md")]
FENCE = re.compile(r"^```(\S*)[^\n]*\n(.*?)^```[ \t]*$", re.S | re.M)


def _blocks():
    out = []
    for path in DOCUMENTS:
        text = path.read_text(encoding="utf-8")
        for m in FENCE.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            out.append((path, line, m.group(1), m.group(2)))
    return out


BLOCKS = _blocks()
PYTHON = [b for b in BLOCKS if b[2] == "python"]


def test_snippets_found():
    assert len(DOCUMENTS) >= 10
    assert len(PYTHON) >= 13
    assert any(path.name == "README.md" for path, *_ in PYTHON)


def test_fences_are_python_or_marked_not_runnable():
    # a block tagged py, python3, pycon, ... would escape the run below
    bad = [f"{path.relative_to(ROOT)}:{line} ```{info}" for path, line, info, _ in BLOCKS
           if info not in ("", "python", "text", "bash", "console", "toml", "yaml", "json", "html")]
    assert not bad, f"use ```python for runnable code, ```text/```bash otherwise: {bad}"


@pytest.mark.parametrize("block", PYTHON, ids=[f"{p.relative_to(ROOT)}:{line}" for p, line, *_ in PYTHON])
def test_snippet_runs(block, tmp_path, monkeypatch):
    path, line, _, code = block
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    compiled = compile(code, f"{path.relative_to(ROOT)}:{line}", "exec")
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            exec(compiled, {"__name__": "__main__"})
    finally:
        if "matplotlib.pyplot" in sys.modules:
            sys.modules["matplotlib.pyplot"].close("all")
    # a warning the snippet gives must be explained on its page, not left for the reader to find
    text = path.read_text(encoding="utf-8")
    undocumented = sorted({w.category.__name__ for w in caught} - _words(text))
    assert not undocumented, f"warnings not mentioned in {path.name}: {undocumented}"
    if path.name == "README.md" and "glstat.bootstrap(" in code:
        # the tour's text describes exactly two BootstrapWarnings (failed resamples, branch jumps)
        messages = [str(w.message) for w in caught if w.category.__name__ == "BootstrapWarning"]
        assert len(messages) == 2, messages
        assert any("74 of 1000 resamples have no lmoments fit" in m for m in messages), messages
        assert any("jumped to another root branch" in m for m in messages), messages


def _words(text):
    return set(re.findall(r"\w+", text))
