"""The oracles a session can be paired with, made fresh for each episode."""

from __future__ import annotations

from vlln.oracle.settings import OracleBackend, OracleSettings
from vlln.tasks.oracle_protocol import Oracle
from vlln.web.config import OracleKind, WebConfig
from vlln.web.human_oracle import AnswerBoard, HumanOracle
from vlln.web.session import OracleFactory


def oracle_factory(config: WebConfig) -> OracleFactory:
    """Makes a session's oracle: the rule oracle, the helpful oracle, the language-model oracle
    (when the server was given a model) or a person on the oracle page, each seeded per
    episode. The machine oracles are those of ``vlln eval`` (:class:`OracleSettings`),
    answering every question type."""
    rules = OracleSettings()
    helpful = OracleSettings(OracleBackend.HELPFUL)
    llm = None if config.llm is None else OracleSettings(OracleBackend.LLM, config.llm)

    def make(kind: OracleKind, seed: int, board: AnswerBoard) -> Oracle:
        if kind == OracleKind.HUMAN:
            return HumanOracle(board, config.answer_time_limit_s, seed)
        if kind == OracleKind.LLM and llm is not None:
            return llm.make(seed)
        if kind == OracleKind.HELPFUL:
            return helpful.make(seed)
        return rules.make(seed)

    return make
