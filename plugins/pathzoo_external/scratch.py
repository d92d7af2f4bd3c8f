"""Scratch folders for external runs: empty at the start of each run, kept and reused by the process.

Making and removing a folder per run costs milliseconds on some file
systems, as much as the rest of the protocol, so each process keeps a few
(one per run in progress) and empties one after each run instead.
"""

from __future__ import annotations

import atexit
import contextlib
import os
import shutil
import tempfile
import threading
from typing import Iterator

__all__ = ["scratch_folder"]

_free: list[str] = []
_made: list[str] = []
_lock = threading.Lock()


def _empty(folder: str) -> None:
    with os.scandir(folder) as entries:
        for entry in entries:
            if entry.is_dir(follow_symlinks=False):
                shutil.rmtree(entry.path, ignore_errors=True)
            else:
                with contextlib.suppress(OSError):
                    os.unlink(entry.path)


@contextlib.contextmanager
def scratch_folder() -> Iterator[str]:
    """An empty folder of this process's own for one run; emptied when the run ends."""
    with _lock:
        folder = _free.pop() if _free else None
    if folder is None or not os.path.isdir(folder):
        folder = tempfile.mkdtemp(prefix="pathzoo-external-")
        with _lock:
            _made.append(folder)
    try:
        yield folder
    finally:
        _empty(folder)
        with _lock:
            _free.append(folder)


@atexit.register
def _remove_all() -> None:
    for folder in _made:
        shutil.rmtree(folder, ignore_errors=True)
