"""A digest of what a dataset says (actions, poses, goals, dialogs, settings), not of how its
files are encoded: JPEG and parquet bytes depend on library versions, the content does not."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np

from vlln.datagen.reader import HouseDataset, house_folders

_SETTINGS_KEPT_OUT = ("vlln_version", "catalogue")  # change with releases, not with the data


def content_digest(root: Path) -> str:
    """SHA-256 over the build settings, every house's info, episode rows and frame columns
    (floats rounded to 1e-6 m)."""
    digest = hashlib.sha256()
    settings = json.loads((root / "build.json").read_text(encoding="utf-8"))
    for key in _SETTINGS_KEPT_OUT:
        settings.pop(key)
    digest.update(json.dumps(settings, sort_keys=True).encode())
    for folder in house_folders(root):
        data = HouseDataset(folder)
        counts = {k: data.info[k] for k in ("attempted", "rejections", "total_frames")}
        digest.update(json.dumps(counts, sort_keys=True).encode())
        for row in data.episodes:
            digest.update(json.dumps(row, sort_keys=True).encode())
            for name, column in sorted(data.frames(int(row["episode_index"])).items()):
                digest.update(name.encode())
                values = np.round(column, 6) + 0.0 if column.dtype.kind == "f" else column
                digest.update(np.ascontiguousarray(values).tobytes())
    return digest.hexdigest()
