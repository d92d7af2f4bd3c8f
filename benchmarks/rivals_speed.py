"""Speed of the rivals of GGACO's and G-Ant's tables per evaluation, as multiples of a floor timed in the same run.

Run from the repository root::

    python benchmarks/rivals_speed.py                 # ggaco.case3 and gant.complex.1, 2 iterations per plan
    python benchmarks/rivals_speed.py --iterations 5 --scenarios ggaco.case3

Floor: one A* search of the exact family's kernel from the start to the goal
cell over the scenario's graph with its edge lengths
(:meth:`pathzoo_rivals.routes.RouteProblem.shortest_nodes`), the least a
planner that returns a path of that graph can do once. Every figure is CPU
seconds (``time.process_time``, this process only), the minimum of
``--repeats``, its floor timed just before it so that both see the same load
on a shared machine; set-up common to all (loading the scenario, building its
graph) is outside every figure.

Rows:

- ``random route, as before`` / ``random route``: one random frog of
  ``swarm.mosfla`` (and a restart of ``search.movns``): the noisy-weight A* and
  the string-pulling of :meth:`RouteProblem.random_route`; "as before" builds
  the noisy weights with ``length * rng.uniform(...)`` (two graph-sized
  temporaries), the current code draws them into one reused array, the same
  numbers bit for bit;
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
import time
from typing import Callable

import numpy as np

import pathzoo
from pathzoo import Budget, Scenario
from pathzoo_rivals.routes import RouteProblem

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


def random_route_before(problem: RouteProblem, rng: np.random.Generator, noise: float = 2.0) -> np.ndarray | None:
    """The random route with the noisy weights built as two graph-sized temporaries (the reference)."""
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
    seconds, fl = cpu(lambda: random_route_before(problem, np.random.default_rng(0)), repeats, floor)
    row("random route, as before", seconds, fl)
    seconds, fl = cpu(lambda: problem.random_route(np.random.default_rng(0)), repeats, floor)
    row("random route", seconds, fl)
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
    args = parser.parse_args()
    for sid in args.scenarios.split(","):
        scenario_rows(pathzoo.load_scenario(sid), *PLANNERS[sid], args.iterations, args.repeats)


if __name__ == "__main__":
    main()
