"""What a user installs: the console script answers --version without loading the package,
the source distribution holds the tests, docs, examples and benchmarks, and an unrelated
package named ``contact`` is detected with a clear message."""

from __future__ import annotations

import subprocess
import sys
import tarfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_version_answers_without_importing_the_package():
    code = ("import sys, _glstat_entry; _glstat_entry.main(['--version']); "
            "print(sorted(m for m in ('glstat', 'numpy', 'scipy', 'pandas') if m in sys.modules))")
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                         timeout=60)
    elapsed = time.perf_counter() - t0
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0].startswith("glstat ") and lines[1] == "[]"
    assert elapsed < 3.0  # a bare interpreter start; the package import alone takes about 1 s


def test_source_distribution_is_complete(tmp_path):
    out = subprocess.run([sys.executable, "-m", "build", "--sdist", "--outdir",
                          str(tmp_path), str(ROOT)], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    (sdist,) = tmp_path.glob("glstat-*.tar.gz")
    with tarfile.open(sdist) as tar:
        names = {"/".join(n.split("/")[1:]) for n in tar.getnames()}
    for required in ("tests/glstat", "tests/contact", "docs/index.md", "examples", "benchmarks",
                     "_glstat_entry.py", "glstat/py.typed", "contact/py.typed", "CHANGELOG.md"):
        assert any(n == required or n.startswith(required + "/") for n in names), required
    assert not any("__pycache__" in n for n in names)


def test_an_unrelated_contact_package_is_named(tmp_path):
    fake = tmp_path / "contact"
    fake.mkdir()
    (fake / "__init__.py").write_text("'''an unrelated package of the same name'''\n")
    code = "import glstat.study"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                         env={"PYTHONPATH": f"{tmp_path}", "PATH": ""}, cwd=tmp_path)
    assert out.returncode != 0
    assert "is not the contact package glstat ships" in out.stderr
    assert "pip uninstall contact" in out.stderr


def test_ctrl_c_while_the_command_starts_is_one_line(monkeypatch, capsys):
    """Ctrl-C during the first second (NumPy, SciPy and the kernels loading) ends with exit 130
    and one line, not a traceback of the import machinery."""
    import importlib.abc

    import _glstat_entry

    class Interrupting(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path=None, target=None):
            if name == "glstat.cli.commands":
                raise KeyboardInterrupt
            return None

    monkeypatch.delitem(sys.modules, "glstat.cli.commands", raising=False)
    monkeypatch.setattr(sys, "meta_path", [Interrupting(), *sys.meta_path])
    assert _glstat_entry.main(["fit", "x.csv"]) == 130
    err = capsys.readouterr().err
    assert err.strip() == "glstat: interrupted while starting; nothing was run"
