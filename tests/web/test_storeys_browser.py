"""A two-storey episode in headless Chromium: a person climbs the stairs to a target upstairs
while another answers with the map of the storey the navigator is on."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from playwright.sync_api import Browser, Page, sync_playwright

from tests.stairs import SCENE_ID, upstairs_episode
from tests.web.test_browser import WAIT_MS, _start, _walk
from vlln.eval.results import load_run_records
from vlln.tasks.episode import Episode
from vlln.tasks.scenes import SceneCache
from vlln.web.config import WebConfig

from .browser import CHROMIUM, CHROMIUM_ARGS, SCREENSHOTS
from .conftest import START_TIMEOUT, Served, _route, start_server


@pytest.fixture(scope="module")
def upstairs(
    tmp_path_factory: pytest.TempPathFactory,
) -> Iterator[tuple[Served, Episode, list[str]]]:
    """A server with one episode from the foot of the stairs, and the expert's route."""
    scenes = SceneCache()
    episode: Episode = upstairs_episode(scenes.get(SCENE_ID), "stairs-0", near=4.0)
    route = _route(episode, scenes)
    scenes.close()
    out: Path = tmp_path_factory.mktemp("web-storeys")
    config = WebConfig(episodes=(episode,), out=out, answer_time_limit_s=60.0)
    url, server, thread = start_server(config)
    yield Served(url, config), episode, route
    server.should_exit = True  # type: ignore[attr-defined]
    thread.join(timeout=START_TIMEOUT)


@pytest.fixture(scope="module")
def browser() -> Iterator[Browser]:
    with sync_playwright() as playwright:
        launched = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        yield launched
        launched.close()


MAP_PIXEL = """([x, z]) => {
  const image = document.querySelector('#map');
  const canvas = document.createElement('canvas');
  canvas.width = image.naturalWidth;
  canvas.height = image.naturalHeight;
  const context = canvas.getContext('2d');
  context.drawImage(image, 0, 0);
  const [x0, x1, y0, y1] = page.extent;
  const px = ((x - x0) / (x1 - x0)) * canvas.width;
  const py = ((y1 + z) / (y1 - y0)) * canvas.height;
  return Array.from(context.getImageData(px, py, 1, 1).data.slice(0, 3));
}"""


def _map_storey(oracle: Page, storey: int, name: str) -> None:
    """Wait until the oracle's map shows ``storey`` and the heading names it."""
    oracle.wait_for_function(
        f"page.mapStorey === {storey} && document.querySelector('#map').complete",
        timeout=WAIT_MS,
    )
    assert oracle.text_content("#storey") == f": {name}"


@pytest.mark.slow
def test_a_person_climbs_to_a_target_upstairs_and_the_oracle_sees_each_storeys_map(
    browser: Browser, upstairs: tuple[Served, Episode, list[str]]
) -> None:
    served, episode, route = upstairs
    host = browser.new_context(bypass_csp=True, viewport={"width": 1280, "height": 800})
    navigator = host.new_page()
    codes = _start(navigator, served, "human", "p30", "human", 0)
    navigator.click("#navigator-link")
    navigator.wait_for_selector("#instruction:has-text('Search for the')")
    helper = browser.new_context(bypass_csp=True, viewport={"width": 1400, "height": 1000})
    oracle = helper.new_page()
    oracle.goto(f"{served.url}/answer#{codes['oracle']}")
    oracle.wait_for_selector("#target .name")
    _map_storey(oracle, 0, "ground floor")
    ground = oracle.evaluate("document.querySelector('#map').src")
    oracle.screenshot(path=str(SCREENSHOTS / "oracle-ground-floor.png"))

    stop = len(route) - 1
    _walk(navigator, route[:stop])
    _map_storey(oracle, 1, "first floor")
    assert oracle.evaluate("document.querySelector('#map').src") != ground
    # The target's red outline is where the map's extent puts the target's box.
    bbox = episode.goals[0].bbox
    assert bbox is not None
    left_edge = [bbox[0] - 0.15, (bbox[2] + bbox[5]) / 2.0]
    assert oracle.evaluate(MAP_PIXEL, left_edge) == [214, 39, 40]
    navigator.fill("#question", "Am I on the right floor?")
    navigator.click("#ask")
    oracle.wait_for_selector("#question-area:not(.hidden)", timeout=WAIT_MS)
    trail = oracle.evaluate("page.state.trail.length")
    assert 0 < trail < stop  # only the part of the trail walked upstairs
    oracle.screenshot(path=str(SCREENSHOTS / "oracle-first-floor.png"))
    oracle.fill("#answer", "Yes, it is on this floor.")
    oracle.click("#send")
    navigator.wait_for_selector("#dialog li .answer", timeout=WAIT_MS)
    _walk(navigator, route[stop:])
    assert "Success" in (navigator.text_content("#result") or "")
    oracle.wait_for_selector("#result:not(.hidden)", timeout=WAIT_MS)
    host.close()
    helper.close()
    (record,) = load_run_records([served.config.out])
    assert record.scene_id == SCENE_ID and record.steps == len(route)
    assert [turn.answer for turn in record.dialog] == ["Yes, it is on this floor."]


@pytest.fixture(autouse=True, scope="module")
def _screenshot_folder() -> None:
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
