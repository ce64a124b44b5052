"""`vlln eval --agent openai-vlm` against a local server speaking the chat-completions protocol:
scripted replies play episodes exactly as scripted, server trouble is retried and then
recorded as failed steps, and finished episodes survive an interrupted run."""

from __future__ import annotations

import json
import math
import socket
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.oracle.llm.chat_server import ChatServer, Scripted, chat_server, completion
from vlln.agents.expert import ExpertAgent
from vlln.cli import main
from vlln.eval.config import EvalConfig
from vlln.eval.options import ReportOptions
from vlln.eval.play import derive_seed, play_episode
from vlln.eval.report import write_report
from vlln.eval.runner import RunOutcome, run_evaluation
from vlln.prompt import IMAGE_TAG, DialogExchange, build_conversation, connective_for
from vlln.sim.agent import AgentState
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode, write_episodes
from vlln.tasks.metrics import success
from vlln.tasks.record import MAX_STORED_OUTPUT_CHARS, EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import TaskConfig, TaskType
from vlln.tasks.split_files import load_or_build_split
from vlln.world.frame import heading_vector, quaternion_to_yaw

ARROWS = {"TURN_LEFT": "←", "TURN_RIGHT": "→"}


def split_episodes(split_cache: Path) -> list[Episode]:
    return load_or_build_split("test", "iign", 1, split_cache, progress=False)


def episode_file(tmp_path: Path, episode: Episode) -> str:
    path = tmp_path / "episodes.json.gz"
    write_episodes(path, [episode])
    return str(path)


def run(
    server: ChatServer,
    source: str,
    out: Path,
    scenes: SceneCache,
    budget: int = 0,
    stop_after: int | None = None,
    **options: str,
) -> RunOutcome:
    config = EvalConfig(
        agent="openai-vlm",
        task="iign",
        split=None,
        episode_file=source,
        budgets=(budget,),
        max_steps=200,
        agent_options={
            "base_url": server.base_url,
            "model": "scripted-vlm",
            "backoff_s": "0.01",
            "timeout_s": "0.5",
            **options,
        },
    )
    return run_evaluation(config, out, progress=False, scenes=scenes, stop_after=stop_after)


def expert_replies(episode: Episode, scenes: SceneCache) -> tuple[list[str], EpisodeRecord]:
    """The expert's actions on the episode written as model outputs (turn runs of <= 4)."""
    env = NavigationEnv([episode], TaskConfig(task=TaskType.IGN), scenes, privileged=True)
    record = play_episode(env, ExpertAgent(), "expert")
    replies: list[str] = []
    run_name, run_length = "", 0
    for name in [*record.actions, "END"]:
        if name == run_name and run_length < 4:
            run_length += 1
            continue
        if run_name:
            replies.append("<move>" + ARROWS[run_name] * run_length)
        run_name, run_length = (name, 1) if name in ARROWS else ("", 0)
        if name == "MOVE_FORWARD":
            replies.append("<move>↑")
        elif name == "STOP":
            replies.append("<move>STOP")
    return replies, record


def user_texts(request: dict[str, Any]) -> list[str]:
    texts = []
    for message in request["json"]["messages"]:
        if message["role"] == "user":
            texts.append("".join(p.get("text", "") for p in message["content"]))
    return texts


def sent_turns(request: dict[str, Any]) -> list[str]:
    """Every message's text as the prompt wrote it, each picture back as an <image> tag."""
    texts = []
    for message in request["json"]["messages"]:
        content = message["content"]
        if isinstance(content, list):
            content = "".join(p["text"] if p["type"] == "text" else IMAGE_TAG for p in content)
        texts.append(content)
    return texts


def image_count(request: dict[str, Any]) -> int:
    return sum(
        part["type"] == "image_url"
        for message in request["json"]["messages"]
        if isinstance(message["content"], list)
        for part in message["content"]
    )


