"""Dijkstra and A* reproduce the optimal length of every problem of every MovingAI ``.scen`` file.

3183 problems on 5 maps, 1940 of them on the 512 x 512 ``8room_000``; that
file is split into chunks so that ``pytest -n 2`` shares the work. Every
returned path also goes through the harness's validator, and its length is
measured from the path itself, not taken from the planner.
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import numpy as np
import pytest

import pathzoo
from pathzoo.core import Budget, Scenario, Status
from pathzoo.rules import validate_path

SCEN_FILES = {
    "grid/dao/arena.map.scen": 1,
    "grid/rooms/8room_000.map.scen": 6,
    "mapf/random-32-32-20-random-1.scen": 1,
    "mapf/room-32-32-4-random-1.scen": 1,
    "mapf/maze-32-32-2-random-1.scen": 1,
}
"""Every ``.scen`` file of the shared data and the number of chunks it is tested in."""

TOLERANCE = 1e-3
"""The files print optimal lengths to 5-6 significant figures."""

CASES = [
    pytest.param(planner, name, chunk, n, id=f"{planner}-{Path(name).name.split('.')[0]}-{chunk + 1}of{n}")
    for planner in ("exact.dijkstra", "exact.astar")
    for name, n in SCEN_FILES.items()
    for chunk in range(n)
]


def test_every_scen_file_is_covered(shared_data: Path) -> None:
    found = sorted(str(p.relative_to(shared_data / "movingai")) for p in (shared_data / "movingai").rglob("*.scen"))
    assert found == sorted(SCEN_FILES)


def path_length(path: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())


@pytest.mark.slow
@pytest.mark.parametrize(("planner_id", "scen", "chunk", "n_chunks"), CASES)
def test_reproduces_scen_optimum(
    load_scen: Callable[[str], list[Scenario]], planner_id: str, scen: str, chunk: int, n_chunks: int
) -> None:
    problems = load_scen(scen)
    assert len(problems) > 0
    planner = pathzoo.make_planner(planner_id)
    rng = np.random.default_rng(0)
    failures = []
    for scenario in problems[chunk::n_chunks]:
        result = planner.plan(scenario, budget=Budget(), rng=rng)
        if result.status is not Status.SOLVED:
            failures.append(f"{scenario.id}: status {result.status.value} ({result.message})")
            continue
        verdict = validate_path(scenario, result.path)
        length = path_length(result.path)
        if not verdict:
            failures.append(f"{scenario.id}: invalid path: {verdict.reason}")
        elif abs(length - scenario.reference_length) > TOLERANCE:
            failures.append(f"{scenario.id}: length {length:.6f}, .scen optimum {scenario.reference_length}")
    assert not failures, f"{len(failures)} problem(s) failed, first ones:\n" + "\n".join(failures[:10])
