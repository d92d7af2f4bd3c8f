"""The programs a worker starts: in a session of their own, bounded in output and time, killed as a group.

A program is started with ``start_new_session`` (so it and every process
it starts share one process group that :func:`kill_group` ends at once) and
asks the kernel to kill it when the worker dies: through util-linux's
``setpriv --pdeathsig KILL`` where it is installed (an exec, about 1 ms),
else with :func:`pathzoo.parent_death.die_with_parent` run in the child
before the exec (a ``preexec_fn``, which makes Python fork the whole worker:
10-20 ms per run). :func:`pump` feeds its
standard input and reads its standard output and error at the same time,
under a deadline and an output limit.
"""

from __future__ import annotations

import functools
import os
import selectors
import shutil
import signal
import subprocess
import time
from dataclasses import dataclass
from typing import Callable, Sequence

from pathzoo.core.errors import ExternalPlannerError
from pathzoo.parent_death import die_with_parent

__all__ = ["MAX_OUTPUT_BYTES", "STDERR_KEEP_CHARS", "Output", "start", "kill_group", "pump", "run_once",
           "with_stderr", "describe_exit"]

MAX_OUTPUT_BYTES = 64 * 2**20
"""Most bytes a program may write on standard output per answer; more is a protocol error."""

STDERR_KEEP_CHARS = 2000
"""Characters of standard error kept (the last ones) in the run's message."""

_CHUNK = 2**16
_clock = time.perf_counter


@dataclass(frozen=True)
class Output:
    """What a program wrote: its standard output and the tail of its standard error."""

    stdout: bytes
    stderr: str


def with_stderr(line: str, stderr: str) -> str:
    """``line``, followed by the kept tail of standard error when there is one."""
    tail = stderr.strip()
    if not tail:
        return line
    if len(tail) > STDERR_KEEP_CHARS:
        tail = "..." + tail[-STDERR_KEEP_CHARS:]
    return f"{line}\nstandard error:\n{tail}"


def describe_exit(code: int) -> str:
    """``"exited with code 3"`` or ``"was killed by signal 11 (SIGSEGV)"``."""
    if code >= 0:
        return f"exited with code {code}"
    try:
        return f"was killed by signal {-code} ({signal.Signals(-code).name})"
    except ValueError:
        return f"was killed by signal {-code}"


def start(argv: Sequence[str], *, cwd: str, who: str) -> subprocess.Popen[bytes]:
    """Start ``argv`` with piped standard streams in a new session (a relative program path is relative to ``cwd``).

    Raises
    ------
    ExternalPlannerError
        The program does not exist or cannot be executed.
    """
    program = _program(argv[0], cwd, who)
    setpriv = _setpriv()
    command = [setpriv, "--pdeathsig", "KILL", "--", program, *argv[1:]] if setpriv else [program, *argv[1:]]
    try:
        return subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                cwd=cwd, start_new_session=True, preexec_fn=None if setpriv else die_with_parent)
    except OSError as exc:
        raise ExternalPlannerError(f"{who}: cannot start {argv[0]!r}: {exc.strerror or exc}") from None


def _program(name: str, cwd: str, who: str) -> str:
    """The executable ``name`` stands for: a path (relative to ``cwd``) or a program on ``PATH``."""
    path = os.path.join(cwd, name) if os.sep in name else shutil.which(name)
    if path is None or not os.path.isfile(path):
        raise ExternalPlannerError(f"{who}: cannot start {name!r}: no such program")
    if not os.access(path, os.X_OK):
        raise ExternalPlannerError(f"{who}: cannot start {name!r}: not executable (chmod +x?)")
    return path


@functools.lru_cache(maxsize=1)
def _setpriv() -> str | None:
    """util-linux's ``setpriv``, if installed and able to set the parent-death signal."""
    return shutil.which("setpriv")


