"""`vlln bench web`: key press to new frame in the browser, as a person playing sees it.

A server on loopback serves one episode to headless Chromium (Debian's ``chromium``, driven by
Playwright); the benchmark presses turn keys and the page itself times each press until the
new frame is decoded and shown (``window.vllnLatencies``), so the figure includes the request,
the simulator step, rendering on the CPU, JPEG encoding, transfer and decoding.
"""

from __future__ import annotations

import tempfile
import threading
import time
from pathlib import Path

import numpy as np

from vlln.bench.figures import Figure, emit
from vlln.bench.settings import WebBench
from vlln.errors import ConfigError, VllnError
from vlln.sim.simulator import Simulator
from vlln.tasks.generation import generate_house_episodes
from vlln.tasks.spec import TaskType
from vlln.world.generator import generate_house

BROWSER_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]
HOUSE_SEED = 39
WARM_UP = 5


def run_web_benchmark(settings: WebBench) -> list[Figure]:
    """Measure and print p50/p99 key-press-to-frame latency over ``settings.presses`` presses."""
    presses, browser, as_json = settings.presses, settings.browser, settings.as_json
    if not Path(browser).exists():
        raise ConfigError(f"no browser at {browser}; install Debian's chromium or pass --browser")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        raise ConfigError("the web benchmark needs Playwright: pip install playwright") from None
    from vlln.web.config import WebConfig
    from vlln.web.server import build_server

    with Simulator(generate_house(HOUSE_SEED)) as sim:
        episodes = generate_house_episodes(sim, np.random.default_rng(0)).of_task(TaskType.IIGN)
    with tempfile.TemporaryDirectory() as out:
        config = WebConfig(episodes=tuple(episodes[:1]), out=Path(out), requests_per_second=1000.0)
        server = build_server(config, "127.0.0.1", 0, source="benchmark")
        thread = threading.Thread(target=server.run, daemon=True)
        thread.start()
        while not server.started:
            time.sleep(0.02)
        url = f"http://127.0.0.1:{server.servers[0].sockets[0].getsockname()[1]}"
        try:
            latencies = _press(url, presses, browser, sync_playwright)
        finally:
            server.should_exit = True
            thread.join(timeout=30.0)
    timed = np.asarray(latencies[WARM_UP:])
    figures = [
        Figure("key_to_frame_p50_ms", float(np.percentile(timed, 50)), "ms"),
        Figure("key_to_frame_p99_ms", float(np.percentile(timed, 99)), "ms"),
        Figure("key_presses", float(len(timed)), "presses"),
    ]
    for figure in figures:
        emit(figure, as_json)
    return figures


def _press(url: str, presses: int, browser: str, sync_playwright: object) -> list[float]:
    import httpx
    from playwright.sync_api import TimeoutError as PageTimeout

    created = httpx.post(
        f"{url}/api/sessions",
        json={"navigator": "human", "participant": "bench", "oracle": "rules"},
        timeout=30.0,
    ).json()
    with sync_playwright() as playwright:  # type: ignore[operator]
        chromium = playwright.chromium.launch(executable_path=browser, args=BROWSER_ARGS)
        page = chromium.new_page(bypass_csp=True)
        page.goto(f"{url}/navigate#{created['navigator_code']}")
        page.wait_for_function("!document.querySelector('#left').disabled", timeout=60_000)
        for number in range(presses + WARM_UP):
            page.keyboard.press("ArrowLeft" if (number // 12) % 2 == 0 else "ArrowRight")
            try:
                page.wait_for_function(f"window.vllnLatencies.length > {number}", timeout=60_000)
            except PageTimeout:  # a lost press: say what the page showed instead of a trace
                status = page.text_content("#status")
                raise VllnError(
                    f"key press {number + 1} showed no new frame within 60 s; the page says: "
                    f"{status!r}"
                ) from None
        latencies: list[float] = page.evaluate("window.vllnLatencies")
        chromium.close()
    return latencies
