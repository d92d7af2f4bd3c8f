"""The worker side of a run: rebuild planner and scenario, time ``plan()``, report what came back.

:func:`execute_task` runs in whatever process the executor chose. It never
raises: a planner that raises (or calls ``sys.exit``) gives an outcome with
``crash`` set. It does not judge the result either; the harness validates
and measures it afterwards (:mod:`pathzoo.harness.judge`), in the parent
process, where the planner's code never ran.

Scenarios are cached per process (a small LRU, keyed by
:attr:`ScenarioSpec.cache_key`) and their shared geometry (blocked cells,
neighbourhood graph, clearance) is built when they are loaded, before any
clock starts, so no planner pays for it. If a planner modifies a cached
scenario's arrays, the run is flagged and the scenario is evicted.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib
import io
import math
import platform
import threading
import time
import traceback
from collections import OrderedDict
from dataclasses import dataclass, field
from datetime import datetime, timezone
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from pathzoo.core.results import HistoryPoint, PlanResult
from pathzoo.core.status import Status
from pathzoo.testing.warmup import warm_up

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario
    from pathzoo.harness.specs import RunTask, ScenarioSpec

__all__ = [
    "RunOutcome",
    "execute_task",
    "load_cached",
    "ensure_plugins",
    "HistoryRecorder",
    "SCENARIO_CACHE_SIZE",
    "SETUP_TIMEOUT_S",
]

SCENARIO_CACHE_SIZE = 4
"""Scenarios kept loaded per process (runs are ordered scenario by scenario)."""

SETUP_TIMEOUT_S = 900.0
"""Limit on a run's setup in a worker (plugins, planner, scenario, shared geometry), before ``plan()``."""

TRACEBACK_LINES = 12
"""Lines of traceback kept in a crash message."""


@dataclass(frozen=True)
class RunOutcome:
    """What happened in one run, before the harness judges it.

    Attributes
    ----------
    run_key : str
        The task's key.
    status : Status, optional
        The planner's own status; ``None`` when it did not return a PlanResult.
    path, times : ndarray, optional
        Copies of what the planner returned, as float64 when convertible.
    path_error : str
        Why the path could not be converted to a float array ("" if it could).
    iterations, evaluations : int
        The planner's counts.
    message : str
        The planner's message, or the crash description.
    wall_time_s, cpu_time_s : float
        Wall and process CPU time of ``plan()`` only.
    history : tuple of HistoryPoint
        Progress reports, timed by the harness (see :class:`HistoryRecorder`).
    crash : bool
        ``plan()`` raised, returned something else than a PlanResult, the setup
        failed or the worker process died.
    timed_out : bool
        The executor stopped the run at its hard limit.
    scenario_modified : bool
        The planner changed the scenario's arrays.
    versions : dict
        Versions of pathzoo, Python, numpy and the planner's distribution.
    started_at : str
        UTC ISO time the run started.
    """

    run_key: str
    status: Status | None = None
    path: np.ndarray | None = None
    times: np.ndarray | None = None
    path_error: str = ""
    iterations: int = 0
    evaluations: int = 0
    message: str = ""
    wall_time_s: float = math.nan
    cpu_time_s: float = math.nan
    history: tuple[HistoryPoint, ...] = ()
    crash: bool = False
    timed_out: bool = False
    scenario_modified: bool = False
    versions: dict[str, str] = field(default_factory=dict)
    started_at: str = ""


def utc_now() -> str:
    """The current UTC time in ISO format, to the millisecond."""
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")


def describe_exception(exc: BaseException) -> str:
    """``"Type: message"`` plus the last lines of the traceback."""
    head = f"{type(exc).__name__}: {exc}".splitlines()[0] if str(exc) else type(exc).__name__
    tail = traceback.format_exception(type(exc), exc, exc.__traceback__)
    lines = "".join(tail).rstrip().splitlines()[-TRACEBACK_LINES:]
    return head + "\n" + "\n".join(lines)


def _same_cost(a: float, b: float) -> bool:
    return a == b or (math.isnan(a) and math.isnan(b))


class HistoryRecorder:
    """The ``progress`` callback given to planners; the harness adds the time.

    A point is kept on the first report, whenever ``best_cost`` changes, and
    for the last report (unless it repeats the last kept one's counts).
    Reading the curve as "the best cost of the last kept point at or before
    this iteration" gives back exactly what the planner reported, while
    reports that change nothing cost no storage.
    """

    def __init__(self) -> None:
        self.t0 = time.perf_counter()
        self.points: list[HistoryPoint] = []
        self._last: HistoryPoint | None = None

    def __call__(self, iteration: int, evaluations: int, best_cost: float) -> None:
        point = HistoryPoint(int(iteration), int(evaluations), float(best_cost), time.perf_counter() - self.t0)
        last = self._last
        if last is None or not _same_cost(point.best_cost, last.best_cost):
            self.points.append(point)
        self._last = point

    def history(self) -> tuple[HistoryPoint, ...]:
        """The kept points, the last report included."""
        last = self._last
        if last is not None and (last.iteration, last.evaluations) != (self.points[-1].iteration,
                                                                       self.points[-1].evaluations):
            return (*self.points, last)
        return tuple(self.points)


# ------------------------------------------------------------------ plugins
_plugin_lock = threading.Lock()


