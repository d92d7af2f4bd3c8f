"""A warmed worker that forks a fresh child for every run: the child plans, converts and exits.

A worker of the process executor (:mod:`pathzoo.harness.executors.process`)
runs one planner configuration on one scenario kind. It is a *zygote*: told
to warm up (:class:`WarmUp`, which names the configuration and the kind and
nothing of any run), it imports the planner, builds it and warms it up on
synthetic scenarios of that kind (:mod:`pathzoo.harness.synthetic`). Only
then does the harness send it runs. For each, it loads the scenario
(cached, sealed), announces the hand-over (``P``) and forks a child that

- closes every descriptor it inherited but the write end of its result
  pipe (no control socket, no resource-tracker pipe, no life pipe), asks
  the kernel to kill it when the zygote dies, and builds the planner and
  calls ``plan()``;
- converts whatever came back into plain data (the path and times as
  float64 arrays, the message as text, the counts as integers, the
  history), checks the scenario's seal, encodes the outcome
  (:mod:`pathzoo.harness.wire`), writes it to the pipe and exits.

The zygote reads the pipe until the child has exited (its ``pidfd``), reaps
it with ``wait4``, and only then sends the outcome to the harness: the run
ends when the child is gone, never on a frame the planner wrote. The
harness charges each run the CPU of the worker's whole process tree and
cgroup from the end of the worker's previous run (or of its warm-up) to the
end of this one (:class:`~pathzoo.harness.cpu_clock.ChargedCpu`), so
conversion is charged with ``plan()``, and so is anything planner code left
to run in the zygote. Nothing the planner computed in one run can serve a
later one: each child starts from the zygote's state, which no run changes,
and the warm-up ran before any run was known in the process.

Planner code runs in the zygote only while it imports the plugin, builds
the planner and warms it up. What it might leave behind to run later in the
zygote (a thread, a trace or profile hook, a garbage collector callback, a
signal handler or timer, an import hook) is checked after the warm-up
(:class:`Residue`); a zygote with any of it runs no planner. New audit
hooks are refused from the start (:func:`refuse_audit_hooks`), and the
zygote is non-dumpable (:func:`undumpable`): a run's child cannot trace it
or write its memory.
"""

from __future__ import annotations

import ctypes
import gc
import math
import os
import select
import signal
import sys
import threading
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from pathzoo.core.budget import ClockStop
from pathzoo.core.results import PlanResult
from pathzoo.core.status import Status
from pathzoo.harness.bounds import bound_outcome
from pathzoo.harness.history import HistoryRecorder
from pathzoo.harness.outcome import RunOutcome, as_array, describe_exception, message_text, utc_now
from pathzoo.harness.plugin_loading import ensure_plugins
from pathzoo.harness.provenance import provenance, reset_peak_rss, versions_of
from pathzoo.harness.scenario_cache import load_cached
from pathzoo.harness.worker import stopped_by_of

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask

__all__ = ["Zygote", "WarmUp", "Residue", "refuse_audit_hooks", "drop_resource_tracker", "undumpable"]

_READ_CHUNK = 1 << 20


def refuse_audit_hooks() -> None:
    """Refuse every later ``sys.addaudithook`` in this process and its children (a hook would see every file opened)."""

    def hook(event: str, args: Any) -> None:
        if event == "sys.addaudithook":
            raise RuntimeError("pathzoo workers accept no audit hook")  # RuntimeError: the addition is dropped

    sys.addaudithook(hook)


def undumpable() -> None:
    """Make this process (and its children) non-dumpable: no process without ``CAP_SYS_PTRACE`` may trace it or
    read or write its memory, so a run's child cannot change what its zygote reports."""
    try:
        ctypes.CDLL(None, use_errno=True).prctl(4, 0, 0, 0, 0)  # PR_SET_DUMPABLE
    except (OSError, AttributeError):
        pass


