"""Registry entries: what ``pathzoo list`` shows for each planner, scenario and metric, and the lazy declarations behind them."""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, ClassVar, Literal, Mapping

from pathzoo.core.errors import PathzooError
from pathzoo.plugins.requirements import install_hint, missing_modules

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["ScenarioEntry", "LazyClass", "LazyPlanner", "LazyMetric", "PluginEntry", "PluginFailure",
           "PluginDeclarationError", "PATH_MODELS", "HYBRID_MARK"]

PATH_MODELS: tuple[str, ...] = ("grid", "anyangle", "timed")
"""What a planner's paths may be: moves between neighbouring cells, straight segments in any direction, or
timed moves with waits among moving obstacles. Each has its own reference optimum (``docs/metrics.md``)."""

HYBRID_MARK = "[hybrid]"
"""How ``pathzoo list``, leaderboards and reports mark a planner declared ``hybrid``."""


class PluginDeclarationError(PathzooError):
    """A lazily declared planner or metric cannot be imported, or its class disagrees with its declaration."""


@dataclass(frozen=True)
class ScenarioEntry:
    """A scenario that can be loaded by id without loading it up front.

    Parameters
    ----------
    id : str
        Scenario id, e.g. ``"gant.fig7"``.
    summary : str
        One line for ``pathzoo list scenarios``.
    load : callable
        Zero-argument function returning the :class:`~pathzoo.core.scenario.Scenario`.
        It must be picklable (a module-level function or a ``functools.partial``
        of one), because worker processes load scenarios themselves.
    kind : str
        Scenario kind, shown in listings.
    """

    id: str
    summary: str
    load: Callable[[], "Scenario"]
    kind: str = ""


@dataclass(frozen=True)
class LazyClass:
    """A class known by its declared metadata, imported from ``target`` only when it is used.

    Listing plugins reads the declaration alone, so ``pathzoo list`` imports
    none of the modules (numba kernels, OMPL, DEAP) behind it. The first use
    imports the class and checks that it agrees with every declared field, so
    a declaration cannot drift from its class unnoticed.

    Parameters
    ----------
    id : str
        The class's ``id``.
    summary : str
        The class's ``summary``, shown by ``pathzoo list``.
    target : str
        ``"package.module:ClassName"``.
    """

    id: str
    summary: str
    target: str
    declared: ClassVar[tuple[str, ...]] = ("id", "summary")
    """Fields compared with the loaded class's attributes of the same name."""
    absent: ClassVar[Mapping[str, Any]] = {}
    """What a declared field is compared with when the class lacks the attribute."""

    @property
    def import_pending(self) -> bool:
        """Whether :meth:`load` would import the declared module, running its code (it has not been loaded here)."""
        return "_loaded" not in self.__dict__

    def load(self) -> type:
        """Import the class, and check it against the declaration (once; later calls return it at once).

        Raises
        ------
        PluginDeclarationError
            ``target`` cannot be imported, or a declared field differs from
            the class attribute.
        """
        loaded = self.__dict__.get("_loaded")
        if loaded is not None:
            return loaded
        module_name, _, qualname = self.target.partition(":")
        try:
            obj: Any = importlib.import_module(module_name)
            for part in qualname.split("."):
                obj = getattr(obj, part)
        except (ImportError, AttributeError) as exc:
            raise PluginDeclarationError(
                f"'{self.id}' is declared as {self.target!r}, which cannot be imported: {type(exc).__name__}: {exc}"
            ) from exc
        if not qualname or not isinstance(obj, type):
            raise PluginDeclarationError(f"'{self.id}' is declared as {self.target!r}, which is not a class")
        for name in self.declared:
            declared = _comparable(getattr(self, name))
            actual = _comparable(getattr(obj, name, self.absent.get(name)))
            if declared != actual:
                raise PluginDeclarationError(
                    f"'{self.id}' declares {name}={declared!r} but {self.target} has {name}={actual!r}"
                )
        object.__setattr__(self, "_loaded", obj)  # a cache, not a field: equality and repr ignore it
        return obj


