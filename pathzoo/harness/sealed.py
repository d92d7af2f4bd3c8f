"""A worker's scenario arrays in sealed read-only memory, and the cheap check of what a planner could still change.

:func:`seal` copies every array a loaded scenario holds (its fields, its
cached geometry such as ``blocked``, ``clearance`` and the graph's CSR
arrays, and the arrays of its vehicle, rules and moving obstacles) into one
Linux ``memfd`` that is then sealed against writes (``F_SEAL_WRITE``,
``F_SEAL_SHRINK``, ``F_SEAL_GROW``, ``F_SEAL_SEAL``) and mapped shared and
read-only; the scenario's attributes are rebound to read-only views of that
mapping, with the same values, dtypes, shapes and memory order. So:

- ``arr.flags.writeable = True`` (and ``setflags``) raises: the buffer is
  read-only, so numpy refuses, and ``np.copyto`` or an in-place operator
  raises too;
- a write through a raw pointer (``ctypes.memmove``, a C extension) faults
  (``SIGSEGV``, a ``crash`` of that run); ``mprotect`` cannot make the
  mapping writable (the kernel refuses write access to a write-sealed
  memfd) and writing through ``/proc/self/mem`` fails;
- nothing else in the process holds a writable handle on the memory (the
  file descriptor is closed once mapped).

Arrays already in a read-only file mapping (the large graphs of
:mod:`pathzoo.grid.graph_cache`, shared between processes) are left where
they are. Where ``memfd_create`` or its seals are missing (not Linux) the
arrays stay as loaded, and :meth:`ScenarioSeal.intact` hashes their bytes.

What a planner can still change is the Python side: rebinding an attribute
(``object.__setattr__(scenario, "occupancy", other)``, ``scenario.__dict__["graph"] = ...``),
a small field (the vehicle's numbers, the metadata dict) or an array's view
parameters (``arr.shape = ...``). :meth:`ScenarioSeal.intact` hashes exactly
that: the scenario's digest (:func:`pathzoo.harness.digest.scenario_digest`)
with each sealed array fed by identity, address, shape, strides, dtype and
flags instead of its bytes, which costs tens of microseconds instead of a
pass over every byte. (Unmapping the memory and mapping other pages at the
same address with raw system calls is not detected.)
"""

from __future__ import annotations

import mmap
import os
from typing import Any

import numpy as np

from pathzoo.harness.digest import scenario_digest

__all__ = ["ScenarioSeal", "seal", "sealing_available"]

_ALIGN = 64
"""Byte alignment of each array in the mapping (numba and SIMD code see aligned arrays, as from numpy's allocator)."""

_MAX_DEPTH = 4


def sealing_available() -> bool:
    """Whether this system has sealable memory files (``memfd_create`` with ``F_ADD_SEALS``: Linux)."""
    import fcntl

    return hasattr(os, "memfd_create") and hasattr(fcntl, "F_ADD_SEALS")


def _in_read_only_mapping(arr: np.ndarray) -> bool:
    """Whether the array's memory is a read-only ``mmap`` (e.g. a graph memory-mapped from the cache)."""
    base: Any = arr
    while isinstance(base, np.ndarray):
        base = base.base
    return isinstance(base, mmap.mmap) and memoryview(base).readonly


def _sealable(arr: np.ndarray) -> bool:
    return (arr.size > 0 and not arr.dtype.hasobject and (arr.flags.c_contiguous or arr.flags.f_contiguous)
            and not _in_read_only_mapping(arr))


def _holders(obj: Any, depth: int = 0) -> list[Any]:
    """The objects whose ``__dict__`` may hold arrays: the scenario and the dataclass instances below it."""
    out = [obj]
    if depth >= _MAX_DEPTH:
        return out
    for value in vars(obj).values():
        for item in (value if isinstance(value, tuple) else (value,)):
            if hasattr(item, "__dataclass_fields__") and not isinstance(item, type) and hasattr(item, "__dict__"):
                out.extend(_holders(item, depth + 1))
    return out