def drop_resource_tracker() -> None:
    """Close the pipe to the harness's :mod:`multiprocessing` resource tracker, inherited at start.

    Whatever is registered on it is removed by the tracker when the harness
    exits, so a planner holding it could have any shared memory name on the
    host removed. Anything in this process that needs a tracker later starts
    its own, inside the sandbox.
    """
    from multiprocessing import resource_tracker

    tracker: Any = resource_tracker._resource_tracker
    if tracker._fd is not None:
        try:
            os.close(tracker._fd)
        except OSError:
            pass
        tracker._fd, tracker._pid = None, None


def _signal_handlers() -> tuple[Any, ...]:
    out = []
    for sig in signal.valid_signals():
        try:
            out.append(signal.getsignal(sig))
        except (ValueError, OSError):
            out.append(None)
    return tuple(out)


@dataclass(frozen=True)
class Residue:
    """What planner code could leave running in a process: compare :meth:`now` before and after it ran."""

    threads: frozenset[int]
    hooks: tuple[Any, ...]
    gc_callbacks: tuple[int, ...]
    handlers: tuple[Any, ...]
    timers: tuple[tuple[float, float], ...]
    importers: tuple[int, ...]

    @classmethod
    def now(cls) -> "Residue":
        """The state of this process."""
        return cls(
            threads=frozenset(t.ident or 0 for t in threading.enumerate()),
            hooks=(sys.gettrace(), sys.getprofile(), threading.gettrace(), threading.getprofile()),
            gc_callbacks=tuple(id(c) for c in gc.callbacks),
            handlers=_signal_handlers(),
            timers=tuple(signal.getitimer(t) for t in (signal.ITIMER_REAL, signal.ITIMER_VIRTUAL, signal.ITIMER_PROF)),
            importers=tuple(id(x) for x in (*sys.meta_path, *sys.path_hooks)),
        )

    def left(self, since: "Residue") -> list[str]:
        """What is here that was not in ``since``."""
        out = []
        if self.threads - since.threads:
            out.append(f"{len(self.threads - since.threads)} thread(s)")
        if self.hooks != since.hooks:
            out.append("a trace or profile hook")
        if self.gc_callbacks != since.gc_callbacks:
            out.append("a garbage collector callback")
        if self.handlers != since.handlers:
            out.append("a signal handler")
        if self.timers != since.timers:
            out.append("an interval timer")
        if self.importers != since.importers:
            out.append("an import hook")
        return out


@dataclass(frozen=True)
class WarmUp:
    """The order to warm a zygote up: a run of its configuration whose scenario is only a kind.

    Attributes
    ----------
    task : RunTask
        The configuration (planner, parameters, plugins, budget) with a
        scenario spec that names nothing but the kind (:meth:`of`).
    """

    task: "RunTask"

    @classmethod
    def of(cls, task: "RunTask") -> "WarmUp":
        """The warm-up order of ``task``'s configuration: nothing of its run or scenario but the scenario kind."""
        from pathzoo.harness.specs import ScenarioSpec

        return cls(replace(task, run_key="", experiment="", scenario=ScenarioSpec("", task.scenario.kind, "registry"),
                           seed_index=0, seed=0))


