"""Test planners for the harness: honest ones, forgers and saboteurs (a plugin module workers can import).

Register it in the harness process with
``get_registry().add_plugin(forged, "forged-test")``; the harness then ships
the module name to its workers (:func:`pathzoo.harness.planner_info.extra_plugin_modules`).
"""

from __future__ import annotations

import json
import os
import signal
import time
from typing import Sequence

import numpy as np

from pathzoo import Budget, MovingObstacle, Param, Planner, PlanResult, Scenario, ScenarioEntry, Status, hookimpl
from pathzoo.core.planner import ProgressCallback
from pathzoo.grid.reference import reference_path

KINDS = frozenset({"grid2d", "terrain", "air3d", "dynamic"})


def wall_scenario() -> Scenario:
    """6 x 6 cells of 1 m, a wall in column 3 with a gap in row 0; start and goal on the bottom row."""
    occ = np.zeros((6, 6), bool)
    occ[1:, 3] = True
    return Scenario(id="test.wall", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 5.5), goal=(5.5, 5.5))


def sealed_scenario() -> Scenario:
    """Like :func:`wall_scenario` without the gap: the goal is unreachable."""
    occ = np.zeros((6, 6), bool)
    occ[:, 3] = True
    return Scenario(id="test.sealed", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 5.5), goal=(5.5, 5.5))


def street_scenario() -> Scenario:
    """A dynamic scenario: an empty 8 x 3 street with a parked obstacle off the path."""
    return Scenario(id="test.street", kind="dynamic", occupancy=np.zeros((3, 8), bool), cell_size=1.0,
                    start=(0.5, 1.5), goal=(7.5, 1.5), moving_obstacles=(MovingObstacle(0.4, [(4.5, 0.5)], 0.0),))


def ramp_scenario() -> Scenario:
    """A terrain scenario (for planners that do not support terrain)."""
    elev = np.tile(np.arange(4, dtype=float), (3, 1))
    return Scenario(id="test.ramp", kind="terrain", occupancy=np.zeros((3, 4), bool), cell_size=1.0,
                    start=(0.5, 1.5), goal=(3.5, 1.5), elevation=elev)


class Honest(Planner):
    """Returns the graph-optimal path after a random number of improving iterations drawn from ``rng``."""

    id = "test.honest"
    summary = "reference path, random history"
    kinds = KINDS
    params = {"delay_s": Param(0.0, "sleep before answering", low=0.0)}

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        self.check_supports(scenario)
        time.sleep(self.delay_s)
        ref = reference_path(scenario)
        n = int(rng.integers(3, 12))
        costs = np.sort(rng.uniform(ref.length if ref else 1.0, 100.0, n))[::-1]
        for i, c in enumerate(costs):
            if progress is not None:
                progress(i, 10 * (i + 1), float(c))
                progress(i, 10 * (i + 1), float(c))  # a repeated report is not stored twice
        if ref is None:
            return PlanResult(Status.NO_PATH, iterations=n, evaluations=10 * n)
        return PlanResult(Status.SOLVED, path=ref.path.copy(), iterations=n, evaluations=10 * n,
                          extras={"lies": "ignored"})


class Fixed(Planner):
    """Returns whatever path, times and status its parameters give (JSON; ``NaN`` allowed)."""

    id = "test.fixed"
    summary = "returns a given path"
    kinds = KINDS
    params = {
        "path": Param("null", "JSON list of waypoints"),
        "times": Param("null", "JSON list of times"),
        "status": Param("solved", "claimed status", choices=("solved", "no_path", "failed")),
    }

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        path, times = json.loads(self.path), json.loads(self.times)
        return PlanResult(Status(self.status), path=None if path is None else np.array(path, dtype=float),
                          times=None if times is None else np.array(times, dtype=float), iterations=1, evaluations=1)


class Sabotage(Planner):
    """Misbehaves in the way its ``how`` parameter names."""

    id = "test.sabotage"
    summary = "raises, hangs, exits, mutates the scenario or returns garbage"
    kinds = KINDS
    params = {
        "how": Param("raise", "what to do", choices=("raise", "sleep", "exit", "kill", "mutate", "garbage", "sysexit"))
    }

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        if self.how == "raise":
            raise ValueError("planted bug")
        if self.how == "sleep":
            time.sleep(3600)
        if self.how == "exit":
            os._exit(3)
        if self.how == "kill":
            os.kill(os.getpid(), signal.SIGKILL)
        if self.how == "sysexit":
            raise SystemExit(4)
        if self.how == "garbage":
            return "a path, trust me"  # type: ignore[return-value]
        occ = scenario.occupancy
        occ.setflags(write=True)
        occ[...] = False
        return PlanResult(Status.SOLVED, path=np.array([scenario.start, scenario.goal]))


def burn_cpu(seconds: float) -> None:
    """Spin until this process has used ``seconds`` more CPU seconds."""
    end = time.process_time() + seconds
    while time.process_time() < end:
        pass


class Burner(Planner):
    """Burns CPU where its parameters say (constructor, ``plan()``, a child process), then loops on the budget.

    The loop counts one iteration per ``step_cpu_s`` of CPU and stops when the
    budget clock says so; the answer is the reference path.
    """

    id = "test.burner"
    summary = "burns CPU in __init__, plan() or a child process"
    kinds = KINDS
    params = {
        "init_cpu_s": Param(0.0, "CPU seconds burnt in the constructor", low=0.0),
        "child_cpu_s": Param(0.0, "CPU seconds burnt by a child process of plan()", low=0.0),
        "step_cpu_s": Param(0.01, "CPU seconds per iteration of the budget loop", low=0.0),
    }

    def __init__(self, **params: object) -> None:
        super().__init__(**params)
        burn_cpu(self.init_cpu_s)

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        import subprocess
        import sys

        clock = budget.start()
        if self.child_cpu_s:
            spin = f"import time\nend = time.process_time() + {self.child_cpu_s}\nwhile time.process_time() < end: pass"
            subprocess.run([sys.executable, "-S", "-c", spin], check=True)
        iterations = 0
        while not clock.exhausted(iterations=iterations, evaluations=iterations):
            burn_cpu(self.step_cpu_s)
            iterations += 1
            if budget.iterations is None and budget.evaluations is None and not budget.timed:
                break
        ref = reference_path(scenario)
        assert ref is not None
        return PlanResult(Status.SOLVED, path=ref.path.copy(), iterations=iterations, evaluations=iterations)


class GridOnly(Honest):
    """An honest planner that only declares ``grid2d``."""

    id = "test.gridonly"
    kinds = frozenset({"grid2d"})


@hookimpl
def pathzoo_register_planners() -> Sequence[type[Planner]]:
    return [Honest, Fixed, Sabotage, Burner, GridOnly]


@hookimpl
def pathzoo_register_scenarios() -> Sequence[ScenarioEntry]:
    return [
        ScenarioEntry("test.wall", "wall with a gap", wall_scenario, "grid2d"),
        ScenarioEntry("test.sealed", "unreachable goal", sealed_scenario, "grid2d"),
        ScenarioEntry("test.street", "dynamic street", street_scenario, "dynamic"),
        ScenarioEntry("test.ramp", "terrain ramp", ramp_scenario, "terrain"),
    ]