def _arrays(value: Any) -> list[np.ndarray]:
    """The arrays of an attribute value: itself, or the items of a tuple of arrays."""
    if isinstance(value, np.ndarray):
        return [value]
    if isinstance(value, tuple):
        return [item for item in value if isinstance(item, np.ndarray)]
    return []


def _sealed_value(value: Any, views: dict[int, np.ndarray]) -> Any:
    if isinstance(value, np.ndarray):
        return views.get(id(value), value)
    if isinstance(value, tuple) and any(id(item) in views for item in value):
        return tuple(views.get(id(item), item) if isinstance(item, np.ndarray) else item for item in value)
    return value


class ScenarioSeal:
    """The sealed mapping of one scenario's arrays and the digest of everything else (see the module docstring).

    Attributes
    ----------
    sealed : int
        Number of arrays moved into the sealed mapping.
    """

    def __init__(self, scenario: Any, mapping: "mmap.mmap | None", views: list[np.ndarray]) -> None:
        self.scenario = scenario
        self._mapping = mapping
        self._views = views  # held: no other object can be given their identities while the seal lives
        self._ids = frozenset(map(id, views))
        self.sealed = len(views)
        self._digest = self.digest()

    def digest(self) -> str:
        """The scenario's digest with the sealed arrays fed by identity and view parameters, not by their bytes."""
        return scenario_digest(self.scenario, by_identity=self._ids)

    def intact(self) -> bool:
        """Whether nothing a planner can change has changed since :func:`seal`."""
        return self.digest() == self._digest


def seal(scenario: Any) -> ScenarioSeal:
    """Move the scenario's arrays into sealed read-only memory (in place) and return the seal that checks the rest.

    Call it on a loaded scenario whose shared geometry is built
    (:func:`pathzoo.harness.digest.warm`), before any planner sees it.
    """
    holders = _holders(scenario)
    found: dict[int, np.ndarray] = {}
    for holder in holders:
        for value in vars(holder).values():
            for arr in _arrays(value):
                if _sealable(arr):
                    found.setdefault(id(arr), arr)
    if not found or not sealing_available():
        return ScenarioSeal(scenario, None, [])
    mapping, views = _map_sealed(list(found.values()))
    by_id = dict(zip(found, views))
    for holder in holders:
        namespace = vars(holder)
        for name, value in list(namespace.items()):
            new = _sealed_value(value, by_id)
            if new is not value:
                namespace[name] = new  # frozen dataclasses too: their fields live in __dict__
    return ScenarioSeal(scenario, mapping, views)


def _map_sealed(arrays: list[np.ndarray]) -> tuple[mmap.mmap, list[np.ndarray]]:
    """One sealed memfd holding copies of ``arrays``, mapped read-only, and a view of it for each array."""
    import fcntl

    offsets, size = [], 0
    for arr in arrays:
        size = -(-size // _ALIGN) * _ALIGN
        offsets.append(size)
        size += arr.nbytes
    fd = os.memfd_create("pathzoo-scenario", os.MFD_CLOEXEC | os.MFD_ALLOW_SEALING)
    try:
        os.ftruncate(fd, size)
        for arr, offset in zip(arrays, offsets):
            data = (arr if arr.flags.c_contiguous else arr.T).reshape(-1).view(np.uint8).data
            while data:
                written = os.pwrite(fd, data, offset)
                data, offset = data[written:], offset + written
        fcntl.fcntl(fd, fcntl.F_ADD_SEALS,
                    fcntl.F_SEAL_WRITE | fcntl.F_SEAL_SHRINK | fcntl.F_SEAL_GROW | fcntl.F_SEAL_SEAL)
        mapping = mmap.mmap(fd, size, flags=mmap.MAP_SHARED, prot=mmap.PROT_READ)
    finally:
        os.close(fd)  # the mapping keeps the file; no writable handle on it is left
    views = [np.ndarray(arr.shape, arr.dtype, buffer=mapping, offset=offset,
                        order="C" if arr.flags.c_contiguous else "F")
             for arr, offset in zip(arrays, offsets)]
    return mapping, views
