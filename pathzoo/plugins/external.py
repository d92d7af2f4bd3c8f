"""External planners declared without Python code: a command speaking pathzoo's JSON protocol, or an Octave function file.

An :class:`ExternalPlanner` is a lazy planner declaration (like
:class:`~pathzoo.plugins.entries.LazyPlanner`): ``pathzoo list`` shows it
from its fields alone, and the planner class behind it is built by the
bridge (the ``pathzoo_external`` family) when it is first used. It comes
from one of two places:

- a ``[[planner]]`` table of an experiment file with ``command`` or
  ``octave`` instead of ``id`` (:meth:`ExternalPlanner.from_table`, which
  :func:`declare` puts in the registry under ``external.<label>``);
- a package's ``pathzoo_register_planners`` hook, which returns
  :class:`ExternalPlanner` objects with ids of its own.

The protocol is described in ``docs/external-planners.md``.
"""

from __future__ import annotations

import os

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Mapping

from pathzoo.core.errors import InvalidExperimentError, InvalidParameterError
from pathzoo.core.planner import Param
from pathzoo.core.scenario import SCENARIO_KINDS
from pathzoo.plugins.entries import PATH_MODELS, LazyPlanner, PluginDeclarationError, PluginEntry

if TYPE_CHECKING:
    from pathzoo.plugins.manager import Registry

__all__ = ["ExternalPlanner", "declare", "EXPERIMENT_FILES", "EXTERNAL_FAMILY", "TABLE_KEYS"]

EXPERIMENT_FILES = "experiment files"
"""The plugin name under which planners declared in experiment files are registered."""

EXTERNAL_FAMILY = "external"
"""The family of the ids of planners declared in experiment files: ``external.<label>``."""

TABLE_KEYS = ("command", "octave", "label", "kinds", "params", "summary", "path_model")
"""The keys of a ``[[planner]]`` table that declares an external planner."""

_DEFAULT_KINDS = frozenset({"grid2d"})


def _param_value_ok(value: Any) -> bool:
    """A TOML value that can be a parameter: a string, number or boolean, or a list of them."""
    if isinstance(value, (str, int, float, bool)):
        return True
    return isinstance(value, list) and all(isinstance(v, (str, int, float, bool)) for v in value)


def _slug(text: str) -> str:
    """A label as the name part of a planner id (lower case, ``[a-z0-9_-]``)."""
    return re.sub(r"[^a-z0-9_-]+", "-", text.strip().lower()).strip("-")


