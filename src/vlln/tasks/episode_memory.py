"""The memory that reading an episode file may take, refused before it is taken.

Parsed, JSON takes up to 24 times its bytes (``[{},{},...]``: a 64-byte dict for 3 bytes of
text), so a cap on bytes alone lets a hostile file under it take gigabytes. A
:class:`MemoryBudget` charges what parsing allocates, each item at the most it can take: before
parsing, from counts of the tokens of the text (objects, keys, strings, lists, list items,
values). Real files are mostly view points, which the object hook turns into small
:class:`~vlln.tasks.episode.ViewPoint` objects at once: a view point's text is charged as the
view point, and the hook charges the objects of one it does not make, and gives back those of a
repeated goal. A file that would pass the budget is refused as soon as that is known, before
the memory is taken, so the memory held stays within the budget, plus the interpreter's own
and some allocator slack.

The sizes are CPython 3.11's on 64-bit machines, as allocated (in blocks of 8 bytes).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path
from typing import Any

from vlln.errors import DataFormatError
from vlln.files import ReadCap

# A string's object: 49 to 76 bytes and its characters (these are charged as a copy of the text).
STRING = 88
# Each value, as if a number: an int (28 bytes) or a float (24), the digits of a longer int
# counting as a copy of the text too; strings, lists and objects are also charged as such.
VALUE = 32
FLOAT = 24
# A list takes 56 bytes and 8 a slot, with room for an eighth more items and 6 spare: a list
# of n items takes at most 104 + 9n bytes, charged as one list and one slot a comma.
LIST = 120
SLOT = 9
# An empty object; a key's share of a larger one takes at most 120 bytes, charged as its
# string and its entry.
DICT = 64
# A key's slot in its object and in the parser's memo of keys, each table growing to 3 times
# its keys: up to 88 bytes (100,000 distinct keys in one object: 144 bytes a key, 56 its string).
ENTRY = 96
# A view point and the tuple of its position (40 + 64 bytes), its floats apart.
VIEW_POINT = 104

# How write_episodes begins a view point (json.dumps's separators, and the same without
# spaces). Its tokens are not charged as text: its two keys are the same two strings in every
# view point (the parser shares keys), and its two objects and list go when the hook makes it a
# view point; the hook charges them (and the list's first item) when it does not.
VIEW_POINT_STARTS = (b'{"agent_state": {"position": [', b'{"agent_state":{"position":[')
# A start is charged instead as the view point made of it: its object and tuple and its three
# floats, less the charges of two of them and of the view point itself as values after commas.
VIEW_POINT_MADE = VIEW_POINT + 3 * FLOAT - 2 * (VALUE + SLOT) - VALUE

# UTF-8 characters past U+FFFF and past U+00FF, whose strings take 4 or 2 bytes a character,
# and \u escapes of the same (searched apart: one pattern for both searches 20 times slower).
_FOUR_BYTE_LEADS = re.compile(rb"[\xf0-\xff]")
_TWO_BYTE_LEADS = re.compile(rb"[\xc4-\xef]")
_FOUR_BYTE_ESCAPES = re.compile(rb"\\u[dD][89abAB]")
_TWO_BYTE_ESCAPES = re.compile(rb"\\u(?!00)")


class OverBudget(DataFormatError):
    """A file that would take more memory to read than its budget."""


class MemoryBudget:
    """The bytes that reading ``path`` may take: ``per_byte`` a byte of ``cap``."""

    def __init__(self, path: Path, cap: ReadCap, per_byte: int) -> None:
        self.path, self.cap, self.per_byte = path, cap, per_byte
        self.limit = per_byte * cap.limit()
        self.used = 0

    def charge(self, size: int) -> None:
        """Add ``size`` bytes; over the budget is an :class:`OverBudget` error."""
        self.used += size
        if self.used > self.limit:
            raise self._refusal()

    def charge_text(self, raw: bytes) -> None:
        """Charge the JSON text ``raw`` before it is parsed: the decoded text; its strings'
        characters, as a copy of the text at its widest; each object, key, string, list, list
        item and value (every value but the whole follows one of ``,[:``) at its largest; and
        each view point start as a view point. Counts are upper bounds: a bracket in a string
        counts too."""
        text_width, string_width = _character_widths(raw)
        self.charge((text_width + string_width) * len(raw))
        starts = sum(raw.count(start) for start in VIEW_POINT_STARTS)
        commas, colons, lists = raw.count(b","), raw.count(b":") - 2 * starts, raw.count(b"[")
        self.charge(
            DICT * (raw.count(b"{") - 2 * starts)
            + ENTRY * colons
            + STRING * (raw.count(b'"') // 2 - 2 * starts)
            + LIST * (lists - starts)
            + SLOT * commas
            + VALUE * (commas + colons + lists - starts + 1)
            + VIEW_POINT_MADE * starts
        )

    def charge_start(self, obj: dict[str, Any]) -> None:
        """Charge an object with an ``agent_state`` that was not made a view point: it may have
        been a view point start, whose two objects, list and first item were not charged as
        text."""
        size = sys.getsizeof(obj) + VALUE
        state = obj["agent_state"]
        if type(state) is dict:
            size += sys.getsizeof(state) + sys.getsizeof(state.get("position"))
        self.charge(size)

    def refund_view_points(self, count: int) -> None:
        """Give back ``count`` view points made and let go (a repeated goal's)."""
        self.used -= count * (VIEW_POINT + 3 * FLOAT + SLOT)

    def _refusal(self) -> OverBudget:
        return OverBudget(
            f"{self.path} would take more than {self.limit >> 20} MiB of memory to read, the "
            f"limit for {self.cap.what} ({self.per_byte} bytes a byte of its "
            f"{self.cap.limit() >> 20} MiB cap); set {self.cap.variable} to more MiB if the "
            "file is right"
        )


def _character_widths(raw: bytes) -> tuple[int, int]:
    """The bytes a character takes in the text of ``raw`` once decoded, and the most it may
    take in a string of the text (escapes included): 1, 2 or 4 each."""
    text = escaped = 1
    if not raw.isascii():
        text = 4 if _FOUR_BYTE_LEADS.search(raw) else 2 if _TWO_BYTE_LEADS.search(raw) else 1
    if b"\\" in raw:  # a quick test (memchr): most files hold no escape
        escaped = 4 if _FOUR_BYTE_ESCAPES.search(raw) else 2 if _TWO_BYTE_ESCAPES.search(raw) else 1
    return text, max(text, escaped)
