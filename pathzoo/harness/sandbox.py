"""The OS sandbox of a planner's worker process: bubblewrap namespaces inside a cgroup of its own.

A sandboxed worker is started as::

    sh -c 'echo $$ > <each cgroup.procs>; exec "$@"' sh  bwrap <options> -- python -c <multiprocessing spawn>

so it joins its :class:`~pathzoo.harness.cgroup.ProcessGroup` before
anything else runs, and ``bwrap`` (bubblewrap, as in Flatpak) then gives it:

- a mount namespace in which the whole file system is mounted read-only
  (``--ro-bind / /``: ``/usr``, the Python install, pathzoo, the result
  database, the judge's and the harness's numba and graph caches), a fresh
  ``/proc`` whose ``/proc/sys`` is mounted read-only (run by root, a planner
  could otherwise set global sysctls such as ``kernel.core_pattern``, whose
  pipe form runs a program as the host's root), a fresh ``/dev``, empty ``/tmp``, ``/var/tmp``, ``/run`` and
  ``/dev/shm`` (so no socket of the harness, its ``forkserver`` or its
  resource tracker is reachable), and two writable directories: the
  worker's scratch directory (its working directory, ``HOME`` and
  ``TMPDIR``: a memory file system of :attr:`SandboxLimits.scratch_bytes`,
  whose pages count towards the cgroup's memory, so a planner cannot fill
  the disk) and the numba cache of its planner (``NUMBA_CACHE_DIR``); the
  folders the import system resolves (:func:`import_roots`: ``sys.path``,
  editable installs' mapped source folders, imported packages) and those of
  the scenario files under the hidden ones are mounted back, read-only;
- a PID namespace (it sees and can signal only its own processes: not the
  harness, the judge or other workers), a network namespace without any
  interface but loopback, and new IPC, UTS and cgroup namespaces;
- no capabilities (``--cap-drop ALL``): run by root, bubblewrap would keep
  them, and a planner could remount the file system read-write
  (``mount -o remount,bind,rw /``) or create device nodes;
- its own session (``--new-session``: no ``TIOCSTI`` into the terminal), and
  death with the harness (``--die-with-parent``).

``/usr/bin`` and everything else stay readable and executable, so a planner
may run GNU Octave or a compiled program as its child; the child is in the
same namespaces and cgroup.

:func:`sandbox_problem` says why workers cannot be sandboxed here (no
``bwrap``, not Linux, no cgroup v1 controllers, or namespaces refused, as
for unprivileged users where user namespaces are off); the harness then runs
them unsandboxed and says so in one line (see ``docs/sandbox.md``).
"""

from __future__ import annotations

import functools
import hashlib
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Sequence

from pathzoo.core.errors import PathzooError
from pathzoo.harness.cgroup import cgroup_problem

__all__ = ["SandboxUnavailableError", "SandboxImportError", "SandboxLimits", "sandbox_problem", "sandboxed_command", "worker_numba_cache",
           "import_roots", "import_problem", "HIDDEN_DIRS"]

HIDDEN_DIRS = ("/tmp", "/var/tmp", "/run", "/dev/shm")
"""Replaced by empty directories inside the sandbox (sockets and files of other processes live there)."""


class SandboxUnavailableError(PathzooError, RuntimeError):
    """A sandbox was required (``pathzoo run --require-sandbox``) but this system cannot provide one."""


class SandboxImportError(PathzooError, RuntimeError):
    """A module a sandboxed child needs cannot be imported inside the sandbox; the message names its folder."""


@dataclass(frozen=True)
class SandboxLimits:
    """Limits of one sandboxed worker's cgroup.

    Attributes
    ----------
    memory_bytes : int
        Memory of the worker and its children (default 4 GiB).
    max_tasks : int
        Processes and threads (default 512).
    scratch_bytes : int
        Size of the worker's scratch directory, a memory file system of its own (default 1 GiB; its pages also
        count towards ``memory_bytes``).
    """

    memory_bytes: int = 4 << 30
    max_tasks: int = 512
    scratch_bytes: int = 1 << 30

    @classmethod
    def with_memory_gib(cls, gib: float) -> "SandboxLimits":
        """The default limits with ``gib`` GiB of memory."""
        return cls(memory_bytes=int(gib * 2**30))


