"""On-disk cache of large neighbourhood graphs: memory-mapped ``.npy`` files keyed by the scenario's digest.

Building the graph of a 2569 x 1919 terrain takes a few seconds and 0.8 GB;
every worker process of an experiment would do it again. :func:`cached_graph`
stores the CSR arrays of a graph with at least :data:`MIN_CELLS` cells once,
under ``<cache>/graphs/<digest>/``, and later loads them memory-mapped and
read-only, so the operating system shares one copy of the pages between all
processes and the graph costs no build time.

- Location: ``$PATHZOO_CACHE_DIR/graphs``, else
  ``$XDG_CACHE_HOME/pathzoo/graphs``, else ``~/.cache/pathzoo/graphs``.
- Switch off with ``PATHZOO_GRAPH_CACHE=0``; change the size threshold with
  ``PATHZOO_GRAPH_CACHE_MIN_CELLS``.
- Invalidation: the digest covers everything the graph depends on (kind, the
  blocked cells, elevation, cell sizes, ``max_step``, the vehicle) and the
  source code of :mod:`pathzoo.grid.graph`, :mod:`pathzoo.grid.segments`,
  :mod:`pathzoo.grid.terrain` and :mod:`pathzoo.core.tolerances`,
  so a changed scenario or a changed edge rule gets a new entry. Old entries
  are never read again and may be deleted at any time.
- A new entry is built straight into memory-mapped files in a private
  temporary directory, which is then renamed into place, so concurrent
  workers never read a half-written entry.

See ``docs/graph-cache.md``.
"""

from __future__ import annotations

import hashlib
import mmap
import os
import shutil
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario
    from pathzoo.grid.graph import GridGraph

__all__ = ["MIN_CELLS", "cache_dir", "cached_graph", "graph_digest", "release_pages"]

MIN_CELLS = 1_000_000
"""Graphs of fewer cells are built in memory (they take well under a second)."""

_ARRAYS = ("indptr", "indices", "length", "slope", "offset_id", "offsets")
_FORMAT = b"pathzoo-graph-1"


def cache_dir() -> Path:
    """The directory that holds the graph entries (not created here)."""
    root = os.environ.get("PATHZOO_CACHE_DIR")
    if root:
        return Path(root) / "graphs"
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg) if xdg else Path.home() / ".cache") / "pathzoo" / "graphs"


def _code_digest() -> bytes:
    """Hash of the source files whose rules decide the graph's edges and their values."""
    from pathzoo.core import tolerances
    from pathzoo.grid import graph, segments, terrain

    h = hashlib.sha256()
    for module in (graph, segments, terrain, tolerances):
        h.update(Path(str(module.__file__)).read_bytes())
    return h.digest()


def graph_digest(scenario: "Scenario") -> str:
    """Hex digest of everything ``build_graph(scenario)`` depends on (see the module docstring)."""
    h = hashlib.sha256(_FORMAT)
    h.update(_code_digest())
    h.update(repr((scenario.kind, scenario.shape, tuple(scenario.cell_sizes.tolist()), tuple(scenario.max_step),
                   scenario.vehicle)).encode())
    h.update(np.ascontiguousarray(scenario.blocked).tobytes())
    if scenario.kind == "terrain" and scenario.elevation is not None:
        h.update(np.ascontiguousarray(scenario.elevation, dtype=np.float64).tobytes())
    return h.hexdigest()


def _enabled(scenario: "Scenario") -> bool:
    if os.environ.get("PATHZOO_GRAPH_CACHE", "1") == "0":
        return False
    threshold = int(os.environ.get("PATHZOO_GRAPH_CACHE_MIN_CELLS", MIN_CELLS))
    return int(np.prod(scenario.shape)) >= threshold


def _load(entry: Path, scenario: "Scenario") -> "GridGraph | None":
    from pathzoo.grid.graph import GridGraph

    try:
        arrays = {name: np.asarray(np.load(entry / f"{name}.npy", mmap_mode="r", allow_pickle=False))
                  for name in _ARRAYS}
    except (OSError, ValueError):
        return None  # missing or damaged entry: rebuild it
    return GridGraph(shape=tuple(scenario.shape), vehicle=scenario.vehicle, **arrays)


