"""Old module paths that keep working for one release: each is a stand-in module that imports
the module's new home on first use and says where it went (:class:`DeprecationWarning`).

The stand-ins are placed in :data:`sys.modules` when the package is imported, so ``import
glstat.damage`` and ``from glstat.damage import damage_probability`` find them without a
search of the file system, and nothing is imported until a name is used.
"""

from __future__ import annotations

import importlib
import sys
import types
import warnings
from typing import Any

__all__ = ["MovedModule", "register"]


class MovedModule(types.ModuleType):
    """A module that moved: its names come from ``new`` on first use, with a warning."""

    def __init__(self, old: str, new: str) -> None:
        super().__init__(old, f"Moved to {new}.")
        self.__dict__["_moved_to"] = new

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        new = self.__dict__["_moved_to"]
        warnings.warn(f"{self.__name__} moved to {new}; import {name} from there (or from the "
                      f"package's top level) — the old path will be removed in the next release",
                      DeprecationWarning, stacklevel=2)
        return getattr(importlib.import_module(new), name)

    def __dir__(self) -> list[str]:
        return sorted(set(dir(importlib.import_module(self.__dict__["_moved_to"]))))


def register(moves: dict[str, str]) -> dict[str, types.ModuleType]:
    """Place a stand-in in :data:`sys.modules` for each ``old: new`` module path not imported yet.

    Returns
    -------
    dict
        The stand-ins by their last name (what the parent package's ``__getattr__`` returns).
    """
    out: dict[str, types.ModuleType] = {}
    for old, new in moves.items():
        module = sys.modules.get(old)
        if module is None:
            module = sys.modules[old] = MovedModule(old, new)
        out[old.rsplit(".", 1)[-1]] = module
    return out
