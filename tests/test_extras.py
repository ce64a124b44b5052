"""Without the serve extra, the commands that need it say so in one line naming the install:
the real command line, in a process where importing the missing package fails."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

RUN_WITHOUT = (
    "import sys\n"
    "for name in sys.argv[1].split(','):\n"
    "    sys.modules[name] = None  # import fails as if it were not installed\n"
    "from vlln.cli import main\n"
    "sys.exit(main(sys.argv[2:]))\n"
)

COMMANDS = [
    ("fastapi", ["oracle", "serve", "--port", "0"], "vlln oracle serve needs fastapi"),
    ("uvicorn", ["oracle", "serve", "--port", "0"], "vlln oracle serve needs uvicorn"),
    ("fastapi", ["serve", "web", "--split", "test", "--houses", "1"], "vlln serve web needs"),
    ("fastapi", ["bench", "oracle", "--json"], "vlln bench oracle (its service figures) needs"),
    ("aiohttp", ["bench", "oracle", "--json"], "needs aiohttp"),
]


@pytest.mark.parametrize(("missing", "command", "message"), COMMANDS)
@pytest.mark.slow
def test_a_missing_serve_extra_is_one_line(
    tmp_path: Path, missing: str, command: list[str], message: str
) -> None:
    if command[:2] == ["serve", "web"]:
        command = [*command, "--out", str(tmp_path / "study")]
    done = subprocess.run(
        [sys.executable, "-c", RUN_WITHOUT, missing, *command],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 2, done.stderr
    assert done.stderr.count("\n") == 1 and done.stderr.startswith("error: ")
    assert message in done.stderr
    root = Path(__file__).resolve().parents[1]  # the clone this editable install runs from
    assert f"install the serve extra with: pip install -e '{root}[serve]'" in done.stderr
    assert not (tmp_path / "study").exists()
