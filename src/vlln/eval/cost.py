"""What an evaluation will cost, said before it starts.

The figures are the README's, measured on the 2-core development machine: the frontier
agent with dialog plays an episode line in about 1.5 s on one core (`vlln bench eval`), a
line takes about 3 kB, and a run peaks at about 800 MB (one house's simulator, the agent's
map, the oracle). Other agents differ; the estimate says which basis it uses.
"""

from __future__ import annotations

SECONDS_PER_LINE = 1.5
BYTES_PER_LINE = 3_000
PEAK_MEMORY_MB = 800


def describe_duration(seconds: float) -> str:
    """``"about 40 s"``, ``"about 12 min"``, ``"about 3.5 h"``."""
    if seconds < 90:
        return f"about {seconds:.0f} s"
    if seconds < 5400:
        return f"about {seconds / 60:.0f} min"
    return f"about {seconds / 3600:.1f} h"


def eval_cost_line(planned: int, done: int) -> str:
    """One line: what is left to play and what it costs in time, disk and memory."""
    left = planned - done
    seconds = left * SECONDS_PER_LINE
    megabytes = planned * BYTES_PER_LINE / 1e6
    return (
        f"plan: {planned} episode lines, {done} already done; {left} to play, "
        f"{describe_duration(seconds)} on one core at ~{SECONDS_PER_LINE} s a line (frontier "
        f"agent with dialog), ~{max(megabytes, 0.1):.1f} MB of results, "
        f"~{PEAK_MEMORY_MB} MB of memory at peak"
    )
