"""Speed figures, each a ratio to a reference timed in the same run, printed beside its target (issue 26).

Run from the repository root (``../shared`` may sit beside it for more maps)::

    python benchmarks/speed.py            # every section (ggaco.case1 runs 1000 iterations: a few minutes)
    python benchmarks/speed.py --quick    # without ggaco.case1 and gant.simple.1
    python benchmarks/speed.py --only astar          # some sections only (see --help)
    python benchmarks/speed.py --only planners --rows fgdaco   # the planner rows whose label contains "fgdaco"
    python benchmarks/speed.py --write-docs   # also rewrite the table in docs/aco-engine.md (use after a full run)

Targets are ratios, so the state of the host does not decide them:

- ``exact.astar`` against the pure-Python ``pathfinding`` A* (``pip install
  pathzoo[bench]``), at least 50x on every MovingAI map in ``tests/data`` and
  ``../shared/data``;
- ``exact.astar``'s time to answer (one whole ``plan()``) against SciPy's
  full Dijkstra from the start, the graph built beforehand for both, at most
  1.0x on every such map.

The ant colonies' ns per ant-step against a floor kernel are in
``benchmarks/aco.py``; the harness's figures in ``benchmarks/harness.py``.
The papers' times, ``pathzoo list planners``, DSACO from nothing and
GGACO's case 1 are printed as information: the papers' times came from
other hardware and MATLAB, and the rest are absolute seconds.

Times are CPU seconds (``time.process_time``), the median of ``--repeats``
calls; in the A* rows, a sample of ``exact.astar`` or SciPy times a loop of
calls that lasts at least :data:`SAMPLE_S`, and each ``pathfinding`` call
(tens of microseconds at least) is timed alone on a grid of its own, built
untimed; each ``plan()``'s budget and generator are made untimed too.
``cold`` is the first ``plan()`` on a scenario object (per-scenario
tables built), ``warm`` the median of the following calls (tables reused, as
the harness does for every seed of a scenario in one worker). Numba is
compiled beforehand.
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

ROWS = (  # label, planner, scenario, iterations, ants, extra parameters, paper seconds
    ("fgdaco.scenario1", "aco.fgdaco", "fgdaco.scenario1", 100, 20, {}, 28.97),
    ("fgdaco.scenario2", "aco.fgdaco", "fgdaco.scenario2", 100, 20, {}, 38.74),
    ("fgdaco.scenario3", "aco.fgdaco", "fgdaco.scenario3", 100, 20, {}, 74.33),
    ("dsaco.complex, paper's step rule", "aco.dsaco", "dsaco.complex", 500, 10, {"step_rule": "longitude"}, 3.95),
    ("dsaco.complex, graph rule", "aco.dsaco", "dsaco.complex", 500, 10, {}, 3.95),
    ("gant.fig7", "aco.gant", "gant.fig7", 100, 100, {}, 9.38),
    ("iaca.offroad", "aco.iaca", "iaca.offroad", 100, 40, {}, 21.0),
)
BIG_ROWS = (("gant.simple.1", "aco.gant", "gant.simple.1", 30, 20, {}, 671.0),)
ASTAR_TARGET = 50.0
"""``exact.astar`` at least this many times faster than ``pathfinding``'s A*, on every map."""
SCIPY_TARGET = 1.0
"""``exact.astar``'s time to answer at most this multiple of SciPy's full Dijkstra, on every map."""
DATA = Path(__file__).resolve().parents[1]
MAP_DIRS = (DATA / "tests" / "data" / "movingai", DATA / ".." / "shared" / "data" / "movingai")


def cpu_plan(planner, scenario, iterations: int, seed: int = 0) -> tuple[float, pathzoo.PlanResult]:
    """CPU seconds and result of one ``plan()``."""
    started = time.process_time()
    result = planner.plan(scenario, budget=Budget(iterations=iterations), rng=np.random.default_rng(seed))
    return time.process_time() - started, result


