"""A disk cache of completions, so that repeating a request costs nothing.

Entries are keyed by a SHA-256 hash of the server, the model, the messages and the sampling
parameters, one JSON file each (``<folder>/<2 hex>/<hash>.json``), written atomically so that
parallel workers and killed runs never leave a half-written entry. An unreadable entry is a
miss: the request is made again and the entry rewritten.
"""

from __future__ import annotations

import hashlib
import json
import logging
from pathlib import Path
from typing import Any

from vlln.files import ReadCap, parse_json, write_text_atomic
from vlln.oracle.llm.protocol import Message

logger = logging.getLogger(__name__)

# An entry holds one reply of at most MAX_REPLY_BYTES (openai_client), escaped as JSON.
_ENTRY_CAP = ReadCap("a model-cache entry", 8)


def cache_key(base_url: str, model: str, messages: list[Message], params: dict[str, Any]) -> str:
    """The hash that names a request's entry; any change to what is asked changes it."""
    request = {
        "base_url": base_url,
        "model": model,
        "messages": [m.to_json() for m in messages],
        "params": params,
    }
    canonical = json.dumps(request, sort_keys=True, ensure_ascii=False, separators=(",", ":"))
    return hashlib.sha256(canonical.encode("utf-8")).hexdigest()


class ResponseCache:
    """Completion texts on disk, by :func:`cache_key`."""

    def __init__(self, folder: Path) -> None:
        self.folder = Path(folder)

    def _path(self, key: str) -> Path:
        return self.folder / key[:2] / f"{key}.json"

    def get(self, key: str) -> str | None:
        path = self._path(key)
        if not path.is_file():
            return None
        try:
            entry = parse_json(_ENTRY_CAP.read(path))
            text = entry["text"]
        except (OSError, ValueError, KeyError, TypeError) as error:
            logger.warning("ignoring unreadable cache entry %s (%s)", path, error)
            return None
        return text if isinstance(text, str) else None

    def put(self, key: str, text: str) -> None:
        write_text_atomic(self._path(key), json.dumps({"text": text}, ensure_ascii=False) + "\n")