@dataclass(frozen=True)
class ExternalPlanner(LazyPlanner):
    """A planner that is a program: a command (``command``) or an Octave/MATLAB function file (``octave``).

    Parameters
    ----------
    id, summary : str
        As for every planner (``family.name`` and one line for ``pathzoo list``).
    kinds : frozenset of str
        The scenario kinds the program plans on (default ``{"grid2d"}``).
    command : tuple of str
        The program and its arguments, started once per run; it reads the
        problem as JSON on standard input and writes one JSON answer on
        standard output. Give files as absolute paths.
    octave : str
        Absolute path of a function file ``[path, info] = name(problem, params)``,
        run by one GNU Octave process per worker.
    params : mapping of str to Param
        The parameters, sent to the program as ``problem.params``.
    path_model : {"grid", "anyangle", "timed"}
        The kind of path the program returns, which picks the optimum its length is compared with
        (:class:`~pathzoo.plugins.entries.LazyPlanner`; default ``"grid"``).
    """

    target: str = "pathzoo_external.declared:planner_class"
    kinds: frozenset[str] = _DEFAULT_KINDS
    command: tuple[str, ...] = ()
    octave: str = ""
    params: Mapping[str, Param] = field(default_factory=dict)
    declared: ClassVar[tuple[str, ...]] = ("id", "summary", "kinds")

    def __post_init__(self) -> None:
        where = f"external planner '{self.id}'"
        if bool(self.command) == bool(self.octave):
            raise InvalidParameterError(f"{where}: give exactly one of command and octave")
        if self.command and not all(isinstance(arg, str) and arg for arg in self.command):
            raise InvalidParameterError(f"{where}: command must be a list of non-empty strings, got {self.command!r}")
        if self.octave and not self.octave.endswith(".m"):
            raise InvalidParameterError(f"{where}: octave must name a function file ending in .m, got {self.octave!r}")
        if self.path_model not in PATH_MODELS:
            raise InvalidParameterError(f"{where}: path_model must be one of {', '.join(PATH_MODELS)}, "
                                        f"got {self.path_model!r}")
        bad = sorted(set(self.kinds) - set(SCENARIO_KINDS))
        if not self.kinds or bad:
            raise InvalidParameterError(
                f"{where}: kinds must be a non-empty list of {', '.join(SCENARIO_KINDS)}, got {sorted(self.kinds)}")
        object.__setattr__(self, "command", tuple(self.command))
        object.__setattr__(self, "kinds", frozenset(self.kinds))
        object.__setattr__(self, "params", dict(self.params))

    @property
    def folders(self) -> tuple[str, ...]:
        """The folders of the program's files (the function file, every absolute file argument of the command).

        A sandboxed worker is given read access to them
        (:mod:`pathzoo.harness.sandbox` hides the temporary directories).
        """
        files = [self.octave] if self.octave else [arg for arg in self.command if os.path.isabs(arg)
                                                   and os.path.isfile(arg)]
        return tuple(sorted({os.path.dirname(f) for f in files}))

    @property
    def import_pending(self) -> bool:
        """False: building the class runs pathzoo's own bridge, never the program (that runs only in a worker)."""
        return False

    def load(self) -> type:
        """The planner class (built by ``pathzoo_external.declared.planner_class`` on first use, then kept)."""
        loaded = self.__dict__.get("_loaded")
        if loaded is None:
            try:  # the bridge is planner code: imported on first use only
                from pathzoo_external.declared import planner_class
            except ImportError as exc:
                raise PluginDeclarationError(
                    f"'{self.id}' needs pathzoo's bridge to external planners, which cannot be imported: {exc}"
                ) from exc
            loaded = planner_class(self)
            object.__setattr__(self, "_loaded", loaded)  # a cache, not a field
        return loaded

    def __getstate__(self) -> dict[str, Any]:
        return {name: getattr(self, name) for name in self.__dataclass_fields__}  # not the cached class

    def __setstate__(self, state: dict[str, Any]) -> None:
        for name, value in state.items():
            object.__setattr__(self, name, value)

    @classmethod
    def from_table(cls, table: Mapping[str, Any], base: Path) -> "ExternalPlanner":
        """The planner a ``[[planner]]`` table with ``command`` or ``octave`` declares.

        Paths are relative to ``base`` (the experiment file's folder): the
        ``octave`` file, and every ``command`` argument that names an
        existing file there, are made absolute. Each value of ``params``
        becomes a parameter with that default. The id is
        ``external.<label>``; the label defaults to the function file's
        stem or the program's name.

        Raises
        ------
        InvalidExperimentError
            Naming the key that is wrong.
        """
        unknown = sorted(set(table) - set(TABLE_KEYS))
        if unknown:
            raise InvalidExperimentError(f"unknown key(s) {unknown}; allowed with command or octave: "
                                         f"{', '.join(TABLE_KEYS)}")
        command, octave = table.get("command"), table.get("octave")
        if (command is None) == (octave is None):
            raise InvalidExperimentError("give exactly one of command and octave")
        argv: tuple[str, ...] = ()
        function = ""
        if command is not None:
            if isinstance(command, str):
                command = [command]
            if not isinstance(command, list) or not command or not all(isinstance(a, str) and a for a in command):
                raise InvalidExperimentError(f"command must be a list of non-empty strings, got {command!r}")
            argv = tuple(str((base / arg).resolve()) if (base / arg).is_file() else arg for arg in command)
            default_label = Path(command[0]).stem
            what = f"command {' '.join(command)}"
        else:
            if not isinstance(octave, str) or not octave.endswith(".m"):
                raise InvalidExperimentError(f"octave must name a function file ending in .m, got {octave!r}")
            path = (base / octave).resolve()
            if not path.is_file():
                raise InvalidExperimentError(f"octave: no function file {path}")
            function = str(path)
            default_label = path.stem
            what = f"Octave function {path.name}"
        label = table.get("label", default_label)
        if not isinstance(label, str) or not _slug(label):
            raise InvalidExperimentError(f"label must be a non-empty string, got {label!r}")
        kinds = table.get("kinds", sorted(_DEFAULT_KINDS))
        if not isinstance(kinds, list) or not kinds or not all(k in SCENARIO_KINDS for k in kinds):
            raise InvalidExperimentError(f"kinds must be a non-empty list of {', '.join(SCENARIO_KINDS)}, got {kinds!r}")
        values = table.get("params", {})
        if not isinstance(values, dict):
            raise InvalidExperimentError("params must be a table")
        bad = [name for name, value in values.items() if not _param_value_ok(value)]
        if bad:
            raise InvalidExperimentError(f"params {bad}: a value must be a string, number or boolean, or a list of them")
        summary = table.get("summary", f"{label}: {what}")
        if not isinstance(summary, str):
            raise InvalidExperimentError(f"summary must be a string, got {summary!r}")
        path_model = table.get("path_model", "grid")
        if path_model not in PATH_MODELS:
            raise InvalidExperimentError(f"path_model must be one of {', '.join(PATH_MODELS)}, got {path_model!r}")
        try:
            return cls(f"{EXTERNAL_FAMILY}.{_slug(label)}", summary, kinds=frozenset(kinds), command=argv,
                       path_model=path_model,
                       octave=function, params={name: Param(value, "given in the experiment file")
                                                for name, value in values.items()})
        except InvalidParameterError as exc:
            raise InvalidExperimentError(str(exc)) from None


def declare(registry: "Registry", planner: ExternalPlanner) -> None:
    """Register a planner declared in an experiment file, replacing an earlier one of the same id from such a file.

    The declaration read last wins, with its class built anew, so a file
    read again after its program changed gets the new version.

    Raises
    ------
    InvalidExperimentError
        The id belongs to an installed planner.
    """
    entry = registry.planners.get(planner.id)
    if entry is not None and entry.plugin != EXPERIMENT_FILES:
        raise InvalidExperimentError(
            f"'{planner.id}' is the id of a planner of the plugin {entry.plugin}; give this one another label")
    registry.planners[planner.id] = PluginEntry(planner.id, planner.summary, planner, EXPERIMENT_FILES, "", "")
