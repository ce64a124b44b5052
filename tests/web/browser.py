"""Headless Chromium (the Debian package) driven by Playwright, shared by a module's tests."""

from __future__ import annotations

from pathlib import Path

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]
SCREENSHOTS = Path(__file__).resolve().parents[2] / "out" / "web-screenshots"
KEY_OF = {"MOVE_FORWARD": "ArrowUp", "TURN_LEFT": "ArrowLeft", "TURN_RIGHT": "ArrowRight"}
