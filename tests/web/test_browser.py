"""The real pages in headless Chromium: a person navigates, a person leaves an episode, a
person answers an agent, and two people play one episode from two browsers. Screenshots go to
out/web-screenshots/."""

from __future__ import annotations

import json
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from playwright.sync_api import Browser, Page, Response, sync_playwright

from vlln.cli import main
from vlln.eval.results import load_run_records
from vlln.web.config import WebConfig

from .browser import CHROMIUM, CHROMIUM_ARGS, KEY_OF, SCREENSHOTS
from .conftest import START_TIMEOUT, Served, Study, start_server

PRIVILEGED_KEYS = {
    "target",
    "target_id",
    "target_ids",
    "position",
    "positions",
    "pose",
    "trail",
    "gps",
    "compass",
    "instance_ids",
    "map",
    "extent",
    "distance",
    "geodesic",
    "view_points",
    "stop_instance_id",
    "yaw",
    "expert_action",
}
WAIT_MS = 30_000


@pytest.fixture(scope="module")
def browser() -> Iterator[Browser]:
    with sync_playwright() as playwright:
        launched = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        yield launched
        launched.close()


def _keys(value: Any) -> set[str]:
    if isinstance(value, dict):
        return set(value) | {k for v in value.values() for k in _keys(v)}
    if isinstance(value, list):
        return {k for v in value for k in _keys(v)}
    return set()


def _start(
    page: Page, served: Served, navigator: str, participant: str, oracle: str, episode: int
) -> dict[str, str]:
    page.goto(served.url + "/")
    page.wait_for_selector("#navigator option", state="attached")
    page.select_option("#navigator", navigator)
    page.fill("#participant", participant)
    page.select_option("#oracle", oracle)
    page.select_option("#episode", str(episode))
    page.click("#create")
    page.wait_for_selector("#created:not(.hidden)")
    return {
        role: page.text_content(f"#{role}-code") or ""
        for role in ("navigator", "oracle")
        if page.is_visible(f"#{role}-line")
    }


def _walk(page: Page, route: list[str]) -> None:
    """Press the keys of ``route`` one by one, each after the page shows the last move, and
    stop (S twice) when it ends with STOP."""
    page.wait_for_function("document.querySelector('#forward').disabled === false", timeout=WAIT_MS)
    moves = route[:-1] if route[-1] == "STOP" else route
    for action in moves:
        steps_before = page.text_content("#steps")
        frame_before = page.evaluate("window.vllnLatencies.length")
        page.keyboard.press(KEY_OF[action])
        page.wait_for_function(f"window.vllnLatencies.length > {frame_before}", timeout=WAIT_MS)
        assert page.text_content("#steps") != steps_before
    if moves is route:
        return
    page.keyboard.press("s")
    page.keyboard.press("s")
    page.wait_for_selector("#result:not(.hidden)", timeout=WAIT_MS)


@pytest.mark.slow
def test_a_person_reaches_the_target_and_the_record_scores_as_a_success(
    browser: Browser, served: Served, study: Study, capsys: pytest.CaptureFixture[str]
) -> None:
    page = browser.new_page(bypass_csp=True, viewport={"width": 1280, "height": 800})
    payloads: list[Any] = []

    def keep(response: Response) -> None:
        if "/api/navigator" in response.url:
            payloads.append(response.json())

    page.on("response", keep)
    codes = _start(page, served, "human", "p01", "rules", 0)
    assert set(codes) == {"navigator"}
    page.click("#navigator-link")
    page.wait_for_selector("#instruction:has-text('Search for the')")
    page.fill("#question", "What color is it?")
    page.click("#ask")
    page.wait_for_selector("#dialog li")
    half = len(study.routes[0]) // 2
    _walk(page, study.routes[0][:half])
    page.screenshot(path=str(SCREENSHOTS / "navigator.png"))
    link = page.url
    page.close()  # a closed tab loses nothing: the same link resumes the episode
    page = browser.new_page(bypass_csp=True, viewport={"width": 1280, "height": 800})
    page.on("response", keep)
    page.goto(link)
    page.wait_for_selector("#dialog li")
    assert page.text_content("#steps") == str(half)
    _walk(page, study.routes[0][half:])
    assert "Success" in (page.text_content("#result") or "")
    page.close()

    assert payloads and all(not (_keys(p) & PRIVILEGED_KEYS) for p in payloads)
    assert main(["score", str(served.config.out), "--json"]) == 0
    groups = {g["agent"]: g for g in json.loads(capsys.readouterr().out)["groups"]}
    assert groups["human:p01"]["budgets"]["5"]["overall"]["sr"] == 100.0
    (record,) = [r for r in load_run_records([served.config.out]) if r.agent == "human:p01"]
    assert record.oracle == "rules" and record.dialog[0].backend == "rules"


@pytest.fixture
def one_slot(study: Study, tmp_path: Path) -> Iterator[Served]:
    """A server that lets one session be played at a time."""
    config = WebConfig(episodes=tuple(study.episodes), out=tmp_path / "web", max_live_sessions=1)
    url, server, thread = start_server(config)
    yield Served(url, config)
    server.should_exit = True  # type: ignore[attr-defined]
    thread.join(timeout=START_TIMEOUT)


