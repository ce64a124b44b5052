"""Fitting the question classifier from the labelled question sets.

Training reads the training sets (:data:`~oracle_training.question_sets.TRAINING_SETS`), less any
question that reads the same as one of ``heldout`` (which is only measured), adds to each
question :data:`TYPO_COPIES` copies with random one-letter slips (a letter dropped, doubled, swapped
with its neighbour or replaced), so that the character n-grams learn what typing errors look
like, and fits a linear support-vector classifier on TF-IDF features of character 2-5-grams
and of word 1-3-grams with house words read by role. The artefact keeps each label's weights
as whole multiples of a step (its largest weight over :data:`WEIGHT_LEVELS`) and leaves out
the n-grams whose weights all round to zero (:mod:`vlln.oracle.classifier.model` reads it).
Everything random draws from ``seed`` and the artefact's compression is deterministic: the
same data and seed give the same bytes.
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import scipy.sparse
import sklearn
from sklearn.svm import LinearSVC

import vlln
from oracle_training.question_sets import TRAINING_SETS, load_named_set, question_set_path
from vlln.errors import DataFormatError
from vlln.oracle.classifier.model import (
    FEATURE_SETS,
    FORMAT,
    artefact_text,
    packed,
    prepared,
    vectoriser,
)
from vlln.oracle.question_set import LabelledQuestion
from vlln.oracle.topics import LABELS

TYPO_COPIES = 2  # noisy copies of each training question
REGULARISATION = 1.0  # LinearSVC's C
DIGITS = 5  # significant digits kept of each bias
# Each label's weights are stored as whole multiples of its largest weight / WEIGHT_LEVELS
# (-23 ... 23): leaving one writer out scores as with the full weights (15 levels lost about
# a question in a thousand, 31 made the artefact a tenth larger for nothing).
WEIGHT_LEVELS = 23
MIN_COUNT = 2  # training texts an n-gram must occur in to become a feature
_LETTERS = "abcdefghijklmnopqrstuvwxyz"


def training_digest() -> str:
    """SHA-256 of the question files (the held-out one decides what is left out), as
    stored in the artefact."""
    digest = hashlib.sha256()
    for name in (*TRAINING_SETS, "heldout"):
        digest.update(question_set_path(name).read_bytes())
    return digest.hexdigest()


def training_sets() -> dict[str, list[LabelledQuestion]]:
    """Each training set's questions, less those that read the same as a held-out
    one (so that the held-out set stays unseen); raises when one lacks the topic training
    needs."""
    heldout = {prepared(q.question) for q in load_named_set("heldout")}
    sets = {}
    for name in TRAINING_SETS:
        questions = load_named_set(name)
        questions = [q for q in questions if prepared(q.question) not in heldout]
        unlabelled = next((q for q in questions if q.label is None), None)
        if unlabelled is not None:
            raise DataFormatError(
                f"training question {unlabelled.question!r} of set {name!r} has no 'topic'; "
                "give every attribute and other question of the training sets a topic"
            )
        sets[name] = questions
    return sets


def training_questions() -> list[LabelledQuestion]:
    """Every question of :func:`training_sets`, one list."""
    return [q for questions in training_sets().values() for q in questions]


def with_typo(text: str, rng: np.random.Generator) -> str:
    """``text`` with one letter of one word of four or more letters dropped, doubled, swapped
    with the next one or replaced by a random letter."""
    words = text.split(" ")
    long = [i for i, word in enumerate(words) if len(word) >= 4]
    if not long:
        return text
    i = long[int(rng.integers(len(long)))]
    word = words[i]
    k = int(rng.integers(1, len(word) - 1))
    slip = int(rng.integers(4))
    if slip == 0:
        word = word[:k] + word[k + 1 :]
    elif slip == 1:
        word = word[:k] + word[k] + word[k:]
    elif slip == 2:
        word = word[: k - 1] + word[k] + word[k - 1] + word[k + 1 :]
    else:
        word = word[:k] + _LETTERS[int(rng.integers(26))] + word[k + 1 :]
    words[i] = word
    return " ".join(words)


def training_texts(
    questions: Sequence[LabelledQuestion], seed: int = 0
) -> tuple[list[str], list[str]]:
    """The texts the model is fitted to (each question and its typo copies) and their labels;
    raises when a question has no topic."""
    rng = np.random.default_rng(seed)
    texts: list[str] = []
    labels: list[str] = []
    for question in questions:
        label = question.label
        if label is None:
            raise DataFormatError(f"question {question.question!r} has no topic to train on")
        texts.append(question.question)
        labels.append(label)
        for _ in range(TYPO_COPIES):
            texts.append(with_typo(with_typo(question.question, rng), rng))
            labels.append(label)
    return texts, labels


def train_artefact(questions: Sequence[LabelledQuestion], seed: int = 0, digest: str = "") -> bytes:
    """The artefact bytes of a classifier fitted to ``questions`` (all labelled)."""
    texts, labels = training_texts(questions, seed)
    vectorisers = {name: vectoriser(name, min_df=MIN_COUNT) for name in FEATURE_SETS}
    matrices = [v.fit_transform(texts) for v in vectorisers.values()]
    features = scipy.sparse.hstack(matrices).tocsr()
    model = linear_model(seed)
    model.fit(features, labels)
    order = [list(model.classes_).index(label) for label in LABELS if label in model.classes_]
    coef = model.coef_[order].T  # (features, labels)
    steps = np.abs(coef).max(axis=0) / WEIGHT_LEVELS
    steps[steps == 0] = 1.0
    levels = np.rint(coef / steps).astype(np.int8)
    kept = levels.any(axis=1)  # n-grams with a weight that does not round to zero
    vocabulary = [g for v in vectorisers.values() for g in v.get_feature_names_out().tolist()]
    in_documents = np.diff(features.tocsc().indptr)  # documents each n-gram occurs in
    sizes = np.cumsum([0, *(m.shape[1] for m in matrices)])
    artefact: dict[str, Any] = {
        "format": FORMAT,
        "vlln_version": vlln.__version__,
        "sklearn_version": sklearn.__version__,
        "seed": seed,
        "training_digest": digest,
        "labels": [str(model.classes_[i]) for i in order],
        "documents": len(texts),
        "features": {
            name: int(kept[sizes[i] : sizes[i + 1]].sum()) for i, name in enumerate(vectorisers)
        },
        "vocabulary": packed("\n".join(g for g, k in zip(vocabulary, kept, strict=True) if k)),
        "document_frequency": packed(in_documents[kept].astype("<u4")),
        "weight_steps": _rounded(steps),
        "weights": packed(levels[kept]),
        "bias": _rounded(model.intercept_[order]),
    }
    return artefact_text(artefact).encode("utf-8")


def linear_model(seed: int) -> LinearSVC:
    """The unfitted linear classifier."""
    return LinearSVC(C=REGULARISATION, random_state=seed)


def train_all_sets(seed: int) -> bytes:
    """The artefact of the training sets."""
    return train_artefact(training_questions(), seed, training_digest())


def write_artefact(data: bytes, path: Path) -> None:
    """Write the artefact whole: to a neighbour file first, then renamed over ``path``."""
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_name(path.name + ".partial")
    partial.write_bytes(data)
    partial.replace(path)


def _rounded(values: np.ndarray) -> list[float]:
    return [float(f"{x:.{DIGITS}g}") for x in np.asarray(values, np.float64).tolist()]