@dataclass
class Zygote:
    """The state of one worker process across runs (see the module docstring).

    Parameters
    ----------
    stop : ClockStop
        The executor's clock stop for runs with a clock limit (shared with every child).
    """

    stop: ClockStop
    baseline: Residue = field(default_factory=Residue.now)
    planner: Any = None
    residue: list[str] = field(default_factory=list)

    def warm_up(self, order: WarmUp, report: Callable[[str], None]) -> None:
        """Import the plugins, build the planner (then ``report("warming")``: the hard limit starts) and warm it up on
        synthetic scenarios of the order's kind (errors are left to the measured runs, which are judged); note any
        residue."""
        from pathzoo.core.warmup import WARM_UP_BUDGET
        from pathzoo.harness.synthetic import synthetic_scenarios

        task = order.task
        try:
            ensure_plugins(task.plugin_modules)
            self.planner = task.build_planner()
            report("warming")
            budget = WARM_UP_BUDGET if task.budget.time_s is None else replace(WARM_UP_BUDGET,
                                                                               time_s=task.budget.time_s)
            for scenario in synthetic_scenarios(task.scenario.kind):
                try:
                    self.planner.plan(scenario, budget=budget, rng=np.random.default_rng(0), progress=None)
                except BaseException:  # noqa: BLE001 - SystemExit included
                    pass
        except BaseException:  # noqa: BLE001 - the measured run repeats the setup and reports its failure
            self.planner = None
        gc.collect()  # finalisers of the warm-up's objects run now, before any run is known here
        self.residue = Residue.now().left(self.baseline)

    def run(self, task: "RunTask", report: Callable[[str], None], go: Callable[[], None]) -> tuple[bytes, float]:
        """Prepare (``report("started")``), wait for the harness's ``go()``, hand over (``report("planning")``),
        fork; return the child's encoded outcome (or one made here for a failed setup or a dead child) and the
        child's CPU seconds as the kernel reported them on reaping it (with its reaped descendants'; NaN without a
        child).

        A run may be sent while the previous one is still executing; the
        harness says go once it has seen that the previous run left no
        process behind, so the setup overlaps with the harness's check.
        """
        from pathzoo.harness.wire import encode_outcome

        started_at = utc_now()
        _reap()
        try:
            ready = self._prepare(task, report)
        except Exception as exc:  # noqa: BLE001 - the plugin, planner or scenario could not be set up
            ready = RunOutcome(task.run_key, message="run setup failed: " + describe_exception(exc), crash=True)
        go()
        if isinstance(ready, RunOutcome):
            return encode_outcome(replace(ready, started_at=started_at)), math.nan
        scenario, sealed, versions = ready
        report("planning")
        return self._fork(task, scenario, sealed, versions, started_at)

    def _prepare(self, task: "RunTask", report: Callable[[str], None]) -> "tuple[Any, Any, dict[str, str]] | RunOutcome":
        if self.residue:
            return RunOutcome(task.run_key, crash=True, message=(
                f"the planner left {', '.join(self.residue)} running in its worker after its import or warm-up; "
                "pathzoo runs no planner in such a worker"))
        if self.planner is None:
            ensure_plugins(task.plugin_modules)
            self.planner = task.build_planner()
        if self.planner.version != task.planner_version:
            raise RuntimeError(f"{task.planner.id} is version {self.planner.version} in this worker, "
                               f"{task.planner_version} in the harness")
        scenario, sealed = load_cached(task.scenario)
        versions = versions_of(task)
        provenance(versions)  # reads the versions of the libraries loaded so far once here, not in every child
        report("started")
        return scenario, sealed, versions

    def _fork(self, task: "RunTask", scenario: Any, sealed: Any, versions: dict[str, str],
              started_at: str) -> tuple[bytes, float]:
        from pathzoo.harness.wire import MAX_OUTCOME_BYTES, encode_outcome

        read, write = os.pipe()
        try:
            pid = os.fork()
        except OSError as exc:  # out of tasks or memory: the planner's own processes are counted against its limits
            os.close(read)
            os.close(write)
            return encode_outcome(RunOutcome(task.run_key, crash=True, started_at=started_at, versions=versions,
                                             message=f"the run's process could not be started ({exc})")), math.nan
        if pid == 0:  # the child: never returns
            os.close(read)
            _child(task, scenario, sealed, versions, started_at, self.stop, write)
        os.close(write)
        data, exit_status, cpu = _collect(pid, read, MAX_OUTCOME_BYTES)
        if len(data) > MAX_OUTCOME_BYTES:
            return encode_outcome(RunOutcome(task.run_key, crash=True, started_at=started_at,
                                             message=f"the planner's process sent over {MAX_OUTCOME_BYTES} bytes")), cpu
        if exit_status != 0 or not data:
            return encode_outcome(RunOutcome(task.run_key, crash=True, started_at=started_at, versions=versions,
                                             message=f"worker process died ({_describe(exit_status)})")), cpu
        return data, cpu


def _reap() -> None:
    """Reap the children that have ended (the processes a warm-up left, which the harness killed): a zombie still
    counts against the sandbox's task limit."""
    while True:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            return


