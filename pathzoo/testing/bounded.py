"""A hard time limit on a conformance check: it runs in a forked child process that is killed at the limit.

A planner that ignores its budget must fail its check, not hang the test
suite. Python cannot interrupt a loop in compiled code (numba, C
extensions), so the check runs in a child forked from the test process,
which inherits the planner, the warmed-up JIT code and any monkeypatching.
The child reports back a JSON line through a pipe (nothing is unpickled);
the parent waits at most the limit, then kills the child and fails the check.

A first call of a planner may compile numba kernels for seconds or minutes
on a loaded machine; with ``compile_limit_s`` the limit counts only the wall
time outside numba's compilation (the child reports each compilation's start
and end), so a cold cache is not taken for a hung planner while a planner
that ignores its budget is still stopped at ``limit_s``.

A timeout raises :class:`BoundedTimeout`, also when it happened in a bounded
call made inside the child, so the caller can stop calling that planner.

Where ``fork`` is not available (Windows, or macOS by policy) the check runs
in the calling process, without the limit.
"""

from __future__ import annotations

import importlib.util
import json
import multiprocessing as mp
import time
from typing import Any, Callable

__all__ = ["run_bounded", "can_bound", "BoundedTimeout"]

_COMPILING, _RUNNING = b"c", b"r"
"""Messages of the child around numba compilation (a reply is JSON, so it starts with ``{``)."""


class BoundedTimeout(AssertionError):
    """A bounded call did not return within its limit and its process was killed."""


def can_bound() -> bool:
    """Whether this platform can fork, so :func:`run_bounded` enforces its limit."""
    return "fork" in mp.get_all_start_methods()


def _report_compilation(conn: Any) -> None:
    """Send :data:`_COMPILING` when numba starts compiling and :data:`_RUNNING` when it is done (outermost only)."""
    if importlib.util.find_spec("numba") is None:
        return
    from numba.core import event

    class Reporter(event.Listener):
        depth = 0

        def on_start(self, ev: Any) -> None:
            self.depth += 1
            if self.depth == 1:
                conn.send_bytes(_COMPILING)

        def on_end(self, ev: Any) -> None:
            self.depth -= 1
            if self.depth == 0:
                conn.send_bytes(_RUNNING)

    event.register("numba:compile", Reporter())


def _child(fn: Callable[[], Any], conn: Any, compile_aware: bool) -> None:
    reply: dict[str, Any]
    try:
        if compile_aware:
            _report_compilation(conn)
        fn()
        reply = {"ok": True}
    except BaseException as exc:  # noqa: BLE001 - every failure is reported to the parent
        reply = {"ok": False, "type": type(exc).__name__, "assertion": isinstance(exc, AssertionError),
                 "timeout": isinstance(exc, BoundedTimeout), "message": str(exc)}
    conn.send_bytes(json.dumps(reply).encode())
    conn.close()


def _wait(receive: Any, limit_s: float, compile_limit_s: float | None) -> tuple[bool, bytes, float]:
    """The child's reply (``ready``, its bytes) and the limit that passed first, if one did."""
    start = since = time.monotonic()
    outside, compiling = 0.0, False
    total = limit_s if compile_limit_s is None else compile_limit_s
    while True:
        now = time.monotonic()
        left_total = total - (now - start)
        left = left_total if compiling else min(left_total, limit_s - outside - (now - since))
        if left <= 0:
            return False, b"", total if left_total <= 0 else limit_s
        if not receive.poll(left):
            continue
        message = receive.recv_bytes()
        if message == _COMPILING:
            outside += time.monotonic() - since
            compiling = True
        elif message == _RUNNING:
            compiling, since = False, time.monotonic()
        else:
            return True, message, 0.0


def run_bounded(fn: Callable[[], Any], limit_s: float, what: str,
                failure: Callable[[str], BaseException], compile_limit_s: float | None = None) -> None:
    """Run ``fn()`` in a forked child, killed after ``limit_s`` seconds; re-raise its failure here.

    Parameters
    ----------
    fn : callable
        Called without arguments in the child; its return value is ignored.
    limit_s : float
        Wall seconds the child may run (outside numba compilation when
        ``compile_limit_s`` is given).
    what : str
        What ``fn`` does, for the timeout message (``"plan() with Budget(time_s=0.3)"``).
    failure : callable
        Builds the exception raised here from a message: the child's
        assertion message, ``"<Type>: <message>"`` for another error, or
        the child's death without a reply (a timeout raises
        :class:`BoundedTimeout` instead). A bounded call may itself make
        bounded calls (each forks again).
    compile_limit_s : float, optional
        Wall seconds the child may run in all, numba's compilation included;
        ``limit_s`` then counts the time outside compilation only.

    Raises
    ------
    BoundedTimeout
        When the child ran past a limit (and was killed), or reported a
        timeout of a bounded call of its own.
    """
    if not can_bound():
        fn()
        return
    ctx = mp.get_context("fork")
    receive, send = ctx.Pipe(duplex=False)
    # not a daemon: it may fork a bounded call itself
    child = ctx.Process(target=_child, args=(fn, send, compile_limit_s is not None))
    child.start()
    send.close()
    try:
        ready, raw, passed = _wait(receive, limit_s, compile_limit_s)
    except EOFError:  # the child died without a word (os._exit, a signal)
        ready, raw, passed = True, b"", 0.0
    finally:
        receive.close()
        if child.is_alive():
            child.kill()
        child.join()
    if not ready:
        raise BoundedTimeout(f"{what} had not returned after {passed:.3g} s; its process was killed")
    if not raw:
        raise failure(f"{what} ended its process (exit code {child.exitcode}) without returning")
    reply = json.loads(raw)
    if reply["ok"]:
        return
    message = reply["message"] if reply["assertion"] else f"{reply['type']}: {reply['message']}"
    if reply.get("timeout"):
        raise BoundedTimeout(message)
    raise failure(message)

