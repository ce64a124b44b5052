"""Loading the question classifier's artefact and labelling questions with it.

The artefact is JSON, one key a line: the format, versions, seed and training-data digest,
the labels, and the model packed as base85 of xz-compressed arrays (:func:`packed`): the
n-grams of the two TF-IDF feature sets (character 2-5-grams within word boundaries, then word
1-3-grams with house words read by role), how many training texts each occurs in (its idf),
and the linear model's weights, whole multiples of a step per label, with its biases. Plain
numbers rather than a pickle, so that a newer scikit-learn still reads it. Classifying needs
no scikit-learn: each feature set's n-gram splitting is scikit-learn's analyser for its
settings written out (:func:`analyser`; importing scikit-learn, which brings pandas and
scipy.stats, costs about 1.5 s in every process that answers a question), and the weighting and
the linear model are a few array operations: the same numbers as a vectoriser with the stored
n-grams and idf, without its per-call overhead of about a millisecond. Training fits
scikit-learn's vectorisers (:func:`vectoriser`) with the same settings.
"""

from __future__ import annotations

import base64
import json
import lzma
import math
import re
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from importlib.resources import files
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from vlln.errors import DataFormatError
from vlln.files import ReadCap, parse_json
from vlln.oracle.classifier.roles import with_roles
from vlln.oracle.topics import LABELS

if TYPE_CHECKING:
    from sklearn.feature_extraction.text import TfidfVectorizer

FORMAT = 4  # bump when the artefact's layout or features change; older files are then refused
ARTEFACT_NAME = "question_classifier.json"
RETRAIN = "rebuild it with `vlln oracle train-classifier`"
# The shipped artefact is under 1 MB; its arrays unpack to under 3 MB each.
_ARTEFACT_CAP = ReadCap("a question classifier", 16)
_UNPACKED_CAP = 64 << 20  # bytes of one unpacked array: what keeps an xz bomb out of memory
_WORDS = r"(?u)\b\w+\b"
# The feature sets (scikit-learn TfidfVectorizer settings), in the order they are joined.
FEATURE_SETS: dict[str, dict[str, Any]] = {
    "char": {"analyzer": "char_wb", "ngram_range": (2, 5)},
    "roles": {"analyzer": "word", "ngram_range": (1, 3), "token_pattern": _WORDS},
}
TFIDF_SETTINGS: dict[str, Any] = {"sublinear_tf": True, "norm": "l2"}
_WORD = re.compile(r"[a-z0-9]+")


QUESTION_MARK = "zqmark"  # the word the features see for a question mark (no real word)


def prepared(text: str) -> str:
    """The words of ``text``: lower-case letters and digits, one space between them (case,
    spacing and most punctuation say nothing about the intent)."""
    return " ".join(_WORD.findall(text.lower()))


def featured(text: str) -> str:
    """The text the features are read from: :func:`prepared`, and :data:`QUESTION_MARK` when
    ``text`` holds a question mark, which tells "Got it?" (did I find it) from "Got it."."""
    words = prepared(text)
    return f"{words} {QUESTION_MARK}" if "?" in text else words


def featured_by_role(text: str) -> str:
    """:func:`featured` with house words replaced by their role (:mod:`.roles`)."""
    return " ".join(with_roles(featured(text).split()))


# The text each feature set reads.
PREPROCESSORS: dict[str, Callable[[str], str]] = {
    "char": featured,
    "roles": featured_by_role,
}


def vectoriser(name: str, **extra: Any) -> TfidfVectorizer:
    """A TF-IDF vectoriser with the settings of feature set ``name``."""
    # Imported here: scikit-learn takes a second to import, which only classifying needs.
    from sklearn.feature_extraction.text import TfidfVectorizer

    settings = FEATURE_SETS[name]
    return TfidfVectorizer(**settings, **TFIDF_SETTINGS, preprocessor=PREPROCESSORS[name], **extra)


