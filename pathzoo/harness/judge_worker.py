"""The judge's own process: verdict and metrics of each run, where no planner code ever ran, under a time limit.

:class:`JudgeWorker` starts one process (like the workers, a fork of the
``forkserver`` without the parent's ``__main__``: :mod:`pathzoo.harness.launch`)
that loads every scenario itself, from its reference (registry id, file, or the bytes of an
object the parent pickled, sent once per judge process), builds its
geometry, and keeps a small LRU of
them. For each run the parent sends the task and the bounded outcome; the
judge process loads the scenario (limit
:data:`~pathzoo.harness.worker.SETUP_TIMEOUT_S`, like a worker's setup), then
applies :func:`pathzoo.harness.judge.judge` (limit ``judge_timeout_s``,
default :data:`JUDGE_TIMEOUT_S`). A judge past its limit is killed and
replaced, and the run is stored as ``invalid`` with the reason; so is a run
whose judging raised (``MemoryError`` included) or killed the judge process.
The experiment goes on either way.

Because the judge process is not the planner's, nothing a planner does to
its own process (monkeypatching the validator, changing or replacing parts
of its scenario, patching the clock) can reach a verdict, under every
executor, ``inline`` included (though inline the planner shares the
harness's own process, see :class:`~pathzoo.harness.executors.InlineExecutor`).

The judge process loads scenario and metric plugins only (:data:`JUDGE_KINDS`,
:func:`pathzoo.plugins.manager.limit_kinds`): it is forked from the server
before any plugin was imported there (the server imports none, see
:mod:`pathzoo.harness.executors.warmup`), imports no entry point of a
planner group, and of the modules registered by hand only those that
provide scenarios or metrics
(:meth:`~pathzoo.plugins.manager.Registry.judge_modules`). A planner
plugin's import-time code never runs where verdicts are made.
"""

from __future__ import annotations

import signal
import threading
import time
import warnings
from dataclasses import replace
from multiprocessing.connection import Connection
from typing import TYPE_CHECKING, Any

from pathzoo.harness.launch import NoMainContext, default_start_method, die_with_harness, harness_alive, start_server
from pathzoo.harness.poller import Poller
from pathzoo.harness.specs import HeldScenarios
from pathzoo.harness.outcome import describe_exception
from pathzoo.harness.plugin_loading import ensure_plugins, quiet_registry
from pathzoo.harness.scenario_cache import keep_payload, load_unsealed
from pathzoo.harness.worker import SETUP_TIMEOUT_S
from pathzoo.plugins.manager import PluginKind, get_registry, limit_kinds

if TYPE_CHECKING:
    from concurrent.futures import Future
    from multiprocessing.process import BaseProcess

    from pathzoo.core.results import RunRecord
    from pathzoo.harness.specs import RunTask
    from pathzoo.harness.outcome import RunOutcome

__all__ = ["JudgeWorker", "JudgePool", "JUDGE_TIMEOUT_S"]

JUDGE_TIMEOUT_S = 60.0
"""Default limit on judging one run (validation and every metric), scenario loading excluded."""

JUDGE_KINDS: tuple[PluginKind, ...] = ("scenarios", "metrics")
"""The only kinds of plugins the judge process loads (see ``docs/register-a-planner.md``)."""

_clock = time.perf_counter


def _launch_judge() -> "tuple[BaseProcess, Connection]":
    """A new judge process (a fork of the ``forkserver``; spawned where there is none) and our end of its pipe.

    With ``forkserver`` this returns once the server has forked it, so after
    the server's imports (:func:`~pathzoo.harness.launch.start_server`
    starts those early, and must have been called from a thread that lives
    as long as the server should).
    """
    method = default_start_method()
    ctx: Any = NoMainContext(method)
    parent, child = ctx.Pipe(duplex=True)
    # daemonic: it must never hold the harness's exit
    process = ctx.Process(target=_judge_main, args=(child, harness_alive()), name="pathzoo-judge", daemon=True)
    process.start()
    child.close()
    return process, parent