@functools.lru_cache(maxsize=1)
def sandbox_problem() -> str:
    """Why planner processes cannot be sandboxed here, in a few words (``""`` when they can); checked once."""
    if not sys.platform.startswith("linux"):
        return f"no Linux namespaces on {sys.platform}"
    bwrap = shutil.which("bwrap")
    if bwrap is None:
        return "bubblewrap (bwrap) is not installed"
    problem = cgroup_problem()
    if problem:
        return problem
    probe = [bwrap, "--ro-bind", "/", "/", "--proc", "/proc", "--dev", "/dev", "--unshare-all", "--die-with-parent",
             "--", "/bin/true"]
    try:
        done = subprocess.run(probe, capture_output=True, timeout=30)
    except (OSError, subprocess.SubprocessError) as exc:
        return f"bwrap could not run ({exc})"
    if done.returncode:
        err = done.stderr.decode("utf-8", "replace").strip().splitlines()
        return f"bwrap cannot create namespaces here ({err[-1] if err else f'exit code {done.returncode}'})"
    return ""


def worker_numba_cache(planner_id: str) -> Path:
    """The numba cache directory of one planner's sandboxed workers (the only cache they may write).

    Under ``$NUMBA_CACHE_DIR`` when it is set (so a user's choice of numba
    cache, an empty one included, holds for the planners too), else under
    ``$PATHZOO_CACHE_DIR`` (else ``$XDG_CACHE_HOME/pathzoo``, else
    ``~/.cache/pathzoo``), in ``sandbox-numba/<planner id>``: a planner can
    write only there, so it can poison only its own compiled code, never the
    judge's, the harness's or another planner's.
    """
    root = os.environ.get("NUMBA_CACHE_DIR") or os.environ.get("PATHZOO_CACHE_DIR")
    if root:
        base = Path(root)
    else:
        xdg = os.environ.get("XDG_CACHE_HOME")
        base = (Path(xdg) if xdg else Path.home() / ".cache") / "pathzoo"
    safe = "".join(c if c.isalnum() or c in "._-" else "_" for c in planner_id)[:80]
    tag = hashlib.sha256(planner_id.encode()).hexdigest()[:8]
    return base / "sandbox-numba" / f"{safe}-{tag}"


def _under(path: str, roots: Sequence[str]) -> bool:
    return any(path == root or path.startswith(root.rstrip("/") + "/") for root in roots)


def _hidden_roots() -> list[str]:
    roots = list(HIDDEN_DIRS)
    tmp = os.path.realpath(tempfile.gettempdir())
    if not _under(tmp, roots):
        roots.append(tmp)
    return roots


def _visible_again(paths: Iterable[str], hidden: Sequence[str]) -> list[str]:
    """The existing paths (e.g. ``sys.path`` entries, scenario files) under a hidden directory, outermost first."""
    found = sorted({os.path.realpath(p) for p in paths if p and os.path.exists(p)})
    found = [p for p in found if _under(p, hidden)]
    return [p for i, p in enumerate(found) if not any(_under(p, [q]) for q in found[:i])]


def import_roots() -> list[str]:
    """The folders this process's import system resolves modules from; the sandbox binds those it hides.

    ``sys.path``; the folders that editable installs' finders on
    ``sys.meta_path`` map packages to (setuptools' ``MAPPING`` and
    ``NAMESPACES`` of its ``__editable___*_finder`` modules, which are not on
    ``sys.path``); and the folders of the top-level packages already imported
    (whatever finder found them).
    """
    roots = [p for p in sys.path if p]  # '' is the current directory: inside, the child's own (its scratch)
    for finder in sys.meta_path:
        module = sys.modules.get(getattr(finder, "__module__", None) or type(finder).__module__)
        for table in (getattr(module, "MAPPING", None), getattr(module, "NAMESPACES", None)):
            if isinstance(table, dict):
                for value in table.values():
                    roots += [v for v in (value if isinstance(value, list) else [value]) if isinstance(v, str)]
    for name, module in list(sys.modules.items()):
        if "." not in name:  # a top-level package's own folder (a module's would be a whole directory, e.g. /tmp)
            roots += [p for p in getattr(module, "__path__", None) or () if isinstance(p, str)]
    return list(dict.fromkeys(roots))


