"""Run an experiment: skip finished runs, execute the rest, judge, store, and report progress.

The flow of one run::

    parent: task --submit--> executor --(worker: rebuild, plan())--> outcome (timed by the executor)
    parent: outcome --bound--> judge process (validate, metrics) --> RunRecord --store (1 transaction)--> hooks

Every value the planner chose is bounded first (:mod:`pathzoo.harness.bounds`);
judging happens in the judge's own process, on a scenario it loaded itself,
under a time limit (:mod:`pathzoo.harness.judge_worker`), so nothing a
planner does in its worker can change a verdict, and a run that cannot be
judged is stored as ``invalid`` with the reason while the experiment goes on.
"""

from __future__ import annotations

import logging
import os
import sqlite3
import time
import warnings
from collections import Counter
from concurrent.futures import FIRST_COMPLETED, Future, wait
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pathzoo.core.errors import InvalidExperimentError
from pathzoo.core.status import RunStatus
from pathzoo.harness.executors import RunExecutor, make_executor, worker_count
from pathzoo.harness.bounds import bound_outcome
from pathzoo.harness.eta import RunTimes, pilot_first
from pathzoo.harness.run_record import unjudged
from pathzoo.harness.judge_worker import JUDGE_TIMEOUT_S, JudgePool
from pathzoo.harness.planner_info import extra_plugin_modules
from pathzoo.harness.run_queue import RunQueue
from pathzoo.harness.store import read_runs
from pathzoo.harness.store_writer import ResultStore

if TYPE_CHECKING:
    import pandas as pd

    from pathzoo.harness.experiment import Experiment
    from pathzoo.harness.sandbox import SandboxLimits
    from pathzoo.harness.shard import Shard
    from pathzoo.core.results import RunRecord
    from pathzoo.harness.specs import RunTask
    from pathzoo.harness.outcome import RunOutcome
    from pathzoo.plugins.manager import Registry

__all__ = ["run_experiment", "skipped_summary", "never_run", "DEFAULT_DB"]

DEFAULT_DB = "pathzoo-results.sqlite"
"""Result database used when neither the call nor the experiment names one."""

ETA_EVERY_S = 0.5
"""Seconds between two costings of the progress bar's time left (:meth:`~pathzoo.harness.eta.RunTimes.eta`)."""

log = logging.getLogger("pathzoo.harness")


def _call_hook(registry: "Registry", name: str, **kwargs: Any) -> None:
    try:
        getattr(registry.pm.hook, name)(**kwargs)
    except Exception as exc:  # an observer must not stop the experiment
        warnings.warn(f"observer hook {name} raised {type(exc).__name__}: {exc}", RuntimeWarning, stacklevel=2)


def _progress_bar(total: int, name: str, enabled: bool) -> Any:
    if not enabled:
        return None
    from tqdm.auto import tqdm

    # tqdm's own time left follows the latest rate and swings between planners; the postfix 'left' replaces it
    return tqdm(total=total, desc=name, unit="run", dynamic_ncols=True,
                bar_format="{l_bar}{bar}| {n_fmt}/{total_fmt} [{elapsed}, {rate_fmt}{postfix}]")


def _store(store: ResultStore, record: "RunRecord", task: "RunTask", outcome: "RunOutcome",
           retry: tuple[str, ...], label: str) -> "RunRecord":
    """Store a record (``label``: the configuration's name); one the database refuses is stored as ``invalid`` with
    the reason instead."""
    try:
        store.insert(record, replace_statuses=retry, label=label)
        return record
    except (OverflowError, ValueError, TypeError, sqlite3.InterfaceError) as exc:
        fallback = unjudged(task, outcome, f"the result could not be stored ({type(exc).__name__}: {exc})",
                            isolated=record.isolated)
        store.insert(fallback, replace_statuses=retry, label=label)
        return fallback


def _format_eta(seconds: float | None) -> str:
    if seconds is None:
        return "?"
    minutes, secs = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours}h{minutes:02d}m" if hours else f"{minutes}m{secs:02d}s"


