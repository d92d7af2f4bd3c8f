"""Speed of the rivals of GGACO's and G-Ant's tables per evaluation, as multiples of a floor timed in the same run.

Run from the repository root::

    python benchmarks/rivals_speed.py                 # ggaco.case3 and gant.complex.1, 2 iterations per plan
    python benchmarks/rivals_speed.py --iterations 5 --scenarios ggaco.case3
    python benchmarks/rivals_speed.py --scenarios ggaco.case3 --write-docs   # the table of docs/planners/swarm.mosfla.md

Floor: one A* search of the exact family's kernel from the start to the goal
cell over the scenario's graph with its edge lengths
(:meth:`pathzoo_rivals.routes.RouteProblem.shortest_nodes`), the least a
planner that returns a path of that graph can do once. Every figure is CPU
seconds (``time.process_time``, this process only), the minimum of
``--repeats``, its floor timed just before it so that both see the same load
on a shared machine; set-up common to all (loading the scenario, building its
graph) is outside every figure.

Rows:

- ``random route, noisy A* (version 1)``: the random frog of ``swarm.mosfla``
  version 1 (and restart of ``search.movns`` version 1): an A* over the whole
  map with edge lengths scaled by ``U(1, 3)``, string-pulled;
- ``random route, via cell (version 2)``: :meth:`RouteProblem.random_route`,
  the shortest route through a random via cell, string-pulled, after its
  two shortest-path trees (built once per ``plan()``, timed on their own in
  the row ``shortest-path trees``);
- ``<planner>, per evaluation``: CPU of one ``plan()`` at ``--iterations``
  iterations over the evaluations it reports (one evaluation is what the
  planner's page says: a route decoded and costed, an ant walk, an individual);
- ``<planner>, one plan``: exact searches, one ``plan()``.

The target (issue 34's Done-when) is a slice of each table within its CPU
budget: one run of every planner of GGACO's Table 2 on ggaco.case3 at the
paper's budget within 108 CPU s, of G-Ant's Table 5 on gant.complex.1 within
120 CPU s; ``pathzoo reproduce PAPER --estimate`` gives the whole table's cost.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np

import pathzoo
from pathzoo import Budget, Scenario
from pathzoo_rivals.routes import RouteProblem

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doc_table import add_write_docs_option, docs_table  # noqa: E402  (a sibling script)

PLANNERS = {  # scenario: planners per evaluation (iterative) and per plan (exact searches)
    "ggaco.case3": (("aco.ggaco", "swarm.mosfla", "search.movns"), ("exact.zstar", "aco.aco_astar")),
    "gant.complex.1": (("aco.gant", "aco.as", "evo.ga"), ()),
}


def cpu(fn: Callable[[], object], repeats: int, floor: Callable[[], object]) -> tuple[float, float]:
    """Minimum CPU seconds of ``fn`` and of ``floor`` over ``repeats``, the floor timed just before each run."""
    best, best_floor = np.inf, np.inf
    for _ in range(repeats):
        t = time.process_time()
        floor()
        best_floor = min(best_floor, time.process_time() - t)
        t = time.process_time()
        fn()
        best = min(best, time.process_time() - t)
    return best, best_floor


def noisy_route(problem: RouteProblem, rng: np.random.Generator, noise: float = 2.0) -> np.ndarray | None:
    """Version 1's random route: the shortest path under edge lengths scaled by ``U(1, 1 + noise)``, string-pulled."""
    graph = problem.scenario.graph
    nodes = problem.shortest_nodes(graph.length * rng.uniform(1.0, 1.0 + noise, graph.n_edges))
    return None if nodes is None else problem.pull_string(nodes)


def row(label: str, seconds: float, floor: float, evaluations: float = 1.0) -> None:
    per = seconds / max(evaluations, 1.0)
    print(f"| {label} | {evaluations:.0f} | {per * 1e3:.1f} | {floor * 1e3:.1f} | {per / floor:.2f}x |")


def scenario_rows(s: Scenario, iterative: tuple[str, ...], exact: tuple[str, ...], iterations: int,
                  repeats: int) -> None:
    problem = RouteProblem(s)
    problem.shortest_nodes(s.graph.length)  # compile the kernel outside the figures
    floor = lambda: problem.shortest_nodes(s.graph.length)  # noqa: E731
    print(f"\n{s.id} ({s.shape[0]} x {s.shape[1]} cells, {s.graph.n_edges} edges)\n")
    print("| what | evaluations | CPU ms per evaluation | floor ms (one A*) | multiple of the floor |")
    print("|---|---|---|---|---|")
    seconds, fl = cpu(lambda: noisy_route(problem, np.random.default_rng(0)), repeats, floor)
    row("random route, noisy A* (version 1)", seconds, fl)
    seconds, fl = cpu(lambda: RouteProblem(s)._trees(), repeats, floor)
    row("shortest-path trees (once per plan, version 2)", seconds, fl)
    problem._trees()
    rng = np.random.default_rng(0)
    seconds, fl = cpu(lambda: [problem.random_route(rng) for _ in range(100)], repeats, floor)
    row("random route, via cell (version 2)", seconds, fl, 100.0)
    for pid in iterative + exact:
        planner = pathzoo.make_planner(pid)
        budget = Budget(iterations=iterations) if pid in iterative else Budget()
        planner.plan(s, budget=Budget(iterations=1), rng=np.random.default_rng(0))  # compile, build shared tables
        result: list[pathzoo.PlanResult] = []
        seconds, fl = cpu(lambda: result.append(planner.plan(s, budget=budget, rng=np.random.default_rng(0))),
                          repeats, floor)
        if pid in iterative:
            row(f"{pid}, per evaluation ({iterations} iterations)", seconds, fl, float(result[-1].evaluations))
        else:
            row(f"{pid}, one plan", seconds, fl)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--iterations", type=int, default=2, help="iterations per plan() of the iterative rows")
    parser.add_argument("--repeats", type=int, default=2, help="runs per figure (the minimum is printed)")
    parser.add_argument("--scenarios", default=",".join(PLANNERS), help="comma-separated: " + ", ".join(PLANNERS))
    add_write_docs_option(parser, "planners/swarm.mosfla.md")
    args = parser.parse_args()
    with docs_table(args.write_docs, "planners/swarm.mosfla.md", "rivals_speed.py"):
        print(f"CPU per evaluation, {args.iterations} iterations per plan, minimum of {args.repeats} runs:")
        for sid in args.scenarios.split(","):
            scenario_rows(pathzoo.load_scenario(sid), *PLANNERS[sid], args.iterations, args.repeats)


if __name__ == "__main__":
    main()
