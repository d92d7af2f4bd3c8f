"""Issue 12's speed and memory table: each figure measured and printed beside its target, in one run.

Run from the repository root (``../shared`` must sit beside it)::

    python benchmarks/speed.py            # every row (ggaco.case1 runs 1000 iterations: a few minutes)
    python benchmarks/speed.py --quick    # without ggaco.case1 and gant.simple.1
    python benchmarks/speed.py --only ggaco,dsaco   # some sections only (see --help)
    python benchmarks/speed.py --only planners --rows fgdaco   # the planner rows whose label contains "fgdaco"
    python benchmarks/speed.py --write-docs   # also rewrite the table in docs/aco-engine.md (use after a full run)

Times are CPU seconds (``time.process_time``) of one ``plan()`` call, the
median of ``--repeats`` calls, so other processes on a shared machine
inflate them little; the load average is printed first. ``cold`` is the first
``plan()`` on a scenario object (per-scenario tables built), ``warm`` the
median of the following calls (tables reused, as the harness does for every
seed of a scenario in one worker). Numba is compiled beforehand.

``ggaco.case1`` runs in a child process (so its peak RSS is its own), twice:
once with an empty graph cache (the graph is built and stored) and once with
the cache filled (the graph is memory-mapped), each time ``plan()`` once with
the paper's 1000 iterations x 20 ants; then two children at once on the
cached graph (50 colonies each) give the memory of an extra worker.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import pathzoo
from pathzoo import Budget
from pathzoo.cli.cmd_run import positive_int

sys.path.insert(0, str(Path(__file__).resolve().parent))
from aco import room512  # noqa: E402  (the benchmark scripts share their scenario builders)
from doc_table import add_write_docs_option, docs_table  # noqa: E402

ROWS = (  # label, planner, scenario, iterations, ants, extra parameters, paper seconds, target seconds
    ("fgdaco.scenario1", "aco.fgdaco", "fgdaco.scenario1", 100, 20, {}, 28.97, 0.29),
    ("fgdaco.scenario2", "aco.fgdaco", "fgdaco.scenario2", 100, 20, {}, 38.74, 0.39),
    ("fgdaco.scenario3", "aco.fgdaco", "fgdaco.scenario3", 100, 20, {}, 74.33, 0.74),
    ("dsaco.complex, paper's step rule", "aco.dsaco", "dsaco.complex", 500, 10, {"step_rule": "longitude"},
     3.95, 0.04),
    ("dsaco.complex, graph rule", "aco.dsaco", "dsaco.complex", 500, 10, {}, 3.95, 0.04),
    ("gant.fig7", "aco.gant", "gant.fig7", 100, 100, {}, 9.38, 0.066),
    ("iaca.offroad", "aco.iaca", "iaca.offroad", 100, 40, {}, 21.0, 0.034),
)
BIG_ROWS = (("gant.simple.1", "aco.gant", "gant.simple.1", 30, 20, {}, 671.0, 6.7),)
AS_TARGET = 10e6
ASTAR_TARGET = 50.0


def cpu_plan(planner, scenario, iterations: int, seed: int = 0) -> tuple[float, pathzoo.PlanResult]:
    """CPU seconds and result of one ``plan()``."""
    started = time.process_time()
    result = planner.plan(scenario, budget=Budget(iterations=iterations), rng=np.random.default_rng(seed))
    return time.process_time() - started, result


def planner_rows(rows, repeats: int) -> None:
    print("| setting | iterations x ants | cold (s) | warm, median (s) | target (s) | met | paper (s) | speed-up (warm) |")
    print("|---|---|---|---|---|---|---|---|")
    for label, pid, sid, iters, ants, params, paper, target in rows:
        scenario = pathzoo.load_scenario(sid)
        scenario.graph
        pathzoo.make_planner(pid, n_ants=1, **params).plan(  # compile numba on another scenario object
            pathzoo.load_scenario(sid), budget=Budget(iterations=1), rng=np.random.default_rng(0))
        planner = pathzoo.make_planner(pid, n_ants=ants, **params)
        cold, _ = cpu_plan(planner, scenario, iters)
        warm = statistics.median(cpu_plan(planner, scenario, iters)[0] for _ in range(repeats))
        print(f"| {label} | {iters} x {ants} | {cold:.3f} | {warm:.3f} | {target} | "
              f"{'yes' if warm <= target else 'no'} | {paper} | {paper / warm:.0f}x |", flush=True)


def as_throughput(repeats: int) -> None:
    scenario = room512()
    scenario.graph
    planner = pathzoo.make_planner("aco.as")
    cpu_plan(planner, scenario, 1)
    rates = []
    for _ in range(repeats):
        cpu, result = cpu_plan(planner, scenario, 5)
        rates.append(result.extras["ant_steps"] / cpu)
    rate = statistics.median(rates)
    print(f"| aco.as ant-steps per CPU second, 8room_000, 5 colonies, whole plan() | {rate / 1e6:.2f} M | "
          f"{AS_TARGET / 1e6:.0f} M | {'yes' if rate >= AS_TARGET else 'no'} |", flush=True)


def astar_against_pathfinding(n_problems: int, repeats: int = 3) -> None:
    """exact.astar against the pure-Python ``pathfinding`` A* and SciPy's Dijkstra on 8room_000 (512 x 512).

    Each method's time on a problem is the median CPU time of ``repeats``
    calls; the shared graph (and A*'s move table, built with it) exists
    before timing, as the harness keeps both for every problem of a map.
    """
    from pathfinding.core.diagonal_movement import DiagonalMovement
    from pathfinding.core.grid import Grid
    from pathfinding.finder.a_star import AStarFinder
    from scipy.sparse.csgraph import dijkstra

    from pathzoo.io import load_scenario_files
    from pathzoo_exact.kernel import HEAP_FULL, SearchState
    from pathzoo_exact.moves import move_table

    scen = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "movingai" / "grid" / "rooms"
    problems = load_scenario_files((scen / "8room_000.map.scen").resolve())
    buckets = sorted({p.metadata["bucket"] for p in problems})
    chosen = [next(p for p in problems if p.metadata["bucket"] == b)
              for b in np.linspace(buckets[len(buckets) // 10], buckets[-1], n_problems).astype(int)
              if any(p.metadata["bucket"] == b for p in problems)]
    graph = chosen[0].graph
    matrix = graph.to_sparse("length")
    started = time.process_time()
    move_table(graph, "length")
    table_s = time.process_time() - started
    astar = pathzoo.make_planner("exact.astar")
    astar.plan(chosen[0], budget=Budget(), rng=np.random.default_rng(0))
    finder = AStarFinder(diagonal_movement=DiagonalMovement.only_when_no_obstacle)

    def median_cpu(fn):
        times, out = [], None
        for _ in range(repeats):
            started = time.process_time()
            out = fn()
            times.append(time.process_time() - started)
        return statistics.median(times), out

    state = SearchState.start(graph.n_nodes, chosen[0].start_node)

    def search_only(s: pathzoo.Scenario, batch) -> float:
        """CPU seconds of the numba search alone, in a restarted state (what plan() adds is the rest)."""
        state.restart(s.start_node)
        started = time.process_time()
        while batch(state, 1 << 40) == HEAP_FULL:
            state.grow_heap()
        return time.process_time() - started

    ours = theirs = scipy_s = kernel_s = 0.0
    expanded = scipy_nodes = 0
    for s in chosen:
        cpu, result = median_cpu(lambda: astar.plan(s, budget=Budget(), rng=np.random.default_rng(0)))
        ours += cpu
        expanded += result.evaluations
        batch = astar._make_batch(s, s.goal_node)
        kernel_s += statistics.median(search_only(s, batch) for _ in range(repeats))
        walkable = (~s.blocked).astype(int).tolist()
        (sc, sr), (gc, gr) = (tuple(int(v) for v in np.floor(p / s.cell_size)) for p in (s.start, s.goal))
        times = []
        for _ in range(repeats):  # a fresh grid each time (its nodes keep search state), built untimed
            grid = Grid(matrix=walkable)
            started = time.process_time()
            path, _ = finder.find_path(grid.node(sc, sr), grid.node(gc, gr), grid)
            times.append(time.process_time() - started)
        theirs += statistics.median(times)
        length = sum(np.hypot(b.x - a.x, b.y - a.y) for a, b in zip(path, path[1:]))
        if abs(length - result.extras["graph_cost"]) > 1e-9 * length:
            raise RuntimeError(f"pathfinding and exact.astar disagree on {s.id}: {length} vs {result.extras}")
        cpu, dist = median_cpu(lambda: dijkstra(matrix, indices=s.start_node))
        scipy_s += cpu
        scipy_nodes += int(np.isfinite(dist).sum())
    ratio = theirs / ours
    print(f"| exact.astar vs pathfinding A*, {len(chosen)} problems of 8room_000, median of {repeats} "
          f"(CPU {ours:.3f} s vs {theirs:.2f} s; move table built once per graph, numba cache load included: "
          f"{1e3 * table_s:.1f} ms) "
          f"| {ratio:.1f}x | {ASTAR_TARGET:.0f}x | {'yes' if ratio >= ASTAR_TARGET else 'no'} |")
    print(f"| exact.astar: the search kernel's share of those plan() calls (the rest is the state, the path and "
          f"the result) | {kernel_s:.3f} s of {ours:.3f} s ({100 * kernel_s / ours:.0f} %) | - | - |")
    ours_rate, scipy_rate = expanded / ours, scipy_nodes / scipy_s
    print(f"| exact.astar expansions/s (whole plan()) vs scipy dijkstra nodes/s | {ours_rate / 1e6:.2f} M vs "
          f"{scipy_rate / 1e6:.2f} M | >= scipy | {'yes' if ours_rate >= scipy_rate else 'no'} |", flush=True)


CHILD = """
import json, resource, sys, time
import numpy as np
import pathzoo
from pathzoo import Budget
c0 = time.process_time()
s = pathzoo.load_scenario("ggaco.case1")
s.blocked
load_s = time.process_time() - c0
s.graph
graph_s = time.process_time() - c0 - load_s
c1 = time.process_time()
iterations = int(sys.argv[1])
r = pathzoo.make_planner("aco.ggaco", iterations=iterations).plan(s, budget=Budget(), rng=np.random.default_rng(0))
plan_s = time.process_time() - c1
print(json.dumps({"load_s": load_s, "graph_s": graph_s, "plan_s": plan_s, "total_s": time.process_time() - c0,
                  "iterations": r.iterations, "peak_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6}))
"""


def _child_result(proc: subprocess.Popen) -> dict:
    out, err = proc.communicate()
    if proc.returncode:
        raise RuntimeError(f"ggaco.case1 child failed:\n{err}")
    return json.loads(out.strip().splitlines()[-1])


def ggaco_case1() -> None:
    """Paper setting in a fresh process: empty cache, then cache filled, then two workers sharing the cached graph."""
    with tempfile.TemporaryDirectory(prefix="pathzoo-speed-") as cache:
        env = {**os.environ, "PATHZOO_CACHE_DIR": cache}
        run = [sys.executable, "-c", CHILD]
        for label in ("graph built (empty cache)", "graph memory-mapped from the cache"):
            m = _child_result(subprocess.Popen(run + ["1000"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                               text=True))
            print(f"| ggaco.case1, 1000 x 20, {label}: DEM {m['load_s']:.1f} s + graph {m['graph_s']:.1f} s + "
                  f"plan() {m['plan_s']:.1f} s "
                  f"| {m['total_s']:.1f} s | 29.5 s | {'yes' if m['total_s'] <= 29.5 else 'no'} |")
            print(f"| ggaco.case1 peak RSS, {label} | {m['peak_gb']:.2f} GB | 1.5 GB | "
                  f"{'yes' if m['peak_gb'] <= 1.5 else 'no'} |", flush=True)
        # two workers at once on the cached graph (its pages shared through the page cache); 50 colonies
        # each: the peak comes from the set-up, every later colony runs in the same memory
        procs = [subprocess.Popen(run + ["50"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                 for _ in range(2)]
        peaks = [_child_result(p)["peak_gb"] for p in procs]
        print(f"| ggaco.case1 peak RSS of each of 2 concurrent workers (graph pages included) | "
              f"{' and '.join(f'{p:.2f}' for p in peaks)} GB | 1.5 GB per extra worker beyond the shared graph | "
              f"{'yes' if max(peaks) <= 1.5 else 'no'} |", flush=True)


LIST_TARGET = 0.5


def list_planners_time(repeats: int = 5) -> None:
    """Wall seconds of ``pathzoo list planners`` (a fresh process each time), median of ``repeats``; CPU beside it."""
    import resource

    command = [str(Path(sys.executable).parent / "pathzoo"), "list", "planners"]
    walls, cpus = [], []
    for _ in range(repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        started = time.perf_counter()
        subprocess.run(command, capture_output=True, check=True)
        walls.append(time.perf_counter() - started)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    wall = statistics.median(walls)
    print(f"| `pathzoo list planners`, wall seconds, median of {repeats} (CPU {statistics.median(cpus):.2f} s) "
          f"| {wall:.2f} s | {LIST_TARGET} s | {'yes' if wall <= LIST_TARGET else 'no'} |", flush=True)


DSACO_ALL_IN = """
import json, sys, time
import numpy as np
import pathzoo
from pathzoo import Budget
params = json.loads(sys.argv[1])
pathzoo.make_planner("aco.dsaco", n_ants=1, **params).plan(  # compile numba (its cache) on another scenario
    pathzoo.load_scenario("dsaco.simple"), budget=Budget(iterations=1), rng=np.random.default_rng(0))
scenario = pathzoo.load_scenario("dsaco.complex")
scenario.blocked  # the scenario's arrays are read: not counted
cpu = [time.process_time()]
scenario.graph
cpu.append(time.process_time())
pathzoo.make_planner("aco.dsaco", **params).plan(scenario, budget=Budget(iterations=500), rng=np.random.default_rng(0))
cpu.append(time.process_time())
print(json.dumps({"graph_s": cpu[1] - cpu[0], "plan_s": cpu[2] - cpu[1]}))
"""


def dsaco_all_in() -> None:
    """dsaco.complex from nothing in a fresh process: scenario, graph, per-scenario tables and one plan().

    Each rule twice: with the graph built in the process (the default: graphs this small are not cached), and
    with it memory-mapped from a filled graph cache (``PATHZOO_GRAPH_CACHE_MIN_CELLS=0``, one process to fill it
    first), as every worker but the first would find it if small graphs were cached too.
    """
    for label, params in (("paper's step rule", {"step_rule": "longitude"}), ("graph rule", {})):
        with tempfile.TemporaryDirectory() as cache:
            cached = {**os.environ, "PATHZOO_CACHE_DIR": cache, "PATHZOO_GRAPH_CACHE_MIN_CELLS": "0"}
            for graph, env, runs in (("graph built", None, 1), ("graph memory-mapped from the cache", cached, 2)):
                for _ in range(runs):  # with the cache: the first run fills it, the second is measured
                    out = subprocess.run([sys.executable, "-c", DSACO_ALL_IN, json.dumps(params)], capture_output=True,
                                         text=True, check=True, env=env)
                m = json.loads(out.stdout.strip().splitlines()[-1])
                total = m["graph_s"] + m["plan_s"]
                print(f"| dsaco.complex, {label}, 500 x 10, fresh process, {graph}: graph {m['graph_s']:.3f} s + "
                      f"tables and first plan() {m['plan_s']:.3f} s "
                      f"| {total:.3f} s | 0.04 s | {'yes' if total <= 0.04 else 'no'} |", flush=True)


SECTIONS = ("planners", "as", "astar", "list", "dsaco", "ggaco")
"""Parts of the table, in the order they are printed (``--only``)."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip ggaco.case1 and gant.simple.1")
    parser.add_argument("--repeats", type=positive_int, default=3, help="warm plan() calls per row (median)")
    parser.add_argument("--astar-problems", type=positive_int, default=8, help="8room_000 problems for the A* rows")
    parser.add_argument("--only", type=_sections, default=SECTIONS, metavar="SECTIONS",
                        help=f"comma-separated parts to run, of: {', '.join(SECTIONS)} (default: all)")
    parser.add_argument("--rows", metavar="TEXT", default="",
                        help="in the planners section, only the rows whose label contains TEXT (e.g. fgdaco)")
    add_write_docs_option(parser, "aco-engine.md")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs; CPU seconds of one plan()",
          file=sys.stderr)
    with docs_table(args.write_docs, "aco-engine.md", "speed.py"):
        if "planners" in args.only:
            rows = ROWS + (() if args.quick else BIG_ROWS)
            planner_rows(tuple(row for row in rows if args.rows in row[0]), args.repeats)
        print("\n| figure | measured | target | met |\n|---|---|---|---|")
        if "as" in args.only:
            as_throughput(args.repeats)
        if "astar" in args.only:
            astar_against_pathfinding(args.astar_problems)
        if "list" in args.only:
            list_planners_time()
        if "dsaco" in args.only:
            dsaco_all_in()
        if "ggaco" in args.only and not args.quick:
            ggaco_case1()


def _sections(text: str) -> tuple[str, ...]:
    """``--only``'s value: known section names, or a usage error."""
    chosen = tuple(part.strip() for part in text.split(",") if part.strip())
    unknown = [part for part in chosen if part not in SECTIONS]
    if unknown or not chosen:
        raise argparse.ArgumentTypeError(f"unknown section(s) {', '.join(unknown) or '(none)'}; "
                                         f"choose from {', '.join(SECTIONS)}")
    return chosen


if __name__ == "__main__":
    main()
