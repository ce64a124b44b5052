"""The wheel that ``pip wheel .`` builds (the README's install without a package index) holds
every file the package reads, and the command line runs from it."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_the_wheel_holds_the_package_data_and_runs(tmp_path: Path) -> None:
    # Built from a copy, so the build folder setuptools leaves is not in the checkout.
    project = tmp_path / "project"
    project.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, project / name)
    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info")
    shutil.copytree(ROOT / "src", project / "src", ignore=ignore)
    build = [sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "--no-build-isolation"]
    subprocess.run([*build, str(project), "-w", str(tmp_path / "dist")], check=True)
    (wheel,) = (tmp_path / "dist").glob("vlln-*-py3-none-any.whl")

    package = ROOT / "src" / "vlln"
    data = {
        path.relative_to(package.parent).as_posix()
        for path in package.rglob("*")
        if path.is_file() and path.suffix not in (".py", ".pyc")
    }
    assert "vlln/oracle/data/question_classifier.json" in data and any("static" in n for n in data)
    assert not any(name.endswith(".jsonl") for name in data)  # the question sets stay outside
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
        archive.extractall(tmp_path / "installed")
    assert data <= names, sorted(data - names)
    assert "vlln/cli/__init__.py" in names

    # The command line of the unpacked wheel, away from the checkout, classifies with its
    # packaged classifier; the held-out set is not packaged, so it is named.
    env = dict(os.environ, PYTHONPATH=str(tmp_path / "installed"))
    where = subprocess.run(
        [sys.executable, "-c", "import vlln; print(vlln.__file__)"],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        check=True,
    )
    assert where.stdout.startswith(str(tmp_path / "installed"))
    heldout = ROOT / "oracle_training" / "questions" / "questions_heldout_v23_v24.jsonl"
    command = [sys.executable, "-m", "vlln.cli", "oracle", "classify-report"]
    report = subprocess.run(
        [*command, "--questions", str(heldout)],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
    )
    assert report.returncode == 0, report.stderr
    assert "| attribute |" in report.stdout
    bare = subprocess.run(command, capture_output=True, text=True, env=env, cwd=tmp_path)
    assert bare.returncode != 0 and "oracle_training/ folder" in bare.stderr