def ensure_plugins(modules: tuple[tuple[str, str], ...]) -> None:
    """Import and register plugin modules the parent had registered by hand (idempotent)."""
    registry = quiet_registry()
    with _plugin_lock:
        for name, module in modules:
            if registry.pm.get_plugin(name) is None:
                registry.add_plugin(importlib.import_module(module), name)


def quiet_registry() -> Any:
    """The registry, discovered without repeating the parent's plugin warnings on stderr."""
    from pathzoo.plugins.manager import get_registry

    with contextlib.redirect_stderr(io.StringIO()):
        return get_registry()


# ---------------------------------------------------------------- scenarios
_scenarios: "OrderedDict[tuple[str, str, str, str], Scenario]" = OrderedDict()
_scenario_lock = threading.Lock()


def warm(scenario: "Scenario") -> "Scenario":
    """Build the scenario's shared geometry now, outside any timed region."""
    _ = scenario.blocked, scenario.graph, scenario.clearance
    return scenario


def load_cached(spec: "ScenarioSpec", size: int = SCENARIO_CACHE_SIZE) -> "Scenario":
    """Load a scenario once per process (LRU of ``size``), geometry warmed."""
    key = spec.cache_key
    with _scenario_lock:
        if key in _scenarios:
            _scenarios.move_to_end(key)
            return _scenarios[key]
    scenario = warm(spec.load())
    with _scenario_lock:
        _scenarios[key] = scenario
        while len(_scenarios) > size:
            _scenarios.popitem(last=False)
    return scenario


def evict(spec: "ScenarioSpec") -> None:
    """Forget a cached scenario."""
    with _scenario_lock:
        _scenarios.pop(spec.cache_key, None)


def scenario_digest(scenario: "Scenario") -> str:
    """Hash of the scenario's arrays, to detect planners that modify them."""
    h = hashlib.blake2b(digest_size=16)
    for arr in (scenario.occupancy, scenario.elevation, scenario.start, scenario.goal, scenario.blocked):
        if arr is not None:
            h.update(np.ascontiguousarray(arr).tobytes())
    return h.hexdigest()


# --------------------------------------------------------------------- runs
def _versions(task: "RunTask") -> dict[str, str]:
    import pathzoo
    from pathzoo.plugins.manager import get_registry

    entry = get_registry().get("planners", task.planner.id)
    out = {"pathzoo": pathzoo.__version__, "python": platform.python_version(), "numpy": np.__version__}
    if entry.distribution:
        out[entry.distribution] = entry.version
    return out


def _as_array(value: Any) -> tuple[np.ndarray | None, str]:
    if value is None:
        return None, ""
    try:
        return np.array(value, dtype=np.float64), ""
    except (TypeError, ValueError) as exc:
        return None, f"not a numeric array ({type(exc).__name__}: {exc})"


def execute_task(task: "RunTask", on_started: Callable[[], None] | None = None) -> RunOutcome:
    """Run one task in this process and report what happened; never raises.

    Parameters
    ----------
    task : RunTask
        The run.
    on_started : callable, optional
        Called once the planner and scenario are ready, just before the clock
        starts (the process executor starts the hard limit there).
    """
    started_at = utc_now()
    try:
        ensure_plugins(task.plugin_modules)
        planner = task.planner.build()
        if planner.version != task.planner_version:
            raise RuntimeError(
                f"{task.planner.id} is version {planner.version} in this worker, {task.planner_version} in the harness"
            )
        scenario = load_cached(task.scenario)
        versions = _versions(task)
        before = scenario_digest(scenario)
    except Exception as exc:
        return RunOutcome(task.run_key, message="run setup failed: " + describe_exception(exc), crash=True,
                          started_at=started_at)
    rng = np.random.default_rng(task.seed)
    recorder = HistoryRecorder()
    if on_started is not None:
        on_started()
    # inside the hard limit (a hanging planner still times out), outside planning time
    warm_up(planner, scenario.kind)
    crash: BaseException | None = None
    result: Any = None
    recorder.t0 = t0 = time.perf_counter()
    c0 = time.process_time()
    try:
        result = planner.plan(scenario, budget=task.budget, rng=rng, progress=recorder)
    except (Exception, SystemExit) as exc:
        crash = exc
    wall = time.perf_counter() - t0
    cpu = time.process_time() - c0
    modified = scenario_digest(scenario) != before
    if modified:
        evict(task.scenario)
    common: dict[str, Any] = dict(
        wall_time_s=wall, cpu_time_s=cpu, history=recorder.history(), scenario_modified=modified,
        versions=versions, started_at=started_at,
    )
    if crash is not None:
        return RunOutcome(task.run_key, message=describe_exception(crash), crash=True, **common)
    if not isinstance(result, PlanResult) or not isinstance(result.status, Status):
        what = type(result).__name__ if not isinstance(result, PlanResult) else f"status {result.status!r}"
        return RunOutcome(task.run_key, message=f"plan() returned {what}, not a PlanResult with a Status", crash=True,
                          **common)
    path, path_error = _as_array(result.path)
    times, times_error = _as_array(result.times)
    try:
        iterations, evaluations = int(result.iterations), int(result.evaluations)
    except (TypeError, ValueError):
        return RunOutcome(task.run_key, message="plan() returned non-integer iterations/evaluations", crash=True,
                          **common)
    return RunOutcome(
        task.run_key,
        status=result.status,
        path=path,
        times=times,
        path_error=path_error or (f"times {times_error}" if times_error else ""),
        iterations=iterations,
        evaluations=evaluations,
        message=str(result.message),
        **common,
    )

