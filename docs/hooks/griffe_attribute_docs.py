"""Griffe extension for the rendered API reference: docstrings of module-level data.

Griffe reads the docstring of a module attribute only from a string literal after the
assignment. glstat documents some of its data differently, and this extension supplies the
missing docstrings (in the loaded copy only; the sources are not changed):

- ``#:`` comment lines right above an assignment (the Sphinx convention, e.g.
  ``glstat.study.TRUNCATION_TABLE``) become the attribute's docstring;
- an attribute its module exports (listed in ``__all__``) whose value is built at import
  time -- a class made by a factory (``glstat.GeneralizedLambda``) or a scipy distribution
  instance (``glstat.gld_rs``, ``glstat.gld_fkml``) -- gets the docstring of the object the
  module holds when imported.

Configured in mkdocs.yml under the python handler's ``extensions``, before the extension
that turns roles into links, so that roles in these docstrings become links too.
"""

from __future__ import annotations

import importlib
import inspect
import re
from typing import Any

import griffe

#: A line holding only a placeholder of scipy's docstring templates (``%(before_notes)s``).
PLACEHOLDER = re.compile(r"^[ \t]*%\(\w+\)s[ \t]*\n", re.M)


def _comment_docstring(attr: griffe.Attribute) -> str | None:
    """The ``#:`` comment block right above the attribute's first line, if any."""
    module = attr.module
    if attr.lineno is None or module.filepath is None or isinstance(module.filepath, list):
        return None
    lines = module.lines
    block: list[str] = []
    i = attr.lineno - 2  # the line above, 0-based
    while i >= 0 and lines[i].lstrip().startswith("#:"):
        block.insert(0, lines[i].lstrip()[2:].removeprefix(" "))
        i -= 1
    return "\n".join(block) if block else None


def _runtime_docstring(attr: griffe.Attribute) -> str | None:
    """The docstring of the exported object the imported module holds, for a class or an
    instance that carries its own docstring (not the generic one of its type)."""
    module = attr.module
    if attr.name not in (module.exports or ()):
        return None
    try:
        value = getattr(importlib.import_module(module.path), attr.name)
    except Exception:
        return None
    if inspect.isclass(value):
        doc = value.__doc__
    elif "__doc__" in getattr(value, "__dict__", {}):
        # an object documented on its own, such as a scipy distribution: scipy fills the
        # docstring written in its class with generic text (its methods, an example that
        # imports the object from scipy.stats); the project's own text is the class's, less
        # the template's placeholders
        doc = type(value).__doc__
        if isinstance(doc, str):
            doc = PLACEHOLDER.sub("", doc)
    else:
        doc = None
    return inspect.cleandoc(doc) if isinstance(doc, str) and doc.strip() else None


class AttributeDocstrings(griffe.Extension):
    """Give module attributes documented by ``#:`` comments or at import time their docstring."""

    def on_package(self, *, pkg: griffe.Module, loader: griffe.GriffeLoader, **kwargs: Any) -> None:
        for obj in _objects(pkg):
            if not obj.is_module:
                continue
            for member in obj.members.values():
                if member.is_alias or not isinstance(member, griffe.Attribute) or member.docstring:
                    continue
                options = dict(loader.docstring_options)
                text = _comment_docstring(member)
                if text is None:
                    text = _runtime_docstring(member)
                    # griffe sees an attribute, not the class or callable behind it, so it
                    # cannot check the documented parameters against a signature
                    options.update(warn_unknown_params=False, warn_missing_types=False)
                if text:
                    member.docstring = griffe.Docstring(text, parent=member,
                                                        parser=loader.docstring_parser,
                                                        parser_options=options)


def _objects(obj: griffe.Object):
    yield obj
    for member in obj.members.values():
        if not member.is_alias and isinstance(member, griffe.Object):
            yield from _objects(member)
