"""``pathzoo run [EXPERIMENT.toml]``: run an experiment (the bundled default without an argument) and rank it."""

from __future__ import annotations

import argparse
import dataclasses
import errno
import logging
import sys
from contextlib import ExitStack, contextmanager, nullcontext
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterator

from pathzoo.cli.cmd_leaderboard import add_table_options, isolation_note, render_leaderboard
from pathzoo.cli.errors import CommandError
from pathzoo.core.errors import PathzooError

if TYPE_CHECKING:
    from pathzoo.harness.executors import RunExecutor
    from pathzoo.harness.sandbox import SandboxLimits
    from pathzoo.harness.shard import Shard

__all__ = ["add_parser", "add_execution_options", "add_sandbox_memory_option", "executor_of", "positive_int",
           "check_sandbox_memory", "sandbox_memory", "shard_of", "status_list"]

EXECUTORS = ("process", "dask", "inline", "slurm", "pbs", "sge")
CLUSTER_KEYS = ("queue", "account", "cores", "memory", "walltime", "jobs", "prologue")
"""The ``[cluster]`` keys that ``pathzoo run`` also takes as ``--cluster-KEY`` options."""


def positive_int(text: str) -> int:
    """argparse type: an integer >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}")
    return value


def sandbox_memory(text: str) -> "SandboxLimits":
    """argparse type: the memory of each sandboxed worker in GiB (a number > 0), as its limits."""
    from pathzoo.harness.sandbox import SandboxLimits

    try:
        gib = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number of GiB, got {text!r}") from None
    if not gib > 0 or gib == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a positive number of GiB, got {text!r}")
    return SandboxLimits.with_memory_gib(gib)


def add_sandbox_memory_option(parser: argparse.ArgumentParser) -> None:
    """``--sandbox-memory GIB`` (shared with ``pathzoo reproduce``)."""
    parser.add_argument("--sandbox-memory", type=sandbox_memory, metavar="GIB", dest="sandbox_limits",
                        help="memory of each sandboxed worker, its runs included, in GiB (default 4; a run over it "
                        "is stored as a crash, 'out of memory'; docs/sandbox.md)")


def check_sandbox_memory(args: argparse.Namespace, executor: str) -> None:
    """Refuse ``--sandbox-memory`` with an executor whose workers it would not reach."""
    if args.sandbox_limits is not None and executor != "process":
        raise CommandError(f"--sandbox-memory applies to the process executor's workers, not to --executor {executor}")


def shard_of(text: str) -> "Shard":
    """argparse type: ``K/N``, shard K of N (:mod:`pathzoo.harness.shard`)."""
    from pathzoo.harness.shard import parse_shard

    try:
        return parse_shard(text)
    except PathzooError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def status_list(text: str) -> tuple[str, ...]:
    """argparse type: comma-separated run statuses (``crash,timeout``)."""
    from pathzoo.core.status import RunStatus

    allowed = [s.value for s in RunStatus]
    statuses = tuple(dict.fromkeys(t.strip() for t in text.split(",") if t.strip()))
    bad = [t for t in statuses if t not in allowed]
    if bad or not statuses:
        raise argparse.ArgumentTypeError(f"unknown status(es) {bad or [text]}; allowed: {', '.join(allowed)}")
    return statuses


def executor_of(args: argparse.Namespace) -> str:
    """The executor named by :func:`add_execution_options`' options (``"dask:<address>"`` with an address)."""
    if args.dask_address and args.executor != "dask":
        raise CommandError("--dask-address needs --executor dask")
    return f"dask:{args.dask_address}" if args.dask_address else args.executor


def add_execution_options(parser: argparse.ArgumentParser) -> None:
    """``--jobs``, ``--executor``, ``--dask-address`` and ``--no-progress`` (shared with ``pathzoo tune``)."""
    parser.add_argument("--jobs", type=positive_int, metavar="N", help="worker processes (default: number of CPUs)")
    parser.add_argument("--executor", choices=EXECUTORS, default="process",
                        help="where runs execute (default: process); slurm, pbs and sge run Dask workers as jobs "
                        "of that batch system (docs/cluster.md)")
    parser.add_argument("--dask-address", metavar="ADDR", help="Dask scheduler address, with --executor dask")
    parser.add_argument("--no-progress", action="store_true", help="do not show a progress bar")