def analyser(name: str) -> Callable[[str], list[str]]:
    """The n-grams feature set ``name`` reads from a text, in the order and with the
    repetitions of scikit-learn's analyser of :func:`vectoriser` (a test holds them equal on
    every training question)."""
    settings = FEATURE_SETS[name]
    low, high = settings["ngram_range"]
    preprocess = PREPROCESSORS[name]
    if settings["analyzer"] == "char_wb":
        return lambda text: _word_bounded_chars(preprocess(text), low, high)
    tokens = re.compile(settings["token_pattern"]).findall
    return lambda text: _word_grams(tokens(preprocess(text)), low, high)


def _word_bounded_chars(text: str, low: int, high: int) -> list[str]:
    """Character n-grams inside each word padded with a space either side; a padded word no
    longer than n is one n-gram, and then the longer n-grams are skipped."""
    grams: list[str] = []
    for word in text.split():
        padded = f" {word} "
        for n in range(low, high + 1):
            if len(padded) <= n:
                grams.append(padded)
                break
            grams.extend(padded[i : i + n] for i in range(len(padded) - n + 1))
    return grams


def _word_grams(tokens: list[str], low: int, high: int) -> list[str]:
    """Every run of ``low`` to ``high`` consecutive tokens, joined by a space."""
    runs = ((i, n) for n in range(low, high + 1) for i in range(len(tokens) - n + 1))
    return [" ".join(tokens[i : i + n]) for i, n in runs]


def packaged_artefact_path() -> Path:
    """Where the shipped artefact lives (package data of :mod:`vlln.oracle`)."""
    return Path(str(files("vlln.oracle").joinpath("data", ARTEFACT_NAME)))


@dataclass(frozen=True)
class _FeatureSet:
    analyse: Callable[[str], list[str]]
    index: dict[str, int]  # n-gram -> column within this set
    idf: NDArray[np.float64]
    offset: int  # first column of this set in the joined features


@dataclass(frozen=True)
class QuestionClassifier:
    """Labels a question (``attribute:color``, ``route:step``, ...) by a linear model."""

    labels: tuple[str, ...]
    feature_sets: tuple[_FeatureSet, ...]
    weights: NDArray[np.float64]  # (features, labels)
    bias: NDArray[np.float64]  # (labels,)
    meta: dict[str, Any]  # format, versions, training-data digest, seed

    def scores(self, text: str) -> NDArray[np.float64]:
        """The linear model's score of every label (the highest is the prediction)."""
        columns: list[int] = []
        values: list[float] = []
        for part in self.feature_sets:
            counts = Counter(part.index[g] for g in part.analyse(text) if g in part.index)
            if not counts:
                continue
            cols = np.fromiter(counts, np.int64, len(counts))
            tf = 1.0 + np.log(np.fromiter(counts.values(), np.float64, len(counts)))
            weighted = tf * part.idf[cols]
            columns.extend((cols + part.offset).tolist())
            values.extend((weighted / math.sqrt(float(weighted @ weighted))).tolist())
        if not columns:
            return self.bias.copy()
        return np.asarray(values) @ self.weights[columns] + self.bias

    def predict(self, text: str) -> str:
        """The best label of ``text``."""
        return self.labels[int(np.argmax(self.scores(text)))]


@cache
def packaged_classifier() -> QuestionClassifier:
    """The shipped classifier, read once per process."""
    return load_classifier(packaged_artefact_path())


def load_classifier(path: Path) -> QuestionClassifier:
    """Read an artefact; raises :class:`DataFormatError` (one line, naming the fix) when it is
    missing, damaged or of another format."""
    try:
        data = _ARTEFACT_CAP.read(path)
    except FileNotFoundError as error:
        raise DataFormatError(f"the question classifier {path} is missing; {RETRAIN}") from error
    except OSError as error:
        raise DataFormatError(f"cannot read the question classifier {path}: {error}") from error
    return classifier_from_bytes(data, path)


