"""Hostile planners that attack through the operating system: the store, other processes, caches, the network.

A plugin module registered by hand in the test process (planners only: the
judge never imports it). Each planner does its attack, then claims
``SOLVED`` with a straight path through the wall of ``hostile.wall``, so a
harness that is fooled stores ``solved``.
"""

from __future__ import annotations

import os
import signal
import socket
import sqlite3
import subprocess
import sys
import time
from pathlib import Path
from typing import Sequence

import numpy as np

from pathzoo import Budget, Param, Planner, PlanResult, Scenario, Status, hookimpl
from pathzoo.core.planner import ProgressCallback

KINDS = frozenset({"grid2d", "terrain", "air3d", "dynamic"})
GRANDCHILD_ARG = "31.4159"
"""The argument of the ``sleep`` a grandchild becomes: the tests look for it after the experiment."""
HARNESS_MARKER = "pathzoo-hostile-harness-marker"
"""In the command line of the harness the ``KillHarness`` planner hunts."""


def _straight(scenario: Scenario) -> np.ndarray:
    return np.array([scenario.start, scenario.goal], dtype=float)


def _cmdline(pid: str) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode("utf-8", "replace")
    except OSError:
        return ""


def _pids() -> list[str]:
    return [p for p in os.listdir("/proc") if p.isdigit() and int(p) != os.getpid()]


def _parent_of(pid: int) -> int:
    try:
        return int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])
    except (OSError, ValueError, IndexError):
        return 0


def _ancestors() -> list[int]:
    """The chain of parents this process can see (up to the harness when unsandboxed); never beyond them."""
    out, pid = [], os.getppid()
    while pid > 1 and len(out) < 8:
        out.append(pid)
        pid = _parent_of(pid)
    return out


class _Hostile(Planner):
    kinds = KINDS
    summary = "hostile test planner"

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        message = self.attack(scenario)
        return PlanResult(Status.SOLVED, path=_straight(scenario), iterations=1, evaluations=1, message=message)

    def attack(self, scenario: Scenario) -> str:
        raise NotImplementedError


def _forge(db: str, run_key_part: str) -> str:
    """Mark the rival's stored rows invalid and insert forged solved rows: what succeeded, as text."""
    conn = sqlite3.connect(db, timeout=1.0)
    conn.execute("UPDATE runs SET status = 'invalid', valid = 0 WHERE run_key LIKE ?", (f"%{run_key_part}%",))
    conn.commit()
    conn.close()
    return "forged"


class StoreWriter(_Hostile):
    """Finds the result database among its ancestors' open files (and by its path) and rewrites the rival's rows."""

    id = "sandbox.store"
    params = {"db": Param("", "the database path, as an attacker could guess it"),
              "rival": Param("exact.astar", "run keys to spoil")}

    def attack(self, scenario: Scenario) -> str:
        found = {self.db}
        for pid in _ancestors():
            try:
                for fd in os.listdir(f"/proc/{pid}/fd"):
                    target = os.readlink(f"/proc/{pid}/fd/{fd}")
                    if target.endswith(".sqlite"):
                        found.add(f"/proc/{pid}/fd/{fd}")
            except OSError:
                continue
        done = []
        for path in sorted(found):
            try:
                done.append(_forge(path, self.rival))
            except (sqlite3.Error, OSError):
                continue
        time.sleep(0.5)  # let the rival's rows be stored, then try again
        for path in sorted(found):
            try:
                done.append(_forge(path, self.rival))
            except (sqlite3.Error, OSError):
                continue
        return f"wrote to {len(done)} database(s)"


class ReplaceCachedScenario(_Hostile):
    """Replaces the worker's cached copy of the scenario with one whose wall is gone, for the runs after it."""

    id = "sandbox.scenario_cache"

    def attack(self, scenario: Scenario) -> str:
        import dataclasses

        from pathzoo.harness import scenario_cache

        for key, (cached, digest) in list(scenario_cache._scenarios.items()):
            open_map = dataclasses.replace(cached, occupancy=np.zeros_like(cached.occupancy))
            scenario_cache._scenarios[key] = (open_map, digest)
        return "replaced"


class RecursionLimit(_Hostile):
    """Leaves the interpreter's recursion limit at 40."""

    id = "sandbox.recursion"

    def attack(self, scenario: Scenario) -> str:
        sys.setrecursionlimit(40)
        return "limit 40"


def _kill(pids: list[int]) -> int:
    """SIGKILL each pid; how many signals were delivered."""
    killed = 0
    for pid in pids:
        try:
            os.kill(pid, signal.SIGKILL)
            killed += 1
        except OSError:
            pass
    return killed


