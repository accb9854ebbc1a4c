"""A small, safe Markdown subset rendered to HTML (for ``docs/errata.md`` inside the report).

Handles paragraphs, ``-``/``*``/``1.`` lists, fenced code blocks, headings, and inline code,
bold, italics and links. Everything else is shown as text: the input is escaped first, so no
markup in the documents can inject HTML into the report.
"""

from __future__ import annotations

import html
import re

__all__ = ["markdown_to_html"]

_LIST_ITEM = re.compile(r"^\s*(?:[-*]|\d+\.)\s+")
_INLINE = (
    (re.compile(r"\*\*(.+?)\*\*"), r"<strong>\1</strong>"),
    (re.compile(r"(?<![\w*])\*(?!\s)(.+?)(?<!\s)\*(?![\w*])"), r"<em>\1</em>"),
    (re.compile(r"\[([^\]]+)\]\(((?:https?://|#|\.{0,2}/)?[^)\s]*)\)"), r'<a href="\2">\1</a>'),
)


def markdown_to_html(text: str) -> str:
    """HTML for the Markdown subset described in the module docstring.

    Parameters
    ----------
    text : str
        Markdown.

    Returns
    -------
    str
        HTML in which every character of ``text`` outside the recognised markup is escaped.
    """
    out: list[str] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("```"):
            end = next((j for j in range(i + 1, len(lines)) if lines[j].startswith("```")), None)
            end = len(lines) if end is None else end
            out.append(f"<pre>{html.escape(chr(10).join(lines[i + 1 : end]))}</pre>")
            i = end + 1
        elif heading := re.match(r"^(#{1,6})\s+(.*)", line):
            level = min(len(heading.group(1)) + 2, 6)
            out.append(f"<h{level}>{_inline(heading.group(2))}</h{level}>")
            i += 1
        elif _LIST_ITEM.match(line):
            items, i = _block(lines, i, lambda s: bool(_LIST_ITEM.match(s)))
            out.append("<ul>" + "".join(f"<li>{_inline(item)}</li>" for item in items) + "</ul>")
        elif line.strip():
            paragraph, i = _block(lines, i, lambda s: False)
            out.append(f"<p>{_inline(' '.join(paragraph))}</p>")
        else:
            i += 1
    return "\n".join(out)


def _block(lines: list[str], start: int, starts_item) -> tuple[list[str], int]:
    """Items (or one paragraph) from ``start`` until a blank line, heading or fence."""
    items: list[str] = []
    i = start
    while i < len(lines) and lines[i].strip() and not re.match(r"^(#{1,6}\s|```)", lines[i]):
        line = lines[i]
        if starts_item(line) or not items:
            items.append(_LIST_ITEM.sub("", line, count=1).strip())
        else:
            items[-1] += " " + line.strip()
        i += 1
    return items, i


def _inline(text: str) -> str:
    parts = re.split(r"(`[^`]+`)", text)
    rendered = []
    for part in parts:
        if part.startswith("`") and part.endswith("`") and len(part) > 1:
            rendered.append(f"<code>{html.escape(part[1:-1])}</code>")
            continue
        escaped = html.escape(part, quote=False)
        for pattern, replacement in _INLINE:
            escaped = pattern.sub(replacement, escaped)
        rendered.append(escaped)
    return "".join(rendered)
