"""Speed of the ant-colony planners: ant-steps per second, time per iteration, and the papers' settings.

Run from the repository root (``../shared`` must sit beside it)::

    python benchmarks/aco.py               # throughput + G-Ant settings + GGACO on its largest terrain
    python benchmarks/aco.py --quick       # throughput only
    python benchmarks/aco.py --all-ggaco   # also the four other GGACO terrain sizes
    python benchmarks/aco.py --seeds 10    # also DSACO/IACA/FGDACO quality over 10 seeds per paper setting
    python benchmarks/aco.py --later-only --seeds 10   # only the DSACO/IACA/FGDACO sections
    python benchmarks/aco.py --floor-only  # only each colony's ns per ant-step against the floor kernel

Floor: every colony's CPU nanoseconds per ant-step on 8room_000 (512 x 512),
as a multiple of a floor kernel timed in the same process on the same graph:
a compiled random walk that makes one random draw and reads one neighbour row
per step, the least any ant walk must do. A colony's ns per step is
the CPU time spent in the compiled walks (timed around them by this script)
over the ant-steps they made, so set-up (tables, trails, the path) does not
count. IACA and DSACO's step rule run on their papers' maps (on 8room_000 the
first fails and the second stops after one colony), and so do the timed walks
of FGDACO and ACS (``fgdaco.scenario3``: on 8room_000, which has no moving
obstacles, FGDACO walks the static kernels), with the floor timed on that
map's graph. Each figure is the minimum of ``--repeats`` runs of
``--floor-colonies`` colonies, its floor the minimum of as many floor walks
timed one before each run (so that both see the same load on a shared
machine), printed beside its target (issue 26): at most 3x the floor for AS, MMAS, G-Ant and DSACO under
the graph rule, at most 5x for ACS, IACA, DSACO under the paper's step rule
and FGDACO's timed walks (GGACO is shown for information).

Throughput: each variant runs a few colonies with its default parameters on a
100 x 100 random grid and on MovingAI's 8room_000 (512 x 512, its longest
``.scen`` problem). ``steps/s (CPU)`` is ant-steps per CPU second of the whole
``plan()`` call, set-up included (the "one core" figure, insensitive to other
processes); ``steps/s (walks)`` divides by the wall time spent in the compiled
walks only; ``s/iter (CPU)`` is CPU time per colony.

Paper settings: the CPU and wall time of one ``plan()`` call (graph built
beforehand, as the papers time the search) next to the time the paper
reports. The speed-up uses CPU time, which equals wall time on an idle core
and is not inflated when other processes share the machine (the load average
is printed first). Scenarios come from the registered ``gant.*`` and ``ggaco.*`` packs;
when a pack is not installed a stand-in of the same size is used and marked.
"""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import time
from pathlib import Path
from typing import Callable, Iterator

import numpy as np
from numba import njit
from scipy.sparse.csgraph import dijkstra

import pathzoo
from pathzoo import Budget, Scenario, VehicleModel
from pathzoo.generators import fractal_terrain, random_obstacles
from pathzoo.rules import validate_path
from pathzoo.io.movingai import read_map, read_scen

SHARED = Path(__file__).resolve().parents[1] / ".." / "shared" / "data"
VARIANTS = ("aco.as", "aco.mmas", "aco.acs", "aco.ggaco", "aco.gant", "aco.dsaco", "aco.iaca", "aco.fgdaco")

TABLE_HEAD = ("| setting | scenario | iterations x ants | ours, CPU (s) | ours, wall (s) | paper (s) | speed-up (CPU) "
              "| our length |\n|---|---|---|---|---|---|---|---|")

GANT_TABLE4 = {  # (iterations, population): seconds reported in G-Ant's Table 4
    (10, 10): 0.8067, (10, 40): 1.0241, (10, 70): 1.2141, (10, 100): 1.4615,
    (40, 10): 1.6969, (40, 40): 2.5589, (40, 70): 3.0248, (40, 100): 4.3270,
    (70, 10): 2.7683, (70, 40): 4.5592, (70, 70): 5.6998, (70, 100): 7.2338,
    (100, 10): 3.5843, (100, 40): 5.4011, (100, 70): 7.6876, (100, 100): 9.3796,
}
GANT_TABLE6 = {  # space: (iterations, population, seconds) of G-Ant in Table 6
    "simple": (30, 20, 671.5), "moderate": (45, 30, 1078.0), "complex": (50, 40, 1368.64),
}
GGACO_TABLE2 = {  # case: ((rows, cols) as printed, median seconds of GGACO in Table 2)
    1: ((2569, 1919), 2950.5), 2: ((3018, 2178), 3267.7), 3: ((1789, 1512), 1922.3),
    4: ((2789, 2003), 2569.1), 5: ((1568, 1800), 1631.1),
}


