"""The ``glstat`` console script: answers ``--version`` from the package metadata, and hands
every other command to :func:`glstat.cli.main` (which parses the options before NumPy, SciPy
and the kernels load, so ``--help`` and option errors answer at once)."""

from __future__ import annotations

import sys


def _version() -> str:
    """The installed version, from the package metadata; from ``glstat/_version.py`` in a
    source tree that is not installed."""
    import importlib.metadata as md

    try:
        return md.version("glstat")
    except md.PackageNotFoundError:
        import importlib.util
        from pathlib import Path

        path = Path(__file__).resolve().parent / "glstat" / "_version.py"
        spec = importlib.util.spec_from_file_location("_glstat_version", path)
        if spec is None or spec.loader is None:
            return "unknown"
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return str(module.__version__)


def main(argv: list[str] | None = None) -> int:
    """Run the ``glstat`` command line."""
    args = list(sys.argv[1:] if argv is None else argv)
    if args[:1] in (["-V"], ["--version"]):
        print(f"glstat {_version()}")
        return 0
    try:  # Ctrl-C while the command starts ends quietly
        from glstat.cli.commands import main as glstat_main
    except KeyboardInterrupt:
        print("glstat: interrupted while starting; nothing was run", file=sys.stderr)
        return 130
    return glstat_main(args)


if __name__ == "__main__":
    sys.exit(main())
