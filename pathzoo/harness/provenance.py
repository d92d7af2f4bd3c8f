"""What a run ran on: versions of pathzoo, the planner and the libraries loaded in its worker, the CPU, the peak memory.

These values go into a run's ``versions`` mapping (keys :data:`CPU_KEY`,
:data:`CORES_KEY`, :data:`PEAK_RSS_KEY` beside the distribution names) and
from there into the OMPL export's "Running on" and "MB per run" lines.
"""

from __future__ import annotations

import functools
import os
import platform
import sys
from importlib import metadata
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask

__all__ = [
    "TRACKED",
    "CPU_KEY",
    "CORES_KEY",
    "PEAK_RSS_KEY",
    "loaded_distributions",
    "host",
    "reset_peak_rss",
    "peak_rss_mb",
    "versions_of",
    "provenance",
]

TRACKED: dict[str, str] = {
    "numpy": "numpy",
    "scipy": "scipy",
    "numba": "numba",
    "ompl": "ompl",
    "deap": "deap",
    "pyswarms": "pyswarms",
    "skfuzzy": "scikit-fuzzy",
    "optuna": "optuna",
    "pymoo": "pymoo",
}
"""Import name -> distribution name of the libraries planners use; recorded when loaded in the worker."""

CPU_KEY = "cpu"
"""Key of the CPU model in a run's ``versions``."""
CORES_KEY = "cpu_count"
"""Key of the logical core count in a run's ``versions``."""
PEAK_RSS_KEY = "peak_rss_mb"
"""Key of the run's peak resident memory in MiB in a run's ``versions``."""


def loaded_distributions() -> dict[str, str]:
    """``{distribution: version}`` of the :data:`TRACKED` libraries imported in this process.

    A worker process serves many runs, so a library imported by an earlier
    planner in the same process is listed too.
    """
    return {dist: _version(module, dist) for module, dist in TRACKED.items() if module in sys.modules}


@functools.cache
def _version(module: str, dist: str) -> str:
    """The installed version of ``dist`` (read once per process: parsing its metadata takes about 6 ms)."""
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:  # imported from a source tree, not installed
        return str(getattr(sys.modules[module], "__version__", "unknown"))


@functools.cache
def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text(encoding="utf-8", errors="replace").splitlines():
            if line.lower().startswith(("model name", "hardware", "cpu model")):
                return " ".join(line.split(":", 1)[1].split())
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown"


def host() -> dict[str, str]:
    """CPU model and logical core count of this machine."""
    return {CPU_KEY: _cpu_model(), CORES_KEY: str(os.cpu_count() or 0)}


def reset_peak_rss() -> bool:
    """Reset this process's peak resident set size (Linux ``clear_refs`` 5); False where not possible."""
    try:
        Path("/proc/self/clear_refs").write_text("5", encoding="ascii")
        return True
    except OSError:
        return False


def peak_rss_mb() -> float:
    """Peak resident set size of this process in MiB since the last :func:`reset_peak_rss`.

    ``VmHWM`` from ``/proc/self/status`` where it exists; elsewhere the peak
    over the process's life from ``getrusage`` (an upper bound for one run);
    NaN when neither is available.
    """
    try:
        for line in Path("/proc/self/status").read_text(encoding="ascii", errors="replace").splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    except (OSError, ValueError, IndexError):
        pass
    try:
        import resource

        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        return peak / (1024.0 * 1024.0) if sys.platform == "darwin" else peak / 1024.0
    except (ImportError, OSError):
        return float("nan")


def versions_of(task: "RunTask") -> dict[str, str]:
    """The versions of pathzoo, Python, numpy and the task's planner distribution, read before the run."""
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
