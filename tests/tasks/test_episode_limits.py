"""Hostile episode files: integers of thousands of digits, floats past the float range, deep
nesting and values that would take more memory parsed than the file's cap allows are refused in
one line naming the file, through the reader and through `vlln eval`; legal files of many view
points still read."""

from __future__ import annotations

import dataclasses
import gzip
import json
from pathlib import Path

import pytest

from tests.tasks.test_episode import make_episode, raw_episode
from vlln.cli import main
from vlln.errors import DataFormatError
from vlln.tasks import episode as episode_module
from vlln.tasks.episode import EPISODE_FILE_CAP, ViewPoint, read_episodes, write_episodes
from vlln.tasks.json_fields import shown


def hostile_file(path: Path, field: str, text: str) -> Path:
    """An episode file whose one episode has ``field`` written as the raw JSON ``text``."""
    document = json.dumps({"episodes": [raw_episode() | {field: "@"}]}).replace('"@"', text)
    path.write_bytes(gzip.compress(document.encode()))
    return path


HOSTILE = {
    "5000-digit id": ("episode_id", "9" * 5000, "integer of 5000 digits"),
    "400-digit coordinate": ("start_position", "[" + "9" * 400 + ", 0, 0]", "400 digits"),
    "400-digit float": ("start_position", "[" + "9" * 400 + ".5, 0, 0]", "3 finite numbers"),
    "deep nesting": ("info", '{"a": ' + "[" * 5000 + "]" * 5000 + "}", "nested deeper"),
    "nesting under the parser's limit": ("info", "[" * 950 + "]" * 950, "nested deeper"),
    "a lone surrogate in a text": ("episode_id", '"7\\udfff"', "lone UTF-16 surrogate"),
}


@pytest.mark.parametrize("kind", sorted(HOSTILE))
def test_the_reader_refuses_in_one_line(tmp_path: Path, kind: str) -> None:
    field, text, reason = HOSTILE[kind]
    path = hostile_file(tmp_path / "val_iign.json.gz", field, text)
    with pytest.raises(DataFormatError) as info:
        read_episodes(path)
    message = str(info.value)
    assert message.startswith(str(path)) and reason in message
    assert "\n" not in message and len(message) < 300


def test_eval_refuses_a_hostile_episode_file_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = hostile_file(tmp_path / "val_iign.json.gz", "episode_id", "9" * 5000)
    args = ["eval", "--agent", "random", "--task", "iign", "--budget", "0"]
    assert main([*args, "--episode-file", str(path), "--out", str(tmp_path / "run")]) == 2
    error = capsys.readouterr().err
    assert error.startswith("error: ") and error.count("\n") == 1 and "5000 digits" in error


# With a cap of 1 MiB, reading may take 6 MiB: as many of each of these info values as would
# take more parsed, in well under 1 MiB of text (at the default cap, 128 times as many).
MEMORY_HOGS = {
    "floats": ("0.5", 200_000),
    "integers": ("257", 200_000),
    "short strings": ('"ab"', 100_000),
    "empty objects": ("{}", 100_000),
    "objects of one key": ('{"a": 0}', 22_000),
    "empty lists": ("[]", 50_000),
    "lists of one number": ("[0]", 50_000),
}


def info_file(path: Path, item: str, count: int) -> Path:
    """An episode file whose one episode's ``info`` holds a list of ``count`` copies of ``item``."""
    return hostile_file(path, "info", '{"x": [' + ",".join([item] * count) + "]}")


def refuses_for_memory(path: Path) -> None:
    """The one-line refusal of reading ``path`` under a 1 MiB cap (6 MiB of memory)."""
    with pytest.raises(DataFormatError) as info:
        read_episodes(path)
    message = str(info.value)
    assert message == (
        f"{path} would take more than 6 MiB of memory to read, the limit for an episode file "
        "(6 bytes a byte of its 1 MiB cap); set VLLN_MAX_EPISODE_FILE_MB to more MiB if the "
        "file is right"
    )


@pytest.mark.parametrize("kind", sorted(MEMORY_HOGS))
def test_values_that_would_take_too_much_memory_are_refused_before_parsing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, kind: str
) -> None:
    monkeypatch.setenv(EPISODE_FILE_CAP.variable or "", "1")
    item, count = MEMORY_HOGS[kind]
    path = info_file(tmp_path / "val_iign.json.gz", item, count)
    assert len(gzip.decompress(path.read_bytes())) < 1 << 20  # under the cap on bytes

    def parse_json(*args: object, **kwargs: object) -> None:
        raise AssertionError("parsed")

    monkeypatch.setattr(episode_module, "parse_json", parse_json)
    refuses_for_memory(path)


