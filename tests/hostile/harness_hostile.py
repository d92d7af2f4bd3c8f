"""Hostile planners for the harness tests: each attacks the judge, the clock, the store or later runs.

A plugin module (registered by hand in the test process, shipped to workers
by module name). Every planner does its attack and then claims ``SOLVED``
with a path that is *not* valid, unless its docstring says otherwise, so a
harness that is fooled stores ``solved``.
"""

from __future__ import annotations

import gc
import math
import time
from typing import Sequence

import numpy as np

from pathzoo import Budget, MovingObstacle, Param, Planner, PlanResult, Scenario, ScenarioEntry, Status, hookimpl
from pathzoo.core.planner import ProgressCallback

_REAL_CLOCK = time.perf_counter
_REAL_CPU = time.process_time
KINDS = frozenset({"grid2d", "terrain", "air3d", "dynamic"})


def wall_scenario() -> Scenario:
    """6 x 6 cells of 1 m, a wall in column 3 with a gap in row 0; start and goal on the bottom row."""
    occ = np.zeros((6, 6), bool)
    occ[1:, 3] = True
    return Scenario(id="hostile.wall", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 5.5), goal=(5.5, 5.5))


def crossing_scenario() -> Scenario:
    """An empty 8 x 3 street; an obstacle of radius 0.9 m parked on the straight line from start to goal."""
    return Scenario(id="hostile.crossing", kind="dynamic", occupancy=np.zeros((3, 8), bool), cell_size=1.0,
                    start=(0.5, 1.5), goal=(7.5, 1.5), moving_obstacles=(MovingObstacle(0.9, [(4.0, 1.5)], 0.0),))


def validator_modules() -> list:
    """Every module holding a ``validate_path``: the judge's import of it and the rules layer that defines it."""
    import importlib

    out = []
    for name in ("pathzoo.harness.judge", "pathzoo.rules", "pathzoo.rules.validation"):
        try:
            module = importlib.import_module(name)
        except ImportError:
            continue
        if hasattr(module, "validate_path"):
            out.append(module)
    return out


def straight(scenario: Scenario) -> np.ndarray:
    """Start to goal in a straight line: through the wall, or through the parked obstacle."""
    return np.array([scenario.start, scenario.goal], dtype=float)


class _Hostile(Planner):
    kinds = KINDS
    summary = "hostile test planner"

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        return self.attack(scenario) or PlanResult(Status.SOLVED, path=straight(scenario), iterations=1, evaluations=1)

    def attack(self, scenario: Scenario) -> PlanResult | None:
        raise NotImplementedError


class PatchValidator(_Hostile):
    """Replaces the validator everywhere it can reach, then claims a path through the wall."""

    id = "hostile.patch_validator"

    def attack(self, scenario: Scenario) -> None:
        class Fine:
            ok, reason = True, ""

            def __bool__(self) -> bool:
                return True

        for module in validator_modules():
            module.validate_path = lambda *a, **k: Fine()


class DropObstacles(_Hostile):
    """Removes the moving obstacles, replaces the vehicle, then drives through the obstacle."""

    id = "hostile.drop_obstacles"

    def attack(self, scenario: Scenario) -> None:
        from pathzoo import VehicleModel

        object.__setattr__(scenario, "moving_obstacles", ())
        object.__setattr__(scenario, "vehicle", VehicleModel(cruise_speed=1000.0))


class ReplaceGraph(_Hostile):
    """Swaps ``scenario.graph`` for the graph of an empty map (so later grid planners cut through walls)."""

    id = "hostile.replace_graph"

    def attack(self, scenario: Scenario) -> None:
        from pathzoo.grid.graph import build_graph

        empty = Scenario(id=scenario.id, kind=scenario.kind, occupancy=np.zeros_like(scenario.occupancy),
                         cell_size=scenario.cell_size, start=scenario.start, goal=scenario.goal)
        scenario.__dict__["graph"] = build_graph(empty)
        scenario.__dict__["blocked"] = empty.blocked


class PatchClass(_Hostile):
    """Monkeypatches ``Scenario.graph`` on the class: every later planner in this process sees an empty map."""

    id = "hostile.patch_class"

    def attack(self, scenario: Scenario) -> None:
        from pathzoo.grid.graph import build_graph

        empty = Scenario(id=scenario.id, kind=scenario.kind, occupancy=np.zeros_like(scenario.occupancy),
                         cell_size=scenario.cell_size, start=scenario.start, goal=scenario.goal)
        fake = build_graph(empty)
        Scenario.graph = property(lambda self: fake)  # type: ignore[assignment, method-assign]


class PatchClock(_Hostile):
    """Freezes ``time.perf_counter`` and ``time.process_time``, then works for 0.4 s (an honest answer)."""

    id = "hostile.patch_clock"

    def attack(self, scenario: Scenario) -> PlanResult:
        from pathzoo.grid.reference import reference_path

        real = _REAL_CLOCK
        end = real() + 0.4
        while real() < end:
            pass
        time.perf_counter = lambda: 1.0  # type: ignore[assignment]
        time.process_time = lambda: 1.0  # type: ignore[assignment]
        ref = reference_path(scenario)
        return PlanResult(Status.SOLVED, path=ref.path.copy(), iterations=1, evaluations=1)