def _comparable(value: Any) -> Any:
    """Sets and mappings in a form that compares by content (``kinds`` as a set, ``requires`` as a dict)."""
    if isinstance(value, (set, frozenset)):
        return sorted(value)
    if isinstance(value, Mapping):
        return dict(sorted((str(k), str(v)) for k, v in value.items()))
    return value


@dataclass(frozen=True)
class LazyPlanner(LazyClass):
    """A planner declared by its metadata (see :class:`LazyClass`), returned by ``pathzoo_register_planners``.

    Parameters
    ----------
    kinds : frozenset of str
        The class's ``kinds``.
    requires : mapping
        The class's ``requires`` (optional import name to the extra that
        installs it); what ``pathzoo list`` checks to mark the planner
        unavailable, without importing it.
    path_model : {"grid", "anyangle", "timed"}
        The path model of the planner's default configuration (:data:`PATH_MODELS`),
        which picks the reference its length is compared with. A class
        registered without a declaration gives it as a ``path_model`` class
        attribute; ``"grid"`` when it has none.
    hybrid : bool
        The class's ``hybrid``: True for a metaheuristic that hands part of
        its work to an exact search (e.g. A* routes between its waypoints).
        ``pathzoo list``, the leaderboard and the report mark such planners.
    """

    kinds: frozenset[str] = frozenset()
    requires: Mapping[str, str] = field(default_factory=dict)
    path_model: str = "grid"
    hybrid: bool = False

    @property
    def folders(self) -> tuple[str, ...]:
        """Folders of files the planner reads at run time besides the scenario (none; see ``ExternalPlanner``)."""
        return ()

    def __post_init__(self) -> None:
        if self.path_model not in PATH_MODELS:
            raise PluginDeclarationError(
                f"'{self.id}' declares path_model={self.path_model!r}; allowed: {', '.join(PATH_MODELS)}")
    declared: ClassVar[tuple[str, ...]] = ("id", "summary", "kinds", "requires", "hybrid")
    absent: ClassVar[Mapping[str, Any]] = {"requires": {}, "hybrid": False}


@dataclass(frozen=True)
class LazyMetric(LazyClass):
    """A metric declared by its metadata (see :class:`LazyClass`), returned by ``pathzoo_register_metrics``.

    Parameters
    ----------
    unit : str
        The class's ``unit``.
    direction : {"min", "max"}
        The class's ``direction``.
    """

    unit: str = "1"
    direction: Literal["min", "max"] = "min"
    declared: ClassVar[tuple[str, ...]] = ("id", "summary", "unit", "direction")


@dataclass(frozen=True)
class PluginEntry:
    """One registered object with its provenance.

    Parameters
    ----------
    id, summary : str
        As declared.
    provided : object
        What the plugin's hook returned: a class, a :class:`LazyClass`
        declaration, or a :class:`ScenarioEntry`.
    plugin, distribution, version : str
        The plugin (entry-point name) and the distribution that installed it.
    """

    id: str
    summary: str
    provided: Any
    plugin: str
    distribution: str
    version: str

    @property
    def obj(self) -> Any:
        """The class (imported now if it was declared lazily) or the :class:`ScenarioEntry`."""
        return self.provided.load() if isinstance(self.provided, LazyClass) else self.provided

    def declared(self, name: str, default: Any = None) -> Any:
        """An attribute (``kinds``, ``unit``, ...) as declared, without importing a lazily declared class."""
        return getattr(self.provided, name, default)

    @property
    def missing(self) -> dict[str, str]:
        """Optional modules the object needs that are not installed, with their extras."""
        return missing_modules(self.provided)

    @property
    def unavailable(self) -> str:
        """Why the object cannot be used here (``needs pyswarms: pip install "pathzoo[evo]"``), or ``""``."""
        missing = self.missing
        if not missing:
            return ""
        return f"needs {', '.join(sorted(missing))}: {install_hint(missing, self.distribution)}"


@dataclass(frozen=True)
class PluginFailure:
    """A plugin that could not be loaded, an id that clashed, or a hook ignored in its entry-point group."""

    plugin: str
    distribution: str
    error: str
