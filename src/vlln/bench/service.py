"""The oracle service under load: `vlln bench oracle` figures for ``vlln oracle serve``.

The service runs as its own process (``python -m vlln.cli oracle serve``, loopback, with a
token), exactly as a user starts it, so its memory is measured apart from the clients'.
Throughput: :data:`CLIENTS` concurrent clients on loopback each open a session on one house and
send questions from random navigable poses (three asks, then a look at the dialog, repeated)
over one kept-alive connection; every request's latency is taken from send to full reply. The
clients share the machine's cores with the server, so they use aiohttp, whose cost per request
is about a tenth of httpx's: the figure is the server's, not the load generator's. Memory:
one session on each of ``memory_scenes`` distinct houses, then the server's resident memory,
which must stay bounded by its scene cache however many sessions there are.
"""

from __future__ import annotations

import asyncio
import math
import os
import secrets
import socket
import subprocess
import sys
import time
from collections.abc import Callable
from functools import partial
from typing import Any

import aiohttp
import httpx
import numpy as np

from vlln.errors import ConfigError
from vlln.oracle.question_set import heldout_texts
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.tasks.scenes import procedural_scene_id
from vlln.world.generator import generate_house

CLIENTS = 30
ROUNDS = 10  # per client: three asks and one view each
MEMORY_SCENES = 64
START_TIMEOUT_S = 60.0
TIMEOUT = aiohttp.ClientTimeout(total=30.0)
Record = Callable[[str, float, str], None]


def run_service_benchmark(
    record: Record, seed: int = 0, memory_scenes: int = MEMORY_SCENES, rounds: int = ROUNDS
) -> None:
    """Start the service, measure it under load and with many scenes, stop it."""
    token = secrets.token_urlsafe(16)
    port = _free_port()
    command = [
        sys.executable, "-m", "vlln.cli", "oracle", "serve", "--port", str(port),
        "--max-sessions", str(max(64, memory_scenes, CLIENTS * rounds)),
        "--builds-per-minute", "100000", "--client-builds-per-minute", "100000",
    ]  # fmt: skip
    env = os.environ | {"VLLN_ORACLE_TOKEN": token}
    server = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        base = f"http://127.0.0.1:{port}"
        headers = {"Authorization": f"Bearer {token}"}
        _wait_until_up(base, server)
        target, poses = _target_and_poses(seed)
        questions = heldout_texts("vlln bench oracle")
        server_cpu = partial(_cpu_seconds, server.pid)
        load = asyncio.run(_load(base, headers, seed, target, poses, questions, rounds, server_cpu))
        record("service_clients", CLIENTS, "clients")
        record("service_requests_per_s", load["rate"], "req/s")
        record("service_p50_ms", load["p50"], "ms")
        record("service_p99_ms", load["p99"], "ms")
        record("service_errors", load["errors"], "requests")
        record("service_cpu_ms_per_request", load["cpu_ms"], "ms")
        _sessions_on_distinct_scenes(base, headers, memory_scenes)
        record(f"service_rss_{memory_scenes}_scenes_mb", _rss_mb(server.pid), "MB")
    finally:
        server.terminate()
        try:
            server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()
        if server.stderr is not None:
            server.stderr.close()


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port: int = probe.getsockname()[1]
        return port


def _wait_until_up(base: str, server: subprocess.Popen[bytes]) -> None:
    deadline = time.monotonic() + START_TIMEOUT_S
    while time.monotonic() < deadline:
        if server.poll() is not None:
            error = server.stderr.read().decode() if server.stderr else ""
            raise ConfigError(f"the oracle service did not start: {error.strip()[-400:]}")
        try:
            if httpx.get(f"{base}/v1/health", timeout=1.0).status_code == 200:
                return
        except httpx.TransportError:
            time.sleep(0.1)
    raise ConfigError(f"the oracle service did not answer within {START_TIMEOUT_S:.0f} s")