def import_problem(stderr: str) -> str:
    """Why a sandboxed child could not import a module, in one line, from its stderr (``""`` when it is no such case).

    Names the module's folder in this process and the hidden directory it is
    under, or says that this process cannot import it either.
    """
    import importlib.util
    import re

    found = re.findall(r"No module named '([^']+)'", stderr)
    if not found:
        return ""
    name = found[-1]
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError):
        spec = None
    if spec is None:
        return f"module '{name}' cannot be imported (not in this Python either)"
    where = list(spec.submodule_search_locations or []) or [os.path.dirname(spec.origin or "")]
    folder = os.path.realpath(where[0])
    hidden = [root for root in _hidden_roots() if _under(folder, [root])]
    if hidden:
        return (f"module '{name}' is in {folder}, under {hidden[0]}, which the sandbox hides, and no import path or "
                "editable finder of this Python names that folder")
    return f"module '{name}' (in {folder}) cannot be imported inside the sandbox"


def sandboxed_command(command: Sequence[str], *, procs_files: Sequence[str], scratch: Path, numba_cache: Path,
                      readable: Iterable[str] = (), scratch_bytes: int = SandboxLimits.scratch_bytes) -> list[str]:
    """``command`` wrapped to join the cgroup and run inside bubblewrap (see the module docstring).

    Parameters
    ----------
    command : sequence of str
        What to run inside (an absolute executable first).
    procs_files : sequence of str
        The ``cgroup.procs`` files of the worker's group
        (:attr:`~pathzoo.harness.cgroup.ProcessGroup.procs_files`); none for
        a short-lived child that needs no limits (its PID namespace dies
        with it).
    scratch : Path
        The worker's working directory (made if missing): inside, an empty memory file system of
        ``scratch_bytes`` mounted there, so nothing a planner writes reaches the disk or outlives it.
    numba_cache : Path
        The writable numba cache of its planner (:func:`worker_numba_cache`; made if missing).
    readable : iterable of str
        Paths the worker must read besides ``sys.path`` (the directories of
        the scenario files, with the maps they name); only those under a
        hidden directory need naming.
    scratch_bytes : int
        Size of the scratch file system (:attr:`SandboxLimits.scratch_bytes`).
    """
    bwrap = shutil.which("bwrap")
    if bwrap is None:
        raise SandboxUnavailableError("bubblewrap (bwrap) is not installed")
    scratch.mkdir(parents=True, exist_ok=True)
    numba_cache.mkdir(parents=True, exist_ok=True)
    hidden = _hidden_roots()
    args = [bwrap, "--ro-bind", "/", "/", "--dev", "/dev", "--proc", "/proc", "--ro-bind", "/proc/sys", "/proc/sys"]
    for root in hidden:
        if os.path.isdir(root):
            args += ["--tmpfs", root]
    # the interpreter's environment (a venv's pyvenv.cfg and bin/) as well as its import path: a venv made
    # under a hidden directory such as /tmp (CI's is) must still start Python with its site-packages
    python = [sys.prefix, sys.exec_prefix, os.path.dirname(os.path.abspath(sys.executable))]
    for path in _visible_again([*python, *import_roots(), *readable], hidden):
        args += ["--ro-bind", path, path]
    args += ["--size", str(int(scratch_bytes)), "--tmpfs", str(scratch), "--bind", str(numba_cache), str(numba_cache)]
    args += ["--unshare-all", "--cap-drop", "ALL", "--new-session", "--die-with-parent", "--chdir", str(scratch),
             "--setenv", "HOME", str(scratch), "--setenv", "TMPDIR", str(scratch),
             "--setenv", "NUMBA_CACHE_DIR", str(numba_cache), "--", *command]
    join = "".join(f"echo $$ > {shlex.quote(p)} && " for p in procs_files)
    return ["/bin/sh", "-c", f"{join}exec \"$@\" || exit 97", "sh", *args]