def _execute(
    executor: RunExecutor,
    tasks: list["RunTask"],
    store: ResultStore,
    judges: JudgePool,
    registry: "Registry",
    bar: Any,
    retry: tuple[str, ...],
) -> None:
    queue = RunQueue(tasks, executor.lane)
    in_flight: dict[Future[RunOutcome], RunTask] = {}
    judging: dict[Future[RunRecord], tuple[RunTask, RunOutcome]] = {}
    isolated = bool(getattr(executor, "isolated", False))
    failures = 0
    remaining = Counter((t.planner.name, t.scenario.id) for t in tasks)
    times = RunTimes(parallel=executor.capacity)
    eta_due, left = 0.0, _format_eta(None)

    scenarios_seen: set[tuple[str, str, str, str]] = set()

    def submit(task: "RunTask") -> None:
        if task.scenario.cache_key not in scenarios_seen:  # the judges load it while the run executes
            scenarios_seen.add(task.scenario.cache_key)
            judges.prepare(task)
        _call_hook(registry, "pathzoo_run_started", run_key=task.run_key, planner_id=task.planner.id,
                   scenario_id=task.scenario.id, seed=task.seed)
        in_flight[executor.submit(task)] = task

    def submit_more() -> None:
        # a run is done once stored, but up to `lookahead` runs being judged do not hold the next ones back: a worker
        # that ends a run finds its next one queued while the harness judges and stores the last (executors.base)
        while len(in_flight) + max(0, len(judging) - executor.lookahead) < executor.capacity + executor.lookahead:
            task = queue.next()
            if task is None:
                break
            submit(task)
        # and every lane executing a run, or judging its last, has its next one queued, out of order if need be
        # (run_queue)
        started = {f: f.running() or f.done() for f in in_flight}
        queued = {executor.lane(t) for f, t in in_flight.items() if not started[f]}
        busy = [t for f, t in in_flight.items() if started[f]] + [t for t, _ in judging.values()]
        for lane in dict.fromkeys(executor.lane(t) for t in busy):
            if lane is None or lane in queued:  # None: the executor has no lanes
                continue
            task = queue.next_of(lane)
            if task is not None:
                submit(task)

    executor.prepare(tasks)
    submit_more()
    while in_flight or judging:
        grown = executor.capacity_changed()  # a pool that follows a cluster: more runs once workers join
        waited: list[Future[Any]] = [*in_flight, *judging, *([grown] if grown is not None else [])]
        done, _ = wait(waited, return_when=FIRST_COMPLETED)
        for future in done:
            if future is grown:
                times.parallel = executor.capacity  # the time left, costed with the workers present now
            elif future in in_flight:  # judged in a judge process while this thread collects other runs
                task = in_flight.pop(future)
                outcome = bound_outcome(future.result())
                judging[judges.submit(task, outcome, isolated=isolated)] = (task, outcome)
            else:
                task, outcome = judging.pop(future)
                name = task.planner.name
                record = _store(store, future.result(), task, outcome, retry, name)
                _call_hook(registry, "pathzoo_run_finished", record=record)
                if record.status is not RunStatus.SOLVED:
                    failures += 1
                remaining[(name, task.scenario.id)] -= 1
                times.add(name, task.scenario.id, record.wall_time_s)
                if bar is not None:
                    now = time.monotonic()
                    if now >= eta_due or not (in_flight or judging):  # its cost grows with the pairs: not every run
                        left, eta_due = _format_eta(times.eta(remaining)), now + ETA_EVERY_S
                    bar.set_postfix(failures=failures, left=left, refresh=False)
                    bar.update(1)
        submit_more()


def skipped_summary(skipped: "list[tuple[str, str, str]]") -> str:
    """One short line on the unsupported ``(planner, scenario, kind)`` pairs that are not run."""
    kinds = Counter(k for _, _, k in skipped)
    by_kind = ", ".join(f"{k} {n}" for k, n in sorted(kinds.items()))
    return (f"pathzoo: skipping {len(skipped)} unsupported planner x scenario pair(s) "
            f"(scenario kind not supported: {by_kind}); -v lists them")


def never_run(experiment: "Experiment") -> str:
    """``"no planner runs fgdaco.scenario1"`` for the scenarios no planner supports (and planners with no
    scenario), else ``""``: what an experiment holds in vain, likely a mistake worth a warning."""
    pairs = experiment.pairs()
    used_planners = {p.name for p, _ in pairs}
    used_scenarios = {s.id for _, s in pairs}
    idle_scenarios = [s.id for s in experiment.scenarios if s.id not in used_scenarios]
    idle_planners = [p.name for p in experiment.planners if p.name not in used_planners]
    parts = []
    if idle_scenarios:
        parts.append(f"no planner runs {', '.join(idle_scenarios)}")
    if idle_planners:
        parts.append(f"{', '.join(idle_planners)} run(s) on no scenario")
    return "; ".join(parts)