def _judge_main(conn: Connection, alive: Connection) -> None:
    """Loop of the judge process: load the scenario, say so, judge, send the record (or the error)."""
    die_with_harness(alive)  # first: the harness may die during the imports below
    limit_kinds(JUDGE_KINDS)  # before anything discovers plugins: planner plugins are never imported here
    from pathzoo.harness.judge import judge

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    conn.send(("ready",))
    while True:
        try:
            request = conn.recv()
        except (EOFError, OSError):
            return
        if request is None:
            return
        if request[0] == "warm":
            _warm(request[1])
            continue
        task, outcome, isolated = request
        keep_payload(task.scenario)  # first: the harness counts it as held from now on
        try:
            ensure_plugins(task.plugin_modules, missing_ok=True)
            scenario = load_unsealed(task.scenario)
            metrics = [entry.obj() for entry in quiet_registry().metrics.values()]
            loaded_at = _clock()
            conn.send(("loaded", loaded_at))
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                record = judge(task, outcome, scenario, metrics, isolated=isolated)
            conn.send(("done", record, [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)],
                       _clock() - loaded_at))
        except Exception as exc:  # noqa: BLE001 - MemoryError included: the run is invalid, the judge goes on
            conn.send(("error", describe_exception(exc).splitlines()[0]))


_WARMED_KINDS: set[str] = set()
"""The scenario kinds whose validation and metrics this judge process has run once (:func:`_warm`)."""


def _warm(task: "RunTask") -> None:
    """Load the task's scenario and its reference path; on the first scenario of a kind, also judge that path
    once, discarding the record; never raises.

    Loading, hashing and the first validation and metrics on a scenario kind
    (numba code loaded or compiled) then happen while the first runs of the
    scenario execute, not after them. Later scenarios of the kind are only
    loaded: judging their reference path would repeat work no run needs.
    """
    import numpy as np

    from pathzoo.core.status import Status
    from pathzoo.grid.reference import reference_path
    from pathzoo.harness.judge import judge
    from pathzoo.harness.outcome import RunOutcome

    keep_payload(task.scenario)
    try:
        ensure_plugins(task.plugin_modules, missing_ok=True)
        scenario = load_unsealed(task.scenario)
        ref = reference_path(scenario)
        if ref is not None and scenario.kind not in _WARMED_KINDS:
            _WARMED_KINDS.add(scenario.kind)
            outcome = RunOutcome(task.run_key, status=Status.SOLVED, path=np.array(ref.path, dtype=np.float64))
            metrics = [entry.obj() for entry in quiet_registry().metrics.values()]
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                judge(task, outcome, scenario, metrics)
    except Exception:  # noqa: BLE001 - the real run's judging meets the same error and reports it
        return


