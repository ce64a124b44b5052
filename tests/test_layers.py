"""No import points up the layers of the package.

:data:`LAYERS` is the one declaration of the layer order (docs/architecture.md explains it and
is checked against it here). Every ``import`` of every module under ``src/vlln`` is read with
``ast``, including imports inside functions (the lazy imports that keep ``vlln --help`` fast),
under ``if TYPE_CHECKING:`` and in ``try`` blocks, so a dependency cannot hide from the check.
A module may import its own package and any package of a lower layer. The packages of one
layer are independent of each other (the applications, for example, never import one
another). Imports by name at run time (``importlib``, entry-point strings) are not seen.
"""

from __future__ import annotations

import ast
import graphlib
import re
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
TRAINING = ROOT / "oracle_training"  # the classifier's training, beside the package, not in it
ARCHITECTURE = ROOT / "docs" / "architecture.md"

# Bottom to top; each entry is one layer, its packages independent of each other.
# "vlln" is the package root (vlln/__init__.py: the version).
LAYERS: tuple[tuple[str, ...], ...] = (
    ("vlln",),
    ("errors",),
    ("files", "extras", "config", "http"),
    ("world",),
    ("sim",),
    ("tasks",),
    ("oracle", "prompt", "viz"),
    ("agents",),
    ("eval",),
    ("datagen", "gym"),
    ("oracle_service", "web", "train", "cluster"),
    ("bench", "demo"),
    ("cli",),
)


@dataclass(frozen=True)
class Import:
    """One imported module, where it is imported."""

    module: str  # the importing module, e.g. vlln.tasks.env
    line: int
    target: str  # the imported module, e.g. vlln.oracle.protocol


def module_name(path: Path) -> str:
    """``src/vlln/tasks/env.py`` -> ``vlln.tasks.env``; a package's ``__init__`` is the
    package."""
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports_in(source: str, module: str, is_package: bool, known: set[str]) -> list[Import]:
    """Every import of a ``vlln`` module in ``source`` (anywhere in the tree), resolved to
    absolute names. ``from X import name`` counts as importing ``X.name`` when that is one of
    the ``known`` modules (so ``from vlln import errors`` is an import of ``vlln.errors``)."""
    package = module.split(".") if is_package else module.split(".")[:-1]
    found: list[Import] = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - (node.level - 1)]
                origin = ".".join([*base, *([node.module] if node.module else [])])
            else:
                origin = node.module or ""
            targets = [
                f"{origin}.{alias.name}" if f"{origin}.{alias.name}" in known else origin
                for alias in node.names
            ]
        else:
            continue
        found += [
            Import(module, node.lineno, target)
            for target in targets
            if target == "vlln" or target.startswith("vlln.")
        ]
    return found


