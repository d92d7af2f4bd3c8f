"""Options of a batch-system cluster (SLURM, PBS, SGE): the ``[cluster]`` table of an experiment file, or options.

::

    [cluster]
    queue = "short"             # partition / queue (default: the batch system's default)
    account = "my-project"      # account / project to charge (default: none)
    cores = 4                   # cores per job: one Dask worker process of one thread each (default 1)
    memory = "8GB"              # memory per job (default 2GB)
    walltime = "02:00:00"       # per job; a job that ends is replaced while runs remain (default: dask-jobqueue's)
    jobs = 10                   # jobs kept running (default 1)
    prologue = ["module load python/3.11", "source ~/venv/bin/activate"]   # shell lines before the worker starts
    wait_s = 3600               # give up when no job has started a worker by then (default 3600)

``pathzoo run --cluster-queue Q --cluster-cores N ...`` overrides single
keys. A key given neither way comes from dask-jobqueue's own configuration
(``~/.config/dask/jobqueue.yaml``) when it sets one, else the default above;
that file can also set anything not listed here (network interface, local
scratch directory, extra job directives).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, fields, replace
from typing import Any, Callable, Mapping

from pathzoo.core.errors import InvalidExperimentError

__all__ = ["ClusterOptions", "DEFAULTS"]

DEFAULTS: dict[str, Any] = {"cores": 1, "memory": "2GB", "jobs": 1, "wait_s": 3600.0}
"""Values of the keys that neither the experiment, the command line nor dask-jobqueue's configuration sets."""

_MEMORY = re.compile(r"^\s*\d+(\.\d+)?\s*([kKmMgGtT]i?)?[bB]?\s*$")
_WALLTIME = re.compile(r"^(\d+-)?\d+(:\d\d){0,2}$")


@dataclass(frozen=True)
class ClusterOptions:
    """The jobs a batch-system executor submits (see the module docstring); ``None`` means "not given"."""

    queue: str | None = None
    account: str | None = None
    cores: int | None = None
    memory: str | None = None
    walltime: str | None = None
    jobs: int | None = None
    prologue: tuple[str, ...] = ()
    wait_s: float | None = None

    @classmethod
    def from_mapping(cls, table: Any, source: str) -> "ClusterOptions":
        """Check and read the ``[cluster]`` table of the experiment file ``source``; errors name the file and key.

        Raises
        ------
        InvalidExperimentError
            Not a table, an unknown key, or a value of the wrong type or form.
        """
        if not isinstance(table, Mapping):
            raise InvalidExperimentError(f"{source}: field 'cluster': must be a table such as [cluster] with "
                                         "queue = \"short\"")
        allowed = [f.name for f in fields(cls)]
        unknown = sorted(set(table) - set(allowed))
        if unknown:
            raise InvalidExperimentError(f"{source}: field 'cluster': unknown key(s) {unknown}; "
                                         f"allowed: {', '.join(allowed)}")
        return cls().updated(table, lambda key: f"{source}: field 'cluster.{key}'")

    def updated(self, values: Mapping[str, Any], name: Callable[[str], str] = lambda key: f"--cluster-{key}"
                ) -> "ClusterOptions":
        """These options with ``values`` (``None`` values left out) checked and put in; ``name(key)`` starts errors."""
        checked: dict[str, Any] = {}
        for key, value in values.items():
            if value is None:
                continue
            try:
                checked[key] = _check(key, value)
            except ValueError as exc:
                raise InvalidExperimentError(f"{name(key)}: {exc}, got {value!r}") from None
        return replace(self, **checked)

    def value(self, key: str, configured: Any = None) -> Any:
        """The value to use: the one given, else ``configured`` (dask-jobqueue's configuration), else the default."""
        given = getattr(self, key)
        return given if given not in (None, ()) else configured if configured is not None else DEFAULTS.get(key)


def _check(key: str, value: Any) -> Any:
    """``value`` as the option ``key`` holds it; ValueError saying what it must be."""
    if key in ("cores", "jobs"):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise ValueError("must be a positive integer")
        return value
    if key == "wait_s":
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0:
            raise ValueError("must be a positive number of seconds")
        return float(value)
    if key == "prologue":
        lines = [value] if isinstance(value, str) else value
        if not isinstance(lines, (list, tuple)) or not all(isinstance(v, str) and "\n" not in v for v in lines):
            raise ValueError("must be a list of shell lines (strings)")
        return tuple(lines)
    if not isinstance(value, str) or not value.strip():
        raise ValueError("must be a non-empty string")
    if key == "memory" and not _MEMORY.match(value):
        raise ValueError("must be an amount such as \"8GB\" or \"500MB\"")
    if key == "walltime" and not _WALLTIME.match(value):
        raise ValueError("must be a time such as \"01:30:00\" or \"2-00:00:00\"")
    return value