def registered(scenario_id: str) -> Scenario | None:
    """The registered scenario, or None when its pack is not installed."""
    try:
        return pathzoo.load_scenario(scenario_id)
    except pathzoo.UnknownPluginError:
        return None


def grid100() -> Scenario:
    occ = random_obstacles((100, 100), seed=0, density=0.2)
    occ[0, 0] = occ[-1, -1] = False
    return Scenario(id="random100", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 0.5), goal=(99.5, 99.5))


def room512() -> Scenario:
    path = SHARED / "movingai" / "grid" / "rooms" / "8room_000.map"
    longest = max(read_scen(str(path) + ".scen"), key=lambda p: p.optimal_length)
    return Scenario(id="8room_000", kind="grid2d", occupancy=read_map(path), cell_size=1.0,
                    start=(longest.start_col + 0.5, longest.start_row + 0.5),
                    goal=(longest.goal_col + 0.5, longest.goal_row + 0.5), reference_length=longest.optimal_length)


def terrain_standin(rows: int, cols: int) -> Scenario:
    """A fractal DEM of the paper's size whose cells steeper than 20 degrees are blocked (traversable map)."""
    elev = fractal_terrain((rows, cols), seed=1, hurst=0.8, relief=0.01 * max(rows, cols))
    gy, gx = np.gradient(elev)
    blocked = np.degrees(np.arctan(np.hypot(gx, gy))) > 20.0
    blocked[:2, :2] = blocked[-2:, -2:] = False
    return Scenario(id=f"ggaco-standin-{rows}x{cols}", kind="terrain", occupancy=blocked, cell_size=1.0,
                    start=(0.5, 0.5), goal=(cols - 0.5, rows - 0.5), elevation=elev,
                    vehicle=VehicleModel(max_climb_deg=25.0, max_descent_deg=25.0))


FLOOR_ROWS = (  # label, planner, scenario (None: 8room_000), parameters, target multiple of the floor or None
    ("aco.as", "aco.as", None, {}, 3.0),
    ("aco.mmas", "aco.mmas", None, {}, 3.0),
    ("aco.gant", "aco.gant", None, {}, 3.0),
    ("aco.dsaco, graph rule", "aco.dsaco", None, {}, 3.0),
    ("aco.acs", "aco.acs", None, {}, 5.0),
    ("aco.iaca", "aco.iaca", "iaca.offroad", {}, 5.0),
    ("aco.dsaco, paper's step rule", "aco.dsaco", "dsaco.complex", {"step_rule": "longitude"}, 5.0),
    ("aco.fgdaco, static map", "aco.fgdaco", None, {}, 5.0),
    ("aco.fgdaco, timed walks", "aco.fgdaco", "fgdaco.scenario3", {}, 5.0),
    ("aco.acs, timed walks", "aco.acs", "fgdaco.scenario3", {}, 5.0),
    ("aco.ggaco", "aco.ggaco", None, {}, None),
)


@njit(cache=True)
def floor_walk(indptr: np.ndarray, indices: np.ndarray, start: int, n_steps: int, seed: int) -> int:
    """The least an ant walk does: per step one uniform draw and one read of the node's neighbour row.

    Returns the final node so the compiler keeps the walk; a node without
    neighbours restarts the walk at ``start``.
    """
    np.random.seed(seed)
    node = start
    for _ in range(n_steps):
        lo = indptr[node]
        degree = indptr[node + 1] - lo
        if degree == 0:
            node = start
            continue
        node = indices[lo + int(np.random.random() * degree)]
    return node


FLOOR_STEPS = 20_000_000
"""Steps of one timed floor walk."""


def floor_ns(scenario: Scenario, n_steps: int, repeats: int, seed: int = 0) -> float:
    """CPU nanoseconds per step of :func:`floor_walk` on the scenario's graph (minimum of ``repeats``)."""
    g = scenario.graph
    floor_walk(g.indptr, g.indices, scenario.start_node, 10, 0)
    best = math.inf
    for r in range(repeats):
        started = time.process_time()
        floor_walk(g.indptr, g.indices, scenario.start_node, n_steps, seed + r)
        best = min(best, time.process_time() - started)
    return 1e9 * best / n_steps


