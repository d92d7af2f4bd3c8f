"""Distributions the test session pip-installs into its own environment, and their clean-up.

Markers and the lock live in ``sys.prefix`` because that is what the
installs change: every pytest-xdist worker of the session shares it.
"""

from __future__ import annotations

import contextlib
import fcntl
import subprocess
import sys
from pathlib import Path
from typing import Iterator

__all__ = ["environment_lock", "mark_installed_by_tests", "uninstall_what_tests_installed"]

_PREFIX = Path(sys.prefix)
_MARKER = "pathzoo-tests-installed-{}.txt"


@contextlib.contextmanager
def environment_lock() -> Iterator[None]:
    """Hold an exclusive lock on this environment's installs (across processes)."""
    with open(_PREFIX / "pathzoo-tests-install.lock", "w") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def mark_installed_by_tests(distribution: str) -> None:
    """Record that the tests installed ``distribution``, so the session end removes it."""
    (_PREFIX / _MARKER.format(distribution)).write_text(distribution)


def uninstall_what_tests_installed() -> None:
    """Uninstall every distribution recorded by :func:`mark_installed_by_tests`."""
    with environment_lock():
        for marker in _PREFIX.glob(_MARKER.format("*")):
            subprocess.run([sys.executable, "-m", "pip", "uninstall", "--yes", "--quiet", marker.read_text()], check=True)
            marker.unlink()
