"""Executors: where runs execute (``inline``, ``process`` (default), ``dask``, or a batch system: ``slurm``, ``pbs``,
``sge``)."""

from __future__ import annotations

import os
from typing import Any

from pathzoo.core.errors import InvalidExperimentError
from pathzoo.harness.executors.cluster_options import ClusterOptions
from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.executors.inline import InlineExecutor
from pathzoo.harness.executors.process import ProcessExecutor
from pathzoo.harness.sandbox import SandboxLimits, SandboxUnavailableError, sandbox_problem

__all__ = ["RunExecutor", "InlineExecutor", "ProcessExecutor", "ClusterOptions", "dask_executor", "jobqueue_executor",
           "make_executor", "worker_count", "EXECUTORS"]

EXECUTORS: tuple[str, ...] = ("process", "inline", "dask", "slurm", "pbs", "sge")
"""Executor names accepted by :func:`make_executor` (``"dask:<address>"`` names a running cluster)."""


def dask_executor(address: str | None = None, jobs: int | None = None, **kwargs: Any) -> RunExecutor:
    """A :class:`~pathzoo.harness.executors.cluster.DaskExecutor` (imports dask only now).

    Parameters
    ----------
    address : str, optional
        Scheduler address (``"tcp://host:8786"``); a local cluster when omitted.
    jobs : int, optional
        Workers of the local cluster.
    **kwargs
        Passed on (``processes=False`` runs the local workers as threads).
    """
    from pathzoo.harness.executors.cluster import DaskExecutor

    return DaskExecutor(jobs, address=address, **kwargs)


def jobqueue_executor(kind: str, options: "ClusterOptions | None" = None) -> RunExecutor:
    """A :class:`~pathzoo.harness.executors.jobqueue.JobQueueExecutor` (imports dask-jobqueue only now).

    Parameters
    ----------
    kind : {"slurm", "pbs", "sge"}
        The batch system whose jobs run the Dask workers.
    options : ClusterOptions, optional
        The jobs' queue, cores, memory, walltime, number and prologue.
    """
    from pathzoo.harness.executors.jobqueue import JobQueueExecutor

    return JobQueueExecutor(kind, options)


def worker_count(jobs: Any, default: Any = None) -> Any:
    """How many runs go in parallel: ``jobs`` when given, else the experiment's ``default``, else the CPU count.

    Values are passed through unchecked (the caller checks them).
    """
    return jobs or default or os.cpu_count() or 1


def make_executor(spec: "str | RunExecutor", jobs: int, *, require_sandbox: bool = False,
                  limits: SandboxLimits | None = None) -> RunExecutor:
    """Build an executor from its name, or pass an instance through.

    Parameters
    ----------
    spec : str or RunExecutor
        ``"process"``, ``"inline"``, ``"dask"`` (a local Dask cluster),
        ``"dask:tcp://host:8786"`` (an existing scheduler), or ``"slurm"``,
        ``"pbs"``, ``"sge"`` (jobs with default :class:`ClusterOptions`).
    jobs : int
        Worker count for ``process`` and the local Dask cluster.
    require_sandbox : bool
        Refuse to build an executor whose planners would run unsandboxed here
        (``docs/sandbox.md``).
    limits : SandboxLimits, optional
        The limits of each sandboxed worker of the ``process`` executor
        (default: :class:`~pathzoo.harness.sandbox.SandboxLimits`' own).

    Raises
    ------
    InvalidExperimentError
        Unknown executor name.
    SandboxUnavailableError
        ``require_sandbox`` and no sandbox: the inline executor, or a system
        without one (process executor and local Dask cluster).
    """
    if require_sandbox and (spec == "inline" or isinstance(spec, InlineExecutor)):
        raise SandboxUnavailableError("the inline executor runs planners in the harness's own process, never sandboxed")
    if require_sandbox and (spec == "dask" or (isinstance(spec, RunExecutor) and spec.sandbox_problem)):
        problem = sandbox_problem() if spec == "dask" else spec.sandbox_problem  # type: ignore[union-attr]
        if problem:
            raise SandboxUnavailableError(f"planner processes cannot be sandboxed here: {problem}")
    if isinstance(spec, RunExecutor):
        return spec
    if spec == "process":
        return ProcessExecutor(jobs, sandbox=True if require_sandbox else None, limits=limits)
    if spec == "inline":
        return InlineExecutor()
    if spec in ("slurm", "pbs", "sge"):
        return jobqueue_executor(str(spec))
    if spec == "dask" or (isinstance(spec, str) and spec.startswith("dask:")):
        return dask_executor(spec[len("dask:"):] if spec != "dask" else None, jobs)
    raise InvalidExperimentError(f"unknown executor {spec!r}; allowed: {', '.join(EXECUTORS)} or 'dask:<address>'")
