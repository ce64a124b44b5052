"""What an evaluation will cost, said before it starts.

The figures are those of docs/evaluation.md and docs/benchmark.md, measured on the 2-core
development machine, per agent and house preset: seconds per episode line on one core (`vlln
bench eval`, `vlln bench fidelity`), about 3 kB of results a line, and the run's peak memory.
Agents without a measured figure (model agents, whose time is the model server's, and agents of
your own) get no time estimate; the line says which basis it uses."""

from __future__ import annotations

SECONDS_PER_LINE: dict[tuple[str, str], float] = {
    ("frontier", "small"): 1.5,
    ("expert", "small"): 0.4,
    ("random", "small"): 2.5,
    ("frontier", "mp3d"): 6.0,
    ("expert", "mp3d"): 1.0,
    ("random", "mp3d"): 3.5,
}
BYTES_PER_LINE = 3_000
PEAK_MEMORY_MB = {"small": 700, "mp3d": 900}


def describe_duration(seconds: float) -> str:
    """``"about 40 s"``, ``"about 12 min"``, ``"about 3.5 h"``."""
    if seconds < 90:
        return f"about {seconds:.0f} s"
    if seconds < 5400:
        return f"about {seconds / 60:.0f} min"
    return f"about {seconds / 3600:.1f} h"


def eval_cost_line(planned: int, done: int, agent: str = "frontier", preset: str = "small") -> str:
    """One line: what is left to play and what it costs in time, disk and memory."""
    left = planned - done
    megabytes = planned * BYTES_PER_LINE / 1e6
    per_line = SECONDS_PER_LINE.get((agent, preset))
    if per_line is None:
        time = f"time not estimated for agent {agent}"
    else:
        time = (
            f"{describe_duration(left * per_line)} on one core at ~{per_line} s a line "
            f"({agent} agent, {preset} houses)"
        )
    return (
        f"plan: {planned} episode lines, {done} already done; {left} to play, {time}, "
        f"~{max(megabytes, 0.1):.1f} MB of results, "
        f"~{PEAK_MEMORY_MB.get(preset, max(PEAK_MEMORY_MB.values()))} MB of memory at peak"
    )
