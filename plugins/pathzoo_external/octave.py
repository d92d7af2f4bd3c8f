"""One GNU Octave process per worker, started on first use and kept, serving the runs of Octave function files.

The process runs pathzoo's shim (``octave/pathzoo_octave_server.m``): it
reads one request at a time on standard input (a line with its length in
bytes, then the JSON naming the function file, the scratch folder and the
problem), seeds Octave's generators, calls the
function with its printed output captured, and writes one answer line
after a marker. Octave's start-up (about a second) is paid once per
worker, before the deadline of the first request starts; a request that
misses its deadline kills the process, and the next one starts a new one.
The process's working directory is a temporary folder of its own, removed
when it stops.
"""

from __future__ import annotations

import atexit
import os
import shutil
import tempfile
import threading
import time
from typing import Any

from pathzoo.core.errors import ExternalPlannerError
from pathzoo_external.child import Output, describe_exit, kill_group, pump, start, with_stderr
from pathzoo_external.program import SHIM_DIR

__all__ = ["OctaveServer", "octave_server", "OCTAVE_ENV", "DEFAULT_OCTAVE", "MARKER", "STARTUP_LIMIT_S"]

OCTAVE_ENV = "PATHZOO_OCTAVE"
"""Environment variable naming the Octave executable (default :data:`DEFAULT_OCTAVE` on ``PATH``)."""

DEFAULT_OCTAVE = "octave-cli"
"""The Octave executable looked for on ``PATH``."""

MARKER = b"\x1ePATHZOO-ANSWER\x1e"
"""What the shim writes before each answer line (and before ``ready`` once started)."""

STARTUP_LIMIT_S = 120.0
"""Longest Octave start-up accepted."""

_clock = time.perf_counter


def _complete(out: bytearray) -> bool:
    at = out.find(MARKER)
    return at >= 0 and out.find(b"\n", at) >= 0


def _split(out: bytes) -> tuple[bytes, str]:
    """The answer after the marker, and whatever was printed before it (outside the captured output)."""
    at = out.find(MARKER)
    answer = out[at + len(MARKER):].split(b"\n", 1)[0]
    return answer, out[:at].decode("utf-8", "replace")


class OctaveServer:
    """A persistent ``octave-cli`` process running the shim; one per executable per worker process."""

    def __init__(self, executable: str) -> None:
        self.executable = executable
        self.proc: Any = None
        self.home = ""
        self.lock = threading.Lock()

    def _start(self, who: str) -> None:
        path = shutil.which(self.executable)
        if path is None:
            raise ExternalPlannerError(
                f"{who}: GNU Octave is not installed here ('{self.executable}' not found on PATH); install it "
                f"(Debian/Ubuntu: apt-get install octave) or set {OCTAVE_ENV} to its path")
        shim = str(SHIM_DIR).replace("'", "''")
        argv = [path, "--norc", "--no-history", "--quiet", "--no-window-system",
                "--eval", f"addpath('{shim}'); pathzoo_octave_server"]
        self.home = tempfile.mkdtemp(prefix="pathzoo-octave-")
        self.proc = start(argv, cwd=self.home, who=who)
        self._exchange(b"", STARTUP_LIMIT_S, who, "while starting")

    def _exchange(self, data: bytes, limit_s: float | None, who: str, when: str) -> Output:
        """Write ``data`` and read up to a complete answer line; stop the process if that fails."""
        try:
            output = pump(self.proc, data, deadline=None if limit_s is None else _clock() + limit_s, limit_s=limit_s,
                          who=who, done=_complete, close_stdin=False)
        except ExternalPlannerError:
            self.stop()
            raise
        if not _complete(bytearray(output.stdout)):
            code = self.proc.wait()
            self.stop()
            raise ExternalPlannerError(with_stderr(f"{who}: Octave {describe_exit(code)} {when}", output.stderr))
        return output

    def ask(self, request: bytes, *, limit_s: float | None, who: str) -> tuple[bytes, str]:
        """Send one request (JSON text); return the answer line and any output printed outside the function's capture.

        The deadline (``limit_s`` from now, once Octave is running) covers
        the request, the call and the answer.

        Raises
        ------
        ExternalPlannerError
            Octave is missing, died, missed the deadline or flooded its
            output; the process is stopped.
        """
        with self.lock:
            if self.proc is None or self.proc.poll() is not None:
                self._start(who)
            output = self._exchange(b"%d\n" % len(request) + request, limit_s, who, "before answering")
            answer, stray = _split(output.stdout)
            return answer, stray + output.stderr

    def stop(self) -> None:
        """Kill the process (and anything it started); the next request starts a new one."""
        if self.proc is not None:
            kill_group(self.proc)
            self.proc = None
        if self.home:
            shutil.rmtree(self.home, ignore_errors=True)
            self.home = ""


_servers: dict[str, OctaveServer] = {}
_servers_lock = threading.Lock()


def octave_server() -> OctaveServer:
    """This process's server for the executable named by :data:`OCTAVE_ENV` (default :data:`DEFAULT_OCTAVE`)."""
    executable = os.environ.get(OCTAVE_ENV) or DEFAULT_OCTAVE
    with _servers_lock:
        server = _servers.get(executable)
        if server is None:
            server = _servers[executable] = OctaveServer(executable)
        return server


@atexit.register
def _stop_all() -> None:
    for server in list(_servers.values()):
        server.stop()