@contextmanager
def _harness_info_on_stderr() -> Iterator[None]:
    """Show the harness logger's INFO messages (e.g. the unsupported pairs not run) on stderr."""
    logger = logging.getLogger("pathzoo.harness")
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(message)s"))
    level = logger.level
    logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    try:
        yield
    finally:
        logger.removeHandler(handler)
        logger.setLevel(level)


def _add_cluster_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("batch-system jobs (with --executor slurm, pbs or sge; override the "
                                      "experiment file's [cluster] table; docs/cluster.md)")
    group.add_argument("--cluster-queue", metavar="NAME", help="partition or queue (default: the system's)")
    group.add_argument("--cluster-account", metavar="NAME", help="account or project to charge")
    group.add_argument("--cluster-cores", type=positive_int, metavar="N",
                       help="cores per job, one Dask worker process each (default 1)")
    group.add_argument("--cluster-memory", metavar="SIZE", help="memory per job, e.g. 8GB (default 2GB)")
    group.add_argument("--cluster-walltime", metavar="TIME", help="time limit per job, e.g. 02:00:00")
    group.add_argument("--cluster-jobs", type=positive_int, metavar="N", help="jobs kept running (default 1)")
    group.add_argument("--cluster-prologue", action="append", metavar="LINE",
                       help="a shell line the job runs before its worker (repeatable), e.g. 'module load python'")


def _cluster_executor(executor: str, data: dict[str, Any], path: Path, args: argparse.Namespace
                      ) -> "RunExecutor | None":
    """The batch-system executor from the file's ``[cluster]`` table and the ``--cluster-*`` options (its jobs
    submitted now, while the experiment resolves); None for other executors, which take no such option."""
    given = {key: getattr(args, f"cluster_{key}") for key in CLUSTER_KEYS}
    if executor not in ("slurm", "pbs", "sge"):
        named = [f"--cluster-{key}" for key, value in given.items() if value is not None]
        if named:
            raise CommandError(f"{', '.join(named)} need(s) --executor slurm, pbs or sge")
        return None
    from pathzoo.harness.executors import ClusterOptions, jobqueue_executor

    options = ClusterOptions.from_mapping(data.get("cluster", {}), str(path)).updated(given)
    return jobqueue_executor(executor, options)


def _early_executor(executor: str, data: dict[str, Any], args: argparse.Namespace) -> "RunExecutor | None":
    """The process executor, built before the experiment is (its planners described in a child meanwhile), with a
    worker for the first ``[[planner]]`` starting; None for other executors or a file whose check will fail anyway."""
    from pathzoo.harness.executors import ProcessExecutor, make_executor, worker_count
    from pathzoo.harness.sandbox import sandbox_problem
    from pathzoo.plugins.manager import get_registry

    get_registry()  # discovered once (the metric's check may have done it), before the worker's start needs it

    table = data.get("experiment", {})
    planners = data.get("planner")
    jobs = worker_count(args.jobs, table.get("jobs") if isinstance(table, dict) else None)
    if executor != "process" or isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        return None
    if args.require_sandbox and sandbox_problem():  # refused by run_experiment, after the file's own errors
        return None
    pool = make_executor(executor, jobs, require_sandbox=args.require_sandbox, limits=args.sandbox_limits)
    first = planners[0].get("id") if isinstance(planners, list) and planners and isinstance(planners[0], dict) else None
    if isinstance(first, str) and isinstance(pool, ProcessExecutor):
        pool.start_worker(first)
    return pool


