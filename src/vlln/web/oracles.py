"""The oracles a session can be paired with, made fresh for each episode."""

from __future__ import annotations

import numpy as np

from vlln.oracle.llm.openai_client import OpenAIChatClient
from vlln.oracle.llm_oracle import LLMOracle
from vlln.oracle.rule_oracle import RuleOracle
from vlln.tasks.oracle_protocol import Oracle
from vlln.web.config import OracleKind, WebConfig
from vlln.web.human_oracle import AnswerBoard, HumanOracle
from vlln.web.session import OracleFactory


def oracle_factory(config: WebConfig) -> OracleFactory:
    """Makes a session's oracle: the rule oracle, the language-model oracle (when the server
    was given a model) or a person on the oracle page, each seeded per episode."""

    def make(kind: OracleKind, seed: int, board: AnswerBoard) -> Oracle:
        if kind == OracleKind.HUMAN:
            return HumanOracle(board, config.answer_time_limit_s, seed)
        if kind == OracleKind.LLM and config.llm is not None:
            client = OpenAIChatClient(config.llm, rng=np.random.default_rng(seed))
            return LLMOracle(client, seed)
        return RuleOracle(seed)

    return make