CLOCK_HOLDERS = ("pathzoo.harness.worker", "pathzoo.harness.history", "pathzoo.harness.executors.process",
                 "pathzoo.harness.executors.run_clocks", "pathzoo.harness.executors.cluster")
"""Modules whose import-bound clocks (``_clock``, ``_cpu``, ``process_cpu_time``) :class:`PatchAllClocks` freezes."""


class PatchAllClocks(_Hostile):
    """Burns 0.3 s of CPU, then freezes every clock it can reach: ``time``, pathzoo's own, psutil's (an honest answer)."""

    id = "hostile.patch_all_clocks"

    def attack(self, scenario: Scenario) -> PlanResult:
        import importlib
        from types import SimpleNamespace

        import psutil

        from pathzoo.grid.reference import reference_path

        end = _REAL_CPU() + 0.3
        while _REAL_CPU() < end:
            pass
        time.perf_counter = time.process_time = lambda: 1.0  # type: ignore[assignment]
        for name in CLOCK_HOLDERS:
            module = importlib.import_module(name)
            for attr, fake in (("_clock", lambda: 1.0), ("_cpu", lambda: 1.0), ("process_cpu_time", lambda pid: 1.0)):
                if hasattr(module, attr):
                    setattr(module, attr, fake)
        psutil.Process.cpu_times = lambda self: SimpleNamespace(user=0.0, system=0.0)  # type: ignore[method-assign]
        ref = reference_path(scenario)
        return PlanResult(Status.SOLVED, path=ref.path.copy(), iterations=1, evaluations=1)


class SpamStarted(_Hostile):
    """Finds its worker's pipe and keeps announcing a fresh start, so the hard limit never comes."""

    id = "hostile.spam_started"

    def attack(self, scenario: Scenario) -> None:
        from multiprocessing.connection import Connection

        conns = [o for o in gc.get_objects() if isinstance(o, Connection)]
        while True:
            for conn in conns:
                try:
                    conn.send_bytes(b"S")
                except Exception:  # noqa: BLE001
                    pass
            time.sleep(0.05)


class Counts(_Hostile):
    """Reports absurd counts (``how``): ``2**70`` iterations, NaN evaluations, or a string."""

    id = "hostile.counts"
    params = {"how": Param("huge", "which lie", choices=("huge", "nan", "text", "negative"))}

    def attack(self, scenario: Scenario) -> PlanResult:
        from pathzoo.grid.reference import reference_path

        value = {"huge": 2**70, "nan": math.nan, "text": "many", "negative": -5}[self.how]
        path = reference_path(scenario).path.copy()
        return PlanResult(Status.SOLVED, path=path, iterations=value, evaluations=value)  # type: ignore[arg-type]


class Message(_Hostile):
    """A message whose ``__str__`` raises ``SystemExit`` (``exit``) or that is huge with lone surrogates (``huge``)."""

    id = "hostile.message"
    params = {"how": Param("exit", "which message", choices=("exit", "huge"))}

    def attack(self, scenario: Scenario) -> PlanResult:
        class Exits:
            def __str__(self) -> str:
                raise SystemExit(0)

        message = Exits() if self.how == "exit" else "\ud800" * 10 + "x" * 10_000_000
        return PlanResult(Status.FAILED, message=message)  # type: ignore[arg-type]


class ExitAlways(_Hostile):
    """Raises ``SystemExit`` on every call, the untimed warm-up included, or ``KeyboardInterrupt`` (``how``)."""

    id = "hostile.exit_always"
    params = {"how": Param("exit", "what to raise", choices=("exit", "base"))}

    def attack(self, scenario: Scenario) -> None:
        if self.how == "exit":
            raise SystemExit(0)

        class Odd(BaseException):
            pass

        raise Odd("not an Exception")


class HugePath(_Hostile):
    """A path of ``points`` points zig-zagging in the free part of the wall scenario (claimed solved)."""

    id = "hostile.huge_path"
    params = {"points": Param(2_000_000, "number of points", low=2)}

    def attack(self, scenario: Scenario) -> PlanResult:
        n = self.points
        path = np.empty((n, 2))
        path[:, 0] = 0.5 + (np.arange(n) % 2) * 0.5
        path[:, 1] = 5.5
        path[-1] = scenario.goal
        return PlanResult(Status.SOLVED, path=path)


class Flaky(_Hostile):
    """Honest, but crashes while the file ``marker`` exists (a missing dependency, fixed later)."""

    id = "hostile.flaky"
    params = {"marker": Param("", "file whose existence makes it crash")}

    def attack(self, scenario: Scenario) -> PlanResult:
        import os

        from pathzoo.grid.reference import reference_path

        if os.path.exists(self.marker):
            raise ImportError("No module named 'pyswarms'")
        return PlanResult(Status.SOLVED, path=reference_path(scenario).path.copy(), iterations=1, evaluations=1)


