"""Checks of a scan's annotation files before they are parsed, so that a binary, empty or cut
file is one line naming the file and what is wrong, never a traceback or a scene without rooms.

The ``.house`` rules are Matterport3D's own (niessner/Matterport ``data_organization.md``,
section house_segmentations): the first line is ``ASCII 1.1`` (habitat-sim's
``Mp3dSemanticScene.cpp`` refuses any other), the ``H`` record counts the regions, surfaces,
vertices, categories and objects that follow, and every record has a fixed number of fields
(those of real houses, which google-research/valan's ``r2r/house_parser.py`` asserts).
A file cut by a failed copy has fewer records than its ``H`` line counts, or a short last
record; both are refused. HM3D's ``semantic.txt`` has no counts: it must be UTF-8 text
without NUL bytes and list at least one object.
"""

from __future__ import annotations

from pathlib import Path

from vlln.errors import DataFormatError
from vlln.files import ReadCap

HOUSE_HEADER = "ASCII 1.1"
# Fields per record, the record letter included, as real files have them (module doc).
HOUSE_FIELDS = {"H": 29, "L": 18, "R": 20, "S": 22, "V": 13, "C": 11, "O": 24}
# Counts of the H record (its field index) that the records after it must reach.
HOUSE_COUNTS = {"V": 5, "S": 6, "O": 8, "C": 9, "R": 10}
_NAMES = {"R": "regions", "S": "surfaces", "V": "vertices", "C": "categories", "O": "objects"}
# Real .house files and semantic.txt are a few MB; a bigger scan may raise the cap.
ANNOTATION_CAP = ReadCap("a scan's annotation file", 64, "VLLN_MAX_SCAN_ANNOTATION_MB")


def annotation_text(path: Path, what: str) -> str:
    """The text of an annotation file; a binary or non-UTF-8 file is refused, naming ``what``
    the file should be; at most :data:`ANNOTATION_CAP` is read."""
    data = ANNOTATION_CAP.read(path)
    if b"\0" in data:
        raise DataFormatError(f"{path} is a binary file, not {what}; give the scan's own file")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise DataFormatError(
            f"{path} is not UTF-8 text (byte {error.start}), so not {what}; "
            "give the scan's own file"
        ) from None


def house_text(path: Path) -> str:
    """The text of a Matterport3D ``.house`` file, checked as the module doc says."""
    text = annotation_text(path, "a Matterport3D .house file")
    fix = "copy the scan's .house file again"
    lines = text.splitlines()
    if not text.strip():
        raise DataFormatError(f"{path} is empty; {fix}")
    if lines[0].strip() != HOUSE_HEADER:
        raise DataFormatError(
            f"{path} does not start with the line {HOUSE_HEADER!r}, so it is not a Matterport3D "
            f".house file; {fix}"
        )
    found = dict.fromkeys(HOUSE_FIELDS, 0)
    header: list[str] | None = None
    for number, line in enumerate(lines[1:], 2):
        fields = line.split()
        if not fields or fields[0] not in HOUSE_FIELDS:
            continue
        kind = fields[0]
        if len(fields) < HOUSE_FIELDS[kind]:
            raise DataFormatError(
                f"{path}:{number}: a {kind!r} record of {len(fields)} fields, not "
                f"{HOUSE_FIELDS[kind]} (a cut or edited file); {fix}"
            )
        found[kind] += 1
        if kind == "H" and header is None:
            header = fields
    if header is None:
        raise DataFormatError(f"{path} has no 'H' record counting its contents; {fix}")
    for kind, index in HOUSE_COUNTS.items():
        try:
            declared = int(header[index])
        except ValueError:
            raise DataFormatError(
                f"{path}: the 'H' record's count of {_NAMES[kind]} is {header[index]!r}, not a "
                f"number; {fix}"
            ) from None
        if found[kind] < declared:
            raise DataFormatError(
                f"{path} holds {found[kind]} of the {declared} {_NAMES[kind]} its 'H' record "
                f"counts: the file is cut short; {fix}"
            )
    if found["R"] == 0:
        raise DataFormatError(
            f"{path} has no regions ('R' records), so the scene would have no rooms; "
            "give a .house file with its regions"
        )
    return text


def semantic_text(path: Path) -> str:
    """The text of an HM3D ``semantic.txt``: UTF-8, a title line and at least one object."""
    text = annotation_text(path, "an HM3D semantic.txt")
    if not any(line.strip() for line in text.splitlines()[1:]):
        raise DataFormatError(
            f'{path} lists no objects (a title line, then id,hexcolor,"category",region per '
            "object); give the scan's own semantic.txt"
        )
    return text
