"""``pathzoo show SCENARIO -o FILE.png``: draw a scenario's map with its start and goal."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

__all__ = ["add_parser"]


def _run(args: argparse.Namespace) -> int:
    import pathzoo
    from pathzoo.plotting.scenario import save_scenario_png

    out = Path(args.output)
    if not out.parent.is_dir():
        raise FileNotFoundError(2, "output directory does not exist", str(out.parent))
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
