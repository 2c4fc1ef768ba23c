"""Report folders: PNG figures, JSON summary and a self-contained ``index.html``.

A :class:`Report` collects sections (text, tables, figures) while a job runs and writes them at
the end into a folder atomically: ``index.html`` (images embedded as data URIs, readable without
a server), ``summary.json``, each figure as PNG, and any extra files the job attaches (model
files, FMUs).
"""

from __future__ import annotations

import base64
import dataclasses
import html
import json
import math
import os
import shutil
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from vcnc.core.io import atomic_dir
from vcnc.core.jsonsafe import plain

__all__ = ["Report"]


@dataclasses.dataclass
class _Item:
    kind: str  # "heading" | "text" | "table" | "figure" | "file"
    payload: Any


class Report:
    """A report under construction.

    Parameters
    ----------
    title : str
        Title of the page.
    """

    def __init__(self, title: str) -> None:
        self.title = title
        self.items: list[_Item] = []
        self.summary: dict[str, Any] = {}
        self._figures: dict[str, bytes] = {}
        self._files: dict[str, Path | bytes] = {}

    # ----------------------------------------------------------------- building
    def heading(self, text: str) -> None:
        """Start a section."""
        self.items.append(_Item("heading", text))

    def text(self, text: str) -> None:
        """A paragraph (plain text, escaped)."""
        self.items.append(_Item("text", text))

    def table(self, header: Sequence[str], rows: Sequence[Sequence[Any]], *, caption: str = "") -> None:
        """A table; floats are shown with 4 significant digits."""
        self.items.append(_Item("table", (list(header), [list(r) for r in rows], caption)))

    def figure(self, name: str, fig: Any, *, caption: str = "", dpi: int = 110) -> str:
        """Add a matplotlib figure, saved as ``name.png``; the figure is closed. Returns the file name."""
        import io

        import matplotlib.pyplot as plt

        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
        plt.close(fig)
        fname = f"{name}.png"
        self._figures[fname] = buf.getvalue()
        self.items.append(_Item("figure", (fname, caption)))
        return fname

    def attach(self, name: str, source: str | os.PathLike[str] | bytes, *, caption: str = "") -> None:
        """Attach a file (copied into the folder and linked from the page)."""
        self._files[name] = source if isinstance(source, bytes) else Path(source)
        self.items.append(_Item("file", (name, caption)))

    # ------------------------------------------------------------------ output
    def html(self) -> str:
        """The page as one self-contained HTML string."""
        out = [
            "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
            f"<title>{html.escape(self.title)}</title><style>{_CSS}</style></head><body>",
            f"<h1>{html.escape(self.title)}</h1>",
        ]
        for item in self.items:
            if item.kind == "heading":
                out.append(f"<h2>{html.escape(item.payload)}</h2>")
            elif item.kind == "text":
                out.append(f"<p>{html.escape(item.payload)}</p>")
            elif item.kind == "table":
                header, rows, caption = item.payload
                out.append("<table>")
                if caption:
                    out.append(f"<caption>{html.escape(caption)}</caption>")
                out.append("<tr>" + "".join(f"<th>{html.escape(str(h))}</th>" for h in header) + "</tr>")
                for r in rows:
                    out.append("<tr>" + "".join(f"<td>{html.escape(_fmt(v))}</td>" for v in r) + "</tr>")
                out.append("</table>")
            elif item.kind == "figure":
                fname, caption = item.payload
                data = base64.b64encode(self._figures[fname]).decode("ascii")
                out.append(
                    f"<figure><img alt='{html.escape(caption or fname)}' src='data:image/png;base64,{data}'>"
                    f"<figcaption>{html.escape(caption)} <a href='{html.escape(fname)}'>{html.escape(fname)}</a>"
                    "</figcaption></figure>"
                )
            elif item.kind == "file":
                name, caption = item.payload
                out.append(f"<p><a href='{html.escape(name)}'>{html.escape(name)}</a> {html.escape(caption)}</p>")
        out.append("</body></html>")
        return "\n".join(out)

    def write(self, folder: str | os.PathLike[str]) -> Path:
        """Write the folder (atomically: on failure nothing in it changes). Returns its path."""
        folder = Path(folder)
        with atomic_dir(folder) as tmp:
            for fname, data in self._figures.items():
                (tmp / fname).write_bytes(data)
            for name, src in self._files.items():
                if isinstance(src, bytes):
                    (tmp / name).write_bytes(src)
                else:
                    shutil.copyfile(src, tmp / name)
            (tmp / "summary.json").write_text(json.dumps(plain(self.summary), indent=2) + "\n")
            (tmp / "index.html").write_text(self.html())
        return folder


def _fmt(v: Any) -> str:
    if isinstance(v, float):
        if math.isnan(v):
            return "-"
        return f"{v:.4g}"
    return str(v)


_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;max-width:1100px;margin:2em auto;
padding:0 1em;color:#1b1f24;line-height:1.45}
h1{border-bottom:2px solid #2b6cb0;padding-bottom:.3em}h2{margin-top:2em;color:#2b6cb0}
table{border-collapse:collapse;margin:1em 0}th,td{border:1px solid #ccd;padding:.25em .7em;text-align:right}
th{background:#eef3fa}td:first-child,th:first-child{text-align:left}caption{caption-side:top;font-weight:600;
text-align:left;padding:.3em 0}figure{margin:1.5em 0}img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:.9em;color:#555}
"""