@pytest.mark.slow
def test_scripted_replies_play_the_experts_episode_to_success(
    split_cache: Path, scenes: SceneCache, tmp_path: Path
) -> None:
    episode = split_episodes(split_cache)[0]
    replies, expert = expert_replies(episode, scenes)
    assert success(expert) and len(replies) > 8
    with chat_server([completion(text) for text in replies]) as server:
        outcome = run(server, episode_file(tmp_path, episode), tmp_path / "run", scenes)
        requests = list(server.requests)
    (record,) = outcome.records
    assert record.actions == expert.actions
    assert success(record)
    assert [call.text for call in record.model_calls] == replies
    assert len(requests) == len(replies)
    first = requests[0]["json"]
    assert first["model"] == "scripted-vlm"
    assert image_count(requests[0]) == 1  # frame 0: the current view only
    assert image_count(requests[-1]) == 9  # 8 history frames and the current one
    url = first["messages"][0]["content"][1]["image_url"]["url"]
    assert url.startswith("data:image/jpeg;base64,/9j/")
    assert "TURN LEFT (←) or TURN RIGHT (→) by 30 degrees" in user_texts(requests[0])[0]
    # The last decision's prompt is the shared builder's text for that state, byte for byte.
    frame = sum(name != "STOP" for name in expert.actions)
    seed = derive_seed(0, "agent", episode.scene_id, episode.episode_id)
    expected = build_conversation(
        episode.instruction.instruction_text,
        frame,
        [],
        connective=connective_for(seed, episode.episode_id, frame),
        dialog_enabled=False,
    )
    assert sent_turns(requests[-1]) == [turn.text for turn in expected.turns]
    run_json = json.loads((tmp_path / "run" / "run.json").read_text())
    assert run_json["agent"] == "openai-vlm"
    assert run_json["agent_options"]["model"] == "scripted-vlm"


def floor_pixel(episode: Episode, scenes: SceneCache) -> tuple[int, int, float, float] | None:
    """A pixel of the start's look-down view showing navigable floor 1.5-2.5 m ahead."""
    sim = scenes.get(episode.scene_id)
    spec = sim.config.camera
    x, y, z = episode.start_position
    state = AgentState((x, y, z), quaternion_to_yaw(episode.start_rotation), -math.radians(30))
    depth = sim.render(state).depth
    fx, fy, cx, cy = spec.intrinsics()
    dx, dz = heading_vector(state.yaw)
    for ahead in np.linspace(2.5, 1.5, 5):
        gx, gz = x + ahead * dx, z + ahead * dz
        if not sim.grid.is_navigable(gx, gz):
            continue
        local = spec.view_matrix(state.position, state.yaw, state.tilt) @ [gx, y, gz, 1.0]
        d = -float(local[2])
        col, row = round(cx + fx * local[0] / d), round(cy - fy * local[1] / d)
        if 0 <= row < spec.height and abs(float(depth[row, col]) - d) < 0.05:
            return col, row, gx, gz
    return None


def test_a_pixel_goal_is_walked_by_the_follower_for_at_most_8_steps(
    split_cache: Path, scenes: SceneCache, tmp_path: Path
) -> None:
    found = ((e, floor_pixel(e, scenes)) for e in split_episodes(split_cache))
    episode, pixel = next((e, p) for e, p in found if p is not None)
    col, row, gx, gz = pixel
    script = ["<move>↓", f"<move>{col} {row}", "<move>STOP"]
    with chat_server([completion(text) for text in script]) as server:
        outcome = run(server, episode_file(tmp_path, episode), tmp_path / "run", scenes)
        requests = list(server.requests)
    (record,) = outcome.records
    assert len(requests) == 3
    assert image_count(requests[0]) == 1
    assert image_count(requests[1]) == 2  # the look-down view joins the same conversation
    assert requests[1]["json"]["messages"][1] == {"role": "assistant", "content": "<move>↓"}
    assert [c.look_down for c in record.model_calls] == [False, True, False]
    assert record.actions[:2] == ["LOOK_DOWN", f"PIXEL:{col},{row}"]
    walked = record.actions[2:-1]
    assert 1 <= len(walked) <= 8
    assert set(walked) <= {"MOVE_FORWARD", "TURN_LEFT", "TURN_RIGHT"}
    assert record.actions[-1] == "STOP"
    x, z, _ = record.positions[-1]
    start = record.positions[0]
    assert math.hypot(x - gx, z - gz) < math.hypot(start[0] - gx, start[1] - gz)
    assert record.failed_actions == 0


