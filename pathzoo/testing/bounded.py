"""A hard time limit on a conformance check: it runs in a forked child process that is killed at the limit.

A planner that ignores its budget must fail its check, not hang the test
suite. Python cannot interrupt a loop in compiled code (numba, C
extensions), so the check runs in a child forked from the test process,
which inherits the planner, the warmed-up JIT code and any monkeypatching.
The child reports back a JSON line through a pipe (nothing is unpickled);
the parent waits at most the limit, then kills the child and fails the check.

Where ``fork`` is not available (Windows, or macOS by policy) the check runs
in the calling process, without the limit.
"""

from __future__ import annotations

import json
import multiprocessing as mp
from typing import Any, Callable

__all__ = ["run_bounded", "can_bound"]


def can_bound() -> bool:
    """Whether this platform can fork, so :func:`run_bounded` enforces its limit."""
    return "fork" in mp.get_all_start_methods()


def _child(fn: Callable[[], Any], conn: Any) -> None:
    reply: dict[str, Any]
    try:
        fn()
        reply = {"ok": True}
    except BaseException as exc:  # noqa: BLE001 - every failure is reported to the parent
        reply = {"ok": False, "type": type(exc).__name__, "assertion": isinstance(exc, AssertionError),
                 "message": str(exc)}
    conn.send_bytes(json.dumps(reply).encode())
    conn.close()


def run_bounded(fn: Callable[[], Any], limit_s: float, what: str,
                failure: Callable[[str], BaseException]) -> None:
    """Run ``fn()`` in a forked child, killed after ``limit_s`` seconds; re-raise its failure here.

    Parameters
    ----------
    fn : callable
        Called without arguments in the child; its return value is ignored.
    limit_s : float
        Wall seconds the child may run.
    what : str
        What ``fn`` does, for the timeout message (``"plan() with Budget(time_s=0.3)"``).
    failure : callable
        Builds the exception raised here from a message: the child's
        assertion message, ``"<Type>: <message>"`` for another error, or
        the timeout. A bounded call may itself make bounded calls (each
        forks again).
    """
    if not can_bound():
        fn()
        return
    ctx = mp.get_context("fork")
    receive, send = ctx.Pipe(duplex=False)
    child = ctx.Process(target=_child, args=(fn, send))  # not a daemon: it may fork a bounded call itself
    child.start()
    send.close()
    try:
        ready = receive.poll(limit_s)
        raw = receive.recv_bytes() if ready else b""
    except EOFError:  # the child died without a word (os._exit, a signal)
        ready, raw = True, b""
    finally:
        receive.close()
        if child.is_alive():
            child.kill()
        child.join()
    if not ready:
        raise failure(f"{what} had not returned after {limit_s:.3g} s; its process was killed")
    if not raw:
        raise failure(f"{what} ended its process (exit code {child.exitcode}) without returning")
    reply = json.loads(raw)
    if reply["ok"]:
        return
    message = reply["message"] if reply["assertion"] else f"{reply['type']}: {reply['message']}"
    raise failure(message)

