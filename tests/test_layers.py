"""The layers of the code: the statistics library imports without the contact package and
contact without glstat; scipy's private names come through glstat._compat only; no module
imports another module's private names (beyond the listed ones)."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("glstat", "contact", "_glstat_numba")
#: Private names still shared between modules (the table kernels and the plots).
KNOWN = {
    # the table kernels share the region constants and residual of the exact solver
    ("glstat/_core/_table.py", "glstat._core._gld", "_R3A"),
    ("glstat/_core/_table.py", "glstat._core._gld", "_RMX"),
    ("glstat/_core/_table.py", "glstat._core._gld", "_case"),
    ("glstat/_core/_table.py", "glstat._core._gld", "_residual"),
    ("glstat/plot.py", "glstat.gof", "_as_float"),
    ("glstat/plot.py", "glstat.gof", "_models"),
}


def _run(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                          cwd=ROOT)


def test_statistics_library_imports_without_contact():
    proc = _run("import sys; sys.modules['contact'] = None\n"
                "import numpy as np, glstat\n"
                "x = np.random.default_rng(0).gamma(3.0, 1.0, 300)\n"
                "b = glstat.bootstrap(x, n_resamples=20, rng=1)\n"
                "print(float(b.damage_probability(12.0, 50).estimate))\n"
                "import glstat.plot, glstat.regions\n"
                "assert 'contact' not in [m.split('.')[0] for m in sys.modules if sys.modules[m]]")
    assert proc.returncode == 0, proc.stderr
    assert 0.0 <= float(proc.stdout.split()[-1]) <= 1.0


def test_contact_imports_without_glstat():
    proc = _run("import sys; sys.modules['glstat'] = None\n"
                "import contact\n"
                "s = contact.weierstrass((64, 64), 1e-3, 0.5, rq=1.6e-6, rng=1, n_terms=5)\n"
                "print(contact.solve(s, 20e6, 210e9, 0.3).mean_pressure)")
    assert proc.returncode == 0, proc.stderr


def _modules():
    for pkg in PACKAGES:
        yield from sorted((ROOT / pkg).rglob("*.py"))


def _dotted(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _resolve(path: Path, node: ast.ImportFrom) -> str:
    base = _dotted(path).split(".")
    if path.name != "__init__.py":
        base = base[:-1]
    if node.level > 1:
        base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _is_module(dotted: str) -> bool:
    p = ROOT.joinpath(*dotted.split("."))
    return p.with_suffix(".py").is_file() or (p / "__init__.py").is_file()


def test_scipy_privates_only_in_compat():
    bad = []
    for path in _modules():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("scipy"):
                private = any(p.startswith("_") for p in node.module.split(".")) or any(
                    a.name.startswith("_") for a in node.names)
                if private and path.name != "_compat.py":
                    bad.append(f"{path.relative_to(ROOT)}: from {node.module} import ...")
    assert not bad, bad
    # and they are still where glstat._compat takes them from
    from glstat._compat import ShapeInfo, rv_continuous_frozen  # noqa: F401


def test_no_private_names_across_modules():
    found = set()
    for path in _modules():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not (isinstance(node, ast.ImportFrom) and node.level):
                continue
            source = _resolve(path, node)
            for alias in node.names:
                if (alias.name.startswith("_") and not alias.name.startswith("__")
                        and not _is_module(f"{source}.{alias.name}")):
                    found.add((str(path.relative_to(ROOT)), source, alias.name))
    assert found <= KNOWN, sorted(found - KNOWN)
    assert KNOWN <= found, f"no longer needed, remove from KNOWN: {sorted(KNOWN - found)}"
