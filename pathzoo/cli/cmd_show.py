"""``pathzoo show SCENARIO -o FILE.png``: draw a scenario's map with its start and goal."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from pathzoo.cli.errors import CommandError

__all__ = ["add_parser"]


def _image_formats() -> set[str]:
    from matplotlib.backend_bases import FigureCanvasBase

    return set(FigureCanvasBase.get_supported_filetypes())


def _run(args: argparse.Namespace) -> int:
    import pathzoo
    from pathzoo.plotting.scenario import save_scenario_png

    out = Path(args.output)
    if out.is_dir():
        raise CommandError(f"{out}: is a directory; give an image file name such as {out / 'scenario.png'}")
    if not out.parent.is_dir():
        raise FileNotFoundError(2, "output directory does not exist", str(out.parent))
    formats = _image_formats()
    if out.suffix.lower().lstrip(".") not in formats:
        raise CommandError(f"{out}: unknown image format {out.suffix or '(no suffix)'!r}; "
                           f"use one of: {', '.join('.' + f for f in sorted(formats))}")
    scenario = pathzoo.load_scenario(args.scenario)
    written = save_scenario_png(scenario, out, show_graph=args.graph)
    print(f"wrote {written}")
    return 0


def add_parser(subparsers: Any) -> None:
    """Register the ``show`` subcommand."""
    parser = subparsers.add_parser(
        "show",
        help="draw a scenario (map, start and goal) to a PNG file",
        description="Draw a scenario from above: the occupancy map, hillshaded terrain or the top view "
        "of an air volume, moving obstacles, the start and the goal.",
    )
    parser.add_argument("scenario", help="a registered scenario id (see 'pathzoo list scenarios') or a scenario file")
    parser.add_argument("-o", "--output", required=True, metavar="FILE.png", help="image file to write")
    parser.add_argument("--graph", action="store_true", help="also draw the neighbourhood graph (small maps only)")
    parser.set_defaults(handler=_run)
