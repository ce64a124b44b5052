"""Training questions written from templates, reproducible from a seed.

Each label has templates with slots for an object, a second object, a room, a colour and a
material; a question is a template filled from the vocabularies below, then dressed in one of
the ways navigators write: plainly, in chat spellings, with a sentence of context first, in a
language-model prompt's frame ("Question: ..."), with a greeting or a thank-you. Rewrite
``questions/questions_generated.jsonl`` with ``python -m oracle_training.generator [--seed 0]``
from the repository root (then retrain with ``vlln oracle train-classifier`` and commit both);
the same seed gives the same file.
"""

from __future__ import annotations

import argparse
import json
import re

import numpy as np

from oracle_training.question_sets import question_set_path
from oracle_training.templates import CONTEXTS, SMALL_TALK, TEMPLATES
from vlln.oracle.topics import parse_label
from vlln.tasks.oracle_protocol import QuestionType

PER_LABEL = 60  # questions drawn per label beyond one per template (duplicates are dropped)
OBJECTS = (
    "sofa", "chair", "table", "bed", "lamp", "tv", "television", "fridge", "toilet", "sink",
    "cabinet", "shelf", "bookshelf", "desk", "mirror", "plant", "rug", "clock", "vase",
    "cushion", "pillow", "towel", "oven", "microwave", "bathtub", "picture", "painting",
    "stool", "wardrobe", "dresser", "curtain", "washing machine", "coffee table", "armchair",
    "nightstand", "bench", "piano", "radiator", "trash can", "laptop", "kettle", "stove",
)  # fmt: skip
ROOMS = (
    "kitchen", "bedroom", "bathroom", "living room", "hallway", "corridor", "dining room",
    "study", "office", "laundry room", "garage", "toilet", "gym", "storage room", "lounge",
)  # fmt: skip
COLOURS = (
    "red", "blue", "green", "white", "black", "grey", "gray", "brown", "beige", "yellow",
    "orange", "pink", "purple", "dark blue", "light grey", "cream",
)  # fmt: skip
MATERIALS = (
    "wood",
    "wooden",
    "metal",
    "glass",
    "plastic",
    "leather",
    "fabric",
    "ceramic",
    "marble",
)
# Chat spellings: whole words replaced where the writer is in a hurry.
_CHAT = {
    "you": "u", "are": "r", "please": "plz", "what's": "whats", "to": "2", "the": "da",
    "i'm": "im", "don't": "dont", "going": "goin",
    "right": "rite", "thanks": "thx", "okay": "ok", "because": "cuz", "know": "kno",
    "should": "shud", "which": "wich", "where": "wher", "there": "thr", "see": "c",
}  # fmt: skip
_FRAMES = (
    "Question: {q}", "Q: {q}", "USER: {q}", "Navigator: {q}", "Agent question: {q}",
    "Quick question: {q}", "Hey, {q}", "hi! {q}", "Sorry, one more thing. {q}", "{q} Thanks!",
    "{q} thx", "{q} please", "Oracle, {q}", "ok so {q}", "{q} lol", "Hmm. {q}", "{q} ??",
    "Question for the oracle: {q}", "Please answer: {q}", "Um, {q}",
)  # fmt: skip
_SLOTS = re.compile(r"\{(obj|obj2|room|color|material)\}")


def _pick(rng: np.random.Generator, values: tuple[str, ...]) -> str:
    return values[int(rng.integers(len(values)))]


def _filled(template: str, rng: np.random.Generator) -> str:
    objects = list(OBJECTS)
    first = _pick(rng, tuple(objects))
    objects.remove(first)
    values = {
        "obj": first,
        "obj2": _pick(rng, tuple(objects)),
        "room": _pick(rng, ROOMS),
        "color": _pick(rng, COLOURS),
        "material": _pick(rng, MATERIALS),
    }
    return _SLOTS.sub(lambda m: values[m.group(1)], template)


def _chat(text: str, rng: np.random.Generator) -> str:
    words = text.lower().rstrip("?.!").split(" ")
    out = [_CHAT.get(w, w) if rng.random() < 0.7 else w for w in words]
    return " ".join(out) + ("" if rng.random() < 0.5 else "?")


def _dressed(question: str, label: str, rng: np.random.Generator) -> str:
    """``question`` as some navigator might write it."""
    style = int(rng.integers(6))
    if style == 1:
        return _chat(question, rng)
    if style == 2:
        return _pick(rng, _FRAMES).format(q=question)
    if style == 3 and parse_label(label)[0] != QuestionType.OTHER:
        return f"{_filled(_pick(rng, CONTEXTS), rng)} {question}"
    if style == 4:
        return question.lower().rstrip("?")
    return question


def generated_questions(seed: int = 0) -> list[dict[str, str]]:
    """The generated question rows (as in the JSON Lines file), duplicates dropped."""
    rng = np.random.default_rng(seed)
    rows: dict[str, dict[str, str]] = {}
    for label, templates in TEMPLATES.items():
        pool = templates + (SMALL_TALK if label == "other:unknown" else ())
        for _ in range(PER_LABEL + len(pool)):
            question = _dressed(_filled(_pick(rng, pool), rng), label, rng)
            question_type, topic = parse_label(label)
            row = {"question": question, "type": question_type.value}
            if topic is not None:
                key = "route_kind" if question_type == QuestionType.ROUTE else "topic"
                row[key] = topic.value
            rows.setdefault(" ".join(question.lower().split()), row)
    return list(rows.values())


def generated_jsonl(seed: int = 0) -> str:
    """The text of ``questions_generated.jsonl`` for ``seed``."""
    return "".join(json.dumps(row, ensure_ascii=False) + "\n" for row in generated_questions(seed))


def main() -> None:
    parser = argparse.ArgumentParser(description="Rewrite the generated training questions.")
    parser.add_argument("--seed", type=int, default=0, help="seed of the draws (default 0)")
    path = question_set_path("generated")
    path.write_text(generated_jsonl(parser.parse_args().seed), encoding="utf-8")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
