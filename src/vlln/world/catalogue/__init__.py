"""The object catalogue: every category the procedural houses can contain."""

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.registry import Catalogue, default_catalogue

__all__ = [
    "Catalogue",
    "Category",
    "ObjectModel",
    "Placement",
    "Style",
    "Surface",
    "default_catalogue",
]