def test_a_question_is_answered_and_the_answer_reaches_the_next_prompt(
    split_cache: Path, scenes: SceneCache, tmp_path: Path
) -> None:
    episode = split_episodes(split_cache)[0]
    script = ["<talk>What color is it?", "<move>←", "<move>STOP"]
    with chat_server([completion(text) for text in script]) as server:
        outcome = run(server, episode_file(tmp_path, episode), tmp_path / "run", scenes, budget=5)
        requests = list(server.requests)
    (record,) = outcome.records
    (turn,) = record.dialog
    assert turn.question == "What color is it?" and turn.answered
    assert turn.answer
    seed = derive_seed(0, "agent", episode.scene_id, episode.episode_id)
    expected = build_conversation(
        episode.instruction.instruction_text,
        0,
        [DialogExchange(0, turn.question, turn.answer)],
        connective=connective_for(seed, episode.episode_id, 0),
    )
    assert sent_turns(requests[1]) == [t.text for t in expected.turns]
    second = requests[1]["json"]["messages"]
    assert second[1] == {"role": "assistant", "content": "<talk>What color is it?"}
    assert second[2]["role"] == "user"
    assert second[2]["content"] == [{"type": "text", "text": turn.answer}]
    # After a move the exchange sits in the history, after its frame's image.
    history = user_texts(requests[2])[0]
    assert f"<|navigator|>What color is it?<|oracle|>{turn.answer}" in history
    assert record.actions == ["TALK", "TURN_LEFT", "STOP"]