@contextlib.contextmanager
def walk_cpu() -> Iterator[list[float]]:
    """Accumulate the CPU seconds spent in the compiled walks while the block runs.

    The walks are the engine's ``walk`` (every colony but DSACO's; FGDACO's
    timed engine walks through it) and DSACO's ``run_colony`` (walks, fitness
    and updates of a colony in one compiled call); the planners' own timers
    are not used, so this does not depend on how a planner measures itself.
    """
    from pathzoo_aco import dsaco
    from pathzoo_aco.engine.walk import WalkEngine

    spent = [0.0]

    def timed(fn: Callable) -> Callable:
        def wrapper(*args, **kwargs):
            started = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                spent[0] += time.process_time() - started
        return wrapper

    patched = [(WalkEngine, "walk"), (dsaco, "run_colony")]
    originals = [getattr(owner, name) for owner, name in patched]
    for (owner, name), fn in zip(patched, originals):
        setattr(owner, name, timed(fn))
    try:
        yield spent
    finally:
        for (owner, name), fn in zip(patched, originals):
            setattr(owner, name, fn)


def colony_ns(planner_id: str, scenario: Scenario, colonies: int, **params) -> float:
    """CPU ns per ant-step of the compiled walks of one run of ``colonies`` colonies (kernels compiled already)."""
    with walk_cpu() as spent:
        result, _, _ = run(planner_id, scenario, colonies, **params)
    steps = result.extras["ant_steps"]
    return 1e9 * spent[0] / steps if steps else math.inf


def floor_table(colonies: int, repeats: int) -> None:
    """Each colony's ns per ant-step beside the floor's, measured in this process on the same graph."""
    print("## ns per ant-step against the floor\n")
    print("| colony | scenario | ns per ant-step | floor (ns) | x floor | target | met |\n|---|---|---|---|---|---|---|")
    scenarios: dict[str | None, Scenario | None] = {}
    for label, pid, sid, params, target in FLOOR_ROWS:
        if sid not in scenarios:
            scenarios[sid] = room512() if sid is None else registered(sid)
        scenario = scenarios[sid]
        if scenario is None:
            print(f"| {label} | {sid} not installed | | | | | |")
            continue
        scenario.graph
        run(pid, scenario, 1, n_ants=1, **params)  # compile or load the kernels
        floor, ns = math.inf, math.inf
        for r in range(repeats):  # the floor beside each run, so both see the same load on a shared machine
            floor = min(floor, floor_ns(scenario, FLOOR_STEPS, 1, seed=r))
            ns = min(ns, colony_ns(pid, scenario, colonies, **params))
        ratio = ns / floor
        verdict = "-" if target is None else ("yes" if ratio <= target else "no")
        shown = "information" if target is None else f"<= {target:g}x"
        print(f"| {label} | {scenario.id} | {ns:.1f} | {floor:.1f} | {ratio:.2f}x | {shown} | {verdict} |", flush=True)
    print()


def optimum(scenario: Scenario) -> float:
    g = scenario.graph
    return float(dijkstra(g.to_sparse(), indices=scenario.start_node)[scenario.goal_node])


def run(planner_id: str, scenario: Scenario, iterations: int, **params) -> tuple[pathzoo.PlanResult, float, float]:
    """One ``plan()`` call: the result, its wall time and its CPU time (seconds)."""
    planner = pathzoo.make_planner(planner_id, **params)
    started, cpu = time.perf_counter(), time.process_time()
    result = planner.plan(scenario, budget=Budget(iterations=iterations), rng=np.random.default_rng(0))
    wall, cpu = time.perf_counter() - started, time.process_time() - cpu
    if result.solved and not validate_path(scenario, result.path):
        raise RuntimeError(f"{planner_id} returned an invalid path on {scenario.id}")
    return result, wall, cpu


def length(result: pathzoo.PlanResult) -> float:
    return float(np.linalg.norm(np.diff(result.path, axis=0), axis=1).sum()) if result.solved else math.nan