def _run(args: argparse.Namespace) -> int:
    executor = executor_of(args)
    check_sandbox_memory(args, executor)
    from pathzoo.harness.launch import start_server

    start_server()  # it imports while this process reads the experiment; the judge is its fork
    with ExitStack() as stack:
        if args.experiment is None:
            path = stack.enter_context(resources.as_file(resources.files("pathzoo.experiments") / "default.toml"))
        else:
            path = Path(args.experiment)
            if path.is_dir():
                raise CommandError(f"{path} is a directory; give an experiment TOML file")
            if not path.is_file():
                raise FileNotFoundError(errno.ENOENT, "no such experiment file", str(path))
        from pathzoo.harness.experiment import Experiment
        from pathzoo.harness.experiment_checks import resolve_seeds
        from pathzoo.harness.experiment_file import read_toml
        from pathzoo.plugins.metric_lookup import metric_info

        data = read_toml(path)
        metric_info(args.metric)  # a mistyped --metric fails before any run (read from the declarations: no import)
        early = _cluster_executor(executor, data, path, args) or _early_executor(executor, data, args)
        if early is not None:
            stack.callback(early.shutdown)  # idempotent: run_experiment shuts it down when it ran
        exp = Experiment.from_mapping(data, path)  # the file read once
        from pathzoo.harness.runner import DEFAULT_DB, run_experiment

        if args.seeds is not None:
            exp = dataclasses.replace(exp, seeds=resolve_seeds(args.seeds))
        db = args.db or exp.db or DEFAULT_DB
        try:
            with _harness_info_on_stderr() if args.verbose else nullcontext():
                runs = run_experiment(exp, db=db, jobs=args.jobs, executor=early or executor,
                                      progress=not args.no_progress, retry=args.retry,
                                      require_sandbox=args.require_sandbox, shard=args.shard,
                                      sandbox_limits=args.sandbox_limits)
        except KeyboardInterrupt:
            raise CommandError(f"interrupted; finished runs are stored in {db}, run the same command again to resume") \
                from None
    skipped = len(exp.skipped())
    unrun = f"; {skipped} planner x scenario pair(s) not run, the planner not supporting the scenario's kind" + (
        "" if args.verbose else " (-v lists them)") if skipped else ""
    part = f" (shard {args.shard}; 'pathzoo merge' joins the shards' databases)" if args.shard else ""
    print(f"experiment '{exp.name}': {len(runs)} runs stored in {db}{part}{unrun}", file=sys.stderr)
    sys.stdout.write(render_leaderboard(runs, args, db))
    note = isolation_note(runs)
    if note:
        print(note, file=sys.stderr)
    return 0


def add_parser(subparsers: Any) -> None:
    """Register the ``run`` subcommand."""
    parser = subparsers.add_parser(
        "run",
        help="run an experiment and print its leaderboard",
        description="Run planners x scenarios x seeds from an experiment TOML file (without one, the bundled "
        "default comparison), validate every path, store each run in DB and print the leaderboard. "
        "Runs already stored in DB are skipped, so an interrupted run resumes.",
    )
    parser.add_argument(
        "experiment", nargs="?", metavar="EXPERIMENT.toml", help="experiment file (default: the bundled default.toml)"
    )
    parser.add_argument(
        "--db", metavar="FILE", help="SQLite results file (default: the experiment's db, else pathzoo-results.sqlite)"
    )
    add_execution_options(parser)
    _add_cluster_options(parser)
    parser.add_argument(
        "--retry", type=status_list, default=(), metavar="STATUSES",
        help="run again the stored runs with these statuses, comma-separated (e.g. crash,timeout); "
        "each new result replaces the old row",
    )
    parser.add_argument("--seeds", type=positive_int, metavar="N", help="override the experiment's number of seeds")
    parser.add_argument("--shard", type=shard_of, metavar="K/N",
                        help="run only shard K of N: every N-th run of the experiment from the K-th "
                        "(N machines, one shard each; 'pathzoo merge' joins their databases)")
    parser.add_argument("--require-sandbox", action="store_true",
                        help="refuse to run planners outside the OS sandbox (bubblewrap + cgroups; docs/sandbox.md)")
    add_sandbox_memory_option(parser)
    parser.add_argument("-v", "--verbose", action="store_true",
                        help="also list the unsupported planner x scenario pairs that are not run")
    add_table_options(parser)
    parser.set_defaults(handler=_run)
