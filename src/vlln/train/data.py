"""The training export as model inputs: samples read from ``sft.jsonl``, batched with the
model's chat template, loss only on the assistant's tokens."""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from PIL import Image

from vlln.agents.local.encoding import ChatEncoder, ProcessedImage
from vlln.datagen.sft.records import SFT_FILE, SUMMARY_FILE, SftRecord
from vlln.errors import DataFormatError
from vlln.files import ReadCap, open_image, parse_json
from vlln.prompt import IMAGE_TAG, Turn

# export.json holds the settings, the houses and the counts: a few kB.
_SUMMARY_CAP = ReadCap("an export summary", 16)
# A sample is a few kB of text (its images are files apart), while sft.jsonl may hold hundreds
# of MB of them: it is read a line at a time, each to this cap.
SFT_LINE_CAP = ReadCap("a line of sft.jsonl", 1)


@dataclass(frozen=True)
class SftSample:
    """One conversation of the export; ``images`` are absolute paths in ``<image>`` order."""

    sample_id: str
    images: tuple[Path, ...]
    turns: tuple[Turn, ...]


@dataclass(frozen=True)
class ExportFacts:
    """What an export's ``export.json`` says a model trained on it will have seen."""

    history_frames: int
    houses: str  # the preset of the houses its trajectories were walked in


def export_facts(data_dir: Path) -> ExportFacts:
    """The history length and houses of a finished export (exports made before the preset
    was recorded were of small houses)."""
    path = data_dir / SUMMARY_FILE
    try:
        document = parse_json(_SUMMARY_CAP.read(path))
        history = int(document["settings"]["history_frames"])
        return ExportFacts(history, str(document.get("preset", "small")))
    except (OSError, ValueError, KeyError, TypeError) as error:
        raise DataFormatError(
            f"{path} is not an export summary ({error}); re-run the export"
        ) from None


def read_export(data_dir: Path) -> list[SftSample]:
    """Every sample of a complete export, checked: known roles, one image per tag, files
    present, at least one assistant turn."""
    if not (data_dir / SUMMARY_FILE).is_file():
        raise DataFormatError(
            f"{data_dir} is not a finished training export (no {SUMMARY_FILE}); "
            "write one with: vlln data export-sft DATASET --out DIR"
        )
    samples: list[SftSample] = []
    limit = SFT_LINE_CAP.limit()
    with (data_dir / SFT_FILE).open("rb") as lines:
        for number, line in enumerate(iter(lambda: lines.readline(limit + 1), b""), 1):
            where = f"{data_dir / SFT_FILE}, line {number}"
            if len(line) > limit:
                raise DataFormatError(
                    f"{where} holds more than {limit >> 20} MiB, the cap on {SFT_LINE_CAP.what}; "
                    "give the right file"
                )
            try:
                samples.append(_sample(SftRecord.from_line(line), data_dir))
            except (ValueError, KeyError, TypeError) as error:
                raise DataFormatError(f"{where}: {error}") from error
    if not samples:
        raise DataFormatError(f"{data_dir / SFT_FILE} has no samples; export more trajectories")
    return samples


def _sample(record: SftRecord, data_dir: Path) -> SftSample:
    turns = record.turns
    if not any(turn.role == "gpt" for turn in turns):
        raise ValueError("the conversation has no 'gpt' turn to learn")
    images = tuple(data_dir / path for path in record.images)
    tags = sum(turn.text.count(IMAGE_TAG) for turn in turns)
    if tags != len(images):
        raise ValueError(f"{tags} <image> tags but {len(images)} images")
    missing = [str(path) for path in images if not path.is_file()]
    if missing:
        raise ValueError(f"missing image {missing[0]}; re-run the export")
    return SftSample(record.sample_id, images, turns)


class SftCollator:
    """Turns samples into a padded batch with labels (picklable for data-loader workers).

    A frame is shown by many samples (each prompt carries its history), so each image is
    decoded and processed once and kept, least recently used first out, up to
    ``cache_bytes`` of patches per process."""

    def __init__(self, encoder: ChatEncoder, cache_bytes: int = 512 * 2**20) -> None:
        self.encoder = encoder
        self.cache_bytes = cache_bytes
        self._cache: OrderedDict[Path, ProcessedImage] = OrderedDict()
        self._cached_bytes = 0

    def __call__(self, samples: list[SftSample]) -> dict[str, Any]:
        texts = [
            self.encoder.render(sample.turns, add_generation_prompt=False) for sample in samples
        ]
        images = self._processed([sample.images for sample in samples])
        batch = self.encoder.encode_processed(texts, images, padding_side="right")
        batch["labels"] = self.encoder.assistant_labels(batch["input_ids"], batch["attention_mask"])
        return batch

    def _processed(self, groups: list[tuple[Path, ...]]) -> list[list[ProcessedImage]]:
        missing = list(dict.fromkeys(path for group in groups for path in group))
        missing = [path for path in missing if path not in self._cache]
        processed = self.encoder.process_images([load_rgb(path) for path in missing])
        fresh = dict(zip(missing, processed, strict=True))
        out = [[fresh.get(path) or self._cache[path] for path in group] for group in groups]
        for path, image in fresh.items():
            self._remember(path, image)
        for group in groups:
            for path in group:
                if path in self._cache:
                    self._cache.move_to_end(path)
        return out

    def _remember(self, path: Path, image: ProcessedImage) -> None:
        self._cache[path] = image
        self._cached_bytes += image.nbytes
        while self._cached_bytes > self.cache_bytes and self._cache:
            _, dropped = self._cache.popitem(last=False)
            self._cached_bytes -= dropped.nbytes


def load_rgb(path: Path) -> Image.Image:
    """An exported image as the model is given it (RGB)."""
    with open_image(path, path) as image:
        return image.convert("RGB")