def _describe(status: int) -> str:
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        try:
            return f"signal {sig} ({signal.Signals(sig).name})"
        except ValueError:
            return f"signal {sig}"
    return f"exit code {os.waitstatus_to_exitcode(status)}"


def _collect(pid: int, read: int, limit: int) -> tuple[bytes, int, float]:
    """Read the child's pipe until the child has exited, then reap it: ``(bytes, wait status, CPU seconds)``.

    A descendant that keeps the pipe open does not hold the zygote up: the
    end is the child's exit, seen on its ``pidfd``; what it wrote by then is
    read without blocking.
    """
    chunks: list[bytes] = []
    size = 0
    pidfd = os.pidfd_open(pid)
    os.set_blocking(read, False)
    try:
        exited = False
        while not exited:
            ready, _, _ = select.select([read, pidfd], [], [])
            exited = pidfd in ready
            while size <= limit:
                try:
                    chunk = os.read(read, _READ_CHUNK)
                except BlockingIOError:
                    break
                if not chunk:
                    break
                chunks.append(chunk)
                size += len(chunk)
            if size > limit:
                os.kill(pid, signal.SIGKILL)
                exited = True
        _, status, usage = os.wait4(pid, 0)
    finally:
        os.close(pidfd)
        os.close(read)
    return b"".join(chunks), status, usage.ru_utime + usage.ru_stime


def _child(task: "RunTask", scenario: Any, sealed: Any, versions: dict[str, str], started_at: str, stop: ClockStop,
           write: int) -> None:
    """The forked child: plan, convert to plain data, write it, exit (never returns)."""
    status = 0
    try:
        from pathzoo.parent_death import die_with_parent
        from pathzoo.harness.wire import encode_outcome

        gc.freeze()  # the zygote's objects stay where they are: no copy of their pages for the collector
        die_with_parent()
        os.closerange(3, write)
        os.closerange(write + 1, 1 << 16)
        data = encode_outcome(_plan(task, scenario, sealed, versions, started_at, stop))
        view = memoryview(data)
        while view:
            view = view[os.write(write, view):]
    except BaseException:  # noqa: BLE001 - whatever happens, the child leaves through os._exit
        status = 70
    os._exit(status)


def _plan(task: "RunTask", scenario: Any, sealed: Any, versions: dict[str, str], started_at: str,
          stop: ClockStop) -> RunOutcome:
    """Build the planner, plan, and convert the result (all of it charged to the run)."""
    recorder = HistoryRecorder()
    rng = np.random.default_rng(task.seed)
    budget = replace(task.budget, stop=stop) if task.budget.timed else task.budget
    reset_peak_rss()
    crash: BaseException | None = None
    result: Any = None
    try:
        planner = task.build_planner()
        result = planner.plan(scenario, budget=budget, rng=rng, progress=recorder)
    except BaseException as exc:  # noqa: BLE001 - SystemExit and KeyboardInterrupt included
        crash = exc
    common: dict[str, Any] = dict(stopped_by=stopped_by_of(task, budget.stop, result), history=recorder.history(),
                                  versions=provenance(versions), started_at=started_at)
    if crash is not None:
        outcome = RunOutcome(task.run_key, message=message_text(describe_exception(crash)), crash=True, **common)
    elif not isinstance(result, PlanResult) or not isinstance(result.status, Status):
        what = type(result).__name__ if not isinstance(result, PlanResult) else f"status {type(result.status)}"
        outcome = RunOutcome(task.run_key, message=f"plan() returned {what}, not a PlanResult with a Status",
                             crash=True, **common)
    else:
        path, path_error = as_array(result.path)
        times, times_error = as_array(result.times)
        outcome = RunOutcome(task.run_key, status=result.status, path=path, times=times,
                             path_error=path_error or (f"times {times_error}" if times_error else ""),
                             iterations=result.iterations, evaluations=result.evaluations,
                             message=message_text(result.message), **common)
    outcome = bound_outcome(replace(outcome, scenario_modified=not sealed.intact()))
    return outcome
