"""Export and import of the released scene-summary format.

A scene summary is a directory ``<out>/<scene>/`` with two JSON files that the reference
oracle and instruction tools read:

* ``object_dict.json``: ``{instance_id: {category, position, min_points, max_points, scope,
  room, region_id, unique_description, nearby_objects, caption}}`` with instances in id order.
  ``room`` is the region *label* of the instance's room (``"cooking region"``), because the
  reference code looks rooms up by ``scope + "/" + room`` and speaks ``room`` through the label
  table; ``region_id`` (an extra key, ignored by the reference) names the exact region so a
  house with two bedrooms round-trips. Without it (released data) the room is the region of
  that label containing, or else nearest to, the instance's floor-plan centre.
  ``unique_description`` holds ``"fine grained category"`` and the :class:`Attributes`;
  ``nearby_objects`` maps the other instance's id to the relation word (a list of words when
  a pair has several). ``position`` is the box centre; it is written for the reference tools
  and only checked on import, where the box is ``min_points``/``max_points``.
* ``region_dict.json``: ``{scope: [{label, id, poly, enlarge_poly}]}`` with rooms in id
  order, one scope per floor (``<house>_<level>`` with several floors). Polygons are
  ``[x, -z]`` (this module is the only place that frame appears) and ``enlarge_poly`` is
  ``poly`` grown outward by :data:`ENLARGE_MARGIN`, which the reference falls back to for
  points in doorways and on walls.

Files are byte-identical for equal houses: fixed key order, numbers rounded to
:data:`DECIMALS` decimals (so a round trip is exact only to 0.1 mm), two-space indent with each
point on one line, UTF-8, a trailing newline, and written atomically. The format has no doors,
floor heights, yaw, support ids or geometry; an imported :class:`House` has none of them (floors
at 0, yaw 0).
"""

from vlln.world.scene_summary.format import (
    DECIMALS,
    ENLARGE_MARGIN,
    LABEL_TO_ROOM_TYPE,
    OBJECT_DICT_FILE,
    REGION_DICT_FILE,
    ROOM_TYPE_TO_LABEL,
    SPOKEN_ROOM_NAMES,
    UNKNOWN_ROOM_ID,
    grown_polygon,
)
from vlln.world.scene_summary.reader import import_scene_summary
from vlln.world.scene_summary.writer import export_scene_summary

__all__ = [
    "DECIMALS",
    "ENLARGE_MARGIN",
    "LABEL_TO_ROOM_TYPE",
    "OBJECT_DICT_FILE",
    "REGION_DICT_FILE",
    "ROOM_TYPE_TO_LABEL",
    "SPOKEN_ROOM_NAMES",
    "UNKNOWN_ROOM_ID",
    "export_scene_summary",
    "grown_polygon",
    "import_scene_summary",
]
