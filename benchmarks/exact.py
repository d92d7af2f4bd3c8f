"""Exact planners against SciPy's Dijkstra on the 512 x 512 MovingAI map ``8room_000``.

Run from the repository root, with ``shared/`` beside the repository::

    python benchmarks/exact.py               # 10 hardest and 10 middle buckets (200 problems)
    python benchmarks/exact.py --buckets 3   # fewer problems
    python benchmarks/exact.py --write-docs  # also rewrite the table in docs/planners/exact.dijkstra.md

For every problem of the hardest buckets of ``8room_000.map.scen``, and of as
many buckets around the middle one, it times

- ``exact.dijkstra`` and ``exact.astar`` (``plan()``, which includes building
  the search state and the returned path; the neighbourhood graph, and the
  move table their kernel reads on flat grids, are built once beforehand and
  shared, as the harness does), and ``exact.thetastar`` for comparison (its
  any-angle length is below the grid optimum);
- ``scipy.sparse.csgraph.dijkstra`` on ``scenario.graph.to_sparse()`` from the
  start: once over the whole graph, and once with ``limit`` set to the
  optimal cost, SciPy's only way to stop early (it still settles every node
  closer than the goal, and has no single-target exit).

Numba is warmed up before timing. Wall and CPU times are both printed,
because the machine may be shared. Costs are checked to agree to 1e-9.

``python benchmarks/exact.py --dynamic`` checks instead the target of
``exact.sipp``: on the dynamic scenarios of the FGDACO pack, every planner that
supports ``dynamic`` runs through the harness (the judge validates each path
against the moving obstacles) and no valid path may arrive earlier than SIPP's
earliest arrival, i.e. ``arrival_ratio >= 1`` for every grid or timed planner.
Any-angle planners are printed too; SIPP's model is the 8-connected graph, so
they may legitimately arrive earlier, and the table says which model each has.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np
from scipy.sparse.csgraph import dijkstra

import pathzoo
from pathzoo.core import Budget, Scenario
from pathzoo.io import load_scenario_files

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doc_table import add_write_docs_option, docs_table  # noqa: E402  (a sibling script)

ANY_ANGLE = "exact.thetastar"
"""Not an optimum of the graph: its cost is only compared with the others."""

SCEN = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "movingai" / "grid" / "rooms" / "8room_000.map.scen"


def timed(fn: Callable[[], object]) -> tuple[object, float, float]:
    """Result, wall seconds and CPU seconds of one call."""
    wall, cpu = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - wall, time.process_time() - cpu


DYNAMIC_SCENARIOS = ("fgdaco.scenario1", "fgdaco.scenario2", "fgdaco.scenario3", "fgdaco.trap")


def dynamic_target(seeds: int, time_s: float, db: Path) -> int:
    """Print, per dynamic scenario and planner, the earliest valid arrival over SIPP's; 1 if a grid path beats SIPP."""
    from pathzoo.analysis.path_models import path_models
    from pathzoo.grid.reference import earliest_arrival_s

    ids = sorted(e.id for e in pathzoo.list_plugins("planners") if "dynamic" in e.declared("kinds", ()))
    runs = pathzoo.run(ids, list(DYNAMIC_SCENARIOS), seeds=seeds, db=db, budget=Budget(time_s=time_s),
                       progress=False, experiment=f"sipp-target.s{seeds}.t{time_s:g}")
    models = path_models(ids)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"{len(ids)} planners support dynamic: {', '.join(ids)}; {seeds} seed(s), {time_s:g} s each; "
          f"load average {load:.1f}")
    print()
    print("| scenario | SIPP arrival s | planner | path model | valid runs | earliest arrival / SIPP | target |")
    print("|---|---:|---|---|---:|---:|---|")
    broken = 0
    for sid in DYNAMIC_SCENARIOS:
        ref = earliest_arrival_s(pathzoo.load_scenario(sid))
        for pid in ids:
            mine = runs[(runs["scenario"] == sid) & (runs["planner"] == pid)]
            ok = mine[(mine["status"].astype(str) == "solved") & mine["valid"].astype(bool)]
            best = float(ok["arrival_ratio"].min()) if len(ok) else float("nan")
            model = models[pid]
            if model == "anyangle":
                verdict = "n/a (any-angle model)"
            elif not np.isfinite(best):
                verdict = "no valid run"
            else:
                verdict = "met" if best >= 1.0 - 1e-9 else "NOT MET"
                broken += verdict == "NOT MET"
            print(f"| {sid} | {ref:.3f} | {pid} | {model} | {len(ok)}/{len(mine)} | {best:.4f} | >= 1: {verdict} |")
    return 1 if broken else 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--buckets", type=int, default=10, help="number of hardest buckets (default 10)")
    parser.add_argument("--scen", type=Path, default=SCEN, help="the .scen file (default: shared 8room_000)")
    parser.add_argument("--dynamic", action="store_true", help="check exact.sipp's target instead (see above)")
    parser.add_argument("--seeds", type=int, default=3, help="--dynamic: seeds per planner and scenario")
    parser.add_argument("--time-s", type=float, default=20.0, help="--dynamic: wall budget per run, seconds")
    parser.add_argument("--db", type=Path, default=Path("sipp-target.sqlite"), help="--dynamic: results file")
    add_write_docs_option(parser, "planners/exact.dijkstra.md")
    args = parser.parse_args(argv)
    if args.dynamic:
        return dynamic_target(args.seeds, args.time_s, args.db)

    problems = load_scenario_files(args.scen.resolve())
    last = max(p.metadata["bucket"] for p in problems)
    middle = last // 2 + args.buckets // 2
    groups = {
        "hardest": (last - args.buckets + 1, last),
        "middle": (middle - args.buckets + 1, middle),
    }
    graph = problems[0].graph
    matrix = graph.to_sparse("length")
    planners = {pid: pathzoo.make_planner(pid) for pid in ("exact.astar", "exact.dijkstra", "exact.thetastar")}
    for planner in planners.values():  # numba compilation and cache loading
        planner.plan(problems[-1], budget=Budget(), rng=np.random.default_rng(0))

    methods: dict[str, Callable[[Scenario], tuple[float, int]]] = {}
    for pid, planner in planners.items():
        def run(s: Scenario, planner=planner) -> tuple[float, int]:
            r = planner.plan(s, budget=Budget(), rng=np.random.default_rng(0))
            return r.extras["best_cost"], r.evaluations
        methods[pid] = run

    def scipy_full(s: Scenario) -> tuple[float, int]:
        d = dijkstra(matrix, indices=s.start_node)
        return float(d[s.goal_node]), int(np.isfinite(d).sum())

    def scipy_limit(s: Scenario) -> tuple[float, int]:
        d = dijkstra(matrix, indices=s.start_node, limit=s.reference_length + 1e-3)
        return float(d[s.goal_node]), int(np.isfinite(d).sum())

    methods["scipy dijkstra (full)"] = scipy_full
    methods["scipy dijkstra (limit)"] = scipy_limit

    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"{os.cpu_count()} CPUs, load average {load:.1f} at the start", file=sys.stderr)
    with docs_table(args.write_docs, "planners/exact.dijkstra.md", "exact.py"):
        print(f"map {args.scen.name}: {graph.shape[0]}x{graph.shape[1]}, {graph.n_edges} edges")
        for label, (lo, hi) in groups.items():
            chosen = [p for p in problems if lo <= p.metadata["bucket"] <= hi]
            if not measure(label, chosen, methods):
                return 1
        print()
        print("nodes: expanded nodes for the planners, nodes reached (finite distance) for SciPy")
    return 0


