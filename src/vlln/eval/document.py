"""A tiny document model so one report renders to both Markdown and self-contained HTML.

Blocks are headings, paragraphs, pipe tables and images (PNG files next to the document,
referenced by relative path), which is all a benchmark report needs; writing them once and
rendering twice keeps report.md and report.html from drifting apart.
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from dataclasses import dataclass

from vlln.errors import ConfigError


@dataclass(frozen=True)
class Heading:
    level: int  # 1..3
    text: str


@dataclass(frozen=True)
class Paragraph:
    text: str


@dataclass(frozen=True)
class Table:
    """A table as header cells and rows of cells (strings, already formatted)."""

    header: list[str]
    rows: list[list[str]]

    @staticmethod
    def from_markdown(text: str) -> tuple[Table, list[str]]:
        """Split Markdown (a pipe table plus trailing text lines) into the table and the
        non-empty lines after it, e.g. the radii footnote of ``format_table``."""
        lines = text.splitlines()
        table_lines = [line for line in lines if line.startswith("|")]
        rest = [line for line in lines if line.strip() and not line.startswith("|")]
        if len(table_lines) < 2:
            raise ConfigError("expected a Markdown pipe table with a header and a rule line")
        cells = [_cells(line) for line in table_lines]
        return Table(cells[0], cells[2:]), rest


@dataclass(frozen=True)
class Image:
    file: str  # relative to the document
    alt: str


@dataclass(frozen=True)
class Video:
    file: str  # relative to the document
    caption: str


Block = Heading | Paragraph | Table | Image | Video


def _cells(line: str) -> list[str]:
    return [cell.strip() for cell in line.strip().strip("|").split("|")]


def to_markdown(blocks: Sequence[Block]) -> str:
    parts: list[str] = []
    for block in blocks:
        if isinstance(block, Heading):
            parts.append("#" * block.level + " " + block.text)
        elif isinstance(block, Paragraph):
            parts.append(block.text)
        elif isinstance(block, Table):
            rows = [block.header, ["---"] * len(block.header), *block.rows]
            parts.append("\n".join("| " + " | ".join(row) + " |" for row in rows))
        elif isinstance(block, Video):
            parts.append(f"[video: {block.caption}]({block.file})")
        else:
            parts.append(f"![{block.alt}]({block.file})")
    return "\n\n".join(parts) + "\n"


_STYLE = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 72em; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: right; }
th:first-child, td:first-child { text-align: left; }
th { background: #f0f0f0; }
img, video { max-width: 100%; border: 1px solid #ddd; }
figure { margin: 1em 0; }
"""


def to_html(blocks: Sequence[Block], title: str) -> str:
    """A standalone HTML page; images are referenced relatively, like the Markdown."""
    body: list[str] = []
    for block in blocks:
        if isinstance(block, Heading):
            level = min(max(block.level, 1), 6)
            body.append(f"<h{level}>{html.escape(block.text)}</h{level}>")
        elif isinstance(block, Paragraph):
            body.append(f"<p>{html.escape(block.text)}</p>")
        elif isinstance(block, Table):
            head = "".join(f"<th>{html.escape(cell)}</th>" for cell in block.header)
            rows = "".join(
                "<tr>" + "".join(f"<td>{html.escape(cell)}</td>" for cell in row) + "</tr>"
                for row in block.rows
            )
            body.append(f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>")
        elif isinstance(block, Video):
            caption = html.escape(block.caption)
            body.append(
                f'<figure><video controls preload="metadata" src="{html.escape(block.file)}">'
                f"</video><figcaption>{caption}</figcaption></figure>"
            )
        else:
            alt = html.escape(block.alt)
            body.append(
                f'<figure><img src="{html.escape(block.file)}" alt="{alt}">'
                f"<figcaption>{alt}</figcaption></figure>"
            )
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{html.escape(title)}</title>\n<style>{_STYLE}</style>\n</head>\n<body>\n"
        + "\n".join(body)
        + "\n</body>\n</html>\n"
    )
