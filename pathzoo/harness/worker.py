"""The worker side of a run: rebuild planner and scenario, run ``plan()``, report what came back.

:func:`execute_task` runs in whatever process the executor chose. It never
raises (``SystemExit`` and every other ``BaseException`` from the planner,
its warm-up or its message's ``__str__`` included): anything that goes wrong
gives an outcome with ``crash`` set. It does not judge the result either;
the harness does (:mod:`pathzoo.harness.judge`), in a judge process where no
planner code ever ran, on a scenario that process loaded itself.

Scenarios are cached per process (a small LRU, keyed by
:attr:`ScenarioSpec.cache_key`) and their shared geometry (blocked cells,
neighbourhood graph, clearance, every cached property) is built when they
are loaded, before any clock starts, so no planner pays for it. Its arrays
are then moved into sealed read-only memory (:mod:`pathzoo.harness.sealed`),
so no write can change them (numpy refuses, a raw write faults), and after
each run the worker checks what a planner could still change: a planner
that rebound or replaced any part of the scenario, or changed a small
field, is flagged (``scenario_modified``, judged ``invalid``) and the
scenario is evicted, so the next run loads a fresh one.
Monkeypatching is caught by :mod:`pathzoo.harness.tamper` and makes the
executor replace the worker.

The planning clocks start just before the planner is built (its
constructor is planning work) and end when ``plan()`` returns, before the
scenario's check and any other harness work (``docs/timing.md``). The times
measured here (``time.perf_counter`` and ``time.process_time`` inside the
planner's process) are only a fallback: the process and Dask executors time
runs with their own clocks, outside this process. A budget with a clock
limit gets a clock stop (:mod:`pathzoo.harness.clock_stop`): the executor's
shared one, or one read in this process.
"""

from __future__ import annotations

import contextlib
import importlib
import io
import math
import platform
import threading
import time
import traceback
from collections import OrderedDict
from dataclasses import dataclass, field, replace
from datetime import datetime, timezone
from typing import TYPE_CHECKING, Any, Callable, TypeVar

import numpy as np

from pathzoo.core.budget import ClockStop
from pathzoo.core.errors import ExternalPlannerError
from pathzoo.core.results import HistoryPoint, PlanResult
from pathzoo.core.status import Status
from pathzoo.harness.bounds import bound_outcome, bound_text
from pathzoo.harness.clock_stop import InProcessClockStop
from pathzoo.harness.digest import warm
from pathzoo.harness.provenance import PEAK_RSS_KEY, host, loaded_distributions, peak_rss_mb, reset_peak_rss
from pathzoo.harness.sealed import ScenarioSeal, seal

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario
    from pathzoo.harness.specs import RunTask, ScenarioSpec

__all__ = [
    "RunOutcome",
    "execute_task",
    "load_cached",
    "keep_payload",
    "ensure_plugins",
    "HistoryRecorder",
    "SCENARIO_CACHE_SIZE",
    "SETUP_TIMEOUT_S",
    "Report",
    "warm_up_for",
    "as_array",
    "message_text",
    "stopped_by_of",
    "provenance",
    "versions_of",
    "describe_exception",
    "utc_now",
]

SCENARIO_CACHE_SIZE = 4
"""Scenarios kept loaded per process (runs are ordered scenario by scenario)."""

SETUP_TIMEOUT_S = 900.0
"""Limit on a run's setup in a worker (plugins, planner, scenario, shared geometry), before ``plan()``."""

_clock = time.perf_counter  # bound at import, so a planner that patches the time module changes no timing
_cpu = time.process_time

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
        Wall and CPU time of building the planner and its ``plan()`` call.
    stopped_by : str
        The limit that ended the run (:data:`pathzoo.core.budget.STOP_REASONS`);
        the process executor decides the clock stops itself.
    sandboxed : bool
        The planner ran in an OS sandbox (:mod:`pathzoo.harness.sandbox`); set
        by the executor that supervised it, never by the planner's process.
    history : tuple of HistoryPoint
        Progress reports, timed by the harness (see :class:`HistoryRecorder`).
    crash : bool
        ``plan()`` raised, returned something else than a PlanResult, the setup
        failed or the worker process died.
    timed_out : bool
        The executor stopped the run at its hard limit.
    scenario_modified : bool
        The planner rebound, replaced or changed part of the scenario
        (:meth:`~pathzoo.harness.sealed.ScenarioSeal.intact`).
    versions : dict
        Versions of pathzoo, Python, numpy, the planner's distribution and the
        libraries loaded in the worker, with the CPU, core count and the run's
        peak RSS in MiB (:mod:`pathzoo.harness.provenance`).
    started_at : str
        UTC ISO time the run started.
    tainted : bool
        The planner rebound module attributes in its process
        (:mod:`pathzoo.harness.tamper`); the executor must not reuse that process.
    bounds_error : str
        Why a planner-chosen value is out of bounds (:mod:`pathzoo.harness.bounds`);
        the run is judged ``invalid`` with this reason.
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
    stopped_by: str = "none"
    sandboxed: bool = False
    history: tuple[HistoryPoint, ...] = ()
    crash: bool = False
    timed_out: bool = False
    scenario_modified: bool = False
    versions: dict[str, str] = field(default_factory=dict)
    started_at: str = ""
    tainted: bool = False
    bounds_error: str = ""


