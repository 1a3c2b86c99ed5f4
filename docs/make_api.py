"""Write docs/api.md, the API reference, from the public objects' docstrings.

Run: ``python docs/make_api.py`` (the test suite checks that docs/api.md is up to date).
"""

from __future__ import annotations

import importlib
import inspect
import sys
from pathlib import Path

MODULES = [
    ("glstat", "The statistics: GLD distributions, fitting, bootstrap, maxima, damage, goodness of fit"),
    ("glstat.plot", "Figures (matplotlib imported when a figure is drawn)"),
    ("glstat.regions", "Validity regions of the RS parameterisation"),
    ("glstat.study", "The study end to end: campaigns, analysis, report"),
    ("contact", "Rough surfaces and contact models"),
]


def _public_names(module) -> list[str]:
    names = getattr(module, "__all__", None)
    if names is None:
        names = [n for n, v in vars(module).items()
                 if not n.startswith("_") and getattr(v, "__module__", "").startswith(module.__name__)
                 and (inspect.isfunction(v) or inspect.isclass(v))]
    return sorted(names, key=str.lower)


def _signature(obj) -> str:
    try:
        return str(inspect.signature(obj))
    except (TypeError, ValueError):
        return ""


def _doc(obj) -> str:
    doc = inspect.getdoc(obj) or "(no docstring)"
    return doc.strip()


def _section(name: str, obj) -> list[str]:
    lines = [f"### `{name}`", ""]
    if inspect.isclass(obj) or inspect.isfunction(obj):
        lines += ["```python", f"{name}{_signature(obj)}", "```", ""]
    else:
        lines += [f"*instance of `{type(obj).__name__}`*", ""]
    lines += ["```text", _doc(obj), "```", ""]
    if inspect.isclass(obj):
        for attr, member in sorted(vars(obj).items()):
            if attr.startswith("_"):
                continue
            target = member.fget if isinstance(member, property) else member
            if isinstance(member, (staticmethod, classmethod)):
                target = member.__func__
            if not (inspect.isfunction(target) or isinstance(member, property)):
                continue
            sig = "" if isinstance(member, property) else _signature(target)
            first = (inspect.getdoc(target) or "").split("\n\n")[0].replace("\n", " ")
            if not first:  # e.g. parameter properties scipy adds to a class when it is first used
                continue
            lines.append(f"- `{attr}{sig}`{' (property)' if isinstance(member, property) else ''}: {first}")
        lines.append("")
    return lines


def render() -> str:
    out = ["# API reference", "",
           "Generated from the docstrings by `python docs/make_api.py`; do not edit by hand.", ""]
    for modname, title in MODULES:
        module = importlib.import_module(modname)
        out += [f"## `{modname}` — {title}", ""]
        for name in _public_names(module):
            out += _section(f"{modname}.{name}", getattr(module, name))
    return "\n".join(out).rstrip() + "\n"


def main() -> int:
    path = Path(__file__).with_name("api.md")
    path.write_text(render(), encoding="utf-8")
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
