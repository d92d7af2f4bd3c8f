"""The worker side of the process executor: the loop of a worker process and the frames it sends.

A worker (started by :func:`~pathzoo.harness.executors.worker_handle.launch_worker`)
runs :func:`worker_main`: it receives tasks on its pipe, runs each in a
fresh child (:class:`~pathzoo.harness.zygote.Zygote`) and answers with short
tagged byte strings; the harness never unpickles what a worker sends
(:mod:`pathzoo.harness.executors.process` reads the frames, and
:mod:`pathzoo.harness.wire` the outcome).
"""

from __future__ import annotations

import signal
import struct
from multiprocessing.connection import Connection
from typing import Any, Callable

from pathzoo.harness.clock_stop import SharedClockStop
from pathzoo.harness.launch import die_with_harness
from pathzoo.harness.scenario_cache import keep_payload
from pathzoo.harness.tamper import ModuleFingerprint
from pathzoo.harness.zygote import WarmUp, Zygote, drop_resource_tracker, refuse_audit_hooks, undumpable

__all__ = ["EVENTS", "CPU_FRAME", "worker_main"]

EVENTS = {"warming": b"U", "started": b"S", "planning": b"P"}
"""The frame each event of a run sends (:meth:`~pathzoo.harness.zygote.Zygote.run`\'s ``report``)."""


CPU_FRAME = struct.Struct("<d")
"""The child's CPU seconds at the head of a ``D`` message, as the zygote's ``wait4`` read them from the kernel."""


def worker_main(conn: Connection, alive: Connection, stop_flag: Any, sandboxed: bool = False) -> None:
    """Loop of one worker process (a :class:`~pathzoo.harness.zygote.Zygote`): receive a task, run it in a fresh
    child, send the outcome and whether the process is clean."""
    die_with_harness(alive)
    drop_resource_tracker()
    refuse_audit_hooks()
    undumpable()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sandboxed:  # spawned, not forked from the server that has done this already
        import pathzoo.harness.executors.warmup  # noqa: F401
    fingerprint = ModuleFingerprint().update()
    zygote = Zygote(SharedClockStop(stop_flag))
    conn.send_bytes(b"R")
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            return
        if task is None:
            return
        if isinstance(task, WarmUp):
            zygote.warm_up(task, reporter(conn))
            fingerprint.update().changed()  # the modules the warm-up loaded, and the quick check armed, uncharged:
            # checked after a run, only what that run moved is examined, and the outcome goes out sooner
            conn.send_bytes(b"W")
            continue
        keep_payload(task.scenario)  # the executor counts it as held from now on
        try:
            data, child_cpu = zygote.run(task, reporter(conn))
        except (EOFError, OSError):
            return
        changed = fingerprint.changed() + zygote.residue  # the outcome and the verdict on the process go out together
        try:
            conn.send_bytes(b"D" + CPU_FRAME.pack(child_cpu) + data)
        except (EOFError, OSError):
            return
        if changed:
            conn.send_bytes(b"T" + ", ".join(changed).encode("utf-8", "replace")[:1000])
            return
        fingerprint.update()
        conn.send_bytes(b"I")


def reporter(conn: Connection) -> "Callable[[str], None]":
    """The ``report`` callback of :meth:`~pathzoo.harness.zygote.Zygote.run`: send the event."""

    def report(event: str) -> None:
        conn.send_bytes(EVENTS[event])

    return report
