"""``vlln world ...``: draw, export and import houses."""

from __future__ import annotations

import argparse
from pathlib import Path

from vlln.cli.options import Commands, add_preset_option
from vlln.errors import ConfigError


def _world_show(args: argparse.Namespace) -> int:
    from vlln.viz.show import show_world
    from vlln.world.generator import parameters_from_overrides

    if args.scene is not None and (args.param or args.floors is not None):
        raise ConfigError("--scene shows a scanned scene as it is; drop --param and --floors")
    if args.preset is not None and (args.param or args.floors is not None):
        raise ConfigError(
            f"--preset {args.preset} draws the house's parameters from the seed; drop --param "
            "and --floors, or drop --preset"
        )
    params = parameters_from_overrides([*args.param, *_floors(args)])
    scene = None if args.scene is None else Path(args.scene)
    files = show_world(
        args.seed, Path(args.out), args.views, params, scene=scene, preset=args.preset
    )
    print(f"wrote {len(files)} images to {args.out} (map: {files[0]})")
    return 0


def _world_export(args: argparse.Namespace) -> int:
    from vlln.world.generator import generate_house, parameters_from_overrides
    from vlln.world.scans import export_scene, with_subdivided_mesh

    house = generate_house(args.seed, parameters_from_overrides([*args.param, *_floors(args)]))
    if args.subdivide:
        house = with_subdivided_mesh(house, args.subdivide)
    for style in args.style or ["mp3d", "hm3d"]:
        scene_dir = export_scene(house, Path(args.out) / style, style)
        print(f"wrote {scene_dir}")
        if args.episodes:
            from vlln.tasks.scan_episodes import write_scan_episodes

            for path in write_scan_episodes(house, scene_dir, style):
                print(f"wrote {path} (play it with --scenes {scene_dir.parent})")
    return 0


def _world_import(args: argparse.Namespace) -> int:
    import dataclasses
    import json

    from vlln.world.scans import import_scene
    from vlln.world.scene_summary import export_scene_summary

    house, report = import_scene(Path(args.scene))
    if args.summary_out:
        export_scene_summary(house, Path(args.summary_out))
    print(json.dumps(dataclasses.asdict(report), indent=2))
    return 0


def _world_catalogue(args: argparse.Namespace) -> int:
    from vlln.viz.catalogue_sheet import write_catalogue_sheet
    from vlln.world.catalogue import default_catalogue

    catalogue = default_catalogue()
    sheet = write_catalogue_sheet(catalogue, Path(args.out))
    print(f"rendered {len(catalogue)} categories at 640x480; contact sheet: {sheet}")
    return 0


def _floors(args: argparse.Namespace) -> list[str]:
    """``--floors N`` as the house parameter it sets."""
    return [] if args.floors is None else [f"floors={args.floors}"]


def add_world_commands(commands: Commands) -> None:
    world = commands.add_parser("world", help="procedural houses and scans").add_subparsers(
        dest="world_command", required=True
    )
    show = world.add_parser("show", help="write a top-down map and egocentric views of a house")
    show.add_argument("--seed", type=int, default=0, help="house seed (default 0)")
    show.add_argument("--scene", help="a scanned scene folder <dir>/<scene>/ instead of a seed")
    show.add_argument("--out", required=True, help="output directory")
    show.add_argument("--views", type=int, default=4, help="number of rooms to view (default 4)")
    show.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="a house-generator parameter, e.g. --param max_rooms=6 (repeatable)",
    )
    show.add_argument("--floors", type=int, help="storeys joined by stairs, 1 to 3 (default 1)")
    add_preset_option(show, benchmark_default=False)
    show.set_defaults(handler=_world_show)
    export = world.add_parser("export", help="write a house as Matterport3D/HM3D scene folders")
    export.add_argument("--seed", type=int, default=0, help="house seed (default 0)")
    export.add_argument("--out", required=True, help="output folder (<out>/<style>/<scene>/)")
    export.add_argument("--style", action="append", choices=["mp3d", "hm3d"], help="repeatable")
    export.add_argument("--param", action="append", default=[], metavar="NAME=VALUE")
    export.add_argument("--floors", type=int, help="storeys joined by stairs, 1 to 3")
    export.add_argument(
        "--subdivide",
        type=int,
        default=0,
        metavar="N",
        help="split every triangle into 4, N times: a scan-sized test scene (N=2: 16x)",
    )
    export.add_argument(
        "--episodes",
        action="store_true",
        help="also write the house's episodes naming the scan (<style>/<scene>/<scene>.glb)",
    )
    export.set_defaults(handler=_world_export)
    imported = world.add_parser("import", help="read a Matterport3D or HM3D scene folder")
    imported.add_argument("scene", help="scene folder <dir>/<scene>/ (.glb + .house or semantic)")
    imported.add_argument("--summary-out", help="also write its scene summary under this folder")
    imported.set_defaults(handler=_world_import)
    catalogue = world.add_parser(
        "catalogue", help="render every object category at 640x480 and a contact sheet"
    )
    catalogue.add_argument("--out", required=True, help="folder for <category>.png, catalogue.png")
    catalogue.set_defaults(handler=_world_catalogue)
