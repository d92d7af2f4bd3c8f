"""Discovery of plugins through entry points, and the registry of what they provide.

Each kind of plugin has its own entry-point group, so a process loads only the
kinds it needs (:data:`GROUP_KINDS`). The judge process loads scenario and
metric plugins only (:func:`limit_kinds`): a planner plugin's import-time code
never runs where verdicts are made. The group ``pathzoo`` (:data:`ENTRY_POINT_GROUP`,
the one group of pathzoo before 0.2) provides planners only (see ``docs/register-a-planner.md``).
"""

from __future__ import annotations

import fnmatch
import importlib.metadata as md
import threading
from dataclasses import dataclass, field
from typing import Any, Iterable, Literal, Sequence

import pluggy

from pathzoo.core.errors import UnknownPluginError
from pathzoo.core.suggest import did_you_mean
from pathzoo.plugins import hookspecs
from pathzoo.plugins.entries import PluginEntry, PluginFailure

__all__ = ["Registry", "get_registry", "reset_registry", "limit_kinds", "discover", "PluginKind", "KINDS",
           "GROUP_KINDS", "ENTRY_POINT_GROUP", "KIND_GROUPS"]

PluginKind = Literal["planners", "scenarios", "metrics"]
KINDS: tuple[PluginKind, ...] = ("planners", "scenarios", "metrics")

KIND_GROUPS: dict[str, str] = {"planners": "pathzoo.planners", "scenarios": "pathzoo.scenarios",
                               "metrics": "pathzoo.metrics"}
"""The entry-point group of each kind of plugin."""

ENTRY_POINT_GROUP = "pathzoo"
"""The one group of pathzoo before 0.2: its plugins provide planners (and observers), nothing else."""

GROUP_KINDS: dict[str, tuple[str, ...]] = {
    **{group: (kind,) for kind, group in KIND_GROUPS.items()},
    ENTRY_POINT_GROUP: ("planners",),
}
"""What the plugins of each entry-point group may provide; the other registration hooks of a module are ignored."""

_HOOKS: dict[str, str] = {kind: f"pathzoo_register_{kind}" for kind in KINDS}


@dataclass
class Registry:
    """Everything the installed plugins provide.

    Attributes
    ----------
    pm : pluggy.PluginManager
        The plugin manager, with every loaded plugin registered.
    kinds : tuple of str
        The kinds this registry loads (every kind, except in the judge process).
    planners, scenarios, metrics : dict
        Id to :class:`PluginEntry`.
    failures : list of PluginFailure
        Plugins that failed to import, id clashes and ignored hooks.
    entry_point_plugins : set of str
        Names of the plugins loaded from entry points (the others were
        registered by hand with :meth:`add_plugin`).
    """

    pm: pluggy.PluginManager
    kinds: tuple[str, ...] = KINDS
    planners: dict[str, PluginEntry] = field(default_factory=dict)
    scenarios: dict[str, PluginEntry] = field(default_factory=dict)
    metrics: dict[str, PluginEntry] = field(default_factory=dict)
    failures: list[PluginFailure] = field(default_factory=list)
    entry_point_plugins: set[str] = field(default_factory=set)

    def table(self, kind: PluginKind) -> dict[str, PluginEntry]:
        """The id-to-entry mapping of one kind."""
        if kind not in KINDS:
            raise UnknownPluginError(f"unknown plugin kind {kind!r}; allowed: {', '.join(KINDS)}")
        return getattr(self, kind)

    def get(self, kind: PluginKind, plugin_id: str) -> PluginEntry:
        """Look up one entry, with a helpful error for unknown ids."""
        table = self.table(kind)
        try:
            return table[plugin_id]
        except KeyError:
            hint = did_you_mean(plugin_id, table)
            if not hint:  # nothing spelled alike: the ids of the same family, if any
                family = [k for k in table if plugin_id.split(".")[0] == k.split(".")[0]][:8]
                hint = f"; {plugin_id.split('.')[0]} has {', '.join(family)}" if family else ""
            broken = sorted({f.plugin for f in self.failures})
            if broken:
                hint += f"; plugins that failed to load or were partly ignored: {', '.join(broken)}"
            if kind not in self.kinds:
                hint += f"; this process loads no {kind} plugins"
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

    def add_plugin(self, plugin: Any, name: str, distribution: str = "", version: str = "",
                   kinds: Sequence[str] = KINDS) -> None:
        """Register one plugin object and collect what it provides.

        Parameters
        ----------
        plugin : module or object
            Implements some of the hooks of :mod:`pathzoo.plugins.hookspecs`.
        name : str
            Its name in the plugin manager and in listings.
        distribution, version : str
            Where it comes from (empty for a plugin registered by hand).
        kinds : sequence of str
            The kinds it may provide (its entry-point group's, see
            :data:`GROUP_KINDS`); kinds this registry does not load are skipped.
        """
        if not self.pm.is_registered(plugin):
            self.pm.register(plugin, name=name)
        for kind in KINDS:
            fn = getattr(plugin, _HOOKS[kind], None)
            if fn is None or kind not in self.kinds or kind not in kinds:
                continue
            try:
                provided = list(fn() or ())
            except Exception as exc:  # a broken plugin must not break the rest
                self.failures.append(PluginFailure(name, distribution, f"{kind} hook raised {exc!r}"))
                continue
            for obj in provided:
                self._add(kind, obj, name, distribution, version)

    def _add(self, kind: str, obj: Any, plugin: str, distribution: str, version: str) -> None:
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

    def judge_modules(self, modules: Iterable[tuple[str, str]]) -> tuple[tuple[str, str], ...]:
        """The hand-registered ``(name, module)`` pairs the judge process imports: those providing scenarios or metrics.

        A module that registers planners only is left out, so its code never
        runs in the judge. A module registering planners *and* scenarios or
        metrics is imported there (only its scenario and metric hooks are
        called): keep planners in a module of their own to keep them out.
        """
        return tuple(
            (name, module) for name, module in modules
            if any(hasattr(self.pm.get_plugin(name), _HOOKS[kind]) for kind in ("scenarios", "metrics"))
        )