def observe(scenario: Scenario) -> str:
    """What a planner sees of the scenario: the numbers an attack on it would change."""
    graph = scenario.graph
    return (f"occupied {int(scenario.occupancy.sum())} blocked {int(scenario.blocked.sum())} edges {graph.n_edges} "
            f"length {float(graph.length.sum())!r} energy {float(graph.energy.sum())!r} "
            f"clearance {float(scenario.clearance.sum())!r} {scenario.clearance.shape} "
            f"speed {scenario.vehicle.cruise_speed!r} metadata {sorted(scenario.metadata)}")


def _write_zeros(arr: np.ndarray) -> None:
    import ctypes

    ctypes.memset(arr.ctypes.data, 0, arr.nbytes)


def _attack_ctypes_flags(arr: np.ndarray) -> None:
    """Set the array's WRITEABLE flag in its C struct (numpy would refuse), then write through numpy."""
    import ctypes

    flags = ctypes.c_int.from_address(id(arr) + 64)  # PyArrayObject: refcount, type, data, nd, dims, strides, base, descr
    flags.value |= 0x0400  # NPY_ARRAY_WRITEABLE
    assert arr.flags.writeable
    arr[...] = False


def _attack_mprotect(arr: np.ndarray) -> None:
    """Ask the kernel to make the array's pages writable, then write through a raw pointer."""
    import ctypes
    import mmap

    libc = ctypes.CDLL(None, use_errno=True)
    start = arr.ctypes.data // mmap.PAGESIZE * mmap.PAGESIZE
    libc.mprotect(ctypes.c_void_p(start), ctypes.c_size_t(arr.ctypes.data + arr.nbytes - start), 3)
    _write_zeros(arr)


def _attack_proc_mem(arr: np.ndarray) -> None:
    with open("/proc/self/mem", "r+b", buffering=0) as mem:
        mem.seek(arr.ctypes.data)
        mem.write(bytes(arr.nbytes))


def _rebind_occupancy(s: Scenario) -> None:
    object.__setattr__(s, "occupancy", np.zeros_like(s.occupancy))
    s.__dict__["blocked"] = np.zeros_like(s.blocked)


def _set_writeable(s: Scenario) -> None:
    s.blocked.flags.writeable = True
    s.blocked[...] = False


SCENARIO_ATTACKS = {
    "setflags": _set_writeable,
    "copyto": lambda s: np.copyto(s.graph.energy, 0.0),
    "inplace": lambda s: s.graph.energy.__imul__(0.0),
    "rebind": _rebind_occupancy,
    "graph_array": lambda s: object.__setattr__(s.graph, "length", np.zeros_like(s.graph.length)),
    "metadata": lambda s: s.metadata.__setitem__("poison", 1),
    "vehicle": lambda s: object.__setattr__(s.vehicle, "cruise_speed", 1000.0),
    "shape": lambda s: setattr(s.clearance, "shape", (-1,)),
    "ctypes": lambda s: _write_zeros(s.blocked),
    "ctypes_flags": lambda s: _attack_ctypes_flags(s.blocked),
    "mprotect": lambda s: _attack_mprotect(s.blocked),
    "proc_mem": lambda s: _attack_proc_mem(s.blocked),
}
"""Ways to change the cached scenario that later runs of a worker see (``hostile.overwrite``'s ``how``)."""

ATTACKED: set[str] = set()
"""The attacks made in this process (each planner attacks once, in its first run)."""


class Overwrite(Planner):
    """Reports what it sees of the scenario (as a ``FAILED`` run's message), attacking it in its first run in a process.

    The harness's untimed warm-up (on a twin of the scenario) is not attacked.

    A harness that lets the attack through silently stores a later
    ``failed`` run whose message differs from the first one's.
    """

    id = "hostile.overwrite"
    kinds = KINDS
    summary = "changes the cached scenario once"
    params = {"how": Param("setflags", "the attack", choices=tuple(SCENARIO_ATTACKS))}

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        from pathzoo.core.warmup import WARM_UP_BUDGET

        seen = observe(scenario)
        if self.how not in ATTACKED and budget.iterations != WARM_UP_BUDGET.iterations:  # not the warm-up's twin
            ATTACKED.add(self.how)
            SCENARIO_ATTACKS[self.how](scenario)
        return PlanResult(Status.FAILED, iterations=1, evaluations=1, message=seen)


PLANNERS = [PatchValidator, DropObstacles, ReplaceGraph, PatchClass, PatchClock, SpamStarted, Counts, Message,
            ExitAlways, HugePath, Flaky, PatchAllClocks, Overwrite]


@hookimpl
def pathzoo_register_planners() -> Sequence[type[Planner]]:
    return PLANNERS


@hookimpl
def pathzoo_register_scenarios() -> Sequence[ScenarioEntry]:
    return [
        ScenarioEntry("hostile.wall", "wall with a gap", wall_scenario, "grid2d"),
        ScenarioEntry("hostile.crossing", "obstacle parked on the straight line", crossing_scenario, "dynamic"),
    ]
