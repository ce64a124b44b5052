"""``vlln world ...``: draw, export and import houses. Each command's flags come from its
settings class in :mod:`vlln.cli.world_settings`."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from vlln.cli.generated import add_config_command
from vlln.cli.options import Commands

if TYPE_CHECKING:
    from vlln.cli.world_settings import (
        CatalogueCommand,
        ExportCommand,
        ImportCommand,
        ShowCommand,
    )


def _settings(name: str) -> Callable[[], type[Any]]:
    """The settings class ``name``, imported when its command is used."""

    def load() -> type[Any]:
        from vlln.cli import world_settings

        loaded: type[Any] = getattr(world_settings, name)
        return loaded

    return load


def _world_show(command: ShowCommand) -> int:
    from vlln.viz.show import show_world
    from vlln.world.generator import parameters_from_overrides

    params = parameters_from_overrides(command.overrides)
    files = show_world(
        command.seed,
        command.out,
        command.views,
        params,
        scene=command.scene,
        preset=command.preset,
    )
    print(f"wrote {len(files)} images to {command.out} (map: {files[0]})")
    return 0


def _world_export(command: ExportCommand) -> int:
    from vlln.files import check_output_folder
    from vlln.world.generator import generate_house, parameters_from_overrides
    from vlln.world.scans import export_scene, with_subdivided_mesh

    check_output_folder(command.out)
    house = generate_house(command.seed, parameters_from_overrides(command.overrides))
    if command.subdivide:
        house = with_subdivided_mesh(house, command.subdivide)
    for style in command.style or ("mp3d", "hm3d"):
        scene_dir = export_scene(house, command.out / style, style)
        print(f"wrote {scene_dir}")
        if command.episodes:
            from vlln.tasks.scan_episodes import write_scan_episodes

            for path in write_scan_episodes(house, scene_dir, style):
                print(f"wrote {path} (play it with --scenes {scene_dir.parent})")
    return 0


def _world_import(command: ImportCommand) -> int:
    import dataclasses
    import json

    from vlln.world.scans import import_scene
    from vlln.world.scene_summary import export_scene_summary

    house, report = import_scene(command.scene)
    if command.summary_out:
        export_scene_summary(house, command.summary_out)
    print(json.dumps(dataclasses.asdict(report), indent=2))
    return 0


def _world_catalogue(command: CatalogueCommand) -> int:
    from vlln.viz.catalogue_sheet import write_catalogue_sheet
    from vlln.world.catalogue import default_catalogue

    catalogue = default_catalogue()
    sheet = write_catalogue_sheet(catalogue, command.out)
    print(f"rendered {len(catalogue)} categories at 640x480; contact sheet: {sheet}")
    return 0


def add_world_commands(commands: Commands) -> None:
    world = commands.add_parser("world", help="procedural houses and scans").add_subparsers(
        dest="world_command", required=True
    )
    add_config_command(
        world,
        "show",
        _settings("ShowCommand"),
        _world_show,
        help="write a top-down map and egocentric views of a house",
    )
    add_config_command(
        world,
        "export",
        _settings("ExportCommand"),
        _world_export,
        help="write a house as Matterport3D/HM3D scene folders",
    )
    add_config_command(
        world,
        "import",
        _settings("ImportCommand"),
        _world_import,
        help="read a Matterport3D or HM3D scene folder",
    )
    add_config_command(
        world,
        "catalogue",
        _settings("CatalogueCommand"),
        _world_catalogue,
        help="render every object category at 640x480 and a contact sheet",
    )
