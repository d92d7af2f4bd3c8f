"""Start harness processes (workers, the judge) that never import the parent's ``__main__``.

:mod:`multiprocessing`'s ``spawn`` and ``forkserver`` methods make each child
re-import the parent's main module, which runs an unguarded script a second
time in every child (and fails). Like loky and Dask's worker processes,
:class:`NoMainContext` leaves the main module out of the data a child is
prepared with; the child still gets the parent's ``sys.path`` and working
directory. With ``forkserver`` (the default where available) the server
imports pathzoo and every entry-point plugin once
(:mod:`pathzoo.harness.executors.warmup`), so each new child costs a fork.
"""

from __future__ import annotations

import multiprocessing as mp
import threading
from multiprocessing import popen_forkserver, popen_spawn_posix, spawn
from typing import Any

__all__ = ["NoMainContext", "ForkServerNoMainProcess", "SpawnNoMainProcess", "default_start_method"]

_PRELOAD = ["pathzoo.harness.executors.warmup"]
_launch_lock = threading.Lock()


def default_start_method() -> str:
    """``forkserver`` where the platform has it, else ``spawn``."""
    return "forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn"


def _without_main(prepare: Any) -> Any:
    def prepared(name: str) -> dict[str, Any]:
        data = prepare(name)
        data.pop("init_main_from_name", None)
        data.pop("init_main_from_path", None)
        return data
    return prepared


def _no_main_popen(base: Any) -> Any:
    class NoMainPopen(base):  # type: ignore[misc, valid-type]
        """Launch without the main module in the preparation data (so the child never re-imports it)."""

        def _launch(self, process_obj: Any) -> None:
            with _launch_lock:
                original = spawn.get_preparation_data
                spawn.get_preparation_data = _without_main(original)
                try:
                    super()._launch(process_obj)
                finally:
                    spawn.get_preparation_data = original
    return NoMainPopen


class ForkServerNoMainProcess(mp.context.ForkServerProcess):
    """A ``forkserver`` process launched without the parent's main module."""

    @staticmethod
    def _Popen(process_obj: Any) -> Any:
        return _FORKSERVER_POPEN(process_obj)


class SpawnNoMainProcess(mp.context.SpawnProcess):
    """A ``spawn`` process launched without the parent's main module."""

    @staticmethod
    def _Popen(process_obj: Any) -> Any:
        return _SPAWN_POPEN(process_obj)


_FORKSERVER_POPEN = _no_main_popen(popen_forkserver.Popen)
_SPAWN_POPEN = _no_main_popen(popen_spawn_posix.Popen)
_PROCESS = {"forkserver": ForkServerNoMainProcess, "spawn": SpawnNoMainProcess}


class NoMainContext:
    """A ``forkserver`` or ``spawn`` context whose processes do not import the parent's ``__main__``.

    Like loky and Dask's worker processes: the child gets the parent's
    ``sys.path`` and working directory but not its main module, so a script
    without a main guard does not run again in every worker.
    """

    def __init__(self, method: str) -> None:
        self.ctx: Any = mp.get_context(method)
        self.Process = _PROCESS[method]
        if method == "forkserver":
            self.ctx.set_forkserver_preload(_PRELOAD)

    def __getattr__(self, name: str) -> Any:
        return getattr(self.ctx, name)



