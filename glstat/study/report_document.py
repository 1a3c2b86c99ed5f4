"""The study report as a document: sections of headings, paragraphs, tables and figures,
rendered to one self-contained HTML page (figures embedded) and to Markdown with PNG files."""

from __future__ import annotations

import base64
import errno
import html
import io
import math
import os
import re
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["Blocks", "Report", "fmt_cell"]


def fmt_cell(v: Any) -> str:
    """A table cell as text.

    Parameters
    ----------
    v : object
        Booleans become "yes"/"no", integers their digits, floats 4 significant digits
        (scientific notation from 1e5 and below 1e-3, "—" for NaN); anything else ``str(v)``.

    Returns
    -------
    str
    """
    if isinstance(v, bool | np.bool_):
        return "yes" if v else "no"
    if isinstance(v, int | np.integer):
        return str(int(v))
    if isinstance(v, float | np.floating):
        v = float(v)
        if math.isnan(v):
            return "—"
        if v == 0:
            return "0"
        if abs(v) >= 1e5 or abs(v) < 1e-3:
            return f"{v:.3e}"
        return f"{v:.4g}"
    return str(v)


class Blocks:
    """An ordered list of headings, paragraphs, tables and figures: one part of the report."""

    def __init__(self) -> None:
        self.blocks: list[tuple] = []

    def heading(self, text: str, level: int = 2) -> None:
        """Add a section heading."""
        self.blocks.append(("h", level, text))

    def paragraph(self, text: str) -> None:
        """Add a paragraph (Markdown inline syntax: ``code``, **bold**)."""
        self.blocks.append(("p", text))

    def table(self, columns: list[str], rows: list[list[Any]], caption: str = "") -> None:
        """Add a table; cells are formatted with 4 significant digits (:func:`fmt_cell`)."""
        self.blocks.append(("t", columns, [[fmt_cell(c) for c in r] for r in rows], caption))

    def figure(self, name: str, fig: Any, caption: str) -> None:
        """Add a matplotlib figure (rendered to PNG now and closed)."""
        import matplotlib.pyplot as plt

        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=90, bbox_inches="tight")
        plt.close(fig)
        self.blocks.append(("f", name, buf.getvalue(), caption))

    def extend(self, *parts: Blocks) -> None:
        """Append the blocks of other parts, in order."""
        for part in parts:
            self.blocks += part.blocks

    def state_in_captions(self, text: str, marker: str) -> None:
        """Append `` (text)`` to every table and figure caption that does not already hold
        ``marker`` (e.g. the length scale every number holds at)."""
        out = []
        for b in self.blocks:
            if b[0] in ("t", "f") and b[3] and marker not in b[3]:
                caption = b[3].rstrip()
                end = "." if caption.endswith(".") else ""
                b = (*b[:3], f"{caption[:len(caption) - len(end)]} ({text}){end}")
            out.append(b)
        self.blocks = out


class Report(Blocks):
    """The whole report: a title and its blocks, rendered to HTML and Markdown."""

    def __init__(self, title: str) -> None:
        super().__init__()
        self.title = title

    @staticmethod
    def _inline_html(text: str) -> str:
        t = html.escape(text)
        t = re.sub(r"`([^`]+)`", r"<code>\1</code>", t)
        t = re.sub(r"\*\*([^*]+)\*\*", r"<b>\1</b>", t)
        return t

    @staticmethod
    def _inline_markdown(text: str) -> str:
        """``text`` on one line, with HTML markup shown as text and link syntax broken: what the
        report quotes from the user's files (names, columns) can neither start a block, inject
        HTML, nor become a live link or image (``[x](url)``, ``![t](url)``)."""
        return html.escape(re.sub(r"[\r\n]+", " ", text), quote=False).replace("](", "]\\(")

    @classmethod
    def _cell_markdown(cls, text: str) -> str:
        return cls._inline_markdown(text).replace("|", "\\|")

    def to_markdown(self, figdir: str) -> tuple[str, dict[str, bytes]]:
        """Markdown text and the PNG files it references (``figdir/<name>.png``)."""
        md, cell = self._inline_markdown, self._cell_markdown
        lines = [f"# {md(self.title)}", ""]
        files = {}
        for b in self.blocks:
            if b[0] == "h":
                lines += ["#" * b[1] + " " + md(b[2]), ""]
            elif b[0] == "p":
                lines += [md(b[1]), ""]
            elif b[0] == "t":
                _, cols, rows, cap = b
                if cap:
                    lines += [f"*{md(cap)}*", ""]
                lines.append("| " + " | ".join(map(cell, cols)) + " |")
                lines.append("|" + "---|" * len(cols))
                lines += ["| " + " | ".join(map(cell, r)) + " |" for r in rows]
                lines.append("")
            else:
                _, name, png, cap = b
                files[f"{name}.png"] = png
                lines += [f"![{md(cap)}]({figdir}/{name}.png)", "", f"*{md(cap)}*", ""]
        return "\n".join(lines), files

    def to_html(self) -> str:
        """One self-contained HTML page (PNG figures embedded as base64)."""
        out = ["<!DOCTYPE html>", "<html><head><meta charset='utf-8'>",
               f"<title>{html.escape(self.title)}</title>",
               "<style>body{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em;"
               "line-height:1.45}table{border-collapse:collapse;margin:0.5em 0 1.2em}"
               "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}"
               "th{background:#eee}img{max-width:100%}figcaption{font-style:italic;color:#444}"
               "code{background:#f4f4f4}</style></head><body>",
               f"<h1>{html.escape(self.title)}</h1>"]
        for b in self.blocks:
            if b[0] == "h":
                out.append(f"<h{b[1]}>{html.escape(b[2])}</h{b[1]}>")
            elif b[0] == "p":
                out.append(f"<p>{self._inline_html(b[1])}</p>")
            elif b[0] == "t":
                _, cols, rows, cap = b
                out.append("<table>")
                if cap:
                    out.append(f"<caption>{self._inline_html(cap)}</caption>")
                out.append("<tr>" + "".join(f"<th>{html.escape(c)}</th>" for c in cols) + "</tr>")
                for r in rows:
                    out.append("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in r) + "</tr>")
                out.append("</table>")
            else:
                _, name, png, cap = b
                data = base64.b64encode(png).decode("ascii")
                out.append(f"<figure id='{name}'><img alt='{html.escape(cap)}' "
                           f"src='data:image/png;base64,{data}'><figcaption>{self._inline_html(cap)}"
                           f"</figcaption></figure>")
        out.append("</body></html>")
        return "\n".join(out)

    def write(self, out: str | os.PathLike) -> tuple[Path, Path]:
        """Write ``report.html`` and ``report.md`` + ``report_files/*.png`` into ``out`` (atomically)."""
        from .campaign import atomic_write

        out = Path(out)
        folder = out / "report_files"
        if folder.is_symlink():  # never write the figures through a link out of ``out``
            raise OSError(errno.ELOOP, "a symbolic link", str(folder))
        if folder.is_dir():  # figures half-written by a run killed while it wrote them
            from .files import remove_temporaries

            remove_temporaries((folder,))
        md, files = self.to_markdown("report_files")
        for name, png in files.items():
            atomic_write(out / "report_files" / name, png)
        atomic_write(out / "report.md", md.encode())
        atomic_write(out / "report.html", self.to_html().encode())
        return out / "report.html", out / "report.md"
