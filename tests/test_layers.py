"""The layers of the code: the statistics library imports without the contact package and
contact without glstat; scipy's private names come through glstat.distributions.scipy_base only; no module
imports another module's private names (beyond the listed ones)."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("glstat", "contact", "_glstat_runtime.numba_cache")
#: Private names shared between modules, each an exception to the rule: (importer, module, name).
KNOWN: set[tuple[str, str, str]] = set()


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
                if private and path.name != "scipy_base.py":
                    bad.append(f"{path.relative_to(ROOT)}: from {node.module} import ...")
    assert not bad, bad
    # and they are still where glstat.distributions.scipy_base takes them from
    from scipy.stats._distn_infrastructure import rv_continuous_frozen  # noqa: F401


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


#: Import cycles still present, each a set of modules (lazy imports inside functions count).
KNOWN_CYCLES: set[frozenset[str]] = set()


def _import_graph() -> dict[str, set[str]]:
    """Module -> the modules of the three packages it imports (module level or in functions;
    ``from . import name`` of a submodule imports that submodule only)."""
    mods = {}
    for pkg in PACKAGES:
        for f in (ROOT / pkg).rglob("*.py"):
            parts = list(f.relative_to(ROOT).with_suffix("").parts)
            mods[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = f
    graph: dict[str, set[str]] = {m: set() for m in mods}
    for m, f in mods.items():
        package = m.split(".") if f.name == "__init__.py" else m.split(".")[:-1]
        for node in ast.walk(ast.parse(f.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                base = package[: len(package) - node.level + 1] if node.level else []
                mod = ".".join(base + ([node.module] if node.module else []))
                subs = [f"{mod}.{a.name}" for a in node.names if f"{mod}.{a.name}" in mods]
                targets = subs if len(subs) == len(node.names) else [mod, *subs]
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            else:
                continue
            graph[m].update(t for t in targets if t in mods and t != m)
    return graph


def _cycles(graph: dict[str, set[str]]) -> set[frozenset[str]]:
    """The strongly connected components of more than one module (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: set[frozenset[str]] = set()
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            v, children = work[-1]
            w = next(children, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = set()
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.add(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    found.add(frozenset(comp))
    return found


def test_no_import_cycles_beyond_the_known_ones():
    found = _cycles(_import_graph())
    assert found <= KNOWN_CYCLES, [sorted(c) for c in found - KNOWN_CYCLES]
    assert KNOWN_CYCLES <= found, f"no longer a cycle, remove: {[sorted(c) for c in KNOWN_CYCLES - found]}"


def test_the_cycle_finder_finds_a_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert _cycles(graph) == {frozenset({"a", "b", "c"})}


#: The layers of glstat, bottom first: a unit (a folder of glstat, a loose module of it, or
#: another package) imports only units of a lower rank, and itself.
RANKS = {
    "_glstat_runtime": 0, "glstat.errors": 0, "glstat._version": 0,
    "glstat._core": 1, "glstat.regions": 1,
    "glstat._fit_engine": 2,
    "glstat.distributions": 3,
    "glstat.fitting": 4,
    "glstat.extremes": 5, "glstat.gof": 5,
    "glstat.resampling": 6,
    "glstat.prediction": 7, "glstat.plot": 7,
    "glstat.cross_validation": 8,
    "glstat": 9, "glstat.formatting": 9, "contact": 9,
    "glstat.__main__": 10, "glstat.study": 10,
    "glstat.cli": 11,
}


def _unit(module: str) -> str | None:
    parts = module.split(".")
    if parts[0] != "glstat":
        return parts[0] if parts[0] in RANKS else None
    return ".".join(parts[:2])


def test_every_glstat_unit_has_a_rank():
    units = {_unit(m) for m in _import_graph() if m.startswith("glstat")}
    assert units <= set(RANKS), sorted(units - set(RANKS))


def test_folders_import_only_the_layers_below():
    bad = []
    for module, targets in _import_graph().items():
        unit = _unit(module)
        if unit is None or unit == "contact" or unit == "_glstat_runtime":
            continue
        for target in targets:
            other = _unit(target)
            if other is not None and other != unit and RANKS[other] >= RANKS[unit]:
                bad.append(f"{module} imports {target} ({unit} {RANKS[unit]} -> {other} {RANKS[other]})")
    assert not bad, bad


def test_the_layer_rule_fails_on_an_upward_import(monkeypatch):
    monkeypatch.setitem(RANKS, "glstat.fitting", 8)  # the fits above the prediction: an upward edge
    with pytest.raises(AssertionError, match=r"glstat\.fitting"):
        test_folders_import_only_the_layers_below()


def _private(module: str) -> bool:
    last = module.rsplit(".", 1)[-1]
    return last.startswith("_") and not last.startswith("__")


def _folder(module: str, graph: dict[str, set[str]]) -> str:
    """The folder (package) a module lives in."""
    path = ROOT.joinpath(*module.split("."))
    return module if (path / "__init__.py").is_file() else module.rsplit(".", 1)[0]


def test_private_modules_are_used_only_inside_their_folder():
    graph = _import_graph()
    bad = sorted(f"{m} imports {t}" for m, targets in graph.items() for t in targets
                 if _private(t) and _folder(t, graph) != _folder(m, graph))
    assert not bad, bad


def test_glstat_has_at_most_twelve_loose_modules():
    loose = sorted(p.name for p in (ROOT / "glstat").glob("*.py"))
    assert len(loose) <= 12, loose


#: Public modules that gather names defined elsewhere, as their documentation says.
FACADES = {
    "contact/io.py",  # reading and writing of every format: ``contact.io.write``, ``FORMATS``
    "contact/like.py",  # surfaces like a measured one, with the spectrum fit and the comparison
}


def test_only_init_modules_re_export():
    bad = []
    for path in _modules():
        if path.name == "__init__.py" or str(path.relative_to(ROOT)) in FACADES:
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        defined, exported = set(), []
        for node in tree.body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                defined.add(node.name)
            elif isinstance(node, ast.Assign):
                for target in node.targets:
                    defined.update(n.id for n in ast.walk(target) if isinstance(n, ast.Name))
                    if (isinstance(target, ast.Name) and target.id == "__all__"
                            and isinstance(node.value, (ast.List, ast.Tuple))):
                        exported = [ast.literal_eval(e) for e in node.value.elts]
            elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
                defined.add(node.target.id)
        bad.extend(f"{path.relative_to(ROOT)}: {name}" for name in exported if name not in defined)
    assert not bad, bad


def test_no_function_over_120_lines_outside_numerical_kernels():
    long = []
    for path in _modules():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                kernel = any("njit" in ast.unparse(d) for d in node.decorator_list)
                lines = node.end_lineno - node.lineno + 1
                if lines > 120 and not kernel:
                    long.append(f"{path.relative_to(ROOT)}: {node.name} ({lines} lines)")
    assert not long, long
