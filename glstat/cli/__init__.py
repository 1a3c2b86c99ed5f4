"""The ``glstat`` command: ``glstat study``, ``glstat fit FILE`` and ``glstat demo``."""

from .commands import main

__all__ = ["main"]