def planner_rows(rows, repeats: int) -> None:
    """The papers' settings: our CPU time beside the paper's (information: other hardware, MATLAB)."""
    print("| setting | iterations x ants | cold (s) | warm, median (s) | paper (s) | paper / warm |")
    print("|---|---|---|---|---|---|")
    for label, pid, sid, iters, ants, params, paper in rows:
        scenario = pathzoo.load_scenario(sid)
        scenario.graph
        pathzoo.make_planner(pid, n_ants=1, **params).plan(  # compile numba on another scenario object
            pathzoo.load_scenario(sid), budget=Budget(iterations=1), rng=np.random.default_rng(0))
        planner = pathzoo.make_planner(pid, n_ants=ants, **params)
        cold, _ = cpu_plan(planner, scenario, iters)
        warm = statistics.median(cpu_plan(planner, scenario, iters)[0] for _ in range(repeats))
        print(f"| {label} | {iters} x {ants} | {cold:.3f} | {warm:.3f} | {paper} | {paper / warm:.0f}x |",
              flush=True)


def movingai_maps() -> list[Path]:
    """Every MovingAI ``.map`` with a ``.scen`` beside it in tests/data and ../shared/data, once per file name."""
    found: dict[str, Path] = {}
    for folder in MAP_DIRS:
        if folder.is_dir():
            for path in sorted(folder.resolve().rglob("*.map")):
                scen = next((c for c in (Path(f"{path}.scen"), path.with_name(f"{path.stem}-random-1.scen"))
                             if c.exists()), None)
                if scen is not None:
                    found.setdefault(path.name, scen)
    return [found[name] for name in sorted(found)]


