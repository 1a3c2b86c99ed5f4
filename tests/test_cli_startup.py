"""``import glstat`` and the command line's help and option errors load no numerical library:
the public names are imported on first use, the parsers need only the standard library."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import glstat

ROOT = Path(__file__).resolve().parents[1]
HEAVY = {"numpy", "scipy", "numba", "pandas", "matplotlib"}


def _imported(args: list[str]) -> tuple[subprocess.CompletedProcess, set[str]]:
    """Run ``python -X importtime ARGS``; the process and the top-level packages it imported."""
    proc = subprocess.run([sys.executable, "-X", "importtime", *args], capture_output=True,
                          text=True, timeout=120, cwd=ROOT)
    lines = [ln for ln in proc.stderr.splitlines() if ln.startswith("import time:")]
    assert lines, proc.stderr
    names = {ln.rsplit("|", 1)[-1].strip().split(".")[0] for ln in lines[1:]}
    return proc, names


@pytest.mark.parametrize(("argv", "status"), [
    (["fit", "--help"], 0),
    (["study", "--help"], 0),
    (["--help"], 0),
    (["fit", "--bootstrap", "-1", "x.csv"], 2),
    (["fit", "--method", "nope", "x.csv"], 2),
    (["study", "--hurst", "2"], 2),
])
def test_help_and_option_errors_load_no_numerical_library(argv, status):
    proc, names = _imported(["-m", "glstat.cli", *argv])
    assert proc.returncode == status, proc.stderr
    assert "glstat" in names
    assert not names & HEAVY, sorted(names & HEAVY)


def test_the_console_script_answers_help_without_numpy():
    proc, names = _imported(["-c", "import sys, _glstat_entry; "
                                   "sys.exit(_glstat_entry.main(['fit', '--help']))"])
    assert proc.returncode == 0, proc.stderr
    assert "usage: glstat fit" in proc.stdout
    assert not names & HEAVY, sorted(names & HEAVY)


def test_an_option_error_is_reported_as_before(capsys):
    from glstat.cli.commands import main

    assert main(["fit", "--bootstrap", "-1", "x.csv"]) == 2
    err = capsys.readouterr().err
    assert err.strip() == "glstat fit: error: --bootstrap must be 0 (no bootstrap) or at least 2, got -1"


def test_import_glstat_loads_no_numerical_library():
    code = ("import sys, glstat\n"
            "print(sorted({m.split('.')[0] for m in sys.modules} & set(sys.argv[1:])))\n"
            "print(type(glstat.GLD).__name__, 'numpy' in sys.modules)")
    proc = subprocess.run([sys.executable, "-c", code, *sorted(HEAVY)], capture_output=True,
                          text=True, timeout=120, cwd=ROOT)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines() == ["[]", "type True"]


def test_every_public_name_resolves_and_is_listed():
    for name in glstat.__all__:
        assert getattr(glstat, name) is not None
    assert set(glstat.__all__) <= set(dir(glstat))
    assert "__version__" in dir(glstat)
    with pytest.raises(AttributeError, match="no attribute 'not_a_name'"):
        glstat.not_a_name


@pytest.mark.parametrize("module", ["glstat._core.elementary", "glstat._fit_engine.kernels",
                                    "contact._influence"])
def test_a_kernel_module_registers_the_cache_locator_first(module):
    """The numba cache locator is in place whichever kernel module is imported first."""
    code = (f"import sys, importlib\n"
            f"importlib.import_module({module!r})\n"
            f"from numba.core import caching\n"
            f"impl = getattr(caching, 'CacheImpl', None) or getattr(caching, '_CacheImpl')\n"
            f"print(any(getattr(c, '_glstat_locator', False) for c in impl._locator_classes))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=300, cwd=ROOT)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "True"


def test_ctrl_c_while_the_fit_loads_is_one_line(monkeypatch, capsys):
    """Ctrl-C while NumPy, SciPy and the fits load, after the options were checked: exit 130
    and one line."""
    import importlib.abc

    import _glstat_entry

    class Interrupting(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path=None, target=None):
            if name == "glstat.cli.fit":
                raise KeyboardInterrupt
            return None

    monkeypatch.delitem(sys.modules, "glstat.cli.fit", raising=False)
    monkeypatch.setattr(sys, "meta_path", [Interrupting(), *sys.meta_path])
    assert _glstat_entry.main(["fit", "x.csv"]) == 130
    err = capsys.readouterr().err
    assert err.strip() == "glstat: interrupted while starting; nothing was run"
