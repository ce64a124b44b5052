"""Session journals: read back after a kill, a torn last line ignored, codes only as digests."""

from __future__ import annotations

from pathlib import Path

import pytest

from vlln.errors import DataFormatError
from vlln.tasks.oracle_protocol import QuestionType, Reply
from vlln.web.journal import (
    JOURNAL_CAP,
    JOURNAL_FOLDER,
    Journal,
    SessionSpec,
    code_digest,
    read_journal,
    unfinished_journals,
)

SPEC = SessionSpec(
    "s1", 0, "web-0", "vlln/house_00039", "human:p1", "human", 5, 0, code_digest("c")
)


def test_a_journal_reads_back_without_its_torn_last_line(tmp_path: Path) -> None:
    journal = Journal(tmp_path / JOURNAL_FOLDER, SPEC)
    journal.action("MOVE_FORWARD")
    reply = Reply("It is red.", QuestionType.ATTRIBUTE, "human", 1200.0)
    journal.talk("What color is it?", reply)
    journal.talk("And now?", None)
    journal.close()
    with journal.path.open("ab") as handle:
        handle.write(b'{"kind": "action", "act')  # a kill in the middle of a write
    (contents,) = unfinished_journals(tmp_path)
    assert contents.spec == SPEC and not contents.ended
    assert [s.action for s in contents.steps] == ["MOVE_FORWARD", None, None]
    assert contents.steps[1].reply == reply and contents.steps[2].reply is None
    assert f'"navigator_code":"{code_digest("c")}"' in journal.path.read_text()
    reopened = Journal(tmp_path / JOURNAL_FOLDER, SPEC)  # cuts the torn line, then appends
    reopened.end("finished")
    reopened.close()
    contents = read_journal(journal.path)
    assert contents.ended and contents.spec == SPEC and len(contents.steps) == 3
    assert unfinished_journals(tmp_path) == []


def test_a_file_that_is_not_a_journal_is_named(tmp_path: Path) -> None:
    folder = tmp_path / JOURNAL_FOLDER
    folder.mkdir()
    (folder / "x.jsonl").write_text('{"kind": "action", "action": "STOP"}\n')
    with pytest.raises(DataFormatError, match="not a session journal"):
        unfinished_journals(tmp_path)


@pytest.mark.parametrize(
    ("line", "reason"),
    [
        ('{"kind": "action", "action": ' + "[" * 100_000 + "]" * 100_000 + "}", "nested deeper"),
        ('{"kind": "action", "action": ' + "9" * 5000 + "}", "5000 digits"),
        ('{"kind": "invalid", "text": "\\udc80"}', "surrogate"),
    ],
)
def test_a_hostile_journal_line_is_one_line_naming_the_file(
    tmp_path: Path, line: str, reason: str
) -> None:
    journal = Journal(tmp_path / JOURNAL_FOLDER, SPEC)
    journal.close()
    with journal.path.open("a") as handle:
        handle.write(line + "\n")
    with pytest.raises(DataFormatError) as info:
        unfinished_journals(tmp_path)
    message = str(info.value)
    assert message.startswith(f"{journal.path} is not a session journal") and reason in message
    assert "\n" not in message and len(message) < 300


def test_a_journal_past_its_cap_is_refused_unread(tmp_path: Path) -> None:
    journal = Journal(tmp_path / JOURNAL_FOLDER, SPEC)
    journal.close()
    with journal.path.open("ab") as handle:
        handle.truncate(JOURNAL_CAP.limit() + 1)  # sparse: no disk used
    with pytest.raises(DataFormatError, match=f"more than {JOURNAL_CAP.mib} MiB"):
        read_journal(journal.path)
