"""What the harness knows of a planner configuration, learnt in a sandboxed child: the harness imports no planner.

A planner declared lazily (:class:`~pathzoo.plugins.entries.LazyPlanner`) is
known to the harness by its declaration: id, summary, kinds, requires. Its
version, its parameter declarations and the validation of a configuration
live in the planner's module, whose import runs the planner's code. The
harness never imports it: :func:`describe` asks a child process
(``python -m pathzoo.harness.planner_info``, in the OS sandbox where there
is one, :mod:`pathzoo.harness.sandbox`) to build each configuration and
answer, as JSON on its standard output, the version, the validated
parameters with their defaults filled in, the configuration's name
(:func:`~pathzoo.core.planner.config_name`) and the parameter declarations
(:meth:`~pathzoo.core.planner.Param.to_json`). Nothing from the child is
unpickled, and an error comes back as the name of a pathzoo error class and
its message, raised again here.

Answers are kept for the life of the harness process, so building
experiments over the same configurations asks once. A planner whose class
the harness process holds already (registered as a class, or declared
lazily and loaded by the user's own code) is described in-process, with no
child.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any, Mapping, Sequence

from pathzoo.core import errors
from pathzoo.core.errors import InvalidExperimentError, InvalidParameterError, PathzooError
from pathzoo.core.planner import Param

if TYPE_CHECKING:
    from pathzoo.plugins.manager import Registry

__all__ = ["PlannerInfo", "describe", "describe_loaded", "extra_plugin_modules", "info_of", "prefetch",
           "DESCRIBE_TIMEOUT_S"]

DESCRIBE_TIMEOUT_S = 300.0
"""Limit on the child that imports and describes the planners."""

MAX_ANSWER_BYTES = 1 << 24
"""Largest answer read from the child."""


@dataclass(frozen=True)
class PlannerInfo:
    """A planner configuration as the harness knows it.

    Attributes
    ----------
    id, version : str
        The planner's id and version.
    params : mapping
        The validated parameters, defaults filled in.
    kinds : frozenset of str
        The scenario kinds it supports.
    name : str
        ``id(param=value, ...)`` for the parameters off their defaults.
    declared : mapping of str to Param
        The planner's parameter declarations (bounds, choices, tuning ranges), for ``pathzoo tune``.
    """

    id: str
    version: str
    params: Mapping[str, Any]
    kinds: frozenset[str]
    name: str
    declared: Mapping[str, Param]


_cache: dict[tuple[str, str], PlannerInfo] = {}
_lock = threading.Lock()


def _key(planner_id: str, params: Mapping[str, Any]) -> tuple[str, str]:
    return planner_id, json.dumps(_plain(params), sort_keys=True)


def _plain(params: Mapping[str, Any]) -> dict[str, Any]:
    """The parameters as JSON values (numpy scalars as Python ones); others raise InvalidParameterError."""
    out: dict[str, Any] = {}
    for name, value in params.items():
        if hasattr(value, "item") and not isinstance(value, (str, bytes)):
            value = value.item()
        if value is not None and not isinstance(value, (bool, int, float, str)):
            raise InvalidParameterError(f"parameter '{name}' must be a bool, int, float, str or None, got {value!r}")
        if isinstance(value, float) and not math.isfinite(value):
            value = repr(value)  # the planner refuses it with its own message
        out[str(name)] = value
    return out


def describe_loaded(cls: Any, params: Mapping[str, Any]) -> PlannerInfo:
    """Describe a configuration of a class already loaded in this process (validates ``params``)."""
    from pathzoo.core.planner import config_name

    planner = cls(**params)
    values = planner.get_params()
    return PlannerInfo(planner.id, planner.version, values, frozenset(cls.kinds),
                       config_name(planner.id, values, cls.params), dict(cls.params))


def _unloaded(planner_id: str) -> bool:
    """Whether the planner is declared lazily and loading it here would import its module
    (:attr:`~pathzoo.plugins.entries.LazyClass.import_pending`)."""
    from pathzoo.plugins.entries import LazyClass
    from pathzoo.plugins.manager import get_registry

    provided = get_registry().get("planners", planner_id).provided
    return isinstance(provided, LazyClass) and provided.import_pending


def extra_plugin_modules(registry: "Registry") -> tuple[tuple[str, str], ...]:
    """``(name, module)`` of plugins registered by hand (not entry points) that workers must import.

    Entry-point plugins are told apart by what the registry recorded at
    discovery, not by the entry points installed now, so a distribution
    uninstalled since discovery is not mistaken for a hand-registered module.
    Only module plugins can be re-imported by name; a plugin object that is
    not an importable module stays unknown to workers, and its planners crash
    there with an "unknown planner" message (the ``inline`` executor works).
    """
    return tuple(
        (name, plugin.__name__)
        for name, plugin in registry.pm.list_name_plugin()
        if name not in registry.entry_point_plugins
        and isinstance(plugin, ModuleType)
        and plugin.__name__ != "__main__"
    )


def _hand_registered() -> tuple[tuple[str, str], ...]:
    from pathzoo.plugins.manager import get_registry

    return extra_plugin_modules(get_registry())


def prefetch(requests: Sequence[tuple[str, Mapping[str, Any]]]) -> None:
    """Describe the lazily declared, never imported planners among ``requests`` in one child, now.

    Invalid configurations are left for :func:`info_of` to report, one at a time.
    """
    from pathzoo.core.errors import UnknownPluginError

    wanted = []
    for planner_id, params in requests:
        try:
            if _unloaded(planner_id):
                wanted.append((planner_id, params))
        except UnknownPluginError:
            continue
    if wanted:
        try:
            describe(wanted, _hand_registered())
        except PathzooError:
            return


def info_of(planner_id: str, params: Mapping[str, Any]) -> PlannerInfo:
    """A configuration's :class:`PlannerInfo`: cached, described by a child (lazy, unloaded), or in-process.

    Raises
    ------
    UnknownPluginError, InvalidParameterError, InvalidExperimentError
        As :func:`describe`.
    """
    from pathzoo.plugins.manager import get_registry

    key = _key(planner_id, params)
    with _lock:
        info = _cache.get(key)
    if info is None:
        if _unloaded(planner_id):
            info = describe([(planner_id, params)], _hand_registered())[0]
        else:
            info = describe_loaded(get_registry().get("planners", planner_id).obj, params)
        with _lock:
            _cache[key] = _cache[_key(planner_id, info.params)] = info
    return info


def describe(requests: Sequence[tuple[str, Mapping[str, Any]]],
             plugin_modules: tuple[tuple[str, str], ...] = ()) -> list[PlannerInfo]:
    """Describe lazily declared planner configurations in one child process (the cached ones without it).

    Parameters
    ----------
    requests : sequence of (planner id, params)
        The configurations.
    plugin_modules : tuple of (name, module)
        Plugins registered by hand in this process, for the child to register
        too (:func:`extra_plugin_modules`).

    Raises
    ------
    PathzooError
        The first configuration that is invalid (unknown parameter, value
        out of range, unknown planner), as the class the planner raised.
    InvalidExperimentError
        The child failed or answered something else than the protocol.
    """
    keys = [_key(pid, params) for pid, params in requests]
    with _lock:
        missing = list(dict.fromkeys(k for k in keys if k not in _cache))
    if missing:
        answers = _ask_child([(pid, json.loads(params)) for pid, params in missing], plugin_modules)
        for key, answer in zip(missing, answers):
            if "error" in answer:
                raise _error(answer)
            info = PlannerInfo(key[0], str(answer["version"]), dict(answer["params"]), frozenset(answer["kinds"]),
                               str(answer["name"]), answer["declared"])
            with _lock:
                _cache[key] = _cache[_key(info.id, info.params)] = info
    with _lock:
        return [_cache[k] for k in keys]


def _error(answer: Mapping[str, Any]) -> PathzooError:
    if answer.get("error") == "ImportError":
        from pathzoo.harness.sandbox import SandboxImportError, import_problem, sandbox_problem

        problem = "" if sandbox_problem() else import_problem(str(answer.get("message", "")))
        if problem:
            return SandboxImportError(f"{str(answer.get('message', '')).split(':')[0]} could not be imported inside the "
                                      f"sandbox: {problem}")
        return InvalidExperimentError(str(answer.get("message", "")))
    kind = getattr(errors, str(answer.get("error")), None)
    cls = kind if isinstance(kind, type) and issubclass(kind, PathzooError) else InvalidExperimentError
    return cls(str(answer.get("message", "")))


def _ask_child(requests: list[tuple[str, dict[str, Any]]],
               plugin_modules: tuple[tuple[str, str], ...]) -> list[dict[str, Any]]:
    from pathzoo.harness.sandbox import SandboxImportError, import_problem, sandbox_problem, sandboxed_command

    command = [sys.executable, "-m", "pathzoo.harness.planner_info"]
    request = json.dumps({"plugin_modules": [list(m) for m in plugin_modules], "requests": requests,
                          "sys_path": [p or os.getcwd() for p in sys.path]})
    with tempfile.TemporaryDirectory(prefix="pathzoo-describe-") as scratch:
        sandboxed = not sandbox_problem()
        if sandboxed:
            command = sandboxed_command(command, procs_files=(), scratch=Path(scratch),
                                        numba_cache=Path(scratch) / "numba")
        try:
            done = subprocess.run(command, input=request.encode(), capture_output=True, timeout=DESCRIBE_TIMEOUT_S,
                                  cwd=scratch)
        except subprocess.TimeoutExpired:
            raise InvalidExperimentError(f"describing the planners took over {DESCRIBE_TIMEOUT_S:g} s") from None
    try:
        if len(done.stdout) > MAX_ANSWER_BYTES:
            raise ValueError("answer too long")
        answers = json.loads(done.stdout.decode("utf-8"))
        if not isinstance(answers, list) or len(answers) != len(requests) or not all(
                isinstance(a, dict) for a in answers):
            raise ValueError("not one answer per configuration")
        for answer in answers:
            if "error" not in answer and not (isinstance(answer.get("params"), dict)
                                              and isinstance(answer.get("kinds"), list)
                                              and isinstance(answer.get("declared"), dict)):
                raise ValueError("an answer without params, kinds or declarations")
            if "error" not in answer:
                answer["declared"] = {str(n): Param.from_json(d) for n, d in answer["declared"].items()}
    except (UnicodeDecodeError, ValueError) as exc:
        stderr = done.stderr.decode("utf-8", "replace")
        problem = import_problem(stderr) if sandboxed else ""
        if problem:  # the sandbox, not the planner or its parameters
            raise SandboxImportError(f"the planners could not be described inside the sandbox: {problem}") from None
        tail = stderr.strip().splitlines()[-1:] or [f"exit code {done.returncode}"]
        raise InvalidExperimentError(f"the planners could not be described ({exc}; {tail[0]})") from None
    return answers


def _main() -> None:
    """The child: read the request on stdin, answer one JSON object per configuration on stdout."""
    request = json.loads(sys.stdin.read())
    sys.path[:] = [p for p in request["sys_path"] if isinstance(p, str)]
    out = sys.stdout
    sys.stdout = sys.stderr  # whatever a planner module prints stays out of the answer
    from pathzoo.harness.plugin_loading import ensure_plugins, quiet_registry

    answers: list[dict[str, Any]] = []
    try:
        ensure_plugins(tuple((str(n), str(m)) for n, m in request["plugin_modules"]), missing_ok=True)
    except Exception as exc:  # noqa: BLE001 - reported with every configuration
        answers = [{"error": "InvalidExperimentError", "message": f"plugins could not be imported: {exc}"}
                   for _ in request["requests"]]
    registry = quiet_registry()
    for planner_id, params in request["requests"][len(answers):]:
        try:
            info = describe_loaded(registry.get("planners", planner_id).obj, params)
            answers.append({"version": info.version, "params": _plain(info.params), "kinds": sorted(info.kinds),
                            "name": info.name, "declared": {n: p.to_json() for n, p in info.declared.items()}})
        except PathzooError as exc:
            answers.append({"error": type(exc).__name__, "message": str(exc)})
        except ImportError as exc:  # the planner's module or a library it needs: not its parameters
            answers.append({"error": "ImportError", "message": f"{planner_id}: {type(exc).__name__}: {exc}"})
        except Exception as exc:  # noqa: BLE001 - a planner's own check that raised something else
            answers.append({"error": "InvalidParameterError", "message": f"{planner_id}: {type(exc).__name__}: {exc}"})
    out.write(json.dumps(answers))
    out.flush()


if __name__ == "__main__":
    _main()