@pytest.mark.slow
def test_a_person_who_leaves_ends_the_episode_and_frees_the_slot_at_once(
    browser: Browser, one_slot: Served
) -> None:
    lobby = browser.new_page(bypass_csp=True)
    codes = _start(lobby, one_slot, "human", "p33", "rules", 0)
    lobby.fill("#participant", "p34")
    lobby.click("#create")
    lobby.wait_for_selector("#create-error:has-text('the limit is 1')")

    page = browser.new_page(bypass_csp=True, viewport={"width": 1280, "height": 800})
    page.goto(f"{one_slot.url}/navigate#{codes['navigator']}")
    page.wait_for_function("document.querySelector('#forward').disabled === false", timeout=WAIT_MS)
    page.once("dialog", lambda dialog: dialog.accept())  # "Leave this episode? ..."
    page.click("#leave")
    page.wait_for_selector("#result:not(.hidden)", timeout=WAIT_MS)
    assert page.text_content("#result") == "This episode was recorded as abandoned."
    assert page.text_content("#status") == "The episode is over. Thank you!"
    assert page.is_disabled("#leave") and page.is_disabled("#forward")
    page.close()

    lobby.reload()
    lobby.wait_for_selector("#overview:has-text('Sessions')")
    assert "Sessions: 0 live, 0 finished, 1 abandoned." in (lobby.text_content("#overview") or "")
    again = _start(lobby, one_slot, "human", "p34", "rules", 1)
    assert again["navigator"] not in ("", codes["navigator"])
    assert lobby.text_content("#create-error") == ""
    lobby.close()
    (record,) = load_run_records([one_slot.config.out])
    assert (
        record.agent == "human:p33" and record.error == "abandoned: the navigator ended the session"
    )


@pytest.mark.slow
def test_two_people_play_one_episode_from_two_browsers_and_markup_shows_as_text(
    browser: Browser, served: Served, study: Study
) -> None:
    host = browser.new_context(bypass_csp=True, viewport={"width": 1280, "height": 800})
    navigator = host.new_page()
    codes = _start(navigator, served, "human", "p02", "human", 1)
    navigator.screenshot(path=str(SCREENSHOTS / "lobby.png"))
    navigator.click("#navigator-link")
    navigator.wait_for_selector("#instruction:has-text('Search for the')")

    helper = browser.new_context(bypass_csp=True, viewport={"width": 1400, "height": 1000})
    oracle = helper.new_page()
    oracle.goto(served.url + "/")
    oracle.fill("#join-code", codes["oracle"])
    oracle.click("#join")
    oracle.wait_for_url("**/answer#*")
    oracle.wait_for_selector("#target .name")

    half = len(study.routes[1]) // 2
    _walk(navigator, study.routes[1][:half])
    question = "<script>window.pwned = 1</script><b>Which</b> one is it?"
    navigator.fill("#question", question)
    navigator.click("#ask")
    oracle.wait_for_selector("#question-area:not(.hidden)", timeout=WAIT_MS)
    assert oracle.text_content("#question") == question
    assert oracle.eval_on_selector("#question", "node => node.children.length") == 0
    oracle.fill("#answer", "It is the one by the window, <i>left</i> of you.")
    oracle.wait_for_function("document.querySelector('#map').naturalWidth > 0")
    oracle.screenshot(path=str(SCREENSHOTS / "oracle.png"))
    oracle.click("#send")
    navigator.wait_for_selector("#dialog li .answer", timeout=WAIT_MS)
    assert navigator.text_content("#dialog li .question") == f"Q1: {question}"
    assert (
        navigator.text_content("#dialog li .answer")
        == "It is the one by the window, <i>left</i> of you."
    )
    for page in (navigator, oracle):
        assert page.evaluate("typeof window.pwned") == "undefined"

    _walk(navigator, study.routes[1][half:])
    oracle.wait_for_selector("#result:not(.hidden)", timeout=WAIT_MS)
    host.close()
    helper.close()
    (record,) = [
        r for r in load_run_records([served.config.out]) if r.agent == "human:p02 with human oracle"
    ]
    assert record.oracle == "human" and record.dialog[0].backend == "human"
    assert record.dialog[0].question == question and not record.dialog[0].fallback


@pytest.mark.slow
def test_a_person_answers_the_frontier_agents_questions(
    browser: Browser, served: Served, study: Study
) -> None:
    lobby = browser.new_page(bypass_csp=True)
    codes = _start(lobby, served, "frontier", "x", "human", 2)
    assert set(codes) == {"oracle"}
    lobby.close()
    oracle = browser.new_page(bypass_csp=True, viewport={"width": 1400, "height": 1000})
    oracle.goto(f"{served.url}/answer#{codes['oracle']}")
    answers = []
    while True:
        oracle.wait_for_selector(
            "#question-area:not(.hidden), #result:not(.hidden)", timeout=WAIT_MS
        )
        if oracle.is_visible("#result"):
            break
        number = oracle.evaluate("page.state.question.number")
        answers.append(f"Answer {number}: keep going.")
        oracle.fill("#answer", answers[-1])
        oracle.click("#send")
        oracle.wait_for_function(f"!page.state.question || page.state.question.number > {number}")
    oracle.close()
    (record,) = [
        r for r in load_run_records([served.config.out]) if r.agent == "frontier with human oracle"
    ]
    assert answers and [turn.answer for turn in record.dialog if turn.answered] == answers
    assert all(turn.backend == "human" for turn in record.dialog if turn.answered)


@pytest.fixture(autouse=True, scope="module")
def _screenshot_folder() -> None:
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    os.environ.setdefault("VLLN_SCREENSHOTS", str(SCREENSHOTS))