def run_experiment(
    experiment: "Experiment",
    *,
    db: str | Path | None = None,
    jobs: int | None = None,
    executor: "str | RunExecutor" = "process",
    progress: bool = True,
    retry: "tuple[str, ...] | list[str]" = (),
    judge_timeout_s: float = JUDGE_TIMEOUT_S,
    require_sandbox: bool = False,
    shard: "Shard | None" = None,
    sandbox_limits: "SandboxLimits | None" = None,
) -> "pd.DataFrame":
    """Run every run of ``experiment`` not yet stored in ``db``; return exactly the experiment's runs.

    Parameters
    ----------
    experiment : Experiment
        What to run.
    db : path, optional
        Result database (default: the experiment's ``db``, else
        :data:`DEFAULT_DB` in the working directory). Created when missing.
    jobs : int, optional
        Parallel runs (default: the experiment's ``jobs``, else ``os.cpu_count()``).
    executor : str or RunExecutor
        ``"process"`` (default), ``"inline"``, ``"dask"`` or ``"dask:<address>"``
        (see :func:`pathzoo.harness.executors.make_executor`), or an instance.
    progress : bool
        Show a progress bar (runs done, failures, time left) on stderr.
    retry : sequence of str
        Run statuses (``"crash"``, ``"timeout"``, ...) whose stored runs are
        run again; each new result replaces the old row when it is stored.
    judge_timeout_s : float
        Limit on judging one run; a run past it is stored as ``invalid``.
    require_sandbox : bool
        Refuse to run planners outside the OS sandbox
        (:class:`~pathzoo.harness.sandbox.SandboxUnavailableError`, before any
        run); without it an unsandboxed executor is named in one warning of
        the ``pathzoo.harness`` logger (``docs/sandbox.md``).
    shard : Shard, optional
        Run only this shard of the experiment's runs
        (:mod:`pathzoo.harness.shard`; ``pathzoo merge`` joins the shards' databases).
    sandbox_limits : SandboxLimits, optional
        Memory, process and scratch limits of each sandboxed worker of the
        ``process`` executor (default: :class:`~pathzoo.harness.sandbox.SandboxLimits`'
        own, 4 GiB of memory); an executor passed as an instance keeps its own.

    Returns
    -------
    pandas.DataFrame
        :func:`pathzoo.harness.store.read_runs` restricted to this
        experiment's planners x scenarios x seeds (other runs stored under the
        same name, from earlier calls, and runs of other shards, are left out), in the experiment's
        order of runs, not the order they finished in.

    Notes
    -----
    Planner x scenario pairs whose scenario kind the planner does not declare
    are not run; they are counted in one line of the ``pathzoo.harness``
    logger and listed at its INFO level (``pathzoo run -v``). The line is a
    warning only when a scenario is run by no planner or a planner runs on
    no scenario (:func:`never_run`). The progress
    bar's ``left`` is :meth:`pathzoo.harness.eta.RunTimes.eta`. Runs already stored (any status) are skipped, so an interrupted
    experiment resumes where it stopped, without doubled rows.
    """
    from pathzoo.plugins.manager import get_registry

    retry_statuses = _retry_statuses(retry)
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise InvalidExperimentError(f"jobs must be a positive integer, got {jobs!r}")
    db_path = Path(db if db is not None else experiment.db if experiment.db is not None else DEFAULT_DB)
    n_jobs = worker_count(jobs, experiment.jobs)
    registry = get_registry()
    skipped = experiment.skipped()
    if skipped:
        idle = never_run(experiment)  # a planner or scenario in vain is worth a warning; a partial cross product is not
        log.log(logging.WARNING if idle else logging.INFO, "%s", skipped_summary(skipped) + (f"; {idle}" if idle else ""))
        log.info("pathzoo: unsupported pairs not run:\n%s", "\n".join(f"  {p} x {s} ({k})" for p, s, k in skipped))
    with ResultStore(db_path) as store:
        store.add_experiment(experiment)
        finished = store.finished_keys(experiment.name, exclude_statuses=retry_statuses)
        all_tasks = experiment.tasks(extra_plugin_modules(registry))
        if shard is not None:
            all_tasks = shard.select(all_tasks)
        # a pilot of every scenario and planner first, so the time left is costed from the start
        tasks = pilot_first([t for t in all_tasks if t.run_key not in finished],
                            lambda t: (t.planner.name, t.scenario.id))
        if tasks:
            bar = _progress_bar(len(tasks), experiment.name, progress)
            try:
                # the judges first: they start while the executor starts its workers; one per local worker
                with JudgePool(min(n_jobs, os.cpu_count() or 1), judge_timeout_s) as judges, \
                        make_executor(executor, n_jobs, require_sandbox=require_sandbox,
                                      limits=sandbox_limits) as pool:
                    if pool.sandbox_problem:
                        log.warning("pathzoo: planners run without an OS sandbox (%s); see docs/sandbox.md",
                                    pool.sandbox_problem)
                    _execute(pool, tasks, store, judges, registry, bar, retry_statuses)
            finally:
                if bar is not None:
                    bar.close()
        n_runs = store.count_runs(experiment.name)
    _call_hook(registry, "pathzoo_experiment_finished", experiment=experiment.name, db=str(db_path), n_runs=n_runs)
    order = {t.run_key: i for i, t in enumerate(all_tasks)}
    runs = read_runs(db_path, experiment.name, run_keys=order)
    # the experiment's order (planners, then scenarios, then seeds), whatever order the runs finished in
    return runs.iloc[runs["run_key"].map(order).argsort(kind="stable")].reset_index(drop=True)


def _retry_statuses(retry: "tuple[str, ...] | list[str]") -> tuple[str, ...]:
    allowed = [s.value for s in RunStatus]
    if isinstance(retry, str):
        retry = [r for r in retry.split(",") if r]
    bad = [r for r in retry if r not in allowed]
    if bad:
        raise InvalidExperimentError(f"retry: unknown status(es) {bad}; allowed: {', '.join(allowed)}")
    return tuple(dict.fromkeys(retry))
