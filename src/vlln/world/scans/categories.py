"""What a scan's annotation is: an object, the house's shell, a flight of stairs, or nothing.

Matterport3D's ``.house`` names each category twice (its ``C`` records): the raw word the
annotators typed (``category_mapping.tsv``'s ``raw_category``: ``steps``, ``kitchen cabinet``,
``remove``...) and its mpcat40 group, index and name (``metadata/mpcat40.tsv``: 0 ``void``,
1 ``wall`` ... 40 ``misc``, 41 ``unlabeled``). The group decides what an annotation is where
the record gives one from that table; where it does not (HM3D, which has raw words only, or a
record whose group is not the table's), the raw word decides.

Void annotations are dropped: no instance, so no episode and no scene-summary entry, and their
triangles are the shell's like any unannotated surface. They are mpcat40 ``void`` (raw
``remove``, ``delete``, ``remove / behind``: annotators' marks for surfaces to ignore, such as
reflections and people) and ``unlabeled``, objects of no category (``-1`` in an ``O`` record),
and the raw words ``remove``, ``delete``, ``void``, ``unlabeled`` and ``unknown`` (``unknown``
is mpcat40 ``misc`` in Matterport's table, yet it names nothing one could search for).
"""

from __future__ import annotations

# metadata/mpcat40.tsv of niessner/Matterport, by index.
MPCAT40 = (
    "void", "wall", "floor", "chair", "door", "table", "picture", "cabinet", "cushion",
    "window", "sofa", "bed", "curtain", "chest_of_drawers", "plant", "sink", "stairs",
    "ceiling", "toilet", "stool", "towel", "mirror", "tv_monitor", "shower", "column",
    "bathtub", "counter", "fireplace", "lighting", "beam", "railing", "shelving", "blinds",
    "gym_equipment", "seating", "board_panel", "furniture", "appliances", "clothes",
    "objects", "misc", "unlabeled",
)  # fmt: skip
VOID_GROUPS = frozenset({"void", "unlabeled"})
VOID_WORDS = frozenset({"remove", "delete", "remove / behind", "void", "unlabeled", "unknown"})
NO_CATEGORY = ""  # the raw word of an object whose record names no category
# The shell: mpcat40 groups, and raw words for scans without groups.
STRUCTURE_GROUPS = frozenset({"wall", "floor", "ceiling", "column", "beam"})
STRUCTURE_WORDS = frozenset(
    {"floor", "wall", "ceiling", "door frame", "doorframe", "beam", "column"}
)
DOOR_FRAME_WORDS = frozenset({"door frame", "doorframe"})
FLIGHT_GROUP = "stairs"
FLIGHT_WORDS = frozenset({"stairs", "stair", "staircase", "stairway", "steps", "step"})
OBJECTS_GROUP = 39  # mpcat40 "objects": the group an exported category without its own gets


def word(raw: str) -> str:
    """A raw category as a lower-case phrase (``kitchen#cabinet`` -> ``kitchen cabinet``)."""
    return raw.strip().lower().replace("#", " ").replace("_", " ")


def mpcat40_group(index: int, name: str) -> str | None:
    """The mpcat40 group a record names, or ``None`` unless the index and name are a row of
    the table (older vlln exports wrote ``0 <raw word>``)."""
    if 0 <= index < len(MPCAT40) and MPCAT40[index] == name.strip().lower():
        return MPCAT40[index]
    return None


def mpcat40_of(category: str) -> tuple[int, str]:
    """The group to write for one of vlln's categories: the table's row of that name
    (``stairs``, ``chair``, ``bed``...), else ``objects``."""
    name = category.replace(" ", "_")
    if name in MPCAT40 and name not in VOID_GROUPS:
        return MPCAT40.index(name), name
    return OBJECTS_GROUP, MPCAT40[OBJECTS_GROUP]


def is_void(raw: str, group: str | None) -> bool:
    return group in VOID_GROUPS or raw == NO_CATEGORY or word(raw) in VOID_WORDS


def is_structure(raw: str, group: str | None) -> bool:
    return group in STRUCTURE_GROUPS or word(raw) in STRUCTURE_WORDS


def is_door_frame(raw: str) -> bool:
    return word(raw) in DOOR_FRAME_WORDS


def is_flight(raw: str, group: str | None) -> bool:
    """Stairs by the mpcat40 group when the record gives one, else by the raw word."""
    if group is not None and group not in VOID_GROUPS:
        return group == FLIGHT_GROUP
    return word(raw) in FLIGHT_WORDS