def _npy_file(path: Path, dtype: type, size: int) -> np.ndarray:
    """A new ``.npy`` file of ``size`` elements, its disk space reserved, memory-mapped for writing.

    The space is reserved up front (``posix_fallocate``), so a full disk is
    an ``OSError`` here rather than a fault while the graph is written.
    """
    header = {"descr": np.lib.format.dtype_to_descr(np.dtype(dtype)), "fortran_order": False, "shape": (size,)}
    with open(path, "wb") as out:
        np.lib.format.write_array_header_1_0(out, header)
        offset = out.tell()
        if size:
            total = offset + size * np.dtype(dtype).itemsize
            if hasattr(os, "posix_fallocate"):
                os.posix_fallocate(out.fileno(), 0, total)
            else:  # nothing reserves the space on this system: a full disk would fault while the graph is written
                out.truncate(total)
    if not size:
        return np.empty(0, dtype)
    return np.asarray(np.memmap(path, dtype=dtype, mode="r+", offset=offset, shape=(size,)))


def _build_stored(entry: Path, scenario: "Scenario") -> "GridGraph | None":
    """Build the graph straight into the files of a new entry and return it memory-mapped from there.

    The arrays are written once, into the page cache, instead of built in
    memory and then copied to disk. The entry is filled in a private
    temporary directory and renamed into place, so concurrent workers never
    read a half-written one; if another process stored it first, its copy
    is used. None when the cache cannot be written (the caller builds in
    memory).
    """
    from pathzoo.grid.graph import build_graph

    try:
        entry.parent.mkdir(parents=True, exist_ok=True)
        tmp = Path(tempfile.mkdtemp(prefix=f".{entry.name}-", dir=entry.parent))
    except OSError:
        return None
    try:
        graph = build_graph(scenario, lambda name, dtype, size: _npy_file(tmp / f"{name}.npy", dtype, size))
        np.save(tmp / "offsets.npy", graph.offsets, allow_pickle=False)
        del graph  # the writable mappings go; the pages stay in the page cache
        os.rename(tmp, entry)
    except OSError:  # another process stored it first, or the disk is full
        pass
    finally:
        shutil.rmtree(tmp, ignore_errors=True)  # nothing left after the rename
    return _load(entry, scenario) if entry.is_dir() else None


def cached_graph(scenario: "Scenario") -> "GridGraph":
    """The scenario's graph: loaded memory-mapped from the cache, or built (into the cache when large)."""
    from pathzoo.grid.graph import build_graph

    if not _enabled(scenario):
        return build_graph(scenario)
    entry = cache_dir() / graph_digest(scenario)
    if entry.is_dir():
        graph = _load(entry, scenario)
        if graph is not None:
            return graph
        shutil.rmtree(entry, ignore_errors=True)  # damaged: store it again
    # stored and handed back memory-mapped: the pages are shared with other workers
    return _build_stored(entry, scenario) or build_graph(scenario)


def release_pages(graph: "GridGraph", edges: slice | None = None) -> None:
    """Let go of this process's resident copies of a memory-mapped graph's pages (no-op for in-memory graphs).

    The pages stay in the operating system's page cache, so a later read
    maps them back in without reading the disk; meanwhile they no longer
    count in this process's resident memory. Call it after a pass over the
    graph (a planner's set-up) that later work does not repeat.

    Parameters
    ----------
    graph : GridGraph
        The graph (from :func:`cached_graph`).
    edges : slice, optional
        Release only the pages wholly inside this range of edges of the
        per-edge arrays (``indices``, ``length``, ``slope``, ``offset_id``);
        by default every array, whole.
    """
    names = _ARRAYS if edges is None else ("indices", "length", "slope", "offset_id")
    for name in names:
        arr = getattr(graph, name)
        mapped = arr
        while isinstance(mapped, np.ndarray) and not isinstance(mapped, np.memmap):
            mapped = mapped.base
        if not isinstance(mapped, np.memmap) or getattr(mapped, "_mmap", None) is None:
            continue
        if edges is None:
            mapped._mmap.madvise(mmap.MADV_DONTNEED)  # type: ignore[attr-defined]  # numpy's private mmap
            continue
        lo, hi, _ = edges.indices(len(arr))
        base = mapped.ctypes.data - mapped.offset % mmap.ALLOCATIONGRANULARITY  # address of the mapping's start
        first = arr.ctypes.data + lo * arr.itemsize - base
        last = arr.ctypes.data + hi * arr.itemsize - base
        first = -(-first // mmap.PAGESIZE) * mmap.PAGESIZE
        last = last // mmap.PAGESIZE * mmap.PAGESIZE
        if last > first:
            mapped._mmap.madvise(mmap.MADV_DONTNEED, first, last - first)  # type: ignore[attr-defined]