def measure(label: str, chosen: list[Scenario], methods: dict[str, Callable[[Scenario], tuple[float, int]]]) -> bool:
    """Time every method on every problem and print one table; False on a cost mismatch."""
    wall: dict[str, list[float]] = {m: [] for m in methods}
    cpu: dict[str, list[float]] = {m: [] for m in methods}
    nodes: dict[str, list[int]] = {m: [] for m in methods}
    ratio: dict[str, list[float]] = {m: [] for m in methods}
    for s in chosen:
        costs = []
        for name, fn in methods.items():
            (cost, count), w, c = timed(lambda: fn(s))
            wall[name].append(w)
            cpu[name].append(c)
            nodes[name].append(count)
            costs.append(cost)
        exact = [c for name, c in zip(methods, costs) if name != ANY_ANGLE]
        if max(exact) - min(exact) > 1e-9 * max(exact):
            print(f"cost mismatch on {s.id}: {costs}", file=sys.stderr)
            return False
        for name, c in zip(methods, costs):
            ratio[name].append(c / exact[0])
    buckets = sorted({s.metadata["bucket"] for s in chosen})
    lengths = [s.reference_length for s in chosen]
    print()
    print(f"{label}: {len(chosen)} problems of buckets {buckets[0]}..{buckets[-1]} "
          f"(optimal length {min(lengths):.1f}..{max(lengths):.1f})")
    print()
    ref_wall = sum(wall["scipy dijkstra (full)"])
    ref_cpu = sum(cpu["scipy dijkstra (full)"])
    print("| method | total wall s | median wall ms | total CPU s | median nodes | scipy full / method (wall) | (CPU) | mean cost / optimum |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name in methods:
        print(
            f"| {name} | {sum(wall[name]):.2f} | {1e3 * statistics.median(wall[name]):.1f} | {sum(cpu[name]):.2f} | "
            f"{statistics.median(nodes[name]):.0f} | {ref_wall / sum(wall[name]):.2f} | {ref_cpu / sum(cpu[name]):.2f} | "
            f"{statistics.fmean(ratio[name]):.4f} |"
        )
    return True


if __name__ == "__main__":
    sys.exit(main())
