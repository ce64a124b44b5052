"""The set-up script's functions (scripts/setup-lib.sh), run by bash against real apt-get and
pip: apt waits for a lock that another process holds; torch's CPU build comes from its wheel
index, or from pip's configured index when that cannot be reached (local package indexes
serving small stand-in wheels, so nothing is downloaded)."""

from __future__ import annotations

import fcntl
import http.server
import os
import socket
import subprocess
import sys
import threading
import time
import zipfile
from collections.abc import Iterator
from functools import partial
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[1]
LIB = ROOT / "scripts" / "setup-lib.sh"
LOCK_WAIT_S = 4.0  # how long apt_get must keep waiting for a held lock before it is freed


def _bash(script: str, env: dict[str, str]) -> subprocess.Popen[str]:
    return subprocess.Popen(
        ["bash", "-c", f"set -euo pipefail; source {LIB}; {script}"],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )


def _apt_sandbox(root: Path) -> list[str]:
    """apt-get options that point every state and lock file into ``root``."""
    for folder in ("lists/partial", "parts", "dpkg", "cache/archives/partial"):
        (root / folder).mkdir(parents=True)
    (root / "dpkg" / "status").touch()
    return [
        f"-o Dir::State::Lists={root / 'lists'}",
        "-o Dir::Etc::SourceList=/dev/null",
        f"-o Dir::Etc::SourceParts={root / 'parts'}",
        f"-o Dir::State::status={root / 'dpkg' / 'status'}",
        f"-o Dir::Cache={root / 'cache'}",
    ]


@pytest.mark.slow
@pytest.mark.parametrize(
    ("lock", "command"), [("lists/lock", "update"), ("dpkg/lock-frontend", "install -y")]
)
def test_apt_get_waits_for_a_lock_another_process_holds(
    tmp_path: Path, lock: str, command: str
) -> None:
    options = " ".join(_apt_sandbox(tmp_path))
    with (tmp_path / lock).open("a") as held:
        fcntl.lockf(held, fcntl.LOCK_EX)  # as another apt-get would
        env = {key: value for key, value in os.environ.items() if key != "SUDO"}
        run = _bash(f"apt_get {options} {command}", env | {"APT_LOCK_TIMEOUT": "120"})
        # Still running seconds later: it waits instead of failing. (Whether apt says so in
        # its progress lines varies, so the test does not wait for its words.)
        waited = time.monotonic() + LOCK_WAIT_S
        while run.poll() is None and time.monotonic() < waited:
            time.sleep(0.1)
        if run.poll() is not None:
            pytest.fail(f"apt-get ended without waiting: {run.communicate()[0]}")
        fcntl.lockf(held, fcntl.LOCK_UN)
    output, _ = run.communicate(timeout=120)
    assert run.returncode == 0, output


def _wheel(folder: Path, version: str) -> str:
    """A pure-Python stand-in for torch ``version``: a module that knows its version."""
    name = f"torch-{version}-py3-none-any.whl"
    info = f"torch-{version}.dist-info"
    files = {
        "torch/__init__.py": f"__version__ = {version!r}\n",
        f"{info}/METADATA": f"Metadata-Version: 2.1\nName: torch\nVersion: {version}\n",
        f"{info}/WHEEL": "Wheel-Version: 1.0\nGenerator: test\nRoot-Is-Purelib: true\n"
        "Tag: py3-none-any\n",
    }
    record = "".join(f"{path},,\n" for path in files) + f"{info}/RECORD,,\n"
    with zipfile.ZipFile(folder / name, "w") as archive:
        for path, text in {**files, f"{info}/RECORD": record}.items():
            archive.writestr(path, text)
    return name


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format: str, *args: Any) -> None:
        """No access log among the test's output."""


@pytest.fixture
def indexes(tmp_path: Path) -> Iterator[str]:
    """A web server with two simple package indexes (PEP 503): ``/cpu/``, which holds torch's
    CPU build, and ``/pypi/``, which holds the plain build."""
    for index, version in (("cpu", "2.13.0+cpu"), ("pypi", "2.13.0")):
        page = tmp_path / "site" / index / "torch"
        page.mkdir(parents=True)
        name = _wheel(page, version)
        (page / "index.html").write_text(f'<a href="{name.replace("+", "%2B")}">{name}</a>')
    site = partial(_QuietHandler, directory=str(tmp_path / "site"))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), site)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}"
    server.shutdown()
    server.server_close()


def _closed_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


@pytest.mark.slow
def test_torch_comes_from_the_cpu_index_or_else_from_the_configured_one(
    tmp_path: Path, indexes: str
) -> None:
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    # pip sees only the indexes named here: no configuration files, no PIP_* settings.
    env = {
        key: value
        for key, value in os.environ.items()
        if not key.startswith("PIP_") and key != "TORCH_VERSION"
    }
    env |= {"PIP_CONFIG_FILE": os.devnull, "PIP_INDEX_URL": f"{indexes}/pypi/"}
    installed = [str(python), "-c", "import torch; print(torch.__version__)"]

    cpu = _bash(f"install_torch {python}", env | {"TORCH_CPU_INDEX": f"{indexes}/cpu/"})
    output, _ = cpu.communicate(timeout=300)
    assert cpu.returncode == 0, output
    assert "note:" not in output
    assert subprocess.run(installed, capture_output=True, text=True).stdout == "2.13.0+cpu\n"

    subprocess.run([str(python), "-m", "pip", "uninstall", "-q", "-y", "torch"], check=True)
    unreachable = f"http://127.0.0.1:{_closed_port()}/cpu/"
    fallback = _bash(f"install_torch {python}", env | {"TORCH_CPU_INDEX": unreachable})
    output, _ = fallback.communicate(timeout=300)
    assert fallback.returncode == 0, output
    assert f"torch's CPU wheel index {unreachable} could not be used" in output
    assert subprocess.run(installed, capture_output=True, text=True).stdout == "2.13.0\n"