class KillWorkers(_Hostile):
    """Sends SIGKILL to its siblings (the other workers and the judge, when they share its parent)."""

    id = "sandbox.kill_workers"

    def attack(self, scenario: Scenario) -> str:
        siblings = [int(p) for p in _pids() if _parent_of(int(p)) == os.getppid() and os.getppid() > 1]
        return f"killed {_kill(siblings)}"


class KillHarness(_Hostile):
    """Sends SIGKILL to the harness (found by a marker in its command line) and to its own parent."""

    id = "sandbox.kill_harness"

    def attack(self, scenario: Scenario) -> str:
        harness = [int(p) for p in _pids() if HARNESS_MARKER in _cmdline(p) and "multiprocessing" not in _cmdline(p)]
        killed = _kill(harness)
        _kill([os.getppid()])
        return f"killed {killed}"


class Grandchild(_Hostile):
    """Leaves a grandchild (fork, setsid, fork) that becomes ``sleep 31.4159`` and outlives the run."""

    id = "sandbox.grandchild"

    def attack(self, scenario: Scenario) -> str:
        pid = os.fork()
        if pid == 0:
            os.setsid()
            if os.fork() == 0:
                os.execv("/bin/sleep", ["sleep", GRANDCHILD_ARG])
            os._exit(0)
        os.waitpid(pid, 0)
        return "left a grandchild"


def numba_index_files() -> list[Path]:
    """Where numba keeps the cache index of pathzoo's own compiled functions (in the installed package)."""
    import pathzoo

    return [Path(pathzoo.__file__).parent / "grid" / "__pycache__" / "pathzoo-sandbox-canary.nbi"]


class PoisonCache(_Hostile):
    """Writes a numba cache index (read with pickle by the judge) into the installed package.

    First it tries to make the file system writable again (``mount -o
    remount,bind,rw /``), which root with its capabilities could do inside
    a mount namespace.
    """

    id = "sandbox.poison_cache"

    def attack(self, scenario: Scenario) -> str:
        subprocess.run(["mount", "-o", "remount,bind,rw", "/"], capture_output=True, check=False)
        written = 0
        for path in numba_index_files():
            try:
                path.parent.mkdir(exist_ok=True)
                path.write_bytes(b"not a pickle you want to load")
                written += 1
            except OSError:
                pass
        return f"wrote {written}"


class Network(_Hostile):
    """Connects to a TCP port on the host's loopback."""

    id = "sandbox.network"
    params = {"port": Param(1, "the port to connect to", low=1, high=65535)}

    def attack(self, scenario: Scenario) -> str:
        try:
            with socket.create_connection(("127.0.0.1", self.port), timeout=2.0) as conn:
                conn.sendall(b"leak")
            return "connected"
        except OSError as exc:
            return f"no connection ({type(exc).__name__})"


class Hog(_Hostile):
    """Touches ``mib`` MiB of memory, forks ``children`` sleeping children, or writes ``disk_mib`` MiB to a file."""

    id = "sandbox.hog"
    params = {"mib": Param(0, "memory to touch", low=0), "children": Param(0, "children to fork", low=0),
              "disk_mib": Param(0, "MiB to write to a file in the working directory", low=0)}

    def attack(self, scenario: Scenario) -> str:
        if self.disk_mib:
            written = 0
            try:
                with open("fill", "wb") as fh:
                    for _ in range(self.disk_mib):
                        fh.write(b"\0" * 2**20)
                        fh.flush()
                        written += 1
            except OSError as exc:
                return f"wrote {written} MiB ({exc.strerror})"
            return f"wrote {written} MiB"
        block = np.ones(self.mib * 2**20 // 8) if self.mib else None
        started = 0
        for _ in range(self.children):
            try:
                if os.fork() == 0:
                    time.sleep(60)
                    os._exit(0)
                started += 1
            except OSError:
                break
        return f"touched {0 if block is None else block.nbytes >> 20} MiB, {started} children"


class Spin(_Hostile):
    """Burns CPU in a child process while the planner itself sleeps, then claims success."""

    id = "sandbox.spin"
    params = {"seconds": Param(1.0, "CPU seconds of the child", low=0.0)}

    def attack(self, scenario: Scenario) -> str:
        pid = os.fork()
        if pid == 0:
            end = time.process_time() + self.seconds
            while time.process_time() < end:
                pass
            os._exit(0)
        os.waitpid(pid, 0)
        return "spun in a child"


PLANNERS = [StoreWriter, ReplaceCachedScenario, RecursionLimit, KillWorkers, KillHarness, Grandchild, PoisonCache,
            Network, Hog, Spin]


@hookimpl
def pathzoo_register_planners() -> Sequence[type[Planner]]:
    return PLANNERS