def utc_now() -> str:
    """The current UTC time in ISO format, to the millisecond."""
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")


def describe_exception(exc: BaseException) -> str:
    """``"Type: message"`` plus the last lines of the traceback.

    An :class:`~pathzoo.core.errors.ExternalPlannerError` is its own
    report (one line naming the planner and the cause, then the program's
    standard error): the bridge's traceback would add nothing.
    """
    if isinstance(exc, ExternalPlannerError):
        return str(exc)
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
        self.t0 = _clock()
        self.points: list[HistoryPoint] = []
        self._last: HistoryPoint | None = None

    def __call__(self, iteration: int, evaluations: int, best_cost: float) -> None:
        point = HistoryPoint(int(iteration), int(evaluations), float(best_cost), _clock() - self.t0)
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


def ensure_plugins(modules: tuple[tuple[str, str], ...], *, missing_ok: bool = False) -> None:
    """Import and register plugin modules the parent had registered by hand (idempotent).

    With ``missing_ok`` a module that cannot be imported here (e.g. one made
    at run time in the parent's ``__main__``) is skipped: the judge needs only
    the scenario and metric plugins, and fails later, naming what is missing,
    if one of those was in it.
    """
    registry = quiet_registry()
    with _plugin_lock:
        for name, module in modules:
            if registry.pm.get_plugin(name) is None:
                try:
                    registry.add_plugin(importlib.import_module(module), name)
                except ImportError:
                    if not missing_ok:
                        raise


def quiet_registry() -> Any:
    """The registry, discovered without repeating the parent's plugin warnings on stderr."""
    from pathzoo.plugins.manager import get_registry

    with contextlib.redirect_stderr(io.StringIO()):
        return get_registry()


# ---------------------------------------------------------------- scenarios
_scenarios: "OrderedDict[tuple[str, str, str, str], tuple[Scenario, ScenarioSeal]]" = OrderedDict()
_scenario_lock = threading.Lock()
_payloads: dict[str, bytes] = {}


def keep_payload(spec: "ScenarioSpec") -> None:
    """Keep the pickled bytes of a scenario object sent in full, for the specs sent later by reference.

    The processes the harness sends objects to by reference (its workers
    and the judge, :meth:`~pathzoo.harness.specs.ScenarioSpec.by_reference`)
    call it on receipt of each task, before any planner code runs, whatever
    fails after. The bytes are kept for the life of the process (bytes
    cannot be changed in place, so a planner cannot alter what later runs
    load).
    """
    if spec.payload:
        _payloads.setdefault(spec.digest, spec.payload)


def load_cached(spec: "ScenarioSpec", size: int = SCENARIO_CACHE_SIZE) -> "tuple[Scenario, ScenarioSeal]":
    """Load a scenario once per process (LRU of ``size``), geometry warmed and arrays sealed; returns it with its seal.

    A scenario object sent by reference is loaded from the bytes
    :func:`keep_payload` kept.
    """
    def make() -> "tuple[Scenario, ScenarioSeal]":
        scenario = _load(spec)
        return scenario, seal(scenario)

    return _lru(_scenarios, spec.cache_key, size, make)


_T = TypeVar("_T")


def _lru(cache: "OrderedDict[Any, _T]", key: Any, size: int, make: Callable[[], _T]) -> _T:
    """``cache[key]``, made by ``make`` (outside the lock) when missing; entries beyond the ``size`` most recent go."""
    with _scenario_lock:
        if key in cache:
            cache.move_to_end(key)
            return cache[key]
    value = make()
    with _scenario_lock:
        cache[key] = value
        while len(cache) > size:
            cache.popitem(last=False)
    return value


