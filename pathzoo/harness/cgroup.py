"""A cgroup (v1) per sandboxed worker: limits on memory and process count, its CPU time, and killing its whole tree.

:class:`ProcessGroup` makes one group in each of the controllers
:data:`CONTROLLERS`, nested under the harness's own group of that
controller (read from ``/proc/self/cgroup``), so the limits of whatever runs
the harness still apply. A worker joins its group before it execs the
sandbox (:mod:`pathzoo.harness.sandbox`), so every process it or its planner
ever starts is in the group, whatever it does (``fork``, ``setsid``, double
fork): the kernel keeps a process in its parent's cgroup.

- :meth:`ProcessGroup.cpu_seconds` is ``cpuacct.usage``: user and system CPU
  time of every process that was ever in the group, dead children included,
  read from outside (about 20 microseconds);
- :meth:`ProcessGroup.pids` lists the processes in it (``cgroup.procs``);
- :meth:`ProcessGroup.kill` freezes the group (``freezer``), so that no
  process in it can fork while it is emptied, sends ``SIGKILL`` to each
  process, thaws it and waits until it is empty;
- ``memory.limit_in_bytes`` and ``pids.max`` bound memory and the number of
  tasks (threads count); a planner past the memory limit is killed by the
  kernel's OOM killer, one past the task limit gets ``EAGAIN`` from ``fork``.

Only the cgroup v1 layout (one hierarchy per controller under
``/sys/fs/cgroup/<controller>``) is supported; :func:`cgroup_problem` says
why groups cannot be made here.
"""

from __future__ import annotations

import errno
import os
import signal
import time
from pathlib import Path

__all__ = ["CONTROLLERS", "ProcessGroup", "cgroup_problem", "CGROUP_ROOT"]

CGROUP_ROOT = Path("/sys/fs/cgroup")
CONTROLLERS = ("pids", "memory", "cpuacct", "freezer")
"""The v1 controllers a worker's group uses."""

_KILL_ROUNDS = 200


def _own_groups() -> dict[str, str]:
    """This process's group path in each v1 controller hierarchy (``/proc/self/cgroup``)."""
    out: dict[str, str] = {}
    try:
        lines = Path("/proc/self/cgroup").read_text().splitlines()
    except OSError:
        return out
    for line in lines:
        _, controllers, path = line.split(":", 2)
        for controller in controllers.split(","):
            if controller:
                out[controller] = path
    return out


def _base(controller: str, own: dict[str, str]) -> Path:
    return CGROUP_ROOT / controller / own.get(controller, "/").lstrip("/")


def cgroup_problem() -> str:
    """Why per-worker cgroups cannot be made here (``""`` when they can)."""
    own = _own_groups()
    for controller in CONTROLLERS:
        base = _base(controller, own)
        if not (base / "cgroup.procs").is_file():
            return f"no cgroup v1 '{controller}' controller at {base}"
        if not os.access(base, os.W_OK):
            return f"cannot create cgroups under {base} (not writable)"
    return ""


def _remove_stale(base: Path) -> None:
    """Remove the empty groups left by harnesses that were killed (``pathzoo-<pid>`` of a pid that is gone)."""
    try:
        stale = [d for d in base.glob("pathzoo-*") if not Path(f"/proc/{d.name[8:]}").exists()]
    except OSError:
        return
    for harness in stale:
        for directory in [*harness.iterdir(), harness]:
            try:
                directory.rmdir()  # only an empty group can be removed: a live process keeps its own
            except OSError:
                pass


class ProcessGroup:
    """One cgroup per controller of :data:`CONTROLLERS`, made now (see the module docstring).

    Parameters
    ----------
    name : str
        Its name, unique within the harness process (it is made under
        ``pathzoo-<harness pid>/``).
    memory_bytes : int
        ``memory.limit_in_bytes``.
    max_tasks : int
        ``pids.max`` (processes and threads).
    """

    def __init__(self, name: str, *, memory_bytes: int, max_tasks: int) -> None:
        own = _own_groups()
        for controller in CONTROLLERS:
            _remove_stale(_base(controller, own))
        self.dirs = {c: _base(c, own) / f"pathzoo-{os.getpid()}" / name for c in CONTROLLERS}
        for path in self.dirs.values():
            path.mkdir(parents=True, exist_ok=True)
        (self.dirs["memory"] / "memory.limit_in_bytes").write_text(str(int(memory_bytes)))
        (self.dirs["pids"] / "pids.max").write_text(str(int(max_tasks)))
        self._usage = os.open(self.dirs["cpuacct"] / "cpuacct.usage", os.O_RDONLY | os.O_CLOEXEC)
        self._procs = str(self.dirs["freezer"] / "cgroup.procs")  # read after every run: no path built each time

    @property
    def procs_files(self) -> list[str]:
        """The ``cgroup.procs`` file of each controller: a process joins the group by writing its pid to each."""
        return [str(path / "cgroup.procs") for path in self.dirs.values()]

    def cpu_seconds(self) -> float:
        """CPU seconds (user + system) used by every process ever in the group (``cpuacct.usage``)."""
        return int(os.pread(self._usage, 32, 0)) / 1e9

    def pids(self) -> list[int]:
        """The processes in the group now."""
        try:
            with open(self._procs, "rb") as procs:
                text = procs.read()
        except OSError:
            return []
        return [int(p) for p in text.split()]

    def out_of_memory(self) -> bool:
        """Whether the kernel's OOM killer has killed a process of the group."""
        try:
            text = (self.dirs["memory"] / "memory.oom_control").read_text()
        except OSError:
            return False
        return any(line.split()[:1] == ["oom_kill"] and line.split()[1] != "0" for line in text.splitlines())

    def _freeze(self, state: str) -> None:
        try:
            (self.dirs["freezer"] / "freezer.state").write_text(state)
        except OSError:
            pass

    def kill(self, spare: frozenset[int] = frozenset()) -> None:
        """``SIGKILL`` every process of the group but those in ``spare``, none able to fork meanwhile; returns once
        only those are left."""
        for _ in range(_KILL_ROUNDS):
            pids = [pid for pid in self.pids() if pid not in spare]
            if not pids:
                return
            self._freeze("FROZEN")
            for pid in pids:
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            self._freeze("THAWED")  # a frozen process dies of SIGKILL only once thawed
            time.sleep(0.001)

    def remove(self) -> None:
        """Kill what is left and remove the groups (and the harness's parent group once it is empty)."""
        self.kill()
        os.close(self._usage)
        for path in self.dirs.values():
            for directory in (path, path.parent):
                try:
                    directory.rmdir()
                except OSError as exc:
                    if exc.errno not in (errno.ENOENT, errno.EBUSY, errno.ENOTEMPTY):
                        raise
