"""The exception tree of vlln.

Every error a user can cause derives from :class:`VllnError` and says what is wrong and how to
fix it, so command-line entry points can print the message instead of a traceback::

    VllnError
    ├── ConfigError                 a setting or argument has an invalid value
    │   ├── UnknownCategoryError    an object category the catalogue does not have
    │   └── HouseParametersError    house-generator parameters that cannot be satisfied
    ├── DataFormatError             a file does not follow the expected format
    ├── WriteError                  a file cannot be written (a full disk, a read-only folder)
    ├── RendererUnavailableError    no headless OpenGL (EGL) context could be created
    ├── ServerDownError             a model or oracle server failed too many requests in a row
    └── NavigationError             a point or goal is off the navigable area or unreachable
        └── EpisodeRefusedError     an episode that cannot be played honestly in its scene
"""

from __future__ import annotations


class VllnError(Exception):
    """Base class of all errors raised on purpose by vlln."""


class ConfigError(VllnError, ValueError):
    """A setting or argument has an invalid value."""


class UnknownCategoryError(ConfigError, KeyError):
    """An object category that the catalogue does not know."""

    def __str__(self) -> str:  # KeyError would otherwise quote the message
        return str(self.args[0]) if self.args else ""


class HouseParametersError(ConfigError):
    """House-generator parameters that no house can satisfy."""


class DataFormatError(VllnError, ValueError):
    """A file or record does not follow the expected format."""


class WriteError(VllnError, OSError):
    """A file cannot be written: the disk is full, the folder read-only or not ours. What was
    written before stays, so the same command resumes once the cause is fixed."""


class RendererUnavailableError(VllnError, RuntimeError):
    """No headless OpenGL context could be created."""


class ServerDownError(VllnError, RuntimeError):
    """A model or oracle server failed its client's limit of requests in a row: a run stops
    (keeping its finished episodes) rather than play on against a server that is down."""


class NavigationError(VllnError, ValueError):
    """A point or goal set is off the navigable area or cannot be reached."""


class EpisodeRefusedError(NavigationError):
    """An episode whose start or goals cannot be reached on their own storeys of its scene: it
    is not played (a runner records the refusal and goes on), never played on another storey."""

    def __init__(self, episode_id: str, scene_id: str, reason: str) -> None:
        super().__init__(f"episode {episode_id} in {scene_id} is refused: {reason}")
        self.episode_id = episode_id
        self.scene_id = scene_id
        self.reason = reason
