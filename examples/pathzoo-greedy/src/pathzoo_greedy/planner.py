"""Greedy best-first search on a scenario's neighbourhood graph, guided only by a distance heuristic."""

from __future__ import annotations

import heapq
import math
from typing import ClassVar, Mapping

import numpy as np

import pathzoo
from pathzoo import Budget, Param, PlanResult, Scenario, Status
from pathzoo.core import ProgressCallback
from pathzoo.grid.paths import centre_path

__all__ = ["GreedyBestFirst"]


def _heuristic(scenario: Scenario, kind: str) -> np.ndarray:
    """Distance in metres from every cell centre to the goal cell centre."""
    rows, cols = np.indices(scenario.shape)
    goal_row, goal_col = divmod(scenario.goal_node, scenario.shape[1])
    dr = np.abs(rows - goal_row).ravel().astype(float)
    dc = np.abs(cols - goal_col).ravel().astype(float)
    if kind == "octile":  # straight moves cost 1 cell, diagonal ones sqrt(2)
        cells = np.maximum(dr, dc) + (math.sqrt(2.0) - 1.0) * np.minimum(dr, dc)
    else:
        cells = np.hypot(dr, dc)
    return cells * scenario.cell_size


class GreedyBestFirst(pathzoo.Planner):
    """Greedy best-first search: always expand the open cell closest to the goal.

    It ignores the cost travelled so far, so it is fast but not optimal. The
    whole search is one iteration and evaluates one candidate path; the time
    budget is checked every ``check_every`` expansions.
    """

    id: ClassVar[str] = "greedy.best_first"
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = "Greedy best-first search on the grid graph (octile heuristic)"
    kinds: ClassVar[frozenset[str]] = frozenset({"grid2d", "terrain"})
    params: ClassVar[Mapping[str, Param]] = {
        "heuristic": Param("octile", "distance estimate to the goal", choices=("octile", "euclidean")),
        "check_every": Param(256, "node expansions between two looks at the clock", low=1, high=1_000_000),
    }

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Search from the start cell to the goal cell; see the class docstring."""
        self.check_supports(scenario)
        clock = budget.start()
        graph = scenario.graph
        h = _heuristic(scenario, self.heuristic)
        start, goal = scenario.start_node, scenario.goal_node
        parent = {start: start}
        frontier = [(h[start], start)]
        expanded = 0
        while frontier:
            _, node = heapq.heappop(frontier)
            if node == goal:
                return self._solved(scenario, parent, goal, progress)
            expanded += 1
            if expanded % self.check_every == 0 and clock.exhausted():
                return PlanResult(Status.FAILED, iterations=1, message=f"time budget out after {expanded} expansions")
            for nxt in graph.neighbours(node):
                nxt = int(nxt)
                if nxt not in parent:
                    parent[nxt] = node
                    heapq.heappush(frontier, (h[nxt], nxt))
        return PlanResult(Status.NO_PATH, iterations=1, message=f"goal unreachable ({expanded} cells searched)")

    @staticmethod
    def _solved(
        scenario: Scenario, parent: dict[int, int], goal: int, progress: ProgressCallback | None
    ) -> PlanResult:
        nodes = [goal]
        while parent[nodes[-1]] != nodes[-1]:
            nodes.append(parent[nodes[-1]])
        # cell centres, from exactly the start to exactly the goal
        path = centre_path(scenario, np.array(nodes[::-1]))
        length = float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())
        if progress is not None:
            progress(1, 1, length)
        return PlanResult(Status.SOLVED, path=path, iterations=1, evaluations=1)
