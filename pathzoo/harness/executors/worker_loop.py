"""The worker side of the process executor: the loop of a worker process and the frames it sends.

A worker (started by :func:`~pathzoo.harness.executors.worker_handle.launch_worker`)
runs :func:`worker_main`: it receives tasks on its pipe, runs each in a
fresh child (:class:`~pathzoo.harness.zygote.Zygote`) and answers with short
tagged byte strings; the harness never unpickles what a worker sends
(:mod:`pathzoo.harness.executors.process` reads the frames, and
:mod:`pathzoo.harness.wire` the outcome).

The frames, and what the harness does with each:

- ``R`` (ready) once started, ``I`` (idle) after each run when the process
  is still clean, ``T`` (tainted) when the run rebound module attributes
  (:mod:`pathzoo.harness.tamper`) or the warm-up left planner code running
  (:class:`~pathzoo.harness.zygote.Residue`): that worker is retired and a
  fresh one started, so no planner's patch reaches another run;
- a new worker is first sent a :class:`~pathzoo.harness.zygote.WarmUp`
  (the configuration and the scenario kind, nothing of any run): ``U``
  once it has built the planner (the warm-up has the run's hard limit
  ``timeout_s`` from there), ``W`` when its warm-up is done: the worker's
  CPU is charged to its runs from then on, and the run is sent;
- ``S`` (started: scenario loaded and its graph built): the hard limit
  ``timeout_s`` counts from the *first* ``S``; later ones are ignored. The
  setup before it has its own limit,
  :data:`~pathzoo.harness.worker.SETUP_TIMEOUT_S`, and is recorded as ``crash``;
- after ``S`` the worker waits for the harness's ``G`` (:data:`GO`). An idle
  worker gets it with its run. A busy one may be sent its configuration's
  next run ahead, behind its current one in the pipe: it sets that run up
  as soon as it has sent ``D`` and ``I``, and the harness says ``G`` once it
  has seen at ``I`` that the last run left no process behind (else the
  worker is retired and the run sent ahead goes to another);
- ``P`` (hand-over, just before the worker forks the run's child): the wall
  clock starts;
- ``D`` + the child's CPU seconds (``wait4``) + the outcome, sent once the
  child has exited and been reaped: the run ends. Wall time is the
  harness's ``time.perf_counter`` from ``P`` to ``D``; CPU time is the
  larger of the worker's process tree and cgroup
  (:class:`~pathzoo.harness.cpu_clock.ChargedCpu`: for a sandboxed worker,
  the tree under its ``bwrap`` process) from the end of the previous run
  (or ``W``) to ``D``, and of the child's figure from ``D`` (which can only
  raise it), all read from the kernel, so a planner cannot change its own
  timings (``docs/sandbox.md``, "What a run is charged"). While a run with
  a clock limit plans, the monitor reads these clocks (for ``cpu_s``: see
  :data:`~pathzoo.harness.executors.run_clocks.CLOCK_POLL_S`) and sets the worker's shared stop byte
  (:class:`~pathzoo.harness.clock_stop.SharedClockStop`) when a limit is
  spent; the run is stored with the stop the harness set (``stopped_by``),
  whatever the planner did with the byte. A ``D`` before ``P`` (a failed
  setup) is a ``crash`` whatever it says; any other frame while a run is
  out (a repeated one, or one the planner's warm-up wrote on the control
  socket) is ignored.
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

__all__ = ["EVENTS", "GO", "CPU_FRAME", "worker_main"]

EVENTS = {"warming": b"U", "started": b"S", "planning": b"P"}
"""The frame each event of a run sends (:meth:`~pathzoo.harness.zygote.Zygote.run`\'s ``report``)."""


GO = b"G"
"""The harness's word that the worker may hand its current run over (its last one left nothing behind)."""

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
            data, child_cpu = zygote.run(task, reporter(conn), go_waiter(conn))
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
        conn.send_bytes(b"I")  # right behind the outcome: the harness reads both at one wake-up, and may send the next
        fingerprint.update()  # run at once (it waits in the pipe while the modules this run loaded are snapshotted)


def go_waiter(conn: Connection) -> "Callable[[], None]":
    """The ``go`` callback of :meth:`~pathzoo.harness.zygote.Zygote.run`: wait for the harness's ``G``
    (:class:`EOFError` for anything else)."""

    def go() -> None:
        if conn.recv_bytes(16) != GO:
            raise EOFError("the harness sent something other than G")

    return go


def reporter(conn: Connection) -> "Callable[[str], None]":
    """The ``report`` callback of :meth:`~pathzoo.harness.zygote.Zygote.run`: send the event."""

    def report(event: str) -> None:
        conn.send_bytes(EVENTS[event])

    return report
