"""Notice a planner that rebinds module attributes (monkeypatching) in its worker process.

:class:`ModuleFingerprint` snapshots the namespaces of every loaded module
and of the classes those modules define, and tracks the code-like
attributes (modules, classes, functions, builtins, methods and descriptors)
and float constants in them. :meth:`ModuleFingerprint.changed` compares the
live state with it: an attribute that was
there before and now is another object (``time.perf_counter = fake``,
``GridGraph.neighbours = fake``), or a module replaced in ``sys.modules``,
means the process can no longer be trusted to run another planner. New
attributes and new modules (lazy imports, numba caches), and attributes that
held ``None`` or plain data objects (lazily set globals, lazy-import proxies,
counters) are not tracked, since libraries rebind those themselves.

The quick check after each run reads each namespace's dict *version tag*
(PEP 509: CPython gives a dict a new one on every insertion, replacement or
deletion) where the interpreter has one (CPython 3.11-3.13, checked on a
probe dict at import); only the namespaces whose tag moved are compared
attribute by attribute. Elsewhere it compares every key and value by
identity (see :class:`ModuleFingerprint`).

The executors act on it: the process executor retires such a worker and
starts a fresh one, the Dask executor restarts it, so no planner's patch can
reach a later run. A false alarm (a library that rebinds one of its own
globals) costs a worker restart, never a result.
"""

from __future__ import annotations

import ctypes
import functools
import gc
import itertools
import operator
import sys
import types
from typing import Any

__all__ = ["ModuleFingerprint"]

_TRACKED = (types.ModuleType, type, types.FunctionType, types.BuiltinFunctionType, types.MethodType,
            types.MethodDescriptorType, types.WrapperDescriptorType, staticmethod, classmethod, property,
            functools.partial, functools.cached_property, float)


def _attributes(obj: Any) -> dict[str, Any]:
    try:
        return dict(vars(obj))
    except TypeError:
        return {}


class ModuleFingerprint:
    """Snapshots of the namespaces of every loaded module and of the classes each defines.

    :meth:`update` snapshots modules loaded since the last call (the first
    call takes about 0.02-0.07 s of CPU with every plugin loaded).
    :meth:`changed` first asks the last state it found clean
    (:class:`_CleanState`) which namespaces may have changed since, and
    examines only those attribute by attribute against their snapshots
    (re-snapshotting one whose difference is not a tracked one); a replaced
    ``sys.modules`` entry makes it examine everything. With dict version
    tags (see the module docstring) asking costs about 0.3 ms with every
    plugin loaded (4,400 namespaces, 75,000 attributes); without them the
    clean state compares every key and value by identity (``operator.is_``,
    never ``==``, which a planner's object could answer falsely), which
    touches every object and cost 12-30 ms per run on a loaded machine.
    """

    def __init__(self) -> None:
        self._modules: dict[str, int] = {}
        self._owners: dict[int, tuple[str, Any, dict[str, Any]]] = {}
        self._clean: _CleanState | None = None
        self._seen_modules = -1

    def _snap(self, label: str, owner: Any) -> int:
        self._owners[id(owner)] = (label, owner, _attributes(owner))
        return id(owner)

    def update(self) -> "ModuleFingerprint":
        """Snapshot the modules loaded since the last call (and their classes).

        Nothing to do while ``sys.modules`` has as many entries as at the last
        call: a module removed since makes :meth:`changed` examine everything.
        The new snapshots join the clean state as they are, so the next
        :meth:`changed` stays quick.
        """
        if len(sys.modules) == self._seen_modules:
            return self
        self._seen_modules = len(sys.modules)
        names: list[str] = []
        keys: list[int] = []
        for name, module in list(sys.modules.items()):
            if module is None or name in self._modules:
                continue
            self._modules[name] = id(module)
            names.append(name)
            keys.append(self._snap(name, module))
            for value in list(_attributes(module).values()):
                if isinstance(value, type) and getattr(value, "__module__", None) == name:
                    keys.append(self._snap(f"{name}.{value.__qualname__}", value))
        if self._clean is not None:
            self._clean.add(names, keys, self._owners)
        return self

    def changed(self, limit: int = 5) -> list[str]:
        """Up to ``limit`` names (``"module.attribute"``) whose tracked object was replaced or deleted."""
        clean = self._clean
        moved = None if clean is None else clean.moved()
        if moved is not None and not moved:
            return []
        out = self._examine(limit, None if moved is None else [key for key, _ in moved])
        if not out:
            if clean is not None and moved is not None:
                clean.accept(moved)
            else:
                self._clean = _CleanState(list(self._modules), self._owners)
        return out

    def _examine(self, limit: int, keys: "list[int] | None") -> list[str]:
        """The attribute-by-attribute comparison with the snapshots, of the owners ``keys`` (all with None)."""
        out = [] if keys is not None else [
            f"sys.modules[{name!r}]" for name, ident in self._modules.items()
            if sys.modules.get(name) is not None and id(sys.modules[name]) != ident]
        for key in list(self._owners) if keys is None else keys:
            label, owner, old = self._owners[key]
            try:
                new = vars(owner)
            except TypeError:
                continue
            n = len(old)
            if (len(new) >= n and all(map(operator.is_, old.values(), itertools.islice(new.values(), n)))
                    and list(old) == list(itertools.islice(new, n))):
                continue
            found = [f"{label}.{attr}" for attr, value in old.items()
                     if issubclass(type(value), _TRACKED) and (attr not in new or new[attr] is not value)]
            if found:
                out.extend(found)
            else:  # only untracked data changed (a lazily set global): the new state is the reference
                self._owners[key] = (label, owner, _attributes(owner))
        return out[:limit]


