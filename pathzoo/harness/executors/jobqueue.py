"""Batch-system executors (``slurm``, ``pbs``, ``sge``): Dask workers started as cluster jobs by dask-jobqueue.

The harness process (the head: it may run on a login node) starts a Dask
scheduler and submits :attr:`ClusterOptions.jobs` jobs (``pip install
pathzoo[dask]`` brings dask-jobqueue). Each job starts ``cores`` Dask worker
processes of one thread each, and from then on everything is the
:class:`~pathzoo.harness.executors.cluster.DaskExecutor`: each planner in a
supervised child of its worker, timed from outside, the pool following the
workers as jobs leave the queue or end. What the executor does for the user:

- the job script exports ``DASK_DISTRIBUTED__WORKER__DAEMON=False`` (Dask's
  daemonic workers could not start the planners' processes), and the head's
  ``NUMBA_CACHE_DIR`` and ``SLURM_CONF`` when they are set, so the jobs
  compile into (and load from) the same numba cache as the head and talk to
  the same SLURM; the prologue lines of the options run before the worker;
- :meth:`JobQueueExecutor.prepare` waits for the first worker before the
  first run, saying so, and gives up with an error after ``wait_s``;
- jobs are kept at ``jobs`` (dask adaptive scaling between ``jobs`` and
  ``jobs``): a job that reaches its walltime is replaced while runs remain;
- every job is cancelled (``scancel``, ``qdel``) when the executor shuts
  down: at the end, on an error and on Ctrl-C. A head killed outright leaves
  jobs whose workers exit on their own once the scheduler is gone (Dask's
  ``death-timeout``, 60 s);
- dask-jobqueue replaces the Ctrl-C handler when it is imported (with one
  that calls ``sys.exit``); the executor puts Python's back, so Ctrl-C stops
  ``pathzoo run`` with its usual message.

Job scripts and their output go to ``pathzoo-jobs/`` in the working directory.
"""

from __future__ import annotations

import os
import shutil
import signal
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pathzoo.core.errors import PathzooError
from pathzoo.harness.executors.cluster import DaskExecutor, log
from pathzoo.harness.executors.cluster_options import ClusterOptions

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask

__all__ = ["JobQueueExecutor", "JOBQUEUE_EXECUTORS", "LOG_DIRECTORY", "job_prologue"]

JOBQUEUE_EXECUTORS: dict[str, str] = {"slurm": "SLURMCluster", "pbs": "PBSCluster", "sge": "SGECluster"}
"""Executor name: the dask-jobqueue cluster class that submits its jobs."""

LOG_DIRECTORY = "pathzoo-jobs"
"""Where the jobs' output goes (relative to the working directory)."""

_FORWARDED = ("NUMBA_CACHE_DIR", "SLURM_CONF")
_NOTICE_S = 30.0


def job_prologue(options: ClusterOptions) -> list[str]:
    """The shell lines a job runs before its Dask worker: the environment the harness needs, then the user's."""
    lines = ["export DASK_DISTRIBUTED__WORKER__DAEMON=False"]
    lines += [f"export {name}={_quoted(os.environ[name])}" for name in _FORWARDED if os.environ.get(name)]
    return lines + list(options.prologue)


def _quoted(text: str) -> str:
    return "'" + text.replace("'", "'\"'\"'") + "'"


def _import_jobqueue() -> Any:
    handler = signal.getsignal(signal.SIGINT)
    try:
        import dask_jobqueue
    except ImportError:
        raise PathzooError("the batch-system executors need dask-jobqueue: pip install 'pathzoo[dask]'") from None
    finally:
        signal.signal(signal.SIGINT, handler)  # dask_jobqueue.runner sets one that calls sys.exit() on import
    return dask_jobqueue


async def _submit(cluster: Any, jobs: int) -> None:
    """Submit ``jobs`` jobs and wait for the batch system's answer (on the cluster's event loop).

    ``scale`` leaves the submission to a callback whose failure is only
    logged (a traceback, then a wait for workers that never come); awaiting
    the cluster's own state correction raises it instead.
    """
    while len(cluster.worker_spec) < jobs:
        cluster.worker_spec.update(cluster.new_worker_spec())
    await cluster._correct_state()


