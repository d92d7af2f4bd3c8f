"""Exact planners: the graph searches against SciPy's Dijkstra, the any-angle optimum against its targets.

Run from the repository root, with ``shared/`` beside the repository::

    python benchmarks/exact.py                     # both parts
    python benchmarks/exact.py --part graph        # Dijkstra/A* only
    python benchmarks/exact.py --part anyangle     # the any-angle optimum only
    python benchmarks/exact.py --buckets 3 --every 4   # fewer problems
    python benchmarks/exact.py --part graph --write-docs  # also rewrite the table in docs/planners/exact.dijkstra.md
    python benchmarks/exact.py --dynamic           # exact.sipp's target instead (below)

Part ``graph`` (the 512 x 512 MovingAI map ``8room_000``, 10 hardest and 10
middle buckets, 200 problems):

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

Part ``anyangle`` (issue 22), every figure beside its target:

- on each 512 x 512 MovingAI map of ``shared/data/movingai/grid`` (rooms,
  mazes, random): the mesh's build time (CPU, target <= 2 s), and on every
  ``--every``-th problem of its ``.scen`` file (all by default) the query
  CPU time of ``anyangle_path`` with the built mesh (median <= 20 ms, max <=
  500 ms) and whether the problem was solved (target: all). The reference
  timed in the same run is ``exact.thetastar`` (``plan()``) on every tenth
  of those problems, whose length the optimum must never exceed;
  ``exact.anyangle``'s ``plan()`` on the same problems must return a path
  the judge (``validate_path``) accepts;
- agreement with the visibility-graph search (``method="visibility"``,
  the independent reference): every problem of the 32 x 32 maps and
  ``arena``, and 20 random cell-centre problems on the 256 x 256 top-left
  quarter of each 512 x 512 map; target: lengths equal within 1e-6 on all;
- for information, 1024 x 1024 maps made by tiling each 512 x 512 map
  2 x 2: mesh time and query times on 50 random problems whose goal is
  reachable (a goal outside the start's component is answered at once).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Callable, TypeVar

import numpy as np
from scipy.sparse.csgraph import dijkstra

import pathzoo
from pathzoo.core import Budget, Scenario
from pathzoo.io import load_scenario_files

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doc_table import add_write_docs_option, docs_table  # noqa: E402  (a sibling script)

ANY_ANGLE = "exact.thetastar"
"""Not an optimum of the graph: its cost is only compared with the others."""

GRID_DATA = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "movingai"
"""The MovingAI maps and problems (``shared/data/movingai`` beside the repository)."""

SCEN = GRID_DATA / "grid" / "rooms" / "8room_000.map.scen"


T = TypeVar("T")


def timed(fn: Callable[[], T]) -> tuple[T, float, float]:
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
    parser.add_argument("--part", choices=("graph", "anyangle", "all"), default="all", help="which part to run")
    parser.add_argument("--every", type=int, default=1, help="any-angle part: every n-th problem of each map")
    parser.add_argument("--dynamic", action="store_true", help="check exact.sipp's target instead (see above)")
    parser.add_argument("--seeds", type=int, default=3, help="--dynamic: seeds per planner and scenario")
    parser.add_argument("--time-s", type=float, default=20.0, help="--dynamic: wall budget per run, seconds")
    parser.add_argument("--db", type=Path, default=Path("sipp-target.sqlite"), help="--dynamic: results file")
    add_write_docs_option(parser, "planners/exact.dijkstra.md")
    args = parser.parse_args(argv)
    if args.dynamic:
        return dynamic_target(args.seeds, args.time_s, args.db)
    if args.part in ("graph", "all") and graph_part(args) != 0:
        return 1
    if args.part in ("anyangle", "all"):
        return anyangle_part(args.every)
    return 0


def graph_part(args: argparse.Namespace) -> int:
    """The exact graph planners against SciPy on one map (the ``graph`` part)."""

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


def _verdict(ok: bool) -> str:
    return "met" if ok else "NOT met"


def anyangle_part(every: int) -> int:
    """The any-angle optimum on the 512 x 512 maps and against the visibility graph; 0 when every target is met."""
    from pathzoo.grid.anyangle import anyangle_path
    from pathzoo.grid.navmesh import navigation_mesh
    from pathzoo.rules import validate_path

    maps = sorted(GRID_DATA.glob("grid/*/*.map.scen"))
    big = [m for m in maps if load_scenario_files(m)[0].blocked.shape == (512, 512)]
    small = sorted(GRID_DATA.glob("mapf/*.scen")) + [m for m in maps if m not in big]
    thetastar, planner = pathzoo.make_planner("exact.thetastar"), pathzoo.make_planner("exact.anyangle")
    warm = load_scenario_files(big[0])[0]
    thetastar.plan(warm, budget=Budget(), rng=np.random.default_rng(0))
    planner.plan(warm, budget=Budget(), rng=np.random.default_rng(0))
    all_met = True
    print()
    print("any-angle optimum (Polyanya on the rectangle mesh), CPU times")
    print()
    print("| map | mesh s (<= 2) | problems | solved | median ms (<= 20) | max ms (<= 500) "
          "| Theta* median ms | Theta* / Polyanya (median) | longer than Theta* | judge rejects |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for scen in big:
        problems = load_scenario_files(scen)[::every]
        blocked = problems[0].blocked
        (mesh, _, mesh_cpu) = timed(lambda: navigation_mesh(blocked))
        times, solved = [], 0
        lengths: dict[int, float] = {}
        for k, s in enumerate(problems):
            ref, _, cpu = timed(lambda: anyangle_path(blocked, s.start, s.goal, s.cell_size, mesh=lambda: mesh))
            times.append(cpu)
            if ref is not None and ref.length <= s.reference_length + 1e-5:
                solved += 1
                lengths[k] = ref.length
        theta_times, longer, rejected = [], 0, 0
        for k in range(0, len(problems), 10):
            s = problems[k]
            r, _, cpu = timed(lambda: thetastar.plan(s, budget=Budget(), rng=np.random.default_rng(0)))
            theta_times.append(cpu)
            if k not in lengths or lengths[k] > float(r.extras["best_cost"]) + 1e-9:
                longer += 1
            mine = planner.plan(s, budget=Budget(), rng=np.random.default_rng(0))
            if mine.path is None or not validate_path(s, mine.path):
                rejected += 1
        med, worst = 1e3 * statistics.median(times), 1e3 * max(times)
        theta_med = 1e3 * statistics.median(theta_times)
        met = mesh_cpu <= 2 and solved == len(problems) and med <= 20 and worst <= 500 and not longer and not rejected
        all_met &= met
        print(f"| {scen.name.removesuffix('.map.scen')} | {mesh_cpu:.3f} | {len(problems)} | {solved} | {med:.2f} "
              f"| {worst:.1f} | {theta_med:.1f} | {theta_med / med:.1f} | {longer} of {len(theta_times)} "
              f"| {rejected} of {len(theta_times)} |")
    print()
    print("1024 x 1024 (each 512 x 512 map tiled 2 x 2; 50 random reachable cell-centre problems; no target):")
    rng = np.random.default_rng(0)
    for scen in big:
        tiled = np.tile(load_scenario_files(scen)[0].blocked, (2, 2))
        (mesh, _, mesh_cpu) = timed(lambda: navigation_mesh(tiled))
        free = np.argwhere(~tiled)
        component = mesh.component[mesh.cell_polygon[free[:, 0], free[:, 1]]]
        times = []
        for _ in range(50):
            i = rng.integers(len(free))
            j = rng.choice(np.flatnonzero(component == component[i]))
            times.append(timed(lambda: anyangle_path(tiled, free[i][::-1] + 0.5, free[j][::-1] + 0.5, 1.0,
                                                     mesh=lambda: mesh))[2])
        print(f"- {scen.name.removesuffix('.map.scen')}: mesh {mesh_cpu:.3f} s, query median "
              f"{1e3 * statistics.median(times):.1f} ms, max {1e3 * max(times):.1f} ms")
    print()
    worst_diff, count, fast_cpu, slow_cpu = 0.0, 0, 0.0, 0.0
    cases = []
    for scen in small:
        cases += [(s.blocked, s.start / s.cell_size, s.goal / s.cell_size) for s in load_scenario_files(scen)[::every]]
    for scen in big:
        quarter = load_scenario_files(scen)[0].blocked[:256, :256]
        free = np.argwhere(~quarter)
        for _ in range(20):
            i, j = rng.choice(len(free), 2, replace=False)
            cases.append((quarter, free[i][::-1] + 0.5, free[j][::-1] + 0.5))
    for blocked, start, goal in cases:
        fast, _, c1 = timed(lambda: anyangle_path(blocked, start, goal, 1.0))
        slow, _, c2 = timed(lambda: anyangle_path(blocked, start, goal, 1.0, method="visibility"))
        fast_cpu += c1
        slow_cpu += c2
        count += 1
        if (fast is None) != (slow is None):
            worst_diff = math.inf
        elif fast is not None and slow is not None:
            worst_diff = max(worst_diff, abs(fast.length - slow.length))
    all_met &= worst_diff <= 1e-6
    print(f"agreement with the visibility graph on {count} problems of maps up to 256 x 256: largest length "
          f"difference {worst_diff:.2e} (target <= 1e-6: {_verdict(worst_diff <= 1e-6)}); CPU {fast_cpu:.2f} s "
          f"against {slow_cpu:.2f} s (visibility graph / Polyanya {slow_cpu / fast_cpu:.0f})")
    print(f"every any-angle target: {_verdict(all_met)}")
    return 0 if all_met else 1


if __name__ == "__main__":
    sys.exit(main())