class JudgeWorker:
    """One judge process, restarted when it overruns or dies (see the module docstring).

    Parameters
    ----------
    judge_timeout_s : float
        Limit on judging one run once its scenario is loaded.

    The process is a fork of the ``forkserver`` the workers are forked
    from, which imports no plugin and runs no planner code
    (:mod:`pathzoo.harness.executors.warmup`), so the judge starts with
    numba and the harness's validators loaded but no planner plugin.
    """

    def __init__(self, judge_timeout_s: float = JUDGE_TIMEOUT_S) -> None:
        self.judge_timeout_s = float(judge_timeout_s)
        self._process: BaseProcess | None = None
        self._conn: Connection | None = None
        self._ready = False
        self._held = HeldScenarios()
        self._lock = threading.Lock()
        self._launching: threading.Thread | None = None
        self._launch_error: BaseException | None = None
        self._warm_later: list[RunTask] = []
        self._poller = Poller()

    def __enter__(self) -> "JudgeWorker":
        self._launch()  # it starts while the first runs execute
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _launch(self) -> None:
        """Start the judge process if there is none, waiting neither for the server to fork it nor for its "ready".

        The fork is asked for in a thread: with ``forkserver`` it comes only
        once the server has done its imports, and the first runs need not
        wait for that to be queued. Warm-ups asked for meanwhile
        (:meth:`prepare`) are sent as soon as the judge is there.
        """
        with self._lock:
            if self._conn is not None or self._launching is not None:
                return
            start_server(default_start_method())  # from this thread: the server dies with the thread that started it
            self._ready, self._held, self._launch_error = False, HeldScenarios(), None
            self._launching = threading.Thread(target=self._connect, name="pathzoo-judge-launch", daemon=True)
            self._launching.start()

    def _connect(self) -> None:
        """In the launching thread: fork the judge, then send it the warm-ups asked for meanwhile."""
        try:
            process, conn = _launch_judge()
        except BaseException as exc:  # noqa: BLE001 - raised again by _launched, in the harness's thread
            self._launch_error = exc
            return
        with self._lock:
            self._process, self._conn = process, conn
            for task in self._warm_later:
                self._send_warm(task)
            self._warm_later.clear()

    def _launched(self) -> None:
        """Wait for a launch in progress (raising what it raised)."""
        launching = self._launching
        if launching is not None:
            launching.join()
            self._launching = None
            self._warm_later.clear()  # sent, or for a judge that never came
            if self._launch_error is not None:
                raise self._launch_error

    def _start(self) -> Connection:
        """The connection to a judge process that said it is ready."""
        self._launch()
        self._launched()
        assert self._conn is not None
        if not self._ready:
            if self._receive(_clock() + SETUP_TIMEOUT_S) != ("ready",):
                self._stop()
                raise RuntimeError("the judge process failed to start")
            self._ready = True
        return self._conn

    def _stop(self) -> None:
        self._launched()
        if self._process is not None and self._process.pid is not None:
            self._process.kill()
            self._process.join()
        if self._conn is not None:
            self._conn.close()
        self._process, self._conn = None, None

    def _for_judge(self, task: "RunTask") -> "RunTask":
        """The task as the judge process gets it, for runs and warm-ups alike.

        Of the hand-registered plugin modules, only those that provide
        scenarios or metrics, never a planner's; a scenario object the judge
        process holds already goes by reference.
        """
        return replace(self._held.outgoing(task), plugin_modules=get_registry().judge_modules(task.plugin_modules))

    def prepare(self, task: "RunTask") -> None:
        """Let the judge load the task's scenario and warm up on it now.

        Nothing comes back: the next :meth:`judge` call waits for it under
        its setup limit.
        """
        self._launch()
        with self._lock:
            if self._conn is None:  # still being forked: sent once it is
                self._warm_later.append(task)
            else:
                self._send_warm(task)

    def _send_warm(self, task: "RunTask") -> None:
        assert self._conn is not None
        try:
            self._conn.send(("warm", self._for_judge(task)))
            self._held.sent(task)
        except (OSError, EOFError):  # the judge died: judge() notices and restarts it
            pass

    def close(self) -> None:
        """Stop the judge process."""
        try:
            self._launched()
        except Exception:  # noqa: BLE001 - a judge that could not start has nothing to stop
            pass
        if self._conn is not None and self._process is not None:
            try:
                self._conn.send(None)
                self._process.join(2.0)
            except OSError:
                pass
        self._stop()

    def _receive(self, deadline: float) -> Any:
        """The next message, ``"timeout"`` when none has come by ``deadline`` (this module's clock), or ``"died"``;
        a message already waiting is read even past the deadline (this thread may have been slow to look)."""
        assert self._conn is not None and self._process is not None
        while True:
            ready = self._poller.wait([self._conn, self._process.sentinel], max(0.0, deadline - _clock()))
            if self._conn in ready:
                try:
                    return self._conn.recv()
                except (EOFError, OSError):
                    return "died"
            if self._process.sentinel in ready:
                return "died"
            if _clock() >= deadline:
                return "timeout"

    def judge(self, task: "RunTask", outcome: "RunOutcome", *, isolated: bool = True) -> "RunRecord":
        """The stored record of one run: judged in the judge process, or ``invalid`` when it could not be."""
        from pathzoo.harness.run_record import unjudged

        for attempt in range(2):
            conn = self._start()
            try:
                with self._lock:  # a warm-up (prepare) may be sent from another thread
                    conn.send((self._for_judge(task), outcome, isolated))
                    self._held.sent(task)
                break
            except Exception as exc:  # noqa: BLE001 - e.g. a scenario object that does not pickle
                died = isinstance(exc, (OSError, EOFError))
                if died:  # since its last verdict (killed, or its server was): a fresh judge takes this run
                    self._stop()
                if attempt or not died:
                    return unjudged(task, outcome, f"the run could not be sent to the judge ({type(exc).__name__})",
                                    isolated=isolated)
        reply = self._receive(_clock() + SETUP_TIMEOUT_S)
        limit = SETUP_TIMEOUT_S
        if isinstance(reply, tuple) and reply[0] == "loaded":
            # the limit runs from the judge's own "loaded", not from when this thread read it: a harness slow to
            # look neither lets a judge run past the limit nor cuts a verdict that came in time
            limit = self.judge_timeout_s
            reply = self._receive(reply[1] + limit)
            if isinstance(reply, tuple) and reply[0] == "done" and reply[3] > limit:
                reply = "timeout"
        if isinstance(reply, tuple) and reply[0] == "done":
            for text in reply[2]:  # e.g. a metric that failed: warn here, where the caller can see it
                warnings.warn(text, RuntimeWarning, stacklevel=2)
            return reply[1]
        if isinstance(reply, tuple) and reply[0] == "error":
            return unjudged(task, outcome, f"the run could not be judged: {reply[1]}", isolated=isolated)
        if reply == "timeout":
            what = "judging" if limit == self.judge_timeout_s else "loading the scenario for judging"
            reason = f"{what} took over {limit:g} s"
        elif reply == "died":
            assert self._process is not None
            self._process.join(1.0)
            code = self._process.exitcode
            reason = f"the judge process died while judging this run (exit code {code})"
        else:
            reason = f"the judge sent {reply!r}"
        self._stop()  # overran, died or confused: a fresh judge for the next run
        return unjudged(task, outcome, reason, isolated=isolated)