def test_many_distinct_keys_are_refused_before_parsing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(EPISODE_FILE_CAP.variable or "", "1")
    keys = ",".join(f'"k{i}": 0' for i in range(28_000))
    path = hostile_file(tmp_path / "val_iign.json.gz", "info", "{" + keys + "}")
    refuses_for_memory(path)


def test_text_whose_characters_widen_once_decoded_is_refused_before_it_is_decoded(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """One character past U+FFFF makes every character of the text take 4 bytes, and every
    character of its string."""
    monkeypatch.setenv(EPISODE_FILE_CAP.variable or "", "1")
    text = "a" * 900_000
    narrow = hostile_file(tmp_path / "narrow.json.gz", "info", f'{{"x": "{text}"}}')
    assert read_episodes(narrow)[0].info == {"x": text}
    refuses_for_memory(hostile_file(tmp_path / "wide.json.gz", "info", f'{{"x": "😀{text}"}}'))


def test_view_point_starts_that_are_no_view_points_are_charged_as_parsed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The text of a view point is charged as the small ViewPoint it becomes; one that does not
    become one (a text in its position) is kept as two objects and a list, and refused."""
    monkeypatch.setenv(EPISODE_FILE_CAP.variable or "", "1")
    start = '{"agent_state": {"position": [0.5, 0.0, %s]}}'
    items = ",".join([start % "1.5"] * 12_000)
    path = hostile_file(tmp_path / "val_iign.json.gz", "info", '{"x": [' + items + "]}")
    (episode,) = read_episodes(path)
    assert episode.info["x"] == [ViewPoint((0.5, 0.0, 1.5))] * 12_000
    items = ",".join([start % '"x"'] * 12_000)
    refuses_for_memory(hostile_file(path, "info", '{"x": [' + items + "]}"))


def test_view_points_are_charged_as_what_they_become(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Without spaces, view points are charged 6.3 bytes a byte of text, as the ViewPoint
    objects they become: a file of nothing else near its cap (1.97 of 2 MiB) would take more
    than the 12 MiB allowed."""
    monkeypatch.setenv(EPISODE_FILE_CAP.variable or "", "2")
    point = '{"agent_state":{"position":[0.5,0.0,1.5]}}'
    path = hostile_file(
        tmp_path / "val_iign.json.gz", "info", '{"x":[' + ",".join([point] * 48_000) + "]}"
    )
    assert len(gzip.decompress(path.read_bytes())) < 2 << 20
    with pytest.raises(DataFormatError, match="would take more than 12 MiB of memory to read"):
        read_episodes(path)


@pytest.mark.parametrize("compact", [False, True])
def test_a_file_of_many_view_points_near_its_cap_reads_unchanged(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, compact: bool
) -> None:
    """19,000 view points in 0.93 MiB, as written (at the default cap, 2.4 million in 119 MiB),
    or without spaces: each takes less memory than its text would be charged if it were not a
    view point."""
    monkeypatch.setenv(EPISODE_FILE_CAP.variable or "", "1")
    points = tuple(ViewPoint((i * 0.25, 0.0, 1.5)) for i in range(19_000))
    episode = make_episode(3)
    target = dataclasses.replace(episode.goals[0], view_points=points)
    episode = dataclasses.replace(episode, goals=(target, *episode.goals[1:]))
    path = tmp_path / "val_objectnav.json.gz"
    write_episodes(path, [episode])
    text = gzip.decompress(path.read_bytes())
    assert 0.85 * (1 << 20) < len(text) < 1 << 20
    if compact:
        text = json.dumps(json.loads(text), separators=(",", ":")).encode()
        path.write_bytes(gzip.compress(text))
    assert read_episodes(path) == [episode]


def test_a_long_value_in_an_error_is_shown_cut_short(tmp_path: Path) -> None:
    path = hostile_file(
        tmp_path / "val_iign.json.gz", "info", "[" + ",".join(["1e15"] * 100_000) + "]"
    )
    with pytest.raises(DataFormatError) as info:
        read_episodes(path)
    shown_value = ("[" + ", ".join(["1000000000000000.0"] * 5))[:77] + "..."
    assert str(info.value).endswith(
        f"field 'info': expected a JSON object or null, got {shown_value}"
    )


@pytest.mark.parametrize(
    "value",
    [
        [1, 2.5, "a", None, True],
        {"a": [1, {"b": None}], "c": -0.0},
        [[[[[]]]]],
        list(range(100)),
        {str(i): i for i in range(40)},
        "it's",
        'say "hi"',
        "it's " + "x" * 200,
        "x" * 200 + "it's",
        "both ' \" " + "x" * 200,
        "é😀\n\\" * 30,
        ["a'b" * 50],
    ],
)
def test_shown_is_the_repr_cut_to_80_characters(value: object) -> None:
    full = repr(value)
    assert shown(value) == (full if len(full) <= 80 else full[:77] + "...")