def _new_manager() -> pluggy.PluginManager:
    pm = pluggy.PluginManager(hookspecs.PROJECT)
    pm.add_hookspecs(hookspecs)
    return pm


def _entry_points(kinds: Sequence[str]) -> list[md.EntryPoint]:
    installed = md.entry_points()
    return [ep for group, provides in GROUP_KINDS.items() if set(provides) & set(kinds)
            for ep in installed.select(group=group)]


def _ignored_hooks(plugin: Any, ep: md.EntryPoint, declared: set[tuple[str, str]]) -> list[str]:
    """Registration hooks of ``plugin`` that its group does not allow, and that no other group declares it for."""
    allowed = GROUP_KINDS.get(ep.group, ())
    return [kind for kind in KINDS
            if kind not in allowed and hasattr(plugin, _HOOKS[kind]) and (KIND_GROUPS[kind], ep.value) not in declared]


def discover(entry_points: Iterable[md.EntryPoint] | None = None, kinds: Sequence[str] = KINDS) -> Registry:
    """Load the plugins of the entry-point groups that provide ``kinds`` into a new registry.

    Parameters
    ----------
    entry_points : iterable of EntryPoint, optional
        The entry points to consider (default: the installed ones); each
        provides what its group allows (:data:`GROUP_KINDS`).
    kinds : sequence of str
        The kinds to load; groups that provide none of them are not imported.

    A plugin that fails to import is recorded in :attr:`Registry.failures` with
    its name and error, and the rest keep working; so is a registration hook
    its group does not allow (a ``pathzoo`` plugin registering scenarios).
    """
    registry = Registry(_new_manager(), tuple(k for k in KINDS if k in kinds))
    eps = _entry_points(kinds) if entry_points is None else [
        ep for ep in entry_points if set(GROUP_KINDS.get(ep.group, ())) & set(kinds)]
    declared = {(ep.group, ep.value) for ep in eps}
    order = list(GROUP_KINDS)
    seen: set[tuple[str, str]] = set()
    for ep in sorted(eps, key=lambda e: (order.index(e.group), e.name != "core", e.name)):
        if (ep.group, ep.name) in seen:
            continue
        seen.add((ep.group, ep.name))
        dist = ep.dist.name if ep.dist is not None else ""
        version = ep.dist.version if ep.dist is not None else ""
        try:
            plugin = ep.load()
        except Exception as exc:
            registry.failures.append(PluginFailure(ep.name, dist, f"import failed: {type(exc).__name__}: {exc}"))
            continue
        name = ep.name if registry.pm.get_plugin(ep.name) in (None, plugin) else f"{ep.group}:{ep.name}"
        registry.add_plugin(plugin, name, dist, version, GROUP_KINDS[ep.group])
        registry.entry_point_plugins.add(registry.pm.get_name(plugin) or name)
        for kind in _ignored_hooks(plugin, ep, declared):
            registry.failures.append(PluginFailure(
                ep.name, dist, f"its {kind} hook is ignored: the '{ep.group}' entry-point group provides "
                f"{' and '.join(GROUP_KINDS[ep.group])} only; declare the module under '{KIND_GROUPS[kind]}'"))
    return registry


_lock = threading.Lock()
_registry: Registry | None = None
_kinds: tuple[str, ...] = KINDS


def get_registry() -> Registry:
    """The process-wide registry, discovered on first use (the kinds of :func:`limit_kinds` only).

    Plugins that fail to load are recorded in :attr:`Registry.failures`, not
    printed: ``pathzoo list`` reports them, and an unknown-id error names them.
    """
    global _registry
    with _lock:
        if _registry is None:
            _registry = discover(kinds=_kinds)
        return _registry


def limit_kinds(kinds: Sequence[PluginKind]) -> None:
    """Make this process load only plugins of ``kinds`` from now on (the judge: scenarios and metrics).

    Raises
    ------
    RuntimeError
        The registry was already discovered with other kinds: the plugins
        are imported, and cannot be unloaded.
    """
    global _kinds
    wanted = tuple(k for k in KINDS if k in kinds)
    with _lock:
        if _registry is not None and _registry.kinds != wanted:
            raise RuntimeError(f"plugins of {', '.join(_registry.kinds)} are already loaded in this process")
        _kinds = wanted


def reset_registry() -> None:
    """Forget the registry so the next use rediscovers plugins (for tests)."""
    global _registry
    with _lock:
        _registry = None
