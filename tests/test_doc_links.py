"""Every relative link in the README, the contributor guide and docs/ names a file that exists,
so moving or renaming a page cannot leave a reader at a dead link."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# Inline links and images, `[text](target)` or `![alt](target "title")`, and reference
# definitions, `[label]: target`.
_INLINE = re.compile(r"\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
_REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s|$)", re.MULTILINE)
_FENCE = re.compile(r"^```.*?^```", re.MULTILINE | re.DOTALL)


def _pages() -> list[Path]:
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    contributing = ROOT / "CONTRIBUTING.md"
    return [*pages, contributing] if contributing.exists() else pages


def relative_links(text: str) -> list[str]:
    """Link targets outside code blocks that point into the repository (no scheme, not an
    anchor of the same page), without their anchor."""
    prose = _FENCE.sub("", text)
    targets = [*_INLINE.findall(prose), *_REFERENCE.findall(prose)]
    return [
        target.split("#", 1)[0]
        for target in targets
        if not re.match(r"[A-Za-z][A-Za-z0-9+.-]*:", target) and not target.startswith("#")
    ]


def test_the_link_finder_sees_inline_image_and_reference_links_only() -> None:
    text = (
        'See [a](docs/a.md#part), ![b](images/b.png "B") and [c][c], [web](https://x.org), '
        "[here](#top).\n\n[c]: other/c.md\n\n```\n[in code](missing.md)\n```\n"
    )
    assert sorted(relative_links(text)) == ["docs/a.md", "images/b.png", "other/c.md"]


def test_every_relative_link_points_to_an_existing_file() -> None:
    pages = _pages()
    assert ROOT / "README.md" in pages and len(pages) > 10
    broken = [
        f"{page.relative_to(ROOT)}: {target}"
        for page in pages
        for target in relative_links(page.read_text(encoding="utf-8"))
        if not (page.parent / target).exists()
    ]
    assert broken == [], "broken links (fix the path or the page):\n" + "\n".join(broken)