def _target_and_poses(seed: int) -> tuple[int, list[dict[str, Any]]]:
    """A target with view points and 200 navigable poses in house ``seed``."""
    with Simulator(generate_house(seed)) as sim:
        grid = sim.grid
        component = grid.largest_component()
        target = next(
            inst.id
            for inst in sim.house.instances
            if any(grid.component_of(*p) == component for p in view_points(grid, inst.box))
        )
        rng = np.random.default_rng(seed)
        poses = []
        for _ in range(200):
            x, z = grid.sample_navigable_point(rng, component)
            yaw = float(rng.uniform(-math.pi, math.pi))
            poses.append({"position": [x, grid.floor_y, z], "yaw": yaw, "tilt": 0.0})
    return target, poses


async def _load(
    base: str,
    headers: dict[str, str],
    seed: int,
    target: int,
    poses: list[dict[str, Any]],
    questions: list[str],
    rounds: int,
    server_cpu: Callable[[], float],
) -> dict[str, float]:
    """Latencies of every timed request, the request rate and the server's CPU time per
    request, all counted from the moment every client has its session."""
    latencies: list[float] = []
    errors = 0

    async def client(number: int) -> None:
        nonlocal errors
        rng = np.random.default_rng([seed, number])
        async with aiohttp.ClientSession(
            base, headers=headers, connector=aiohttp.TCPConnector(limit=1), timeout=TIMEOUT
        ) as http:
            body = {"scene_id": procedural_scene_id(seed), "target_instance_id": target}
            sessions = []  # one per round: its three questions fit the paper's budget
            for _ in range(rounds):
                async with http.post("/v1/sessions", json=body) as created:
                    sessions.append((await created.json())["session_id"])
            await ready.wait()  # every session exists (the house built once) ...
            if number == 0:
                clock.append(time.perf_counter())  # ... before the clock starts
                cpu.append(server_cpu())
            for session in sessions:
                for step in range(4):
                    began = time.perf_counter()
                    if step < 3:
                        ask = {
                            "question": questions[int(rng.integers(len(questions)))],
                            "pose": poses[int(rng.integers(len(poses)))],
                        }
                        request = http.post(f"/v1/sessions/{session}/ask", json=ask)
                    else:
                        request = http.get(f"/v1/sessions/{session}")
                    async with request as reply:
                        await reply.read()
                    latencies.append((time.perf_counter() - began) * 1e3)
                    errors += reply.status != 200

    ready = asyncio.Barrier(CLIENTS)
    clock: list[float] = []
    cpu: list[float] = []
    await asyncio.gather(*(client(number) for number in range(CLIENTS)))
    seconds = time.perf_counter() - clock[0]
    return {
        "cpu_ms": (server_cpu() - cpu[0]) * 1e3 / len(latencies),
        "rate": len(latencies) / seconds,
        "p50": float(np.percentile(latencies, 50)),
        "p99": float(np.percentile(latencies, 99)),
        "errors": float(errors),
    }


def _sessions_on_distinct_scenes(base: str, headers: dict[str, str], scenes: int) -> None:
    """One session on each of ``scenes`` houses (the first instance that can be a target)."""
    with httpx.Client(base_url=base, headers=headers, timeout=120.0) as http:
        for seed in range(1, scenes + 1):
            for instance in range(1, 60):
                body = {"scene_id": procedural_scene_id(seed), "target_instance_id": instance}
                reply = http.post("/v1/sessions", json=body)
                if reply.status_code == 201:
                    break
                if reply.status_code == 429:
                    raise ConfigError(f"the service refused a house build: {reply.text}")


def _cpu_seconds(pid: int) -> float:
    """CPU time (user and system, every thread) the process has used so far: a figure that,
    unlike requests per second, hardly depends on what else the machine is running."""
    with open(f"/proc/{pid}/stat", encoding="ascii") as stat:
        fields = stat.read().rpartition(")")[2].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _rss_mb(pid: int) -> float:
    with open(f"/proc/{pid}/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    raise ConfigError(f"no resident memory reported for process {pid}")
