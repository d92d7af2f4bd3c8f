"""Wait on pipes and process sentinels with one ``poll`` object kept across calls.

:func:`multiprocessing.connection.wait` builds, registers and closes a new
selector on every call; the harness waits several times per run (each
message of a worker, each answer of the judge), so :class:`Poller` keeps
one :func:`select.poll` object and only changes its registrations when the
set of objects changes. Where ``select.poll`` is missing it falls back to
:func:`multiprocessing.connection.wait`.
"""

from __future__ import annotations

import select
from multiprocessing.connection import wait as mp_wait
from typing import Any, Sequence

__all__ = ["Poller"]

_READABLE = getattr(select, "POLLIN", 0) | getattr(select, "POLLPRI", 0)


def _fd(obj: Any) -> int:
    return obj if isinstance(obj, int) else obj.fileno()


class Poller:
    """``wait(objects, timeout)`` like :func:`multiprocessing.connection.wait`, on a kept ``poll`` object.

    Objects are connections (anything with ``fileno()``) or file
    descriptors (process sentinels). A hang-up or an error counts as ready,
    as it does for :func:`multiprocessing.connection.wait`, so a reader sees
    the end of the stream.
    """

    def __init__(self) -> None:
        self._poll = select.poll() if hasattr(select, "poll") else None
        self._registered: set[int] = set()

    def wait(self, objects: Sequence[Any], timeout: float | None = None) -> list[Any]:
        """The objects ready for reading, waiting at most ``timeout`` seconds (``None``: no limit)."""
        if self._poll is None:
            return list(mp_wait(objects, timeout))
        by_fd = {_fd(obj): obj for obj in objects}
        wanted = by_fd.keys()
        if wanted != self._registered:
            for fd in self._registered - wanted:
                self._poll.unregister(fd)
            for fd in wanted - self._registered:
                self._poll.register(fd, _READABLE)
            self._registered = set(wanted)
        ms = None if timeout is None else max(0, int(-(-timeout * 1000 // 1)))
        return [by_fd[fd] for fd, _ in self._poll.poll(ms) if fd in by_fd]
