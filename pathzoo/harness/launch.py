"""Start harness processes (workers, the judge) that never import the parent's ``__main__``.

:mod:`multiprocessing`'s ``spawn`` and ``forkserver`` methods make each child
re-import the parent's main module, which runs an unguarded script a second
time in every child (and fails). Like loky and Dask's worker processes,
:class:`NoMainContext` leaves the main module out of the data a child is
prepared with; the child still gets the parent's ``sys.path`` and working
directory. With ``forkserver`` (the default where available) the server
imports numpy, numba, scipy and pathzoo's own harness, geometry and
validation code once, and warms numba up, but imports no plugin
(:mod:`pathzoo.harness.executors.warmup`); the workers and the judge are all
forks of it, so each starts with that done instead of redoing it, and the
judge still starts in a process where no planner code ever ran.
:func:`start_server` starts it early, so it imports while the harness is
still reading the experiment.

Children die with the harness (:func:`die_with_harness`): a ``kill -9`` of
the harness process leaves no worker or judge behind. On Linux each child
asks the kernel for ``SIGKILL`` when its parent dies
(``prctl(PR_SET_PDEATHSIG)``). A forkserver child's parent is the server,
which exits when its own life pipe from the harness reports end of file; each
child inherits a write end of that pipe (so that it could fork through the
server itself), which would keep the server, and so the child, alive after
the harness's death, so the child closes it first. Everywhere, a watchdog
thread also ends the child when the read end of a pipe whose only writer is
the harness reports end of file (it cannot run while a planner holds the GIL
in a long C call, which is why the kernel's signal comes first).
"""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import os
import signal
import threading
from multiprocessing import popen_forkserver, popen_spawn_posix, resource_tracker, spawn
from multiprocessing.connection import Connection
from typing import Any, Iterator

from pathzoo.parent_death import die_with_parent

__all__ = [
    "PRELOAD",
    "NoMainContext",
    "ForkServerNoMainProcess",
    "SpawnNoMainProcess",
    "SandboxedProcess",
    "default_start_method",
    "start_server",
    "harness_alive",
    "die_with_harness",
    "die_with_parent",
]

PRELOAD = ("pathzoo.harness.executors.warmup", "pathzoo.harness.executors.worker_loop")
"""What the ``forkserver`` imports, in order: what every harness process needs (it stops the server with the harness
first), then the workers' code."""
_launch_lock = threading.Lock()


def default_start_method() -> str:
    """``forkserver`` where the platform has it, else ``spawn``."""
    return "forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn"


def start_server(method: str | None = None) -> None:
    """Start the ``forkserver`` now if it is not running, without waiting for it (no-op for ``spawn``).

    The server imports what every harness process needs
    (:mod:`pathzoo.harness.executors.warmup`) while the caller goes on, e.g.
    reading and checking the experiment on the other core; the judge and
    each worker then cost a fork instead of a cold start. The server dies
    with the thread that started it (see :func:`die_with_parent`), so call
    this from the main thread: the executors and the judge do, from the
    thread that builds them.
    """
    if (method or default_start_method()) != "forkserver":
        return
    NoMainContext("forkserver")  # sets the preload list of the server
    from multiprocessing import forkserver

    with _main_left_out():
        forkserver.ensure_running()


_alive: tuple[Connection, Connection] | None = None


def harness_alive() -> Connection:
    """The read end of this process's life pipe, to hand to each child (see :func:`die_with_harness`).

    The write end is kept by this process only and never written to or
    closed, so a child's read end reports end of file exactly when this
    process is gone.
    """
    global _alive
    with _launch_lock:
        if _alive is None:
            _alive = mp.Pipe(duplex=False)
        return _alive[0]


def die_with_harness(alive: Connection) -> None:
    """In a child: be killed when the harness dies (see the module docstring); call it first thing.

    Parameters
    ----------
    alive : Connection
        The child's copy of :func:`harness_alive`.
    """
    from multiprocessing import forkserver

    server: Any = forkserver._forkserver  # a forkserver child inherits the write end of the server's own life pipe:
    if server._forkserver_alive_fd is not None:  # with it open, the server outlives the harness while we run
        os.close(server._forkserver_alive_fd)
        server._forkserver_alive_fd = None
    die_with_parent()

    def watch() -> None:
        try:
            alive.poll(None)  # only end of file ever arrives
        except (OSError, EOFError):
            pass
        os.kill(os.getpid(), signal.SIGKILL)

    threading.Thread(target=watch, name="pathzoo-harness-watch", daemon=True).start()


def _without_main(prepare: Any, sandboxed: bool) -> Any:
    def prepared(name: str) -> dict[str, Any]:
        data = prepare(name)
        data.pop("init_main_from_name", None)
        data.pop("init_main_from_path", None)
        if sandboxed:  # it stays in its scratch directory; "" on sys.path still means the harness's directory
            cwd = data.pop("dir", os.getcwd())
            data["sys_path"] = [p or cwd for p in data.get("sys_path", [])]
        return data
    return prepared


@contextlib.contextmanager
def _main_left_out(sandbox_prefix: "list[str] | None" = None) -> Iterator[None]:
    """Launches made inside get preparation data without the parent's main module (one launch at a time).

    With ``sandbox_prefix`` (a ``spawn`` launch only) the child's command
    line is that prefix followed by the usual ``python -c ...``
    (:func:`pathzoo.harness.sandbox.sandboxed_command`).
    """
    with _launch_lock:
        original = spawn.get_preparation_data, spawn.get_command_line, spawn.get_executable
        spawn.get_preparation_data = _without_main(original[0], sandbox_prefix is not None)
        if sandbox_prefix is not None:
            python, command_line = os.fsdecode(original[2]()), original[1]
            spawn.get_command_line = lambda **kwds: [*sandbox_prefix, python, *command_line(**kwds)[1:]]
            spawn.get_executable = lambda: os.fsencode(sandbox_prefix[0])  # type: ignore[assignment, return-value]
        try:
            yield
        finally:
            spawn.get_preparation_data, spawn.get_command_line, spawn.get_executable = original


def _no_main_popen(base: Any) -> Any:
    class NoMainPopen(base):
        """Launch without the main module in the preparation data (so the child never re-imports it)."""

        def _launch(self, process_obj: Any) -> None:
            with _main_left_out():
                super()._launch(process_obj)
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


class _SandboxedPopen(popen_spawn_posix.Popen):
    """A ``spawn`` launch through the process's :attr:`SandboxedProcess.sandbox_prefix`."""

    def _launch(self, process_obj: Any) -> None:
        resource_tracker.ensure_running()  # before the command line is patched: it is spawned with the same calls
        with _main_left_out(process_obj.sandbox_prefix):
            super()._launch(process_obj)  # type: ignore[misc]


class SandboxedProcess(mp.context.SpawnProcess):
    """A ``spawn`` process started inside the sandbox given by ``sandbox_prefix`` (set it before ``start``).

    ``sandbox_prefix`` is the command that runs the rest of its command line
    in the sandbox (:func:`pathzoo.harness.sandbox.sandboxed_command` of no
    command); the child is launched without the parent's main module and
    stays in the sandbox's working directory.
    """

    sandbox_prefix: list[str] = []

    @staticmethod
    def _Popen(process_obj: Any) -> Any:
        return _SandboxedPopen(process_obj)


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
            self.ctx.set_forkserver_preload(list(PRELOAD))

    def __getattr__(self, name: str) -> Any:
        return getattr(self.ctx, name)