def throughput(iterations: int) -> None:
    print("## Throughput (default parameters)\n")
    print(f"{'planner':10} {'map':10} {'iters':>5} {'ant-steps':>11} {'steps/s (CPU)':>14} {'steps/s (walks)':>15} "
          f"{'s/iter (CPU)':>12} {'length':>9} {'optimum':>9}")
    for scenario in (grid100(), room512()):
        scenario.graph
        best = optimum(scenario)
        for pid in VARIANTS:
            run(pid, scenario, 1, n_ants=1)  # load the compiled kernel
            result, _, cpu = run(pid, scenario, iterations)
            steps = result.extras["ant_steps"]
            print(f"{pid:10} {scenario.id:10} {result.iterations:5d} {steps:11d} {steps / cpu:14.3g} "
                  f"{steps / result.extras['walk_time_s']:15.3g} {cpu / max(result.iterations, 1):12.3f} "
                  f"{length(result):9.1f} {best:9.1f}")
    print()


def paper_row(label: str, planner_id: str, scenario: Scenario, standin: bool, iterations: int, paper_s: float,
              **params) -> None:
    result, wall, cpu = run(planner_id, scenario, iterations, **params)
    mark = " (stand-in)" if standin else ""
    print(f"| {label} | {scenario.id}{mark} | {iterations} x {params.get('n_ants', 'default')} | {cpu:.2f} | "
          f"{wall:.2f} | {paper_s:g} | {paper_s / cpu:.0f}x | {length(result):.2f} |")


def gant_settings() -> None:
    print("## G-Ant (Jabbarpour et al. 2017)\n")
    print(TABLE_HEAD)
    fig7 = registered("gant.fig7")
    standin = fig7 is None
    if fig7 is None:
        occ = np.zeros(100, bool)
        occ[np.random.default_rng(0).choice(np.arange(1, 99), 16, replace=False)] = True
        fig7 = Scenario(id="gant-fig7", kind="grid2d", occupancy=occ.reshape(10, 10), cell_size=1.0,
                        start=(0.5, 0.5), goal=(9.5, 9.5))
    fig7.graph
    run("aco.gant", fig7, 1, n_ants=1)  # load the compiled kernel
    for (iters, ants), paper_s in GANT_TABLE4.items():
        paper_row("Table 4", "aco.gant", fig7, standin, iters, paper_s, n_ants=ants)
    for space, (iters, ants, paper_s) in GANT_TABLE6.items():
        scenario = registered(f"gant.{space}.1")
        if scenario is None:
            print(f"| Table 6 | gant.{space}.1 not installed | | | | {paper_s:g} | | |")
            continue
        scenario.graph
        paper_row("Table 6", "aco.gant", scenario, False, iters, paper_s, n_ants=ants)
    print()


def ggaco_settings(cases: tuple[int, ...]) -> None:
    print("## GGACO (Sangeetha & Ravichandran 2024/25), default parameters (1000 iterations x 20 ants)\n")
    print(TABLE_HEAD)
    packs = {s.id: s for s in (pathzoo.list_plugins("scenarios")) if s.id.startswith("ggaco.")}
    for case in cases:
        (rows, cols), paper_s = GGACO_TABLE2[case]
        found = [sid for sid, entry in packs.items() if sid.startswith(f"ggaco.case{case}")]
        scenario = registered(found[0]) if found else None
        standin = scenario is None
        if scenario is None:
            scenario = terrain_standin(rows, cols)
        started = time.perf_counter()
        scenario.graph
        print(f"<!-- graph of {scenario.id}: {scenario.graph.n_edges} edges built in "
              f"{time.perf_counter() - started:.1f} s -->")
        paper_row(f"Table 2, case {case}", "aco.ggaco", scenario, standin, 1000, paper_s)
    print()


# ---------------------------------------------------------------- DSACO, IACA and FGDACO
DSACO_TABLE5 = {"s": 3.9541, "length": 74.1204, "fitness": 83.0249}  # mean of 30 runs, complex terrain
IACA_TABLE5 = {"s": 21.0, "points": 21, "distance": 33.5}  # the IACA row (equal to Dijkstra's path)
FGDACO_TABLE7 = {1: (28.97, 126.65), 2: (38.74, 135.96), 3: (74.33, 197.69)}  # median (s, length m) of 30 runs
LATER_SETTINGS = (  # label, planner, scenario, iterations, ants, paper seconds, extra parameters
    ("DSACO Table 5", "aco.dsaco", "dsaco.complex", 500, 10, DSACO_TABLE5["s"], {}),
    ("DSACO Table 5, longitude rule", "aco.dsaco", "dsaco.complex", 500, 10, DSACO_TABLE5["s"],
     {"step_rule": "longitude"}),
    ("IACA Table 5", "aco.iaca", "iaca.offroad", 100, 40, IACA_TABLE5["s"], {}),
    *((f"FGDACO Table 7, scenario {k}", "aco.fgdaco", f"fgdaco.scenario{k}", 100, 20, paper[0], {})
      for k, paper in FGDACO_TABLE7.items()),
)


