"""The documentation site renders every public name, and the gallery shows the examples' code.

docs/reference.md is rendered by mkdocstrings, which reads the sources statically (griffe).
A ``::: module`` entry renders the names the module binds in its own source (imports,
definitions, assignments) and that carry a docstring; it misses a name imported on first use
(a module ``__getattr__``) and a function that has the name of a submodule (the submodule
wins). Such names need an explicit ``::: defining.module.name`` entry. This test reads the
entries of docs/reference.md and checks every name of the public ``__all__`` lists against
them, with the same rules, without building the site (``bash .ci/docs`` builds it).
"""

from __future__ import annotations

import ast
import functools
import importlib
import importlib.util
import inspect
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PUBLIC_MODULES = ["glstat", "glstat.plot", "glstat.regions", "glstat.study", "contact"]
ENTRY = re.compile(r"^::: *(?P<path>[\w.]+) *$", re.M)


def _entries() -> list[str]:
    return ENTRY.findall((DOCS / "reference.md").read_text(encoding="utf-8"))


@functools.cache
def _source(module_name: str) -> tuple[Path, ast.Module]:
    origin = importlib.util.find_spec(module_name).origin
    path = Path(origin)
    return path, ast.parse(path.read_text(encoding="utf-8"))


def _is_type_checking_block(node: ast.stmt) -> bool:
    """Whether ``node`` is ``if TYPE_CHECKING:`` (the static reader renders its imports, as the
    package's names that load on first use are declared there)."""
    return (isinstance(node, ast.If) and isinstance(node.test, ast.Name)
            and node.test.id == "TYPE_CHECKING")


def _top_level_bindings(tree: ast.Module) -> dict[str, ast.stmt]:
    """Names bound by the module's own top-level statements, the imports of a top-level
    ``if TYPE_CHECKING:`` block included (not inside ``__getattr__``)."""
    out: dict[str, ast.stmt] = {}
    body = [n for node in tree.body
            for n in (node.body if _is_type_checking_block(node) else [node])]
    for node in body:
        if isinstance(node, ast.ImportFrom | ast.Import):
            for alias in node.names:
                out[alias.asname or alias.name.split(".")[0]] = node
        elif isinstance(node, ast.FunctionDef | ast.ClassDef):
            out[node.name] = node
        elif isinstance(node, ast.Assign):
            for target in node.targets:
                if isinstance(target, ast.Name):
                    out[target.id] = node
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            out[node.target.id] = node
    return out


def _is_submodule(module_name: str, name: str) -> bool:
    path, _ = _source(module_name)
    return path.name == "__init__.py" and ((path.parent / f"{name}.py").is_file()
                                           or (path.parent / name / "__init__.py").is_file())


def _data_documented(module_name: str, name: str, value: object, depth: int = 0) -> bool:
    """A docstring for module data, as the site finds it: a string literal after the
    assignment, ``#:`` comments above it, or (an exported class or object built at import
    time) the docstring of the object itself; followed through ``from ... import``."""
    if inspect.isclass(value) or "__doc__" in getattr(value, "__dict__", {}):
        return bool((value.__doc__ or "").strip())
    path, tree = _source(module_name)
    node = _top_level_bindings(tree).get(name)
    if node is None or depth > 5:
        return False
    if isinstance(node, ast.ImportFrom):
        source = importlib.util.resolve_name("." * node.level + (node.module or ""), module_name
                                             if path.name == "__init__.py"
                                             else module_name.rpartition(".")[0])
        original = next(a.name for a in node.names if (a.asname or a.name) == name)
        return _data_documented(source, original, value, depth + 1)
    lines = path.read_text(encoding="utf-8").splitlines()
    if node.lineno >= 2 and lines[node.lineno - 2].lstrip().startswith("#:"):
        return True
    following = tree.body.index(node) + 1
    return (following < len(tree.body) and isinstance(tree.body[following], ast.Expr)
            and isinstance(tree.body[following].value, ast.Constant)
            and isinstance(tree.body[following].value.value, str))


