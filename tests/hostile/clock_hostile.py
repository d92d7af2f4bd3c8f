"""Hostile planners that attack the run's clock, the host's sysctls and the resource tracker (issue 32).

Each clock attacker does the same work as :class:`HonestWork` (``WORK_CPU_S``
of busy work plus an A* search on the scenario, whose path it returns) but
hides the work where a harness that trusts the planner's process would not
charge it: before a forged "planned" frame, in the conversion of the path
or the message, or in the untimed warm-up. A registered plugin module (the
judge never imports it); ``hostile.wall`` and MovingAI maps are fine
scenarios.
"""

from __future__ import annotations

import os
import stat
import struct
import time
from typing import Any, Sequence

import numpy as np

import pathzoo
from pathzoo import Budget, Param, Planner, PlanResult, Scenario, Status, hookimpl
from pathzoo.core.planner import ProgressCallback

KINDS = frozenset({"grid2d", "terrain", "air3d", "dynamic"})
WORK_CPU_S = 2.0
"""CPU seconds of busy work each clock attacker does besides its search."""


def _burn(seconds: float = WORK_CPU_S) -> None:
    end = time.process_time() + seconds
    x = 0
    while time.process_time() < end:
        x += 1


def _search(scenario: Scenario) -> PlanResult:
    astar = pathzoo.make_planner("exact.astar")
    return astar.plan(scenario, budget=Budget(), rng=np.random.default_rng(0))


def _work(scenario: Scenario) -> PlanResult:
    _burn()
    return _search(scenario)


class _Clocked(Planner):
    kinds = KINDS
    summary = "hostile clock test planner"


class HonestWork(_Clocked):
    """The reference: the work, done in ``plan()``."""

    id = "clock.honest"

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        return _work(scenario)


def _frame(payload: bytes) -> bytes:
    """A message as :class:`multiprocessing.connection.Connection` frames it."""
    return struct.pack("!i", len(payload)) + payload


class ForgedPlanned(_Clocked):
    """Writes a "planned" frame (``E``) on every socket it holds, then works."""

    id = "clock.forged_planned"

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        written = 0
        for fd in range(3, 256):
            try:
                if stat.S_ISSOCK(os.fstat(fd).st_mode):
                    os.write(fd, _frame(b"E"))
                    written += 1
            except OSError:
                pass
        result = _work(scenario)
        return PlanResult(result.status, path=result.path, iterations=result.iterations,
                          evaluations=result.evaluations, message=f"forged on {written} sockets")


class _SearchingPath:
    """A path that does the work when converted (``__array__``)."""

    def __init__(self, scenario: Scenario) -> None:
        self.scenario = scenario

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        path = _work(self.scenario).path
        return np.asarray(path, dtype=dtype)


class ArrayWorks(_Clocked):
    """Returns a path whose ``__array__`` searches."""

    id = "clock.array_works"

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        return PlanResult(Status.SOLVED, path=_SearchingPath(scenario), iterations=1,  # type: ignore[arg-type]
                          evaluations=1)


class _LazySequence:
    """A path that does the work on the first ``len()`` or index."""

    def __init__(self, scenario: Scenario) -> None:
        self.scenario = scenario
        self.points: Any = None

    def _points(self) -> Any:
        if self.points is None:
            self.points = [tuple(p) for p in _work(self.scenario).path]
        return self.points

    def __len__(self) -> int:
        return len(self._points())

    def __getitem__(self, i: int) -> Any:
        return self._points()[i]


class LazyPath(_Clocked):
    """Returns a path whose ``__len__`` / ``__getitem__`` search."""

    id = "clock.lazy_path"

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        return PlanResult(Status.SOLVED, path=_LazySequence(scenario), iterations=1,  # type: ignore[arg-type]
                          evaluations=1)


class _BurningText:
    def __str__(self) -> str:
        _burn()
        return "burnt"


class BurningMessage(_Clocked):
    """Searches in ``plan()`` but burns its busy work in its message's ``__str__``."""

    id = "clock.burning_message"

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        result = _search(scenario)
        return PlanResult(result.status, path=result.path, iterations=result.iterations,
                          evaluations=result.evaluations, message=_BurningText())  # type: ignore[arg-type]


_MEMO: dict[str, PlanResult] = {}


class WarmUpMemo(_Clocked):
    """Does the work the first time it sees a scenario id (the warm-up, when that sees the run's scenario), and
    answers from memory afterwards."""

    id = "clock.warm_up_memo"

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        if scenario.id not in _MEMO:
            _MEMO[scenario.id] = _work(scenario)
        return _MEMO[scenario.id]


class ProcSys(_Clocked):
    """Counts the files under ``/proc/sys`` it could open for writing (without writing); says how many."""

    id = "clock.proc_sys"

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        writable = []
        for root, _, files in os.walk("/proc/sys"):
            for name in files:
                path = os.path.join(root, name)
                try:
                    os.close(os.open(path, os.O_WRONLY))
                    writable.append(path)
                except OSError:
                    pass
        result = _search(scenario)
        return PlanResult(result.status, path=result.path, iterations=1, evaluations=1,
                          message=f"{len(writable)} writable: {' '.join(writable[:3])}")


class TrackerUnlink(_Clocked):
    """Registers ``victim`` (a host ``/dev/shm`` name) as leaked shared memory on the resource tracker's pipe, if its
    process holds one, so that the tracker would remove it when the harness exits."""

    id = "clock.tracker_unlink"
    params = {"victim": Param("/pathzoo-victim", "the shared memory name to have removed")}

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        from multiprocessing import resource_tracker

        fd = resource_tracker._resource_tracker._fd
        written = 0
        if fd is not None:
            try:
                os.write(fd, f"REGISTER:{self.victim}:shared_memory\n".encode())
                written = 1
            except OSError:
                pass
        result = _search(scenario)
        return PlanResult(result.status, path=result.path, iterations=1, evaluations=1,
                          message=f"registered on {written} pipes")


PLANNERS: list[type[Planner]] = [HonestWork, ForgedPlanned, ArrayWorks, LazyPath, BurningMessage, WarmUpMemo, ProcSys,
                                 TrackerUnlink]


@hookimpl
def pathzoo_register_planners() -> Sequence[type[Planner]]:
    return PLANNERS