def later_settings() -> None:
    """Time of one ``plan()`` call in the DSACO, IACA and FGDACO paper settings, next to the papers' times."""
    print("## DSACO (Mai et al. 2023), IACA (Wang et al. 2018), FGDACO (Sangeetha et al. 2021)\n")
    print(TABLE_HEAD)
    for label, pid, sid, iters, ants, paper_s, params in LATER_SETTINGS:
        scenario = registered(sid)
        if scenario is None:
            print(f"| {label} | {sid} not installed | | | | {paper_s:g} | | |")
            continue
        scenario.graph
        run(pid, scenario, 1, n_ants=1, **params)  # load the compiled kernels
        paper_row(label, pid, scenario, False, iters, paper_s, n_ants=ants, **params)
    print()


def later_quality(seeds: int) -> None:
    """Median and IQR over ``seeds`` runs of each setting: length, the planner's own cost, CPU time."""
    print(f"## DSACO, IACA, FGDACO: {seeds} seeds per paper setting (median [IQR])\n")
    print("| setting | length | planner's cost | path points | CPU (s) | paper |\n|---|---|---|---|---|---|")
    papers = {"aco.dsaco": f"length {DSACO_TABLE5['length']} km, fitness {DSACO_TABLE5['fitness']} (mean)",
              "aco.iaca": f"{IACA_TABLE5['points']} points, distance {IACA_TABLE5['distance']}"}
    for label, pid, sid, iters, ants, _, params in LATER_SETTINGS:
        scenario = registered(sid)
        if scenario is None:
            continue
        planner = pathzoo.make_planner(pid, n_ants=ants, **params)
        rows = []
        for seed in range(seeds):
            costs: list[float] = []
            cpu = time.process_time()
            result = planner.plan(scenario, budget=Budget(iterations=iters), rng=np.random.default_rng(seed),
                                  progress=lambda i, e, c: costs.append(c))
            cpu = time.process_time() - cpu
            if result.solved and not validate_path(scenario, result.path):
                raise RuntimeError(f"{pid} returned an invalid path on {sid}")
            rows.append((length(result) / scenario.cell_size, costs[-1] if costs else math.nan,
                         len(result.path) if result.solved else math.nan, cpu))
        cells = []
        for column in np.array(rows).T:
            q1, q2, q3 = np.nanpercentile(column, [25, 50, 75])
            cells.append(f"{q2:.2f} [{q1:.2f}, {q3:.2f}]")
        paper = papers.get(pid) or f"length {FGDACO_TABLE7[int(sid[-1])][1]} m (median)"
        print(f"| {label} | {' | '.join(cells)} | {paper} |")
    print("\nLengths are in cells (DSACO: km; IACA: 10 m cells; FGDACO: m). The planner's cost is DSACO's fitness "
          "(eq. 20), IACA's eq. 21 distance, FGDACO's length.\n")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="throughput only")
    parser.add_argument("--all-ggaco", action="store_true", help="all five GGACO terrain sizes")
    parser.add_argument("--iterations", type=int, default=5, help="colonies per throughput run")
    parser.add_argument("--later-only", action="store_true", help="only the DSACO/IACA/FGDACO sections")
    parser.add_argument("--floor-only", action="store_true", help="only the ns-per-step table against the floor")
    parser.add_argument("--floor-colonies", type=int, default=3,
                        help="colonies per run in the floor table")
    parser.add_argument("--repeats", type=int, default=3, help="measurements per floor-table figure (minimum kept)")
    parser.add_argument("--seeds", type=int, default=0,
                        help="also run the DSACO/IACA/FGDACO paper settings over this many seeds")
    args = parser.parse_args()
    print(f"load average: {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs\n")
    floor_table(args.floor_colonies, args.repeats)
    if args.floor_only:
        return
    if not args.later_only:
        throughput(args.iterations)
    if args.quick:
        return
    if not args.later_only:
        gant_settings()
        ggaco_settings((1, 2, 3, 4, 5) if args.all_ggaco else (1,))
    later_settings()
    if args.seeds:
        later_quality(args.seeds)


if __name__ == "__main__":
    main()