def _forget_refused(cluster: Any) -> None:
    """Cancel the jobs of a submission that was refused in part, and forget them all (so that it closes)."""
    for job in list(cluster.workers.values()):
        if getattr(job, "job_id", None):
            try:
                cluster.sync(job.close)
            except Exception:  # noqa: BLE001 - a job that cannot be cancelled has ended
                pass
    cluster.workers.clear()
    cluster.worker_spec.clear()
    cluster._created.clear()


class JobQueueExecutor(DaskExecutor):
    """Runs on Dask workers that are jobs of a batch system (see the module docstring).

    Parameters
    ----------
    kind : {"slurm", "pbs", "sge"}
        The batch system.
    options : ClusterOptions, optional
        Queue, cores, memory, walltime, jobs, prologue, wait (defaults: see
        :mod:`~pathzoo.harness.executors.cluster_options`).

    Raises
    ------
    PathzooError
        dask-jobqueue is missing, or the cluster cannot be made (the batch
        system's command is missing, say).
    """

    def __init__(self, kind: str, options: ClusterOptions | None = None) -> None:
        import dask

        jobqueue = _import_jobqueue()
        self.kind = kind
        self.options = options = options or ClusterOptions()
        config = f"jobqueue.{kind}"
        given = {"queue": options.queue, "walltime": options.walltime}  # else dask-jobqueue's configuration
        if options.account:
            given["project" if kind == "sge" else "account"] = options.account
        cores = options.value("cores", dask.config.get(f"{config}.cores", None))
        Path(LOG_DIRECTORY).mkdir(exist_ok=True)
        try:
            cluster = getattr(jobqueue, JOBQUEUE_EXECUTORS[kind])(
                cores=cores, processes=cores,  # one thread per worker process: one planner child each
                memory=options.value("memory", dask.config.get(f"{config}.memory", None)),
                job_script_prologue=job_prologue(options), log_directory=LOG_DIRECTORY, job_name="pathzoo",
                scheduler_options={"dashboard_address": ":0"}, **{k: v for k, v in given.items() if v is not None},
            )
        except (OSError, ValueError, RuntimeError) as exc:
            raise PathzooError(f"cannot set up the {kind} cluster: {' '.join(str(exc).split())}") from None
        submit = getattr(cluster.job_cls, "submit_command", "")
        if submit and shutil.which(submit.split()[0]) is None:
            cluster.close()
            raise PathzooError(f"--executor {kind} needs the batch system's {submit.split()[0]!r} command, not found "
                               "here: run pathzoo where jobs are submitted (a login node)")
        jobs = options.value("jobs")
        try:
            try:
                cluster.sync(_submit, cluster, jobs)  # submitted now: a refused job is an error here, not a traceback
            except RuntimeError as exc:  # dask-jobqueue's "Command exited with non-zero exit code", with stderr
                _forget_refused(cluster)
                said = [line.strip() for line in str(exc).splitlines() if "error" in line.lower()]
                raise PathzooError(f"the {kind} job was refused: {said[0] if said else ' '.join(str(exc).split())}"
                                   ) from None
            cluster.adapt(minimum_jobs=jobs, maximum_jobs=jobs)  # a job that ends is replaced while runs remain
            super().__init__(cluster=cluster)
        except BaseException:
            cluster.close()
            raise
        log.warning("pathzoo: %d %s job(s) of %d core(s) requested; their output goes to %s/", jobs, kind, cores,
                    LOG_DIRECTORY)

    def connected_threads(self) -> int:
        """Threads of the workers connected now (as the executor's watchdog last saw them)."""
        return sum(self._workers.values())

    def prepare(self, tasks: "list[RunTask]") -> None:
        """Wait for the first worker (a job that left the queue), at most ``wait_s``.

        Raises
        ------
        PathzooError
            No worker joined in time.
        """
        wait_s = float(self.options.value("wait_s"))
        start = noticed = time.monotonic()
        while not self.connected_threads():
            now = time.monotonic()
            if now - start >= wait_s:
                raise PathzooError(f"no {self.kind} job started a Dask worker within {wait_s:g} s: see the queue "
                                   f"({'squeue' if self.kind == 'slurm' else 'qstat'}) and the jobs' output in "
                                   f"{LOG_DIRECTORY}/")
            if now - noticed >= _NOTICE_S:
                log.warning("pathzoo: still waiting for the %s jobs to start (%.0f s)", self.kind, now - start)
                noticed = now
            time.sleep(0.5)
