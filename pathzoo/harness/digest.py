"""A hash of everything a scenario holds, to notice a planner that changed or replaced any part of it.

:func:`scenario_digest` walks the scenario's fields *and* its cached shared
geometry (``blocked``, ``graph``, ``clearance``, and anything else stored on
the instance): arrays by dtype, shape and bytes, dataclasses (vehicle, rules,
moving obstacles, the graph) field by field, and every object's type, so a
planner that swaps ``scenario.graph`` for a look-alike, drops
``moving_obstacles`` or replaces ``vehicle`` changes the digest just as one
that writes into ``occupancy``.

The hash is SHA-256, the fastest cryptographic hash in :mod:`hashlib` on CPUs
with SHA instructions (1.6 GB/s against 0.8 GB/s for BLAKE2b, measured).
Arrays in sealed read-only memory (:mod:`pathzoo.harness.sealed`) can be fed
by identity instead of bytes: that is the worker's check after each run.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
from typing import Any

import numpy as np

__all__ = ["scenario_digest", "warm"]

_MAX_DEPTH = 6


_TAGS: dict[type, bytes] = {}
_FIELDS: dict[type, "tuple[str, ...] | None"] = {}


def _tag(kind: type) -> bytes:
    """``b"<module.qualname>"`` of a type (kept per type: the walk meets the same few types every time)."""
    tag = _TAGS.get(kind)
    if tag is None:
        tag = _TAGS[kind] = f"<{kind.__module__}.{kind.__qualname__}>".encode()
    return tag


def _fields(kind: type) -> "tuple[str, ...] | None":
    """The field names of a dataclass type, None for any other type (kept per type, as first seen)."""
    if kind not in _FIELDS:
        _FIELDS[kind] = tuple(f.name for f in dataclasses.fields(kind)) if dataclasses.is_dataclass(kind) else None
    return _FIELDS[kind]


def _feed(h: Any, value: Any, by_identity: frozenset[int], depth: int = 0) -> None:
    kind = type(value)
    h.update(_tag(kind))
    if depth > _MAX_DEPTH:
        h.update(repr(id(value)).encode())
        return
    if isinstance(value, np.ndarray):
        h.update(f"{value.dtype.str}{value.shape}".encode())
        if id(value) in by_identity:  # its bytes cannot change (pathzoo.harness.sealed): which memory, seen how
            h.update(f"{id(value)} {value.ctypes.data} {value.strides} {value.flags.num}".encode())
        else:
            h.update(np.ascontiguousarray(value).view(np.uint8).data if value.size else b"")
        return
    names = _fields(kind)
    if names is not None:
        namespace = getattr(value, "__dict__", {})
        extra = sorted(k for k in namespace if k not in names)
        for name in (*names, *extra):
            h.update(name.encode())
            _feed(h, getattr(value, name), by_identity, depth + 1)
    elif isinstance(value, (list, tuple)):
        h.update(str(len(value)).encode())
        for item in value:
            _feed(h, item, by_identity, depth + 1)
    elif isinstance(value, (dict, frozenset, set)) or hasattr(value, "items"):
        items = list(value.items()) if hasattr(value, "items") else [(v, None) for v in value]
        h.update(str(len(items)).encode())
        for key, item in sorted(items, key=lambda kv: repr(kv[0])):
            _feed(h, key, by_identity, depth + 1)
            _feed(h, item, by_identity, depth + 1)
    else:
        h.update(repr(value).encode("utf-8", "replace"))


def _cached_properties(obj: Any) -> list[str]:
    return [name for klass in type(obj).__mro__ for name, attr in vars(klass).items()
            if isinstance(attr, functools.cached_property)]


def warm(scenario: Any) -> Any:
    """Compute every cached property of the scenario and of its graph now (outside any timed region).

    The shared geometry is then built once per process, and a digest taken
    after a run differs from the one taken at load only if something was
    changed, not merely computed.
    """
    for name in _cached_properties(scenario):
        getattr(scenario, name)
    for name in _cached_properties(scenario.graph):
        getattr(scenario.graph, name)
    return scenario


def scenario_digest(scenario: Any, by_identity: frozenset[int] = frozenset()) -> str:
    """Hex digest of a scenario's fields and of the shared geometry cached on it (see the module docstring).

    Arrays whose ``id`` is in ``by_identity`` (those in sealed read-only
    memory, :mod:`pathzoo.harness.sealed`) are fed by identity, address,
    strides and flags instead of their bytes.
    """
    h = hashlib.sha256()  # twice blake2b's speed where the CPU has SHA instructions: 1.6 against 0.8 GB/s here
    _feed(h, scenario, by_identity)
    return h.hexdigest()