def spread(problems: list, n: int) -> list:
    """``n`` problems spread over the file's buckets (lengths), the longest included."""
    order = sorted(problems, key=lambda p: p.reference_length or 0.0)
    picks = np.unique(np.linspace(len(order) // 10, len(order) - 1, n).astype(int))
    return [order[i] for i in picks]


SAMPLE_S = 2e-3
"""Shortest timed sample (CPU seconds): a shorter call is timed in a loop of calls, so that the clock's own cost
(about half a microsecond per reading) and resolution do not weigh on a call of a few microseconds."""


def calls_per_sample(once: float) -> int:
    """Calls in one timed sample when one call took ``once`` CPU seconds."""
    return max(1, int(SAMPLE_S / max(once, 1e-7)))


def cpu_once(fn: Callable[[], object]) -> float:
    """CPU seconds of one call of ``fn``."""
    started = time.process_time()
    fn()
    return time.process_time() - started


def median_cpu(fn: Callable[[], object], repeats: int) -> tuple[float, object]:
    """Median over ``repeats`` samples of the CPU seconds per call of ``fn``, and its last result."""
    calls = calls_per_sample(min(cpu_once(fn) for _ in range(5)))  # warm, and no single slow call decides
    times, out = [], None
    for _ in range(repeats):
        started = time.process_time()
        for _ in range(calls):
            out = fn()
        times.append((time.process_time() - started) / calls)
    return statistics.median(times), out


def pathfinding_cpu(s: pathzoo.Scenario, repeats: int) -> tuple[float, float]:
    """Median CPU seconds of ``pathfinding``'s A* on the scenario (a fresh grid each call, built untimed), and its length.

    A call takes at least tens of microseconds, so each is timed alone: the
    clock's cost is then below 1 %, and only one grid (hundreds of MB on a
    512 x 512 map) exists at a time.
    """
    from pathfinding.core.diagonal_movement import DiagonalMovement
    from pathfinding.core.grid import Grid
    from pathfinding.finder.a_star import AStarFinder

    finder = AStarFinder(diagonal_movement=DiagonalMovement.only_when_no_obstacle)
    walkable = (~s.blocked).astype(int).tolist()
    (sx, sy), (gx, gy) = (tuple(int(v) for v in np.floor(p / s.cell_size)) for p in (s.start, s.goal))
    times, path = [], []
    for _ in range(repeats):  # its nodes keep search state, so each call gets a new grid
        grid = Grid(matrix=walkable)
        started = time.process_time()
        path, _ = finder.find_path(grid.node(sx, sy), grid.node(gx, gy), grid)
        times.append(time.process_time() - started)
        del grid
    length = sum(np.hypot(b.x - a.x, b.y - a.y) for a, b in zip(path, path[1:]))
    return statistics.median(times), float(length)


def astar_rows(n_problems: int, repeats: int) -> None:
    """Per map: exact.astar against ``pathfinding``'s A* and against SciPy's full Dijkstra, CPU milliseconds summed.

    The graph (and A*'s move table, built with it) exists before any timing,
    as the harness keeps both for every problem of a map; A*'s numba kernel
    is compiled beforehand. A* and ``pathfinding`` must agree on every length.
    """
    from scipy.sparse.csgraph import dijkstra

    from pathzoo.io import load_scenario_files

    astar = pathzoo.make_planner("exact.astar")
    print("| map | problems | exact.astar (ms) | pathfinding (ms) | x faster | target | met "
          "| SciPy Dijkstra (ms) | A* / SciPy | target | met |\n|---|---|---|---|---|---|---|---|---|---|---|")
    for scen in movingai_maps():
        chosen = spread(load_scenario_files(scen), n_problems)
        matrix = chosen[0].graph.to_sparse("length")
        astar.plan(chosen[0], budget=Budget(), rng=np.random.default_rng(0))  # the move table and the kernel
        ours = theirs = scipy_s = 0.0
        for s in chosen:
            budget, rng, source = Budget(), np.random.default_rng(0), s.start_node  # inputs, made untimed
            cpu, result = median_cpu(lambda: astar.plan(s, budget=budget, rng=rng), repeats)
            ours += cpu
            cpu, length = pathfinding_cpu(s, repeats)
            theirs += cpu
            cost = result.extras["graph_cost"]
            if abs(length - cost) > 1e-9 * max(length, 1.0):
                raise RuntimeError(f"pathfinding and exact.astar disagree on {s.id}: {length} vs {cost}")
            scipy_s += median_cpu(lambda: dijkstra(matrix, indices=source), repeats)[0]
        faster, share = theirs / ours, ours / scipy_s
        print(f"| {scen.name.removesuffix('.scen')} | {len(chosen)} | {1e3 * ours:.3g} | {1e3 * theirs:.4g} | {faster:.1f}x "
              f"| >= {ASTAR_TARGET:g}x | {'yes' if faster >= ASTAR_TARGET else 'no'} | {1e3 * scipy_s:.3g} | {share:.2f}x "
              f"| <= {SCIPY_TARGET:g}x | {'yes' if share <= SCIPY_TARGET else 'no'} |", flush=True)
    print()


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
                  f"| {m['total_s']:.1f} s |")
            print(f"| ggaco.case1 peak RSS, {label} | {m['peak_gb']:.2f} GB |", flush=True)
        # two workers at once on the cached graph (its pages shared through the page cache); 50 colonies
        # each: the peak comes from the set-up, every later colony runs in the same memory
        procs = [subprocess.Popen(run + ["50"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                 for _ in range(2)]
        peaks = [_child_result(p)["peak_gb"] for p in procs]
        print(f"| ggaco.case1 peak RSS of each of 2 concurrent workers (graph pages included) | "
              f"{' and '.join(f'{p:.2f}' for p in peaks)} GB |", flush=True)


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
          f"| {wall:.2f} s |", flush=True)


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
                      f"| {total:.3f} s |", flush=True)


SECTIONS = ("astar", "planners", "list", "dsaco", "ggaco")
"""Parts of the table, in the order they are printed (``--only``)."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip ggaco.case1 and gant.simple.1")
    parser.add_argument("--repeats", type=positive_int, default=3, help="warm plan() calls per row (median)")
    parser.add_argument("--astar-problems", type=positive_int, default=8, help="problems per map for the A* rows")
    parser.add_argument("--only", type=_sections, default=SECTIONS, metavar="SECTIONS",
                        help=f"comma-separated parts to run, of: {', '.join(SECTIONS)} (default: all)")
    parser.add_argument("--rows", metavar="TEXT", default="",
                        help="in the planners section, only the rows whose label contains TEXT (e.g. fgdaco)")
    add_write_docs_option(parser, "aco-engine.md")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs; CPU seconds", file=sys.stderr)
    with docs_table(args.write_docs, "aco-engine.md", "speed.py"):
        if "astar" in args.only:
            print("### exact.astar against pathfinding's A* and SciPy's Dijkstra (targets)\n")
            astar_rows(args.astar_problems, args.repeats)
        if "planners" in args.only:
            print("### The papers' settings (information)\n")
            rows = ROWS + (() if args.quick else BIG_ROWS)
            planner_rows(tuple(row for row in rows if args.rows in row[0]), args.repeats)
        print("\n### Absolute figures (information)\n\n| figure | measured |\n|---|---|")
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
