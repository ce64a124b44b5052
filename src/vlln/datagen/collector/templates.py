"""How the collector words its questions: several paraphrases per question type.

``{category}`` is the target's category as the instruction names it. Every template must be
classified by the oracle as the type it is used for (a test checks this), so that the recorded
question type and the trigger agree.
"""

from __future__ import annotations

import numpy as np

ATTRIBUTE_TEMPLATES: dict[str, tuple[str, ...]] = {
    "color": (
        "What color is the {category}?",
        "What is the color of the target?",
        "Can you tell me the colour of the {category} I am looking for?",
        "Which color should the {category} be?",
    ),
    "material": (
        "What is the {category} made of?",
        "What material is the target made of?",
        "Can you tell me the material of the {category}?",
    ),
    "texture": (
        "What texture does the {category} have?",
        "Is the {category} patterned or plain? What is its texture?",
    ),
    "shape": (
        "What shape is the {category}?",
        "Can you describe the shape of the target?",
    ),
    "size": (
        "How big is the {category}?",
        "Is the {category} small or large?",
    ),
    "room": (
        "Which room is the {category} in?",
        "In which room can I find the target?",
        "What room is the {category} located in?",
    ),
}

ROUTE_TEMPLATES: tuple[str, ...] = (
    "Which way should I go to find the {category}?",
    "Where should I go next to reach the {category}?",
    "How do I get to the {category} from here?",
    "Can you tell me the way to the target?",
    "Which direction is the {category}?",
    "I am not sure where to go. Which way is the {category}?",
    "Could you guide me toward the {category}?",
    "What route should I take to the target?",
    "In which direction should I head?",
    "Where is the {category} relative to me?",
    "Can you point me in the right direction?",
    "How can I reach the {category}?",
)

DISAMBIGUATION_TEMPLATES: tuple[str, ...] = (
    "Is this the {category} you are looking for?",
    "Is this the one?",
    "Is this the target?",
    "Is the {category} in front of me the one you mean?",
    "Am I looking at the right {category}?",
    "Is this {category} the target?",
    "Is it this {category}?",
    "Is this the {category} you mean?",
    "Did I find the right {category}?",
    "Is the object in front of me the target?",
    "Is this the correct {category}?",
    "Is this the {category} I should find?",
    "Could this be the {category} you want?",
    "Is this one the target {category}?",
    "Have I found the target?",
    "Is this the right one?",
    "Is that the {category} you described?",
    "Am I looking at the target now?",
    "Is the {category} ahead of me the one?",
    "Is this the {category} I am searching for?",
    "Is this the one you asked for?",
    "Is this {category} the one you mean?",
    "Should I go to this {category}? Is it the target?",
    "Is the {category} I see now the target?",
)


def fill(templates: tuple[str, ...], category: str, rng: np.random.Generator) -> str:
    """One template, drawn with ``rng``, with the category filled in."""
    return templates[int(rng.integers(len(templates)))].format(category=category)
