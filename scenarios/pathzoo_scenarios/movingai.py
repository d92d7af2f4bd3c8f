"""MovingAI pack: every problem of the bundled MovingAI ``.scen`` files, with its optimal length.

Ids are ``movingai.<map>.b<bucket>.<index>``: the map's file stem, the
problem's bucket and its 0-based line index in the ``.scen`` file, e.g.
``movingai.arena.b1.17``. Glob patterns select families without
duplicates:

- ``movingai.arena.*``: every problem on ``arena``;
- ``movingai.8room_000.b50.*``: the problems of bucket 50;
- ``movingai.arena.*.17``: problem 17, whatever its bucket.

Scenarios come from :func:`pathzoo.io.scenarios_from_scen`: 1 m cells,
start and goal at cell centres, ``reference_length`` = the file's optimal
length. They are built lazily, once per map (``functools.lru_cache``), and
all problems of one map share its map array and neighbourhood graph.
Data and attribution: ``data/README.md``, ``data/movingai/HOG2_LICENSE.txt``.
"""

from __future__ import annotations

from functools import lru_cache, partial
from pathlib import Path

from pathzoo.core import InvalidParameterError, Scenario
from pathzoo.io.movingai import read_scen, scenarios_from_scen
from pathzoo.plugins.entries import ScenarioEntry
from pathzoo_scenarios.common import DATA_DIR, check_choice, pack_metadata

__all__ = ["PACK_VERSION", "SCEN_FILES", "scen_path", "scenario_id", "load", "entries"]

PACK_VERSION = 1
MOVINGAI_DIR = DATA_DIR / "movingai"

SCEN_FILES: dict[str, str] = {
    "arena": "arena.map.scen",
    "8room_000": "8room_000.map.scen",
    "maze-32-32-2": "maze-32-32-2-random-1.scen",
    "random-32-32-20": "random-32-32-20-random-1.scen",
    "room-32-32-4": "room-32-32-4-random-1.scen",
}
"""Map stem to its bundled ``.scen`` file."""


def scen_path(map_stem: str) -> Path:
    """Path of the bundled ``.scen`` file of a map."""
    return MOVINGAI_DIR / SCEN_FILES[map_stem]


def scenario_id(map_stem: str, bucket: int, index: int) -> str:
    """The registry id of one problem."""
    return f"movingai.{map_stem}.b{bucket}.{index}"


@lru_cache(maxsize=None)
def _map_scenarios(map_stem: str) -> tuple[Scenario, ...]:
    return tuple(scenarios_from_scen(scen_path(map_stem)))


def load(map_stem: str, index: int) -> Scenario:
    """Problem ``index`` of a map's ``.scen`` file as a pack scenario (shares the map's graph)."""
    check_choice(map_stem, SCEN_FILES, "map_stem")
    problems = _map_scenarios(map_stem)
    if not 0 <= index < len(problems):
        raise InvalidParameterError(f"index must be in 0..{len(problems) - 1} for map {map_stem}, got {index!r}")
    base = problems[index]
    bucket = int(base.metadata["bucket"])
    meta = pack_metadata(
        "movingai",
        PACK_VERSION,
        f"MovingAI benchmark (Sturtevant 2012), {SCEN_FILES[map_stem]} problem {index}",
        map=map_stem,
        bucket=bucket,
        problem_index=index,
        scen_file=SCEN_FILES[map_stem],
        file=base.metadata["map"],
    )
    return base.with_endpoints(
        base.start,
        base.goal,
        id=scenario_id(map_stem, bucket, index),
        reference_length=base.reference_length,
        metadata=meta,
    )


def entries() -> list[ScenarioEntry]:
    """One entry per problem of every bundled ``.scen`` file (reads the problem lists only)."""
    out = []
    for stem in SCEN_FILES:
        for p in read_scen(scen_path(stem)):
            out.append(
                ScenarioEntry(
                    id=scenario_id(stem, p.bucket, p.index),
                    summary=(
                        f"MovingAI {stem} ({p.width}x{p.height}) problem {p.index}, bucket {p.bucket}, "
                        f"optimal {p.optimal_length:g}"
                    ),
                    load=partial(load, stem, p.index),
                    kind="grid2d",
                )
            )
    return out
