"""`vlln bench oracle`: how long the offline oracle takes to answer, overall and per type.

Questions are drawn from the held-out set of the repository's ``oracle_training/`` (so the
mix of types is a navigator's, not ours), asked from random agent poses in a generated house
about randomly chosen targets.
Only :meth:`RuleOracle.answer` is timed: the view each question comes with is rendered
before the clock starts, and :meth:`RuleOracle.start` (which builds the episode's distance
field once) is reported on its own as ``oracle_start_ms``.
"""

from __future__ import annotations

import math
import time

import numpy as np

from vlln.bench.figures import Figure, emit, median_seconds
from vlln.bench.settings import OracleBench
from vlln.errors import ConfigError
from vlln.extras import SERVICE_BENCH_PACKAGES, require_extra
from vlln.oracle.classify import analyse_question
from vlln.oracle.question_set import heldout_texts
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import AgentState
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.tasks.oracle_protocol import EpisodeContext, Question, QuestionType
from vlln.world.generator import generate_house
from vlln.world.model import ObjectInstance

TARGETS = 4  # episodes (targets) the questions are spread over
QUESTIONS_PER_POSE = 4  # questions asked from each rendered pose


def run_oracle_benchmark(settings: OracleBench) -> list[Figure]:
    """Measure and print the oracle's answer latency over ``settings.questions`` questions and,
    when ``settings.service_scenes`` > 0, the HTTP service under load
    (:mod:`vlln.bench.service`, which needs the serve extra)."""
    seed, questions, as_json = settings.seed, settings.questions, settings.as_json
    if settings.service_scenes > 0:  # refused before the first figure, not after
        require_extra("serve", "vlln bench oracle (its service figures)", SERVICE_BENCH_PACKAGES)
    figures: list[Figure] = []

    def record(metric: str, value: float, unit: str) -> None:
        figure = Figure(metric, value, unit)
        figures.append(figure)
        emit(figure, as_json)

    texts = heldout_texts("vlln bench oracle")
    record("classify_us", _classify_us(texts), "us")
    rng = np.random.default_rng(seed)
    oracle = RuleOracle(seed)
    latencies: dict[str, list[float]] = {}
    start_ms: list[float] = []
    with Simulator(generate_house(seed)) as sim:
        targets = _targets(sim, rng)
        per_target = math.ceil(questions / len(targets))
        for number, (target, points) in enumerate(targets):
            context = EpisodeContext(sim, target, tuple(points))
            began = time.perf_counter()
            oracle.start(context)
            start_ms.append((time.perf_counter() - began) * 1e3)
            count = min(per_target, questions - number * per_target)
            for group, milliseconds in _answer_latencies(sim, oracle, texts, count, rng):
                latencies.setdefault(group, []).append(milliseconds)
    every = [ms for group in latencies.values() for ms in group]
    record("answer_p50_ms", float(np.percentile(every, 50)), "ms")
    record("answer_p99_ms", float(np.percentile(every, 99)), "ms")
    for group in sorted(latencies):
        record(f"{group}_p50_ms", float(np.percentile(latencies[group], 50)), "ms")
        record(f"{group}_p99_ms", float(np.percentile(latencies[group], 99)), "ms")
    record("oracle_start_ms", float(np.median(start_ms)), "ms")
    if settings.service_scenes > 0:
        from vlln.bench.service import run_service_benchmark

        run_service_benchmark(record, seed, settings.service_scenes)
    return figures


def _classify_us(texts: list[str]) -> float:
    """Mean time to analyse one question, after a first pass has loaded the classifier."""
    for text in texts:
        analyse_question(text)

    def every() -> None:
        for text in texts:
            analyse_question(text)

    return median_seconds(every, repeats=5) / len(texts) * 1e6


def _targets(
    sim: Simulator, rng: np.random.Generator
) -> list[tuple[ObjectInstance, list[tuple[float, float]]]]:
    """Random objects with view points in the house's main navigable area."""
    component = sim.grid.largest_component()
    chosen = []
    for index in rng.permutation(len(sim.house.instances)).tolist():
        inst = sim.house.instances[index]
        points = [
            p for p in view_points(sim.grid, inst.box) if sim.grid.component_of(*p) == component
        ]
        if points:
            chosen.append((inst, points))
        if len(chosen) == TARGETS:
            break
    if not chosen:
        raise ConfigError(f"house {sim.house.name} has no reachable object to ask about")
    return chosen


def _answer_latencies(
    sim: Simulator, oracle: RuleOracle, texts: list[str], count: int, rng: np.random.Generator
) -> list[tuple[str, float]]:
    """(question group, milliseconds) for ``count`` questions asked from random poses."""
    component = sim.grid.largest_component()
    timed: list[tuple[str, float]] = []
    while len(timed) < count:
        x, z = sim.grid.sample_navigable_point(rng, component)
        state = AgentState((x, sim.grid.floor_y, z), float(rng.uniform(-math.pi, math.pi)), 0.0)
        frame = sim.render(state)
        for index in rng.integers(len(texts), size=min(QUESTIONS_PER_POSE, count - len(timed))):
            text = texts[int(index)]
            question = Question(text, state, frame)
            began = time.perf_counter()
            oracle.answer(question)
            timed.append((_group(text), (time.perf_counter() - began) * 1e3))
    return timed


def _group(text: str) -> str:
    """The answer path a question takes: its type, and for route questions its granularity."""
    analysis = analyse_question(text)
    if analysis.question_type == QuestionType.ROUTE and analysis.route_kind is not None:
        return f"route_{analysis.route_kind.value}"
    return analysis.question_type.value
