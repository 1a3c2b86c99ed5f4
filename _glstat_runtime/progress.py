"""Progress of long loops on standard error: a tqdm bar on a terminal, a few plain lines in a
log (a file, a pipe, CI), where a bar's carriage returns would pile up as one long line."""

from __future__ import annotations

import os
import sys
import time
from typing import Any

__all__ = ["LineProgress", "progress_bar"]


class LineProgress:
    """A progress report in whole lines: ``desc: k of n unit (p %)`` at every ``step`` of the
    total (a tenth by default) and at the end, with the elapsed seconds."""

    def __init__(self, total: int, desc: str, unit: str, initial: int = 0, step: float = 0.1,
                 stream: Any = None) -> None:
        self.total, self.desc, self.unit = int(total), desc, unit
        self.n = int(initial)
        self.step = max(1, round(step * self.total)) if self.total else 1
        self.next = (self.n // self.step + 1) * self.step
        self.stream = sys.stderr if stream is None else stream
        self.start = time.perf_counter()
        self.closed = False

    def _line(self) -> None:
        pct = f" ({100 * self.n / self.total:.0f} %)" if self.total else ""
        print(f"{self.desc}: {self.n} of {self.total} {self.unit}s{pct}, "
              f"{time.perf_counter() - self.start:.0f} s", file=self.stream, flush=True)

    def update(self, n: int = 1) -> None:
        """Count ``n`` more items; write a line when a step is passed."""
        self.n += int(n)
        if self.n >= self.next and self.n < self.total:
            self._line()
            self.next = (self.n // self.step + 1) * self.step

    def close(self) -> None:
        """Write the last line (once)."""
        if not self.closed and self.n > 0:
            self._line()
        self.closed = True


def progress_bar(total: int, desc: str, unit: str, *, enabled: bool = True, initial: int = 0,
                 **tqdm_options: Any) -> Any:
    """A progress report for ``total`` items: a tqdm bar when standard error is a terminal,
    :class:`LineProgress` lines otherwise; a disabled tqdm bar (a no-op) when not ``enabled``
    or when the environment variable ``TQDM_DISABLE`` is set (as by ``glstat -q``)."""
    from tqdm import tqdm

    if not enabled or os.environ.get("TQDM_DISABLE", "").strip().lower() in ("1", "true", "yes"):
        return tqdm(total=total, disable=True)
    stream = sys.stderr
    if not (hasattr(stream, "isatty") and stream.isatty()):
        return LineProgress(total, desc, unit, initial=initial)
    return tqdm(total=total, desc=desc, unit=unit, initial=initial, file=stream, **tqdm_options)
