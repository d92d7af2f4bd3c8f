"""The on-disk graph cache: same arrays as a fresh build, keyed by everything the graph depends on."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pathzoo import Budget, Scenario, VehicleModel, make_planner
from pathzoo.generators import fractal_terrain
from pathzoo.grid.graph import build_graph
from pathzoo.grid.graph_cache import cache_dir, cached_graph, graph_digest, release_pages

ARRAYS = ("indptr", "indices", "length", "slope", "offset_id", "offsets")


def _terrain(climb: float = 25.0, seed: int = 1) -> Scenario:
    elev = fractal_terrain((40, 50), seed=seed, hurst=0.8, relief=8.0)
    return Scenario(id="cache-terrain", kind="terrain", occupancy=np.zeros((40, 50), bool), cell_size=1.0,
                    start=(0.5, 0.5), goal=(49.5, 39.5), elevation=elev,
                    vehicle=VehicleModel(max_climb_deg=climb, max_descent_deg=climb))


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("PATHZOO_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("PATHZOO_GRAPH_CACHE_MIN_CELLS", "1")
    return tmp_path


def test_cached_graph_equals_a_fresh_build_and_is_read_only(cache):
    built = cached_graph(_terrain())  # stored
    entry = cache_dir() / graph_digest(_terrain())
    assert entry.is_dir()
    loaded = cached_graph(_terrain())  # memory-mapped
    fresh = build_graph(_terrain())
    for name in ARRAYS:
        a, b, c = getattr(built, name), getattr(loaded, name), getattr(fresh, name)
        assert a.dtype == b.dtype == c.dtype and np.array_equal(a, c) and np.array_equal(b, c)
    assert not loaded.indices.flags.writeable


def test_digest_changes_with_what_the_graph_depends_on(cache):
    base = graph_digest(_terrain())
    assert graph_digest(_terrain()) == base
    assert graph_digest(_terrain(climb=20.0)) != base
    assert graph_digest(_terrain(seed=2)) != base


def test_planner_result_is_the_same_on_a_cached_graph(cache, monkeypatch):
    planner = make_planner("aco.ggaco", n_ants=5)
    runs = []
    for _ in range(2):  # the first scenario builds and stores the graph, the second loads it
        r = planner.plan(_terrain(), budget=Budget(iterations=3), rng=np.random.default_rng(3))
        runs.append((r.path.tobytes(), r.iterations, r.extras["ant_steps"]))
    monkeypatch.setenv("PATHZOO_GRAPH_CACHE", "0")
    r = planner.plan(_terrain(), budget=Budget(iterations=3), rng=np.random.default_rng(3))
    assert runs[0] == runs[1] == (r.path.tobytes(), r.iterations, r.extras["ant_steps"])


def test_damaged_entry_is_rebuilt(cache):
    cached_graph(_terrain())
    entry = cache_dir() / graph_digest(_terrain())
    (entry / "length.npy").write_bytes(b"not an array")
    graph = cached_graph(_terrain())
    assert np.array_equal(graph.length, build_graph(_terrain()).length)
    assert np.array_equal(cached_graph(_terrain()).length, graph.length)


def _mapped_kb(path_part: str) -> int:
    """Resident kB of this process's mappings of files whose path contains ``path_part`` (Linux)."""
    total, current = 0, ""
    for line in open("/proc/self/smaps"):
        head = line.split()
        if head and "-" in head[0] and len(head) >= 5 and not head[0].endswith(":"):
            current = head[-1] if len(head) >= 6 else ""
        elif line.startswith("Rss:") and path_part in current:
            total += int(head[1])
    return total


def test_a_fresh_build_is_returned_memory_mapped_and_pages_can_be_released(cache):
    built = cached_graph(_terrain())  # built, stored, and handed back as the stored (mapped) copy
    assert isinstance(built.length.base, np.memmap)
    fresh = build_graph(_terrain())
    entry = str(cache_dir() / graph_digest(_terrain()))
    float(built.length.sum() + built.slope.sum() + built.indices.sum())  # map every page in
    before = _mapped_kb(entry) if Path("/proc/self/smaps").exists() else None
    release_pages(built, slice(0, 10))  # a range smaller than a page releases nothing, harmlessly
    release_pages(built)
    if before is not None:
        assert before > 0 and _mapped_kb(entry) == 0
    for name in ARRAYS:  # still readable, same values
        assert np.array_equal(getattr(built, name), getattr(fresh, name))
    release_pages(fresh)  # in-memory graph: nothing to do


def test_a_graph_is_built_straight_into_its_entry_and_an_edgeless_one_too(cache):
    cached_graph(_terrain())
    entries = sorted(p.name for p in cache_dir().iterdir())
    assert entries == [graph_digest(_terrain())]  # no temporary directory left behind
    assert sorted(p.name for p in (cache_dir() / entries[0]).iterdir()) == sorted(f"{n}.npy" for n in ARRAYS)
    walled = Scenario(id="walled", kind="grid2d", occupancy=np.array([[False, True, False]]), cell_size=1.0,
                      start=(0.5, 0.5), goal=(2.5, 0.5))
    for graph in (cached_graph(walled), cached_graph(walled)):  # stored, then loaded
        assert graph.n_edges == 0 and graph.indices.dtype == np.int64 and graph.offset_id.dtype == np.int16
        assert np.array_equal(graph.indptr, build_graph(walled).indptr)