def packed(value: str | NDArray[Any]) -> str:
    """Text or an array's bytes, xz-compressed (deterministically), in base85 (a JSON string)."""
    data = value.encode("utf-8") if isinstance(value, str) else value.tobytes()
    return base64.b85encode(lzma.compress(data, preset=9 | lzma.PRESET_EXTREME)).decode("ascii")


def unpacked(text: str) -> bytes:
    """The bytes :func:`packed` packed; more than 64 MiB of them is a ValueError."""
    decompressor = lzma.LZMADecompressor()
    data = decompressor.decompress(base64.b85decode(text), max_length=_UNPACKED_CAP + 1)
    if len(data) > _UNPACKED_CAP:
        raise ValueError(f"an array of more than {_UNPACKED_CAP >> 20} MiB")
    if not decompressor.eof:
        raise lzma.LZMAError("Compressed data ended before the end-of-stream marker was reached")
    return data


def artefact_text(artefact: dict[str, Any]) -> str:
    """The artefact as JSON, sorted keys, one a line (its few figures readable at a glance)."""
    lines = [f"{json.dumps(key)}: {json.dumps(artefact[key])}" for key in sorted(artefact)]
    return "{\n" + ",\n".join(lines) + "\n}\n"


def classifier_from_bytes(data: bytes, path: Path | str = "in memory") -> QuestionClassifier:
    """An artefact's classifier from its bytes (``path`` names it in errors)."""
    try:
        raw = parse_json(data)
    except DataFormatError as error:
        raise DataFormatError(
            f"the question classifier {path} is damaged ({error}); {RETRAIN}"
        ) from error
    if not isinstance(raw, dict) or raw.get("format") != FORMAT:
        found = raw.get("format") if isinstance(raw, dict) else None
        raise DataFormatError(
            f"the question classifier {path} has format {found!r}, this vlln reads format "
            f"{FORMAT}; {RETRAIN}"
        )
    try:
        return _from_json(raw)
    except (KeyError, TypeError, ValueError, lzma.LZMAError) as error:
        raise DataFormatError(
            f"the question classifier {path} is damaged ({type(error).__name__}: {error}); "
            f"{RETRAIN}"
        ) from error


def _from_json(raw: dict[str, Any]) -> QuestionClassifier:
    labels = tuple(raw["labels"])
    if set(labels) != set(LABELS):
        raise ValueError(f"its labels {labels} are not this vlln's {LABELS}")
    vocabulary = unpacked(raw["vocabulary"]).decode("utf-8").split("\n")
    in_documents = np.frombuffer(unpacked(raw["document_frequency"]), "<u4")
    # scikit-learn's smooth idf of an n-gram found in df of the n training texts.
    idf = np.log((1.0 + raw["documents"]) / (1.0 + in_documents)) + 1.0
    levels = np.frombuffer(unpacked(raw["weights"]), np.int8)
    weights = levels.reshape(-1, len(labels)) * np.asarray(raw["weight_steps"], np.float64)
    bias = np.asarray(raw["bias"], np.float64)
    sizes = [int(raw["features"][name]) for name in FEATURE_SETS]
    if not len(vocabulary) == len(idf) == weights.shape[0] == sum(sizes):
        raise ValueError(f"{sizes} features, {len(vocabulary)} n-grams, {len(idf)} idf weights")
    if bias.shape != (len(labels),):
        raise ValueError(f"{bias.shape[0]} biases for {len(labels)} labels")
    parts = []
    offset = 0
    for name, size in zip(FEATURE_SETS, sizes, strict=True):
        index = {gram: i for i, gram in enumerate(vocabulary[offset : offset + size])}
        parts.append(_FeatureSet(analyser(name), index, idf[offset : offset + size], offset))
        offset += size
    meta = {k: raw[k] for k in ("format", "vlln_version", "sklearn_version", "seed")}
    meta["training_digest"] = raw["training_digest"]
    return QuestionClassifier(labels, tuple(parts), np.ascontiguousarray(weights), bias, meta)