def kill_group(proc: subprocess.Popen[bytes]) -> None:
    """Kill the program and everything it started (its process group), and reap it."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    for stream in (proc.stdin, proc.stdout, proc.stderr):
        if stream is not None:
            try:
                stream.close()
            except OSError:
                pass
    proc.wait()


def pump(proc: subprocess.Popen[bytes], data: bytes, *, deadline: float | None, who: str, limit_s: float | None,
         done: Callable[[bytearray], bool] | None = None, close_stdin: bool = True) -> Output:
    """Write ``data`` to the program and read its output until it closes standard output or ``done(stdout)``.

    Parameters
    ----------
    deadline : float, optional
        :func:`time.perf_counter` time by which the program must be done.
    limit_s : float, optional
        The allowance the deadline stands for, for the message.
    done : callable, optional
        Stop reading as soon as it returns True for the output so far (a
        server's complete answer); default: read to end of file.
    close_stdin : bool
        Close standard input once ``data`` is written (a one-shot program).

    Raises
    ------
    ExternalPlannerError
        The deadline passed, or standard output grew past
        :data:`MAX_OUTPUT_BYTES`; the caller must kill the program.
    """
    assert proc.stdin is not None and proc.stdout is not None and proc.stderr is not None
    out, err = bytearray(), bytearray()
    view, pos = memoryview(data), 0
    with selectors.DefaultSelector() as sel:
        if data:
            os.set_blocking(proc.stdin.fileno(), False)
            sel.register(proc.stdin, selectors.EVENT_WRITE)
        elif close_stdin:
            proc.stdin.close()
        for stream in (proc.stdout, proc.stderr):
            os.set_blocking(stream.fileno(), False)
            sel.register(stream, selectors.EVENT_READ)
        while any(key.fileobj is not proc.stdin for key in sel.get_map().values()):
            timeout = None if deadline is None else deadline - _clock()
            if timeout is not None and timeout <= 0:
                raise ExternalPlannerError(with_stderr(
                    f"{who}: no answer within {limit_s:.3g} s; the program was stopped", _text(err)))
            for key, _ in sel.select(timeout):
                if key.fileobj is proc.stdin:
                    try:
                        pos += os.write(proc.stdin.fileno(), view[pos:pos + _CHUNK])
                    except BrokenPipeError:  # it stopped reading: its answer (or exit) tells why
                        pos = len(view)
                    if pos >= len(view):
                        sel.unregister(proc.stdin)
                        os.set_blocking(proc.stdin.fileno(), True)
                        if close_stdin:
                            proc.stdin.close()
                    continue
                chunk = os.read(key.fd, _CHUNK)
                if not chunk:
                    sel.unregister(key.fileobj)
                elif key.fileobj is proc.stdout:
                    out += chunk
                    if len(out) > MAX_OUTPUT_BYTES:
                        raise ExternalPlannerError(with_stderr(
                            f"{who}: wrote more than {MAX_OUTPUT_BYTES // 2**20} MiB on standard output; the program "
                            "was stopped (the answer is one JSON object)", _text(err)))
                    if done is not None and done(out):
                        return Output(bytes(out), _text(err))
                else:
                    err += chunk
                    del err[:-4 * STDERR_KEEP_CHARS]
    return Output(bytes(out), _text(err))


def _text(data: bytearray) -> str:
    return data.decode("utf-8", "replace")


def run_once(argv: Sequence[str], data: bytes, *, cwd: str, deadline: float | None, limit_s: float | None,
             who: str) -> Output:
    """Start ``argv``, give it ``data`` on standard input and return what it wrote once it has exited with code 0.

    The program's process group is killed on return, whatever happens.

    Raises
    ------
    ExternalPlannerError
        It could not start, did not finish by the deadline, flooded its
        standard output, or exited with another code or by a signal.
    """
    proc = start(argv, cwd=cwd, who=who)
    try:
        output = pump(proc, data, deadline=deadline, limit_s=limit_s, who=who)
        try:
            code = proc.wait(None if deadline is None else max(0.0, deadline - _clock()))
        except subprocess.TimeoutExpired:
            raise ExternalPlannerError(with_stderr(
                f"{who}: closed its standard output but did not exit within {limit_s:.3g} s; the program was stopped",
                output.stderr)) from None
    finally:
        kill_group(proc)
    if code != 0:
        raise ExternalPlannerError(with_stderr(f"{who}: {describe_exit(code)}", output.stderr))
    return output