def _load(spec: "ScenarioSpec") -> "Scenario":
    """Load a scenario with its shared geometry built (an object sent by reference from the kept bytes)."""
    if spec.source == "object" and not spec.payload and spec.digest in _payloads:
        spec = replace(spec, payload=_payloads[spec.digest])
    return warm(spec.load())


def evict(spec: "ScenarioSpec") -> None:
    """Forget a cached scenario."""
    with _scenario_lock:
        _scenarios.pop(spec.cache_key, None)


# ------------------------------------------------------------------ warm-up
_twins: "OrderedDict[tuple[str, str, str, str], Scenario]" = OrderedDict()
_warmed_for: set[tuple[str, str, tuple[str, str, str, str]]] = set()
_TWINS = 2
"""Warm-up twins of scenarios kept per process."""


def _twin(spec: "ScenarioSpec") -> "Scenario":
    """A second copy of a scenario, loaded and sealed as the runs' copy is (same types and flags), for warm-ups only."""
    def make() -> "Scenario":
        scenario = _load(spec)
        seal(scenario)  # the twin's arrays go where the run's do: numba meets the same array types
        return scenario

    return _lru(_twins, spec.cache_key, _TWINS, make)


def warm_up_for(task: "RunTask", planner: Any) -> None:
    """Warm ``planner`` up on a twin of the task's scenario, once per configuration and scenario in this process.

    The twin is loaded the way the measured run's scenario is, so the warm-up
    meets the same argument types and compiles every numba specialisation
    the run needs (:func:`pathzoo.core.warmup.warm_up`); being another
    object, it keeps whatever the planner caches on a scenario away from
    the measured runs. Errors are left to the measured run.

    The warm-up has the run's own wall limit when the run has one (a
    program planner, :mod:`pathzoo.plugins.external`, sets its deadline from
    it, and under the inline executor nothing else would stop a program
    that never answers); otherwise only the count limit of
    :data:`~pathzoo.core.warmup.WARM_UP_BUDGET`.
    """
    from pathzoo.core.warmup import WARM_UP_BUDGET, warm_up  # not at the top: imported before numba is needed

    key = (task.planner.id, task.params_hash, task.scenario.cache_key)
    with _scenario_lock:
        if key in _warmed_for:
            return
        _warmed_for.add(key)
    budget = WARM_UP_BUDGET if task.budget.time_s is None else replace(WARM_UP_BUDGET, time_s=task.budget.time_s)
    warm_up(planner, task.scenario.kind, budget, on=_twin(task.scenario))


# --------------------------------------------------------------------- runs
def versions_of(task: "RunTask") -> dict[str, str]:
    from pathzoo.plugins.manager import get_registry
    from pathzoo.version import installed_version

    out = {"pathzoo": installed_version(), "python": platform.python_version(), "numpy": np.__version__}
    entry = get_registry().planners.get(task.planner.id)
    if entry is not None and entry.distribution:
        out[entry.distribution] = entry.version
    return out


def provenance(versions: dict[str, str]) -> dict[str, str]:
    """``versions`` with the host, the run's peak RSS and the libraries loaded by now (after ``plan()``)."""
    return {**versions, **host(), PEAK_RSS_KEY: f"{peak_rss_mb():.1f}", **loaded_distributions()}


def as_array(value: Any) -> tuple[np.ndarray | None, str]:
    if value is None:
        return None, ""
    try:
        return np.array(value, dtype=np.float64), ""
    except Exception as exc:  # noqa: BLE001 - any object a planner returns
        return None, f"not a numeric array ({type(exc).__name__}: {exc})"


Report = Callable[[str], None]
"""Callback through which :func:`execute_task` announces ``"started"`` (setup done), ``"planning"`` and ``"planned"``."""


def message_text(value: Any) -> str:
    """The planner's message as text; a ``__str__`` that fails or exits gives a note instead."""
    try:
        return bound_text(str(value))
    except BaseException as exc:  # noqa: BLE001 - SystemExit from a hostile __str__ included
        return f"(message could not be converted to text: {type(exc).__name__})"