@pytest.mark.slow
def test_server_trouble_is_retried_then_recorded_as_failed_steps(
    split_cache: Path, scenes: SceneCache, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    episode = split_episodes(split_cache)[0]
    script = [
        Scripted(500, "boom"),
        Scripted(429, "slow down", {"Retry-After": "0"}),
        Scripted(200, completion("<move>←").body, delay_s=1.0),  # past the 0.5 s timeout
        Scripted(200, "{not json"),
        completion("<move>←"),  # fifth attempt of the first call: played
        Scripted(503, "down"),
        Scripted(503, "down"),
        Scripted(503, "down"),  # the second call gives up after 1 + 2 retries
        completion("<move>turn around please"),  # unreadable: a parse failure
        completion("<move>STOP"),
    ]
    with chat_server(script) as server:
        outcome = run(
            server,
            episode_file(tmp_path, episode),
            tmp_path / "run",
            scenes,
            max_retries="4",
            max_failures="10",  # below, the run would stop at the fourth failure in a row
        )
        first_call = [request["json"] for request in server.requests[:5]]
    (record,) = outcome.records
    assert record.actions[0] == "TURN_LEFT"
    assert all(body == first_call[0] for body in first_call)  # one call, four retries
    assert record.model_calls[0].latency_ms > 500.0  # it waited out the timeout
    with chat_server(script[5:]) as server:
        outcome = run(
            server, episode_file(tmp_path, episode), tmp_path / "run2", scenes, max_retries="2"
        )
    (record,) = outcome.records
    assert record.actions == ["FAILED:server", "FAILED:parse", "STOP"]
    assert record.failures == {"server": 1, "parse": 1}
    assert record.failed_actions == 2 and record.steps == 3
    server_call, parse_call, stop_call = record.model_calls
    assert server_call.text is None and "503" in (server_call.error or "")
    assert parse_call.text == "<move>turn around please"
    assert stop_call.text == "<move>STOP"
    summary = json.loads((tmp_path / "run2" / "summary.json").read_text())
    assert summary["groups"][0]["budgets"]["0"]["failed_actions"] == {"parse": 1, "server": 1}
    markdown = (tmp_path / "run2" / "summary.md").read_text()
    assert "Failed actions at budget 0: parse 1, server 1." in markdown
    assert main(["score", str(tmp_path / "run2")]) == 0
    assert "Failed actions at budget 0: parse 1, server 1." in capsys.readouterr().out
    write_report([tmp_path / "run2"], tmp_path / "report", ReportOptions(samples=0))
    report = (tmp_path / "report" / "report.md").read_text()
    assert "openai-vlm IIGN budget 0: parse 1, server 1" in report


def test_the_camera_returns_level_after_a_look_down_whatever_follows(
    split_cache: Path, scenes: SceneCache, tmp_path: Path
) -> None:
    episode = split_episodes(split_cache)[0]
    script = ["<move>↓", "<move>←←", "<move>↓", "<move>12", "<move>STOP"]
    with chat_server([completion(text) for text in script]) as server:
        outcome = run(server, episode_file(tmp_path, episode), tmp_path / "run", scenes)
        requests = list(server.requests)
    (record,) = outcome.records
    assert record.actions == [
        "LOOK_DOWN",
        "LOOK_UP",
        "TURN_LEFT",
        "TURN_LEFT",
        "LOOK_DOWN",
        "FAILED:parse",
        "STOP",
    ]
    assert record.failures == {"parse": 1}
    assert [image_count(r) for r in requests] == [1, 2, 3, 4, 3]  # frames 0, 0, 2, 2, 2


def test_an_interrupted_run_keeps_finished_episodes_and_resumes(
    split_cache: Path, scenes: SceneCache, tmp_path: Path
) -> None:
    episodes = split_episodes(split_cache)[:2]
    path = tmp_path / "two.json.gz"
    write_episodes(path, episodes)
    out = tmp_path / "run"
    with chat_server([completion("<move>→"), completion("<move>STOP")]) as server:
        first = run(server, str(path), out, scenes, stop_after=1)
        assert first.played == 1 and not first.complete
        line = (out / "episodes.jsonl").read_text().splitlines()[0]
        calls = len(server.requests)
        second = run(server, str(path), out, scenes)
        assert second.played == 1 and second.complete
        assert len(server.requests) == calls + 1  # the script's last reply, STOP, repeats
    lines = (out / "episodes.jsonl").read_text().splitlines()
    assert lines[0] == line and len(lines) == 2
    assert json.loads(line)["actions"] == ["TURN_RIGHT", "STOP"]
    assert json.loads(lines[1])["actions"] == ["STOP"]


def test_the_cli_runs_the_agent_and_refuses_a_missing_model(
    split_cache: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    episode = split_episodes(split_cache)[0]
    source = episode_file(tmp_path, episode)
    common = ["eval", "--agent", "openai-vlm", "--task", "iign", "--budget", "0"]
    common += ["--episode-file", source, "--quiet"]
    assert main([*common, "--out", str(tmp_path / "a"), "--base-url", "http://127.0.0.1:9/v1"]) == 2
    assert "the openai-vlm agent needs --model (the served model" in capsys.readouterr().err
    with chat_server([completion("<move>STOP")]) as server:
        args = ["--base-url", server.base_url, "--model", "m", "--api-key-env", "VLLN_TEST_KEY"]
        assert main([*common, "--out", str(tmp_path / "b"), *args]) == 0
    run_json = json.loads((tmp_path / "b" / "run.json").read_text())
    assert run_json["agent_options"] == {
        "api_key_env": "VLLN_TEST_KEY",
        "base_url": server.base_url,
        "model": "m",
    }
    assert "openai-vlm on IIGN" in capsys.readouterr().out


def test_a_trickling_server_is_cut_off_and_counted_as_a_server_failure(
    split_cache: Path, scenes: SceneCache, tmp_path: Path
) -> None:
    episode = split_episodes(split_cache)[0]
    # One byte every 50 ms: no read waits long, but the reply would take over 10 s.
    trickle = Scripted(200, completion("<move>←").body, trickle_s=0.05)
    with chat_server([trickle, completion("<move>STOP")]) as server:
        outcome = run(
            server, episode_file(tmp_path, episode), tmp_path / "run", scenes, max_retries="0"
        )
    (record,) = outcome.records
    assert record.actions == ["FAILED:server", "STOP"]
    assert record.failures == {"server": 1}
    failed = record.model_calls[0]
    assert failed.text is None and "0.5 s deadline" in (failed.error or "")
    assert failed.latency_ms < 5000.0  # cut off long before the reply could end
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["health"]["failures"]["model server failures"] == 1


@pytest.mark.slow
def test_a_reply_nested_100000_deep_is_counted_as_a_failed_call(
    split_cache: Path, scenes: SceneCache, tmp_path: Path
) -> None:
    episode = split_episodes(split_cache)[0]
    deep = Scripted(200, '{"choices": ' + "[" * 100_000 + "]" * 100_000 + "}")
    with chat_server([deep, completion("<move>STOP")]) as server:
        outcome = run(
            server, episode_file(tmp_path, episode), tmp_path / "run", scenes, max_retries="0"
        )
    (record,) = outcome.records
    assert record.actions == ["FAILED:server", "STOP"]
    assert "nested deeper" in (record.model_calls[0].error or "")


def test_an_endless_output_is_stored_cut_and_the_cut_counted(
    split_cache: Path, scenes: SceneCache, tmp_path: Path
) -> None:
    episode = split_episodes(split_cache)[0]
    endless = "<move>←" + " and on" * 30_000  # a server that ignores max_tokens
    with chat_server([completion(endless), completion("<move>STOP")]) as server:
        outcome = run(server, episode_file(tmp_path, episode), tmp_path / "run", scenes)
    (record,) = outcome.records
    long_call, stop_call = record.model_calls
    assert long_call.text == endless[:MAX_STORED_OUTPUT_CHARS]
    assert long_call.truncated_chars == len(endless) - MAX_STORED_OUTPUT_CHARS
    assert stop_call.text == "<move>STOP" and stop_call.truncated_chars == 0
    line = (tmp_path / "run" / "episodes.jsonl").read_text()
    assert len(line.encode()) < 4 * MAX_STORED_OUTPUT_CHARS + 10_000
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["health"]["failures"]["truncated model outputs"] == 1


def test_a_server_that_does_not_answer_is_refused_before_any_episode(
    split_cache: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    with socket.socket() as taken:  # a loopback port nothing listens on once it is closed
        taken.bind(("127.0.0.1", 0))
        port = taken.getsockname()[1]
    source = episode_file(tmp_path, split_episodes(split_cache)[0])
    args = ["eval", "--agent", "openai-vlm", "--task", "iign", "--budget", "0", "--quiet"]
    args += ["--episode-file", source, "--model", "m", "--out", str(tmp_path / "run")]
    assert main([*args, "--base-url", f"http://127.0.0.1:{port}/v1"]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1
    assert error.startswith(f"error: the model server at http://127.0.0.1:{port}/v1 does not")
    assert not (tmp_path / "run" / "episodes.jsonl").exists()


@pytest.mark.slow
def test_a_run_whose_every_model_call_failed_ends_non_zero(
    split_cache: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The server answers, but refuses every chat call: the episodes are kept, and the
    command says that they measure the server and exits non-zero."""
    source = episode_file(tmp_path, split_episodes(split_cache)[0])
    args = ["eval", "--agent", "openai-vlm", "--task", "iign", "--budget", "0", "--quiet"]
    args += ["--episode-file", source, "--model", "m", "--out", str(tmp_path / "run")]
    args += ["--model-retries", "0", "--model-max-failures", "10", "--max-steps", "6"]
    refusal = Scripted(404, {"error": {"message": "The model `m` does not exist."}})
    with chat_server([refusal]) as server:
        assert main([*args, "--base-url", server.base_url]) == 1
        calls = len(server.requests)
    error = capsys.readouterr().err.splitlines()[-1]
    assert error.startswith(f"error: none of {calls} model calls got a reply from the model's")
    assert "(the first: " in error and "404" in error and "rerun with a new --out" in error
    (record,) = (json.loads(line) for line in (tmp_path / "run" / "episodes.jsonl").open())
    assert record["failures"] == {"server": calls} and calls == 6
    # Scoring the folder later says the same, and fails too.
    assert main(["score", str(tmp_path / "run")]) == 1
    assert "error: none of 6 model calls got a reply" in capsys.readouterr().err