_WORD = ctypes.sizeof(ctypes.c_ssize_t)
_TAG_OFFSET = 3 * _WORD
"""Where a dict's version tag sits in CPython 3.11-3.13: after the reference count, the type and ``ma_used``."""


def _tags_readable() -> bool:
    """Whether dicts carry a version tag at :data:`_TAG_OFFSET` that moves on every change (tried on a probe)."""
    if sys.implementation.name != "cpython" or not (3, 11) <= sys.version_info[:2] <= (3, 13):
        return False
    probe = {"a": 0}
    used = ctypes.c_ssize_t.from_address(id(probe) + 2 * _WORD)
    tag = ctypes.c_uint64.from_address(id(probe) + _TAG_OFFSET)
    seen = [tag.value]
    probe["a"] = 1
    seen.append(tag.value)
    probe["b"] = 2
    seen.append(tag.value)
    del probe["a"]
    seen.append(tag.value)
    return used.value == 1 and len(set(seen)) == 4


_TAGS = _tags_readable()


def _dict_of(namespace: Any) -> "dict[str, Any] | None":
    """The dict behind a module's namespace or a class's ``mappingproxy``; None if there is none.

    A dict subclass counts (``ctypes`` types keep their namespace in one):
    it carries the version tag at the same place, and moves it on every
    change made through the dict's own storage.
    """
    if type(namespace) is dict:
        return namespace
    inner = gc.get_referents(namespace) if type(namespace) is types.MappingProxyType else []
    return inner[0] if len(inner) == 1 and isinstance(inner[0], dict) else None


class _CleanState:
    """What :meth:`ModuleFingerprint.changed` needs to tell which namespaces may have changed since a clean check.

    It holds every module entry and namespace (so no identity can be reused
    by a new object while it exists). With version tags it reads each
    namespace dict's tag in place (a ``ctypes`` view of it); without them it
    keeps every key and value, to compare by identity.
    """

    def __init__(self, module_names: list[str], owners: "dict[int, tuple[str, Any, dict[str, Any]]]") -> None:
        self.module_names: list[str] = []
        self.modules: list[Any] = []
        self.keys: list[int] = []
        self.namespaces: list[Any] = []
        if _TAGS:
            self.untagged: list[int] = []  # examined after every run
            self.tagged: list[int] = []
            self.tags: list[ctypes.c_uint64] = []
            self.seen: list[int] = []
            self.index: dict[int, int] = {}
        else:
            self.sizes: list[int] = []
            self.flat_keys: list[Any] = []
            self.values: list[Any] = []
        self.add(module_names, list(owners), owners)

    def add(self, module_names: list[str], keys: list[int],
            owners: "dict[int, tuple[str, Any, dict[str, Any]]]") -> None:
        """Hold also these modules and owners, just snapshotted (so clean as they are now)."""
        self.module_names += module_names
        self.modules += map(sys.modules.get, module_names)
        held = set(self.keys)
        keys = [key for key in dict.fromkeys(keys) if key not in held and _namespace(owners[key][1]) is not None]
        namespaces = [_namespace(owners[key][1]) for key in keys]
        self.keys += keys
        self.namespaces += namespaces
        if _TAGS:
            for key, d in zip(keys, map(_dict_of, namespaces)):
                if d is None:
                    self.untagged.append(key)
                    continue
                self.index[key] = len(self.tagged)
                self.tagged.append(key)
                self.tags.append(ctypes.c_uint64.from_address(id(d) + _TAG_OFFSET))
                self.seen.append(self.tags[-1].value)
        else:
            self.sizes += map(len, namespaces)
            self.flat_keys += itertools.chain.from_iterable(namespaces)
            self.values += itertools.chain.from_iterable(map(_VALUES, namespaces))

    def moved(self) -> "list[tuple[int, int | None]] | None":
        """``(owner key, its tag now)`` of each namespace that may have changed; None to examine everything.

        None when a ``sys.modules`` entry is another object, or (without
        version tags) when any namespace differs. A namespace without a plain
        dict behind it is always listed (tag None).
        """
        if not all(map(operator.is_, self.modules, map(sys.modules.get, self.module_names))):
            return None
        if not _TAGS:
            return [] if self._identical() else None
        now = list(map(_TAG_VALUE, self.tags))
        moved: list[tuple[int, int | None]] = [(key, None) for key in self.untagged]
        if now != self.seen:  # plain ints: == cannot be fooled
            moved += [(key, tag) for key, tag, old in zip(self.tagged, now, self.seen) if tag != old]
        return moved

    def accept(self, moved: "list[tuple[int, int | None]]") -> None:
        """Take the tags read by :meth:`moved` as the clean ones (those namespaces were examined and found clean)."""
        for key, tag in moved:
            if tag is not None:
                self.seen[self.index[key]] = tag

    def _identical(self) -> bool:
        """Whether every namespace key and value is still the very same object."""
        if list(map(len, self.namespaces)) != self.sizes:
            return False
        keys = itertools.chain.from_iterable(self.namespaces)
        values = itertools.chain.from_iterable(map(_VALUES, self.namespaces))
        return all(map(operator.is_, self.flat_keys, keys)) and all(map(operator.is_, self.values, values))


_VALUES = operator.methodcaller("values")
_TAG_VALUE = operator.attrgetter("value")


def _namespace(owner: Any) -> Any:
    """The live namespace of a module (its ``__dict__``) or class (a read-only view of it); None if it has none."""
    try:
        return vars(owner)
    except TypeError:
        return None
