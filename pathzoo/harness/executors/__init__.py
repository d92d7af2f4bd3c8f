"""Executors: where runs execute (``inline``, ``process`` (default) or ``dask``)."""

from __future__ import annotations

from typing import Any

from pathzoo.core.errors import InvalidExperimentError
from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.executors.inline import InlineExecutor
from pathzoo.harness.executors.process import ProcessExecutor

__all__ = ["RunExecutor", "InlineExecutor", "ProcessExecutor", "dask_executor", "make_executor", "EXECUTORS"]

EXECUTORS: tuple[str, ...] = ("process", "inline", "dask")
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


def make_executor(spec: "str | RunExecutor", jobs: int) -> RunExecutor:
    """Build an executor from its name, or pass an instance through.

    Parameters
    ----------
    spec : str or RunExecutor
        ``"process"``, ``"inline"``, ``"dask"`` (a local Dask cluster) or
        ``"dask:tcp://host:8786"`` (an existing scheduler).
    jobs : int
        Worker count for ``process`` and the local Dask cluster.

    Raises
    ------
    InvalidExperimentError
        Unknown executor name.
    """
    if isinstance(spec, RunExecutor):
        return spec
    if spec == "process":
        return ProcessExecutor(jobs)
    if spec == "inline":
        return InlineExecutor()
    if spec == "dask" or (isinstance(spec, str) and spec.startswith("dask:")):
        return dask_executor(spec[len("dask:"):] if spec != "dask" else None, jobs)
    raise InvalidExperimentError(f"unknown executor {spec!r}; allowed: {', '.join(EXECUTORS)} or 'dask:<address>'")