class JudgePool:
    """Several :class:`JudgeWorker` processes judging runs side by side, so judging scales with the workers.

    :meth:`submit` returns at once with a future of the run's record; a
    thread per judge sends the run to a free judge process and waits for its
    verdict, so the harness's thread goes on collecting and storing other
    runs meanwhile. Each judge process is as :class:`JudgeWorker` describes
    (no planner code ever ran in it); every record is the same whichever
    judge made it.

    Each scenario has a home judge, dealt in turn as scenarios are prepared:
    only that judge loads it ahead (:meth:`prepare`), and its runs go there
    while it is free, else to any free judge (which then loads the scenario
    itself). So a study of many scenarios loads each about once, not once per
    judge, and one of few scenarios still keeps every judge busy.

    Parameters
    ----------
    size : int
        Judge processes (at least 1).
    judge_timeout_s : float
        Limit on judging one run once its scenario is loaded.
    """

    def __init__(self, size: int, judge_timeout_s: float = JUDGE_TIMEOUT_S) -> None:
        from concurrent.futures import ThreadPoolExecutor

        self.judges = [JudgeWorker(judge_timeout_s) for _ in range(max(1, int(size)))]
        self._free = list(self.judges)
        self._freed = threading.Condition()
        self._home: dict[Any, JudgeWorker] = {}  # scenario cache key -> the judge that loads it ahead
        self._threads = ThreadPoolExecutor(len(self.judges), thread_name_prefix="pathzoo-judge")

    def __enter__(self) -> "JudgePool":
        for judge in self.judges:
            judge.__enter__()
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def prepare(self, task: "RunTask") -> None:
        """Let the scenario's home judge (the next in turn) load the task's scenario and warm up on it now
        (:meth:`JudgeWorker.prepare`)."""
        judge = self._home.setdefault(task.scenario.cache_key, self.judges[len(self._home) % len(self.judges)])
        judge.prepare(task)

    def submit(self, task: "RunTask", outcome: "RunOutcome", *, isolated: bool = True) -> "Future[RunRecord]":
        """The future record of one run (:meth:`JudgeWorker.judge` in its scenario's home judge if free, else in
        the first judge free)."""
        return self._threads.submit(self._judge, task, outcome, isolated)

    def _judge(self, task: "RunTask", outcome: "RunOutcome", isolated: bool) -> "RunRecord":
        home = self._home.get(task.scenario.cache_key)
        with self._freed:
            self._freed.wait_for(lambda: bool(self._free))
            judge = home if home in self._free else self._free[0]
            self._free.remove(judge)
        try:
            return judge.judge(task, outcome, isolated=isolated)
        finally:
            with self._freed:
                self._free.append(judge)
                self._freed.notify()

    def close(self) -> None:
        """Stop the judge processes (a verdict being awaited ends as the process dies) and their threads."""
        for judge in self.judges:
            judge.close()
        self._threads.shutdown(wait=True, cancel_futures=True)
