"""Griffe extension for the rendered API reference: Sphinx roles in docstrings become links.

The docstrings of glstat and contact use Sphinx/numpydoc roles (``:func:`glstat.fit```,
``:class:`~contact.Surface```, ``:mod:`glstat.extremes```, ``:data:`TABLE1```, ...), which
Markdown would show as the role markup followed by code. When mkdocstrings loads a package,
this extension rewrites each role, in the loaded copy of the docstring only, into a
cross-reference that mkdocs-autorefs turns into a link to the object's entry:

- a relative name is looked up the way Python would from the documented object (its class,
  its module, the enclosing packages), then as an absolute path;
- a name that a package imports on first use (a module ``__getattr__``) is found by importing
  the package and is linked to the object's defining module;
- a target with no entry on the site (a private helper, a module that is not rendered, an
  object of numpy or scipy) stays as code, with the full name as tooltip, and does not make
  the strict build fail.

``~a.b.c`` shows ``c``; ``title <a.b.c>`` shows ``title``. ``:math:`...``` and the formula of a
``.. math::`` directive are shown as code.
Configured in mkdocs.yml under
the python handler's ``extensions``.
"""

from __future__ import annotations

import html
import importlib
import logging
import re
from typing import Any

import griffe

_log = logging.getLogger("mkdocs.plugins.griffe_roles")

#: ``:role:`target``` with an optional domain (``:py:func:``); the target has no backquote.
ROLE = re.compile(r":(?:py:)?(?P<role>func|meth|class|mod|data|attr|obj|exc|const|attribute)"
                  r":`(?P<target>[^`]+)`")
#: ``:math:`tex``` (shown as code: the site loads no script, so no math rendering).
MATH = re.compile(r":math:`(?P<tex>[^`]+)`")
#: The line of a ``.. math::`` directive: its indented formula then shows as a code block.
MATH_DIRECTIVE = re.compile(r"^[ \t]*\.\. math::[ \t]*\n", re.M)
#: ``title <target>`` inside a role.
EXPLICIT_TITLE = re.compile(r"^(?P<title>.+?)\s*<(?P<target>[^<>]+)>$")


def _exists(collection: griffe.ModulesCollection, path: str) -> bool:
    try:
        collection[path]
    except Exception:  # a missing member, an alias into a package that is not loaded
        return False
    return True


def _runtime_path(path: str) -> str | None:
    """Defining path of the object importable as ``path``, for names imported on first use."""
    parts = path.split(".")
    for split in range(len(parts) - 1, 0, -1):
        try:
            obj: Any = importlib.import_module(".".join(parts[:split]))
        except Exception:
            continue
        try:
            for name in parts[split:]:
                obj = getattr(obj, name)
        except AttributeError:
            return None
        module, qualname = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
        if module and qualname and "<" not in qualname:
            return f"{module}.{qualname}"
        return None
    return None


def _scopes(obj: griffe.Object) -> list[str]:
    """Paths searched for a relative name, innermost first."""
    scope: griffe.Object | None = obj if obj.is_module or obj.is_class else obj.parent
    out = []
    while scope is not None:
        out.append(scope.path)
        scope = scope.parent
    return out


class RolesToCrossrefs(griffe.Extension):
    """Rewrite Sphinx roles in the docstrings of a loaded package into autorefs cross-references."""

    def on_package(self, *, pkg: griffe.Module, loader: griffe.GriffeLoader, **kwargs: Any) -> None:
        collection = loader.modules_collection
        root = pkg.path
        count = 0
        for obj in self._objects(pkg):
            docstring = obj.docstring
            if docstring is None or (":`" not in docstring.value and ".. math::" not in docstring.value):
                continue
            docstring.value, n = ROLE.subn(lambda m, o=obj: self._crossref(m, o, collection, root),
                                           docstring.value)
            docstring.value = MATH_DIRECTIVE.sub("", docstring.value)
            docstring.value = MATH.sub(lambda m: f"<code>{html.escape(m['tex'])}</code>", docstring.value)
            count += n
            docstring.__dict__.pop("parsed", None)  # parsed again from the new text
        _log.info("griffe_roles: %d roles in the docstrings of %s made cross-references", count, root)

    def _objects(self, obj: griffe.Object):
        yield obj
        for member in obj.members.values():
            if not member.is_alias and isinstance(member, griffe.Object):
                yield from self._objects(member)

    def _crossref(self, match: re.Match[str], obj: griffe.Object,
                  collection: griffe.ModulesCollection, root: str) -> str:
        target = match["target"].strip()
        explicit = EXPLICIT_TITLE.match(target)
        if explicit:
            title, target = explicit["title"], explicit["target"].strip()
        else:
            title = None
        short = target.startswith("~")
        target = target.lstrip("~").lstrip(".")
        if title is None:
            title = target.rsplit(".", 1)[-1] if short else target
        candidates = [f"{scope}.{target}" for scope in _scopes(obj)] + [target]
        identifier = next((c for c in candidates if _exists(collection, c)), None)
        if identifier is None:  # imported on first use, or in another package
            identifier = next((p for c in candidates if c.split(".")[0] == root
                               and (p := _runtime_path(c)) is not None), target)
        return (f'<autoref identifier="{html.escape(identifier)}" optional>'
                f"<code>{html.escape(title)}</code></autoref>")