def execute_task(task: "RunTask", report: Report | None = None, *, interruptible: bool = False,
                 stop: ClockStop | None = None) -> RunOutcome:
    """Run one task in this process and report what happened; never raises.

    Parameters
    ----------
    task : RunTask
        The run.
    report : callable, optional
        Called with ``"started"`` once the planner and scenario are ready (the
        hard limit starts there, before the warm-up), with ``"planning"`` just
        before the measured planner is built (the planning clocks start
        there) and with ``"planned"`` as soon as ``plan()`` returns (they end
        there). It may block until the executor has read its clocks.
    interruptible : bool
        Let ``KeyboardInterrupt`` through (the inline executor, where Ctrl-C is
        the user's); otherwise it is a crash like any other exception.
    stop : ClockStop, optional
        The executor's clock stop for a budget with a clock limit (default:
        an :class:`~pathzoo.harness.clock_stop.InProcessClockStop`).
    """
    try:
        return bound_outcome(_execute(task, report or (lambda event: None), stop))
    except KeyboardInterrupt:
        if interruptible:
            raise
        return RunOutcome(task.run_key, crash=True, message="KeyboardInterrupt raised in the run")
    except BaseException as exc:  # noqa: BLE001 - whatever a planner raises, the run is an outcome
        return RunOutcome(task.run_key, crash=True, message=message_text(describe_exception(exc)))


def stopped_by_of(task: "RunTask", stop: ClockStop | None, result: Any) -> str:
    """The clock stop reported to the planner, else the count limit its result reached, else ``"none"``."""
    clock = None if stop is None else stop.reason()
    if clock is not None:
        return clock
    if isinstance(result, PlanResult):
        try:
            return task.budget.count_reached(int(result.iterations), int(result.evaluations)) or "none"
        except BaseException:  # noqa: BLE001 - counts of any type; bound_outcome reports them
            return "none"
    return "none"


def _execute(task: "RunTask", report: Report, stop: ClockStop | None) -> RunOutcome:
    started_at = utc_now()
    try:
        ensure_plugins(task.plugin_modules)
        planner = task.build_planner()  # for the version check and the warm-up; the measured run builds its own
        if planner.version != task.planner_version:
            raise RuntimeError(
                f"{task.planner.id} is version {planner.version} in this worker, {task.planner_version} in the harness"
            )
        scenario, sealed = load_cached(task.scenario)
        versions = versions_of(task)
    except Exception as exc:
        return RunOutcome(task.run_key, message="run setup failed: " + describe_exception(exc), crash=True,
                          started_at=started_at)
    rng = np.random.default_rng(task.seed)
    recorder = HistoryRecorder()
    report("started")
    crash: BaseException | None = None
    result: Any = None
    t0 = c0 = math.nan
    budget = task.budget
    try:
        # inside the hard limit (a hanging planner still times out), outside planning time
        warm_up_for(task, planner)
        reset_peak_rss()
        report("planning")
        recorder.t0 = t0 = _clock()
        c0 = _cpu()
        if budget.timed:
            stop = stop if stop is not None else InProcessClockStop(budget)
            budget = replace(budget, stop=stop)
        planner = task.build_planner()  # measured and limited: work done in a constructor is planning work
        result = planner.plan(scenario, budget=budget, rng=rng, progress=recorder)
    except KeyboardInterrupt:
        raise
    except BaseException as exc:  # noqa: BLE001 - SystemExit included
        crash = exc
    wall = _clock() - t0  # NaN when plan() never started
    cpu = _cpu() - c0
    if not math.isnan(t0):
        report("planned")
    stopped_by = stopped_by_of(task, budget.stop, result)
    versions = provenance(versions)
    modified = not sealed.intact()
    if modified:
        evict(task.scenario)
    common: dict[str, Any] = dict(
        wall_time_s=wall, cpu_time_s=cpu, stopped_by=stopped_by, history=recorder.history(), scenario_modified=modified,
        versions=versions, started_at=started_at,
    )
    if crash is not None:
        return RunOutcome(task.run_key, message=message_text(describe_exception(crash)), crash=True, **common)
    if not isinstance(result, PlanResult) or not isinstance(result.status, Status):
        what = type(result).__name__ if not isinstance(result, PlanResult) else f"status {type(result.status)}"
        return RunOutcome(task.run_key, message=f"plan() returned {what}, not a PlanResult with a Status", crash=True,
                          **common)
    path, path_error = as_array(result.path)
    times, times_error = as_array(result.times)
    return RunOutcome(
        task.run_key,
        status=result.status,
        path=path,
        times=times,
        path_error=path_error or (f"times {times_error}" if times_error else ""),
        iterations=result.iterations,
        evaluations=result.evaluations,
        message=message_text(result.message),
        **common,
    )