def package_of(module: str) -> str:
    """The top-level package a module belongs to (``vlln`` for the root itself)."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def problems(imports: list[Import], layers: tuple[tuple[str, ...], ...]) -> list[str]:
    """One line per import that points up the layers, or sideways within a layer, or that
    involves a package placed in no layer."""
    level = {package: index for index, layer in enumerate(layers) for package in layer}

    def name(index: int) -> str:
        return f"layer {index + 1} ({' | '.join(layers[index])})"

    found: list[str] = []
    for item in dict.fromkeys(imports):  # "from X import a, b" is one import of X
        source, target = package_of(item.module), package_of(item.target)
        if source == target:
            continue
        where = f"{item.module} line {item.line} imports {item.target}"
        unplaced = [package for package in (source, target) if package not in level]
        if unplaced:
            found.append(f"{where}: vlln.{unplaced[0]} is in no layer; add it to LAYERS")
        elif level[target] > level[source]:
            found.append(f"{where}: {name(level[source])} is below {name(level[target])}")
        elif level[target] == level[source]:
            found.append(
                f"{where}: {source} and {target} share {name(level[source])}, whose packages "
                "are independent"
            )
    return found


def package_imports() -> list[Import]:
    paths = sorted(SRC.joinpath("vlln").rglob("*.py"))
    known = {module_name(path) for path in paths}
    return [
        item
        for path in paths
        for item in imports_in(
            path.read_text(encoding="utf-8"), module_name(path), path.name == "__init__.py", known
        )
    ]


def test_no_import_points_up_the_layers() -> None:
    imports = package_imports()
    assert len(imports) > 1000  # the walk reached the modules (and their lazy imports)
    assert any(item.module == "vlln.cli.oracle" for item in imports)  # one inside a function
    assert problems(imports, LAYERS) == []


def module_graph(imports: list[Import], known: set[str]) -> dict[str, set[str]]:
    """Each module and the modules it imports (``from vlln.a import b`` of a name in module
    ``vlln.a`` counts as importing ``vlln.a``)."""
    graph: dict[str, set[str]] = {}
    for item in imports:
        target = item.target
        while target not in known and "." in target:
            target = target.rsplit(".", 1)[0]
        if target in known and target != item.module:
            graph.setdefault(item.module, set()).add(target)
    return graph


def test_no_two_modules_import_each_other() -> None:
    known = {module_name(path) for path in SRC.joinpath("vlln").rglob("*.py")}
    graph = module_graph(package_imports(), known)
    try:
        tuple(graphlib.TopologicalSorter(graph).static_order())
    except graphlib.CycleError as error:
        pytest.fail(f"import cycle: {' -> '.join(error.args[1])}")


def test_the_cycle_check_sees_a_lazy_import_back() -> None:
    known = {"vlln.bench.sim", "vlln.bench.parallel"}
    imports = imports_in("from vlln.bench.parallel import run", "vlln.bench.sim", False, known)
    imports += imports_in(
        "def f():\n    from vlln.bench.sim import _walk", "vlln.bench.parallel", False, known
    )
    with pytest.raises(graphlib.CycleError):
        tuple(graphlib.TopologicalSorter(module_graph(imports, known)).static_order())


def test_every_package_has_a_layer() -> None:
    packages = {package_of(module_name(path)) for path in SRC.joinpath("vlln").rglob("*.py")}
    placed = [package for layer in LAYERS for package in layer]
    assert sorted(packages) == sorted(placed), "each package of src/vlln in exactly one layer"


def test_the_architecture_document_lists_the_same_layers() -> None:
    rows = re.findall(r"^\| (\d+) \| ([^|]+) \|", ARCHITECTURE.read_text(encoding="utf-8"), re.M)
    documented = [tuple(re.findall(r"`([a-z_]+)/?`", packages)) for _, packages in rows]
    assert [int(number) for number, _ in rows] == list(range(1, len(LAYERS) + 1))
    assert documented == list(LAYERS)


def test_the_training_folder_sits_on_the_oracle_and_only_its_commands_reach_it() -> None:
    # oracle_training/ is not installed: it may import the oracle and what lies below it, and
    # the package imports it only inside the functions of the commands that train and
    # measure the classifier (which say where it is when an install lacks it).
    oracle = next(i for i, layer in enumerate(LAYERS) if "oracle" in layer)
    allowed = {package for layer in LAYERS[: oracle + 1] for package in layer}
    for path in sorted(TRAINING.glob("*.py")):
        imports = imports_in(path.read_text(encoding="utf-8"), "vlln.oracle.training", False, set())
        assert {package_of(item.target) for item in imports} <= allowed, path.name
    reaching = set()
    for path in sorted(SRC.joinpath("vlln").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            else:
                names = [node.module or ""] if isinstance(node, ast.ImportFrom) else []
            if any(name.split(".")[0] == "oracle_training" for name in names):
                reaching.add(module_name(path))
                assert node.col_offset > 0, f"{module_name(path)} line {node.lineno}"
    assert reaching == {"vlln.cli.oracle", "vlln.oracle.question_set"}


SYNTHETIC = """
from typing import TYPE_CHECKING

from vlln.errors import ConfigError
from . import model

if TYPE_CHECKING:
    from vlln.tasks.episode import Episode


def lazy():
    from ..sim import simulator
    import vlln.cli
"""


def test_the_check_finds_upward_imports_wherever_they_are() -> None:
    known = {"vlln.world.model", "vlln.sim.simulator", "vlln.errors", "vlln.cli"}
    imports = imports_in(SYNTHETIC, "vlln.world.fake", False, known)
    assert [(item.line, item.target) for item in imports] == [
        (4, "vlln.errors"),
        (5, "vlln.world.model"),
        (8, "vlln.tasks.episode"),
        (12, "vlln.sim.simulator"),
        (13, "vlln.cli"),
    ]
    assert problems(imports, LAYERS) == [
        "vlln.world.fake line 8 imports vlln.tasks.episode: layer 4 (world) is below "
        "layer 6 (tasks)",
        "vlln.world.fake line 12 imports vlln.sim.simulator: layer 4 (world) is below "
        "layer 5 (sim)",
        "vlln.world.fake line 13 imports vlln.cli: layer 4 (world) is below layer 13 (cli)",
    ]


@pytest.mark.parametrize(
    ("module", "source", "expected"),
    [
        ("vlln.web.app", "from vlln.train import sft", "share layer 11"),
        ("vlln.newpkg", "from vlln.world import model", "vlln.newpkg is in no layer"),
        ("vlln.tasks.env", "from vlln.oracle.protocol import Oracle", "layer 6 (tasks) is below"),
    ],
)
def test_sideways_and_unplaced_imports_are_refused(module: str, source: str, expected: str) -> None:
    found = problems(imports_in(source, module, False, set()), LAYERS)
    assert len(found) == 1 and expected in found[0]


def test_downward_imports_pass() -> None:
    source = "from vlln.tasks.env import NavigationEnv\nfrom vlln.http.gate import RequestGate"
    assert problems(imports_in(source, "vlln.web.app", False, set()), LAYERS) == []
