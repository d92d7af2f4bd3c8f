"""Discovery of plugins through entry points, and the registry of what they provide."""

from __future__ import annotations

import fnmatch
import importlib.metadata as md
import threading
from dataclasses import dataclass, field
from typing import Any, Iterable, Literal

import pluggy

from pathzoo.core.errors import UnknownPluginError
from pathzoo.plugins import hookspecs
from pathzoo.plugins.entries import PluginEntry, PluginFailure, ScenarioEntry

__all__ = ["Registry", "get_registry", "reset_registry", "PluginKind", "ENTRY_POINT_GROUP"]

ENTRY_POINT_GROUP = "pathzoo"
PluginKind = Literal["planners", "scenarios", "metrics"]
_KINDS: tuple[str, ...] = ("planners", "scenarios", "metrics")


@dataclass
class Registry:
    """Everything the installed plugins provide.

    Attributes
    ----------
    pm : pluggy.PluginManager
        The plugin manager, with every loaded plugin registered.
    planners, scenarios, metrics : dict
        Id to :class:`PluginEntry`.
    failures : list of PluginFailure
        Plugins that failed to import, and id clashes.
    entry_point_plugins : set of str
        Names of the plugins loaded from entry points (the others were
        registered by hand with :meth:`add_plugin`).
    """

    pm: pluggy.PluginManager
    planners: dict[str, PluginEntry] = field(default_factory=dict)
    scenarios: dict[str, PluginEntry] = field(default_factory=dict)
    metrics: dict[str, PluginEntry] = field(default_factory=dict)
    failures: list[PluginFailure] = field(default_factory=list)
    entry_point_plugins: set[str] = field(default_factory=set)

    def table(self, kind: PluginKind) -> dict[str, PluginEntry]:
        """The id-to-entry mapping of one kind."""
        if kind not in _KINDS:
            raise UnknownPluginError(f"unknown plugin kind {kind!r}; allowed: {', '.join(_KINDS)}")
        return getattr(self, kind)

    def get(self, kind: PluginKind, plugin_id: str) -> PluginEntry:
        """Look up one entry, with a helpful error for unknown ids."""
        table = self.table(kind)
        try:
            return table[plugin_id]
        except KeyError:
            close = [k for k in table if plugin_id.split(".")[0] == k.split(".")[0]][:8]
            hint = f"; did you mean one of: {', '.join(close)}" if close else ""
            broken = sorted({f.plugin for f in self.failures})
            if broken:
                hint += f"; plugins that failed to load: {', '.join(broken)}"
            singular = kind[:-1]
            raise UnknownPluginError(
                f"unknown {singular} '{plugin_id}'{hint} (see 'pathzoo list {kind}')"
            ) from None

    def match(self, kind: PluginKind, pattern: str) -> list[str]:
        """Ids matching a glob pattern such as ``"movingai.arena.*"`` (sorted)."""
        table = self.table(kind)
        if pattern in table:
            return [pattern]
        found = sorted(k for k in table if fnmatch.fnmatchcase(k, pattern))
        if not found:
            self.get(kind, pattern)  # raises UnknownPluginError
        return found

    def add_plugin(self, plugin: Any, name: str, distribution: str = "", version: str = "") -> None:
        """Register one plugin object and collect what it provides."""
        self.pm.register(plugin, name=name)
        impls = {
            "planners": getattr(plugin, "pathzoo_register_planners", None),
            "scenarios": getattr(plugin, "pathzoo_register_scenarios", None),
            "metrics": getattr(plugin, "pathzoo_register_metrics", None),
        }
        for kind, fn in impls.items():
            if fn is None:
                continue
            try:
                provided = list(fn() or ())
            except Exception as exc:  # a broken plugin must not break the rest
                self.failures.append(PluginFailure(name, distribution, f"{kind} hook raised {exc!r}"))
                continue
            for obj in provided:
                self._add(kind, obj, name, distribution, version)

    def _add(self, kind: str, obj: Any, plugin: str, distribution: str, version: str) -> None:
        if isinstance(obj, ScenarioEntry):
            oid, summary = obj.id, obj.summary
        else:
            oid, summary = getattr(obj, "id", ""), getattr(obj, "summary", "")
        if not oid:
            self.failures.append(PluginFailure(plugin, distribution, f"a {kind[:-1]} without an id: {obj!r}"))
            return
        table = getattr(self, kind)
        if oid in table:
            prev = table[oid]
            self.failures.append(
                PluginFailure(plugin, distribution, f"{kind[:-1]} id '{oid}' already provided by {prev.plugin}; ignored")
            )
            return
        table[oid] = PluginEntry(oid, summary, obj, plugin, distribution, version)


def _new_manager() -> pluggy.PluginManager:
    pm = pluggy.PluginManager(hookspecs.PROJECT)
    pm.add_hookspecs(hookspecs)
    return pm


def discover(entry_points: Iterable[md.EntryPoint] | None = None) -> Registry:
    """Load every plugin of the ``pathzoo`` entry-point group into a new registry.

    A plugin that fails to import is recorded in :attr:`Registry.failures` with
    its name and error, and the rest keep working.
    """
    registry = Registry(_new_manager())
    eps = md.entry_points(group=ENTRY_POINT_GROUP) if entry_points is None else entry_points
    seen: set[str] = set()
    for ep in sorted(eps, key=lambda e: (e.name != "core", e.name)):
        if ep.name in seen:
            continue
        seen.add(ep.name)
        dist = ep.dist.name if ep.dist is not None else ""
        version = ep.dist.version if ep.dist is not None else ""
        try:
            plugin = ep.load()
        except Exception as exc:
            registry.failures.append(PluginFailure(ep.name, dist, f"import failed: {type(exc).__name__}: {exc}"))
            continue
        registry.add_plugin(plugin, ep.name, dist, version)
        registry.entry_point_plugins.add(ep.name)
    return registry


_lock = threading.Lock()
_registry: Registry | None = None


def get_registry() -> Registry:
    """The process-wide registry, discovered on first use.

    Plugins that fail to load are recorded in :attr:`Registry.failures`, not
    printed: ``pathzoo list`` reports them, and an unknown-id error names them.
    """
    global _registry
    with _lock:
        if _registry is None:
            _registry = discover()
        return _registry


def reset_registry() -> None:
    """Forget the registry so the next use rediscovers plugins (for tests)."""
    global _registry
    with _lock:
        _registry = None
