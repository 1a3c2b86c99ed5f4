"""The version of glstat (the one source of it: pyproject.toml reads it)."""

__version__ = "0.1.0"
