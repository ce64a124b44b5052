"""The reference benchmark's object categories (its ``normal_category.json``), in its order.

These are the cleaned Matterport3D category names its episodes and scene summaries use. The
catalogue models every one that can stand in a house under the same name; a few name places
or things that are no part of a house's contents (:data:`NOT_IN_A_HOUSE`).
"""

from __future__ import annotations

REFERENCE_CATEGORIES: tuple[str, ...] = (
    "chair", "picture", "pillow", "table", "cabinet", "plant", "couch", "curtain", "stand",
    "stool", "bed", "toilet", "stairs", "cushion", "bench", "desk", "tv", "counter",
    "countertop", "bathtub", "fireplace", "drawer", "dresser", "ottoman", "blanket",
    "refrigerator", "excercise equipment", "washing machine", "wardrobe", "oven", "footstool",
    "stove", "blinds", "vanity", "heater", "kitchen island", "air conditioner", "range hood",
    "ladder", "clothes dryer", "piano", "sheet", "guitar", "pool table", "pool", "water cooler",
    "drum", "blackboard", "cart", "stall", "car", "umbrella", "garbage", "balcony", "person",
    "water heater", "bicycle", "crib", "luggage", "bottle", "plate", "switch", "toy", "shoe",
    "bowl", "cup", "wine", "telephone", "purse", "tissue box", "shower", "candle", "mask",
    "sign", "jar", "hanger", "tissue", "teapot", "soap", "soap dispenser", "hat", "candlestick",
    "tray", "treadmill", "pan", "brush", "seasoning", "trophy", "socket", "kettle", "album",
    "camera", "shampoo", "tablet", "remote control", "soap dish", "body loofah", "cosmetics",
    "mouse", "pitcher", "can", "cap", "radio", "hook", "sponge", "hamper", "notebook",
    "detergent", "knife", "plug", "magazine", "adhesive tape", "hair dryer", "glove", "bread",
)  # fmt: skip

NOT_IN_A_HOUSE: tuple[str, ...] = ("balcony", "pool", "stall", "car")