def _module_entry_renders(module_name: str, name: str) -> bool:
    """Whether ``::: module_name`` renders ``name`` (statically visible, documented)."""
    _, tree = _source(module_name)
    if name not in _top_level_bindings(tree) or _is_submodule(module_name, name):
        return False
    value = getattr(importlib.import_module(module_name), name)
    if inspect.isfunction(value) or inspect.isclass(value):
        return bool((value.__doc__ or "").strip())
    return _data_documented(module_name, name, value)


def _resolve(path: str) -> object:
    """The object an explicit entry renders, imported at run time."""
    parts = path.split(".")
    for split in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:split]))
        except ImportError:
            continue
        for attr in parts[split:]:
            obj = getattr(obj, attr)
        return obj
    raise ImportError(path)


def _coverage(entries: list[str]) -> tuple[list[str], list[str]]:
    """(public names not rendered, public names rendered twice) for the given entries."""
    explicit = {}
    for path in entries:
        if path not in PUBLIC_MODULES:
            explicit[path] = _resolve(path)
    missing, twice = [], []
    for module_name in PUBLIC_MODULES:
        module = importlib.import_module(module_name)
        for name in module.__all__:
            value = getattr(module, name)
            by_module = module_name in entries and _module_entry_renders(module_name, name)
            by_entry = [p for p, obj in explicit.items()
                        if p.rsplit(".", 1)[-1] == name and obj is value]
            if not by_module and not by_entry:
                missing.append(f"{module_name}.{name}")
            elif by_module + len(by_entry) > 1:
                twice.append(f"{module_name}.{name}")
    return missing, twice


def test_every_public_name_is_rendered_once():
    entries = _entries()
    assert set(PUBLIC_MODULES) <= set(entries), "a public module has no `::: module` entry"
    missing, twice = _coverage(entries)
    assert not missing, ("not rendered by docs/reference.md (add `::: defining.module.name` "
                         f"entries): {missing}")
    assert not twice, f"rendered twice in docs/reference.md (drop the explicit entry): {twice}"


@pytest.mark.parametrize("name", ["contact.solve_bem", "contact.resample", "glstat.GeneralizedLambda",
                                  "glstat.study.rq_for_pressure"])
def test_missing_entry_is_detected(name):
    # the names a module entry cannot render: without their explicit entry the check fails
    entries = [p for p in _entries() if not p.endswith("." + name.rsplit(".", 1)[-1])]
    missing, _ = _coverage(entries)
    assert name in missing


def test_gallery_shows_the_code_of_every_figure():
    spec = importlib.util.spec_from_file_location("gallery_figures", DOCS / "gallery_figures.py")
    gallery_figures = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gallery_figures)
    text = (DOCS / "gallery.md").read_text(encoding="utf-8")
    sections = re.split(r"^## ", text, flags=re.M)
    for script, _args, _pngs in gallery_figures.FIGURES:
        section = next((s for s in sections if f"`{script}`" in s.splitlines()[0]), None)
        assert section is not None, f"docs/gallery.md has no section for {script}"
        figure = section.find("](img/gallery_")
        include = section.find(f'--8<-- "examples/{script}"')
        assert 0 <= figure < include, f"the code of {script} is not included below its figure"
        assert (ROOT / "examples" / script).is_file()


def test_every_example_has_its_gallery_section_and_its_row_on_the_home_page():
    gallery = (DOCS / "gallery.md").read_text(encoding="utf-8")
    home = (DOCS / "index.md").read_text(encoding="utf-8")
    headings = [s.splitlines()[0] for s in re.split(r"^## ", gallery, flags=re.M)[1:]]
    for script in sorted(p.name for p in (ROOT / "examples").glob("*.py")):
        assert any(f"`{script}`" in h for h in headings), f"docs/gallery.md lacks {script}"
        assert f'--8<-- "examples/{script}"' in gallery, f"docs/gallery.md omits the code of {script}"
        assert f"| `{script}` |" in home, f"docs/index.md's table of examples lacks {script}"
