"""The classifier's labelled question sets, in ``questions/``, by name.

It is trained on ``train`` (navigator questions), ``extra`` (questions written for training:
every topic, typos, chat spellings, word orders), ``v6`` ... ``v12``, ``v17``, ``v18`` (former
held-out sets, each measured and then trained on), ``written_*``, ``v13`` ... ``v16`` and
``v19`` ... ``v22`` (written for training by other writers) and ``generated`` (written from
templates by :mod:`oracle_training.generator`, reproducible from a seed); ``heldout`` is
written separately and frozen, only ever measured. The format:
:mod:`vlln.oracle.question_set`.
"""

from __future__ import annotations

from pathlib import Path

from vlln.errors import ConfigError
from vlln.oracle.question_set import LabelledQuestion, load_question_set

QUESTIONS = Path(__file__).resolve().parent / "questions"

# A held-out set stops being held out once the classifier is trained on it or tuned on its
# errors; each replacement is a new file, written without looking at the classifier.
_FILES = {
    "train": "questions_train.jsonl",
    "extra": "questions_extra.jsonl",
    "v6": "questions_heldout_v6.jsonl",
    "generated": "questions_generated.jsonl",
    "written_a": "questions_written_a.jsonl",
    "written_b": "questions_written_b.jsonl",
    "written_c": "questions_written_c.jsonl",
    "written_d": "questions_written_d.jsonl",
    "written_e": "questions_written_e.jsonl",
    "written_f": "questions_written_f.jsonl",
    "v7": "questions_v7.jsonl",
    "v8": "questions_v8.jsonl",
    "v9": "questions_v9.jsonl",
    "v10": "questions_v10.jsonl",
    "v11": "questions_v11.jsonl",
    "v12": "questions_v12.jsonl",
    "v13": "questions_v13.jsonl",
    "v14": "questions_v14.jsonl",
    "v15": "questions_v15.jsonl",
    "v16": "questions_v16.jsonl",
    "v17": "questions_v17.jsonl",
    "v18": "questions_v18.jsonl",
    "v19": "questions_v19.jsonl",
    "v20": "questions_v20.jsonl",
    "v21": "questions_v21.jsonl",
    "v22": "questions_v22.jsonl",
    "heldout": "questions_heldout_v23_v24.jsonl",
}
# written_*: questions written from the task definition alone, in human navigators' (a),
# vision-language agents' (b), short and non-native (c) and mid-dialog (d) styles, and (e)
# from the labelling guide (docs/oracle-classifier.md), weighted to short utterances, chatter
# and yes/no questions that read like another type, and (f) as mid-episode dialog by four
# kinds of navigator, narration included; v13 ... v16 from the guide, each by eight personas
# (people and model agents) the writer was given (v13-v15) or chose (v16); v19 ... v22 as
# contrasting pairs, two utterances that read almost alike but differ in type.
SETS = tuple(_FILES)
TRAINING_SETS = tuple(name for name in SETS if name != "heldout")


def question_set_path(name: str) -> Path:
    """Where the set ``name`` (one of :data:`SETS`) lives."""
    if name not in SETS:
        raise ConfigError(f"unknown question set {name!r}; choose one of {SETS}")
    return QUESTIONS / _FILES[name]


def load_named_set(name: str) -> list[LabelledQuestion]:
    """The set ``name`` (one of :data:`SETS`)."""
    return load_question_set(question_set_path(name))
