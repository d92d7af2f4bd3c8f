"""The scenarios a worker process keeps loaded: geometry warmed, arrays sealed, objects sent by reference.

Scenarios are cached per process (a small LRU, keyed by
:attr:`ScenarioSpec.cache_key`) and their shared geometry (blocked cells,
neighbourhood graph, clearance, every cached property) is built when they
are loaded, before any clock starts, so no planner pays for it. Its arrays
are then moved into sealed read-only memory (:mod:`pathzoo.harness.sealed`),
so no write can change them (numpy refuses, a raw write faults), and after
each run the worker checks what a planner could still change: a planner
that rebound or replaced any part of the scenario, or changed a small
field, is flagged (``scenario_modified``, judged ``invalid``) and the
scenario is evicted (:func:`evict`), so the next run loads a fresh one.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from dataclasses import replace
from typing import TYPE_CHECKING, Any, Callable, TypeVar

from pathzoo.harness.digest import warm
from pathzoo.harness.sealed import ScenarioSeal, seal

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario
    from pathzoo.harness.specs import ScenarioSpec

__all__ = ["SCENARIO_CACHE_SIZE", "SEALED_CACHE_CELLS", "UNSEALED_CACHE_CELLS", "keep_payload", "load_cached",
           "load_unsealed", "load_warm", "lru", "evict", "cache_lock"]

SCENARIO_CACHE_SIZE = 4
"""Scenarios kept loaded per process (runs are ordered scenario by scenario)."""

SEALED_CACHE_CELLS = 1 << 22
"""Map cells that :func:`load_cached` keeps loaded in all, beyond one scenario.

A worker holds a scenario's graph and its sealed copy: for one of GGACO's
terrain maps (2.7-6.6 million cells) 1.6-3.9 GiB. With four of them a
worker went over its sandbox's memory limit while loading the next, so
maps this large are kept one at a time (two while the next one loads).
"""

UNSEALED_CACHE_CELLS = 1 << 20
"""Map cells that :func:`load_unsealed` keeps loaded beyond :data:`SCENARIO_CACHE_SIZE` scenarios.

A judge meets a scenario once per configuration, and a sweep's pilot
(:func:`~pathzoo.harness.eta.pilot_first`) runs each scenario's first
configuration long before the others, so with four scenarios a study of
many small problems loads each, and derives its reference paths, once per
configuration. Counting cells, it keeps 1,024 problems of a 32 x 32 map
(about 45 KB each with their reference paths), 16 of a 256 x 256 one, and
never fewer than four scenarios, whatever their size.
"""

_scenarios: "OrderedDict[tuple[str, str, str, str], tuple[Scenario, ScenarioSeal]]" = OrderedDict()
cache_lock = threading.Lock()
_unsealed: "OrderedDict[tuple[str, str, str, str], Scenario]" = OrderedDict()
_payloads: dict[str, bytes] = {}


def keep_payload(spec: "ScenarioSpec") -> None:
    """Keep the pickled bytes of a scenario object sent in full, for the specs sent later by reference.

    The processes the harness sends objects to by reference (its workers
    and the judge, :meth:`~pathzoo.harness.specs.ScenarioSpec.by_reference`)
    call it on receipt of each task, before any planner code runs, whatever
    fails after. The bytes are kept for the life of the process (bytes
    cannot be changed in place, so a planner cannot alter what later runs
    load).
    """
    if spec.payload:
        _payloads.setdefault(spec.digest, spec.payload)


def load_cached(spec: "ScenarioSpec", size: int = SCENARIO_CACHE_SIZE,
                cells: int = SEALED_CACHE_CELLS) -> "tuple[Scenario, ScenarioSeal]":
    """Load a scenario once per process, geometry warmed and arrays sealed; returns it with its seal. The most recent
    ``size`` are kept, while their maps hold at most ``cells`` cells in all (the last one whatever its size).

    A scenario object sent by reference is loaded from the bytes
    :func:`keep_payload` kept.
    """
    def make() -> "tuple[Scenario, ScenarioSeal]":
        scenario = load_warm(spec)
        return scenario, seal(scenario)

    return lru(_scenarios, spec.cache_key, size, make, cells=(cells, 1, lambda kept: kept[0].occupancy.size))


def load_unsealed(spec: "ScenarioSpec", cells: int = UNSEALED_CACHE_CELLS) -> "Scenario":
    """Load a scenario once per process, geometry warmed, arrays not sealed; keep the most recent ones while their
    maps hold at most ``cells`` cells in all, and at least :data:`SCENARIO_CACHE_SIZE` of them.

    For a process where no planner code ever runs (the judge's): there the
    seal would guard against nothing, and moving the arrays into sealed
    memory and taking the scenario's digest cost about as much as loading it.
    """
    return lru(_unsealed, spec.cache_key, None, lambda: load_warm(spec),
               cells=(cells, SCENARIO_CACHE_SIZE, lambda kept: kept.occupancy.size))


_T = TypeVar("_T")


def lru(cache: "OrderedDict[Any, _T]", key: Any, size: int | None, make: Callable[[], _T],
        cells: "tuple[int, int, Callable[[_T], int]] | None" = None) -> _T:
    """``cache[key]``, made by ``make`` (outside the lock) when missing; entries beyond the ``size`` most recent go
    (``None``: no count limit). With ``cells = (budget, keep, cells_of)``, the oldest also go while the maps of those
    left hold over ``budget`` cells and more than ``keep`` are left."""
    with cache_lock:
        if key in cache:
            cache.move_to_end(key)
            return cache[key]
    value = make()
    with cache_lock:
        cache[key] = value
        while size is not None and len(cache) > size:
            cache.popitem(last=False)
        if cells is not None:
            budget, keep, cells_of = cells
            held = sum(map(cells_of, cache.values()))
            while len(cache) > keep and held > budget:
                held -= cells_of(cache.popitem(last=False)[1])
    return value


def load_warm(spec: "ScenarioSpec") -> "Scenario":
    """Load a scenario with its shared geometry built (an object sent by reference from the kept bytes)."""
    if spec.source == "object" and not spec.payload and spec.digest in _payloads:
        spec = replace(spec, payload=_payloads[spec.digest])
    return warm(spec.load())


def evict(spec: "ScenarioSpec") -> None:
    """Forget a cached scenario."""
    with cache_lock:
        _scenarios.pop(spec.cache_key, None)
