"""What a dataset build will cost, said before it starts (and asked about when it is large).

The figures are those of docs/evaluation.md and docs/benchmark.md, measured on the 2-core
development machine with `vlln bench data` and the 20-house build: about 10.7 s of one core per
trajectory tried (collection, filtering, rendering both cameras again, pixel goals, encoding),
about 4.7 MB of disk per trajectory tried (83 % are kept, 5.6 MB each: a JPEG of both cameras
per frame), and about 500 MB of memory (one house's simulator and the frames of one
trajectory)."""

from __future__ import annotations

from dataclasses import dataclass

from vlln.eval.cost import describe_duration

SECONDS_PER_TRAJECTORY = 10.7
MB_PER_TRAJECTORY = 4.7
PEAK_MEMORY_MB = 500
CONFIRM_ABOVE_S = 3600.0  # an interactive build longer than this asks first


@dataclass(frozen=True)
class BuildCost:
    trajectories: int
    seconds: float
    disk_mb: float

    @property
    def large(self) -> bool:
        return self.seconds > CONFIRM_ABOVE_S

    def line(self) -> str:
        disk = f"{self.disk_mb / 1000:.1f} GB" if self.disk_mb >= 1000 else f"{self.disk_mb:.0f} MB"
        return (
            f"estimate: {self.trajectories} trajectories to try, "
            f"{describe_duration(self.seconds)} on one core (~{SECONDS_PER_TRAJECTORY} s each; "
            f"--shard i/n runs n processes side by side), ~{disk} of disk, "
            f"~{PEAK_MEMORY_MB} MB of memory per process"
        )


def build_cost(houses: int, per_house: int) -> BuildCost:
    """The cost of trying ``per_house`` trajectories in each of ``houses`` houses (0 = every
    IIGN episode of a house, counted as 20, the default)."""
    trajectories = houses * (per_house or 20)
    return BuildCost(
        trajectories, trajectories * SECONDS_PER_TRAJECTORY, trajectories * MB_PER_TRAJECTORY
    )
